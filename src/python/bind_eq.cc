// eq_apply(): one RIR through rir-eq apply's per-RIR step (equalize_rir_set in src/eq/eq_set.cc):
// the target gains drawn from the model with the stream Rng::for_item(seed, rir id), then
// equalize_rir() with the model's gain method. For the same id, seed and options the samples
// are those `rir-eq apply --format=float` writes.
#include <utility>

#include <pybind11/stl.h>

#include "arrays.h"
#include "bindings.h"
#include "eq/eq_model.h"
#include "eq/equalize.h"
#include "util/error.h"
#include "util/rng.h"
#include "util/strings.h"

namespace tsrir::python {
namespace {

py::dict gains_dict(const RelativeGainsDb& gains) {
  py::dict d;
  for (size_t i = 0; i < gains.size(); ++i) d[py::float_(kEqPointsHz[i])] = gains[i];
  return d;
}

}  // namespace

void bind_eq(py::module_& m) {
  const EqApplyOptions defaults;  // the programs' defaults
  m.def(
      "eq_apply",
      [](const std::string& model_path, const py::handle& rir, double fs, int64_t seed, const std::string& rir_id,
         int taps, const std::string& window, int refine_iterations, double max_boost_db, double max_cut_db,
         const std::string& level) {
        Signal signal;
        signal.id = rir_id;
        signal.sample_rate_hz = fs;
        signal.samples = to_samples(rir, "rir");
        if (taps != 0 && (taps < 3 || taps % 2 == 0))
          throw Error("taps must be 0 (automatic) or odd and >= 3, got " + std::to_string(taps));
        if (refine_iterations < 0) throw Error("refine_iterations must be >= 0");
        if (!(max_boost_db > 0) || !(max_cut_db > 0)) throw Error("max_boost_db and max_cut_db must be positive");
        EqApplyOptions eq;
        eq.fir.taps = taps;
        eq.fir.window = parse_fir_window(window);
        eq.refine_iterations = refine_iterations;
        eq.max_boost_db = max_boost_db;
        eq.max_cut_db = max_cut_db;
        eq.level = parse_eq_level(level);
        eq.measure_output = true;
        EqResult result;
        {
          py::gil_scoped_release release;
          const EqModel model = load_eq_model(model_path);
          model.mixture.validate("EQ model");
          if (fs != model.sample_rate_hz)
            throw Error("RIR '" + rir_id + "' is at " + format_double(fs) + " Hz but the EQ model was fitted at " +
                        format_double(model.sample_rate_hz) + " Hz (resample it first: tsrir.resample)");
          eq.gain_method = model.gain_method;
          Rng rng = Rng::for_item(static_cast<uint64_t>(seed), rir_id);
          const RelativeGainsDb target = draw_target_gains(model, rng);
          result = equalize_rir(signal, target, eq);
        }
        py::dict info;
        info["before_db"] = gains_dict(result.before_db);
        info["target_db"] = gains_dict(result.target_db);
        info["predicted_db"] = gains_dict(result.predicted_db);
        info["after_db"] = gains_dict(result.after_db);
        info["clamped"] = result.clamped;
        info["filters_designed"] = result.filters_designed;
        return py::make_tuple(to_numpy(std::move(result.rir.samples)), info);
      },
      py::arg("model_path"), py::arg("rir"), py::arg("fs"), py::arg("seed") = 0, py::arg("rir_id") = "rir",
      py::arg("taps") = defaults.fir.taps, py::arg("window") = "hamming",
      py::arg("refine_iterations") = defaults.refine_iterations, py::arg("max_boost_db") = defaults.max_boost_db,
      py::arg("max_cut_db") = defaults.max_cut_db, py::arg("level") = eq_level_name(defaults.level),
      "rir-eq apply for one RIR: returns (equalized float32 RIR, gains dict).");
}

}  // namespace tsrir::python
