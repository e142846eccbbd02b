#!/usr/bin/env python3
"""Where a translation moved an RIR's levels, re each RIR's own waveform peak (issue 34's diagnosis).

  bench/gan/translation_level_change.py WORK_DIR
  bench/gan/translation_level_change.py --bands WORK_DIR

WORK_DIR is a work dir that `gan-fidelity-suite ... keep` left: its test_syn/ (the inputs), sr/ (their
translations, same file names), train_real/ and train_syn/. Prints
  - per translated RIR, the change (translation - input) in dB of the > 2 kHz energy in the direct
    window (onset - 1 ms to onset + 2.5 ms) and after it: medians and interquartile ranges;
  - the broadband energy after the direct window re the peak's square, medians per set.
With --bands instead: the median change (translation - input, dB) of each octave-wide band's energy
(6th-order Butterworth, zero-phase: not the generator's raised-cosine bands) in windows after the
onset, a table whose rows are bands and columns time windows: where in time and frequency a
translation moves levels (a change meant for one band that also moves another shows up here).
The onset is the first sample within 20 dB of the peak (as the generator's). Needs numpy and scipy
(Debian python3-scipy); reads WAVs only (16 kHz, or 48 kHz resampled 1:3: rir_bands.py), writes nothing.
"""
import glob
import os
import sys

import numpy as np
from scipy.signal import sosfiltfilt

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rir_bands import butterworth_band, onset, read_rir, window_levels_db  # noqa: E402

HIGH_PASS = butterworth_band(2000, None)
BEFORE, AFTER = 16, 40  # samples: 1 ms before the onset, 2.5 ms after it


def high_band_levels_db(x):
    h, on = sosfiltfilt(HIGH_PASS, x), onset(x)
    return np.array([10 * np.log10(np.sum(h[max(0, on - BEFORE):on + AFTER] ** 2)),
                     10 * np.log10(np.sum(h[on + AFTER:] ** 2))])


def after_direct_db(x):
    return 10 * np.log10(np.sum(x[onset(x) + AFTER:] ** 2))


BAND_EDGES_HZ = [(None, 200), (200, 500), (500, 1000), (1000, 2000), (2000, 4000), (4000, None)]
WINDOWS_MS = [(-1, 2.5), (2.5, 20), (20, 50), (50, 100), (100, 200), (200, 400)]
BAND_FILTERS = [butterworth_band(low, high) for low, high in BAND_EDGES_HZ]


def band_window_levels_db(x):
    start = onset(x)
    return np.array([window_levels_db(sosfiltfilt(sos, x), start, WINDOWS_MS) for sos in BAND_FILTERS])


def print_band_table(work, pairs):
    change = np.median([band_window_levels_db(read_rir(out)) - band_window_levels_db(read_rir(inp))
                        for inp, out in pairs], axis=0)
    print(f'{work}: median change, translation - input, dB ({len(pairs)} RIRs); rows: band, columns: ms after the onset')
    print('band (Hz)   ' + ''.join(f'{f"{a:g}..{e:g}":>11}' for a, e in WINDOWS_MS))
    for (low, high), row in zip(BAND_EDGES_HZ, change):
        name = f'{low or 0:g}-{high:g}' if high else f'> {low:g}'
        print(f'{name:<12}' + ''.join(f'{v:+11.2f}' for v in row))


def main():
    bands = len(sys.argv) == 3 and sys.argv[1] == '--bands'
    if len(sys.argv) != 2 and not bands:
        sys.exit(__doc__)
    work = sys.argv[-1]
    if bands:
        pairs = [(p, os.path.join(work, 'sr', os.path.basename(p)))
                 for p in sorted(glob.glob(os.path.join(work, 'test_syn', '*.wav')))]
        pairs = [(i, o) for i, o in pairs if os.path.exists(o)]
        if not pairs:
            sys.exit(f'{work}: no translated RIR (sr/) matches an input (test_syn/)')
        return print_band_table(work, pairs)
    changes = []
    for path in sorted(glob.glob(os.path.join(work, 'test_syn', '*.wav'))):
        out = os.path.join(work, 'sr', os.path.basename(path))
        if os.path.exists(out):
            changes.append(high_band_levels_db(read_rir(out)) - high_band_levels_db(read_rir(path)))
    if not changes:
        sys.exit(f'{work}: no translated RIR (sr/) matches an input (test_syn/)')
    changes = np.array(changes)
    for column, name in enumerate(['direct window', 'after it']):
        q1, median, q3 = np.percentile(changes[:, column], [25, 50, 75])
        print(f'{work}: > 2 kHz, {name}: change {median:+.2f} dB (IQR {q1:+.2f} .. {q3:+.2f}), {len(changes)} RIRs')
    for name in ['train_real', 'train_syn', 'test_syn', 'sr']:
        files = sorted(glob.glob(os.path.join(work, name, '*.wav')))
        if files:
            level = np.median([after_direct_db(read_rir(f)) for f in files])
            print(f'{work}: {name}: broadband energy after the direct window re peak^2, median {level:+.2f} dB ({len(files)} RIRs)')


if __name__ == '__main__':
    main()
