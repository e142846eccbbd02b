#!/usr/bin/env python3
"""Deterministic inputs for the golden-output tests (tests/<area>/golden_test.sh).

Written with the standard library only (wave + a fixed linear congruential generator), so the
bytes do not depend on numpy's generators or on any tsrir code: speech-like recordings, noises,
RIRs (exponentially decaying noise behind a direct impulse), Kaldi data dirs, rir/noise lists and
scps, and a room table for rir-room-list. Usage: make_inputs.py <dir>
"""
import math
import os
import struct
import sys
import wave


class Lcg:
    """Numerical Recipes' 32-bit LCG: the same numbers on every machine and Python version."""

    def __init__(self, seed):
        self.state = (seed * 2654435761 + 12345) & 0xFFFFFFFF

    def uniform(self):
        self.state = (1664525 * self.state + 1013904223) & 0xFFFFFFFF
        return self.state / 4294967296.0

    def noise(self):
        return 2.0 * self.uniform() - 1.0


def write_wav(path, samples, rate):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    frames = b"".join(struct.pack("<h", max(-32768, min(32767, int(round(s * 32767))))) for s in samples)
    with wave.open(path, "wb") as w:
        w.setnchannels(1)
        w.setsampwidth(2)
        w.setframerate(rate)
        w.writeframes(frames)


def speech_like(seconds, rate, seed):
    rng = Lcg(seed)
    n = int(seconds * rate)
    f0 = 110.0 + 40.0 * rng.uniform()
    out = []
    for i in range(n):
        t = i / rate
        envelope = 0.5 * (1.0 - math.cos(2.0 * math.pi * 3.0 * t)) * min(1.0, t * 20.0)
        voiced = sum(math.sin(2.0 * math.pi * f0 * k * t) / k for k in range(1, 6))
        out.append(0.2 * envelope * voiced + 0.01 * rng.noise())
    return out


def noise(seconds, rate, seed, level=0.3):
    rng = Lcg(seed)
    return [level * rng.noise() for _ in range(int(seconds * rate))]


def rir(seconds, rate, seed, t60_s, delay_samples):
    rng = Lcg(seed)
    n = int(seconds * rate)
    out = [0.0] * n
    out[delay_samples] = 0.9
    decay = 6.9078 / (t60_s * rate)  # amplitude e^(-decay n): -60 dB at t60
    for i in range(delay_samples + 1, n):
        out[i] = 0.25 * rng.noise() * math.exp(-decay * (i - delay_samples))
    return out


def write_text(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(text)


def main(root):
    # Recordings: three 8 kHz utterances of two speakers (small golden wavs); u3 is read through a pipe.
    lengths = {"spkA-u1": 0.5, "spkA-u2": 0.8, "spkB-u3": 1.1}
    wav_scp, utt2spk, text = [], [], []
    for k, (utt, seconds) in enumerate(sorted(lengths.items())):
        write_wav(f"{root}/audio/{utt}.wav", speech_like(seconds, 8000, 100 + k), 8000)
        rx = f"cat audio/{utt}.wav |" if utt == "spkB-u3" else f"audio/{utt}.wav"
        wav_scp.append(f"{utt} {rx}")
        utt2spk.append(f"{utt} {utt.split('-')[0]}")
        text.append(f"{utt} HELLO WORLD {k}")
    write_text(f"{root}/in/wav.scp", "\n".join(wav_scp) + "\n")
    write_text(f"{root}/in/utt2spk", "\n".join(utt2spk) + "\n")
    write_text(f"{root}/in/text", "\n".join(text) + "\n")
    write_text(f"{root}/in/reco2dur", "spkA-u1 0.5\n")
    # A data dir with segments and the optional tables that are renamed per copy.
    write_wav(f"{root}/audio/rec1.wav", speech_like(1.3, 8000, 200), 8000)
    write_text(f"{root}/in_seg/wav.scp", "rec1 audio/rec1.wav\n")
    write_text(f"{root}/in_seg/segments", "rec1-a rec1 0.00 0.60\nrec1-b rec1 0.70 1.25\n")
    write_text(f"{root}/in_seg/utt2spk", "rec1-a spk1\nrec1-b spk1\n")
    write_text(f"{root}/in_seg/reco2file_and_channel", "rec1 rec1 A\n")
    write_text(f"{root}/in_seg/vad.scp", "rec1 vad/rec1.ark:7\n")

    # RIRs: room A (two 8 kHz), room B (one 16 kHz: resampled to the speech's rate).
    write_wav(f"{root}/rirs/a1.wav", rir(0.25, 8000, 11, 0.3, 10), 8000)
    write_wav(f"{root}/rirs/a2.wav", rir(0.30, 8000, 12, 0.5, 18), 8000)
    write_wav(f"{root}/rirs/b1.wav", rir(0.25, 16000, 13, 0.2, 20), 16000)
    write_text(f"{root}/lists/rir_list_a",
               "--rir-id a1 --room-id roomA rirs/a1.wav\n--rir-id a2 --room-id roomA rirs/a2.wav\n")
    write_text(f"{root}/lists/rir_list_b", "--rir-id b1 --room-id roomB rirs/b1.wav\n")
    write_text(f"{root}/lists/rir.scp", "a1 rirs/a1.wav\na2 rirs/a2.wav\n")

    # Noises: an isotropic one of room A, a background and a short foreground point source.
    write_wav(f"{root}/noise/iso_a.wav", noise(2.0, 8000, 21), 8000)
    write_wav(f"{root}/noise/ps_bg.wav", noise(0.7, 8000, 22), 8000)
    write_wav(f"{root}/noise/fg_short.wav", noise(0.2, 8000, 23, 0.5), 8000)
    write_text(f"{root}/lists/noise_list",
               "--noise-id iso_a --noise-type isotropic --room-linkage roomA noise/iso_a.wav\n"
               "--noise-id ps_bg --noise-type point-source --bg-fg-type background noise/ps_bg.wav\n"
               "--noise-id fg_short --noise-type point-source --bg-fg-type foreground noise/fg_short.wav\n")
    write_text(f"{root}/lists/noise.scp", "n_bg noise/ps_bg.wav\nn_iso noise/iso_a.wav\n")

    # RIR sets for rir-eq and rir-metrics: "real" (32, enough for a two-component mixture of the
    # seven gains; varied decays) and "sim" (four).
    real, sim = [], []
    for k in range(32):
        write_wav(f"{root}/real/r{k:02d}.wav", rir(0.4, 16000, 40 + k, 0.2 + 0.015 * k, 16 + k), 16000)
        real.append(f"r{k:02d} real/r{k:02d}.wav")
    for k in range(4):
        write_wav(f"{root}/sim/s{k}.wav", rir(0.15, 16000, 60 + k, 0.1 + 0.02 * k, 24 + 5 * k), 16000)
        sim.append(f"s{k} sim/s{k}.wav")
    write_text(f"{root}/real/rir.scp", "\n".join(real) + "\n")
    write_text(f"{root}/sim/rir.scp", "\n".join(sim) + "\n")

    # Rooms for rir-simulate and rir-room-list.
    write_text(f"{root}/rooms.txt",
               "r1 room=6,4.5,3 src=2,1.5,1.6 mic=4,3,1.2 t60=0.4\n"
               "r2 room=5,4,2.7 src=1,1,1.5 mic=3.5,2.5,1.4 absorption=0.3 room-id=small\n"
               "r3 room=8,6,3.2 src=2,2,1.7 mic=6,4.5,1.3 t60=0.7 scattering=0.2\n")
    write_text(f"{root}/room_table.txt",
               "rir-id Lx Ly Lz sx sy sz mx my mz room-id\n"
               "t1 6 4.5 3 2 1.5 1.6 4 3 1.2 roomT\n"
               "t2 6 4.5 3 1 1 1.5 5 3.5 1.4 roomT\n"
               "t3 5 4 2.7 1 2 1.5 3.5 2.5 1.4 roomU\n")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: make_inputs.py <dir>")
    main(sys.argv[1])
