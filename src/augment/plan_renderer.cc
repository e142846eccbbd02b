#include "augment/plan_renderer.h"

#include "augment/noise_signal.h"
#include "augment/rate_policy.h"
#include "augment/wav_reverberate.h"
#include "util/error.h"

namespace tsrir {

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

std::shared_ptr<const PreparedRir> PlanRenderer::speech_rir(const RecordingPlan& plan, double rate) {
  if (plan.rir_channel < 0) return rir(plan.rir, rate);
  const std::shared_ptr<const RirChannels> channels = rir_channels(plan.rir, rate);
  if (!channels) return nullptr;
  if (static_cast<size_t>(plan.rir_channel) >= channels->size()) {
    const RirChoice& choice = sources_.rirs[static_cast<size_t>(plan.rir)];
    throw Error(choice.where + " (RIR '" + choice.id + "'): has " + std::to_string(channels->size()) +
                " channel(s), no channel " + std::to_string(plan.rir_channel));
  }
  // Shares ownership of all the RIR's channels (aliasing constructor).
  return std::shared_ptr<const PreparedRir>(channels, (*channels)[static_cast<size_t>(plan.rir_channel)].get());
}

std::vector<std::vector<float>> PlanRenderer::render_channels(const std::vector<float>& speech, double rate,
                                                              const RecordingPlan& plan) {
  if (!plan.noises.empty()) throw Error("multichannel output adds no noises, but the plan has some");
  const std::shared_ptr<const RirChannels> rirs = rir_channels(plan.rir, rate);
  if (!rirs) return {reverberate_channel(speech, rate, nullptr, {}, reverb_)};
  std::vector<std::vector<float>> out;
  for (const auto& rir : *rirs) out.push_back(reverberate_channel(speech, rate, rir.get(), {}, reverb_));
  return out;
}

std::vector<AdditiveSignal> PlanRenderer::additive_signals(const RecordingPlan& plan, double rate) {
  std::vector<AdditiveSignal> additive;
  for (const PlannedNoise& planned : plan.noises) {
    const NoiseChoice& choice = sources_.noises[static_cast<size_t>(planned.noise)];
    std::shared_ptr<const std::vector<float>> noise = noises_.get({planned.noise, rate}, [&] {
      const std::string what = choice.where + " (noise '" + choice.id + "')";
      return first_channel_of(read_channels_at_rate(choice.rxfilename, rate, what), what);
    });
    const std::shared_ptr<const PreparedRir> noise_rir = rir(planned.rir, rate);
    additive.push_back(planned_noise_signal(planned, noise, noise_rir.get(), rate));
  }
  return additive;
}

std::vector<float> PlanRenderer::render(const std::vector<float>& speech, double rate, const RecordingPlan& plan) {
  const std::shared_ptr<const PreparedRir> rir = speech_rir(plan, rate);
  const std::vector<AdditiveSignal> additive = additive_signals(plan, rate);
  return reverberate_channel(speech, rate, rir.get(), additive, reverb_);
}

}  // namespace tsrir
