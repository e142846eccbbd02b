#!/usr/bin/env python3
"""Prints band_accuracy.sh's table from the rir-metrics JSON files in DIR (tsrir_<room>.json,
pra_<room>.json; a missing pra file prints "absent")."""
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import rooms  # noqa: E402

BANDS = ["125", "250", "500", "1000", "2000", "4000"]


def load(path):
    if not os.path.exists(path):
        return None
    with open(path) as f:
        return json.load(f)["rirs"]


def mean(rirs, get):
    v = [get(r) for r in rirs]
    v = [x for x in v if x is not None]
    return sum(v) / len(v) if v else None


def f(x, fmt="%.3f"):
    return "absent" if x is None else fmt % x


def main():
    d = sys.argv[1]
    print("\n## Per-band T30 / EDT (s) and broadband C50 (dB): tsrir gas vs pyroomacoustics hybrid vs Sabine/Eyring")
    print("| room | source | n | " + " | ".join("T30 %s" % b for b in BANDS) + " | EDT 500-1k mean | C50 | T60 (rir-metrics) |")
    print("|---|---|---|" + "---|" * (len(BANDS) + 3))
    for r in rooms.rooms():
        for tool, label in (("tsrir", "tsrir gas"), ("pra", "pyroomacoustics hybrid")):
            rirs = load(os.path.join(d, "%s_%s.json" % (tool, r["name"])))
            if rirs is None:
                print("| %s | %s | - | " % (r["name"], label) + " | ".join(["absent"] * (len(BANDS) + 3)) + " |")
                continue
            t30 = [mean(rirs, lambda x, b=b: (x["bands"].get(b) or {}).get("T30")) for b in BANDS]
            edt = mean(rirs, lambda x: 0.5 * (x["bands"]["500"]["EDT"] + x["bands"]["1000"]["EDT"])
                       if x["bands"]["500"]["EDT"] and x["bands"]["1000"]["EDT"] else None)
            print("| %s | %s | %d | " % (r["name"], label, len(rirs)) + " | ".join(f(x) for x in t30) +
                  " | %s | %s | %s |" % (f(edt), f(mean(rirs, lambda x: x["C50"]), "%.1f"), f(mean(rirs, lambda x: x["T60"]))))
        sab, eyr = rooms.sabine_t60(r), rooms.eyring_t60(r)
        print("| %s | Sabine (alpha %.3f, all bands) | - | " % (r["name"], r["alpha"]) + " | ".join(["%.3f" % sab] * len(BANDS)) + " | | | %.3f |" % sab)
        print("| %s | Eyring (alpha %.3f, all bands) | - | " % (r["name"], r["alpha"]) + " | ".join(["%.3f" % eyr] * len(BANDS)) + " | | | %.3f |" % eyr)


if __name__ == "__main__":
    main()
