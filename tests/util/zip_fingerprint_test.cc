// zip_fingerprint against archives written here by a minimal zip writer of its own (stored
// entries, real CRC-32s, optional zip64 end records and archive comment), not by LibTorch.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "util/error.h"
#include "util/zip_fingerprint.h"

namespace fs = std::filesystem;

namespace {

uint32_t crc32(const std::string& data) {
  uint32_t crc = 0xffffffffu;
  for (unsigned char byte : data) {
    crc ^= byte;
    for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

void put(std::string& out, uint64_t value, int bytes) {
  for (int i = 0; i < bytes; ++i) out.push_back(char((value >> (8 * i)) & 0xff));
}

struct ZipForm {
  bool zip64 = false;
  std::string comment;
};

// Local headers and data, the central directory, then the end records.
std::string make_zip(const std::vector<std::pair<std::string, std::string>>& entries, const ZipForm& form) {
  std::string out, directory;
  for (const auto& [name, data] : entries) {
    const uint64_t offset = out.size();
    const uint32_t crc = crc32(data);
    put(out, 0x04034b50, 4);
    put(out, 20, 2), put(out, 0, 2), put(out, 0, 2), put(out, 0, 2), put(out, 0, 2);  // version, flags, stored, time, date
    put(out, crc, 4), put(out, data.size(), 4), put(out, data.size(), 4);
    put(out, name.size(), 2), put(out, 0, 2);
    out += name + data;
    put(directory, 0x02014b50, 4);
    put(directory, 20, 2), put(directory, 20, 2), put(directory, 0, 2), put(directory, 0, 2);
    put(directory, 0, 2), put(directory, 0, 2);
    put(directory, crc, 4), put(directory, data.size(), 4), put(directory, data.size(), 4);
    put(directory, name.size(), 2), put(directory, 0, 2), put(directory, 0, 2);  // name, extra, comment
    put(directory, 0, 2), put(directory, 0, 2), put(directory, 0, 4), put(directory, offset, 4);
    directory += name;
  }
  const uint64_t dir_offset = out.size();
  out += directory;
  if (form.zip64) {
    const uint64_t record = out.size();
    put(out, 0x06064b50, 4), put(out, 44, 8), put(out, 45, 2), put(out, 45, 2), put(out, 0, 4), put(out, 0, 4);
    put(out, entries.size(), 8), put(out, entries.size(), 8), put(out, directory.size(), 8), put(out, dir_offset, 8);
    put(out, 0x07064b50, 4), put(out, 0, 4), put(out, record, 8), put(out, 1, 4);
  }
  put(out, 0x06054b50, 4), put(out, 0, 2), put(out, 0, 2);
  put(out, form.zip64 ? 0xffff : entries.size(), 2), put(out, form.zip64 ? 0xffff : entries.size(), 2);
  put(out, form.zip64 ? 0xffffffffu : directory.size(), 4), put(out, form.zip64 ? 0xffffffffu : dir_offset, 4);
  put(out, form.comment.size(), 2);
  return out + form.comment;
}

class ZipFingerprint : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = (fs::temp_directory_path() / ("tsrir_zip_fingerprint_" + std::to_string(::getpid()))).string();
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& bytes) const {
    const std::string path = dir_ + "/" + name;
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  }
  std::string dir_;
};

const std::vector<std::pair<std::string, std::string>> kEntries = {
    {"archive/data.pkl", "pickled structure"}, {"archive/data/0", std::string(1000, 'a')}, {"archive/data/1", "weights"}};

TEST_F(ZipFingerprint, SameContentSameFingerprintAnyChangeAnother) {
  const std::string a = tsrir::zip_fingerprint(write("a.zip", make_zip(kEntries, {})));
  EXPECT_EQ(a.size(), 16u);
  EXPECT_EQ(tsrir::zip_fingerprint(write("a2.zip", make_zip(kEntries, {}))), a);
  auto changed = kEntries;
  changed[1].second[500] = 'b';  // one byte of a record, same size: only its CRC-32 tells
  EXPECT_NE(tsrir::zip_fingerprint(write("b.zip", make_zip(changed, {}))), a);
  changed = kEntries;
  changed[2].first = "archive/data/2";
  EXPECT_NE(tsrir::zip_fingerprint(write("c.zip", make_zip(changed, {}))), a);
}

// The directory is found through the zip64 end records (LibTorch writes them for archives over
// 4 GiB) and past an archive comment: the same directory, the same fingerprint.
TEST_F(ZipFingerprint, Zip64AndCommentFindTheSameDirectory) {
  const std::string plain = tsrir::zip_fingerprint(write("plain.zip", make_zip(kEntries, {})));
  EXPECT_EQ(tsrir::zip_fingerprint(write("z64.zip", make_zip(kEntries, {true, ""}))), plain);
  EXPECT_EQ(tsrir::zip_fingerprint(write("comment.zip", make_zip(kEntries, {false, "a comment holding PK\x05\x06 and 22 bytes after it"}))),
            plain);
  EXPECT_EQ(tsrir::zip_fingerprint(write("both.zip", make_zip(kEntries, {true, "a comment"}))), plain);
}

TEST_F(ZipFingerprint, NotAZipNamesTheFile) {
  auto message = [](const std::string& path) {
    try {
      tsrir::zip_fingerprint(path);
    } catch (const tsrir::Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  for (const auto& [name, bytes] :
       std::vector<std::pair<std::string, std::string>>{{"text.pt", "garbage, not an archive"}, {"empty.pt", ""}}) {
    const std::string path = write(name, bytes);
    EXPECT_NE(message(path).find(path), std::string::npos) << message(path);
  }
  // A directory said to lie past the end of the file (a truncated download).
  std::string truncated = make_zip(kEntries, {});
  truncated.erase(30, 200);
  const std::string path = write("truncated.zip", truncated);
  EXPECT_NE(message(path).find("not a zip archive"), std::string::npos) << message(path);
  EXPECT_NE(message(dir_ + "/absent.pt").find("cannot open"), std::string::npos);
}

}  // namespace
