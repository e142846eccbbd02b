// A TS-RIRGAN model on disk: the checkpoint training resumes from, and the generator files
// translation reads (LibTorch archives). Private to src/gan (and its unit tests).
#pragma once
#include <string>

#include "gan/gan_networks.h"

namespace tsrir {
namespace gan {

// Checkpoint: one file with the settings text, the step, all four networks and the optimiser
// state; written to a temporary name and renamed. CPU tensors, so any device can load it.
void save_checkpoint(const std::string& path, const CycleGan& model, long long step);
// Restores everything into `model` (which must have been built from matching settings) and
// returns the step. Errors name the file: unreadable/corrupt, other width, missing tensors.
long long load_checkpoint(const std::string& path, CycleGan& model);
// The settings stored in a checkpoint (Error if the file is not a TS-RIRGAN checkpoint).
GanSettings read_checkpoint_settings(const std::string& path);

// Generator files: beside a checkpoint, each direction's translating generator alone
// (generator-g_real.pt, generator-g_synthetic.pt), with the weights translation uses by default
// (the moving average where the model keeps one), the settings, the step and the checkpoint's
// zip fingerprint (util/zip_fingerprint.h). Why: gas-to-real needs one generator, and the
// checkpoint holds six networks' weights and four optimisers' state (1.29 GB at width 64, its
// reading 1-3 s of a 170-RIR translation; one generator file is 166 MB). Written after the
// checkpoint, each to a temporary name and renamed.
std::string generator_file_path(const std::string& checkpoint_path, const std::string& name);
void save_generator_files(const std::string& checkpoint_path, const CycleGan& model, long long step);

// Which of a generator's stored weights translate: the last step's, or the moving average where
// the model keeps one (GanSettings::generator_average_decay > 0; the last step's otherwise).
enum class GeneratorWeights { kLast, kAverageWhereKept };
// Builds one generator ("g_real" or "g_synthetic") with the checkpoint's settings and weights;
// fills *settings and *step. Reads the generator file beside the checkpoint when it holds the
// weights asked for and its fingerprint is the checkpoint's (a file left from another checkpoint,
// or one that cannot be read, is ignored, with a warning); the checkpoint otherwise. *read_from
// (if given): the file read.
Generator load_generator(const std::string& path, const std::string& name, GeneratorWeights weights,
                         GanSettings* settings, long long* step, std::string* read_from = nullptr);

}  // namespace gan
}  // namespace tsrir
