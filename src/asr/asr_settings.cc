#include "asr/asr_settings.h"

#include <fstream>
#include <sstream>

#include "io/atomic_output.h"
#include "util/error.h"
#include "util/strings.h"

namespace tsrir {
namespace {

std::string num(double v) { return format_double(v, 12); }

const std::string& get(const AsrSettings& s, const std::string& key, const std::string& where) {
  auto it = s.find(key);
  if (it == s.end()) throw Error(where + ": settings lack '" + key + "'");
  return it->second;
}

double get_double(const AsrSettings& s, const std::string& key, const std::string& where) {
  return parse_double(get(s, key, where), where + ": " + key);
}

int get_int(const AsrSettings& s, const std::string& key, const std::string& where) {
  return int(parse_int(get(s, key, where), where + ": " + key));
}

}  // namespace

AsrSettings asr_settings_of(const AsrTrainOptions& o) {
  AsrSettings s;
  s["format"] = "tsrir-asr-ctc-1";
  s["sample-rate"] = num(o.features.sample_rate_hz);
  s["frame-length-ms"] = num(o.features.frame_length_ms);
  s["frame-shift-ms"] = num(o.features.frame_shift_ms);
  s["num-mel-bins"] = std::to_string(o.features.num_mel_bins);
  s["low-hz"] = num(o.features.low_hz);
  s["high-hz"] = num(o.features.high_hz);
  s["preemphasis"] = num(o.features.preemphasis);
  s["conv-layers"] = std::to_string(o.model.conv_layers);
  s["conv-channels"] = std::to_string(o.model.conv_channels);
  s["conv-kernel"] = std::to_string(o.model.conv_kernel);
  s["subsampling"] = std::to_string(o.model.subsampling);
  s["rnn-type"] = rnn_type_name(o.model.rnn_type);
  s["rnn-layers"] = std::to_string(o.model.rnn_layers);
  s["rnn-hidden"] = std::to_string(o.model.rnn_hidden);
  s["dropout"] = num(o.model.dropout);
  s["seed"] = std::to_string(o.seed);
  s["batch-size"] = std::to_string(o.batch_size);
  // Written only when on, so that models trained before the option keep their settings.
  if (o.sample_copies) s["sample-copies"] = "true";
  s["learning-rate"] = num(o.learning_rate);
  s["grad-clip"] = num(o.grad_clip);
  s["time-masks"] = std::to_string(o.time_masks);
  s["max-time-mask"] = num(o.max_time_mask);
  s["freq-masks"] = std::to_string(o.freq_masks);
  s["max-freq-mask"] = std::to_string(o.max_freq_mask);
  s["data-dir"] = absolute_path(o.data_dir);
  return s;
}

std::string asr_settings_text(const AsrSettings& s) {
  std::ostringstream os;
  for (const auto& [k, v] : s) os << k << ' ' << v << '\n';
  return os.str();
}

void write_asr_settings(const std::string& path, const AsrSettings& s) {
  AtomicTextFile out(path);
  out.stream() << asr_settings_text(s);
  out.commit();
}

AsrSettings parse_asr_settings(const std::string& text, const std::string& where) {
  AsrSettings s;
  std::istringstream in(text);
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    ++n;
    const std::string t = trim(line);
    if (t.empty()) continue;
    const size_t space = t.find(' ');
    if (space == std::string::npos) throw Error(located(where, n, "expected 'key value', got '" + t + "'"));
    s[t.substr(0, space)] = trim(t.substr(space + 1));
  }
  if (s.count("format") == 0 || s["format"] != "tsrir-asr-ctc-1") {
    throw Error(where + ": not the settings of an asr-train model (format tsrir-asr-ctc-1)");
  }
  return s;
}

AsrSettings read_asr_settings(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open (is this an asr-train model dir?)");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return parse_asr_settings(buffer.str(), path);
}

LogMelOptions feature_options_of(const AsrSettings& s, const std::string& where) {
  LogMelOptions f;
  f.sample_rate_hz = get_double(s, "sample-rate", where);
  f.frame_length_ms = get_double(s, "frame-length-ms", where);
  f.frame_shift_ms = get_double(s, "frame-shift-ms", where);
  f.num_mel_bins = get_int(s, "num-mel-bins", where);
  f.low_hz = get_double(s, "low-hz", where);
  f.high_hz = get_double(s, "high-hz", where);
  f.preemphasis = get_double(s, "preemphasis", where);
  return f;
}

AsrModelConfig model_config_of(const AsrSettings& s, const std::string& where) {
  AsrModelConfig m;
  m.conv_layers = get_int(s, "conv-layers", where);
  m.conv_channels = get_int(s, "conv-channels", where);
  m.conv_kernel = get_int(s, "conv-kernel", where);
  m.subsampling = get_int(s, "subsampling", where);
  const std::string& rnn = get(s, "rnn-type", where);
  if (rnn != "gru" && rnn != "lstm") throw Error(where + ": rnn-type must be gru or lstm, got '" + rnn + "'");
  m.rnn_type = rnn == "lstm" ? RnnType::kLstm : RnnType::kGru;
  m.rnn_layers = get_int(s, "rnn-layers", where);
  m.rnn_hidden = get_int(s, "rnn-hidden", where);
  m.dropout = get_double(s, "dropout", where);
  return m;
}

std::string settings_difference(const AsrSettings& stored, const AsrSettings& asked) {
  std::string diff;
  for (const auto& [k, v] : stored) {
    auto it = asked.find(k);
    if (it == asked.end() || it->second != v) diff += " --" + k + "=" + v;
  }
  return diff;
}

}  // namespace tsrir
