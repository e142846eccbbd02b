"""tsrir.manifests against the formats as Lhotse documents and defines them (Lhotse itself is not
installable here: Debian has no package and PyPI is out of reach), on real files written by the
toolkit (rir-simulate's RIR set, reverberate-data's data dir): the schema, round trips back to
Kaldi lists (which then augment exactly as the originals), ESPnet scp and SpeechBrain CSV."""
import csv
import json
import math
import os
import shutil
import unittest

from tsrir_testlib import np, program, run, speech_like, temp_dir, write_text, write_wav16
import tsrir
import tsrir.manifests as mf

# The example RecordingSet of Lhotse's documentation (docs/corpus.rst), as a dict per recording.
LHOTSE_DOC_EXAMPLE = [
    {"id": "recording-1", "sampling_rate": 8000, "num_samples": 4000, "duration": 0.5,
     "sources": [{"type": "file", "channels": [0], "source": "test/fixtures/mono_c0.wav"},
                 {"type": "file", "channels": [1], "source": "test/fixtures/mono_c1.wav"}]},
    {"id": "recording-2", "sampling_rate": 8000, "num_samples": 8000, "duration": 1.0,
     "sources": [{"type": "file", "channels": [0, 1], "source": "test/fixtures/stereo.wav"}]},
]
ROOMS = ("r1 room=6,4.5,3 src=2,1.5,1.6 mic=4,3,1.2 t60=0.6 room-id=roomA\n"
         "r2 room=6,4.5,3 src=1,1,1.5 mic=5,3.5,1.2 t60=0.6 room-id=roomA\n"
         "r3 room=4,3,2.6 src=1,1,1.5 mic=2.5,2,1.2 t60=0.3 room-id=roomB\n")


class Manifests(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.dir = d = temp_dir("manifests")
        write_text(d + "/rooms.txt", ROOMS)
        run([program("rir-simulate"), "--length=0.8", "--format=float", d + "/rooms.txt", d + "/rirs"])
        cls.recordings, cls.cuts = mf.export_rir_set(d + "/rirs/rir_list", d + "/lhotse_rirs",
                                                     room_list=d + "/rooms.txt")

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.dir, ignore_errors=True)

    def test_schema_as_lhotse_documents_it(self):
        for rec in LHOTSE_DOC_EXAMPLE:  # the documentation's own example passes the check
            mf.check_recording(dict(rec), "doc")
        recs = mf.read_recordings(self.recordings)
        self.assertEqual([r["id"] for r in recs], ["r1", "r2", "r3"])
        for r in recs:
            # The documented keys (and channel_ids, which Lhotse fills in), nothing else: Lhotse
            # builds Recording(**dict), which rejects unknown keys.
            self.assertEqual(set(r), {"id", "sources", "sampling_rate", "num_samples", "duration", "channel_ids"})
            self.assertEqual(r["sources"][0]["type"], "file")
            self.assertTrue(os.path.isabs(r["sources"][0]["source"]))
            h, fs = tsrir.read_audio(r["sources"][0]["source"])
            self.assertEqual((r["sampling_rate"], r["num_samples"]), (16000, h.shape[1]))
            self.assertEqual(r["duration"], h.shape[1] / 16000)
        with self.assertRaisesRegex(tsrir.Error, "custom"):
            mf.check_recording(dict(LHOTSE_DOC_EXAMPLE[1], custom={"a": 1}), "x")
        with self.assertRaisesRegex(tsrir.Error, "num_samples"):
            mf.check_recording({k: v for k, v in LHOTSE_DOC_EXAMPLE[1].items() if k != "num_samples"}, "x")

    def test_cut_metadata(self):
        cuts = [c for c, _ in mf.read_jsonl(self.cuts)]
        self.assertEqual([c["type"] for c in cuts], ["MonoCut"] * 3)
        rooms = {r["rir_id"]: r for r in tsrir.read_room_list(self.dir + "/rooms.txt")}
        for c in cuts:
            self.assertEqual(set(c), {"id", "start", "duration", "channel", "supervisions", "recording", "custom", "type"})
            mf.check_recording(c["recording"], c["id"])
            cu = c["custom"]
            self.assertEqual(cu["room_id"], rooms[c["id"]]["room_id"])
            self.assertEqual(cu["src_m"], list(rooms[c["id"]]["src_m"]))
            h, fs = tsrir.read_audio(c["recording"]["sources"][0]["source"])
            self.assertEqual(cu["T60_s"], tsrir.metrics(h[0], fs, rir_id=c["id"])["T60"])
            # The direct-path index is where sound arrives: distance / c, from the geometry alone.
            dist = math.dist(cu["src_m"], cu["mic_m"])
            self.assertLessEqual(abs(cu["direct_path_index"] - dist / 343.0 * fs), 2, c["id"])
            target = 0.6 if c["id"] != "r3" else 0.3
            self.assertLess(abs(cu["T60_s"] - target) / target, 0.2)

    def test_round_trip_to_kaldi_lists_augments_the_same(self):
        d = self.dir
        back = mf.import_rir_recordings(self.recordings, d + "/rir_list_back", cuts_jsonl=self.cuts)
        orig = tsrir.read_rir_list(d + "/rirs/rir_list")
        again = tsrir.read_rir_list(back)
        self.assertEqual([(e["rir_id"], e["room_id"], os.path.abspath(e["rxfilename"])) for e in orig],
                         [(e["rir_id"], e["room_id"], e["rxfilename"]) for e in again])
        # Noise: a Lhotse RecordingSet of noises -> Kaldi noise_list.
        write_wav16(d + "/n1.wav", 0.2 * np.random.default_rng(1).standard_normal(20000), 16000)
        write_text(d + "/noises.jsonl", json.dumps(mf.recording_dict("n1", d + "/n1.wav")) + "\n")
        noise_list = mf.import_noise_recordings(d + "/noises.jsonl", d + "/noise_list")
        self.assertEqual([(n["noise_id"], n["noise_type"]) for n in tsrir.read_noise_list(noise_list)],
                         [("n1", "point-source")])
        write_wav16(d + "/s.wav", speech_like(16000, 16000, 3), 16000)
        recs = {"u1": d + "/s.wav", "u2": "cat %s |" % (d + "/s.wav")}
        opts = dict(recordings=recs, seed=5, noise_start="random")
        a = tsrir.Augmenter(rir_set_parameters=[d + "/rirs/rir_list"], **opts)
        b = tsrir.Augmenter(rir_set_parameters=[back], **opts)
        for u in recs:
            for copy in (1, 2, 3):
                np.testing.assert_array_equal(a.augment(u, copy)[0], b.augment(u, copy)[0])
        # The imported noise list augments as the same list written by hand.
        write_text(d + "/noise_list_by_hand",
                   "--noise-id n1 --noise-type point-source --bg-fg-type background %s/n1.wav\n" % d)
        c = tsrir.Augmenter(rir_set_parameters=[back], noise_set_parameters=[noise_list], **opts)
        e = tsrir.Augmenter(rir_set_parameters=[back], noise_set_parameters=[d + "/noise_list_by_hand"], **opts)
        self.assertEqual(c.num_noises, 1)
        for u in recs:
            for copy in (1, 2, 3):
                self.assertEqual(c.plan(u, copy), e.plan(u, copy))
                np.testing.assert_array_equal(c.augment(u, copy)[0], e.augment(u, copy)[0])

    def test_data_dir_with_pipes(self):
        d = self.dir + "/data"
        os.makedirs(d, exist_ok=True)
        write_wav16(self.dir + "/a.wav", speech_like(24000, 16000, 4), 16000)
        write_text(d + "/wav.scp", "a %s\nb cat %s |\n" % (self.dir + "/a.wav", self.dir + "/a.wav"))
        write_text(d + "/utt2spk", "a s1\nb s1\n")
        write_text(d + "/text", "a HELLO\nb WORLD\n")
        recs, sups = mf.export_data_dir(d, self.dir + "/lhotse_data")
        rs = {r["id"]: r for r in mf.read_recordings(recs)}
        self.assertEqual(rs["b"]["sources"][0], {"type": "command", "channels": [0], "source": "cat %s" % (self.dir + "/a.wav")})
        self.assertEqual(rs["a"]["num_samples"], rs["b"]["num_samples"])
        self.assertEqual(mf.recording_rxfilename(rs["b"], "b"), "cat %s |" % (self.dir + "/a.wav"))
        ss = [s for s, _ in mf.read_jsonl(sups)]
        self.assertEqual([(s["id"], s["recording_id"], s["speaker"], s["text"], s["duration"]) for s in ss],
                         [("a", "a", "s1", "HELLO", 1.5), ("b", "b", "s1", "WORLD", 1.5)])
        with self.assertRaisesRegex(tsrir.Error, "exists"):
            mf.export_data_dir(d, self.dir + "/lhotse_data")

    def test_espnet_and_speechbrain_lists(self):
        recs = mf.read_recordings(self.recordings)
        fs = recs[0]["sampling_rate"]
        scp = mf.write_espnet_scp(self.recordings, self.dir + "/rirs.scp", sampling_rate=fs)
        with open(scp) as f:
            rows = [line.split() for line in f]
        self.assertEqual(rows, [[r["id"], r["sources"][0]["source"]] for r in recs])
        path = mf.write_speechbrain_csv(self.recordings, self.dir + "/rirs.csv", sampling_rate=fs)
        with open(path, newline="") as f:
            table = list(csv.DictReader(f))
        self.assertEqual([(t["ID"], float(t["duration"]), t["wav"]) for t in table],
                         [(r["id"], r["duration"], r["sources"][0]["source"]) for r in recs])


    def test_lists_are_at_the_corpus_rate_or_say_so(self):
        import warnings
        write_wav16(self.dir + "/r48.wav", np.r_[0.8, np.zeros(4799)], 48000)
        write_wav16(self.dir + "/r16.wav", np.r_[0.8, np.zeros(1599)], 16000)
        write_text(self.dir + "/mixed.scp", "r16 %s/r16.wav\nr48 %s/r48.wav\n" % (self.dir, self.dir))
        recs = self.dir + "/mixed_lhotse/recordings.jsonl"
        lines = [mf._json_line(mf.recording_dict(i, p)) for i, p in
                 (("r16", self.dir + "/r16.wav"), ("r48", self.dir + "/r48.wav"))]
        mf._write_lines(recs, lines, False)
        with self.assertRaisesRegex(tsrir.Error, r"'r48' at 48000 Hz.*resample_dir"):
            mf.write_espnet_scp(recs, self.dir + "/m.scp", sampling_rate=16000)
        self.assertFalse(os.path.exists(self.dir + "/m.scp"))
        scp = mf.write_espnet_scp(recs, self.dir + "/m.scp", sampling_rate=16000, resample_dir=self.dir + "/rs")
        with open(scp) as f:
            listed = dict(line.split() for line in f)
        self.assertEqual(listed["r16"], self.dir + "/r16.wav")
        self.assertEqual(listed["r48"], os.path.abspath(self.dir + "/rs/r48.wav"))
        x, fs = tsrir.read_audio(listed["r48"])
        self.assertEqual((fs, x.shape), (16000, (1, 1600)))
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            mf.write_speechbrain_csv(recs, self.dir + "/m.csv")
        messages = [str(w.message) for w in caught if issubclass(w.category, tsrir.TsrirWarning)]
        self.assertTrue(any("16000 Hz (1), 48000 Hz (1)" in m for m in messages), messages)


if __name__ == "__main__":
    unittest.main()
