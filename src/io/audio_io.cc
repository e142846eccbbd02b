#include "io/audio_io.h"

#include <sndfile.h>
#include <sox.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iostream>
#include <mutex>
#include <sstream>

#include "io/atomic_output.h"
#include "io/rxfile.h"
#include "util/error.h"
#include "util/strings.h"

namespace tsrir {
namespace {

// Real conversions stay far inside this (8 kHz <-> 192 kHz is 24); beyond it a header is lying.
constexpr double kMaxResampleRatio = 64.0;

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
  if (sf_command(nullptr, SFC_GET_FORMAT_INFO, &info, sizeof info) == 0) out = info.name;
  info.format = format & SF_FORMAT_SUBMASK;
  if (sf_command(nullptr, SFC_GET_FORMAT_INFO, &info, sizeof info) == 0) out += std::string(" ") + info.name;
  return out;
}

// libsndfile silently shortens a WAV whose header claims more data than the file holds; its
// log says "data : N (should be M)". A lying header is a truncated file to us -- except for the
// placeholder sizes of writers that cannot seek back (sox to a pipe writes 0x7FFFF000, others
// 0xFFFFFFFF): like Kaldi's wave reader, those mean "read to the end of the stream".
void check_header_sizes(SNDFILE* f, const std::string& name) {
  char log[8192];
  sf_command(f, SFC_GET_LOG_INFO, log, sizeof log);
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
    sf_count_t got = sf_readf_float(f, interleaved.data() + old, block_frames);
    interleaved.resize(old + static_cast<size_t>(std::max<sf_count_t>(got, 0)) * ch);
    if (got <= 0) break;
  }
  if (sf_error(f) != SF_ERR_NO_ERROR) throw Error(name + ": cannot decode audio: " + sf_strerror(f));
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

void put_u32(std::vector<char>& b, uint32_t v) {
  for (int i = 0; i < 4; ++i) b.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
}
void put_u16(std::vector<char>& b, uint16_t v) {
  b.push_back(static_cast<char>(v & 0xff));
  b.push_back(static_cast<char>(v >> 8));
}

std::once_flag g_sox_once;
std::mutex g_sox_mutex;

struct SoxSource {
  const float* data;
  size_t n, pos;
  double scale;
};
struct SoxSink {
  std::vector<float>* out;
  double scale;
};

int sox_source_drain(sox_effect_t* effp, sox_sample_t* obuf, size_t* osamp) {
  auto* src = *static_cast<SoxSource**>(effp->priv);
  size_t n = std::min(*osamp, src->n - src->pos);
  for (size_t i = 0; i < n; ++i) {
    double v = src->data[src->pos + i] * src->scale;
    obuf[i] = static_cast<sox_sample_t>(std::lround(std::clamp(v, -1.0, 1.0) * 2147483647.0));
  }
  src->pos += n;
  *osamp = n;
  return n ? SOX_SUCCESS : SOX_EOF;
}

int sox_sink_flow(sox_effect_t* effp, const sox_sample_t* ibuf, sox_sample_t*, size_t* isamp, size_t* osamp) {
  auto* sink = *static_cast<SoxSink**>(effp->priv);
  for (size_t i = 0; i < *isamp; ++i) sink->out->push_back(static_cast<float>(ibuf[i] / 2147483648.0 * sink->scale));
  *osamp = 0;
  return SOX_SUCCESS;
}

const sox_effect_handler_t* source_handler() {
  static sox_effect_handler_t h = {"tsrir_source", nullptr, SOX_EFF_MCHAN, nullptr, nullptr, nullptr,
                                   sox_source_drain, nullptr, nullptr, sizeof(SoxSource*)};
  return &h;
}
const sox_effect_handler_t* sink_handler() {
  static sox_effect_handler_t h = {"tsrir_sink", nullptr, SOX_EFF_MCHAN, nullptr, nullptr, sox_sink_flow,
                                   nullptr, nullptr, nullptr, sizeof(SoxSink*)};
  return &h;
}

}  // namespace

AudioInfo probe_audio(const std::string& path) {
  SF_INFO sf{};
  SNDFILE* f = sf_open(path.c_str(), SFM_READ, &sf);
  if (!f) throw Error(path + ": cannot open audio: " + sf_strerror(nullptr));
  sf_close(f);
  AudioInfo info;
  fill_info(sf, &info);
  return info;
}

std::vector<std::vector<float>> decode_audio_bytes(const std::vector<char>& bytes, AudioInfo* info,
                                                   const std::string& name) {
  if (bytes.empty()) throw Error(name + ": empty input (no audio data)");
  MemoryFile mem{&bytes, 0};
  SF_VIRTUAL_IO vio{mem_len, mem_seek, mem_read, mem_write, mem_tell};
  SF_INFO sf{};
  SNDFILE* f = sf_open_virtual(&vio, SFM_READ, &sf, &mem);
  if (!f) throw Error(name + ": unreadable or unsupported audio: " + sf_strerror(nullptr));
  try {
    auto channels = read_all(f, sf, name);
    fill_info(sf, info);
    sf_close(f);
    return channels;
  } catch (...) {
    sf_close(f);
    throw;
  }
}

std::vector<std::vector<float>> read_audio_channels(const std::string& rx, AudioInfo* info,
                                                    const std::string& context) {
  const std::string name = name_of(rx, context);
  std::string t = trim(rx);
  if (t == "-" || is_pipe_rxfilename(t)) return decode_audio_bytes(read_rxfile(rx, context), info, name);
  SF_INFO sf{};
  SNDFILE* f = sf_open(rx.c_str(), SFM_READ, &sf);
  if (!f) {
    std::ifstream probe(rx, std::ios::binary);
    if (!probe) throw Error(name + ": cannot open: " + std::strerror(errno));
    throw Error(name + ": unreadable or unsupported audio: " + sf_strerror(nullptr));
  }
  try {
    auto channels = read_all(f, sf, name);
    fill_info(sf, info);
    sf_close(f);
    return channels;
  } catch (...) {
    sf_close(f);
    throw;
  }
}

AudioFileReader::AudioFileReader(const std::string& path, const std::string& context, const std::string& shown_name)
    : name_(name_of(shown_name.empty() ? path : shown_name, context)) {
  SF_INFO sf{};
  SNDFILE* f = sf_open(path.c_str(), SFM_READ, &sf);
  if (!f) {
    std::ifstream probe(path, std::ios::binary);
    if (!probe) throw Error(name_ + ": cannot open: " + std::strerror(errno));
    throw Error(name_ + ": unreadable or unsupported audio: " + sf_strerror(nullptr));
  }
  try {
    check_header_sizes(f, name_);
    if (sf.channels <= 0) throw Error(name_ + ": no audio channels");
    if (sf.frames <= 0) throw Error(name_ + ": zero-length audio");
  } catch (...) {
    sf_close(f);
    throw;
  }
  file_ = f;
  fill_info(sf, &info_);
}

AudioFileReader::~AudioFileReader() {
  if (file_) sf_close(static_cast<SNDFILE*>(file_));
}

size_t AudioFileReader::read(std::vector<float>* interleaved, size_t max_frames) {
  SNDFILE* f = static_cast<SNDFILE*>(file_);
  const size_t ch = static_cast<size_t>(info_.channels);
  interleaved->resize(max_frames * ch);
  const sf_count_t got = max_frames ? sf_readf_float(f, interleaved->data(), static_cast<sf_count_t>(max_frames)) : 0;
  const size_t frames = static_cast<size_t>(std::max<sf_count_t>(got, 0));
  interleaved->resize(frames * ch);
  if (sf_error(f) != SF_ERR_NO_ERROR) throw Error(name_ + ": cannot decode audio: " + sf_strerror(f));
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

SampleFormat parse_sample_format(const std::string& name) {
  if (name == "int16") return SampleFormat::kInt16;
  if (name == "float" || name == "float32") return SampleFormat::kFloat32;
  throw Error("unknown sample format '" + name + "' (expected int16 or float)");
}

namespace {

// One sample as every WAV encoder here writes it; returns false for NaN/Inf (nothing appended).
inline bool put_sample(std::vector<char>& b, float v, bool is_float, long long* clipped) {
  if (!std::isfinite(v)) return false;
  if (is_float) {
    uint32_t u;
    std::memcpy(&u, &v, 4);
    put_u32(b, u);
  } else {
    // Round to nearest in float (exact for |v| < 2^8) and clip; Kaldi truncates toward zero.
    float s = std::nearbyint(v * 32768.0f);
    if (s > 32767.0f || s < -32768.0f) {
      ++*clipped;
      s = std::clamp(s, -32768.0f, 32767.0f);
    }
    put_u16(b, static_cast<uint16_t>(static_cast<int16_t>(s)));
  }
  return true;
}

}  // namespace

std::vector<char> wav_header(size_t frames, int channels, double sample_rate_hz, SampleFormat format) {
  if (channels <= 0 || channels > 65535) throw Error("cannot write audio with " + std::to_string(channels) + " channels");
  if (!(sample_rate_hz > 0) || sample_rate_hz > 4294967295.0) throw Error("cannot write audio: bad sample rate");
  const uint16_t nch = static_cast<uint16_t>(channels);
  const bool is_float = format == SampleFormat::kFloat32;
  const uint16_t bytes_per_sample = is_float ? 4 : 2;
  const uint64_t data_bytes = static_cast<uint64_t>(frames) * nch * bytes_per_sample;
  if (data_bytes > 0xFFFFFFFFull - 64) throw Error("cannot write audio: longer than a WAV file can hold (4 GB)");
  std::vector<char> b;
  b.reserve(44);
  b.insert(b.end(), {'R', 'I', 'F', 'F'});
  put_u32(b, static_cast<uint32_t>(36 + data_bytes));
  b.insert(b.end(), {'W', 'A', 'V', 'E', 'f', 'm', 't', ' '});
  put_u32(b, 16);
  put_u16(b, is_float ? 3 : 1);
  put_u16(b, nch);
  const uint32_t rate = static_cast<uint32_t>(std::lround(sample_rate_hz));
  put_u32(b, rate);
  put_u32(b, rate * nch * bytes_per_sample);
  put_u16(b, static_cast<uint16_t>(nch * bytes_per_sample));
  put_u16(b, static_cast<uint16_t>(8 * bytes_per_sample));
  b.insert(b.end(), {'d', 'a', 't', 'a'});
  put_u32(b, static_cast<uint32_t>(data_bytes));
  return b;
}

void append_wav_frames(const float* interleaved, size_t frames, int channels, SampleFormat format,
                       long long first_frame, std::vector<char>* out, long long* clipped) {
  const bool is_float = format == SampleFormat::kFloat32;
  const size_t count = frames * static_cast<size_t>(channels);
  out->reserve(out->size() + count * (is_float ? 4 : 2));
  long long clipped_here = 0;
  for (size_t i = 0; i < count; ++i) {
    if (!put_sample(*out, interleaved[i], is_float, &clipped_here))
      throw Error("cannot write audio: NaN or Inf sample at frame " +
                  std::to_string(first_frame + static_cast<long long>(i / static_cast<size_t>(channels))));
  }
  if (clipped) *clipped += clipped_here;
}

std::vector<char> encode_wav(const std::vector<std::vector<float>>& channels, double sample_rate_hz,
                             const AudioWriteOptions& options) {
  if (channels.empty()) throw Error("cannot write audio with no channels");
  const size_t frames = channels[0].size();
  for (const auto& c : channels)
    if (c.size() != frames) throw Error("cannot write audio: channels differ in length");
  if (!(sample_rate_hz > 0) || sample_rate_hz > 4294967295.0) throw Error("cannot write audio: bad sample rate");
  const uint16_t nch = static_cast<uint16_t>(channels.size());
  const bool is_float = options.format == SampleFormat::kFloat32;
  std::vector<char> b = wav_header(frames, nch, sample_rate_hz, options.format);
  b.reserve(b.size() + frames * nch * (is_float ? 4 : 2));
  long long clipped = 0;
  for (size_t n = 0; n < frames; ++n) {
    for (uint16_t c = 0; c < nch; ++c) {
      if (!put_sample(b, channels[c][n], is_float, &clipped))
        throw Error("cannot write audio: NaN or Inf sample at frame " + std::to_string(n));
    }
  }
  if (options.clipped_samples) *options.clipped_samples = clipped;
  return b;
}

void write_wav_channels(const std::string& path, const std::vector<std::vector<float>>& channels,
                        double sample_rate_hz, const AudioWriteOptions& options) {
  std::vector<char> bytes = encode_wav(channels, sample_rate_hz, options);
  if (path == "-") {
    std::cout.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    std::cout.flush();
    if (!std::cout) throw Error("error writing audio to standard output");
    return;
  }
  AtomicTextFile out(path);
  out.stream().write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.commit();
}

void write_wav(const std::string& path, const Signal& signal, const AudioWriteOptions& options) {
  write_wav_channels(path, {signal.samples}, signal.sample_rate_hz, options);
}

std::vector<float> resample(const std::vector<float>& samples, double from_hz, double to_hz) {
  if (!(from_hz > 0) || !(to_hz > 0)) throw Error("resample: sample rates must be positive");
  if (!(to_hz / from_hz <= kMaxResampleRatio && from_hz / to_hz <= kMaxResampleRatio)) {
    throw Error("resample: " + format_double(from_hz) + " Hz to " + format_double(to_hz) + " Hz is beyond the ratio " +
                format_double(kMaxResampleRatio));
  }
  if (std::fabs(from_hz - to_hz) < 1e-9 || samples.empty()) return samples;
  std::call_once(g_sox_once, []() {
    if (sox_init() != SOX_SUCCESS) throw Error("cannot initialise libsox");
    sox_globals.verbosity = 1;
  });
  double peak = 0.0;
  for (float v : samples) peak = std::max(peak, static_cast<double>(std::fabs(v)));
  // Keep headroom for the filter's overshoot: sox works in 32-bit fixed point.
  const double scale = peak > 0 ? 0.5 / peak : 1.0;
  std::vector<float> out;
  out.reserve(static_cast<size_t>(samples.size() * to_hz / from_hz) + 64);
  SoxSource src{samples.data(), samples.size(), 0, scale};
  SoxSink sink{&out, 1.0 / scale};
  {
    std::lock_guard<std::mutex> lock(g_sox_mutex);
    sox_signalinfo_t in_sig{from_hz, 1, 32, 0, nullptr};
    sox_signalinfo_t out_sig{to_hz, 1, 32, 0, nullptr};
    sox_encodinginfo_t enc{};
    enc.encoding = SOX_ENCODING_SIGN2;
    enc.bits_per_sample = 32;
    sox_effects_chain_t* chain = sox_create_effects_chain(&enc, &enc);
    sox_signalinfo_t interm = in_sig;
    sox_effect_t* e = sox_create_effect(source_handler());
    *static_cast<SoxSource**>(e->priv) = &src;
    sox_add_effect(chain, e, &interm, &in_sig);
    free(e);
    e = sox_create_effect(sox_find_effect("rate"));
    char opt_v[] = "-v";
    char* args[] = {opt_v};
    if (sox_effect_options(e, 1, args) != SOX_SUCCESS) throw Error("libsox: bad rate options");
    sox_add_effect(chain, e, &interm, &out_sig);
    free(e);
    e = sox_create_effect(sink_handler());
    *static_cast<SoxSink**>(e->priv) = &sink;
    sox_add_effect(chain, e, &interm, &out_sig);
    free(e);
    sox_flow_effects(chain, nullptr, nullptr);
    sox_delete_effects_chain(chain);
  }
  const size_t expected = static_cast<size_t>(std::llround(samples.size() * to_hz / from_hz));
  out.resize(expected, 0.0f);
  return out;
}

Signal resample(const Signal& signal, double to_hz) {
  Signal out = signal;
  out.samples = resample(signal.samples, signal.sample_rate_hz, to_hz);
  out.sample_rate_hz = to_hz;
  return out;
}

}  // namespace tsrir
