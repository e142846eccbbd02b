#!/usr/bin/env python3
"""pyroomacoustics' measure_rt60 over the RIRs of a Kaldi scp (<id> <wav path>; plain paths only).
  PYTHONPATH=$PRA_PYTHONPATH python3 pra_rt60.py rir.scp [decay_db (30)]
Prints one line per RIR "<id> <rt60 s>", then "cpu_s_per_rir=<mean process CPU s of measure_rt60>"
(file reading excluded)."""
import sys
import time

import numpy as np
import scipy.io.wavfile
from pyroomacoustics.experimental import measure_rt60

decay = float(sys.argv[2]) if len(sys.argv) > 2 else 30.0
rirs = []
with open(sys.argv[1]) as f:
    for line in f:
        rid, path = line.split()[:2]
        fs, h = scipy.io.wavfile.read(path)
        rirs.append((rid, fs, np.asarray(h, dtype=np.float64)))
out, c0 = [], time.process_time()
for rid, fs, h in rirs:
    out.append((rid, measure_rt60(h, fs=fs, decay_db=decay)))
cpu = time.process_time() - c0
for rid, t in out:
    print(rid, "%.4f" % t)
print("cpu_s_per_rir=%.6f" % (cpu / len(rirs)))
