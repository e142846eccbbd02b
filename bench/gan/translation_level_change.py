#!/usr/bin/env python3
"""Where a translation moved an RIR's levels, re each RIR's own waveform peak (issue 34's diagnosis).

  bench/gan/translation_level_change.py WORK_DIR

WORK_DIR is a work dir that `gan-fidelity-suite ... keep` left: its test_syn/ (the inputs), sr/ (their
translations, same file names), train_real/ and train_syn/. Prints
  - per translated RIR, the change (translation - input) in dB of the > 2 kHz energy in the direct
    window (onset - 1 ms to onset + 2.5 ms) and after it: medians and interquartile ranges;
  - the broadband energy after the direct window re the peak's square, medians per set.
The onset is the first sample within 20 dB of the peak (as the generator's). Needs numpy and scipy
(Debian python3-scipy); reads WAVs only, writes nothing.
"""
import glob
import os
import sys

import numpy as np
from scipy.io import wavfile
from scipy.signal import butter, sosfiltfilt

RATE_HZ = 16000
HIGH_PASS = butter(6, 2000, 'highpass', fs=RATE_HZ, output='sos')
BEFORE, AFTER = 16, 40  # samples: 1 ms before the onset, 2.5 ms after it


def peak_normalised(path):
    rate, x = wavfile.read(path)
    if rate != RATE_HZ:
        sys.exit(f'{path}: {rate} Hz, expected {RATE_HZ}')
    x = x.astype(float)
    return x / np.max(np.abs(x))


def onset(x):
    return int(np.argmax(np.abs(x) >= 0.1))


def high_band_levels_db(x):
    h, on = sosfiltfilt(HIGH_PASS, x), onset(x)
    return np.array([10 * np.log10(np.sum(h[max(0, on - BEFORE):on + AFTER] ** 2)),
                     10 * np.log10(np.sum(h[on + AFTER:] ** 2))])


def after_direct_db(x):
    return 10 * np.log10(np.sum(x[onset(x) + AFTER:] ** 2))


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    work = sys.argv[1]
    changes = []
    for path in sorted(glob.glob(os.path.join(work, 'test_syn', '*.wav'))):
        out = os.path.join(work, 'sr', os.path.basename(path))
        if os.path.exists(out):
            changes.append(high_band_levels_db(peak_normalised(out)) - high_band_levels_db(peak_normalised(path)))
    if not changes:
        sys.exit(f'{work}: no translated RIR (sr/) matches an input (test_syn/)')
    changes = np.array(changes)
    for column, name in enumerate(['direct window', 'after it']):
        q1, median, q3 = np.percentile(changes[:, column], [25, 50, 75])
        print(f'{work}: > 2 kHz, {name}: change {median:+.2f} dB (IQR {q1:+.2f} .. {q3:+.2f}), {len(changes)} RIRs')
    for name in ['train_real', 'train_syn', 'test_syn', 'sr']:
        files = sorted(glob.glob(os.path.join(work, name, '*.wav')))
        if files:
            level = np.median([after_direct_db(peak_normalised(f)) for f in files])
            print(f'{work}: {name}: broadband energy after the direct window re peak^2, median {level:+.2f} dB ({len(files)} RIRs)')


if __name__ == '__main__':
    main()
