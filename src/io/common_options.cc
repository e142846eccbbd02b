#include "io/common_options.h"

#include "util/error.h"

namespace tsrir {
namespace {

// Passes registrations on with a check added to the setter (values are checked where they are
// parsed, so an error names the option, the file and line of a --config).
class Checked : public OptionsItf {
 public:
  Checked(OptionsItf* next, std::function<void(const std::string&)> check) : next_(next), check_(std::move(check)) {}
  void RegisterAlias(const std::string& alias, const std::string& name) override { next_->RegisterAlias(alias, name); }
  void RegisterSpec(OptionSpec spec) override {
    spec.set = [set = spec.set, check = check_](const std::string& text) {
      set(text);
      check(text);
    };
    next_->RegisterSpec(std::move(spec));
  }

 private:
  OptionsItf* next_;
  std::function<void(const std::string&)> check_;
};

}  // namespace

CommonOptions& CommonOptions::threads(int* num_threads, const std::string& what) {
  Checked checked(opts_, [num_threads](const std::string&) {
    if (*num_threads < 1) throw Error("expected at least 1");
  });
  checked.Register("num-threads", num_threads, what.empty() ? "threads, at least 1" : "threads, at least 1 (" + what + ")");
  return *this;
}

CommonOptions& CommonOptions::seed(Seed* seed, const std::string& what) {
  opts_->Register("seed", seed, "random seed (any integer) of " + what);
  opts_->RegisterAlias("random-seed", "seed");
  return *this;
}

CommonOptions& CommonOptions::audio_format(SampleFormat* format) {
  opts_->RegisterEnum("format", format, sample_format_choices(), "sample format of the audio written");
  return *this;
}

CommonOptions& CommonOptions::overwrite(bool* overwrite) {
  opts_->Register("overwrite", overwrite,
                  "write into an output directory that tsrir did not write (or replace files another "
                  "run wrote there); only files of the names this program writes are replaced, nothing is deleted");
  return *this;
}

}  // namespace tsrir
