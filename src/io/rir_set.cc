#include "io/rir_set.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <set>

#include "io/kaldi_lists.h"
#include "io/kaldi_table.h"
#include "io/shell.h"
#include "io/wav_writer.h"
#include "util/cli.h"
#include "util/error.h"
#include "util/strings.h"

namespace fs = std::filesystem;

namespace tsrir {
namespace {

bool has_audio_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (auto& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".wav" || ext == ".flac" || ext == ".ogg" || ext == ".oga" || ext == ".aiff" || ext == ".aif" ||
         ext == ".au" || ext == ".w64" || ext == ".rf64" || ext == ".caf" || ext == ".opus";
}

// The first line that is not blank: an scp's does not start with "--" (kaldi_lists.h).
bool is_scp_form(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    const std::string t = trim(line);
    if (!t.empty()) return t.rfind("--", 0) != 0;
  }
  return false;
}

void take_rooms_from_list_beside(const std::string& scp, std::vector<RirRef>* refs) {
  const std::string list = (fs::path(scp).parent_path() / "rir_list").string();
  if (fs::absolute(list).lexically_normal() == fs::absolute(scp).lexically_normal()) return;
  if (!fs::is_regular_file(list) || is_scp_form(list)) {
    if (refs->size() > 1)
      log_warning(scp + ": an scp gives no room ids and there is no rir_list beside it: each of its " +
                  std::to_string(refs->size()) + " RIRs is taken as its own room (give the rir_list to keep rooms)");
    return;
  }
  std::map<std::string, std::string> room_of;
  for (const auto& e : read_rir_list(list)) room_of[e.rir_id] = e.room_id;
  for (RirRef& r : *refs) {
    auto it = room_of.find(r.id);
    if (it == room_of.end())
      throw Error(r.where + ": RIR '" + r.id + "' is not in " + list +
                  ", the rir_list beside this scp that gives its RIRs' rooms; give a rir_list instead of the scp, " +
                  "or make the two lists agree");
    r.room_id = it->second;
  }
}

}  // namespace

std::vector<RirRef> read_rir_refs(const std::string& path, InputLedger* inputs) {
  if (!fs::exists(path)) throw Error(path + ": no such file");
  std::vector<RirRef> refs;
  if (has_audio_extension(path)) {
    RirRef r;
    r.id = fs::path(path).stem().string();
    r.room_id = r.id;
    r.rxfilename = path;
    r.where = path;
    refs.push_back(r);
    if (inputs) inputs->add(path);
    return refs;
  }
  if (inputs) inputs->add(path);
  for (const auto& e : read_rir_list(path)) {
    RirRef r;
    r.id = e.rir_id;
    r.room_id = e.room_id;
    r.rxfilename = e.rxfilename;
    r.where = path + ":" + std::to_string(e.line);
    if (inputs) inputs->add(r.rxfilename);
    refs.push_back(std::move(r));
  }
  if (!refs.empty() && is_scp_form(path)) take_rooms_from_list_beside(path, &refs);
  return refs;
}

Signal load_rir(const RirRef& ref, const AudioReadOptions& options) {
  AudioReadOptions o = options;
  o.context = ref.where + " (RIR '" + ref.id + "')";
  Signal s = read_audio(ref.rxfilename, o);
  s.id = ref.id;
  return s;
}

std::vector<Signal> load_rir_channels(const RirRef& ref, const AudioReadOptions& options) {
  AudioInfo info;
  std::vector<std::vector<float>> channels =
      read_audio_channels(ref.rxfilename, &info, ref.where + " (RIR '" + ref.id + "')");
  std::vector<Signal> out;
  for (std::vector<float>& c : channels) {
    Signal s{ref.id, info.sample_rate_hz, std::move(c)};
    if (options.target_rate_hz > 0 && s.sample_rate_hz != options.target_rate_hz) s = resample(s, options.target_rate_hz);
    out.push_back(std::move(s));
  }
  return out;
}

RirSetWriter::RirSetWriter(const std::string& out_dir, SampleFormat format)
    : dir_(out_dir), format_(format) {}

void RirSetWriter::add(const Signal& rir, const std::string& room_id) { add_channels({rir}, room_id); }

void RirSetWriter::add_channels(const std::vector<Signal>& channels, const std::string& room_id) {
  if (channels.empty()) throw Error("RirSetWriter: an RIR needs at least one channel");
  const Signal& rir = channels.front();
  std::vector<std::vector<float>> samples;
  for (const Signal& c : channels) {
    if (c.id != rir.id || c.sample_rate_hz != rir.sample_rate_hz || c.size() != rir.size()) {
      throw Error("RIR '" + rir.id + "': its channels differ in id, rate or length");
    }
    samples.push_back(c.samples);
  }
  if (rir.id.empty() || rir.id.find_first_of("/ \t\r\n") != std::string::npos || rir.id == "." || rir.id == "..") {
    throw Error("RIR id '" + rir.id + "' cannot be used as a file name (empty, or contains '/' or whitespace)");
  }
  // A line break in the room id would split its rir_list line: the set could not be read back.
  if (room_id.find_first_of("\r\n") != std::string::npos) {
    throw Error("RIR '" + rir.id + "': room id contains a line break");
  }
  AudioWriteOptions o;
  o.format = format_;
  long long clipped = 0;
  o.clipped_samples = &clipped;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    // A set, not a scan of rows_: sets of 10^5 RIRs are normal, and a scan made add() quadratic.
    if (!ids_.insert(rir.id).second) throw Error("duplicate RIR id '" + rir.id + "' in output set");
    rows_.push_back({rir.id, room_id.empty() ? rir.id : room_id});
  }
  // The staging dir is the writer's own until commit() moves it into place whole (and is removed
  // without it), so each WAV goes there under its final name at once (WavFileMode::kDirect).
  o.file_mode = WavFileMode::kDirect;
  write_wav_channels((fs::path(dir_.path()) / (rir.id + ".wav")).string(), samples, rir.sample_rate_hz, o);
  if (clipped > 0) {
    throw Error("RIR '" + rir.id + "': " + std::to_string(clipped) +
                " samples exceed full scale in 16-bit output; normalise it or use --format=float");
  }
}

void RirSetWriter::commit() {
  std::vector<Row> rows;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    rows = rows_;
  }
  if (rows.empty()) throw Error("no RIRs to write to " + dir_.final_path());
  std::vector<std::pair<std::string, std::string>> scp;
  std::sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) { return c_locale_less(a.id, b.id); });
  // Paths in the tables point at the final location, absolute, so the lists work from anywhere.
  const std::string final_abs = absolute_path(dir_.final_path());
  {
    std::ofstream list((fs::path(dir_.path()) / "rir_list").string());
    for (const auto& r : rows) {
      const std::string wav = (fs::path(final_abs) / (r.id + ".wav")).string();
      scp.emplace_back(r.id, wav);
      RirListEntry e;
      e.rir_id = r.id;
      e.room_id = r.room_id;
      e.rxfilename = wav;
      list << format_rir_list_line(e) << '\n';
    }
    if (!list) throw Error("cannot write " + dir_.final_path() + "/rir_list");
  }
  write_table((fs::path(dir_.path()) / "rir.scp").string(), scp);
  dir_.commit();
}

}  // namespace tsrir
