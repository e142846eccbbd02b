#!/usr/bin/env python3
"""Run-level summary of several R3VIVAL translation pages (bench/gan/r3vival_translation.sh, one
training seed each, same split and options but the seed): per seed, G(GAS)'s Table-1 means and how
many of the 4 parameters moved toward the measured room; per parameter, in how many runs it moved
toward real and the mean and spread over runs of the move (G(GAS) - GAS) against the gap (real - GAS);
per octave band, how many runs moved each band's RT and EDT toward real.
--side-by-side: pages of different configurations (same split), one column of G(GAS) per page: the
Table-1 means and each octave band's RT.
Usage: r3vival_seeds.py [--side-by-side] PAGE [PAGE ...] > summary.md   (standard library only)"""
import math
import re
import sys

PARAMS = ["T60 (s)", "DRR (dB)", "EDT (s)", "C50 (dB)"]


def read_page(path):
    text = open(path).read()
    seed = re.search(r"--seed=(\d+)", text)
    machine = re.search(r"Machine: ([^;]*); ([0-9TZ:-]+);", text)
    train_s = re.search(r"Training took (\d+) s", text)
    table1, bands, band_rt = {}, {}, {}
    for line in text.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) == 5 and cells[0] in PARAMS:
            table1[cells[0]] = tuple(float(c) for c in cells[1:4])  # real, GAS, G(GAS)
        if len(cells) == 9 and re.fullmatch(r"[0-9.]+", cells[0]):
            bands[cells[0]] = (cells[4], cells[8])  # RT, EDT: toward|away
            band_rt[cells[0]] = tuple(float(c) for c in cells[1:4])  # RT real, GAS, G(GAS)
    if len(table1) != 4:
        sys.exit(f"{path}: no Table 1 (want the rows {', '.join(PARAMS)})")
    return {"path": path, "seed": seed.group(1) if seed else "?", "machine": machine.group(1) if machine else "?",
            "date": machine.group(2) if machine else "?", "train_s": train_s.group(1) if train_s else "?",
            "table1": table1, "bands": bands, "band_rt": band_rt}


def mean_sd(values):
    m = sum(values) / len(values)
    sd = math.sqrt(sum((v - m) ** 2 for v in values) / (len(values) - 1)) if len(values) > 1 else float("nan")
    return m, sd


def side_by_side(runs):
    w = print
    w("| measure | real | GAS | " + " | ".join(f"G(GAS), `{r['path']}`" for r in runs) + " |")
    w("|---|---|---|" + "---|" * len(runs))
    for p in PARAMS:
        real, gas = runs[0]["table1"][p][:2]
        w(f"| {p} | {real:.3f} | {gas:.3f} | " + " | ".join(f"{r['table1'][p][2]:.3f}" for r in runs) + " |")
    for b in (b for b in runs[0]["band_rt"] if all(b in r["band_rt"] for r in runs)):
        real, gas = runs[0]["band_rt"][b][:2]
        w(f"| RT at {b} Hz (s) | {real:.3f} | {gas:.3f} | " + " | ".join(f"{r['band_rt'][b][2]:.3f}" for r in runs) + " |")
    w("| closer to real (of T60, DRR, EDT, C50) | | | "
      + " | ".join(str(sum(abs(g - re_) < abs(ga - re_) for re_, ga, g in r["table1"].values())) for r in runs) + " |")


def main():
    args = sys.argv[1:]
    compare = bool(args) and args[0] == "--side-by-side"
    runs = [read_page(p) for p in args[compare:]]
    if not runs:
        sys.exit(__doc__)
    n = len(runs)
    for r in runs[1:]:
        if any(r["table1"][p][:2] != runs[0]["table1"][p][:2] for p in PARAMS):
            sys.exit(f"{r['path']}: its real or GAS means differ from {runs[0]['path']}'s: not the same split")
    if compare:
        side_by_side(runs)
        return
    w = print
    w("| seed | page | machine, date | training s | " + " | ".join("G(GAS) " + p for p in PARAMS) + " | closer |")
    w("|---|---|---|---|" + "---|" * len(PARAMS) + "---|")
    for r in runs:
        closer = sum(abs(g - real) < abs(gas - real) for real, gas, g in r["table1"].values())
        w(f"| {r['seed']} | `{r['path']}` | {r['machine']}, {r['date']} | {r['train_s']} | "
          + " | ".join(f"{r['table1'][p][2]:.3f}" for p in PARAMS) + f" | {closer} of 4 |")
    w("")
    w(f"Per parameter over the {n} runs: the move G(GAS) - GAS as a fraction of the gap real - GAS (1: all")
    w("the way to real; negative: away), mean and standard deviation over runs, and the runs that moved it toward real.\n")
    w("| parameter | real | GAS | move / gap, mean | sd over runs | runs toward real |")
    w("|---|---|---|---|---|---|")
    for p in PARAMS:
        real, gas = runs[0]["table1"][p][:2]
        fractions = [(r["table1"][p][2] - gas) / (real - gas) for r in runs]
        toward = sum(abs(r["table1"][p][2] - real) < abs(gas - real) for r in runs)
        m, sd = mean_sd(fractions)
        w(f"| {p} | {real:.3f} | {gas:.3f} | {m:+.2f} | {sd:.2f} | {toward} of {n} |")
    w("")
    bands = [b for b in runs[0]["bands"] if all(b in r["bands"] for r in runs)]
    if bands:
        w("Per octave band: the runs that moved the band's decay toward real.\n")
        w("| band (Hz) | " + " | ".join(bands) + " |")
        w("|---|" + "---|" * len(bands))
        for k, name in ((0, "RT"), (1, "EDT")):
            w(f"| {name} | " + " | ".join(f"{sum(r['bands'][b][k] == 'toward' for r in runs)} of {n}" for b in bands) + " |")


if __name__ == "__main__":
    main()
