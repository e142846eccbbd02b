"""Runs every example of README.md as printed: each command of its ```sh blocks (continuation lines
joined), in README order, in one scratch directory, with the programs of BIN first on PATH and the
tsrir package of PYTHONPATH importable by `python3`; the ```python block is example.py, the file the
README runs. A command passes when it exits 0 (and, for a few, when what it writes is there).

The README marks the few commands this does not run as printed, and says why, beside them; each is
listed in NOT_RUN / SUBSTITUTED below with the README text that must say so (checked here, so a
README edit cannot silently drop the note). Inputs the examples take for granted (rooms.txt from
R3VIVAL, real.scp, a Kaldi data dir data/clean, noise lists, speech.wav) are prepared first by
prepare_inputs.sh, from ../shared/data when present; commands that need ../shared/data are skipped
with a message when it is absent.

usage: readme_examples.py <README.md> <scratch dir> [--only REGEX]
Env: PATH (BIN first), PYTHONPATH, TSRIR_HAVE_SHARED=0|1, TSRIR_HAVE_TORCH_PROGRAMS=0|1.
"""
import os
import re
import subprocess
import sys
import time

# Commands not run here (prefix of the README command -> (why, README text that must say so)).
NOT_RUN = {
    "./utils/run_demo.sh": ("the whole demo (minutes); tests/recipe runs its reduced form",
                            "tests/recipe runs the demo's reduced form"),
    "./utils/run_tests.sh": ("the test suite itself", "the test suite itself"),
    "cmake --install build --prefix /opt/tsrir": ("run by this test with a temporary prefix instead of /opt/tsrir",
                                                  "with a temporary prefix"),
    "python3 -m venv": ("tests/install/venv_install_test.sh runs it", "venv_install_test.sh"),
    "~/venvs/tsrir/bin/pip": ("tests/install/venv_install_test.sh runs it", "venv_install_test.sh"),
    "python3 -m build": ("tests/install/venv_install_test.sh runs it", "venv_install_test.sh"),
}
# Commands run as a smaller variant: README text -> (replacement, README text that must say so).
SUBSTITUTED = {
    "--steps=20000 --width=64 --batch-size=64": ("--steps=2 --width=4 --batch-size=2",
                                                 "the README test trains it for 2 steps at width 4"),
    "asr-train --epochs=15": ("asr-train --epochs=1", "trains one epoch instead of 15"),
    "make_digit_corpus.sh digits 1 180 36": ("make_digit_corpus.sh digits 1 24 6",
                                             "The README test makes 24 + 6 utterances"),
}
# Commands that read ../shared/data (skipped when it is absent) and those that need LibTorch.
NEEDS_SHARED = ("rir-room-list --format=r3vival",)
NEEDS_TORCH = ("ts-rirgan-train", "gas-to-real", "asr-train", "asr-decode", "tests/asr/make_digit_corpus.sh",
               "examples/python/farfield_dataloader.py")
# What some commands must leave behind (a command's first words -> files).
PRODUCES = {
    "rir-room-list": ["rooms.txt"],
    "rir-simulate --sample-rate=16000 --length=auto one_room.txt": ["sim_one/r1.wav", "sim_one/rir_list"],
    "rir-simulate --sample-rate=16000 --length=1.0": ["gas/rir.scp", "gas/rir_list"],
    "rir-simulate --format=float --length=0.5 array_room.txt": ["sim_array/a1.wav", "sim_array/rir_list"],
    "wav-reverberate --multi-channel-output=true": ["far8.wav"],
    "reverberate-data --multi-channel-output=true": ["data/rvb8/wav.scp"],
    "rir-simulate --format=float --length=0.5 office.txt": ["sim_office/a1.wav", "sim_office/n1.wav"],
    "reverberate-data --split-channels=true": ["data/rvb8n/wav.scp", "data/rvb8n/reco2file_and_channel"],
    "rir-eq --real=real.scp": ["gas_eq/rir_list"],
    "reverberate-data --rir-set-parameters '0.5, real/rir_list'": ["data/rvb/wav.scp"],
    "reverberate-data --rir-set-parameters gas_eq/rir_list": ["data/rvb_wavs/wav.scp"],
    "wav-reverberate --impulse-response=sim_one/r1.wav": ["far.wav"],
    "rir-diagnose": ["diag/findings.json", "diag/report.html"],
    "python3 example.py": ["far.wav", "lhotse_rirs/cuts.jsonl", "rir_list_from_lhotse"],
}


def blocks(readme):
    """[(language, text, line number)] of the fenced blocks."""
    out, lang, start, lines = [], None, 0, []
    for number, line in enumerate(readme.splitlines(), 1):
        if line.startswith("```"):
            if lang is None:
                lang, start, lines = line[3:].strip() or "output", number, []
            else:
                out.append((lang, "\n".join(lines), start))
                lang = None
        elif lang is not None:
            lines.append(line)
    return out


def commands(block_text, first_line):
    """The block's commands: continuation lines joined; (command, README line)."""
    out, pending, start = [], "", first_line
    for offset, line in enumerate(block_text.splitlines(), 1):
        if not pending:
            start = first_line + offset
        if line.rstrip().endswith("\\"):
            pending += line.rstrip()[:-1] + " "
            continue
        command = (pending + line).strip()
        pending = ""
        if command and not command.startswith("#"):
            out.append((command, start))
    return out


def starts(command, prefixes):
    return any(command.startswith(p) or (" " + p) in command for p in prefixes)


def run_command(command, at, scratch, have_shared, have_torch):
    """Runs one README command as printed (or its stated variant): ("ok" | "skip" | "failed", text)."""
    label = "README.md:%d: %s" % (at, command if len(command) < 100 else command[:97] + "...")
    skip = next((why for prefix, (why, _) in NOT_RUN.items() if command.startswith(prefix)), None)
    if skip is None and not have_shared and starts(command, NEEDS_SHARED):
        skip = "needs ../shared/data, absent here"
    if skip is None and not have_torch and starts(command, NEEDS_TORCH):
        skip = "the LibTorch programs are not built (TSRIR_WITH_TORCH=OFF)"
    if skip:
        return "skip", "%s (%s)" % (label, skip)
    run_as = command
    for text_in, (replacement, _) in SUBSTITUTED.items():
        run_as = run_as.replace(text_in, replacement)
    shown = "" if run_as == command else " (run as: %s)" % run_as
    started = time.time()
    r = subprocess.run(["bash", "-c", "set -o pipefail; " + run_as], cwd=scratch, stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE, text=True)
    took = time.time() - started
    errors = [l for l in r.stderr.splitlines() if "ERROR" in l]
    problem = None
    if r.returncode != 0:
        problem = "exit status %d\n%s" % (r.returncode, "\n".join(r.stderr.splitlines()[-15:]))
    elif errors:  # e.g. a pipe's command that was cut off (flac: "ERROR, decoded number ...")
        problem = "exit status 0 but an error on stderr:\n" + "\n".join(errors[:5])
    else:
        for key, files in PRODUCES.items():
            if command.startswith(key) or (key == "python3 example.py" and command.endswith(key)):
                missing = [f for f in files if not os.path.exists(os.path.join(scratch, f))]
                if missing:
                    problem = "did not write %s" % ", ".join(missing)
    if problem:
        return "failed", "%s%s (%.1f s): %s" % (label, shown, took, problem)
    return "ok", "%s%s (%.1f s)" % (label, shown, took)


def main():
    readme_path, scratch = sys.argv[1], sys.argv[2]
    only = sys.argv[4] if len(sys.argv) > 4 and sys.argv[3] == "--only" else None
    with open(readme_path) as f:
        readme = f.read()
    failures = []
    flat = " ".join(readme.split())  # notes may wrap across lines
    for prefix, (_, note) in NOT_RUN.items():
        if note not in flat:
            failures.append("README.md does not say beside '%s' that it is not run here ('%s')" % (prefix, note))
    for text, (_, note) in SUBSTITUTED.items():
        if text in readme and note not in flat:
            failures.append("README.md runs '%s' here as a smaller variant but does not say so ('%s')" % (text, note))
    found = blocks(readme)
    pythons = [text for lang, text, _ in found if lang == "python"]
    if len(pythons) != 1:
        failures.append("README.md should hold exactly one ```python block (example.py), found %d" % len(pythons))
    else:
        with open(os.path.join(scratch, "example.py"), "w") as f:
            f.write(pythons[0] + "\n")
    have_shared = os.environ.get("TSRIR_HAVE_SHARED") == "1"
    have_torch = os.environ.get("TSRIR_HAVE_TORCH_PROGRAMS") == "1"
    ran = 0
    todo = [(command, at) for lang, text, line in found if lang == "sh" for command, at in commands(text, line)]
    todo = [(c, at) for c, at in todo if not only or re.search(only, c)]
    # The README is documentation, not a script: a section may use what a later one makes (Table 1
    # of rir-metrics reads rir-eq's output). A command that fails is run again once after all the
    # others; only its second failure counts.
    retry = []
    for attempt in (1, 2):
        for command, at in todo if attempt == 1 else retry:
            outcome, text = run_command(command, at, scratch, have_shared, have_torch)
            if outcome == "failed" and attempt == 1:
                retry.append((command, at))
                print("again later: " + text.splitlines()[0], flush=True)
            elif outcome == "failed":
                failures.append(text)
                print("FAIL: " + text, flush=True)
            else:
                ran += outcome == "ok"
                print("%s: %s" % (outcome, text), flush=True)
    if ran == 0 and not failures:
        failures.append("no README command ran")
    for f in failures:
        print("FAIL: " + f, file=sys.stderr)
    print("%d README commands ran, %d failure(s)" % (ran, len(failures)))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
