#!/usr/bin/env python3
"""Checks that a ts-rirgan-train model dir is the model a command would train.

Usage: translator_matches.py MODEL_DIR --program=ts-rirgan-train --steps=N [--config=FILE] [--key=value ...]

run_table2.sh --import-translator uses it before it takes a model trained elsewhere (a GPU
machine): every option's value (the program's defaults as its --help lists them, then the
--config file, then the command's options, later ones winning as in ts-rirgan-train) must equal the model's settings.txt entry of that name
('-' read as '_'; numbers compared as numbers, to 1e-9 relative), and loss_log.csv must end at
step N. ts-rirgan-train stores gain_weight as 0 for generators other than band_gain (it is
unused there; src/gan/gan_train.cc), and so is it expected here. Options that settings.txt does not store (they do not shape the model, e.g.
--collapse-check-every) are listed and not compared. Exit status 0 when the model matches, 1 with
every mismatch listed otherwise.
"""
import math
import os
import re
import subprocess
import sys


def help_defaults(program):
    """The '--key arg (=value)' defaults of a Kaldi-style program's --help."""
    text = subprocess.run([program, "--help"], capture_output=True, text=True).stdout
    text += subprocess.run([program, "--help"], capture_output=True, text=True).stderr
    return {m.group(1): m.group(2) for m in re.finditer(r"^\s+--([a-z0-9-]+) arg \(=([^)]*)\)", text, re.M)}


def parse_options(args):
    """--key=value arguments (and the lines of --config files) in order; later ones win."""
    options = {}
    for arg in args:
        if not arg.startswith("--") or "=" not in arg:
            raise SystemExit(f"translator_matches.py: expected --key=value, got '{arg}'")
        key, value = arg[2:].split("=", 1)
        if key == "config":
            with open(value) as f:
                lines = [ln.split("#", 1)[0].strip() for ln in f]
            options.update(parse_options([ln for ln in lines if ln]))
        else:
            options[key] = value
    return options


def read_settings(path):
    settings = {}
    with open(path) as f:
        for number, line in enumerate(f, 1):
            parts = line.split(None, 1)
            if len(parts) == 2:
                settings[parts[0]] = parts[1].strip()
            elif parts:
                raise SystemExit(f"translator_matches.py: {path}:{number}: not 'key value': {line.strip()}")
    return settings


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
    model, given = argv[1], parse_options(argv[2:])
    if "program" not in given or "steps" not in given:
        raise SystemExit("translator_matches.py: --program and --steps are required")
    options = help_defaults(given.pop("program"))
    options.update(given)
    steps = int(options.pop("steps"))
    if options.get("generator") != "band_gain":
        options["gain-weight"] = "0"
    settings = read_settings(os.path.join(model, "settings.txt"))
    problems, unchecked = [], []
    for key, value in options.items():
        stored = key.replace("-", "_")
        if stored not in settings:
            unchecked.append(key)
        elif not same(settings[stored], value):
            problems.append(f"{stored}: the model has {settings[stored]}, the command asks {value}")
    done = last_step(os.path.join(model, "loss_log.csv"))
    if done != steps:
        problems.append(f"steps: the model's loss_log.csv ends at step {done}, the command asks {steps}")
    if unchecked:
        print(f"translator_matches.py: not stored in settings.txt, not compared: {' '.join(unchecked)}", file=sys.stderr)
    for p in problems:
        print(f"translator_matches.py: {model}: {p}", file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
