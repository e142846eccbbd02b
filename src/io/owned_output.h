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
//  - it refuses an output directory that is, contains or lies inside any input (real paths, through
//    symlinks, including every file a list or wav.scp points at, pipes' file arguments included);
//  - files are written into a staging directory (.tsrir-staging.tmp.<pid>.<n>) inside the output
//    and renamed to their final names at commit, under an exclusive lock on the directory (two runs
//    sharing a directory see each other's files); a failed run leaves no staging directory and
//    removes directories it created that stayed empty.
#pragma once
#include <string>
#include <vector>

namespace tsrir {

class OptionsItf;

// Who writes and whether --overwrite was given: the policy every owned output of the process
// follows. A program's main makes one from its command line and installs it after parsing:
//   OutputPolicy policy(cli.program());  policy.Register(&cli);  cli.parse(...);
//   install_output_policy(policy);
struct OutputPolicy {
  std::string program = "tsrir";  // recorded in the marker as each file's writer
  bool overwrite = false;         // --overwrite: may write into a directory it does not own

  OutputPolicy() = default;
  // The program, not its sub-command: "rir-eq apply" and "rir-eq" write the same outputs.
  explicit OutputPolicy(const std::string& program_name);
  void Register(OptionsItf* opts);  // --overwrite (io/common_options.h)
};
// The installed policy (before any: program "tsrir", no --overwrite, as for the Python module).
const OutputPolicy& output_policy();
void install_output_policy(const OutputPolicy& policy);

// Records an input: a path, a directory, or an rxfilename (a pipe's existing file arguments count).
// Readers in src/io call it for the files they read and the files a list points at; every owned
// output is checked against every input noted so far, at creation and again at commit.
void note_input(const std::string& rx);
void note_inputs(const std::vector<std::string>& rxs);
void clear_noted_inputs();  // for tests
// Throws Error when `output_dir` is, contains or lies inside a noted input.
void check_output_not_input(const std::string& output_dir);

// Throws Error when the file `path` is a noted input (real paths); AtomicTextFile and write_wav call
// it for every file they are asked to write outside a staging directory.
void check_file_not_input(const std::string& path);

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
