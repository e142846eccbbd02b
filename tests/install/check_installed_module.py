"""Run by tests/install/*.sh with an installed tsrir (a venv's or a `cmake --install` prefix's), from
a directory outside the source and build trees: the package must come from where it was installed,
and work: an RIR from the simulator with the T60 asked for (measured by the module's rir-metrics),
a WAV written and read back, int sampling rates, Python exceptions.

usage: python3 check_installed_module.py <directory the package must be under> <forbidden dir>...
"""
import os
import sys
import tempfile

expected_root, forbidden = os.path.realpath(sys.argv[1]), [os.path.realpath(d) for d in sys.argv[2:]]
for entry in sys.path:
    real = os.path.realpath(entry or os.getcwd())
    for bad in forbidden:
        assert not (real + "/").startswith(bad + "/"), "sys.path holds %s, inside %s" % (entry, bad)

import numpy as np  # noqa: E402
import tsrir  # noqa: E402

where = os.path.realpath(tsrir.__file__)
assert where.startswith(expected_root + "/"), "tsrir imported from %s, not from under %s" % (where, expected_root)
assert os.path.realpath(tsrir._tsrir.__file__).startswith(expected_root + "/"), tsrir._tsrir.__file__

h = tsrir.simulate(room=(6, 4.5, 3), src=(2, 1.5, 1.6), mic=(4, 3, 1.2), fs=16000, t60=0.6, seed=1)
assert h.shape == (16000,) and h.dtype == np.float32, (h.shape, h.dtype)
t60 = tsrir.metrics(h, 16000)["T60"]
assert 0.45 < t60 < 0.75, "T60 %.3f s for an RIR simulated with t60=0.6" % t60

d = tempfile.mkdtemp(prefix="tsrir_installed_")
tsrir.write_wav(d + "/h.wav", h, 16000)
back, fs = tsrir.read_audio(d + "/h.wav")
assert type(fs) is int and fs == 16000, repr(fs)
assert back.shape == (1, 16000) and np.max(np.abs(back[0] - h)) <= 1.0 / 32768 + 1e-7
try:
    tsrir.reverberate(back[0], h, 16000, noise=back[0], snr_db="ten")
    raise AssertionError("snr_db='ten' was accepted")
except TypeError as e:
    assert "snr_db" in str(e), str(e)
os.remove(d + "/h.wav")
os.rmdir(d)
print("ok: tsrir from %s: T60 %.2f s, WAV round trip at %d Hz" % (os.path.dirname(where), t60, fs))
