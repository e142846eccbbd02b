// Sample-rate conversion with libsox's "rate -v" (very high quality, linear phase), apart from
// audio file I/O. Each call builds its own effects chain; calls from several threads are safe but
// run one at a time under one process-wide lock, because concurrent first calls into libsox
// corrupted the heap (see resampler.cc). Every libsox handle is owned by RAII, so an error cannot
// leak a chain.
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
