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

// The three passes over one input file (reverberate_stream.h), with what each leaves for the next.
class StreamReverberator {
 public:
  StreamReverberator(const std::string& input_path, const std::string& context, const std::string& shown_name,
                     int input_channel, const std::vector<StreamChannel>& channels, const ReverbOptions& options,
                     const StreamSettings& settings)
      : input_path_(input_path), context_(context), shown_name_(shown_name), input_channel_(input_channel),
        channels_(channels), options_(options), settings_(settings), num_out_(channels.size()),
        block_frames_(std::max<size_t>(1, settings.block_frames)) {}

  // Pass 1: input power, length, SNR reference energies.
  void measure_input() {
    AudioFileReader reader(input_path_, context_, shown_name_);
    fs_ = reader.info().sample_rate_hz;
    if (input_channel_ < 0 || input_channel_ >= reader.info().channels)
      throw Error((context_.empty() ? std::string("input") : context_) + ": channel " + std::to_string(input_channel_) +
                  " requested but it has " + std::to_string(reader.info().channels) + " channel(s)");
    std::vector<PowerSum> reference_power(num_out_);
    std::vector<std::unique_ptr<StreamingConvolution>> reference_convolution(num_out_);
    for (size_t c = 0; c < num_out_; ++c) {
      const PreparedRir* rir = channels_[c].rir;
      // As in memory: the reference is needed only for additive signals' scales.
      if (!rir || channels_[c].additive.empty()) continue;
      const Convolver& engine =
          options_.snr_reference == SnrReference::kEarlyReverb ? rir->early_convolver() : rir->full_convolver();
      PowerSum* sum = &reference_power[c];
      reference_convolution[c] = std::make_unique<StreamingConvolution>(
          engine, [sum](size_t, float* y, size_t count) { sum->add(y, count); }, settings_.chunk_samples);
    }
    while (const size_t frames = read_channel(reader, input_channel_, block_frames_, &interleaved_, &x_)) {
      power_before_.add(x_.data(), frames);
      for (auto& convolution : reference_convolution)
        if (convolution) convolution->push(x_.data(), frames);
      n_ += frames;
    }
    reference_energy_.assign(num_out_, power_before_.mean());
    for (size_t c = 0; c < num_out_; ++c) {
      if (!reference_convolution[c]) continue;
      reference_convolution[c]->finish();
      reference_convolution[c].reset();
      const double mean = reference_power[c].mean();
      reference_energy_[c] = options_.snr_reference == SnrReference::kEarlyReverb
                                 ? early_energy_from_padded_power(mean, n_, *channels_[c].rir)
                                 : mean;
    }
  }

  // What pass 2 adds and keeps, per channel (all channels have the same output length), and where
  // it goes: straight to the output when the gain is known and nothing is tiled, else to a spill file.
  void place_output(const std::string& output_wx) {
    pass_.resize(num_out_);
    for (size_t c = 0; c < num_out_; ++c) {
      const PreparedRir* rir = channels_[c].rir;
      const size_t y_length = rir ? n_ + rir->size() - 1 : n_;
      for (size_t i = 0; i < channels_[c].additive.size(); ++i)
        pass_[c].placements.push_back(place_additive(channels_[c].additive[i], i, y_length, fs_, reference_energy_[c],
                                                     options_.loop_additive_signals || channels_[c].additive[i].loop));
      pass_[c].geometry = output_geometry(n_, rir, options_, fs_);
      if (pass_[c].geometry.length != pass_[0].geometry.length ||
          pass_[c].geometry.available != pass_[0].geometry.available)
        throw Error("output channels differ in length (impulse responses of different lengths)");
    }
    frames_out_ = pass_[0].geometry.length;
    // y[shift, shift + keep) is all the output reads: out[t] = gain * y[shift + t % keep].
    keep_ = std::min(pass_[0].geometry.available, frames_out_);
    wav_header(frames_out_, static_cast<int>(num_out_), fs_, settings_.format);  // beyond 4 GB: fail before the work
    gain_known_ = options_.volume > 0 || !options_.normalize_output;
    direct_ = gain_known_ && frames_out_ <= pass_[0].geometry.available;
    gain_.assign(num_out_, static_cast<float>(output_gain(options_, power_before_.mean(), 0.0)));
    if (direct_) {
      sink_ = std::make_unique<WavSink>(output_wx, static_cast<int>(num_out_), frames_out_, fs_, settings_.format);
    } else if (keep_ > 0) {
      spill_ = std::make_unique<TempFile>(settings_.temp_base);
    }
  }

  // Pass 2: y = x ⊛ h + noise, run by run.
  void reverberate() {
    for (size_t c = 0; c < num_out_; ++c) {
      if (!channels_[c].rir) continue;
      pass_[c].convolution = std::make_unique<StreamingConvolution>(
          channels_[c].rir->full_convolver(),
          [this, c](size_t first, float* y, size_t count) { take_run(c, first, y, count); }, settings_.chunk_samples);
    }
    AudioFileReader reader(input_path_, context_, shown_name_);
    std::vector<float> own;
    size_t position = 0;
    while (const size_t frames = read_channel(reader, input_channel_, block_frames_, &interleaved_, &x_)) {
      for (size_t c = 0; c < num_out_; ++c) {
        if (pass_[c].convolution) {
          pass_[c].convolution->push(x_.data(), frames);
        } else {
          own.assign(x_.begin(), x_.begin() + static_cast<long>(frames));
          take_run(c, position, own.data(), frames);
        }
      }
      position += frames;
      if (direct_) write_pending();
    }
    if (position != n_)
      throw Error((context_.empty() ? "" : context_ + ": ") + (shown_name_.empty() ? input_path_ : shown_name_) +
                  ": the input changed while being read (" + std::to_string(n_) + " frames, then " +
                  std::to_string(position) + ")");
    for (ChannelPass& p : pass_)
      if (p.convolution) p.convolution->finish();
  }

  // Pass 3 (when pass 2 did not write the output): the gains are known now; scale, tile and encode
  // the kept part of y. Then the output is committed.
  StreamResult encode(const std::string& output_wx) {
    if (!direct_) {
      if (!gain_known_)
        for (size_t c = 0; c < num_out_; ++c)
          gain_[c] = static_cast<float>(output_gain(options_, power_before_.mean(), pass_[c].power_after.mean()));
      sink_ = std::make_unique<WavSink>(output_wx, static_cast<int>(num_out_), frames_out_, fs_, settings_.format);
      std::vector<float> run_buffer;
      for (size_t t = 0; t < frames_out_;) {
        const size_t j = t % keep_;
        const size_t run = std::min({block_frames_, keep_ - j, frames_out_ - t});
        frames_buffer_.resize(run * num_out_);
        run_buffer.resize(run);
        for (size_t c = 0; c < num_out_; ++c) {
          spill_->read_at((static_cast<uint64_t>(c) * keep_ + j) * sizeof(float), run_buffer.data(), run * sizeof(float));
          for (size_t f = 0; f < run; ++f) frames_buffer_[f * num_out_ + c] = gain_[c] * run_buffer[f];
        }
        sink_->write(frames_buffer_.data(), run);
        t += run;
      }
    } else {
      write_pending();
    }
    sink_->commit();
    StreamResult result;
    result.frames = frames_out_;
    result.channels = static_cast<int>(num_out_);
    result.clipped_samples = sink_->clipped_samples();
    return result;
  }

 private:
  // One run of channel c's y (samples [first, first + count)): noise added, power summed, and the
  // part the output reads kept.
  void take_run(size_t c, size_t first, float* y, size_t count) {
    ChannelPass& p = pass_[c];
    for (const AdditivePlacement& placement : p.placements) add_placed(placement, first, y, count);
    if (!gain_known_) p.power_after.add(y, count);
    const size_t lo = std::max(first, p.geometry.shift), hi = std::min(first + count, p.geometry.shift + keep_);
    if (lo >= hi) return;
    const float* part = y + (lo - first);
    if (direct_) {
      p.pending.insert(p.pending.end(), part, part + (hi - lo));
    } else {
      const uint64_t at = (static_cast<uint64_t>(c) * keep_ + (lo - p.geometry.shift)) * sizeof(float);
      spill_->write_at(at, part, (hi - lo) * sizeof(float));
    }
  }

  // Direct output: the frames every channel has ready, scaled and interleaved.
  void write_pending() {
    size_t ready = pass_[0].pending.size();
    for (const ChannelPass& p : pass_) ready = std::min(ready, p.pending.size());
    if (ready == 0) return;
    frames_buffer_.resize(ready * num_out_);
    for (size_t c = 0; c < num_out_; ++c) {
      const float* src = pass_[c].pending.data();
      for (size_t f = 0; f < ready; ++f) frames_buffer_[f * num_out_ + c] = gain_[c] * src[f];
      pass_[c].pending.erase(pass_[c].pending.begin(), pass_[c].pending.begin() + static_cast<long>(ready));
    }
    sink_->write(frames_buffer_.data(), ready);
  }

  const std::string& input_path_;
  const std::string& context_;
  const std::string& shown_name_;
  const int input_channel_;
  const std::vector<StreamChannel>& channels_;
  const ReverbOptions& options_;
  const StreamSettings& settings_;
  const size_t num_out_, block_frames_;
  std::vector<float> interleaved_, x_, frames_buffer_;
  // Pass 1's results.
  double fs_ = 0.0;
  size_t n_ = 0;
  PowerSum power_before_;
  std::vector<double> reference_energy_;
  // The output's shape and destination.
  std::vector<ChannelPass> pass_;
  size_t frames_out_ = 0, keep_ = 0;
  bool gain_known_ = false, direct_ = false;
  std::vector<float> gain_;
  std::unique_ptr<TempFile> spill_;
  std::unique_ptr<WavSink> sink_;
};

}  // namespace

StreamResult reverberate_stream(const std::string& input_path, const std::string& context,
                                const std::string& shown_name, int input_channel,
                                const std::vector<StreamChannel>& channels, const ReverbOptions& options,
                                const std::string& output_wx, const StreamSettings& settings) {
  if (channels.empty()) throw Error("no output channels");
  StreamReverberator stream(input_path, context, shown_name, input_channel, channels, options, settings);
  stream.measure_input();
  stream.place_output(output_wx);
  stream.reverberate();
  return stream.encode(output_wx);
}

}  // namespace tsrir
