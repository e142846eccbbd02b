"""Shared by the Python tests: fabricated signals, an independent WAV reader/writer (Python's own
`wave` module, not the toolkit's libsndfile path), and running the built programs.

The tests exit with status 77 (ctest: skipped) when the module cannot be imported.
"""
import os
import subprocess
import sys
import tempfile
import wave

try:
    import numpy as np
    import tsrir  # noqa: F401  (the built package, through PYTHONPATH)
except ImportError as e:  # pragma: no cover
    print("skipped: the tsrir Python module or numpy is not available (%s)" % e)
    sys.exit(77)

BIN = os.environ.get("TSRIR_BIN_DIR", "")


def program(name):
    path = os.path.join(BIN, name)
    if not os.access(path, os.X_OK):
        raise RuntimeError("program %s not built (TSRIR_BIN_DIR=%s)" % (name, BIN))
    return path


def run(args, cwd=None):
    """Runs a program; raises with its stderr when it fails."""
    r = subprocess.run(args, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        raise RuntimeError("%s failed (%d):\n%s" % (" ".join(args), r.returncode, r.stderr))
    return r.stdout


def temp_dir(tag):
    return tempfile.mkdtemp(prefix="tsrir_py_%s_" % tag)


def speech_like(n, fs, seed):
    """Voiced-speech-like test signal: harmonics of a gliding f0, syllable-rate envelope, noise."""
    rng = np.random.default_rng(seed)
    t = np.arange(n) / fs
    f0 = 110 + 30 * np.sin(2 * np.pi * 0.7 * t + rng.uniform(0, 6))
    phase = 2 * np.pi * np.cumsum(f0) / fs
    x = sum(np.sin(k * phase) / k for k in range(1, 12))
    env = 0.5 * (1 + np.sin(2 * np.pi * 4 * t + rng.uniform(0, 6))) ** 2
    return 0.2 * env * x + 0.01 * rng.standard_normal(n)


def synthetic_rir(n, fs, delay, t60, seed, channels=1):
    """A direct spike at `delay` followed by exponentially decaying noise (its own formulation,
    not the toolkit's simulator)."""
    rng = np.random.default_rng(seed)
    out = []
    for c in range(channels):
        t = np.arange(n) / fs
        h = rng.standard_normal(n) * np.exp(-6.91 * t / t60) * 0.3
        h[: delay + c] = 0
        h[delay + c] = 1.0
        out.append(h / np.max(np.abs(h)) * 0.8)
    return np.array(out) if channels > 1 else out[0]


def write_wav16(path, x, fs):
    """int16 PCM through Python's wave module: samples rounded from full scale 1.0 = 32768."""
    x = np.atleast_2d(np.asarray(x, dtype=np.float64))
    q = np.clip(np.round(x * 32768), -32768, 32767).astype("<i2")
    with wave.open(path, "wb") as w:
        w.setnchannels(q.shape[0])
        w.setsampwidth(2)
        w.setframerate(int(fs))
        w.writeframes(q.T.copy().tobytes())


def read_wav16(path_or_bytes):
    """(int16 array (channels, n), fs) through Python's wave module."""
    import io
    src = io.BytesIO(path_or_bytes) if isinstance(path_or_bytes, bytes) else path_or_bytes
    with wave.open(src, "rb") as w:
        if w.getsampwidth() != 2:
            raise ValueError("not 16-bit")
        ch, fs, n = w.getnchannels(), w.getframerate(), w.getnframes()
        data = np.frombuffer(w.readframes(n), dtype="<i2").reshape(n, ch).T
    return data, fs


def write_text(path, text):
    with open(path, "w") as f:
        f.write(text)
