"""On-the-fly far-field copies of a Kaldi data directory, for PyTorch data loaders.

FarFieldDataset(data_dir, augmenter, copies=1) lists (copy, recording) pairs in reverberate-data's
order (copies 1..N, recordings in wav.scp byte order) and returns for each the far-field copy
that `reverberate-data --num-replications=N --write-wavs=...` writes for it, as a float32
torch tensor (full scale 1.0). Draws depend on (seed, copy, recording id) only, so the output
does not depend on num_workers, the worker an item lands in, or the order it is asked for; a new
epoch gets new draws with `dataset.set_epoch(e)` (copies e*N+1 .. e*N+N: what reverberate-data
would write as those copies).

Needs torch only for the tensors (python3-torch); without torch use .item_numpy(i).
Recordings only: segments are not cut (as reverberate-data, which works on recordings).
"""
import os

import numpy as np

from . import _tsrir


def read_wav_scp(data_dir):
    """(id, rxfilename) pairs of <data_dir>/wav.scp in byte order of the ids (Kaldi's sort -C)."""
    path = os.path.join(data_dir, "wav.scp")
    entries = {}
    with open(path, "rb") as f:
        for n, raw in enumerate(f, 1):
            line = raw.decode("utf-8").rstrip("\r\n")
            if not line.strip():
                continue
            parts = line.strip().split(None, 1)
            if len(parts) != 2:
                raise _tsrir.Error("%s:%d: expected '<recording-id> <rxfilename>'" % (path, n))
            if parts[0] in entries:
                raise _tsrir.Error("%s:%d: duplicate recording id '%s'" % (path, n, parts[0]))
            entries[parts[0]] = parts[1]
    return sorted(entries.items(), key=lambda kv: kv[0].encode("utf-8"))


try:
    import torch
    _Base = torch.utils.data.Dataset
except ImportError:  # pragma: no cover
    torch = None
    _Base = object


class FarFieldDataset(_Base):
    def __init__(self, data_dir, augmenter, copies=1):
        if copies < 1:
            raise _tsrir.Error("copies must be >= 1")
        self.recordings = read_wav_scp(data_dir)
        self.augmenter = augmenter
        self.copies = copies
        self.epoch = 0

    def set_epoch(self, epoch):
        self.epoch = int(epoch)

    def __len__(self):
        return self.copies * len(self.recordings)

    def key(self, index):
        """(copy, recording id, rxfilename) of item `index`."""
        if not 0 <= index < len(self):
            raise IndexError(index)
        copy = index // len(self.recordings) + 1 + self.epoch * self.copies
        rid, rx = self.recordings[index % len(self.recordings)]
        return copy, rid, rx

    def item_numpy(self, index):
        copy, rid, rx = self.key(index)
        samples, fs = self.augmenter.augment_rxfilename(rx, rid, copy)
        return {"id": self.augmenter.plan(rid, copy)["new_id"], "recording": rid, "copy": copy,
                "fs": fs, "audio": samples}

    def __getitem__(self, index):
        item = self.item_numpy(index)
        if torch is not None:
            item["audio"] = torch.from_numpy(np.ascontiguousarray(item["audio"]))
        return item


def pad_collate(items):
    """Batches items of different lengths: audio zero-padded to the longest, with lengths."""
    lengths = [len(i["audio"]) for i in items]
    audio = torch.zeros(len(items), max(lengths))
    for row, i in enumerate(items):
        audio[row, : lengths[row]] = i["audio"]
    return {"id": [i["id"] for i in items], "audio": audio, "lengths": torch.tensor(lengths),
            "fs": items[0]["fs"]}
