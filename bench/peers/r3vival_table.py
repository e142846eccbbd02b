#!/usr/bin/env python3
"""Table of r3vival_t30.sh: per-band T30 of simulated vs measured held-out R3VIVAL RIRs."""
import json
import os
import sys

BANDS = ["125", "250", "500", "1000", "2000", "4000"]
d = sys.argv[1]


def load(name):
    with open(os.path.join(d, name + ".json")) as f:
        return {r["id"]: r for r in json.load(f)["rirs"]}


def t30(r, b):
    return (r["bands"].get(b) or {}).get("T30")


meas = load("measured")
print("\n## R3VIVAL held-out positions (%d RIRs): per-band T30, mean absolute error vs measured (s)" % len(meas))
print("| model | " + " | ".join("T30 %s Hz" % b for b in BANDS) + " | mean over bands |")
print("|---|" + "---|" * (len(BANDS) + 1))
per_cond = {}
for variant, label in (("baseline", "gas, stated flat T60 (baseline)"),
                       ("fitted_absorption", "gas + rir-diagnose's fitted band_absorption + scattering"),
                       ("extended", "full extended model (rir-diagnose)")):
    sim = load(variant)
    maes = []
    for b in BANDS:
        errs = [abs(t30(sim[i], b) - t30(m, b)) for i, m in meas.items()
                if i in sim and t30(sim[i], b) is not None and t30(m, b) is not None]
        maes.append(sum(errs) / len(errs) if errs else float("nan"))
    print("| %s | " % label + " | ".join("%.3f" % x for x in maes) + " | %.3f |" % (sum(maes) / len(maes)))
    per_cond[variant] = sim
print("\n## Mean T30 per condition (s): measured / fitted absorption / baseline")
print("| condition | " + " | ".join("%s Hz" % b for b in BANDS) + " |")
print("|---|" + "---|" * len(BANDS))
for cond in ("000", "025", "050", "075", "100"):
    ids = [i for i in meas if "_%s_" % cond in i]
    cells = []
    for b in BANDS:
        def m(src):
            v = [t30(src[i], b) for i in ids if i in src and t30(src[i], b) is not None]
            return sum(v) / len(v) if v else float("nan")
        cells.append("%.2f / %.2f / %.2f" % (m(meas), m(per_cond["fitted_absorption"]), m(per_cond["baseline"])))
    print("| %s (%d) | " % (cond, len(ids)) + " | ".join(cells) + " |")
