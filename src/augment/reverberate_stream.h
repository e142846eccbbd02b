// reverberate_channel() for utterances too long to hold: the same output, byte for byte, with
// memory bounded independently of the utterance's length (a 2-hour one included).
//
// The semantics need whole-signal numbers before the first output sample: the SNR reference
// energy, the noise scales and the normalisation gain. So the input file is read in passes:
//  1. input power, length N and (with additive signals) the SNR reference: x ⊛ h_early (or x ⊛ h)
//     streamed through the engine, only its energy kept;
//  2. y = x ⊛ h + noise, streamed; the output power accumulated; the part of y the output uses
//     goes unscaled (float) to a temporary file -- or, when the gain is known in advance
//     (--volume, --normalize-output=false) and nothing is tiled, straight to the output;
//  3. the temporary file read back (cyclically for --duration tiling), scaled, encoded.
// Every number is computed by the steps the in-memory path uses (reverb_steps.h) and the
// convolution by the one engine on its own block grid (stream_convolution.h), hence the
// identical output. The output's length is known after pass 1, so the WAV header is written
// first and stdout or a pipe work as well as files (written atomically).
#pragma once
#include <string>
#include <vector>

#include "augment/reverberate.h"
#include "io/audio_io.h"

namespace tsrir {

// One output channel: its RIR (null: none) and additive signals, as reverberate_channel takes them.
struct StreamChannel {
  const PreparedRir* rir = nullptr;
  std::vector<AdditiveSignal> additive;
};

struct StreamSettings {
  std::string temp_base;                  // temporaries: <temp_base>.tmp.<pid>.<n> (temp_file.h)
  SampleFormat format = SampleFormat::kInt16;
  size_t chunk_samples = size_t{1} << 20; // outputs per engine call (~4 MB of float)
  size_t block_frames = size_t{1} << 16;  // frames per read and per write
};

struct StreamResult {
  size_t frames = 0;
  int channels = 0;
  long long clipped_samples = 0;
};

// Reverberates channel `input_channel` of the audio file `input_path` (seekable; errors name
// `context` and `shown_name`, default the path) into one output channel per entry of `channels`,
// all at the file's sample rate (RIRs and additive signals must already be), written to
// `output_wx` ("-", "| command" or a file) as a WAV. Throws Error as reverberate_channel does;
// a file output then does not appear, temporaries are removed.
StreamResult reverberate_stream(const std::string& input_path, const std::string& context,
                                const std::string& shown_name, int input_channel,
                                const std::vector<StreamChannel>& channels, const ReverbOptions& options,
                                const std::string& output_wx, const StreamSettings& settings);

}  // namespace tsrir
