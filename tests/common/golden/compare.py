#!/usr/bin/env python3
"""Compares a program run's outputs with the golden copies kept in the repository.

  compare.py --expected DIR --actual DIR [--replace FROM=TO ...] [--update]

Text files are compared after each --replace (the scratch directory and the bin directory become
placeholders); WAV files by header and samples. Ownership markers (.tsrir-owned) are left out:
they hold file times. The comparison is exact (byte for byte after the replacements) when the
machine is the kind the golden files were made on (same CPU model, recorded in DIR/.machine) or
TSRIR_GOLDEN_EXACT=1; on another kind of machine FFTW may choose other algorithms, so samples may
differ by 2 LSB (int16) or 1e-5 of the peak (float) and printed numbers by 1e-3 relative, and the
report says which files were exact. --update writes the actual outputs as the new golden copies.
"""
import argparse
import os
import re
import shutil
import struct
import sys

SKIP = {".tsrir-owned"}


def machine_kind():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return "unknown"


def files_under(root):
    out = []
    for dirpath, _, names in os.walk(root):
        for name in names:
            if name in SKIP or name == ".machine":
                continue
            out.append(os.path.relpath(os.path.join(dirpath, name), root))
    return sorted(out)


def read_wav(data):
    """(format tag, channels, rate, bits, samples as numbers) of a RIFF/WAVE file."""
    if data[:4] != b"RIFF" or data[8:12] != b"WAVE":
        raise ValueError("not a RIFF/WAVE file")
    pos, fmt, samples = 12, None, None
    while pos + 8 <= len(data):
        cid, size = data[pos:pos + 4], struct.unpack("<I", data[pos + 4:pos + 8])[0]
        body = data[pos + 8:pos + 8 + size]
        if cid == b"fmt ":
            tag, channels, rate, _, _, bits = struct.unpack("<HHIIHH", body[:16])
            if tag == 0xFFFE:  # WAVE_FORMAT_EXTENSIBLE: the sub-format's first two bytes
                tag = struct.unpack("<H", body[24:26])[0]
            fmt = (tag, channels, rate, bits)
        elif cid == b"data":
            samples = body
        pos += 8 + size + (size & 1)
    if fmt is None or samples is None:
        raise ValueError("no fmt or data chunk")
    tag, channels, rate, bits = fmt
    if tag == 1 and bits == 16:
        values = struct.unpack(f"<{len(samples) // 2}h", samples)
    elif tag == 3 and bits == 32:
        values = struct.unpack(f"<{len(samples) // 4}f", samples)
    else:
        raise ValueError(f"unsupported sample format {tag}/{bits}")
    return fmt, values


def compare_wav(expected, actual):
    """None when equal within tolerance, else why not."""
    ef, ev = read_wav(expected)
    af, av = read_wav(actual)
    if ef != af:
        return f"header {af} (format, channels, rate, bits), golden {ef}"
    if len(ev) != len(av):
        return f"{len(av)} samples, golden {len(ev)}"
    worst = max((abs(a - b) for a, b in zip(ev, av)), default=0)
    if ef[0] == 1:
        return None if worst <= 2 else f"samples differ by up to {worst} LSB (tolerance 2)"
    peak = max((abs(v) for v in ev), default=0.0)
    return None if worst <= 1e-5 * max(peak, 1e-30) else f"samples differ by up to {worst:g} (peak {peak:g})"


NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def compare_text(expected, actual):
    """None when the texts agree but for numbers within 1e-3 relative, else the first difference."""
    el, al = expected.splitlines(), actual.splitlines()
    if len(el) != len(al):
        return f"{len(al)} lines, golden {len(el)}"
    for n, (e, a) in enumerate(zip(el, al), 1):
        if e == a:
            continue
        if NUMBER.sub("#", e) != NUMBER.sub("#", a):
            return f"line {n}: '{a}', golden '{e}'"
        for x, y in zip(NUMBER.findall(e), NUMBER.findall(a)):
            if abs(float(x) - float(y)) > 1e-3 * max(1.0, abs(float(x))):
                return f"line {n}: '{a}', golden '{e}'"
    return None


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--expected", required=True)
    p.add_argument("--actual", required=True)
    p.add_argument("--replace", action="append", default=[])
    p.add_argument("--update", action="store_true")
    args = p.parse_args()
    replacements = [r.split("=", 1) for r in args.replace]
    # Longest first, so that a path inside another is replaced whole.
    replacements.sort(key=lambda r: -len(r[0]))

    def normalised(path):
        data = open(path, "rb").read()
        if path.endswith(".wav"):
            return data
        text = data.decode("utf-8")
        for old, new in replacements:
            text = text.replace(old, new)
        return text.encode("utf-8")

    actual_files = files_under(args.actual)
    if args.update:
        shutil.rmtree(args.expected, ignore_errors=True)
        for rel in actual_files:
            dst = os.path.join(args.expected, rel)
            os.makedirs(os.path.dirname(dst), exist_ok=True)
            open(dst, "wb").write(normalised(os.path.join(args.actual, rel)))
        open(os.path.join(args.expected, ".machine"), "w").write(machine_kind() + "\n")
        print(f"golden: wrote {len(actual_files)} files to {args.expected}")
        return 0

    made_on = open(os.path.join(args.expected, ".machine")).read().strip()
    exact = os.environ.get("TSRIR_GOLDEN_EXACT", "1" if made_on == machine_kind() else "0") == "1"
    expected_files = files_under(args.expected)
    problems, inexact = [], []
    for rel in sorted(set(expected_files) - set(actual_files)):
        problems.append(f"{rel}: missing")
    for rel in sorted(set(actual_files) - set(expected_files)):
        problems.append(f"{rel}: not in the golden outputs")
    for rel in sorted(set(expected_files) & set(actual_files)):
        e = open(os.path.join(args.expected, rel), "rb").read()
        a = normalised(os.path.join(args.actual, rel))
        if e == a:
            continue
        if exact:
            problems.append(f"{rel}: differs (exact comparison: the golden files were made on this kind of machine)")
            continue
        try:
            why = compare_wav(e, a) if rel.endswith(".wav") else compare_text(e.decode(), a.decode())
        except (ValueError, UnicodeDecodeError, struct.error) as err:
            why = str(err)
        if why:
            problems.append(f"{rel}: {why}")
        else:
            inexact.append(rel)
    mode = "exact" if exact else f"tolerant (golden files made on '{made_on}')"
    print(f"golden: {len(expected_files)} files compared, {mode}; "
          f"{len(expected_files) - len(inexact) - len(problems)} identical, {len(inexact)} within tolerance")
    for rel in inexact:
        print(f"  within tolerance, not identical: {rel}")
    for problem in problems:
        print(f"  FAIL {problem}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
