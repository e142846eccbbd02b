#!/usr/bin/env python3
"""Microphone arrays and polar patterns (issue 33): rir-simulate's image sources (--model=ism,
scattering 0, through the tsrir module's simulate_line, the same code) against RIR-Generator
(Habets; microphone patterns and orientation, no source patterns), same room, array, reflection
coefficient (beta = sqrt(1 - alpha), all six surfaces), RIR-Generator's high-pass filter off.

  PYTHONPATH=build/python array_accuracy.py RIR_GENERATOR_ARRAY [window ms (50)]
RIR_GENERATOR_ARRAY: a driver around computeRIR() of RIR-Generator's rir_generator_core.cpp, built
outside this repository (nothing of RIR-Generator is committed), called as
  driver --room=Lx,Ly,Lz --src=x,y,z --mics=x,y,z;x,y,z;... --beta=B --nsamples=N --mtype=o|s|c|h|b
         --orientation=AZ_DEG,EL_DEG --c=343 --fs=16000 OUT
writing OUT as float64 little-endian, microphone after microphone (N samples each), order -1
(every image), high-pass off.
Per configuration (the reference room of bench/peers/rooms.py, an 8-microphone circular array of
radius 5 cm, each pattern at an orientation): per microphone the direct sound's time (a parabola
through |h| at the geometric arrival, computed here) and amplitude in both, the TDOA to
microphone 0 in both, and the sample-by-sample difference energy over the window relative to
RIR-Generator's (full band: the two band-limit their arrivals differently, 16 vs 128 taps).
"""
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

import tsrir

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import rooms  # noqa: E402
from rooms import fmt, peak  # noqa: E402

FS = 16000
C = 343.0
ROOM = (6.0, 4.5, 3.0)
SRC = (2.0, 1.5, 1.6)
CENTRE = (4.0, 3.0, 1.2)
ALPHA = 0.169644          # the reference room's absorption (rooms.py)
PATTERNS = [("omni", "o", 0.0), ("subcardioid", "s", 210.0), ("cardioid", "c", 216.87),
            ("hypercardioid", "h", 180.0), ("figure8", "b", 90.0)]


def mics():
    return [(CENTRE[0] + 0.05 * math.cos(2 * math.pi * k / 8), CENTRE[1] + 0.05 * math.sin(2 * math.pi * k / 8),
             CENTRE[2]) for k in range(8)]


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    driver = sys.argv[1]
    win_ms = float(sys.argv[2]) if len(sys.argv) > 2 else 50.0
    n = int(win_ms * FS / 1000)
    print(rooms.machine_line())
    print("## 8-mic circular array (r = 5 cm) in the reference room: rir-simulate --model=ism vs RIR-Generator, %g ms"
          % win_ms)
    print("| pattern, axis azimuth | direct time diff, worst (samples) | TDOA to mic 0 diff, worst (samples) | "
          "direct amplitude ratio tsrir/RIR-Gen, min / max | pattern gain (direct re omni) range over the mics, "
          "tsrir | worst gain difference tsrir - RIR-Gen | difference energy over the window (dB re RIR-Gen), worst "
          "mic |")
    print("|---|---|---|---|---|---|---|")
    beta = math.sqrt(1 - ALPHA)
    positions = mics()
    omni = None  # direct amplitudes of the omni run, per microphone: (tsrir, RIR-Gen)
    with tempfile.TemporaryDirectory() as tmp:
        for name, mtype, az in PATTERNS:
            line = "arr room=%s src=%s mic=%s absorption=%.9f scattering=0 mic_pattern=%s mic_dir=%g,0" % (
                fmt(ROOM), fmt(SRC), ";".join(fmt(p) for p in positions), ALPHA, name, az)
            ours = tsrir.simulate_line(line, FS, "ism:transition_ms=%g" % (win_ms + 10), 0, win_ms / 1000 + 0.02)
            out = os.path.join(tmp, "rg.bin")
            subprocess.run([driver, "--room=" + fmt(ROOM), "--src=" + fmt(SRC),
                            "--mics=" + ";".join(fmt(p) for p in positions), "--beta=%.9f" % beta,
                            "--nsamples=%d" % n, "--mtype=" + mtype, "--orientation=%g,0" % az, "--c=%g" % C,
                            "--fs=%d" % FS, out], check=True)
            rg = np.fromfile(out, dtype="<f8").reshape(len(positions), n)
            dt, tdoa, ratio, amps, err_db = [], [], [], [], []
            t0 = None
            for m, p in enumerate(positions):
                d = [SRC[i] - p[i] for i in range(3)]
                r = math.sqrt(sum(x * x for x in d))
                p1, a1 = peak(ours[m], r / C * FS)
                p2, a2 = peak(rg[m], r / C * FS)
                if t0 is None:
                    t0 = (p1, p2)
                dt.append(p1 - p2)
                tdoa.append((p1 - t0[0]) - (p2 - t0[1]))
                ratio.append(a1 / a2 if a2 != 0 else float("nan"))
                amps.append((a1, a2))
                err_db.append(10 * math.log10(np.sum((ours[m][:n] - rg[m]) ** 2) / np.sum(rg[m] ** 2)))
            ratio = np.array(ratio)
            if omni is None:
                omni = amps
            gains = np.array([(a1 / o1, a2 / o2) for (a1, a2), (o1, o2) in zip(amps, omni)])
            print("| %s, %g deg | %.3f | %.3f | %.4f / %.4f | %+.3f .. %+.3f | %.4f | %.1f |" % (
                name, az, np.max(np.abs(dt)), np.max(np.abs(tdoa)), np.nanmin(ratio), np.nanmax(ratio),
                gains[:, 0].min(), gains[:, 0].max(), np.max(np.abs(gains[:, 0] - gains[:, 1])), max(err_db)))


if __name__ == "__main__":
    main()
