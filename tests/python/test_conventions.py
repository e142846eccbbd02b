"""Python conventions of the tsrir package (issue 32): typed exceptions naming the argument, the
library's warnings through `warnings`, torch in -> torch out, int sampling rates, documented
functions, and no silent rate or channel change in Augmenter (resampled to sample_rate when given,
refused otherwise; a multichannel recording named in a warning)."""
import inspect
import shutil
import unittest
import warnings

from tsrir_testlib import np, program, run, speech_like, temp_dir, write_text, write_wav16
import tsrir
import tsrir.data
import tsrir.manifests

FS = 16000


def tones(fs, seconds=1.0):
    """Partials below 4 kHz defined analytically at each rate (not by the resampler under test)."""
    t = np.arange(int(round(seconds * fs))) / fs
    return 0.2 * np.sin(2 * np.pi * 220 * t) + 0.1 * np.sin(2 * np.pi * 1330 * t + 0.3)


class TypedErrors(unittest.TestCase):
    def test_wrong_kinds_are_type_errors_naming_the_argument(self):
        x, h = np.ones(200), np.r_[1.0, np.zeros(9)]
        cases = [
            (lambda: tsrir.reverberate(x, h, FS, noise=x, snr_db="ten"), "snr_db"),
            (lambda: tsrir.reverberate(x, h, "16k"), "fs"),
            (lambda: tsrir.reverberate("speech.wav", h, FS), "speech"),
            (lambda: tsrir.reverberate(x, h, FS, normalize="yes"), "normalize"),
            (lambda: tsrir.simulate(room=(6, 4, 3), src=(1, 1, 1), mic="centre"), "mic"),
            (lambda: tsrir.simulate(room=(6, 4, 3), src=(1, 1, 1), mic=(2, 2, 1), seed=1.5), "seed"),
            (lambda: tsrir.metrics(h, FS, onset=5), "onset"),
            (lambda: tsrir.read_audio(3), "rxfilename"),
            (lambda: tsrir.resample(x, FS, None), "to_hz"),
        ]
        for call, name in cases:
            with self.subTest(name=name):
                with self.assertRaises(TypeError) as caught:
                    call()
                self.assertIn(name, str(caught.exception))
                self.assertNotIn("Unable to cast", str(caught.exception))

    def test_wrong_values_are_value_errors_naming_the_argument(self):
        x, h = np.ones(200), np.r_[1.0, np.zeros(9)]
        cases = [
            (lambda: tsrir.simulate(room=(6, 4, 3), src=(1, 1, 1), mic=[(2, 2), (3, 3)]), "mic"),
            (lambda: tsrir.simulate(room=(6, 4, 3), src=(1, 1, 1), mic=(2, 2, 1), extra={"mic_pattern": "shotgun"}),
             "mic_pattern"),
            (lambda: tsrir.simulate(room=(6, 4, 3), src=(1, 1, 1), mic=(2, 2, 1), fs=-16000), "fs"),
            (lambda: tsrir.simulate(room=(6, 4, 3), src=(1, 1, 1), mic=(2, 2, 1), t60=[0.5, 0.4]), "t60"),
            (lambda: tsrir.reverberate(np.ones((2, 2, 2)), h, FS), "speech"),
            (lambda: tsrir.reverberate(np.ones((4, 200)), h, FS, multi_channel_output=True), "multi_channel_output"),
            (lambda: tsrir.reverberate(x, h, FS, shift="onset"), "shift"),
            (lambda: tsrir.reverberate(x, h, FS, noise=[x, x], snr_db=[1, 2, 3]), "snr_db"),
            (lambda: tsrir.encode_wav(x, FS, format="mp3"), "format"),
        ]
        for call, name in cases:
            with self.subTest(name=name):
                with self.assertRaises(ValueError) as caught:
                    call()
                self.assertIn(name, str(caught.exception))
        # What the library rejects is a tsrir.Error, itself a ValueError.
        with self.assertRaisesRegex(tsrir.Error, "not finite") as caught:
            tsrir.reverberate(np.array([0.0, float("nan")]), h, FS)
        self.assertIsInstance(caught.exception, ValueError)


class WarningsAndRates(unittest.TestCase):
    def setUp(self):
        self.dir = temp_dir("conventions")
        write_wav16(self.dir + "/a16.wav", tones(16000), 16000)
        write_wav16(self.dir + "/b48.wav", tones(48000), 48000)
        write_wav16(self.dir + "/st16.wav", np.stack([tones(16000), 0 * tones(16000)]), 16000)
        write_text(self.dir + "/rooms.txt", "r1 room=5,4,3 src=1,1,1.5 mic=3,2.5,1.2 t60=0.4\n")
        run([program("rir-simulate"), "--length=0.3", self.dir + "/rooms.txt", self.dir + "/rirs"])
        self.rirs = [self.dir + "/rirs/rir_list"]

    def tearDown(self):
        shutil.rmtree(self.dir, ignore_errors=True)

    def test_sampling_rates_are_int(self):
        samples, fs = tsrir.read_audio(self.dir + "/b48.wav")
        self.assertIs(type(fs), int)
        self.assertEqual(fs, 48000)
        self.assertIs(type(tsrir.audio_info(self.dir + "/a16.wav")["sample_rate"]), int)
        aug = tsrir.Augmenter(recordings={"a": self.dir + "/a16.wav"}, rir_set_parameters=self.rirs)
        y, fs = aug.augment("a")
        self.assertIs(type(fs), int)
        self.assertIs(type(aug.sample_rate), int)

    def test_library_warnings_go_through_warnings(self):
        empty = self.dir + "/empty_noise_list"
        write_text(empty, "")
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            tsrir.Augmenter(recordings={"a": self.dir + "/a16.wav"}, rir_set_parameters=self.rirs,
                            noise_set_parameters=[empty])
        messages = [str(w.message) for w in caught if issubclass(w.category, tsrir.TsrirWarning)]
        self.assertTrue(any("the noise list is empty" in m for m in messages), messages)
        with warnings.catch_warnings():
            warnings.simplefilter("error", tsrir.TsrirWarning)
            with self.assertRaises(tsrir.TsrirWarning):
                tsrir.Augmenter(recordings={"a": self.dir + "/a16.wav"}, rir_set_parameters=self.rirs,
                                noise_set_parameters=[empty])

    def test_a_mixed_rate_recording_is_refused_without_sample_rate(self):
        recs = {"a": self.dir + "/a16.wav", "b": self.dir + "/b48.wav"}
        aug = tsrir.Augmenter(recordings=recs, rir_set_parameters=self.rirs)
        self.assertEqual(aug.sample_rate, 16000)  # the first recording's
        with self.assertRaisesRegex(tsrir.Error, r"recording 'b'.*48000 Hz.*16000 Hz.*sample_rate|--sample-rate"):
            aug.augment("b")
        with self.assertRaisesRegex(tsrir.Error, "48000 Hz"):
            aug(tones(48000), 48000, "b")

    def test_sample_rate_resamples_to_the_corpus_rate(self):
        recs = {"a": self.dir + "/a16.wav", "b": self.dir + "/b48.wav"}
        aug = tsrir.Augmenter(recordings=recs, rir_set_parameters=self.rirs, sample_rate=16000, seed=3)
        ya, fa = aug.augment("a")
        yb, fb = aug.augment("b")
        self.assertEqual((fa, fb), (16000, 16000))
        self.assertEqual(len(yb), len(ya))
        # Same tones, same RIR (one in the list): the resampled 48 kHz recording gives the native one's output.
        inner = slice(2000, len(ya) - 2000)
        err = np.sum((ya[inner] - yb[inner]) ** 2) / np.sum(ya[inner] ** 2)
        self.assertLess(10 * np.log10(err), -40)

    def test_a_multichannel_recording_is_named_in_a_warning(self):
        aug = tsrir.Augmenter(recordings={"s": self.dir + "/st16.wav"}, rir_set_parameters=self.rirs)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            aug.augment("s")
        messages = [str(w.message) for w in caught if issubclass(w.category, tsrir.TsrirWarning)]
        self.assertTrue(any("recording 's': 2 channels; using channel 0" in m for m in messages), messages)
        x = np.stack([speech_like(4000, FS, 1), speech_like(4000, FS, 2)])
        h = np.r_[1.0, np.zeros(9)]
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            tsrir.reverberate(x, h, FS)
            tsrir.reverberate(x, h, FS, input_channel=1)
        messages = [str(w.message) for w in caught if issubclass(w.category, tsrir.TsrirWarning)]
        self.assertEqual(messages, ["speech has 2 channels; using channel 0 (give input_channel= to choose another)"])


class Torch(unittest.TestCase):
    def setUp(self):
        try:
            import torch
        except ImportError:
            self.skipTest("torch is not installed (python3-torch)")
        self.torch = torch

    def test_tensors_in_tensors_out(self):
        torch = self.torch
        x = speech_like(8000, FS, 4)
        h = tsrir.simulate((5, 4, 3), (1, 1, 1.5), (3, 2.5, 1.2), t60=0.3, length=0.2)
        for dtype in (torch.float32, torch.float64):
            y = tsrir.reverberate(torch.tensor(x, dtype=dtype), torch.tensor(h), FS)
            self.assertIsInstance(y, torch.Tensor)
            self.assertEqual((y.dtype, y.device.type), (dtype, "cpu"))
            np.testing.assert_allclose(y.numpy(), tsrir.reverberate(x, h, FS), rtol=0, atol=1e-6)
        r = tsrir.resample(torch.tensor(x, dtype=torch.float32), FS, 8000)
        self.assertIsInstance(r, torch.Tensor)
        self.assertEqual(r.shape, (4000,))
        self.assertIsInstance(tsrir.reverberate(x, h, FS), np.ndarray)  # numpy in, numpy out


class Documented(unittest.TestCase):
    def test_every_public_function_has_a_docstring_with_shapes_or_units(self):
        for name in tsrir.__all__:
            obj = getattr(tsrir, name)
            doc = inspect.getdoc(obj) or ""
            with self.subTest(name=name):
                self.assertGreater(len(doc), 40, "%s has no real docstring" % name)
        # The submodules' public functions and the public methods of their classes too.
        for module in (tsrir, tsrir.data, tsrir.manifests):
            for name, obj in vars(module).items():
                if name.startswith("_") or not callable(obj) or not getattr(obj, "__module__", "").startswith("tsrir"):
                    continue
                members = [(name, obj)]
                if inspect.isclass(obj) and not issubclass(obj, BaseException):
                    members += [(name + "." + m, f) for m, f in vars(obj).items() if not m.startswith("_") and callable(f)]
                for full, f in members:
                    with self.subTest(name=module.__name__ + "." + full):
                        self.assertGreater(len(inspect.getdoc(f) or ""), 30, "%s has no real docstring" % full)
        for name in ("simulate", "reverberate", "metrics", "resample", "read_audio", "eq_apply"):
            doc = inspect.getdoc(getattr(tsrir, name))
            with self.subTest(name=name):
                self.assertRegex(doc, r"\(samples,\)|\(taps,\)|\(channels, samples\)")
                self.assertRegex(doc, r"\bHz\b")


if __name__ == "__main__":
    unittest.main()
