#include "io/wav_reader.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "util/error.h"

namespace tsrir {
namespace {

uint16_t u16(const char* p) {
  const auto* b = reinterpret_cast<const unsigned char*>(p);
  return static_cast<uint16_t>(b[0] | (b[1] << 8));
}
uint32_t u32(const char* p) {
  const auto* b = reinterpret_cast<const unsigned char*>(p);
  return static_cast<uint32_t>(b[0]) | (static_cast<uint32_t>(b[1]) << 8) | (static_cast<uint32_t>(b[2]) << 16) |
         (static_cast<uint32_t>(b[3]) << 24);
}

constexpr uint16_t kFormatPcm = 1;
constexpr uint16_t kFormatFloat = 3;
constexpr uint16_t kFormatExtensible = 0xFFFE;
// KSDATAFORMAT_SUBTYPE_{PCM,IEEE_FLOAT}: the format code then 00000000-0010-8000-00AA00389B71.
constexpr unsigned char kSubtypeGuidTail[14] = {0x00, 0x00, 0x00, 0x00, 0x10, 0x00, 0x80,
                                                0x00, 0x00, 0xAA, 0x00, 0x38, 0x9B, 0x71};

// Chunks that may precede the data without changing how libsndfile decodes it.
bool is_passive_chunk(const char* id) {
  static const char* kIds[] = {"fact", "LIST", "PEAK", "JUNK", "bext", "cue ", "smpl", "inst", "id3 ", "ID3 "};
  for (const char* k : kIds)
    if (std::memcmp(id, k, 4) == 0) return true;
  return false;
}

// The fmt chunk's body; false for any layout this reader leaves to libsndfile.
bool parse_fmt(const char* body, uint32_t length, PlainWavLayout* out) {
  if (length != 16 && length != 18 && length != 40) return false;
  uint16_t tag = u16(body);
  const int channels = u16(body + 2);
  const uint32_t rate = u32(body + 4);
  const uint32_t byte_rate = u32(body + 8);
  const int block_align = u16(body + 12);
  const int bits = u16(body + 14);
  bool extensible = false;
  if (length >= 18 && tag != kFormatExtensible && u16(body + 16) != 0) return false;  // cbSize: no extension
  if (tag == kFormatExtensible) {
    if (length != 40 || u16(body + 16) != 22) return false;
    if (u16(body + 18) != bits) return false;  // valid bits per sample: all of them
    if (std::memcmp(body + 26, kSubtypeGuidTail, sizeof kSubtypeGuidTail) != 0) return false;
    tag = u16(body + 24);
    extensible = true;
  }
  const bool is_float = tag == kFormatFloat;
  if (!(tag == kFormatPcm && (bits == 16 || bits == 24 || bits == 32)) && !(is_float && bits == 32)) return false;
  if (channels < 1 || rate < 1) return false;
  if (block_align != channels * (bits / 8) || byte_rate != static_cast<uint64_t>(rate) * block_align) return false;
  out->channels = channels;
  out->sample_rate_hz = rate;
  out->bits = bits;
  out->is_float = is_float;
  out->extensible = extensible;
  return true;
}

}  // namespace

std::string PlainWavLayout::format_name() const {
  std::string major = extensible ? "WAVEX (Microsoft)" : "WAV (Microsoft)";
  if (is_float) return major + " 32 bit float";
  return major + " Signed " + std::to_string(bits) + " bit PCM";
}

bool parse_plain_wav(const char* bytes, size_t size, PlainWavLayout* layout) {
  if (size < 12 || std::memcmp(bytes, "RIFF", 4) != 0 || std::memcmp(bytes + 8, "WAVE", 4) != 0) return false;
  PlainWavLayout found;
  bool have_fmt = false;
  uint64_t pos = 12;
  while (pos + 8 <= size) {
    const char* id = bytes + pos;
    const uint64_t length = u32(bytes + pos + 4);
    const uint64_t body = pos + 8;
    if (std::memcmp(id, "data", 4) == 0) {
      if (!have_fmt || length == 0 || body + length > size) return false;
      const uint64_t block = static_cast<uint64_t>(found.channels) * (found.bits / 8);
      if (length % block != 0) return false;
      found.data_offset = static_cast<size_t>(body);
      found.frames = static_cast<size_t>(length / block);
      *layout = found;
      return true;
    }
    if (body + length > size) return false;
    if (std::memcmp(id, "fmt ", 4) == 0) {
      if (have_fmt || !parse_fmt(bytes + body, static_cast<uint32_t>(length), &found)) return false;
      have_fmt = true;
    } else if (!is_passive_chunk(id)) {
      return false;
    }
    pos = body + length + (length & 1);
  }
  return false;
}

namespace {

// One loop per encoding (the format test hoisted out of the per-sample loop): `sample(p)` converts
// the `width` bytes at p.
template <typename Convert>
void decode_frames(const char* p, size_t width, size_t count, std::vector<std::vector<float>>* channels,
                   Convert sample) {
  const size_t ch = channels->size();
  if (ch == 1) {
    float* out = (*channels)[0].data();
    for (size_t n = 0; n < count; ++n, p += width) out[n] = sample(p);
    return;
  }
  for (size_t n = 0; n < count; ++n)
    for (size_t c = 0; c < ch; ++c, p += width) (*channels)[c][n] = sample(p);
}

}  // namespace

void decode_plain_wav(const char* bytes, const PlainWavLayout& layout, size_t first, size_t count,
                      const std::string& name, std::vector<std::vector<float>>* channels) {
  const size_t ch = static_cast<size_t>(layout.channels);
  const size_t width = static_cast<size_t>(layout.bits / 8);
  channels->resize(ch);
  for (auto& c : *channels) c.resize(count);
  const char* p = bytes + layout.data_offset + first * ch * width;
  // libsndfile's float reading of integer PCM: (float) sample * (1.0f / 2^(bits-1)), exact for 16
  // and 24 bits (libsndfile reads 24-bit samples shifted into the top of an int, as here).
  constexpr float k16 = 1.0f / 32768.0f;
  constexpr float k32 = 1.0f / 2147483648.0f;
  if (layout.is_float) {
    decode_frames(p, width, count, channels, [](const char* q) {
      float v;
      std::memcpy(&v, q, 4);
      return v;
    });
    bool finite = true;
    for (const auto& v : *channels)
      for (float x : v) finite &= std::isfinite(x);
    // Report the first bad sample in file order, as the libsndfile path does.
    for (size_t n = 0; !finite && n < count; ++n)
      for (size_t c = 0; c < ch; ++c)
        if (!std::isfinite((*channels)[c][n]))
          throw Error(name + ": NaN or Inf sample at frame " + std::to_string(first + n) + " channel " +
                      std::to_string(c));
  } else if (layout.bits == 16) {
    decode_frames(p, width, count, channels,
                  [k16](const char* q) { return static_cast<float>(static_cast<int16_t>(u16(q))) * k16; });
  } else if (layout.bits == 24) {
    decode_frames(p, width, count, channels, [k32](const char* q) {
      const auto* b = reinterpret_cast<const unsigned char*>(q);
      const uint32_t shifted = (static_cast<uint32_t>(b[0]) << 8) | (static_cast<uint32_t>(b[1]) << 16) |
                               (static_cast<uint32_t>(b[2]) << 24);
      return static_cast<float>(static_cast<int32_t>(shifted)) * k32;
    });
  } else {
    decode_frames(p, width, count, channels,
                  [k32](const char* q) { return static_cast<float>(static_cast<int32_t>(u32(q))) * k32; });
  }
}

MappedFile::~MappedFile() {
  if (data_) munmap(const_cast<char*>(data_), size_);
}

bool MappedFile::open(const std::string& path, bool populate) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  struct stat st;
  bool ok = fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0;
  if (ok) {
    // Small files (the usual utterance, RIR or noise) are mapped in one go rather than page by page
    // on first touch; a long recording, or any file that is only probed, stays unread.
    constexpr off_t kPopulateLimit = 64 << 20;
    const int flags = MAP_PRIVATE | (populate && st.st_size <= kPopulateLimit ? MAP_POPULATE : 0);
    void* p = mmap(nullptr, static_cast<size_t>(st.st_size), PROT_READ, flags, fd, 0);
    ok = p != MAP_FAILED;
    if (ok) {
      data_ = static_cast<const char*>(p);
      size_ = static_cast<size_t>(st.st_size);
    }
  }
  ::close(fd);
  return ok;
}

void MappedFile::populate_range(size_t offset, size_t length) const {
#ifdef MADV_POPULATE_READ
  if (!data_ || offset >= size_ || length == 0) return;
  const uintptr_t page = static_cast<uintptr_t>(sysconf(_SC_PAGESIZE));
  const uintptr_t begin = reinterpret_cast<uintptr_t>(data_ + offset) & ~(page - 1);
  const uintptr_t end = reinterpret_cast<uintptr_t>(data_ + offset + std::min(length, size_ - offset));
  madvise(reinterpret_cast<void*>(begin), end - begin, MADV_POPULATE_READ);  // advice: failure is harmless
#else
  (void)offset, (void)length;
#endif
}

}  // namespace tsrir
