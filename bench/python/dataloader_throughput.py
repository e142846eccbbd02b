#!/usr/bin/env python3
"""Throughput of on-the-fly far-field augmentation (tsrir.data.FarFieldDataset in a torch
DataLoader) against reading the same copies pre-written by reverberate-data --write-wavs.

  PYTHONPATH=build/python python3 bench/python/dataloader_throughput.py [--build-dir build]
      [--recordings 100] [--rooms 50]

Speech: the LibriSpeech utterances of ../shared/data/speech/librispeech (read in place, listed
under several recording ids), else generated speech-like signals. RIRs: rir-simulate, --rooms
random shoebox rooms (gas model, length auto). Noise: three real recordings of
../shared/data/noise (44.1 kHz Ogg, resampled by the loader), else generated noise; SNRs and noise rules: reverberate-data's defaults.
Prints a table: utterances/s per core (CPU time of the process doing the work) for
  - reverberate-data --write-wavs --num-threads=1 (writing the copies),
  - reading those wavs in a DataLoader (num_workers=0),
  - on-the-fly in a DataLoader (num_workers=0), first epoch (caches cold) and next epoch (warm),
and the wall-clock rate with 4 workers (next epoch). Say the machine load (uptime) beside the figures.
"""
import argparse
import glob
import os
import random
import resource
import shutil
import subprocess
import sys
import tempfile
import time

import numpy as np
import torch

import tsrir
from tsrir.data import FarFieldDataset

HERE = os.path.dirname(os.path.abspath(__file__))
SHARED = os.path.normpath(os.path.join(HERE, "..", "..", "..", "shared", "data"))


def children_cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def make_inputs(d, build, recordings, rooms, rng):
    speech_files = sorted(glob.glob(os.path.join(SHARED, "speech", "librispeech", "*.wav")) +
                          glob.glob(os.path.join(SHARED, "speech", "librispeech", "*.flac")))
    os.makedirs(d + "/in")
    if speech_files:
        source = "LibriSpeech utterances of ../shared/data (%d files)" % len(speech_files)
    else:
        source = "generated speech-like signals"
        speech_files = []
        for k in range(5):
            path = "%s/gen%d.wav" % (d, k)
            t = np.arange(int(12 * 16000)) / 16000
            x = 0.1 * np.sin(2 * np.pi * 120 * t) * (1 + np.sin(2 * np.pi * 4 * t)) + 0.01 * rng.standard_normal(len(t))
            tsrir.write_wav(path, x.astype(np.float32), 16000)
            speech_files.append(path)
    with open(d + "/in/wav.scp", "w") as scp, open(d + "/in/utt2spk", "w") as u2s:
        for i in range(recordings):
            rid = "spk%02d-utt%04d" % (i % 10, i)
            scp.write("%s %s\n" % (rid, speech_files[i % len(speech_files)]))
            u2s.write("%s spk%02d\n" % (rid, i % 10))
    lines = []
    for i in range(rooms):
        L = [rng.uniform(3, 10), rng.uniform(3, 8), rng.uniform(2.4, 4)]
        src = [rng.uniform(0.5, v - 0.5) for v in L]
        mic = [rng.uniform(0.5, v - 0.5) for v in L]
        lines.append("room%03d room=%.3f,%.3f,%.3f src=%.3f,%.3f,%.3f mic=%.3f,%.3f,%.3f t60=%.3f\n"
                     % tuple([i] + L + src + mic + [rng.uniform(0.25, 0.9)]))
    with open(d + "/rooms.txt", "w") as f:
        f.writelines(lines)
    subprocess.run([os.path.join(build, "bin", "rir-simulate"), "--length=auto", "--seed=1", d + "/rooms.txt",
                    d + "/rirs"], check=True, stderr=subprocess.DEVNULL)
    noise_files = [os.path.join(SHARED, "noise", n) for n in ("coffee-shop.ogg", "city.ogg", "rain.ogg")]
    noise_files = [n for n in noise_files if os.path.exists(n)]
    if not noise_files:
        path = d + "/noise.wav"
        tsrir.write_wav(path, (0.1 * rng.standard_normal(10 * 16000)).astype(np.float32), 16000)
        noise_files = [path]
    with open(d + "/noise_list", "w") as f:
        for k, n in enumerate(noise_files):
            f.write("--noise-id n%d --noise-type point-source %s\n" % (k, n))
    return source, noise_files


class ReadWavs(torch.utils.data.Dataset):
    def __init__(self, data_dir):
        with open(os.path.join(data_dir, "wav.scp")) as f:
            self.recordings = [line.strip().split(None, 1) for line in f if line.strip()]

    def __len__(self):
        return len(self.recordings)

    def __getitem__(self, i):
        x, fs = tsrir.read_audio(self.recordings[i][1])
        return torch.from_numpy(x[0])


def one_thread(_):
    torch.set_num_threads(1)


def drain(dataset, workers):
    loader = torch.utils.data.DataLoader(dataset, batch_size=None, num_workers=workers, worker_init_fn=one_thread)
    n, audio = 0, 0
    for item in loader:
        n += 1
        audio += len(item["audio"] if isinstance(item, dict) else item)
    return n, audio


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--build-dir", default=os.path.join(HERE, "..", "..", "build"))
    p.add_argument("--recordings", type=int, default=100)
    p.add_argument("--rooms", type=int, default=50)
    p.add_argument("--workers", type=int, default=4)
    args = p.parse_args()
    torch.set_num_threads(1)
    rng = random.Random(1)
    d = tempfile.mkdtemp(prefix="tsrir_bench_dl_")
    try:
        source, noises = make_inputs(d, os.path.abspath(args.build_dir), args.recordings, args.rooms, rng)
        opts = dict(rir_set_parameters=[d + "/rirs/rir_list"], noise_set_parameters=[d + "/noise_list"],
                    seed=7, prefix="rvb")
        rows = []
        cpu0, t0 = children_cpu(), time.time()
        subprocess.run([os.path.join(args.build_dir, "bin", "reverberate-data"), "--rir-set-parameters=" + opts["rir_set_parameters"][0],
                        "--noise-set-parameters=" + opts["noise_set_parameters"][0], "--random-seed=7",
                        "--num-threads=1", "--write-wavs=" + d + "/wavs", d + "/in", d + "/out"],
                       check=True, stderr=subprocess.DEVNULL)
        cpu, wall = children_cpu() - cpu0, time.time() - t0
        rows.append(("reverberate-data --write-wavs, 1 thread (writes the copies)", args.recordings / cpu, args.recordings / wall))

        c0, t0 = time.process_time(), time.time()
        n, audio = drain(ReadWavs(d + "/out"), 0)
        cpu, wall = time.process_time() - c0, time.time() - t0
        audio_s = audio / 16000
        rows.append(("DataLoader reading the pre-written wavs, num_workers=0", n / cpu, n / wall))

        aug = tsrir.Augmenter(data_dir=d + "/in", **opts)
        dataset = FarFieldDataset(aug)
        # Epoch 0 fills the load-once caches (every RIR and noise read, resampled and prepared
        # once); later epochs (new draws: copy 2, 3, ...) find them warm, and forked workers
        # inherit them.
        c0, t0 = time.process_time(), time.time()
        n, _ = drain(dataset, 0)
        cpu, wall = time.process_time() - c0, time.time() - t0
        rows.append(("on the fly (tsrir.data.FarFieldDataset), num_workers=0, first epoch", n / cpu, n / wall))
        dataset.set_epoch(1)
        c0, t0 = time.process_time(), time.time()
        n, _ = drain(dataset, 0)
        cpu, wall = time.process_time() - c0, time.time() - t0
        rows.append(("on the fly, num_workers=0, next epoch (caches warm)", n / cpu, n / wall))
        dataset.set_epoch(2)
        t0 = time.time()
        n, _ = drain(dataset, args.workers)
        wall = time.time() - t0
        rows.append(("on the fly, num_workers=%d, next epoch (wall only)" % args.workers, float("nan"), n / wall))

        print("# %d recordings (%.0f s of audio; %s), %d simulated rooms, %d noises, SNRs and noise rules: reverberate-data's defaults"
              % (args.recordings, audio_s, source, args.rooms, len(noises)))
        print("# load: %s" % open("/proc/loadavg").read().strip())
        print("| run | utterances/s per core (CPU time) | utterances/s wall |")
        print("|---|---|---|")
        for name, per_core, per_wall in rows:
            print("| %s | %s | %.1f |" % (name, "-" if per_core != per_core else "%.1f" % per_core, per_wall))
    finally:
        shutil.rmtree(d, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
