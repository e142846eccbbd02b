"""tsrir.data.FarFieldDataset in a torch DataLoader with 4 worker processes: every item equals the
wav reverberate-data --write-wavs writes for the same seed, copy and recording id (after the same
16-bit encoding), for two epochs (copies 1-2 and 3-4), in any order; and the example script runs.
Skipped (77) without python3-torch."""
import os
import shutil
import subprocess
import sys
import unittest

from tsrir_testlib import np, program, read_wav16, run, temp_dir
import tsrir

try:
    import torch
except ImportError:
    print("skipped: python3-torch is not installed (apt-get install python3-torch)")
    sys.exit(77)

from tsrir.data import FarFieldDataset, pad_collate  # noqa: E402
from test_augmenter import make_data, program_options, read_scp, settings  # noqa: E402


class FarField(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        torch.set_num_threads(1)
        cls.dir = d = temp_dir("torch")
        make_data(d)
        opts = [o for o in program_options(d) if not o.startswith("--num-replications")]
        run([program("reverberate-data")] + opts + ["--num-replications=4", "--write-wavs=%s/wavs" % d,
                                                     d + "/in", d + "/out"])
        cls.wav_scp = read_scp(d + "/out/wav.scp")

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.dir, ignore_errors=True)

    def test_four_workers_equal_reverberate_data(self):
        dataset = FarFieldDataset(tsrir.Augmenter(**settings(self.dir)), copies=2)
        self.assertEqual(len(dataset), 12)
        seen = set()
        for epoch in (0, 1):
            dataset.set_epoch(epoch)
            loader = torch.utils.data.DataLoader(dataset, batch_size=None, num_workers=4, shuffle=True,
                                                 generator=torch.Generator().manual_seed(epoch))
            for item in loader:
                self.assertIsInstance(item["audio"], torch.Tensor)
                expected, fs = read_wav16(self.wav_scp[item["id"]])
                got, _ = read_wav16(tsrir.encode_wav(item["audio"].numpy(), item["fs"]))
                np.testing.assert_array_equal(got, expected, item["id"])
                seen.add(item["id"])
        self.assertEqual(seen, set(self.wav_scp))  # copies 1..4 of every recording, each once

    def test_arguments_are_checked_by_name(self):
        augmenter = tsrir.Augmenter(**settings(self.dir))
        with self.assertRaisesRegex(TypeError, "copies: expected an integer"):
            FarFieldDataset(augmenter, copies="2")
        with self.assertRaisesRegex(ValueError, "copies: must be >= 1"):
            FarFieldDataset(augmenter, copies=0)
        with self.assertRaisesRegex(ValueError, "epoch: must be >= 0"):
            FarFieldDataset(augmenter).set_epoch(-1)
        self.assertEqual(FarFieldDataset(augmenter, copies=np.int64(2)).copies, 2)

    def test_batches(self):
        dataset = FarFieldDataset(tsrir.Augmenter(**settings(self.dir)))
        loader = torch.utils.data.DataLoader(dataset, batch_size=4, num_workers=2, collate_fn=pad_collate)
        batches = list(loader)
        self.assertEqual(sum(len(b["id"]) for b in batches), 6)
        b = batches[0]
        self.assertEqual(b["audio"].shape, (4, int(b["lengths"].max())))
        for row, n in enumerate(b["lengths"].tolist()):
            self.assertTrue(torch.all(b["audio"][row, n:] == 0))

    def test_example_script_runs(self):
        src = os.environ.get("TSRIR_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
        opts = [o for o in program_options(self.dir) if not o.startswith("--num-replications")]
        # As README prints it: options with their values as separate words, the data dir last.
        words = [w for o in opts for w in (o.split("=", 1) if o.startswith("--") and "=" in o else [o])]
        args = [sys.executable, os.path.join(src, "examples/python/farfield_dataloader.py"),
                "--num-workers", "4", "--epochs", "2", "--batch-size", "2"] + words + [self.dir + "/in"]
        out = subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=240)
        self.assertEqual(out.returncode, 0, out.stderr)
        self.assertIn("epoch 1: 6 utterances", out.stdout)


if __name__ == "__main__":
    unittest.main()
