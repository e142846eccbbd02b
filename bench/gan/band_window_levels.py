#!/usr/bin/env python3
"""Where in time and frequency sets of RIRs differ: octave band x time window levels (issue 34, item 3).

  bench/gan/band_window_levels.py NAME=SCP [NAME=SCP ...]

Each SCP is a Kaldi list "<id> <wav path>" (16 kHz, or 48 kHz resampled by 1:3 polyphase: rir_bands.py). For
every RIR: the waveform scaled to its own peak (as the envelope critic's map is re each RIR's loudest
cell), the onset (first sample within 20 dB of the peak), then each band's energy (6th-order
Butterworth octave bands, zero-phase: not the generator's raised-cosine bands nor rir-metrics'
filters) in windows after the onset, in dB re the peak's square. Prints per set the median level of
each band and window over its RIRs, then each later set minus the first (rows: bands, columns:
windows). With the real set first and the synthetic set second, a band and window where
(translation - synthetic) differs in sign from (real - synthetic) is one the translator moves the
wrong way.

A second table per set: each band's decay rate in dB/s, a least-squares line through the band's
10 ms frame levels in each of five spans from 50 to 800 ms after the onset (medians over RIRs):
a tail that bends (a floor, or a second slope) shows as two different rates.
Needs numpy and scipy (Debian python3-scipy); reads WAVs only, writes nothing.
"""
import os
import sys

import numpy as np
from scipy.signal import sosfiltfilt

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rir_bands import RATE_HZ, butterworth_band, onset, read_rir, read_scp, samples, window_levels_db  # noqa: E402

CENTRES_HZ = [125, 250, 500, 1000, 2000, 4000]
WINDOWS_MS = [(-1, 2.5), (2.5, 20), (20, 50), (50, 100), (100, 200), (200, 400), (400, 700), (700, 1000)]
SLOPE_SPANS_MS = [(50, 150), (150, 300), (300, 450), (450, 600), (600, 800)]
FRAME_MS = 10
# Octave bands, the top one cut below Nyquist.
FILTERS = [butterworth_band(c / np.sqrt(2), min(c * np.sqrt(2), 0.95 * RATE_HZ / 2)) for c in CENTRES_HZ]


def rir_tables(x):
    """(band x window levels in dB re peak^2, band x span decay rates in dB/s) of one RIR."""
    start = onset(x)
    levels, rates = [], []
    frame = samples(FRAME_MS)
    for sos in FILTERS:
        band = sosfiltfilt(sos, x)
        levels.append(window_levels_db(band, start, WINDOWS_MS))
        b = band ** 2
        row = []
        for a, e in SLOPE_SPANS_MS:
            starts = range(start + samples(a), min(start + samples(e), len(b) - frame) + 1, frame)
            frames = np.array([10 * np.log10(np.mean(b[s:s + frame]) + 1e-30) for s in starts])
            if len(frames) < 3:
                row.append(np.nan)
                continue
            t_s = np.arange(len(frames)) * FRAME_MS / 1000
            row.append(np.polyfit(t_s, frames, 1)[0])
        rates.append(row)
    return np.array(levels), np.array(rates)


def print_table(title, table, columns, width=11):
    """A bands x columns table of dB values, one row per octave band."""
    print(f'\n{title}')
    print(f'{"band (Hz)":<10}' + ''.join(f'{c:>{width}}' for c in columns))
    for centre, row in zip(CENTRES_HZ, table):
        print(f'{centre:<10}' + ''.join(f'{v:+{width}.1f}' for v in row))


def named_sets(argv, usage):
    """[(name, scp)] from NAME=SCP arguments; the usage text and exit without one."""
    if len(argv) < 1 or any('=' not in a for a in argv):
        sys.exit(usage)
    return [a.split('=', 1) for a in argv]


def main():
    sets = named_sets(sys.argv[1:], __doc__)
    window_names = [f'{a:g}..{e:g}' for a, e in WINDOWS_MS]
    span_names = [f'{a:g}..{e:g}' for a, e in SLOPE_SPANS_MS]
    medians = {}
    for name, scp in sets:
        tables = [rir_tables(read_rir(p)) for p in read_scp(scp)]
        levels = np.median([t[0] for t in tables], axis=0)
        rates = np.nanmedian([t[1] for t in tables], axis=0)
        medians[name] = levels
        print_table(f'{name} ({len(tables)} RIRs): median level, dB re peak^2; columns: ms after the onset',
                    levels, window_names)
        print_table(f'{name}: median decay rate, dB/s, over ms after the onset', rates, span_names)
    first = sets[0][0]
    for name, _ in sets[1:]:
        print_table(f'{name} - {first}: difference of the median levels, dB', medians[name] - medians[first],
                    window_names)
    if len(sets) >= 3:
        base = sets[1][0]
        for name, _ in sets[2:]:
            print_table(f'{name} - {base}: difference of the median levels, dB', medians[name] - medians[base],
                        window_names)


if __name__ == '__main__':
    main()
