#!/usr/bin/env python3
"""Inputs for bench/gan/cuda_check.sh, made with numpy alone (the GPU machine has neither espeak-ng
nor sox nor the measured RIRs): two RIR domains and a tiny Kaldi data dir. They exercise the
programs and time them; nothing is learned from them (the cost of a step does not depend on the
content). 16 kHz mono 16-bit WAV, so that neither libsndfile nor libsox is needed to read them.
  rirs/synthetic/*.wav  exponentially decaying noise after a direct impulse (RT60 0.3-0.9 s)
  rirs/real/*.wav       the same with early reflections, a low-passed tail and a noise floor
  asr/{train,test}/     "speech": per character a 70 ms tone whose pitch codes the letter
Usage: cuda_check_data.py <out-dir> <rirs-per-domain> <train-utts> <test-utts>"""
import os
import sys
import wave

import numpy as np

RATE = 16000


def write_wav(path, x):
    x = np.clip(x / max(1e-9, np.max(np.abs(x))) * 0.9, -1, 1)
    with wave.open(path, "wb") as w:
        w.setnchannels(1)
        w.setsampwidth(2)
        w.setframerate(RATE)
        w.writeframes((x * 32767).astype("<i2").tobytes())


def rir(rng, real):
    n = int(RATE * 0.9)
    rt60 = rng.uniform(0.3, 0.9)
    t = np.arange(n) / RATE
    delay = int(rng.uniform(0.002, 0.01) * RATE)
    tail = rng.standard_normal(n) * np.exp(-6.9 * t / rt60) * 0.3
    h = np.zeros(n)
    h[delay] = 1.0
    h[delay:] += tail[: n - delay]
    if real:
        for _ in range(6):
            h[delay + int(rng.uniform(0.002, 0.03) * RATE)] += rng.uniform(-0.6, 0.6)
        h = np.convolve(h, np.ones(4) / 4, mode="same") + rng.standard_normal(n) * 1e-3
    return h


def utterance(rng, text):
    pieces = []
    for ch in text:
        if ch == " ":
            pieces.append(np.zeros(int(0.08 * RATE)))
            continue
        f = 300.0 + 90.0 * (ord(ch) - ord("a"))
        t = np.arange(int(0.07 * RATE)) / RATE
        pieces.append(np.sin(2 * np.pi * f * t) * np.hanning(t.size))
        pieces.append(np.zeros(int(0.01 * RATE)))
    x = np.concatenate([np.zeros(int(0.1 * RATE))] + pieces + [np.zeros(int(0.1 * RATE))])
    return x + rng.standard_normal(x.size) * 0.01


def data_dir(rng, d, n, words):
    os.makedirs(os.path.join(d, "wav"), exist_ok=True)
    scp, text, u2s = [], [], []
    for i in range(n):
        utt = "spk%d-u%04d" % (i % 4, i)
        sentence = " ".join(rng.choice(words, size=rng.integers(2, 5)))
        path = os.path.join(d, "wav", utt + ".wav")
        write_wav(path, utterance(rng, sentence))
        scp.append("%s %s" % (utt, path))
        text.append("%s %s" % (utt, sentence))
        u2s.append("%s spk%d" % (utt, i % 4))
    for name, rows in (("wav.scp", scp), ("text", text), ("utt2spk", u2s)):
        with open(os.path.join(d, name), "w") as f:
            f.write("\n".join(sorted(rows)) + "\n")


def main():
    out, n_rirs, n_train, n_test = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4])
    rng = np.random.default_rng(31)
    for domain in ("synthetic", "real"):
        d = os.path.join(out, "rirs", domain)
        os.makedirs(d, exist_ok=True)
        with open(os.path.join(out, "rirs", domain + ".scp"), "w") as scp:
            for i in range(n_rirs):
                path = os.path.join(d, "%s%04d.wav" % (domain[0], i))
                write_wav(path, rir(rng, domain == "real"))
                scp.write("%s%04d %s\n" % (domain[0], i, path))
    words = ["cat", "dog", "sun", "red", "tree", "blue", "fish", "moon", "wind", "stone"]
    data_dir(rng, os.path.join(out, "asr", "train"), n_train, words)
    data_dir(rng, os.path.join(out, "asr", "test"), n_test, words)


if __name__ == "__main__":
    main()
