// Sets of RIRs as the programs read and write them. Input: a Kaldi scp (<id> <rxfilename>), a
// Kaldi rir_list (--rir-id ... <rxfilename>), or a single audio file (id = file name without
// extension). Output: <dir>/<id>.wav, <dir>/rir.scp and <dir>/rir_list, written as one unit into a
// directory owned by the toolkit (io/owned_output.h: never a directory it did not write, never an
// input, never deleting another's files).
// Room ids travel with the RIRs whichever list form is given: an scp has none, so the rir_list
// beside it (same directory, as every program here writes them) gives them; without one, each RIR
// is its own room and a warning says so.
#pragma once
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include "io/audio_io.h"
#include "io/atomic_output.h"
#include "io/owned_output.h"
#include "io/signal.h"

namespace tsrir {

struct RirRef {
  std::string id;
  std::string room_id;      // from a rir_list (given, or beside the scp); = id otherwise
  std::string rxfilename;
  std::string where;        // "file:line" (or the file name) for messages
};

// Detects the kind of `path` as described above. Errors: missing file, malformed lines,
// duplicate ids (each with file:line), an scp id missing from the rir_list beside it. Records the
// list and every file it points at in `inputs` (a program passes run_inputs(), io/owned_output.h;
// null: recorded nowhere).
std::vector<RirRef> read_rir_refs(const std::string& path, InputLedger* inputs);

// Loads one RIR (resampled if options.target_rate_hz > 0); the Signal's id is ref.id. Errors name
// the id and where it was listed.
Signal load_rir(const RirRef& ref, const AudioReadOptions& options = {});

// Every channel of one RIR (a microphone array's: channel c = microphone c), each with id ref.id;
// resampled to options.target_rate_hz if > 0 (options.channel is ignored).
std::vector<Signal> load_rir_channels(const RirRef& ref, const AudioReadOptions& options = {});

// Writes a complete RIR set into out_dir: its files appear at commit(); files of an earlier run of
// the same program there are replaced, nothing else is touched.
class RirSetWriter {
 public:
  RirSetWriter(const std::string& out_dir, SampleFormat format);
  // Thread-safe. Ids must be unique and usable as file names (else Error).
  void add(const Signal& rir, const std::string& room_id = "");
  // One multichannel RIR (a microphone array's): channels[c] is channel c, all with the same id,
  // rate and length.
  void add_channels(const std::vector<Signal>& channels, const std::string& room_id = "");
  void commit();   // writes rir.scp and rir_list (sorted by id) and renames the directory
  const std::string& temp_dir() const { return dir_.path(); }

 private:
  OwnedOutputDir dir_;
  SampleFormat format_;
  struct Row { std::string id, room_id; };
  std::vector<Row> rows_;
  std::set<std::string> ids_;
  std::mutex mutex_;
};

}  // namespace tsrir
