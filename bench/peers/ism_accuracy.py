#!/usr/bin/env python3
"""Image sources of rir-simulate (--model=ism, scattering 0) against RIR-Generator (Habets), same
room, positions and reflection coefficients (beta = sqrt(1 - alpha) on all six surfaces), no
diffuse part, RIR-Generator's high-pass filter off (issue 20).

  ism_accuracy.py TSRIR_BIN RIR_GENERATOR [N reflections (20)] [window ms (100)]
For each room of rooms.txt: the first N arrivals that stand alone (no other image within 1 ms;
coincident images are merged; ISO_MS below), whose times come from the geometry computed here (a third,
independent formulation); in each RIR the peak within +-2 samples of that time, located to a
fraction of a sample by a parabola through |h|. Prints per room the worst and mean arrival-time
difference (samples) and amplitude ratio tsrir / RIR-Generator, and the sample-by-sample
difference energy over the whole window relative to RIR-Generator's energy (dB).
"""
import itertools
import math
import os
import subprocess
import sys
import tempfile

import numpy as np
import scipy.io.wavfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import rooms  # noqa: E402

FS = 16000
C = 343.0
ISO_MS = 0.25  # 4 samples: two sinc main lobes apart; side lobes of a neighbour still bias an amplitude by up to a few %


def read(path):
    fs, x = scipy.io.wavfile.read(path)
    assert fs == FS, path
    return np.asarray(x, dtype=np.float64)


def arrivals(r, max_s):
    """(delay in samples, amplitude) of every image within max_s, coincident ones merged."""
    L, s, m = r["dim"], r["src"], r["mic"]
    beta = r["beta"]
    nmax = [int(math.ceil(max_s * C / (2 * l))) + 1 for l in L]
    out = {}
    for n in itertools.product(*[range(-k, k + 1) for k in nmax]):
        for q in itertools.product((0, 1), repeat=3):
            d2, hits = 0.0, 0
            for i in range(3):
                x = (1 - 2 * q[i]) * s[i] + 2 * n[i] * L[i] - m[i]
                d2 += x * x
                hits += abs(n[i] - q[i]) + abs(n[i])
            d = math.sqrt(d2)
            if d / C >= max_s:
                continue
            key = round(d / C * FS, 6)
            out[key] = out.get(key, 0.0) + beta ** hits / (4 * math.pi * d)
    return sorted(out.items())


peak = rooms.peak


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    tsrir_bin, rirgen = sys.argv[1], sys.argv[2]
    nref = int(sys.argv[3]) if len(sys.argv) > 3 else 20
    win_ms = float(sys.argv[4]) if len(sys.argv) > 4 else 100.0
    nsamp = int(win_ms * FS / 1000)
    print(rooms.machine_line())
    print("## Image sources: rir-simulate --model=ism vs RIR-Generator, first %d arrivals isolated by > %g ms, %g ms window"
          % (nref, ISO_MS, win_ms))
    print("| room | beta | arrivals compared | time diff, mean / worst (samples) | amplitude ratio tsrir/RIR-Gen, mean / worst | "
          "direct sound ratio | difference energy over %g ms (dB re RIR-Gen), full band / below 6 kHz |" % win_ms)
    print("|---|---|---|---|---|---|---|")
    import scipy.signal
    sos = scipy.signal.butter(8, 6000, fs=FS, output="sos")
    with tempfile.TemporaryDirectory() as tmp:
        for r in rooms.rooms():
            lst = os.path.join(tmp, "rooms.txt")
            with open(lst, "w") as f:
                f.write("%s room=%s src=%s mic=%s absorption=%.9f scattering=0\n" % (
                    r["name"], rooms.fmt(r["dim"]), rooms.fmt(r["src"]), rooms.fmt(r["mic"]), r["alpha"]))
            out = os.path.join(tmp, "o_" + r["name"])
            subprocess.run([os.path.join(tsrir_bin, "rir-simulate"), "--fs=%d" % FS, "--format=float",
                            "--length=%g" % (win_ms / 1000 + 0.02), "--model=ism:transition_ms=%g" % (win_ms + 10),
                            lst, out], check=True, stderr=subprocess.DEVNULL)
            ours = read(os.path.join(out, r["name"] + ".wav"))[:nsamp]
            rg_wav = os.path.join(tmp, "rg_%s.wav" % r["name"])
            subprocess.run([rirgen, "--room=" + rooms.fmt(r["dim"]), "--src=" + rooms.fmt(r["src"]),
                            "--mic=" + rooms.fmt(r["mic"]), "--beta=%.9f" % r["beta"], "--nsamples=%d" % nsamp,
                            "--order=-1", "--hp=0", "--c=%g" % C, "--fs=%d" % FS, rg_wav], check=True)
            rg = read(rg_wav)
            arr = arrivals(r, win_ms / 1000 - 0.005)
            times = [t for t, _ in arr]
            iso = [(t, a) for k, (t, a) in enumerate(arr)
                   if all(abs(t - u) > ISO_MS / 1000 * FS for j, u in enumerate(times) if j != k)][:nref]
            dt, ratio = [], []
            for t, _ in iso:
                p1, a1 = peak(ours, t)
                p2, a2 = peak(rg, t)
                dt.append(p1 - p2)
                ratio.append(a1 / a2)
            dt, ratio = np.array(dt), np.array(ratio)
            direct = peak(ours, arr[0][0])[1] / peak(rg, arr[0][0])[1]
            n = min(len(ours), len(rg))
            err_db = 10 * math.log10(np.sum((ours[:n] - rg[:n]) ** 2) / np.sum(rg[:n] ** 2))
            lo1, lo2 = scipy.signal.sosfiltfilt(sos, ours[:n]), scipy.signal.sosfiltfilt(sos, rg[:n])
            err_lo = 10 * math.log10(np.sum((lo1 - lo2) ** 2) / np.sum(lo2 ** 2))
            worst_r = ratio[np.argmax(np.abs(ratio - 1))]
            print("| %s | %.4f | %d | %+.3f / %.3f | %.4f / %.4f | %.4f | %.1f / %.1f |" % (
                r["name"], r["beta"], len(iso), dt.mean(), np.abs(dt).max(), ratio.mean(), worst_r, direct, err_db, err_lo))


if __name__ == "__main__":
    main()
