// settings.txt of an ASR model dir: "key value" lines that define the features, the network and
// the training run (not the epoch count or time limit, which a resumed run may extend), written and
// read through AsrTrainOptions::Register (util/settings_file.h): an option added there is a setting.
#pragma once
#include <string>

#include "asr/asr.h"
#include "util/settings_file.h"

namespace tsrir {

using AsrSettings = SettingsValues;

AsrSettings asr_settings_of(const AsrTrainOptions& options);
void write_asr_settings(const std::string& path, const AsrSettings& settings);
AsrSettings read_asr_settings(const std::string& path);
// The text form (also stored inside checkpoints).
std::string asr_settings_text(const AsrSettings& settings);
AsrSettings parse_asr_settings(const std::string& text, const std::string& where);
// The features and network of a stored model. Errors name `where`.
LogMelOptions feature_options_of(const AsrSettings& settings, const std::string& where);
AsrModelConfig model_config_of(const AsrSettings& settings, const std::string& where);
// Settings that differ: settings_difference (util/settings_file.h).

}  // namespace tsrir
