"""Augmenter against reverberate-data on the same data directory, lists and seed: every copy of
every recording equals the wav that reverberate-data --write-wavs writes (after the same 16-bit
encoding), and the plan equals the pipe reverberate-data writes without --write-wavs. Then the
data-loader properties: the same output in any order, in 4 forked or spawned worker processes,
and after pickling."""
import multiprocessing as mp
import os
import random
import shlex
import shutil
import subprocess
import unittest

from tsrir_testlib import (np, program, read_wav16, run, speech_like, synthetic_rir, temp_dir,
                           write_text, write_wav16)
import tsrir

FS = 16000
SEED = 11
COPIES = 2


def make_data(d):
    """A Kaldi data dir (6 recordings, one of them a pipe), two RIR sets (one RIR at 48 kHz) and a
    noise list (an isotropic noise linked to a room, an 8 kHz point source, a short one)."""
    for sub in ("audio", "rirs", "noise", "lists", "in"):
        os.makedirs(os.path.join(d, sub), exist_ok=True)
    wav_scp, utt2spk, ids = [], [], []
    k = 0
    for spk in ("spkA", "spkB"):
        for i in range(3):
            utt = "%s-u%d" % (spk, i)
            path = "%s/audio/%s.wav" % (d, utt)
            write_wav16(path, speech_like(9600 + 3200 * i, FS, 100 + k), FS)
            rx = ("cat %s |" % shlex.quote(path)) if k == 4 else path
            wav_scp.append("%s %s\n" % (utt, rx))
            utt2spk.append("%s %s\n" % (utt, spk))
            ids.append((utt, rx))
            k += 1
    write_text(d + "/in/wav.scp", "".join(wav_scp))
    write_text(d + "/in/utt2spk", "".join(utt2spk))
    write_wav16(d + "/rirs/a1.wav", synthetic_rir(4000, FS, 40, 0.3, 1), FS)
    write_wav16(d + "/rirs/a2.wav", synthetic_rir(6000, FS, 70, 0.5, 2), FS)
    write_wav16(d + "/rirs/b1_48k.wav", synthetic_rir(12000, 48000, 100, 0.2, 3), 48000)
    write_text(d + "/lists/rir_list_a", "--rir-id a1 --room-id roomA %s/rirs/a1.wav\n"
                                        "--rir-id a2 --room-id roomA %s/rirs/a2.wav\n" % (d, d))
    write_text(d + "/lists/rir_list_b", "--rir-id b1 --room-id roomB %s/rirs/b1_48k.wav\n" % d)
    rng = np.random.default_rng(4)
    write_wav16(d + "/noise/iso_a.wav", 0.3 * rng.standard_normal(48000), FS)
    write_wav16(d + "/noise/ps_8k.wav", 0.3 * rng.standard_normal(16000), 8000)
    write_wav16(d + "/noise/short.wav", 0.3 * rng.standard_normal(4800), FS)
    write_text(d + "/lists/noise_list",
               "--noise-id iso_a --noise-type isotropic --room-linkage roomA %s/noise/iso_a.wav\n"
               "--noise-id ps_8k --noise-type point-source --bg-fg-type background %s/noise/ps_8k.wav\n"
               "--noise-id short --noise-type point-source %s/noise/short.wav\n" % (d, d, d))
    return ids


# The library's reverberate-data: one noise per recording with --snrs, or (noise-type registry)
# Kaldi's foreground/background SNRs and per-type probabilities. The program's options are made
# from the same dict as the Augmenter's, so both always get the same settings.
NOISE_TYPES = "background_snrs" in tsrir.Augmenter.option_defaults()


def settings(d, **overrides):
    s = dict(rir_set_parameters=["0.6, %s/lists/rir_list_a" % d, "%s/lists/rir_list_b" % d],
             noise_set_parameters=["%s/lists/noise_list" % d], speech_rvb_probability=0.8, seed=SEED,
             prefix="rvb", noise_start="random")
    if NOISE_TYPES:
        s.update(foreground_snrs="15:5:0", background_snrs="0:15", isotropic_noise_addition_probability=0.7,
                 pointsource_noise_addition_probability=0.7)
    else:
        s.update(snrs="0:15", noise_addition_probability=0.7)
    s.update(overrides)
    return dict(s, data_dir=d + "/in")


def program_options(d, **overrides):
    opts = []
    for key, value in settings(d, **overrides).items():
        if key == "data_dir":
            continue
        name = "random-seed" if key == "seed" else key.replace("_", "-")
        for v in (value if isinstance(value, list) else [value]):
            opts.append("--%s=%s" % (name, v))
    return opts + ["--num-replications=%d" % COPIES]


def read_scp(path):
    with open(path) as f:
        return dict(line.rstrip("\n").split(" ", 1) for line in f if line.strip())


# Worker-side state for the multiprocessing tests (one Augmenter per worker process).
_worker_aug = None


def _init_worker(aug):
    global _worker_aug
    _worker_aug = aug


def _work(item):
    rx, utt, copy = item
    y, fs = _worker_aug.augment(utt, copy)
    return utt, copy, tsrir.encode_wav(y, fs)


class AugmenterVsReverberateData(unittest.TestCase):
    OVERRIDES = {}  # noise from a random offset, looped (the paper's way)

    @classmethod
    def setUpClass(cls):
        cls.dir = d = temp_dir("aug")
        cls.ids = make_data(d)
        opts = program_options(d, **cls.OVERRIDES)
        run([program("reverberate-data")] + opts + ["--write-wavs=%s/wavs" % d, d + "/in", d + "/out"])
        run([program("reverberate-data")] + opts + [d + "/in", d + "/out_pipes"])
        cls.aug = tsrir.Augmenter(**settings(d, **cls.OVERRIDES))

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.dir, ignore_errors=True)

    def items(self):
        return [(rx, utt, copy) for copy in range(1, COPIES + 1) for utt, rx in self.ids]

    def test_outputs_equal_reverberate_data_wavs(self):
        wav_scp = read_scp(self.dir + "/out/wav.scp")
        self.assertEqual(len(wav_scp), COPIES * len(self.ids))
        kinds = set()
        for rx, utt, copy in self.items():
            plan = self.aug.plan(utt, copy)
            self.assertIn(plan["new_id"], wav_scp)
            expected, fs = read_wav16(wav_scp[plan["new_id"]])
            speech, sfs = tsrir.read_audio(rx)
            y = self.aug(speech[0], sfs, utt, copy)
            got, _ = read_wav16(tsrir.encode_wav(y, sfs))
            np.testing.assert_array_equal(got, expected, plan["new_id"])
            kinds.add((plan["rir_id"] is not None, len(plan["noises"]) > 0))
            y2, fs2 = self.aug.augment(utt, copy)
            np.testing.assert_array_equal(y2, y)
            self.assertEqual(plan["rxfilename"], rx)
        # The seed reached every case: reverberated with and without noise, and noise alone or none.
        self.assertGreaterEqual(len(kinds), 3, kinds)

    def test_plans_equal_reverberate_data_pipes(self):
        pipes = read_scp(self.dir + "/out_pipes/wav.scp")
        for rx, utt, copy in self.items():
            plan = self.aug.plan(utt, copy)
            pipe = pipes[plan["new_id"]]
            if plan["rir_id"] is None and not plan["noises"]:
                self.assertEqual(pipe, rx)
                continue
            # The outer wav-reverberate's options (after the source's own pipe, if any).
            words = shlex.split(pipe.split(" | ")[-1] if rx.endswith("|") else pipe)
            opts = dict(w[2:].split("=", 1) for w in words if w.startswith("--") and "=" in w)
            self.assertEqual(opts.get("impulse-response"), plan["rir_rxfilename"])
            if not plan["noises"]:
                self.assertNotIn("additive-signals", opts)
                continue
            snrs = [float(v) for v in opts["snrs"].split(",")]
            self.assertEqual(len(snrs), len(plan["noises"]))
            for n, snr in zip(plan["noises"], snrs):
                self.assertAlmostEqual(snr, n["snr_db"], places=9)
                self.assertIn(n["rxfilename"], opts["additive-signals"])
            starts = [float(v) for v in opts["start-times"].split(",")]
            for n, start in zip(plan["noises"], starts):
                self.assertAlmostEqual(start, n["start_time_s"], places=6)
            if "additive-offsets" in opts:
                offsets = [float(v) for v in opts["additive-offsets"].split(",")]
                self.assertEqual(offsets, [n["offset_s"] for n in plan["noises"]])
            else:  # Kaldi's own options only: every noise from its start
                self.assertEqual([n["offset_s"] for n in plan["noises"]], [0.0] * len(plan["noises"]))

    def test_any_order_any_worker_count(self):
        serial = {(u, c): b for u, c, b in map(_work_with(self.aug), self.items())}
        # A fresh Augmenter asked in another order, for a late copy first, plans the same.
        fresh = tsrir.Augmenter(**settings(self.dir, **self.OVERRIDES))
        for rx, utt, copy in reversed(self.items()):
            self.assertEqual(fresh.plan(utt, copy), self.aug.plan(utt, copy))
        shuffled = self.items()
        random.Random(3).shuffle(shuffled)
        for method in ("fork", "spawn"):
            ctx = mp.get_context(method)
            with ctx.Pool(4, initializer=_init_worker, initargs=(self.aug,)) as pool:
                parallel = {(u, c): b for u, c, b in pool.map(_work, shuffled, chunksize=1)}
            self.assertEqual(parallel, serial, method)

    def test_copies_and_seeds_differ(self):
        rx, utt = self.ids[0][1], self.ids[0][0]
        speech, fs = tsrir.read_audio(rx)
        other = tsrir.Augmenter(**settings(self.dir, **dict(self.OVERRIDES, seed=SEED + 1)))
        self.assertEqual(other.options["seed"], SEED + 1)
        plans = {str(self.aug.plan(utt, c)) for c in range(1, 6)} | {str(other.plan(utt, 1))}
        self.assertGreater(len(plans), 3)

    def test_bad_lists_name_the_file(self):
        bad = self.dir + "/lists/bad_noise"
        write_text(bad, "--noise-id n --noise-type no-such-type %s/noise/short.wav\n" % self.dir)
        recs = {"u": self.ids[0][1]}
        with self.assertRaisesRegex(tsrir.Error, "bad_noise"):
            tsrir.Augmenter(recordings=recs, rir_set_parameters=[self.dir + "/lists/rir_list_a"],
                            noise_set_parameters=[bad])
        with self.assertRaisesRegex(tsrir.Error, "nothere"):
            tsrir.Augmenter(recordings=recs, rir_set_parameters=[self.dir + "/nothere/rir_list"])
        with self.assertRaises(tsrir.Error):
            tsrir.Augmenter(recordings=recs, rir_set_parameters=[self.dir + "/lists/rir_list_a"],
                            speech_rvb_probability=1.5)
        with self.assertRaisesRegex(TypeError, "unexpected keyword argument .snr."):
            tsrir.Augmenter(recordings=recs, rir_set_parameters=[self.dir + "/lists/rir_list_a"], snr="1")
        # Choices are reverberate-data's own names (one table with the command line's).
        with self.assertRaisesRegex(tsrir.Error, "option 'noise_start': expected one of: zero, random"):
            tsrir.Augmenter(recordings=recs, rir_set_parameters=[self.dir + "/lists/rir_list_a"], noise_start="late")
        with self.assertRaisesRegex(tsrir.Error, "not in"):
            self.aug.plan("no-such-recording")
        with self.assertRaisesRegex(tsrir.Error, "nowhere"):
            tsrir.Augmenter(data_dir=self.dir + "/nowhere", rir_set_parameters=[self.dir + "/lists/rir_list_a"])


class AugmenterVsReverberateDataZeroStart(AugmenterVsReverberateData):
    # Kaldi's way: noise from its start (with noise types: background noise extended to the
    # recording by a nested wav-reverberate, point sources at random start times).
    OVERRIDES = {"noise_start": "zero"}


def run_bytes(args):
    """A program's stdout as bytes (a wav written to '-')."""
    return subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, check=True).stdout


def read_bytes(path):
    with open(path, "rb") as f:
        return f.read()


def write_array_noises(d, tag, step, n, seed):
    """<d>/noise_list3<tag>: a 3-channel isotropic noise of room 'arr' (a sine per channel, n
    samples) and a mono foreground point-source noise."""
    iso = np.array([0.05 * np.sin(step * (c + 1) * np.arange(n)) for c in range(3)])
    write_wav16("%s/iso3%s.wav" % (d, tag), iso, FS)
    write_wav16("%s/ps%s.wav" % (d, tag), speech_like(3000, FS, seed) * 0.3, FS)
    write_text("%s/noise_list3%s" % (d, tag),
               "--noise-id iso3 --noise-type isotropic --room-linkage arr %s/iso3%s.wav\n"
               "--noise-id ps --noise-type point-source --bg-fg-type foreground %s/ps%s.wav\n" % (d, tag, d, tag))


class MultichannelFarField(unittest.TestCase):
    """--multi-channel-output=true with a microphone array's RIRs (rir-simulate, 3 microphones):
    one 3-channel recording per utterance; channel c is what wav-reverberate makes with RIR
    channel c alone (--rir-channel=c, the mono path); the pipes, --write-wavs (in memory and
    streamed) and the Augmenter agree, noises included (a 3-channel isotropic noise, a point
    source through the array's RIR); a mono isotropic noise is refused with a clear error."""

    @classmethod
    def setUpClass(cls):
        cls.dir = d = temp_dir("mc")
        os.makedirs(d + "/in")
        wav_scp = []
        for i, n in enumerate((12000, 20000)):
            write_wav16("%s/u%d.wav" % (d, i), speech_like(n, FS, 300 + i), FS)
            wav_scp.append("u%d %s/u%d.wav\n" % (i, d, i))
        write_text(d + "/in/wav.scp", "".join(wav_scp))
        write_text(d + "/in/utt2spk", "u0 s0\nu1 s1\n")
        write_text(d + "/rooms.txt", "arr room=6,4.5,3 src=2,1.5,1.6 mic=4,3,1.2;4.05,3,1.2;4.1,3.02,1.2 t60=0.4\n")
        run([program("rir-simulate"), "--length=0.4", d + "/rooms.txt", d + "/rirs"])
        cls.base = ["--multi-channel-output=true", "--rir-set-parameters", d + "/rirs/rir_list",
                    "--random-seed", "3"]

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.dir, ignore_errors=True)

    def test_one_multichannel_recording_per_utterance_everywhere_equal(self):
        d = self.dir
        run([program("reverberate-data")] + self.base + [d + "/in", d + "/pipes"])
        run([program("reverberate-data")] + self.base + ["--write-wavs", d + "/w", d + "/in", d + "/wavs"])
        run([program("reverberate-data")] + self.base + ["--max-in-memory-duration", "0.5", "--write-wavs",
                                                          d + "/ws", d + "/in", d + "/streamed"])
        aug = tsrir.Augmenter(data_dir=d + "/in", rir_set_parameters=[d + "/rirs/rir_list"], seed=3,
                              multi_channel_output=True)
        pipes = read_scp(d + "/pipes/wav.scp")
        self.assertEqual(sorted(pipes), ["u0", "u1"])
        for utt, pipe in pipes.items():
            self.assertIn("--multi-channel-output=true", pipe)
            piped = run_bytes(["sh", "-c", pipe.rstrip().rstrip("|")])
            written = read_bytes("%s/w/%s.wav" % (d, utt))
            self.assertEqual(piped, written, utt)
            self.assertEqual(read_bytes("%s/ws/%s.wav" % (d, utt)), written, utt)  # streamed (> 0.5 s)
            x, fs = read_wav16(written)
            self.assertEqual(x.shape[0], 3)
            y, _ = aug.augment(utt)
            self.assertEqual(y.shape, x.shape)
            self.assertEqual(tsrir.encode_wav(y, fs), written)
            for c in range(3):
                mono, _ = read_wav16(run_bytes([program("wav-reverberate"), "--shift-output=true", "--rir-channel=%d" % c,
                                          "--impulse-response=" + d + "/rirs/arr.wav", "%s/%s.wav" % (d, utt), "-"]))
                np.testing.assert_array_equal(x[c], mono[0], "%s channel %d" % (utt, c))

    def test_noises_per_channel_pipes_and_augmenter_agree(self):
        d = self.dir
        write_array_noises(d, "", 0.01, 7000, 77)
        noisy = self.base + ["--noise-set-parameters", d + "/noise_list3", "--max-noises-per-recording", "1"]
        run([program("reverberate-data")] + noisy + [d + "/in", d + "/noisy"])
        aug = tsrir.Augmenter(data_dir=d + "/in", rir_set_parameters=[d + "/rirs/rir_list"], seed=3,
                              noise_set_parameters=[d + "/noise_list3"], max_noises_per_recording=1,
                              multi_channel_output=True)
        for utt, pipe in read_scp(d + "/noisy/wav.scp").items():
            self.assertIn("iso3.wav", pipe)
            self.assertIn("ps.wav", pipe)
            piped = run_bytes(["sh", "-c", pipe.rstrip().rstrip("|")])
            y, fs = aug.augment(utt)
            self.assertEqual(y.shape[0], 3)
            self.assertEqual(tsrir.encode_wav(y, fs), piped, utt)

    def test_split_channels_equal_the_per_channel_data_dir(self):
        """split_channels=True: one mono copy per channel, keyed as reverberate-data --split-channels
        keys its entries (prefix="rvb": the program forces it for several copies, the Augmenter
        cannot know how many will be asked for), each the bytes of that entry's --write-wavs wav
        (noises included); a copy that is not reverberated keeps its id; multichannel speech is
        refused."""
        d = self.dir
        write_array_noises(d, "s", 0.013, 9000, 78)
        options = ["--rir-set-parameters", d + "/rirs/rir_list", "--noise-set-parameters", d + "/noise_list3s",
                   "--max-noises-per-recording", "1", "--num-replications", "3", "--speech-rvb-probability", "0.5",
                   "--random-seed", "4"]
        run([program("reverberate-data"), "--split-channels=true"] + options +
            ["--write-wavs", d + "/split_w", d + "/in", d + "/split"])
        entries = read_scp(d + "/split/wav.scp")
        aug = tsrir.Augmenter(data_dir=d + "/in", rir_set_parameters=[d + "/rirs/rir_list"], seed=4,
                              noise_set_parameters=[d + "/noise_list3s"], max_noises_per_recording=1,
                              speech_rvb_probability=0.5, prefix="rvb", split_channels=True)
        multi = tsrir.Augmenter(data_dir=d + "/in", rir_set_parameters=[d + "/rirs/rir_list"], seed=4,
                                noise_set_parameters=[d + "/noise_list3s"], max_noises_per_recording=1,
                                speech_rvb_probability=0.5, prefix="rvb", multi_channel_output=True)
        got = {}
        for utt in ("u0", "u1"):
            for copy in (1, 2, 3):
                y, fs = aug.augment(utt, copy)
                self.assertEqual(list(y), sorted(y))
                got.update({k: tsrir.encode_wav(v, fs) for k, v in y.items()})
                if len(y) == 3:  # the split form is the multichannel one, channel by channel
                    m, _ = multi.augment(utt, copy)
                    for c, v in enumerate(y.values()):
                        np.testing.assert_array_equal(v, m[c])
        self.assertEqual(sorted(got), sorted(entries))
        self.assertTrue(any(k.endswith(".CH3") for k in got) and any(".CH" not in k for k in got), sorted(got))
        for key, wav in got.items():
            self.assertEqual(wav, read_bytes("%s/split_w/%s.wav" % (d, key)), key)
        x, _ = read_wav16(d + "/u0.wav")
        from_samples = aug(x[0].astype(np.float32) / 32768, FS, "u0", 2)
        self.assertEqual({k: tsrir.encode_wav(v, FS) for k, v in from_samples.items()},
                         {k: got[k] for k in from_samples})
        with self.assertRaises(ValueError) as caught:
            aug(np.zeros((2, 8000), dtype=np.float32), FS, "u0")
        self.assertIn("split_channels", str(caught.exception))

    def test_mono_noise_and_multichannel_speech_are_clear_errors(self):
        d = self.dir
        write_wav16(d + "/noise.wav", 0.1 * np.ones(100), FS)
        write_text(d + "/noise_list", "--noise-id n --noise-type isotropic --room-linkage arr %s/noise.wav\n" % d)
        with self.assertRaises(Exception) as caught:
            run([program("reverberate-data")] + self.base + ["--noise-set-parameters", d + "/noise_list",
                                                              d + "/in", d + "/bad"])
        self.assertIn("has 1 channel(s) but recording", str(caught.exception))
        self.assertIn("--multi-channel-output", str(caught.exception))
        self.assertFalse(os.path.exists(d + "/bad"))
        aug = tsrir.Augmenter(data_dir=d + "/in", rir_set_parameters=[d + "/rirs/rir_list"],
                              noise_set_parameters=[d + "/noise_list"], multi_channel_output=True)
        with self.assertRaises(Exception) as caught:
            aug.augment("u0")
        self.assertIn("has 1 channel(s), but microphone 1 of the array needs its own", str(caught.exception))
        aug = tsrir.Augmenter(data_dir=d + "/in", rir_set_parameters=[d + "/rirs/rir_list"], multi_channel_output=True)
        with self.assertRaises(ValueError) as caught:
            aug(np.zeros((4, 8000), dtype=np.float32), FS, "u0")
        self.assertIn("multi_channel_output", str(caught.exception))


def _work_with(aug):
    def work(item):
        rx, utt, copy = item
        y, fs = aug.augment(utt, copy)
        return utt, copy, tsrir.encode_wav(y, fs)
    return work


if __name__ == "__main__":
    unittest.main()
