#include "io/audio_io.h"

#include <sndfile.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <utility>

#include "io/rxfile.h"
#include "io/sndfile_api.h"
#include "io/wav_reader.h"
#include "util/error.h"
#include "util/strings.h"

namespace tsrir {
namespace {

std::string name_of(const std::string& rx, const std::string& context) {
  return context.empty() ? rx : context + ": " + rx;
}

// In-memory source for libsndfile's virtual I/O (pipes, stdin, fuzzing).
struct MemoryFile {
  const std::vector<char>* bytes;
  sf_count_t pos = 0;
};
sf_count_t mem_len(void* u) { return static_cast<sf_count_t>(static_cast<MemoryFile*>(u)->bytes->size()); }
sf_count_t mem_seek(sf_count_t off, int whence, void* u) {
  auto* m = static_cast<MemoryFile*>(u);
  sf_count_t size = static_cast<sf_count_t>(m->bytes->size());
  sf_count_t base = whence == SEEK_SET ? 0 : whence == SEEK_CUR ? m->pos : size;
  sf_count_t p = base + off;
  if (p < 0 || p > size) return -1;
  m->pos = p;
  return p;
}
sf_count_t mem_read(void* ptr, sf_count_t count, void* u) {
  auto* m = static_cast<MemoryFile*>(u);
  sf_count_t size = static_cast<sf_count_t>(m->bytes->size());
  sf_count_t n = std::max<sf_count_t>(0, std::min(count, size - m->pos));
  if (n > 0) std::memcpy(ptr, m->bytes->data() + m->pos, static_cast<size_t>(n));
  m->pos += n;
  return n;
}
sf_count_t mem_write(const void*, sf_count_t, void*) { return 0; }
sf_count_t mem_tell(void* u) { return static_cast<MemoryFile*>(u)->pos; }

std::string format_name(int format) {
  SF_FORMAT_INFO info;
  std::string out;
  info.format = format & SF_FORMAT_TYPEMASK;
  if (sndfile().command(nullptr, SFC_GET_FORMAT_INFO, &info, sizeof info) == 0) out = info.name;
  info.format = format & SF_FORMAT_SUBMASK;
  if (sndfile().command(nullptr, SFC_GET_FORMAT_INFO, &info, sizeof info) == 0) out += std::string(" ") + info.name;
  return out;
}

// libsndfile silently shortens a WAV whose header claims more data than the file holds; its
// log says "data : N (should be M)". A lying header is a truncated file to us -- except for the
// placeholder sizes of writers that cannot seek back (sox to a pipe writes 0x7FFFF000, others
// 0xFFFFFFFF): like Kaldi's wave reader, those mean "read to the end of the stream".
void check_header_sizes(SNDFILE* f, const std::string& name) {
  char log[8192];
  sndfile().command(f, SFC_GET_LOG_INFO, log, sizeof log);
  std::istringstream log_lines(log);
  for (std::string line; std::getline(log_lines, line);) {
    if (starts_with(line, "data") && line.find("should be") != std::string::npos) {
      const bool stream_placeholder = line.find(": 2147479552 ") != std::string::npos ||
                                      line.find(": 4294967295 ") != std::string::npos;
      if (!stream_placeholder) {
        throw Error(name + ": truncated audio file (header and data size disagree: " + trim(line) + ")");
      }
    }
  }
}

void check_finite(const float* interleaved, size_t count, int channels, long long first_frame,
                  const std::string& name) {
  for (size_t i = 0; i < count; ++i) {
    if (!std::isfinite(interleaved[i])) {
      throw Error(name + ": NaN or Inf sample at frame " + std::to_string(first_frame + static_cast<long long>(i / channels)) +
                  " channel " + std::to_string(i % channels));
    }
  }
}

// Reads all frames from an open handle; checks truncation, emptiness and finiteness.
std::vector<std::vector<float>> read_all(SNDFILE* f, const SF_INFO& info, const std::string& name) {
  check_header_sizes(f, name);
  if (info.channels <= 0) throw Error(name + ": no audio channels");
  if (info.frames <= 0) throw Error(name + ": zero-length audio");
  const int ch = info.channels;
  // Decoded straight into one buffer (no per-block copy), ~64k samples per read whatever the
  // channel count. The header's frame count only sizes the first reservation, capped, so a lying
  // header cannot make a small file allocate much. A mono file (the usual case) is moved out
  // without a second copy: a 2-hour 16 kHz utterance peaks near 1x its size instead of ~3x.
  const sf_count_t block_frames = std::max<sf_count_t>(1, 65536 / ch);
  std::vector<float> interleaved;
  interleaved.reserve(static_cast<size_t>(std::min<sf_count_t>(info.frames, (sf_count_t{1} << 26) / ch)) * ch);
  for (;;) {
    const size_t old = interleaved.size();
    interleaved.resize(old + static_cast<size_t>(block_frames) * ch);
    sf_count_t got = sndfile().readf_float(f, interleaved.data() + old, block_frames);
    interleaved.resize(old + static_cast<size_t>(std::max<sf_count_t>(got, 0)) * ch);
    if (got <= 0) break;
  }
  if (sndfile().error(f) != SF_ERR_NO_ERROR) throw Error(name + ": cannot decode audio: " + sndfile().strerror(f));
  const size_t frames = interleaved.size() / ch;
  if (frames == 0) throw Error(name + ": zero-length audio");
  if (static_cast<sf_count_t>(frames) < info.frames) {
    throw Error(name + ": truncated audio file (" + std::to_string(frames) + " of " +
                std::to_string(info.frames) + " frames decodable)");
  }
  check_finite(interleaved.data(), interleaved.size(), ch, 0, name);
  std::vector<std::vector<float>> channels(ch);
  if (ch == 1) {
    channels[0] = std::move(interleaved);
    return channels;
  }
  for (auto& c : channels) c.resize(frames);
  for (size_t n = 0; n < frames; ++n)
    for (int c = 0; c < ch; ++c) channels[c][n] = interleaved[n * ch + c];
  return channels;
}

void fill_info(const SF_INFO& sf, AudioInfo* info) {
  if (!info) return;
  info->sample_rate_hz = sf.samplerate;
  info->channels = sf.channels;
  info->frames = sf.frames;
  info->format = format_name(sf.format);
  info->int16_samples = (sf.format & SF_FORMAT_SUBMASK) == SF_FORMAT_PCM_16;
}

Signal select_channel(std::vector<std::vector<float>>&& channels, double rate, const AudioReadOptions& o,
                      const std::string& name) {
  Signal s;
  s.sample_rate_hz = rate;
  const int n = static_cast<int>(channels.size());
  if (o.channel >= 0) {
    if (o.channel >= n) {
      throw Error(name + ": channel " + std::to_string(o.channel) + " requested but the file has " +
                  std::to_string(n) + " channel(s)");
    }
    s.samples = std::move(channels[o.channel]);
  } else {
    s.samples.assign(channels[0].size(), 0.0f);
    for (const auto& c : channels)
      for (size_t i = 0; i < c.size(); ++i) s.samples[i] += c[i] / n;
  }
  if (o.target_rate_hz > 0 && std::fabs(o.target_rate_hz - rate) > 1e-9) {
    // A header claiming e.g. 1 Hz would otherwise be resampled 16000-fold (1 GB per second).
    if (!(o.target_rate_hz / rate <= kMaxResampleRatio && rate / o.target_rate_hz <= kMaxResampleRatio)) {
      throw Error(name + ": sample rate " + format_double(rate) + " Hz cannot be resampled to " +
                  format_double(o.target_rate_hz) + " Hz (ratio beyond " + format_double(kMaxResampleRatio) +
                  "; is the header's sample rate right?)");
    }
    s.samples = resample(s.samples, rate, o.target_rate_hz);
    s.sample_rate_hz = o.target_rate_hz;
  }
  return s;
}

struct SndFileCloser {
  void operator()(SNDFILE* f) const { sndfile().close(f); }
};
using SndFile = std::unique_ptr<SNDFILE, SndFileCloser>;

// The one place a file is opened for reading. A file that cannot be read at all gets the system's
// reason; one that libsndfile cannot decode gets libsndfile's.
SndFile open_for_reading(const std::string& path, SF_INFO* sf, const std::string& name) {
  *sf = SF_INFO{};
  SndFile f(sndfile().open(path.c_str(), SFM_READ, sf));
  if (!f) {
    std::ifstream probe(path, std::ios::binary);
    if (!probe) throw Error(name + ": cannot open: " + std::strerror(errno));
    throw Error(name + ": unreadable or unsupported audio: " + sndfile().strerror(nullptr));
  }
  return f;
}

void fill_info(const PlainWavLayout& layout, AudioInfo* info) {
  if (!info) return;
  info->sample_rate_hz = layout.sample_rate_hz;
  info->channels = layout.channels;
  info->frames = static_cast<long long>(layout.frames);
  info->format = layout.format_name();
  info->int16_samples = layout.bits == 16 && !layout.is_float;
}

}  // namespace

AudioInfo probe_audio(const std::string& path) {
  MappedFile mapped;
  PlainWavLayout layout;
  if (mapped.open(path, /*populate=*/false) && parse_plain_wav(mapped.data(), mapped.size(), &layout)) {
    AudioInfo info;
    fill_info(layout, &info);
    return info;
  }
  SF_INFO sf{};
  open_for_reading(path, &sf, path);
  AudioInfo info;
  fill_info(sf, &info);
  return info;
}

std::vector<std::vector<float>> decode_audio_bytes(const std::vector<char>& bytes, AudioInfo* info,
                                                   const std::string& name) {
  if (bytes.empty()) throw Error(name + ": empty input (no audio data)");
  PlainWavLayout layout;
  if (parse_plain_wav(bytes.data(), bytes.size(), &layout)) {
    std::vector<std::vector<float>> channels;
    decode_plain_wav(bytes.data(), layout, 0, layout.frames, name, &channels);
    fill_info(layout, info);
    return channels;
  }
  MemoryFile mem{&bytes, 0};
  SF_VIRTUAL_IO vio{mem_len, mem_seek, mem_read, mem_write, mem_tell};
  SF_INFO sf{};
  SndFile f(sndfile().open_virtual(&vio, SFM_READ, &sf, &mem));
  if (!f) throw Error(name + ": unreadable or unsupported audio: " + sndfile().strerror(nullptr));
  auto channels = read_all(f.get(), sf, name);
  fill_info(sf, info);
  return channels;
}

std::vector<std::vector<float>> read_audio_channels(const std::string& rx, AudioInfo* info,
                                                    const std::string& context) {
  return read_audio_channels_prefix(rx, static_cast<size_t>(-1), info, context);
}

std::vector<std::vector<float>> read_audio_channels_prefix(const std::string& rx, size_t max_frames, AudioInfo* info,
                                                           const std::string& context) {
  const std::string name = name_of(rx, context);
  std::string t = trim(rx);
  auto cut = [max_frames](std::vector<std::vector<float>> channels) {
    for (auto& c : channels)
      if (c.size() > max_frames) c.resize(max_frames);
    return channels;
  };
  if (t == "-" || is_pipe_rxfilename(t)) return cut(decode_audio_bytes(read_rxfile(rx, context), info, name));
  {
    MappedFile mapped;
    PlainWavLayout layout;
    // A prefix (a 30 s noise cut to a 10 s utterance) prefaults only the samples it decodes.
    const bool whole = max_frames == static_cast<size_t>(-1);
    if (mapped.open(rx, whole) && parse_plain_wav(mapped.data(), mapped.size(), &layout)) {
      // Integer samples cannot be NaN or Inf: a prefix needs no look at the rest.
      const size_t count = layout.is_float ? layout.frames : std::min(layout.frames, max_frames);
      if (!whole)
        mapped.populate_range(layout.data_offset,
                              count * static_cast<size_t>(layout.channels) * static_cast<size_t>(layout.bits / 8));
      std::vector<std::vector<float>> channels;
      decode_plain_wav(mapped.data(), layout, 0, count, name, &channels);
      fill_info(layout, info);
      return cut(std::move(channels));
    }
  }
  SF_INFO sf{};
  const SndFile f = open_for_reading(rx, &sf, name);
  auto channels = read_all(f.get(), sf, name);
  fill_info(sf, info);
  return cut(std::move(channels));
}

struct AudioFileReader::SoundFile {
  SndFile handle;
};

AudioFileReader::AudioFileReader(const std::string& path, const std::string& context, const std::string& shown_name)
    : name_(name_of(shown_name.empty() ? path : shown_name, context)) {
  SF_INFO sf{};
  SndFile f = open_for_reading(path, &sf, name_);
  check_header_sizes(f.get(), name_);
  if (sf.channels <= 0) throw Error(name_ + ": no audio channels");
  if (sf.frames <= 0) throw Error(name_ + ": zero-length audio");
  file_ = std::make_unique<SoundFile>(SoundFile{std::move(f)});
  fill_info(sf, &info_);
}

AudioFileReader::~AudioFileReader() = default;

size_t AudioFileReader::read(std::vector<float>* interleaved, size_t max_frames) {
  SNDFILE* f = file_->handle.get();
  const size_t ch = static_cast<size_t>(info_.channels);
  interleaved->resize(max_frames * ch);
  const sf_count_t got =
      max_frames ? sndfile().readf_float(f, interleaved->data(), static_cast<sf_count_t>(max_frames)) : 0;
  const size_t frames = static_cast<size_t>(std::max<sf_count_t>(got, 0));
  interleaved->resize(frames * ch);
  if (sndfile().error(f) != SF_ERR_NO_ERROR) throw Error(name_ + ": cannot decode audio: " + sndfile().strerror(f));
  check_finite(interleaved->data(), interleaved->size(), info_.channels, frames_read_, name_);
  frames_read_ += static_cast<long long>(frames);
  if (frames == 0 && max_frames > 0) {
    // The end: the same checks as a whole-file read.
    if (frames_read_ == 0) throw Error(name_ + ": zero-length audio");
    if (frames_read_ < info_.frames) {
      throw Error(name_ + ": truncated audio file (" + std::to_string(frames_read_) + " of " +
                  std::to_string(info_.frames) + " frames decodable)");
    }
  }
  return frames;
}

Signal read_audio(const std::string& rx, const AudioReadOptions& options) {
  AudioInfo info;
  auto channels = read_audio_channels(rx, &info, options.context);
  return select_channel(std::move(channels), info.sample_rate_hz, options, name_of(rx, options.context));
}

}  // namespace tsrir
