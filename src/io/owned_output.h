// The output-ownership rule, one mechanism for every program and stage that writes a directory:
//  - a directory a program writes is marked as the toolkit's by a marker file, .tsrir-owned, that
//    lists every file a tsrir program wrote there (name, size, modification time, program, and the
//    output it belongs to);
//  - a program creates or replaces only the files it names itself (<id>.wav, its lists, the marker);
//  - it refuses a non-empty directory that holds no marker, and a file of one of its names that the
//    marker does not list as its own (another program's, another data dir's wavs, a user's file),
//    unless the user says --overwrite -- and even then it replaces only files of its own names;
//  - it never deletes a file it did not write: a re-run removes only the files its own previous run
//    listed and that are unchanged since (same size and time), and that it no longer writes;
//  - it refuses an output directory that is, contains or lies inside any input of the run (its
//    InputLedger: real paths, through symlinks, including every file a list or wav.scp points at,
//    pipes' file arguments included);
//  - files are written into a staging directory (.tsrir-staging.tmp.<pid>.<n>) inside the output
//    and renamed to their final names at commit, under an exclusive lock on the directory (two runs
//    sharing a directory see each other's files); a failed run leaves no staging directory and
//    removes directories it created that stayed empty.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "io/input_ledger.h"

namespace tsrir {

class OptionsItf;

// Who writes, whether --overwrite was given, and what the run has read: the policy every owned
// output and atomic file of the process follows. A program's main makes one from its command line
// and installs it after parsing:
//   OutputPolicy policy(cli.program());  policy.Register(&cli);  cli.parse(...);
//   install_output_policy(policy);
// then hands run_inputs() to the readers of its inputs.
struct OutputPolicy {
  std::string program = "tsrir";  // recorded in the marker as each file's writer
  bool overwrite = false;         // --overwrite: may write into a directory it does not own
  // What the run has read: every owned output is checked against it at creation and at commit,
  // every atomic file (AtomicTextFile, write_wav) when it is opened. Copies share it.
  std::shared_ptr<InputLedger> inputs = std::make_shared<InputLedger>();

  OutputPolicy() = default;
  // The program, not its sub-command: "rir-eq apply" and "rir-eq" write the same outputs.
  explicit OutputPolicy(const std::string& program_name);
  void Register(OptionsItf* opts);  // --overwrite (io/common_options.h)
};
// The installed policy (before any: program "tsrir", no --overwrite, an empty ledger, as for the
// Python module, whose readers record into it).
const OutputPolicy& output_policy();
void install_output_policy(const OutputPolicy& policy);
// The installed policy's ledger: what a program hands the readers of its inputs.
InputLedger* run_inputs();

// The name of the marker file.
extern const char* const kOwnedMarkerName;

class OwnedOutputDir {
 public:
  // `owner` says which output the files belong to when several share a directory (reverberate-data's
  // --write-wavs dir: the data dir the wavs serve); empty = the directory itself.
  explicit OwnedOutputDir(const std::string& final_dir, const std::string& owner = "");
  ~OwnedOutputDir();  // without commit(): removes the staging dir and directories it created empty
  const std::string& path() const { return staging_dir_; }  // write files here, flat, final names
  const std::string& final_path() const { return final_dir_; }
  // Fails early when any of these names could not be committed (call before long work).
  void check_names(const std::vector<std::string>& names) const;
  // Moves every file in the staging dir to its final name, updates the marker, removes the files
  // of this writer's previous run that it did not write again.
  void commit();
  OwnedOutputDir(const OwnedOutputDir&) = delete;
  OwnedOutputDir& operator=(const OwnedOutputDir&) = delete;

 private:
  std::string final_dir_, staging_dir_, owner_;
  std::vector<std::string> created_dirs_;  // deepest last
  bool committed_ = false;
};

// For outputs written in place over a long run (ts-rirgan-train's model dir: checkpoints rewritten
// as it trains, --resume): checks the directory as OwnedOutputDir does, creates it, and records
// `names` as the program's files in its marker before anything is written.
void claim_output_dir(const std::string& dir, const std::vector<std::string>& names);

}  // namespace tsrir
