#include "augment/augment_plan.h"

#include <cmath>
#include <cstdio>

#include "io/rxfile.h"
#include "io/shell.h"
#include "util/error.h"
#include "util/rng.h"
#include "util/strings.h"

namespace tsrir {

std::string copy_id(const std::string& id, const std::string& prefix, int copy) {
  if (prefix.empty()) return id;
  return prefix + std::to_string(copy) + "-" + id;
}

double pipe_rounded(double value) { return std::round(value * 1e6) / 1e6; }

std::string pipe_number(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.6f", pipe_rounded(value));
  std::string s = buffer;
  // "1.500000" -> "1.5", "3.000000" -> "3"
  while (!s.empty() && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  if (s == "-0") s = "0";
  return s;
}

std::vector<RecordingPlan> plan_recordings(const std::map<std::string, std::string>& wav_scp,
                                           const AugmentSources& sources, const SnrSpec& snrs,
                                           const PlanOptions& options) {
  if (options.num_replications < 1) throw Error("--num-replications must be at least 1");
  std::vector<double> rir_weights;
  for (const auto& r : sources.rirs) rir_weights.push_back(r.probability);
  std::vector<RecordingPlan> plans;
  const int first_copy = options.include_original_data ? 0 : 1;
  for (int copy = first_copy; copy <= options.num_replications; ++copy) {
    for (const auto& [id, rx] : wav_scp) {
      RecordingPlan plan;
      plan.copy = copy;
      plan.source_id = id;
      plan.new_id = copy_id(id, options.prefix, copy);
      plan.source_rx = rx;
      if (copy > 0) {
        Rng rng = Rng::for_item(options.random_seed, std::to_string(copy) + "/" + id);
        const double u_rvb = rng.uniform();
        const double u_rir = rng.uniform();
        const double u_add = rng.uniform();
        const double u_noise = rng.uniform();
        const double u_offset = rng.uniform();
        std::string room;
        if (!sources.rirs.empty() && u_rvb < options.speech_rvb_probability) {
          plan.rir = static_cast<long>(weighted_index(rir_weights, u_rir));
          room = sources.rirs[static_cast<size_t>(plan.rir)].room_id;
        }
        std::vector<size_t> candidates = sources.noises_for_room(room);
        if (!candidates.empty() && u_add < options.noise_addition_probability) {
          std::vector<double> w;
          for (size_t i : candidates) w.push_back(sources.noises[i].probability);
          plan.noise = static_cast<long>(candidates[weighted_index(w, u_noise)]);
          plan.noise_offset_fraction = options.random_noise_start ? u_offset : 0.0;
          plan.snr_db = pipe_rounded(snrs.draw(rng));
        }
      }
      plans.push_back(std::move(plan));
    }
  }
  return plans;
}

void resolve_noise_offsets(const std::map<long, double>& noise_duration_s, std::vector<RecordingPlan>* plans) {
  for (RecordingPlan& plan : *plans) {
    if (plan.noise < 0) continue;
    auto it = noise_duration_s.find(plan.noise);
    if (it == noise_duration_s.end()) throw Error("internal: no duration for noise " + std::to_string(plan.noise));
    // Rounding down keeps the offset strictly inside the noise.
    plan.noise_offset_s = std::floor(plan.noise_offset_fraction * it->second * 1e6) / 1e6;
  }
}

std::string format_pipe(const RecordingPlan& plan, const AugmentSources& sources, const PipeOptions& options) {
  if (!plan.modified()) return plan.source_rx;
  // A plain file is read by the program itself (Kaldi writes "cat <file> |" first: one process
  // more per utterance); a pipe feeds it through stdin.
  const bool piped_source = is_pipe_rxfilename(plan.source_rx);
  std::string input = "-";
  std::string out;
  if (piped_source) {
    out = trim(plan.source_rx) + " ";
  } else {
    input = trim(plan.source_rx);
    if (starts_with(input, "-")) input = "./" + input;  // never mistaken for an option
    input = shell_quote(input);
  }
  out += shell_quote(options.program);
  out += " " + std::string(options.shift_output ? "--shift-output=true" : "--shift-output=false");
  if (!options.normalize_output) out += " --normalize-output=false";
  if (plan.rir >= 0)
    out += " " + shell_quote("--impulse-response=" + sources.rirs[static_cast<size_t>(plan.rir)].rxfilename);
  if (plan.noise >= 0) {
    const NoiseChoice& noise = sources.noises[static_cast<size_t>(plan.noise)];
    if (noise.rxfilename.find(',') != std::string::npos)
      throw Error(noise.where + ": noise rxfilename '" + noise.rxfilename +
                  "' contains a comma, which wav-reverberate's --additive-signals cannot hold; use --write-wavs");
    out += " " + shell_quote("--additive-signals=" + noise.rxfilename);
    out += " --start-times=0";
    out += " " + shell_quote("--snrs=" + pipe_number(plan.snr_db));
    out += " " + shell_quote("--additive-offsets=" + pipe_number(plan.noise_offset_s));
    out += " --loop-additive-signals=true";
    if (options.snr_reference != SnrReference::kEarlyReverb)
      out += " --snr-reference=" + snr_reference_name(options.snr_reference);
  }
  out += " " + input + " - |";
  return out;
}

}  // namespace tsrir
