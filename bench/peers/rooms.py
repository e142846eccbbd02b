#!/usr/bin/env python3
"""Room table of the side-by-side benchmarks (rooms.txt) and the one absorption every tool gets.

  rooms.py list                 -> name Lx,Ly,Lz src mic t60 alpha beta ism_samples (one line per room)
ism_samples: 16 kHz samples up to tsrir's image-source transition time (the delay before which
about 2000 images arrive, src/sim/image_sources.cc), i.e. the image set of --model=ism.
  rooms.py tsrir NAME N [scat]  -> N lines of a tsrir room list for that room (ids NAME_0001 ...)
Absorption: Eyring inversion of the target T60 with c = 343 m/s, the same as tsrir's t60= key,
but written out as absorption= so that pyroomacoustics and RIR-Generator get the identical value
(beta = sqrt(1 - alpha) for RIR-Generator's pressure reflection coefficients).
"""
import math
import os
import sys
import time

C = 343.0


def rooms():
    here = os.path.dirname(os.path.abspath(__file__))
    out = []
    with open(os.path.join(here, "rooms.txt")) as f:
        for line in f:
            line = line.split("#")[0].strip()
            if not line:
                continue
            name, dim, src, mic, t60 = line.split()
            dim = [float(x) for x in dim.split(",")]
            src = [float(x) for x in src.split(",")]
            mic = [float(x) for x in mic.split(",")]
            t60 = float(t60)
            V = dim[0] * dim[1] * dim[2]
            S = 2 * (dim[0] * dim[1] + dim[0] * dim[2] + dim[1] * dim[2])
            alpha = 1.0 - math.exp(-24 * math.log(10) * V / (C * S * t60))
            dist = math.sqrt(sum((a - b) ** 2 for a, b in zip(src, mic)))
            t_tr = max((3 * V * 2000 / (4 * math.pi)) ** (1 / 3) / C, dist / C + 1e-3)
            out.append(dict(name=name, dim=dim, src=src, mic=mic, t60=t60, V=V, S=S, alpha=alpha,
                            beta=math.sqrt(1 - alpha), ism_samples=int(math.ceil(t_tr * 16000))))
    return out


def by_name(name):
    for r in rooms():
        if r["name"] == name:
            return r
    sys.exit("rooms.py: no room '%s' in rooms.txt" % name)


def sabine_t60(r, alpha=None):
    a = r["alpha"] if alpha is None else alpha
    return 24 * math.log(10) * r["V"] / (C * r["S"] * a)


def eyring_t60(r, alpha=None):
    a = r["alpha"] if alpha is None else alpha
    return 24 * math.log(10) * r["V"] / (C * r["S"] * -math.log(1 - a))


def peak(h, pos):
    """(time in samples, amplitude) of the arrival near `pos`: the largest |h| within +-2 samples,
    refined by a parabola through |h| (shared by ism_accuracy.py and array_accuracy.py)."""
    i0 = int(round(pos))
    seg = range(max(1, i0 - 2), min(len(h) - 1, i0 + 3))
    i = max(seg, key=lambda k: abs(h[k]))
    a, b, c = abs(h[i - 1]), abs(h[i]), abs(h[i + 1])
    den = a - 2 * b + c
    off = 0.5 * (a - c) / den if den != 0 else 0.0
    return i + off, h[i] - 0.25 * (h[i - 1] - h[i + 1]) * off


def machine_line():
    """The first line of an accuracy table: cores, date and load (accuracy does not depend on it)."""
    with open("/proc/loadavg") as f:
        load = " ".join(f.read().split()[:3])
    return "machine: %d cores, %s UTC, load average %s (accuracy does not depend on it)" % (
        os.cpu_count(), time.strftime("%Y-%m-%d %H:%M", time.gmtime()), load)


def fmt(v):
    return ",".join("%g" % x for x in v)


if __name__ == "__main__":
    if len(sys.argv) >= 2 and sys.argv[1] == "list":
        for r in rooms():
            print(r["name"], fmt(r["dim"]), fmt(r["src"]), fmt(r["mic"]), r["t60"], "%.6f" % r["alpha"],
                  "%.6f" % r["beta"], r["ism_samples"])
    elif len(sys.argv) >= 4 and sys.argv[1] == "tsrir":
        r = by_name(sys.argv[2])
        scat = sys.argv[4] if len(sys.argv) > 4 else "0.1"
        for i in range(int(sys.argv[3])):
            print("%s_%04d room=%s src=%s mic=%s absorption=%.6f scattering=%s" %
                  (r["name"], i + 1, fmt(r["dim"]), fmt(r["src"]), fmt(r["mic"]), r["alpha"], scat))
    else:
        sys.exit(__doc__)
