// A recording's plan (augment_plan.h) made into audio, as reverberate-data --write-wavs writes it
// and as the Python Augmenter gives it for one utterance: the plan's RIR and noises read at the
// speech's sample rate (each (item, rate) loaded once, by whichever thread needs it first, a noise
// once for its mono and its per-microphone forms; channel 0 of a multichannel file in the mono
// form, with rate_policy.h's warning), each noise made as the pipe's nested step would make it,
// then reverberate_channel(). Thread-safe.
#pragma once
#include <map>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

#include "augment/augment_plan.h"
#include "augment/reverberate.h"

namespace tsrir {

class PlanRenderer {
 public:
  // `sources` must outlive the renderer.
  PlanRenderer(const AugmentSources& sources, ReverbOptions reverb);
  PlanRenderer(const PlanRenderer&) = delete;
  PlanRenderer& operator=(const PlanRenderer&) = delete;

  // RIR `index` of the sources at `rate` (null for -1: no RIR).
  std::shared_ptr<const PreparedRir> rir(long index, double rate);
  // The RIR the plan's speech is reverberated with: its channel plan.rir_channel (from
  // --split-channels), else channel 0; null without one.
  std::shared_ptr<const PreparedRir> speech_rir(const RecordingPlan& plan, double rate);
  // The plan's noises as they are added to the reverberant speech. `channel` < 0: the mono form
  // (channel 0 of every noise and noise RIR, with rate_policy.h's warning); else as microphone
  // `channel` of an array receives them (wav-reverberate's multichannel rules, wav_reverberate.h):
  // a noise with an RIR is its channel 0 through that RIR's channel `channel`, one without is its
  // own channel `channel` (it must have one per microphone).
  std::vector<AdditiveSignal> additive_signals(const RecordingPlan& plan, double rate, int channel = -1);
  // The far-field copy of `speech` (one channel at `rate`), before any encoding.
  std::vector<float> render(const std::vector<float>& speech, double rate, const RecordingPlan& plan);
  // Every channel of RIR `index` (a microphone array's) at `rate` (null for -1).
  using RirChannels = std::vector<std::unique_ptr<const PreparedRir>>;
  std::shared_ptr<const RirChannels> rir_channels(long index, double rate);
  // --multi-channel-output: one far-field channel per channel of the plan's RIR (one channel when
  // there is none), as wav-reverberate --multi-channel-output=true: channel c = render() of the
  // plan split to channel c (additive_signals(plan, rate, c), SNR against channel c's speech).
  std::vector<std::vector<float>> render_channels(const std::vector<float>& speech, double rate,
                                                  const RecordingPlan& plan);
  const ReverbOptions& reverb() const { return reverb_; }

 private:
  // Loads each (item, rate) once; other threads wanting the same one wait for that load.
  template <typename T>
  class LoadOnce {
   public:
    template <typename Load>
    std::shared_ptr<const T> get(const std::pair<long, double>& key, Load load);

   private:
    struct Slot {
      std::once_flag once;
      std::shared_ptr<const T> value;
      std::exception_ptr error;
    };
    std::mutex mutex_;
    std::map<std::pair<long, double>, std::shared_ptr<Slot>> slots_;
  };

  const AugmentSources& sources_;
  ReverbOptions reverb_;
  LoadOnce<PreparedRir> rirs_;
  LoadOnce<RirChannels> rir_channels_;
  // Every channel of a noise at one rate, read (and resampled) once for both forms: the mono form
  // is channel 0, an array microphone's is its own channel. The multichannel warning is given once,
  // when the mono form is first taken (a mono-only run keeps the other channels too).
  struct NoiseChannels {
    explicit NoiseChannels(std::vector<std::vector<float>>&& c) : channels(std::move(c)) {}
    std::vector<std::vector<float>> channels;
    mutable std::once_flag mono_warning;
  };
  LoadOnce<NoiseChannels> noises_;
  std::shared_ptr<const NoiseChannels> noise_channels(long index, double rate);
  // Channel 0 of noise `index` at `rate` (the mono form, with rate_policy.h's warning).
  std::shared_ptr<const std::vector<float>> mono_noise(long index, double rate);
  // Channel `channel` of noise `index` / of RIR `index` at `rate`, or an error naming the file,
  // its channel count and (`user`) what needed the channel.
  std::shared_ptr<const std::vector<float>> noise_channel(long index, double rate, int channel);
  std::shared_ptr<const PreparedRir> rir_channel(long index, double rate, int channel, const std::string& user);
};

}  // namespace tsrir
