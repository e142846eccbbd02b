#include "asr/asr_settings.h"

#include "io/atomic_output.h"
#include "util/error.h"
#include "util/strings.h"

namespace tsrir {
namespace {

// settings.txt holds the options that define the features, the network and the training run, under
// their option names (AsrTrainOptions::Register), sorted, with 12 significant digits: the bytes of
// the files written before the settings followed the options, five of whose keys are kept.
class AsrSettingsFile {
 public:
  AsrSettingsFile() : file_("tsrir-asr-ctc-1", "the settings of an asr-train model", style()) {
    options_.Register(&file_);
    file_.Register("data-dir", &data_dir_, "the training data dir (absolute)");
    // What a resumed run may change (asr.h): not settings.
    file_.Exclude({"epochs", "max-minutes", "num-threads", "device", "resume", "progress-interval"});
    // Added after models were written (main wrote it only when on): older files read as off.
    file_.OmitWhenDefault({"sample-copies"}, file_.values());  // options_ are still the defaults
    file_.Rename("frame-length", "frame-length-ms");
    file_.Rename("frame-shift", "frame-shift-ms");
    file_.Rename("low-freq", "low-hz");
    file_.Rename("high-freq", "high-hz");
    file_.Rename("preemphasis-coefficient", "preemphasis");
  }
  AsrSettingsFile(const AsrSettingsFile&) = delete;  // file_ points into options_
  AsrSettingsFile& operator=(const AsrSettingsFile&) = delete;

  AsrTrainOptions& options() { return options_; }
  std::string& data_dir() { return data_dir_; }
  SettingsFile& file() { return file_; }

 private:
  static SettingsStyle style() {
    SettingsStyle s;
    s.sorted = true;
    s.double_digits = 12;
    s.require_all = true;
    return s;
  }
  AsrTrainOptions options_;
  std::string data_dir_;
  SettingsFile file_;
};

}  // namespace

AsrSettings asr_settings_of(const AsrTrainOptions& options) {
  AsrSettingsFile settings;
  settings.options() = options;
  settings.data_dir() = absolute_path(options.data_dir);
  return settings.file().values();
}

std::string asr_settings_text(const AsrSettings& settings) {
  std::string text;
  for (const auto& [key, value] : settings) text += key + ' ' + value + '\n';
  return text;
}

void write_asr_settings(const std::string& path, const AsrSettings& settings) {
  AtomicTextFile out(path);
  out.stream() << asr_settings_text(settings);
  out.commit();
}

AsrSettings parse_asr_settings(const std::string& text, const std::string& where) {
  AsrSettingsFile settings;
  settings.file().parse(text, where);  // every value checked, errors at file:line
  return settings.file().read(text, where);
}

AsrSettings read_asr_settings(const std::string& path) {
  std::string text;
  try {
    text = read_settings_text(path);
  } catch (const Error&) {
    throw Error(path + ": cannot open (is this an asr-train model dir?)");
  }
  return parse_asr_settings(text, path);
}

LogMelOptions feature_options_of(const AsrSettings& stored, const std::string& where) {
  AsrSettingsFile settings;
  settings.file().apply(stored, where);
  return settings.options().features;
}

AsrModelConfig model_config_of(const AsrSettings& stored, const std::string& where) {
  AsrSettingsFile settings;
  settings.file().apply(stored, where);
  return settings.options().model;
}

}  // namespace tsrir
