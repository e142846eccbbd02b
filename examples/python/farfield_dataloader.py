#!/usr/bin/env python3
"""Far-field training data on the fly: a PyTorch DataLoader over a Kaldi data directory whose
items are reverberate-data's far-field copies, made in the loader's worker processes instead of
being written to disk first.

Example (the lists are reverberate-data's; any Kaldi data dir with a wav.scp; options and the
data dir in any order):
  python3 examples/python/farfield_dataloader.py \
      --rir-set-parameters "0.5, data/sim_rirs/rir_list" --noise-set-parameters data/noise/noise_list \
      --random-seed 7 --copies 1 --num-workers 4 --epochs 2 data/train_clean

Options other than --copies, --epochs, --num-workers and --batch-size are reverberate-data's own
(those that decide what happens to a recording), with its defaults (--help lists them).

Each batch is padded audio + lengths (tsrir.data.pad_collate). Epoch e uses reverberate-data's
copies e*C+1..e*C+C, so every epoch sees new rooms and noises and a given (seed, epoch, id) always
gives the same audio, whatever --num-workers. Prints one line per epoch with the throughput.
"""
import argparse
import os
import time

import torch

import tsrir
from tsrir.data import FarFieldDataset, pad_collate


def one_thread(_worker_id):
    torch.set_num_threads(1)


def parse_bool(text):
    if text.lower() in ("true", "1", "yes"):
        return True
    if text.lower() in ("false", "0", "no"):
        return False
    raise argparse.ArgumentTypeError("expected true or false, got %r" % text)


def add_reverberate_data_options(parser):
    """reverberate-data's own options, typed by the library's defaults (tsrir.Augmenter.option_defaults()):
    registered with argparse so that their values and the data dir may come in any order."""
    group = parser.add_argument_group("reverberate-data's options (its defaults; see reverberate-data --help)")
    for key, default in sorted(tsrir.Augmenter.option_defaults().items()):
        flags = ["--random-seed", "--seed"] if key == "seed" else ["--" + key.replace("_", "-")]
        if isinstance(default, list):
            group.add_argument(*flags, dest=key, action="append", default=None, metavar="VALUE",
                               help="repeatable")
        elif isinstance(default, bool):
            group.add_argument(*flags, dest=key, type=parse_bool, default=None, metavar="true|false",
                               help="default %s" % str(default).lower())
        else:
            group.add_argument(*flags, dest=key, type=type(default), default=None, help="default %r" % (default,))
    return sorted(tsrir.Augmenter.option_defaults())


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("data_dir", help="a Kaldi data dir (its wav.scp; reco2dur when present)")
    p.add_argument("--copies", type=int, default=1, help="far-field copies per recording and epoch")
    p.add_argument("--epochs", type=int, default=1)
    p.add_argument("--num-workers", type=int, default=4, help="DataLoader worker processes")
    p.add_argument("--batch-size", type=int, default=8)
    keys = add_reverberate_data_options(p)
    args = p.parse_args(argv)
    options = {k: getattr(args, k) for k in keys if getattr(args, k) is not None}
    options.setdefault("prefix", "rvb")

    augmenter = tsrir.Augmenter(data_dir=args.data_dir, **options)
    dataset = FarFieldDataset(augmenter, copies=args.copies)
    # One thread per worker: the C++ work runs without the GIL, the workers are the parallelism.
    loader = torch.utils.data.DataLoader(dataset, batch_size=args.batch_size, num_workers=args.num_workers,
                                         collate_fn=pad_collate, shuffle=True,
                                         worker_init_fn=one_thread,
                                         persistent_workers=False)
    for epoch in range(args.epochs):
        dataset.set_epoch(epoch)
        start, utterances, audio_s = time.time(), 0, 0.0
        for batch in loader:
            utterances += len(batch["id"])
            audio_s += float(batch["lengths"].sum()) / batch["fs"]
        wall = time.time() - start
        print("epoch %d: %d utterances, %.1f s of audio in %.2f s wall: %.1f utterances/s with %d workers"
              % (epoch, utterances, audio_s, wall, utterances / max(wall, 1e-9), args.num_workers), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
