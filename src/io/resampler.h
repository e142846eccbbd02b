// Sample-rate conversion with libsox's "rate -v" (very high quality, linear phase), apart from
// audio file I/O. Each call builds its own effects chain (no shared state, no global lock: calls on
// several threads run at once; libsox's shared FFT cache is lock-protected in its OpenMP build),
// and every libsox handle is owned by RAII, so an error cannot leak a chain.
#pragma once
#include <vector>

#include "io/signal.h"

namespace tsrir {

// Real conversions stay far inside this (8 kHz <-> 192 kHz is 24); beyond it a header is lying.
constexpr double kMaxResampleRatio = 64.0;

// Throws Error for non-positive rates or a ratio beyond kMaxResampleRatio, and for any libsox
// failure. Returns the input unchanged when the rates match. The output has
// round(n * to_hz / from_hz) samples.
std::vector<float> resample(const std::vector<float>& samples, double from_hz, double to_hz);
Signal resample(const Signal& signal, double to_hz);

}  // namespace tsrir
