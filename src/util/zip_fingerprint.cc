#include "util/zip_fingerprint.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <vector>

#include "util/error.h"
#include "util/rng.h"

namespace tsrir {
namespace {

// Little-endian fields of the zip format (APPNOTE.TXT 4.3.14-4.3.16).
uint64_t read_le(const char* p, int bytes) {
  uint64_t v = 0;
  for (int i = bytes - 1; i >= 0; --i) v = (v << 8) | uint8_t(p[i]);
  return v;
}

constexpr uint32_t kEndOfDirectory = 0x06054b50, kZip64Locator = 0x07064b50, kZip64End = 0x06064b50;
constexpr int64_t kEndSize = 22, kLocatorSize = 20, kZip64EndSize = 56, kMaxComment = 65535;

std::vector<char> read_at(std::ifstream& in, int64_t offset, int64_t size, const std::string& path) {
  std::vector<char> bytes(size_t(std::max<int64_t>(size, 0)));
  in.seekg(offset);
  if (size < 0 || !in.read(bytes.data(), size)) throw Error(path + ": not a zip archive (truncated)");
  return bytes;
}

}  // namespace

std::string zip_fingerprint(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw Error(path + ": cannot open");
  const int64_t file_size = in.tellg();
  // The end-of-directory record is the last 22 bytes plus a comment of at most 64 KiB: the last
  // signature whose comment length reaches exactly to the end (a comment may hold the signature).
  const int64_t tail_size = std::min(file_size, kEndSize + kMaxComment);
  const std::vector<char> tail = read_at(in, file_size - tail_size, tail_size, path);
  int64_t end = -1;
  for (int64_t i = tail_size - kEndSize; i >= 0; --i) {
    if (read_le(&tail[size_t(i)], 4) == kEndOfDirectory &&
        i + kEndSize + int64_t(read_le(&tail[size_t(i) + 20], 2)) == tail_size) {
      end = i;
      break;
    }
  }
  if (end < 0) throw Error(path + ": not a zip archive (no end-of-directory record)");
  uint64_t dir_size = read_le(&tail[size_t(end) + 12], 4), dir_offset = read_le(&tail[size_t(end) + 16], 4);
  if (dir_size == 0xffffffffu || dir_offset == 0xffffffffu) {
    // zip64: the locator just before the record points to the 64-bit end-of-directory record.
    const int64_t locator = file_size - tail_size + end - kLocatorSize;
    const std::vector<char> loc = read_at(in, locator, kLocatorSize, path);
    if (read_le(loc.data(), 4) != kZip64Locator) throw Error(path + ": not a zip archive (bad zip64 locator)");
    const std::vector<char> rec = read_at(in, int64_t(read_le(&loc[8], 8)), kZip64EndSize, path);
    if (read_le(rec.data(), 4) != kZip64End) throw Error(path + ": not a zip archive (bad zip64 record)");
    dir_size = read_le(&rec[40], 8);
    dir_offset = read_le(&rec[48], 8);
  }
  if (dir_offset > uint64_t(file_size) || dir_size > uint64_t(file_size) - dir_offset) {
    throw Error(path + ": not a zip archive (central directory outside the file)");
  }
  const std::vector<char> directory = read_at(in, int64_t(dir_offset), int64_t(dir_size), path);
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx",
                static_cast<unsigned long long>(stable_hash(std::string_view(directory.data(), directory.size()))));
  return hex;
}

}  // namespace tsrir
