"""The module against the programs, on the same inputs: reverberate() vs wav-reverberate (byte for
byte on the output file), simulate() vs rir-simulate --format=float (sample for sample),
metrics() vs rir-metrics --format=json (the same dict), eq_apply() vs rir-eq apply --format=float.
The inputs are written by Python's wave module and fabricated here, not by the toolkit."""
import json
import math
import os
import shutil
import unittest

from tsrir_testlib import (np, program, read_wav16, run, speech_like, synthetic_rir, temp_dir,
                           write_text, write_wav16)
import tsrir

FS = 16000


class Reverberate(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.dir = temp_dir("rvb")
        d = cls.dir
        write_wav16(d + "/speech.wav", speech_like(int(1.3 * FS), FS, 1), FS)
        write_wav16(d + "/rir.wav", synthetic_rir(6000, FS, 57, 0.5, 2), FS)
        write_wav16(d + "/rir2.wav", synthetic_rir(5000, FS, 30, 0.4, 3, channels=2), FS)
        write_wav16(d + "/rir48.wav", synthetic_rir(15000, 48000, 120, 0.3, 4), 48000)
        rng = np.random.default_rng(5)
        write_wav16(d + "/noise.wav", 0.3 * rng.standard_normal(int(0.7 * FS)), FS)
        write_wav16(d + "/noise2.wav", 0.2 * rng.standard_normal((2, int(2.0 * FS))), FS)
        write_wav16(d + "/babble.wav", speech_like(int(1.6 * FS), FS, 9), FS)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.dir, ignore_errors=True)

    def load(self, name):
        """The samples the program reads, through the toolkit's reader; checked against an
        independent reader (wave, int16 / 32768)."""
        x, fs = tsrir.read_audio(self.dir + "/" + name)
        q, fs2 = read_wav16(self.dir + "/" + name)
        self.assertEqual(fs, fs2)
        np.testing.assert_array_equal(x, q.astype(np.float32) / 32768)
        return x

    def check(self, options, **kwargs):
        out = self.dir + "/out.wav"
        if os.path.exists(out):
            os.remove(out)
        run([program("wav-reverberate")] + options + [self.dir + "/speech.wav", out])
        speech = self.load("speech.wav")[0]
        y = tsrir.reverberate(speech, fs=FS, **kwargs)
        with open(out, "rb") as f:
            expected = f.read()
        got = tsrir.encode_wav(y, FS)
        self.assertEqual(len(got), len(expected))
        self.assertEqual(got, expected, "output file differs from wav-reverberate %s" % " ".join(options))
        # Not trivially equal: the output is reverberant speech, not silence or the input.
        q, _ = read_wav16(expected)
        self.assertGreater(np.abs(q).max(), 1000)
        return y

    def test_rir_only_peak_shift(self):
        h = self.load("rir.wav")[0]
        y = self.check(["--impulse-response=%s/rir.wav" % self.dir, "--shift-output=true"], rir=h, shift="peak")
        self.assertEqual(len(y), int(1.3 * FS))

    def test_no_shift_keeps_tail(self):
        h = self.load("rir.wav")[0]
        y = self.check(["--impulse-response=%s/rir.wav" % self.dir, "--shift-output=false"], rir=h, shift=None)
        self.assertEqual(len(y), int(1.3 * FS) + 6000 - 1)

    def test_noise_snr_offsets_loop(self):
        h = self.load("rir.wav")[0]
        n1, n2 = self.load("noise.wav")[0], self.load("babble.wav")[0]
        self.check(["--impulse-response=%s/rir.wav" % self.dir,
                    "--additive-signals=%s/noise.wav,%s/babble.wav" % (self.dir, self.dir),
                    "--snrs=7.5,12", "--start-times=0,0.25", "--additive-offsets=0.1,0.3",
                    "--loop-additive-signals=true"],
                   rir=h, noise=[n1, n2], snr_db=[7.5, 12], start_time_s=[0, 0.25], offset_s=[0.1, 0.3],
                   loop_noise=True)

    def test_kaldi_noise_volume_duration_full_reference(self):
        h = self.load("rir.wav")[0]
        n1 = self.load("noise.wav")[0]
        self.check(["--impulse-response=%s/rir.wav" % self.dir, "--additive-signals=%s/noise.wav" % self.dir,
                    "--snrs=3", "--start-times=0.4", "--volume=0.3", "--duration=2.1",
                    "--snr-reference=full"],
                   rir=h, noise=n1, snr_db=3, start_time_s=0.4, volume=0.3, duration_s=2.1,
                   snr_reference="full")

    def test_multichannel_rir(self):
        h = self.load("rir2.wav")
        n = self.load("noise2.wav")
        y = self.check(["--impulse-response=%s/rir2.wav" % self.dir, "--additive-signals=%s/noise2.wav" % self.dir,
                        "--snrs=10", "--start-times=0", "--multi-channel-output=true"],
                       rir=h, noise=n, snr_db=10, multi_channel_output=True)
        self.assertEqual(y.shape[0], 2)
        self.check(["--impulse-response=%s/rir2.wav" % self.dir, "--rir-channel=1"], rir=h, rir_channel=1)

    def test_rir_at_another_rate_is_resampled(self):
        h = self.load("rir48.wav")[0]
        self.check(["--impulse-response=%s/rir48.wav" % self.dir], rir=h, rir_fs=48000)

    def test_noise_only(self):
        n1 = self.load("noise.wav")[0]
        self.check(["--additive-signals=%s/noise.wav" % self.dir, "--snrs=5", "--start-times=0"],
                   rir=None, noise=n1, snr_db=5)

    def test_direct_shift(self):
        """shift="direct": wav-reverberate's output advanced to the direct sound, not to the
        largest sample. An RIR whose direct sound (sample 40) is weaker than a reflection (sample
        300): the program's full output (--shift-output=false) read from sample 40 on, bit for bit."""
        rng = np.random.default_rng(8)
        h = np.zeros(4000)
        h[40], h[300] = 0.45, 0.9
        h[301:] = 0.05 * rng.standard_normal(3699) * np.exp(-np.arange(3699) / 800)
        write_wav16(self.dir + "/rir_reflection.wav", h, FS)
        hq = self.load("rir_reflection.wav")[0]
        self.assertEqual((tsrir.rir_onset_index(hq, FS), tsrir.rir_shift_index(hq, FS)), (40, 300))
        out = self.dir + "/full.wav"
        run([program("wav-reverberate"), "--impulse-response=%s/rir_reflection.wav" % self.dir,
             "--shift-output=false", self.dir + "/speech.wav", out])
        full, _ = read_wav16(out)
        speech = self.load("speech.wav")[0]
        y = tsrir.reverberate(speech, hq, FS, shift="direct")
        got, _ = read_wav16(tsrir.encode_wav(y, FS))
        np.testing.assert_array_equal(got[0], full[0, 40:40 + len(speech)])
        # The peak shift is the program's --shift-output=true: 260 samples later.
        peak, _ = read_wav16(tsrir.encode_wav(tsrir.reverberate(speech, hq, FS, shift="peak"), FS))
        np.testing.assert_array_equal(peak[0], full[0, 300:300 + len(speech)])

    def test_direct_shift_on_simulated_rooms(self):
        """The onset is the direct path (distance / c from the geometry) where the largest sample
        is a reflection, and equals the peak where the direct sound is the largest."""
        import math
        far = dict(room=(6, 4.5, 3), src=(1, 1, 1.5), mic=(5, 3.5, 1.2))
        h = tsrir.simulate(t60=0.6, length=0.8, **far)
        expected = math.dist(far["src"], far["mic"]) / 343.0 * FS
        self.assertLessEqual(abs(tsrir.rir_onset_index(h, FS) - expected), 2)
        self.assertGreater(tsrir.rir_shift_index(h, FS) - expected, 50)
        near = tsrir.simulate((6, 4.5, 3), (2, 1.5, 1.6), (4, 3, 1.2), t60=0.6, length=0.8)
        x = speech_like(FS, FS, 3)
        self.assertEqual(tsrir.rir_onset_index(near, FS), tsrir.rir_shift_index(near, FS))
        np.testing.assert_array_equal(tsrir.reverberate(x, near, FS, shift="direct"),
                                      tsrir.reverberate(x, near, FS, shift="peak"))

    def test_errors_are_clear(self):
        with self.assertRaisesRegex(TypeError, "snr_db"):
            tsrir.reverberate(np.ones(100), None, FS, noise=np.ones(50))
        with self.assertRaisesRegex(tsrir.Error, "not finite"):
            tsrir.reverberate(np.array([0.0, float("nan")]), np.ones(10), FS)


class GilReleased(unittest.TestCase):
    def test_python_runs_while_cpp_works(self):
        """A Python thread keeps running during one long reverberate() call in another thread:
        the GIL is released. (Held, the main loop would stall for the whole call.)"""
        import threading
        import time
        h = tsrir.simulate((20, 15, 8), (2, 1.5, 1.6), (14, 9, 1.2), fs=48000, t60=2.0, length=8.0)
        x = np.random.default_rng(0).standard_normal(48000 * 60).astype(np.float32)
        span = {}

        def work():
            span["start"] = time.monotonic()
            tsrir.reverberate(x, h, 48000)
            span["end"] = time.monotonic()

        t = threading.Thread(target=work)
        ticks = []
        t.start()
        while t.is_alive():
            ticks.append(time.monotonic())
        t.join()
        inside = [v for v in ticks if span["start"] < v < span["end"]]
        duration = span["end"] - span["start"]
        self.assertGreater(duration, 0.05)
        gaps = np.diff([span["start"]] + inside + [span["end"]])
        # Python's switch interval is 5 ms; a held GIL would leave one gap of the whole call.
        self.assertLess(gaps.max(), 0.5 * duration, "main thread stalled %.3f s of a %.3f s call"
                        % (gaps.max(), duration))


ROOMS = [
    # (rir id, room-list keys, simulate() keyword arguments)
    ("r1", "room=6,4.5,3 src=2,1.5,1.6 mic=4,3,1.2 t60=0.6",
     dict(room=(6, 4.5, 3), src=(2, 1.5, 1.6), mic=(4, 3, 1.2), t60=0.6)),
    ("r2", "room=5,4,2.8 src=1,1,1.5 mic=3.5,2.5,1.2 absorption=0.1,0.15,0.2,0.25,0.3,0.35,0.4,0.4 "
           "scattering=0.3 room-id=roomB absorption.floor=0.5",
     dict(room=[5, 4, 2.8], src=[1, 1, 1.5], mic=[3.5, 2.5, 1.2],
          absorption=[0.1, 0.15, 0.2, 0.25, 0.3, 0.35, 0.4, 0.4], scattering=0.3,
          extra={"room-id": "roomB", "absorption.floor": 0.5})),
    # A 3-microphone array of cardioids facing the source: one 3-channel RIR, (3, samples) here.
    ("r3", "room=6,4.5,3 src=2,1.5,1.6 mic=4,3,1.2;4.05,3,1.2;4.1,3,1.2 mic_pattern=cardioid mic_dir=-140,0 "
           "src_pattern=subcardioid t60=0.5",
     dict(room=(6, 4.5, 3), src=(2, 1.5, 1.6), mic=[(4, 3, 1.2), (4.05, 3, 1.2), (4.1, 3, 1.2)], t60=0.5,
          extra={"mic_pattern": "cardioid", "mic_dir": (-140, 0), "src_pattern": "subcardioid"})),
]


class SimulateMetricsEq(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.dir = d = temp_dir("sim")
        write_text(d + "/rooms.txt", "".join("%s %s\n" % (rid, keys) for rid, keys, _ in ROOMS))
        cls.models = {}
        for model, length in (("gas", "0.5"), ("gas+air+modes", "auto")):
            out = "%s/sim_%s" % (d, model.replace("+", "_"))
            run([program("rir-simulate"), "--fs=16000", "--length=" + length, "--seed=3", "--model=" + model,
                 "--format=float", d + "/rooms.txt", out])
            cls.models[(model, length)] = out

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.dir, ignore_errors=True)

    def test_simulate_equals_rir_simulate(self):
        for (model, length), out in self.models.items():
            for rid, _, kwargs in ROOMS:
                expected, fs = tsrir.read_audio("%s/%s.wav" % (out, rid))
                got = tsrir.simulate(fs=16000, seed=3, model=model, length=length if length == "auto" else 0.5,
                                     rir_id=rid, **kwargs)
                self.assertEqual(fs, 16000)
                # One microphone: (samples,); an array: (microphones, samples), channel order kept.
                np.testing.assert_array_equal(got, expected[0] if got.ndim == 1 else expected,
                                              "%s %s" % (model, rid))
                self.assertEqual(got.ndim, 2 if rid == "r3" else 1)
                self.assertGreater(np.abs(got).max(), 0.01)
        # A different seed or id gives a different diffuse tail (the seed is really used).
        a = tsrir.simulate(seed=3, rir_id="r1", length=0.5, **ROOMS[0][2])
        b = tsrir.simulate(seed=4, rir_id="r1", length=0.5, **ROOMS[0][2])
        self.assertFalse(np.array_equal(a, b))

    def test_metrics_equal_rir_metrics_json(self):
        out = self.models[("gas", "0.5")]
        for definition in ("iso", "irstats"):
            doc = json.loads(run([program("rir-metrics"), "--format=json", "--definition=" + definition,
                                  out + "/rir.scp"]))
            self.assertEqual(len(doc["rirs"]), len(ROOMS))
            for row in doc["rirs"]:
                h, fs = tsrir.read_audio("%s/%s.wav" % (out, row["id"]))
                got = tsrir.metrics(h[0], fs, definition=definition, rir_id=row["id"])
                self.assertEqual(json.dumps(got, sort_keys=True),
                                 json.dumps(tsrir._nan_for_null(row), sort_keys=True))
                self.assertTrue(0.2 < got["T60"] < 1.5, got["T60"])

    def test_eq_apply_equals_rir_eq_apply(self):
        model = self.dir + "/eq.model"
        write_text(model, "tsrir-eq-model 1\nsample_rate_hz 16000\ngain_method octave\n"
                          "points_hz 62.5 125 250 500 2000 4000 8000\nreference_hz 1000\nfitted_rirs 30\n"
                          "covariance diag\ncomponents 1\ncomponent 1\nweight 1\n"
                          "mean 6 3 1 0 -1 -4 -9\nvariance 4 2 1 1 1 2 6\nend\n")
        out = self.models[("gas", "0.5")]
        eq_out = self.dir + "/eq_out"
        run([program("rir-eq"), "apply", "--seed=7", "--format=float", model, out + "/rir.scp", eq_out])
        for rid, _, _ in ROOMS:
            h, fs = tsrir.read_audio("%s/%s.wav" % (out, rid))
            expected, _ = tsrir.read_audio("%s/%s.wav" % (eq_out, rid))
            got, info = tsrir.eq_apply(model, h[0], fs, seed=7, rir_id=rid)
            np.testing.assert_array_equal(got, expected[0])
            self.assertFalse(np.array_equal(got, h[0]))
            # The gains it reached are near the drawn target (what rir-eq reports).
            for f, target in info["target_db"].items():
                self.assertLess(abs(info["after_db"][f] - target), 1.0, f)


if __name__ == "__main__":
    unittest.main()
