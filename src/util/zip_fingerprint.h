// A cheap fingerprint of a zip archive's contents, read from its end alone: the central directory
// lists every record's name, sizes and CRC-32, so two archives with the same directory hold the
// same bytes (up to CRC-32 collisions). Used to tie a file derived from a checkpoint (LibTorch's
// archives are zip files) to that checkpoint without reading the checkpoint's gigabyte.
#pragma once
#include <string>

namespace tsrir {

// 16 hex digits: the 64-bit FNV-1a hash of the central directory's bytes. Handles zip64
// (archives over 4 GiB). Error naming `path` if it cannot be read or is not a zip archive.
std::string zip_fingerprint(const std::string& path);

}  // namespace tsrir
