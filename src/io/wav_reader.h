// Plain RIFF/WAVE files decoded without libsndfile: 16/24/32-bit PCM and 32-bit IEEE float, also
// as WAVE_FORMAT_EXTENSIBLE, with the same samples and description libsndfile gives for them (the
// tests compare the two on every layout). That is what Kaldi recipes feed wav-reverberate once per
// utterance, and decoding it here spares each run the loading of libsndfile and its codecs.
// Anything else, or anything unusual in a WAV (a chunk order, size or field libsndfile would have
// to interpret: a truncated or streamed data size, a partial frame, inconsistent fmt fields,
// unknown chunks before the data), is declined, and the caller hands the file to libsndfile, so
// every error message and every lenient reading stays libsndfile's.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

namespace tsrir {

struct PlainWavLayout {
  int channels = 0;
  double sample_rate_hz = 0.0;
  int bits = 0;               // 16, 24 or 32
  bool is_float = false;      // 32-bit IEEE float
  bool extensible = false;    // WAVE_FORMAT_EXTENSIBLE (libsndfile: "WAVEX")
  size_t data_offset = 0;     // first byte of the samples in the file
  size_t frames = 0;
  // libsndfile's name of the layout, e.g. "WAV (Microsoft) Signed 16 bit PCM".
  std::string format_name() const;
};

// Parses the header of the `size` bytes at `bytes` (a whole file). False (and *layout untouched)
// when the file is not a plain WAV as described above.
bool parse_plain_wav(const char* bytes, size_t size, PlainWavLayout* layout);

// Decodes frames [first, first + count) of a parsed file into channels[c] (resized to count),
// scaled as libsndfile reads them as float: integers divided by 2^(bits-1), floats as stored.
// Throws Error naming `name` for a NaN or Inf sample (as the libsndfile path does).
void decode_plain_wav(const char* bytes, const PlainWavLayout& layout, size_t first, size_t count,
                      const std::string& name, std::vector<std::vector<float>>* channels);

// A whole file mapped into memory read-only (its pages are read on demand, not copied).
class MappedFile {
 public:
  MappedFile() = default;
  ~MappedFile();
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
  // False when `path` cannot be opened, is not a non-empty regular file, or cannot be mapped: the
  // caller then takes the libsndfile path, whose messages say why.
  // populate = false maps without prefaulting: for a caller that reads only the header (a probe)
  // or a part it then asks for with populate_range().
  bool open(const std::string& path, bool populate = true);
  // Prefaults [offset, offset + length) (clipped to the file) where the kernel can (Linux >= 5.14);
  // otherwise the pages fault in on first touch, as they would anyway.
  void populate_range(size_t offset, size_t length) const;
  const char* data() const { return data_; }
  size_t size() const { return size_; }

 private:
  const char* data_ = nullptr;
  size_t size_ = 0;
};

}  // namespace tsrir
