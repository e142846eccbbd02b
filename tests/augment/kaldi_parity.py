#!/usr/bin/env python3
"""Helpers of kaldi_parity_test.sh (standard library only).

  make-inputs DIR            int16 RIRs in three rooms, noises, RIR/noise lists, a 2,500-recording
                             data dir with reco2dur (data/big) and a 12-recording one without (data/small)
  compare KALDI_DIR OURS_DIR DATA_DIR
                             the output structure (files, ids) and the statistics of the random
                             choices read back from both wav.scp files, within sampling error
  wav-diff A.wav B.wav       the largest sample difference in LSB (int16), printed (any channel count)
  delta-check IN.wav OUT.wav GAIN
                             OUT against the exact answer for a one-tap RIR (IN * GAIN), in LSB
"""
import math
import os
import random
import shlex
import struct
import sys
import wave

# Rooms and RIRs: list A (weight 0.7): room1 r1a (probability 0.5), r1b; room2 r2a. List B: room3 r3a, r3b.
RIR_LIST_A = [("r1a", "room1", 0.5), ("r1b", "room1", None), ("r2a", "room2", None)]
RIR_LIST_B = [("r3a", "room3", None), ("r3b", "room3", None)]
# Noises: list 1 (weight 0.6): isotropic i1 (room1), i1b (room1, probability 0.3), point-source
# background pb1, foreground pf1; list 2: foreground pf2, isotropic i3 (room3).
NOISE_LIST_1 = [("i1", "isotropic", "background", "room1", None), ("i1b", "isotropic", "background", "room1", 0.3),
                ("pb1", "point-source", "background", None, None), ("pf1", "point-source", "foreground", None, 0.4)]
NOISE_LIST_2 = [("pf2", "point-source", "foreground", None, None), ("i3", "isotropic", "background", "room3", None)]
FG_SNRS = [20.0, 10.0, 15.0, 5.0, 0.0]
BG_SNRS = [20.0, 10.0, 0.0]
MAX_NOISES_PER_MINUTE = 3


def write_wav(path, samples, rate=16000):
    with wave.open(path, "wb") as w:
        w.setnchannels(1)
        w.setsampwidth(2)
        w.setframerate(rate)
        w.writeframes(b"".join(struct.pack("<h", max(-32768, min(32767, int(round(s))))) for s in samples))


def read_wav(path):
    with wave.open(path, "rb") as w:
        assert w.getsampwidth() == 2, path
        n = w.getnframes() * w.getnchannels()
        return list(struct.unpack("<%dh" % n, w.readframes(w.getnframes())))


def rir(seed, rate=16000, t60=0.4, delay=40):
    rng = random.Random(seed)
    n = int(0.35 * rate)
    out = [0.0] * n
    out[delay] = 20000.0
    for i in range(delay + 1, n):
        out[i] = rng.gauss(0, 1) * 6000.0 * math.exp(-6.9 * (i - delay) / (t60 * rate))
    return out


def speech_like(seconds, seed, rate=16000):
    rng = random.Random(seed)
    out = []
    for i in range(int(seconds * rate)):
        envelope = 0.5 + 0.5 * math.sin(2 * math.pi * 3.1 * i / rate)
        out.append(envelope * (4000 * math.sin(2 * math.pi * 220 * i / rate) + 1500 * rng.gauss(0, 1)))
    return out


def make_inputs(d):
    for sub in ("rirs", "noises", "audio", "data/big", "data/small"):
        os.makedirs(os.path.join(d, sub), exist_ok=True)
    for k, (rid, room, _) in enumerate(RIR_LIST_A + RIR_LIST_B):
        write_wav(os.path.join(d, "rirs", rid + ".wav"), rir(k, t60=0.3 + 0.1 * k, delay=30 + 7 * k))
    for name, entries in (("listA", RIR_LIST_A), ("listB", RIR_LIST_B)):
        with open(os.path.join(d, "rirs", name), "w") as f:
            for rid, room, p in entries:
                f.write("--rir-id %s --room-id %s%s rirs/%s.wav\n" % (rid, room, " --probability %g" % p if p else "", rid))
    rng = random.Random(3)
    for k, (nid, *_rest) in enumerate(NOISE_LIST_1 + NOISE_LIST_2):
        write_wav(os.path.join(d, "noises", nid + ".wav"), [rng.gauss(0, 2000) for _ in range(int(16000 * (0.7 + 0.4 * k)))])
    for name, entries in (("list1", NOISE_LIST_1), ("list2", NOISE_LIST_2)):
        with open(os.path.join(d, "noises", name), "w") as f:
            for nid, ntype, bgfg, room, p in entries:
                f.write("--noise-id %s --noise-type %s --bg-fg-type %s%s%s noises/%s.wav\n" %
                        (nid, ntype, bgfg, " --room-linkage " + room if room else "", " --probability %g" % p if p else "", nid))
    # data/big: durations only matter (both programs read reco2dur); one short file stands in.
    write_wav(os.path.join(d, "audio", "stand_in.wav"), speech_like(1.0, 1))
    rng = random.Random(5)
    with open(os.path.join(d, "data/big/wav.scp"), "w") as w, open(os.path.join(d, "data/big/utt2spk"), "w") as u, \
            open(os.path.join(d, "data/big/reco2dur"), "w") as r:
        for utt, i in sorted(("spk%03d-utt%05d" % (i % 50, i), i) for i in range(2500)):
            w.write("%s %s\n" % (utt, os.path.join(d, "audio", "stand_in.wav")))
            u.write("%s spk%03d\n" % (utt, i % 50))
            r.write("%s %.2f\n" % (utt, rng.uniform(5.0, 150.0)))
    # data/small: real audio of 1.5-25 s, no reco2dur (Kaldi's script calls get_reco2dur.sh).
    utts = sorted(("s%d-u%02d" % (i % 3, i), i) for i in range(12))  # Kaldi wants sorted tables
    with open(os.path.join(d, "data/small/wav.scp"), "w") as w, open(os.path.join(d, "data/small/utt2spk"), "w") as u:
        for utt, i in utts:
            path = os.path.join(d, "audio", utt + ".wav")
            write_wav(path, speech_like(1.5 + 2.0 * i, 10 + i))
            w.write("%s %s\n" % (utt, path))
            u.write("%s s%d\n" % (utt, i % 3))


def positional_and_options(words):
    """Options (--name=value) and positionals of one wav-reverberate invocation."""
    opts, pos = {}, []
    for w in words:
        if w.startswith("--") and "=" in w:
            k, v = w[2:].split("=", 1)
            opts[k] = v
        else:
            pos.append(w)
    return opts, pos


def parse_pipe(line):
    """(speech RIR id or None, [(noise id, rir id or None, duration or None, start, snr)])."""
    words = shlex.split(line)
    idx = [i for i, w in enumerate(words) if w.endswith("wav-reverberate")]
    if not idx:
        return None
    opts, _ = positional_and_options(words[idx[-1] + 1:])
    base = lambda p: os.path.splitext(os.path.basename(p))[0]
    speech_rir = base(opts["impulse-response"]) if "impulse-response" in opts else None
    noises = []
    if "additive-signals" in opts:
        signals = opts["additive-signals"].split(",")
        starts = [float(x) for x in opts["start-times"].split(",")]
        snrs = [float(x) for x in opts["snrs"].split(",")]
        assert len(signals) == len(starts) == len(snrs), line
        # tsrir's own form does Kaldi's nested step in the outer process: one field per signal in
        # --additive-impulse-responses (empty = none) and --additive-durations (0 = as is).
        in_rirs = opts.get("additive-impulse-responses", "").split(",") if "additive-impulse-responses" in opts else None
        in_durs = opts.get("additive-durations", "").split(",") if "additive-durations" in opts else None
        for i, (sig, start, snr) in enumerate(zip(signals, starts, snrs)):
            sw = shlex.split(sig)
            j = [i for i, w in enumerate(sw) if w.endswith("wav-reverberate")]
            if j:
                nopts, npos = positional_and_options(sw[j[0] + 1:])
                noise = [p for p in npos if p not in ("-", "|")][0]
                noises.append((base(noise), base(nopts["impulse-response"]) if "impulse-response" in nopts else None,
                               float(nopts["duration"]) if "duration" in nopts else None, start, snr))
            else:
                rir = base(in_rirs[i]) if in_rirs and in_rirs[i] else None
                dur = float(in_durs[i]) if in_durs and in_durs[i] and float(in_durs[i]) > 0 else None
                noises.append((base(sw[0]), rir, dur, start, snr))
    return speech_rir, noises


def read_table(path):
    out = {}
    with open(path) as f:
        for line in f:
            if line.strip():
                k, _, v = line.strip().partition(" ")
                out[k] = v.strip()
    return out


class Checker:
    def __init__(self):
        self.failures = 0
        self.rows = []

    def close(self, what, a, b, sd, z=4.5):
        ok = abs(a - b) <= z * sd + 1e-12
        self.rows.append("%-58s kaldi %9.4f  tsrir %9.4f  |diff| %.4f <= %.4f  %s" % (what, a, b, abs(a - b), z * sd, "ok" if ok else "FAIL"))
        self.failures += not ok

    def proportion(self, what, ka, kn, oa, on):
        p1, p2 = ka / max(kn, 1), oa / max(on, 1)
        p = (ka + oa) / max(kn + on, 1)
        self.close(what, p1, p2, math.sqrt(max(p * (1 - p), 1e-9) * (1 / max(kn, 1) + 1 / max(on, 1))))

    def exact(self, what, ok, detail=""):
        self.rows.append("%-58s %s %s" % (what, "ok" if ok else "FAIL", detail))
        self.failures += not ok


def statistics(out_dir, durations):
    rooms = {rid: room for rid, room, _ in RIR_LIST_A + RIR_LIST_B}
    noise_type = {n[0]: (n[1], n[2]) for n in NOISE_LIST_1 + NOISE_LIST_2}
    s = {"n": 0, "rvb": 0, "rir": {}, "room_noise": {}, "iso": 0, "iso_id": {}, "ps_added": 0, "ps_count": {},
         "ps_eligible": 0, "ps_id": {}, "fg_pos": [], "bg_snr": [], "fg_snr": [], "same_room": True, "ps_rir": True,
         "iso_ok": True, "bg_shape": True, "noises_per_min": 0.0, "copy0_original": True}
    wav = read_table(os.path.join(out_dir, "wav.scp"))
    for key in sorted(wav):
        copy, _, orig = key.partition("-")
        if copy == "rvb0":
            s["copy0_original"] &= "wav-reverberate" not in wav[key]
            continue
        dur = durations[orig]
        parsed = parse_pipe(wav[key]) or (None, [])
        speech_rir, noises = parsed
        s["n"] += 1
        s["rvb"] += speech_rir is not None
        s["rir"][speech_rir] = s["rir"].get(speech_rir, 0) + 1
        room = rooms.get(speech_rir)
        isos = [n for n in noises if noise_type[n[0]][0] == "isotropic"]
        pss = [n for n in noises if noise_type[n[0]][0] == "point-source"]
        s["iso"] += len(isos) > 0
        s["iso_ok"] &= len(isos) <= 1 and all(n[1] is None and n[2] is not None and n[3] == 0 for n in isos)
        for n in isos:
            s["iso_id"][n[0]] = s["iso_id"].get(n[0], 0) + 1
            s["bg_snr"].append(n[4])
            if room is not None:
                s["same_room"] &= {"i1": "room1", "i1b": "room1", "i3": "room3"}[n[0]] == room
        max_n = int(math.floor(MAX_NOISES_PER_MINUTE * dur / 60))
        if max_n >= 1:
            s["ps_eligible"] += 1
            s["ps_added"] += len(pss) > 0
            if pss:
                s["ps_count"][(max_n, len(pss))] = s["ps_count"].get((max_n, len(pss)), 0) + 1
        else:
            s["bg_shape"] &= not pss
        s["noises_per_min"] += len(pss) / dur * 60
        ps_rooms = set()
        for n in pss:
            s["ps_id"][n[0]] = s["ps_id"].get(n[0], 0) + 1
            s["ps_rir"] &= n[1] is not None
            ps_rooms.add(rooms.get(n[1]))
            if noise_type[n[0]][1] == "foreground":
                s["bg_shape"] &= n[2] is None
                s["fg_pos"].append(n[3] / dur)
                s["fg_snr"].append(n[4])
            else:
                s["bg_shape"] &= n[2] is not None and n[3] == 0
                s["bg_snr"].append(n[4])
        if room is not None and ps_rooms:
            s["same_room"] &= ps_rooms == {room}
        s["same_room"] &= len(ps_rooms) <= 1
    return s


def cyclic(sequence, period):
    return all(sequence[i] == sequence[i - period] for i in range(period, len(sequence)))


def compare(kaldi_dir, ours_dir, data_dir):
    c = Checker()
    # Output structure: the same files (ours adds reco2dur) and the same ids in each.
    kf = set(os.listdir(kaldi_dir)) - {"log", ".backup"}
    # Besides reco2dur, ours holds the marker that says tsrir wrote it (src/io/owned_output.h).
    of = set(os.listdir(ours_dir)) - {"reco2dur", ".tsrir-output", ".tsrir-owned"}
    c.exact("same files (besides our reco2dur)", kf == of, "kaldi %s tsrir %s" % (sorted(kf), sorted(of)))
    for name in sorted(kf & of):
        if os.path.isfile(os.path.join(kaldi_dir, name)):
            kt, ot = read_table(os.path.join(kaldi_dir, name)), read_table(os.path.join(ours_dir, name))
            c.exact("%s: same ids" % name, set(kt) == set(ot), "(%d / %d)" % (len(kt), len(ot)))
            if name != "wav.scp":
                c.exact("%s: same contents" % name, kt == ot)
    durations = {k: float(v) for k, v in read_table(os.path.join(data_dir, "reco2dur")).items()}
    k, o = statistics(kaldi_dir, durations), statistics(ours_dir, durations)
    c.exact("recordings compared", k["n"] == o["n"] and k["n"] >= 2000, "%d / %d" % (k["n"], o["n"]))
    for name, st in (("kaldi", k), ("tsrir", o)):
        c.exact(name + ": copy 0 is the original", st["copy0_original"])
        c.exact(name + ": noise RIRs from the speech's room", st["same_room"])
        c.exact(name + ": every point source through an RIR", st["ps_rir"])
        c.exact(name + ": isotropic: <= 1, no RIR, extended, at 0", st["iso_ok"])
        c.exact(name + ": background extended from 0, foreground not", st["bg_shape"])
        c.exact(name + ": background SNRs cyclic (period %d)" % len(BG_SNRS), cyclic(st["bg_snr"], len(BG_SNRS)))
        c.exact(name + ": foreground SNRs cyclic (period %d)" % len(FG_SNRS), cyclic(st["fg_snr"], len(FG_SNRS)))
        c.exact(name + ": SNR values are the lists'", set(st["bg_snr"]) <= set(BG_SNRS) and set(st["fg_snr"]) <= set(FG_SNRS))
    n = k["n"]
    c.proportion("speech reverberated", k["rvb"], n, o["rvb"], n)
    for r in sorted(set(k["rir"]) | set(o["rir"]), key=str):
        c.proportion("speech RIR %s" % r, k["rir"].get(r, 0), n, o["rir"].get(r, 0), n)
    c.proportion("isotropic noise added", k["iso"], n, o["iso"], n)
    for i in ("i1", "i1b", "i3"):
        c.proportion("isotropic noise %s (of those added)" % i, k["iso_id"].get(i, 0), k["iso"], o["iso_id"].get(i, 0), o["iso"])
    c.proportion("point sources added (N >= 1)", k["ps_added"], k["ps_eligible"], o["ps_added"], o["ps_eligible"])
    kps, ops = sum(k["ps_id"].values()), sum(o["ps_id"].values())
    for i in ("pb1", "pf1", "pf2"):
        c.proportion("point source %s" % i, k["ps_id"].get(i, 0), kps, o["ps_id"].get(i, 0), ops)
    for max_n in sorted({m for m, _ in k["ps_count"]}):
        kt = sum(v for (m, _), v in k["ps_count"].items() if m == max_n)
        ot = sum(v for (m, _), v in o["ps_count"].items() if m == max_n)
        for cnt in range(1, max_n + 1):
            c.proportion("N=%d: %d point sources" % (max_n, cnt), k["ps_count"].get((max_n, cnt), 0), kt,
                         o["ps_count"].get((max_n, cnt), 0), ot)
    c.close("point-source noises per minute (mean)", k["noises_per_min"] / n, o["noises_per_min"] / n,
            math.sqrt(2.0 / n) * 1.2)  # per-recording sd <= ~1.2 noises/min here
    for lo in (0.0, 0.25, 0.5, 0.75):
        kc = sum(lo <= x < lo + 0.25 for x in k["fg_pos"])
        oc = sum(lo <= x < lo + 0.25 for x in o["fg_pos"])
        c.proportion("foreground start in [%.2f, %.2f) of the recording" % (lo, lo + 0.25), kc, len(k["fg_pos"]), oc, len(o["fg_pos"]))
    for v in BG_SNRS:
        c.proportion("background SNR %g" % v, k["bg_snr"].count(v), len(k["bg_snr"]), o["bg_snr"].count(v), len(o["bg_snr"]))
    print("\n".join(c.rows))
    print("parity: %d checks, %d failed" % (len(c.rows), c.failures))
    return 1 if c.failures else 0


def wav_channels(path):
    with wave.open(path, "rb") as w:
        return w.getnchannels()


def wav_diff(a, b):
    x, y = read_wav(a), read_wav(b)
    if wav_channels(a) != wav_channels(b):
        print("channels %d vs %d" % (wav_channels(a), wav_channels(b)))
        return 1
    if len(x) != len(y):
        print("length %d vs %d" % (len(x), len(y)))
        return 1
    d = max((abs(p - q) for p, q in zip(x, y)), default=0)
    rms = math.sqrt(sum((p - q) ** 2 for p, q in zip(x, y)) / max(len(x), 1))
    print("%d %.3f %d" % (d, rms, len(x)))
    return 0


def delta_check(inp, out, gain):
    x, y = read_wav(inp), read_wav(out)
    if len(x) != len(y):
        print("length %d vs %d" % (len(x), len(y)))
        return 1
    print("%.1f" % max(abs(b - a * gain) for a, b in zip(x, y)))
    return 0


if __name__ == "__main__":
    cmd = sys.argv[1]
    if cmd == "make-inputs":
        make_inputs(sys.argv[2])
    elif cmd == "compare":
        sys.exit(compare(sys.argv[2], sys.argv[3], sys.argv[4]))
    elif cmd == "delta-check":
        sys.exit(delta_check(sys.argv[2], sys.argv[3], float(sys.argv[4])))
    elif cmd == "wav-diff":
        sys.exit(wav_diff(sys.argv[2], sys.argv[3]))
    else:
        sys.exit("unknown command " + cmd)
