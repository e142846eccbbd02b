#!/usr/bin/env python3
"""Far-field training data on the fly: a PyTorch DataLoader over a Kaldi data directory whose
items are reverberate-data's far-field copies, made in the loader's worker processes instead of
being written to disk first.

Example (the lists are reverberate-data's; any Kaldi data dir with a wav.scp):
  PYTHONPATH=build/python examples/python/farfield_dataloader.py \
      --rir-set-parameters "0.5, data/sim_rirs/rir_list" --noise-set-parameters data/noise/noise_list \
      --snrs 0:15 --seed 7 --copies 1 --num-workers 4 --epochs 2 data/train_clean

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


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("data_dir")
    p.add_argument("--rir-set-parameters", action="append", default=[])
    p.add_argument("--noise-set-parameters", action="append", default=[])
    p.add_argument("--snrs", default="1:2")
    p.add_argument("--speech-rvb-probability", type=float, default=1.0)
    p.add_argument("--noise-addition-probability", type=float, default=1.0)
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--prefix", default="rvb")
    p.add_argument("--copies", type=int, default=1)
    p.add_argument("--epochs", type=int, default=1)
    p.add_argument("--num-workers", type=int, default=4)
    p.add_argument("--batch-size", type=int, default=8)
    args = p.parse_args(argv)

    augmenter = tsrir.Augmenter(data_dir=args.data_dir, rir_set_parameters=args.rir_set_parameters,
                                noise_set_parameters=args.noise_set_parameters, snrs=args.snrs,
                                speech_rvb_probability=args.speech_rvb_probability,
                                noise_addition_probability=args.noise_addition_probability,
                                seed=args.seed, prefix=args.prefix)
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
