// libsndfile, loaded on first use (util/dynamic_library.h): the decoder of every audio format that
// io/wav_reader.h does not read itself (FLAC, Ogg, 8-bit or 64-bit WAV, AIFF, ...). The functions
// are libsndfile's own, called through this table.
#pragma once
#include <sndfile.h>

namespace tsrir {

struct SndfileApi {
  decltype(&::sf_open) open;
  decltype(&::sf_open_virtual) open_virtual;
  decltype(&::sf_close) close;
  decltype(&::sf_readf_float) readf_float;
  decltype(&::sf_error) error;
  decltype(&::sf_strerror) strerror;
  decltype(&::sf_command) command;
};

// Loads libsndfile the first time (thread-safe); throws Error when it cannot be loaded.
const SndfileApi& sndfile();

}  // namespace tsrir
