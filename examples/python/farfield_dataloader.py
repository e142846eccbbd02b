#!/usr/bin/env python3
"""Far-field training data on the fly: a PyTorch DataLoader over a Kaldi data directory whose
items are reverberate-data's far-field copies, made in the loader's worker processes instead of
being written to disk first.

Example (the lists are reverberate-data's; any Kaldi data dir with a wav.scp):
  PYTHONPATH=build/python examples/python/farfield_dataloader.py \
      --rir-set-parameters "0.5, data/sim_rirs/rir_list" --noise-set-parameters data/noise/noise_list \
      --random-seed 7 --copies 1 --num-workers 4 --epochs 2 data/train_clean

Options other than --copies, --epochs, --num-workers and --batch-size are reverberate-data's own
(those that decide what happens to a recording), with its defaults.

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


def reverberate_data_options(words):
    """reverberate-data's own options ("--name=value" or "--name value") as Augmenter keywords,
    typed by the library's defaults (tsrir.Augmenter.option_defaults())."""
    defaults = tsrir.Augmenter.option_defaults()
    options, i = {}, 0
    while i < len(words):
        word = words[i]
        if not word.startswith("--"):
            raise SystemExit("unexpected argument %r" % word)
        name, eq, value = word[2:].partition("=")
        if not eq:
            i += 1
            if i == len(words):
                raise SystemExit("--%s needs a value" % name)
            value = words[i]
        key = "seed" if name == "random-seed" else name.replace("-", "_")
        if key not in defaults:
            raise SystemExit("unknown option --%s (reverberate-data options here: %s)"
                             % (name, ", ".join(sorted(defaults))))
        default = defaults[key]
        if isinstance(default, list):
            options.setdefault(key, []).append(value)
        elif isinstance(default, bool):
            options[key] = value.lower() in ("true", "1", "yes")
        else:
            options[key] = type(default)(value)
        i += 1
    return options


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter,
                                epilog="Any other --option is reverberate-data's (see reverberate-data --help).")
    p.add_argument("data_dir")
    p.add_argument("--copies", type=int, default=1)
    p.add_argument("--epochs", type=int, default=1)
    p.add_argument("--num-workers", type=int, default=4)
    p.add_argument("--batch-size", type=int, default=8)
    args, rest = p.parse_known_args(argv)
    options = reverberate_data_options(rest)
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
