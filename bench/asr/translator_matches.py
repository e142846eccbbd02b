#!/usr/bin/env python3
"""Checks that a ts-rirgan-train model dir is the model a command would train.

Usage: translator_matches.py MODEL_DIR --program=ts-rirgan-train --steps=N [ts-rirgan-train options ...]

run_table2.sh --import-translator uses it before it takes a model trained elsewhere (a GPU
machine). The program itself says what it would store: `ts-rirgan-train --print-settings` with
the given options (its defaults, --config and the command resolved as in training, and whatever
the chosen generator does not use set as training sets it). Every line must equal the model's
settings.txt line of that key (numbers compared as numbers, to 1e-9 relative), except real_list
and synthetic_list (the lists' absolute paths on the machine that trained it; listed, not
compared); and loss_log.csv must end at step N. Exit status 0 when the model matches, 1 with
every mismatch listed otherwise.
"""
import math
import os
import subprocess
import sys
import tempfile

MACHINE_PATHS = ("real_list", "synthetic_list")


def settings_of(text, where):
    """A settings.txt text as {key: value}."""
    settings = {}
    for number, line in enumerate(text.splitlines(), 1):
        parts = line.split(None, 1)
        if parts:
            settings[parts[0]] = parts[1].strip() if len(parts) == 2 else ""  # "real_list " without --real
    return settings


def planned_settings(program, options):
    """What `program` would store for a new model trained with `options`."""
    with tempfile.TemporaryDirectory() as scratch:  # the model dir argument; --print-settings leaves it
        run = subprocess.run([program, "--print-settings=true", *options, os.path.join(scratch, "model")],
                             capture_output=True, text=True)
    if run.returncode != 0:
        raise SystemExit(f"translator_matches.py: {program} --print-settings failed:\n{run.stderr}")
    return settings_of(run.stdout, f"{program} --print-settings")


def same(a, b):
    try:
        x, y = float(a), float(b)
    except ValueError:
        return a == b
    return math.isclose(x, y, rel_tol=1e-9, abs_tol=0.0)


def last_step(path):
    with open(path) as f:
        rows = [ln for ln in f.read().splitlines() if ln.strip()]
    return int(rows[-1].split(",", 1)[0]) if len(rows) > 1 else 0


def main(argv):
    if len(argv) < 2:
        raise SystemExit(__doc__)
    model, program, steps, options = argv[1], None, None, []
    for arg in argv[2:]:
        if arg.startswith("--program="):
            program = arg.split("=", 1)[1]
        elif arg.startswith("--steps="):
            steps = int(arg.split("=", 1)[1])
        else:
            options.append(arg)
    if program is None or steps is None:
        raise SystemExit("translator_matches.py: --program and --steps are required")
    wanted = planned_settings(program, options)
    with open(os.path.join(model, "settings.txt")) as f:
        stored = settings_of(f.read(), os.path.join(model, "settings.txt"))
    problems = []
    for key in sorted(set(wanted) | set(stored)):
        if key in MACHINE_PATHS:
            continue
        if key not in stored or key not in wanted or not same(stored[key], wanted[key]):
            problems.append(f"{key}: the model has {stored.get(key, '(none)')}, the command asks {wanted.get(key, '(none)')}")
    done = last_step(os.path.join(model, "loss_log.csv"))
    if done != steps:
        problems.append(f"steps: the model's loss_log.csv ends at step {done}, the command asks {steps}")
    print(f"translator_matches.py: not compared (paths on the training machine): {' '.join(MACHINE_PATHS)}", file=sys.stderr)
    for p in problems:
        print(f"translator_matches.py: {model}: {p}", file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
