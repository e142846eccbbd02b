#include "augment/plan_renderer.h"

#include "augment/noise_signal.h"
#include "augment/rate_policy.h"
#include "augment/wav_reverberate.h"
#include "util/error.h"

namespace tsrir {
namespace {

// A noise as errors and warnings name it.
std::string noise_where(const NoiseChoice& choice) { return choice.where + " (noise '" + choice.id + "')"; }

}  // namespace

template <typename T>
template <typename Load>
std::shared_ptr<const T> PlanRenderer::LoadOnce<T>::get(const std::pair<long, double>& key, Load load) {
  std::shared_ptr<Slot> slot;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    auto& s = slots_[key];
    if (!s) s = std::make_shared<Slot>();
    slot = s;
  }
  std::call_once(slot->once, [&] {
    try {
      slot->value = std::make_shared<const T>(load());
    } catch (...) {
      slot->error = std::current_exception();
    }
  });
  if (slot->error) std::rethrow_exception(slot->error);
  return slot->value;
}

PlanRenderer::PlanRenderer(const AugmentSources& sources, ReverbOptions reverb)
    : sources_(sources), reverb_(std::move(reverb)) {}

std::shared_ptr<const PreparedRir> PlanRenderer::rir(long index, double rate) {
  if (index < 0) return nullptr;
  const RirChoice& choice = sources_.rirs[static_cast<size_t>(index)];
  return rirs_.get({index, rate}, [&] {
    const std::string what = choice.where + " (RIR '" + choice.id + "')";
    return PreparedRir(first_channel_of(read_channels_at_rate(choice.rxfilename, rate, what), what), rate);
  });
}

std::shared_ptr<const PlanRenderer::RirChannels> PlanRenderer::rir_channels(long index, double rate) {
  if (index < 0) return nullptr;
  const RirChoice& choice = sources_.rirs[static_cast<size_t>(index)];
  return rir_channels_.get({index, rate}, [&] {
    const std::string what = choice.where + " (RIR '" + choice.id + "')";
    RirChannels channels;
    for (std::vector<float>& c : read_channels_at_rate(choice.rxfilename, rate, what)) {
      channels.push_back(std::make_unique<const PreparedRir>(std::move(c), rate));
    }
    return channels;
  });
}

std::shared_ptr<const PreparedRir> PlanRenderer::rir_channel(long index, double rate, int channel,
                                                             const std::string& user) {
  const std::shared_ptr<const RirChannels> channels = rir_channels(index, rate);
  if (!channels) return nullptr;
  if (static_cast<size_t>(channel) >= channels->size()) {
    const RirChoice& choice = sources_.rirs[static_cast<size_t>(index)];
    throw Error(choice.where + " (RIR '" + choice.id + "'): has " + std::to_string(channels->size()) +
                " channel(s), no channel " + std::to_string(channel) + user);
  }
  // Shares ownership of all the RIR's channels (aliasing constructor).
  return std::shared_ptr<const PreparedRir>(channels, (*channels)[static_cast<size_t>(channel)].get());
}

std::shared_ptr<const PreparedRir> PlanRenderer::speech_rir(const RecordingPlan& plan, double rate) {
  if (plan.rir_channel < 0) return rir(plan.rir, rate);
  return rir_channel(plan.rir, rate, plan.rir_channel, "");
}

std::vector<std::vector<float>> PlanRenderer::render_channels(const std::vector<float>& speech, double rate,
                                                              const RecordingPlan& plan) {
  const std::shared_ptr<const RirChannels> rirs = rir_channels(plan.rir, rate);
  if (!rirs) return {render(speech, rate, plan)};
  std::vector<std::vector<float>> out;
  for (size_t c = 0; c < rirs->size(); ++c) {
    out.push_back(reverberate_channel(speech, rate, (*rirs)[c].get(),
                                      additive_signals(plan, rate, static_cast<int>(c)), reverb_));
  }
  return out;
}

std::shared_ptr<const PlanRenderer::NoiseChannels> PlanRenderer::noise_channels(long index, double rate) {
  const NoiseChoice& choice = sources_.noises[static_cast<size_t>(index)];
  return noises_.get({index, rate},
                     [&] { return read_channels_at_rate(choice.rxfilename, rate, noise_where(choice)); });
}

std::shared_ptr<const std::vector<float>> PlanRenderer::mono_noise(long index, double rate) {
  const std::shared_ptr<const NoiseChannels> noise = noise_channels(index, rate);
  const NoiseChoice& choice = sources_.noises[static_cast<size_t>(index)];
  if (noise->channels.empty()) throw Error(noise_where(choice) + ": no audio channels");
  std::call_once(noise->mono_warning,
                 [&] { warn_channel_used(static_cast<int>(noise->channels.size()), 0, noise_where(choice), ""); });
  return std::shared_ptr<const std::vector<float>>(noise, &noise->channels[0]);
}

std::shared_ptr<const std::vector<float>> PlanRenderer::noise_channel(long index, double rate, int channel) {
  const std::shared_ptr<const NoiseChannels> noise = noise_channels(index, rate);
  const std::vector<std::vector<float>>& channels = noise->channels;
  if (static_cast<size_t>(channel) >= channels.size())
    throw Error(noise_where(sources_.noises[static_cast<size_t>(index)]) + ": has " +
                std::to_string(channels.size()) + " channel(s), but microphone " + std::to_string(channel) +
                " of the array needs its own: a noise added without an RIR needs one channel per channel of " +
                "the speech's RIR (as wav-reverberate --multi-channel-output)");
  return std::shared_ptr<const std::vector<float>>(noise, &channels[static_cast<size_t>(channel)]);
}

std::vector<AdditiveSignal> PlanRenderer::additive_signals(const RecordingPlan& plan, double rate, int channel) {
  std::vector<AdditiveSignal> additive;
  for (const PlannedNoise& planned : plan.noises) {
    const NoiseChoice& choice = sources_.noises[static_cast<size_t>(planned.noise)];
    std::shared_ptr<const std::vector<float>> noise;
    std::shared_ptr<const PreparedRir> noise_rir;
    if (channel < 0 || planned.rir >= 0) {
      noise = mono_noise(planned.noise, rate);
      noise_rir = channel < 0 ? rir(planned.rir, rate)
                              : rir_channel(planned.rir, rate, channel,
                                            " for the point-source noise " + noise_where(choice));
    } else {
      noise = noise_channel(planned.noise, rate, channel);
    }
    additive.push_back(planned_noise_signal(planned, noise, noise_rir.get(), rate));
  }
  return additive;
}

std::vector<float> PlanRenderer::render(const std::vector<float>& speech, double rate, const RecordingPlan& plan) {
  const std::shared_ptr<const PreparedRir> rir = speech_rir(plan, rate);
  const std::vector<AdditiveSignal> additive = additive_signals(plan, rate, plan.rir >= 0 ? plan.rir_channel : -1);
  return reverberate_channel(speech, rate, rir.get(), additive, reverb_);
}

}  // namespace tsrir
