// The speech input of one utterance, opened so that its length never decides the memory used:
// a short input is decoded into memory (the fast path, as before), a long one is left on disk
// for reverberate_stream(): the file itself, or a copy of a pipe or stdin (which cannot be read
// twice) made with bounded memory.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "augment/temp_file.h"
#include "io/audio_io.h"

namespace tsrir {

// Default for --max-in-memory-duration: five minutes of audio. A 5-minute utterance peaks at ~70 MB
// on the in-memory path (1 s RIR, noise); beyond that the passes over the file keep memory flat
// (~30 MB whatever the length). Shorter inputs keep the in-memory path: no temporary files.
constexpr double kDefaultMaxInMemoryDurationS = 300.0;

struct SpeechInput {
  // In memory (short): every channel, and the file's description.
  std::vector<std::vector<float>> channels;
  AudioInfo info;
  // On disk (long): an audio file to read in passes, and the copy it may be of `rx`.
  std::string rx;
  std::string path;
  std::unique_ptr<TempFile> copy;
  bool on_disk() const { return !path.empty(); }
};

// `rx`: a path, "-" or "command |". A file is kept on disk when its header says it is longer than
// `max_in_memory_s` seconds; a pipe or stdin is read into memory up to the bytes of that many
// seconds of 16 kHz float audio (64 kB/s) and copied to a temporary file <temp_base>.tmp.* when it
// is longer. 0 keeps every input on disk. Errors name `context` and `rx`, as read_audio_channels().
SpeechInput open_speech_input(const std::string& rx, double max_in_memory_s, const std::string& temp_base,
                              const std::string& context);

}  // namespace tsrir
