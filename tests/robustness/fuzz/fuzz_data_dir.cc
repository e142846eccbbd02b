// Kaldi data directories: read_data_dir and validate_data_dir on arbitrary file contents. The
// input is split at NUL bytes into wav.scp, utt2spk, spk2utt, text, segments, reco2dur, utt2uniq
// (fewer parts: the later files are absent). Invariants: a directory that reads is consistent
// (every utterance has a recording; segments point into wav.scp with end > start), and one that
// validates cleanly survives write_data_dir + read_data_dir unchanged.
#include <filesystem>

#include "fuzz_common.h"
#include "io/data_dir.h"
#include "util/strings.h"

using namespace tsrir;
namespace fs = std::filesystem;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const char* kFiles[] = {"wav.scp", "utt2spk", "spk2utt", "text", "segments", "reco2dur", "utt2uniq"};
  static const std::string dir = fuzz::scratch_path("data");
  static const std::string out = fuzz::scratch_path("data_out");
  fs::remove_all(dir);
  fs::create_directories(dir);
  auto parts = split(fuzz::as_text(data, size), '\0');
  for (size_t i = 0; i < parts.size() && i < 7; ++i) fuzz::write_file(dir + "/" + kFiles[i], parts[i]);
  fuzz::expect_only_errors([&] {
    auto problems = validate_data_dir(dir);
    DataDir d = read_data_dir(dir);
    for (const auto& [utt, spk] : d.utt2spk) {
      FUZZ_CHECK(!spk.empty(), utt);
      if (d.has_segments()) {
        auto it = d.segments.find(utt);
        FUZZ_CHECK(it != d.segments.end(), "utterance without segment: " + utt);
        FUZZ_CHECK(d.wav_scp.count(it->second.recording_id), "segment of unknown recording: " + utt);
        FUZZ_CHECK(it->second.end_s > it->second.start_s || it->second.end_s == -1, "segment end <= start: " + utt);
      } else {
        FUZZ_CHECK(d.wav_scp.count(utt), "utterance without recording: " + utt);
      }
    }
    if (!problems.empty()) return;
    fs::remove_all(out);
    fs::create_directories(out);
    write_data_dir(out, d);
    DataDir again = read_data_dir(out);
    FUZZ_CHECK(again.wav_scp == d.wav_scp && again.utt2spk == d.utt2spk && again.text == d.text &&
                   again.utt2uniq == d.utt2uniq && again.segments.size() == d.segments.size() &&
                   again.reco2dur.size() == d.reco2dur.size(),
               "write_data_dir + read_data_dir changed a valid directory");
    FUZZ_CHECK(validate_data_dir(out).empty(), "a written valid directory no longer validates");
  });
  return 0;
}
