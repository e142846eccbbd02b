#!/usr/bin/env python3
"""Band levels re an RIR's loudest cell and re its direct sound, per set (issue 34, item 3).

  bench/gan/envelope_reference_levels.py NAME=SCP [NAME=SCP ...]

The envelope critic (src/gan/gan_band_envelope.h) reads each band's level per 32 ms Hann frame (hop
8 ms) re one reference: the RIR's loudest cell (band x frame; --disc-view=waveform+envelope, the
default) or the direct sound (--envelope-reference=direct-sound). This script measures the same
two maps in its own formulation (octave bands as rectangular groups of FFT bins, not the critic's
raised-cosine bands; the direct sound as the energy of the peak +-2.5 ms, in the units of a frame's
power spectrum summed over its bins) and prints per set: in which band each RIR's loudest cell lies,
then the median level (dB) of each octave band at frames starting 0 to 600 ms after the onset (first
sample within 20 dB of the peak) re each reference, then each later set minus the first. Reads the
WAVs only (16 kHz, or 48 kHz resampled 1:3 as band_window_levels.py does); needs numpy and scipy.
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from band_window_levels import CENTRES_HZ, named_sets, print_table  # noqa: E402
from rir_bands import RATE_HZ, read_rir, read_scp  # noqa: E402

FRAME, HOP = 512, 128
DIRECT_HALF = 40  # 2.5 ms
TIMES_MS = [0, 20, 50, 100, 200, 300, 400, 500, 600]
WINDOW = np.hanning(FRAME)
FREQS_HZ = np.fft.rfftfreq(FRAME, 1 / RATE_HZ)
MASKS = np.array([(FREQS_HZ >= c / np.sqrt(2)) & (FREQS_HZ < c * np.sqrt(2)) for c in CENTRES_HZ], float)


def frame_power(frames):
    return np.abs(np.fft.rfft(frames * WINDOW, axis=-1)) ** 2


def rir_maps(x):
    """(band of the loudest cell, levels re it [bands, times], levels re the direct sound [bands, times])."""
    count = (len(x) - FRAME) // HOP + 1
    cells = frame_power(np.stack([x[i * HOP:i * HOP + FRAME] for i in range(count)])) @ MASKS.T  # [frames, bands]
    peak = int(np.argmax(np.abs(x)))
    centred = np.zeros(FRAME)
    centred[FRAME // 2 - DIRECT_HALF:FRAME // 2 + DIRECT_HALF] = np.pad(x, DIRECT_HALF)[peak:peak + 2 * DIRECT_HALF]
    direct = frame_power(centred).sum()
    onset = int(np.argmax(np.abs(x) >= 0.1))
    rows = [min(count - 1, (onset + t * RATE_HZ // 1000) // HOP) for t in TIMES_MS]
    loudest = np.unravel_index(np.argmax(cells), cells.shape)[1]
    chosen = cells[rows].T + 1e-30
    return CENTRES_HZ[loudest], 10 * np.log10(chosen / cells.max()), 10 * np.log10(chosen / direct)


def main():
    sets = named_sets(sys.argv[1:], __doc__)
    medians = {}
    for name, scp in sets:
        maps = [rir_maps(read_rir(p)) for p in read_scp(scp)]
        bands, counts = np.unique([m[0] for m in maps], return_counts=True)
        print(f'{name} ({len(maps)} RIRs): loudest cell in the band of '
              + ', '.join(f'{b} Hz: {c}' for b, c in zip(bands, counts)))
        medians[name] = [np.median([m[k] for m in maps], axis=0) for k in (1, 2)]
    for k, reference in enumerate(['the loudest cell', 'the direct sound (peak +-2.5 ms)']):
        for name, _ in sets:
            print_table(f'{name}: median level re {reference}, dB; columns: ms after the onset', medians[name][k],
                        TIMES_MS, 8)
        for name, _ in sets[1:]:
            print_table(f'{name} - {sets[0][0]}, re {reference}, dB', medians[name][k] - medians[sets[0][0]][k],
                        TIMES_MS, 8)


if __name__ == '__main__':
    main()
