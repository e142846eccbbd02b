"""Runs the Python example of README.md's "From Python" section (its ```python block, verbatim)
in a directory holding what it reads: speech.wav, noise.wav and an RIR set rirs/ written by
rir-simulate. Checks what it prints and writes."""
import os
import re
import shutil
import subprocess
import sys
import unittest

from tsrir_testlib import np, program, read_wav16, run, speech_like, temp_dir, write_text, write_wav16
import tsrir

SOURCE = os.environ.get("TSRIR_SOURCE_DIR", os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))


def readme_python_block():
    with open(os.path.join(SOURCE, "README.md")) as f:
        text = f.read()
    section = text.split("## From Python", 1)[1].split("\n## ", 1)[0]
    m = re.search(r"```python\n(.*?)```", section, re.S)
    if not m:
        raise AssertionError("README.md: no ```python block in the 'From Python' section")
    return m.group(1)


class ReadmeExample(unittest.TestCase):
    def test_example_runs(self):
        d = temp_dir("readme")
        try:
            write_wav16(d + "/speech.wav", speech_like(3 * 16000, 16000, 1), 16000)
            write_wav16(d + "/noise.wav", 0.2 * np.random.default_rng(2).standard_normal(16000), 16000)
            write_text(d + "/rooms.txt", "r1 room=5,4,3 src=1,1,1.5 mic=3,2.5,1.2 t60=0.5\n"
                                         "r2 room=8,6,3 src=2,2,1.5 mic=6,4,1.2 t60=0.8\n")
            run([program("rir-simulate"), "--length=auto", d + "/rooms.txt", d + "/rirs"])
            write_text(d + "/example.py", readme_python_block())
            # The package this test imported (README: PYTHONPATH=build/python).
            env = dict(os.environ, PYTHONPATH=os.path.dirname(os.path.dirname(os.path.abspath(tsrir.__file__))))
            r = subprocess.run([sys.executable, "example.py"], cwd=d, stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True, timeout=120, env=env)
            self.assertEqual(r.returncode, 0, r.stderr)
            m = re.search(r"T60 ([0-9.]+) s  DRR (-?[0-9.]+) dB  C50 (-?[0-9.]+) dB", r.stdout)
            self.assertIsNotNone(m, r.stdout)
            self.assertTrue(0.45 < float(m.group(1)) < 0.75, m.group(0))  # asked for 0.6 s
            self.assertIn("'new_id': 'rvb1-utt1'", r.stdout)
            self.assertRegex(r.stdout, r"'rir_id': 'r[12]'")
            with open(d + "/rir_list_from_lhotse") as f:
                self.assertEqual(len(f.read().splitlines()), 2)
            self.assertTrue(os.path.exists(d + "/lhotse_rirs/cuts.jsonl"))
            far, fs = read_wav16(d + "/far.wav")
            self.assertEqual((far.shape, fs), ((1, 3 * 16000), 16000))
        finally:
            shutil.rmtree(d, ignore_errors=True)


if __name__ == "__main__":
    unittest.main()
