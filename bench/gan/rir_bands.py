"""What the bench/gan measuring scripts share (issue 34): an RIR read and scaled to its own peak, its
onset, 6th-order Butterworth bands (zero-phase; their own formulation, not the generator's
raised-cosine bands nor rir-metrics' filters) and a band's energy in windows after the onset.
Needs numpy and scipy (Debian python3-scipy).
"""
import sys

import numpy as np
from scipy.io import wavfile
from scipy.signal import butter, resample_poly

RATE_HZ = 16000


def read_rir(path):
    """One channel at 16 kHz (48 kHz is resampled here by 1:3 polyphase, as R3VIVAL's), scaled to its peak."""
    rate, x = wavfile.read(path)
    x = x.astype(float)
    if x.ndim > 1:
        sys.exit(f'{path}: {x.shape[1]} channels, expected one')
    if rate == 3 * RATE_HZ:
        x = resample_poly(x, 1, 3)
    elif rate != RATE_HZ:
        sys.exit(f'{path}: {rate} Hz, expected {RATE_HZ} or {3 * RATE_HZ}')
    return x / np.max(np.abs(x))


def read_scp(path):
    """The wav paths of a Kaldi list "<id> <wav path>"."""
    with open(path) as f:
        rows = [line.split() for line in f if line.strip()]
    for number, row in enumerate(rows, 1):
        if len(row) != 2:
            sys.exit(f'{path}:{number}: expected "<id> <wav path>"')
    return [p for _, p in rows]


def onset(x):
    """The first sample within 20 dB of the peak of x (scaled to its peak), as the generator's."""
    return int(np.argmax(np.abs(x) >= 0.1))


def samples(ms):
    return int(round(ms * RATE_HZ / 1000))


def butterworth_band(low_hz, high_hz):
    """Second-order sections of a 6th-order Butterworth band-pass; low-pass without low_hz, high-pass without high_hz."""
    if low_hz is None:
        return butter(6, high_hz, 'lowpass', fs=RATE_HZ, output='sos')
    if high_hz is None:
        return butter(6, low_hz, 'highpass', fs=RATE_HZ, output='sos')
    return butter(6, [low_hz, high_hz], 'bandpass', fs=RATE_HZ, output='sos')


def window_levels_db(band, start, windows_ms):
    """10 log10 of band's energy in each (from, to) window, in ms after sample `start`."""
    return [10 * np.log10(np.sum(band[max(0, start + samples(a)):start + samples(e)] ** 2) + 1e-30)
            for a, e in windows_ms]
