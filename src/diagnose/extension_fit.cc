#include "diagnose/extension_fit.h"

#include "sim/extension_components.h"
#include "sim/model.h"
#include "util/strings.h"

namespace tsrir::diagnose {

Signal render_rir(const std::string& model_spec, const sim::RoomSpec& room, double fs, size_t n, uint64_t seed) {
  sim::register_extension_components();
  return sim::Model::parse(model_spec).render(room, fs, n, seed);
}

std::string spec_num(double v) { return format_double(v, 5); }

}  // namespace tsrir::diagnose
