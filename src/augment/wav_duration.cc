#include "augment/wav_duration.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

#include <sys/wait.h>

#include "io/audio_io.h"
#include "io/kaldi_table.h"
#include "io/rxfile.h"
#include "util/error.h"
#include "util/log.h"
#include "util/strings.h"

namespace tsrir {

bool KaldiSpecifier::has(const std::string& flag) const {
  for (const std::string& f : flags)
    if (f == flag) return true;
  return false;
}

KaldiSpecifier parse_kaldi_specifier(const std::string& text, const std::string& what) {
  const size_t colon = text.find(':');
  if (colon == std::string::npos)
    throw Error(what + " '" + text + "': expected a Kaldi specifier such as scp:wav.scp or ark,t:-");
  KaldiSpecifier s;
  std::vector<std::string> words = split(text.substr(0, colon), ',');
  for (std::string& w : words) w = trim(w);
  for (const std::string& w : words) {
    if (w == "scp" || w == "ark") {
      if (!s.type.empty()) throw Error(what + " '" + text + "': both scp and ark");
      s.type = w;
    } else if (!w.empty()) {
      static const char* known[] = {"t", "b", "p", "s", "cs", "ns", "nf", "f", "o", "no", "r", "nr", "bg"};
      bool ok = false;
      for (const char* k : known) ok |= w == k;
      if (!ok) throw Error(what + " '" + text + "': unknown option '" + w + "'");
      s.flags.push_back(w);
    }
  }
  if (s.type.empty()) throw Error(what + " '" + text + "': neither scp nor ark");
  s.target = trim(text.substr(colon + 1));
  if (s.target.empty()) throw Error(what + " '" + text + "': no file after ':'");
  return s;
}

namespace {

uint32_t le32(const std::vector<char>& b, size_t at) {
  return static_cast<uint32_t>(static_cast<unsigned char>(b[at])) |
         static_cast<uint32_t>(static_cast<unsigned char>(b[at + 1])) << 8 |
         static_cast<uint32_t>(static_cast<unsigned char>(b[at + 2])) << 16 |
         static_cast<uint32_t>(static_cast<unsigned char>(b[at + 3])) << 24;
}

}  // namespace

std::optional<WavHeaderInfo> wav_header_info(const std::vector<char>& bytes) {
  if (bytes.size() < 12 || std::memcmp(bytes.data(), "RIFF", 4) != 0 || std::memcmp(bytes.data() + 8, "WAVE", 4) != 0)
    return std::nullopt;
  WavHeaderInfo info;
  uint32_t block_align = 0;
  for (size_t at = 12; at + 8 <= bytes.size();) {
    const uint32_t size = le32(bytes, at + 4);
    if (std::memcmp(bytes.data() + at, "fmt ", 4) == 0 && at + 8 + 16 <= bytes.size()) {
      info.channels = static_cast<unsigned char>(bytes[at + 10]) | static_cast<unsigned char>(bytes[at + 11]) << 8;
      info.sample_rate_hz = le32(bytes, at + 12);
      block_align = static_cast<uint32_t>(static_cast<unsigned char>(bytes[at + 20])) |
                    static_cast<uint32_t>(static_cast<unsigned char>(bytes[at + 21])) << 8;
    } else if (std::memcmp(bytes.data() + at, "data", 4) == 0) {
      if (info.sample_rate_hz == 0 || block_align == 0) return std::nullopt;
      if (size != 0 && size < 0xFFFFFFF0u)
        info.duration_s = static_cast<double>(size / block_align) / info.sample_rate_hz;
      return info;
    }
    at += 8 + size + (size & 1);
  }
  return std::nullopt;
}

std::optional<double> wav_header_duration_s(const std::vector<char>& bytes) {
  const std::optional<WavHeaderInfo> info = wav_header_info(bytes);
  return info ? info->duration_s : std::nullopt;
}

namespace {

// A pipe's first `head_bytes` bytes; the rest is read to the end and discarded, so the command
// finishes on its own, and a command that fails is an error.
std::vector<char> pipe_head(const std::string& command, size_t head_bytes) {
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) throw Error("cannot start the command");
  std::vector<char> head(head_bytes);
  size_t got = 0;
  while (got < head.size()) {
    const size_t n = std::fread(head.data() + got, 1, head.size() - got, pipe);
    if (n == 0) break;
    got += n;
  }
  head.resize(got);
  std::vector<char> rest(1 << 16);
  while (std::fread(rest.data(), 1, rest.size(), pipe) > 0) {
  }
  const int status = pclose(pipe);
  if (status != 0)
    throw Error("the command '" + command + "' failed (exit status " +
                std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status)) + ")");
  return head;
}

}  // namespace

RxAudioHeader rx_audio_header(const std::string& rx_in, bool read_entire_file, const std::string& where) {
  const std::string rx = trim(rx_in);
  try {
    RxAudioHeader out;
    if (!read_entire_file && is_pipe_rxfilename(rx)) {
      const std::optional<WavHeaderInfo> info = wav_header_info(pipe_head(rx.substr(0, rx.size() - 1), 65536));
      if (info && info->duration_s) return {*info->duration_s, info->sample_rate_hz, info->channels};
    }
    if (read_entire_file || rx == "-" || is_pipe_rxfilename(rx)) {
      AudioInfo info;
      std::vector<std::vector<float>> channels = read_audio_channels(rx, &info, where);
      if (!(info.sample_rate_hz > 0)) throw Error("no sample rate");
      return {static_cast<double>(channels.at(0).size()) / info.sample_rate_hz, info.sample_rate_hz,
              static_cast<int>(channels.size())};
    }
    const AudioInfo info = probe_audio(rx);
    if (!(info.sample_rate_hz > 0)) throw Error("no sample rate");
    return {static_cast<double>(info.frames) / info.sample_rate_hz, info.sample_rate_hz, info.channels};
  } catch (const Error& error) {
    const std::string message = error.what();
    throw Error(message.find(where) == std::string::npos ? where + ": " + message : message);
  }
}

double rx_duration_s(const std::string& rx, bool read_entire_file, const std::string& where) {
  return rx_audio_header(rx, read_entire_file, where).duration_s;
}

void WavDurationOptions::Register(OptionsItf* opts) {
  opts->Register("read-entire-file", &read_entire_file,
                 "If true, decode every recording completely instead of reading file headers");
}

std::vector<RecordingDuration> wav_durations(const std::string& rspecifier, bool read_entire_file) {
  const KaldiSpecifier spec = parse_kaldi_specifier(rspecifier, "wav rspecifier");
  if (spec.type != "scp")
    throw Error("wav rspecifier '" + rspecifier + "': only scp:<wav.scp> is supported (wav archives are not)");
  TableReadOptions options;
  options.allow_duplicates = false;
  const Table table = read_table(spec.target, options);
  std::vector<RecordingDuration> out;
  for (const TableEntry& e : table.entries) {
    const std::string where = spec.target + ":" + std::to_string(e.line) + ": recording '" + e.key + "'";
    const double seconds = rx_duration_s(e.value, read_entire_file, where);
    RecordingDuration d;
    d.key = e.key;
    d.duration_s = static_cast<float>(seconds);
    out.push_back(d);
  }
  return out;
}

std::string format_duration_archive(const std::vector<RecordingDuration>& durations, bool text) {
  std::ostringstream os;
  os.precision(7);
  for (const RecordingDuration& d : durations) {
    os << d.key << ' ';
    if (text) {
      os << d.duration_s << " \n";
    } else {
      os.put('\0');
      os.put('B');
      os.put(static_cast<char>(sizeof(float)));
      os.write(reinterpret_cast<const char*>(&d.duration_s), sizeof(float));
    }
  }
  return os.str();
}

void write_duration_archive(const std::string& wspecifier, const std::vector<RecordingDuration>& durations) {
  const KaldiSpecifier spec = parse_kaldi_specifier(wspecifier, "duration wspecifier");
  if (spec.type != "ark") throw Error("duration wspecifier '" + wspecifier + "': only ark[,t]:<wxfilename> is supported");
  const std::string bytes = format_duration_archive(durations, spec.has("t"));
  const std::string& target = spec.target;
  if (target == "-") {
    if (std::fwrite(bytes.data(), 1, bytes.size(), stdout) != bytes.size() || std::fflush(stdout) != 0)
      throw Error("cannot write to stdout");
    return;
  }
  if (!target.empty() && target.front() == '|') {
    FILE* pipe = popen(target.substr(1).c_str(), "w");
    if (!pipe) throw Error(wspecifier + ": cannot start the output command");
    const bool written = std::fwrite(bytes.data(), 1, bytes.size(), pipe) == bytes.size();
    const int status = pclose(pipe);
    if (!written || status != 0) throw Error(wspecifier + ": the output command failed");
    return;
  }
  const std::string temp = target + ".tmp.wav-to-duration";
  {
    std::ofstream f(temp, std::ios::binary);
    if (!f) throw Error(target + ": cannot write: " + std::strerror(errno));
    f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!f) throw Error(target + ": cannot write");
  }
  if (std::rename(temp.c_str(), target.c_str()) != 0) {
    std::remove(temp.c_str());
    throw Error(target + ": cannot rename into place: " + std::strerror(errno));
  }
}

int run_wav_to_duration(const WavDurationOptions& options, const std::string& rspecifier,
                        const std::string& wspecifier) {
  const std::vector<RecordingDuration> durations = wav_durations(rspecifier, options.read_entire_file);
  write_duration_archive(wspecifier, durations);
  double sum = 0, lo = std::numeric_limits<double>::infinity(), hi = 0;
  for (const auto& d : durations) {
    sum += d.duration_s;
    lo = std::min<double>(lo, d.duration_s);
    hi = std::max<double>(hi, d.duration_s);
  }
  const size_t done = durations.size();
  log_info("Printed duration for " + std::to_string(done) + " audio files.");
  if (done > 0)
    log_info("Mean duration was " + std::to_string(sum / done) + ", min and max durations were " +
             std::to_string(lo) + ", " + std::to_string(hi));
  return done != 0 ? 0 : 1;  // Kaldi: 1 when nothing was written
}

}  // namespace tsrir
