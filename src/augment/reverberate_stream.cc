#include "augment/reverberate_stream.h"

#include <algorithm>
#include <memory>

#include "augment/reverb_steps.h"
#include "augment/stream_convolution.h"
#include "augment/temp_file.h"
#include "augment/wav_sink.h"
#include "util/error.h"

namespace tsrir {
namespace {

// One block of channel `channel` of the reader's frames into *x; returns the frames read.
size_t read_channel(AudioFileReader& reader, int channel, size_t block_frames, std::vector<float>* interleaved,
                    std::vector<float>* x) {
  const size_t frames = reader.read(interleaved, block_frames);
  const size_t ch = static_cast<size_t>(reader.info().channels);
  if (ch == 1) {
    x->swap(*interleaved);
    return frames;
  }
  x->resize(frames);
  for (size_t f = 0; f < frames; ++f) (*x)[f] = (*interleaved)[f * ch + static_cast<size_t>(channel)];
  return frames;
}

// Pass 2's per-channel state: y = x ⊛ h (or x) plus noise, arriving in runs.
struct ChannelPass {
  std::vector<AdditivePlacement> placements;
  OutputGeometry geometry;
  PowerSum power_after;
  std::unique_ptr<StreamingConvolution> convolution;  // null: no RIR
  std::vector<float> pending;                          // direct output: samples not yet written
};

}  // namespace

StreamResult reverberate_stream(const std::string& input_path, const std::string& context,
                                const std::string& shown_name, int input_channel,
                                const std::vector<StreamChannel>& channels, const ReverbOptions& options,
                                const std::string& output_wx, const StreamSettings& settings) {
  if (channels.empty()) throw Error("no output channels");
  const size_t num_out = channels.size();
  const size_t block_frames = std::max<size_t>(1, settings.block_frames);
  std::vector<float> interleaved, x;

  // Pass 1: input power, length, SNR reference energies.
  AudioFileReader first_reader(input_path, context, shown_name);
  const double fs = first_reader.info().sample_rate_hz;
  if (input_channel < 0 || input_channel >= first_reader.info().channels)
    throw Error((context.empty() ? std::string("input") : context) + ": channel " + std::to_string(input_channel) +
                " requested but it has " + std::to_string(first_reader.info().channels) + " channel(s)");
  PowerSum power_before;
  std::vector<PowerSum> reference_power(num_out);
  std::vector<std::unique_ptr<StreamingConvolution>> reference_convolution(num_out);
  for (size_t c = 0; c < num_out; ++c) {
    const PreparedRir* rir = channels[c].rir;
    // As in memory: the reference is needed only for additive signals' scales.
    if (!rir || channels[c].additive.empty()) continue;
    const Convolver& engine =
        options.snr_reference == SnrReference::kEarlyReverb ? rir->early_convolver() : rir->full_convolver();
    PowerSum* sum = &reference_power[c];
    reference_convolution[c] = std::make_unique<StreamingConvolution>(
        engine, [sum](size_t, float* y, size_t count) { sum->add(y, count); }, settings.chunk_samples);
  }
  size_t n = 0;
  while (const size_t frames = read_channel(first_reader, input_channel, block_frames, &interleaved, &x)) {
    power_before.add(x.data(), frames);
    for (auto& convolution : reference_convolution)
      if (convolution) convolution->push(x.data(), frames);
    n += frames;
  }
  std::vector<double> reference_energy(num_out, power_before.mean());
  for (size_t c = 0; c < num_out; ++c) {
    if (!reference_convolution[c]) continue;
    reference_convolution[c]->finish();
    reference_convolution[c].reset();
    const double mean = reference_power[c].mean();
    reference_energy[c] = options.snr_reference == SnrReference::kEarlyReverb
                              ? early_energy_from_padded_power(mean, n, *channels[c].rir)
                              : mean;
  }

  // What pass 2 adds and keeps, per channel; all channels have the same output length.
  std::vector<ChannelPass> pass(num_out);
  for (size_t c = 0; c < num_out; ++c) {
    const PreparedRir* rir = channels[c].rir;
    const size_t y_length = rir ? n + rir->size() - 1 : n;
    for (size_t i = 0; i < channels[c].additive.size(); ++i)
      pass[c].placements.push_back(place_additive(channels[c].additive[i], i, y_length, fs, reference_energy[c],
                                                  options.loop_additive_signals || channels[c].additive[i].loop));
    pass[c].geometry = output_geometry(n, rir, options, fs);
    if (pass[c].geometry.length != pass[0].geometry.length || pass[c].geometry.available != pass[0].geometry.available)
      throw Error("output channels differ in length (impulse responses of different lengths)");
  }
  const size_t frames_out = pass[0].geometry.length;
  // y[shift, shift + keep) is all the output reads: out[t] = gain * y[shift + t % keep].
  const size_t keep = std::min(pass[0].geometry.available, frames_out);
  wav_header(frames_out, static_cast<int>(num_out), fs, settings.format);  // beyond 4 GB: fail before the work
  const bool gain_known = options.volume > 0 || !options.normalize_output;
  // With the gain known and no tiling, pass 2 writes the output itself.
  const bool direct = gain_known && frames_out <= pass[0].geometry.available;
  std::vector<float> gain(num_out, static_cast<float>(output_gain(options, power_before.mean(), 0.0)));

  std::unique_ptr<TempFile> spill;
  std::unique_ptr<WavSink> sink;
  if (direct) {
    sink = std::make_unique<WavSink>(output_wx, static_cast<int>(num_out), frames_out, fs, settings.format);
  } else if (keep > 0) {
    spill = std::make_unique<TempFile>(settings.temp_base);
  }

  // Pass 2: y = x ⊛ h + noise, run by run.
  auto take_run = [&](size_t c, size_t first, float* y, size_t count) {
    ChannelPass& p = pass[c];
    for (const AdditivePlacement& placement : p.placements) add_placed(placement, first, y, count);
    if (!gain_known) p.power_after.add(y, count);
    const size_t lo = std::max(first, p.geometry.shift), hi = std::min(first + count, p.geometry.shift + keep);
    if (lo >= hi) return;
    const float* part = y + (lo - first);
    if (direct) {
      p.pending.insert(p.pending.end(), part, part + (hi - lo));
    } else {
      const uint64_t at = (static_cast<uint64_t>(c) * keep + (lo - p.geometry.shift)) * sizeof(float);
      spill->write_at(at, part, (hi - lo) * sizeof(float));
    }
  };
  std::vector<float> frames_buffer;
  auto write_pending = [&]() {
    size_t ready = pass[0].pending.size();
    for (const ChannelPass& p : pass) ready = std::min(ready, p.pending.size());
    if (ready == 0) return;
    frames_buffer.resize(ready * num_out);
    for (size_t c = 0; c < num_out; ++c) {
      const float* src = pass[c].pending.data();
      for (size_t f = 0; f < ready; ++f) frames_buffer[f * num_out + c] = gain[c] * src[f];
      pass[c].pending.erase(pass[c].pending.begin(), pass[c].pending.begin() + static_cast<long>(ready));
    }
    sink->write(frames_buffer.data(), ready);
  };
  for (size_t c = 0; c < num_out; ++c) {
    if (!channels[c].rir) continue;
    pass[c].convolution = std::make_unique<StreamingConvolution>(
        channels[c].rir->full_convolver(),
        [&take_run, c](size_t first, float* y, size_t count) { take_run(c, first, y, count); }, settings.chunk_samples);
  }
  AudioFileReader second_reader(input_path, context, shown_name);
  std::vector<float> own;
  size_t position = 0;
  while (const size_t frames = read_channel(second_reader, input_channel, block_frames, &interleaved, &x)) {
    for (size_t c = 0; c < num_out; ++c) {
      if (pass[c].convolution) {
        pass[c].convolution->push(x.data(), frames);
      } else {
        own.assign(x.begin(), x.begin() + static_cast<long>(frames));
        take_run(c, position, own.data(), frames);
      }
    }
    position += frames;
    if (direct) write_pending();
  }
  if (position != n)
    throw Error((context.empty() ? "" : context + ": ") + (shown_name.empty() ? input_path : shown_name) +
                ": the input changed while being read (" + std::to_string(n) + " frames, then " +
                std::to_string(position) + ")");
  for (ChannelPass& p : pass)
    if (p.convolution) p.convolution->finish();

  if (!direct) {
    // Pass 3: the gains are known now; scale, tile and encode the kept part of y.
    if (!gain_known)
      for (size_t c = 0; c < num_out; ++c)
        gain[c] = static_cast<float>(output_gain(options, power_before.mean(), pass[c].power_after.mean()));
    sink = std::make_unique<WavSink>(output_wx, static_cast<int>(num_out), frames_out, fs, settings.format);
    std::vector<float> run_buffer;
    for (size_t t = 0; t < frames_out;) {
      const size_t j = t % keep;
      const size_t run = std::min({block_frames, keep - j, frames_out - t});
      frames_buffer.resize(run * num_out);
      run_buffer.resize(run);
      for (size_t c = 0; c < num_out; ++c) {
        spill->read_at((static_cast<uint64_t>(c) * keep + j) * sizeof(float), run_buffer.data(), run * sizeof(float));
        for (size_t f = 0; f < run; ++f) frames_buffer[f * num_out + c] = gain[c] * run_buffer[f];
      }
      sink->write(frames_buffer.data(), run);
      t += run;
    }
  } else {
    write_pending();
  }
  sink->commit();
  StreamResult result;
  result.frames = frames_out;
  result.channels = static_cast<int>(num_out);
  result.clipped_samples = sink->clipped_samples();
  return result;
}

}  // namespace tsrir
