"""On-the-fly far-field copies of a Kaldi data directory, for PyTorch data loaders.

FarFieldDataset(augmenter, copies=1) lists the (copy, recording) pairs of a tsrir.Augmenter made on
a Kaldi data dir (tsrir.Augmenter(data_dir=..., ...)) in reverberate-data's order (copies 1..N,
recordings in wav.scp byte order) and returns for each the far-field copy
that `reverberate-data --num-replications=N --write-wavs=...` writes for it, as a float32
torch tensor (full scale 1.0). Draws depend on (seed, copy, recording id) only, so the output
does not depend on num_workers, the worker an item lands in, or the order it is asked for; a new
epoch gets new draws with `dataset.set_epoch(e)` (copies e*N+1 .. e*N+N: what reverberate-data
would write as those copies).

Needs torch only for the tensors (python3-torch); without torch use .item_numpy(i).
Recordings only: segments are not cut (as reverberate-data, which works on recordings).
"""
import numpy as np

from . import _convert
from . import _tsrir


try:
    import torch
    _Base = torch.utils.data.Dataset
except ImportError:  # pragma: no cover
    torch = None
    _Base = object


class FarFieldDataset(_Base):
    """A map-style dataset of far-field copies: len = copies x recordings; item i is a dict
    {"id": reverberate-data's new id, "recording", "copy", "fs": int Hz, "audio": float32 tensor
    (samples,)} (numpy without torch). augmenter: a tsrir.Augmenter; copies: per recording and epoch;
    set_epoch(e) moves to copies e*copies+1 .. e*copies+copies."""

    def __init__(self, augmenter, copies=1):
        copies = _convert.number(copies, "copies", integer=True, minimum=1)
        self.recordings = augmenter.recordings
        self.augmenter = augmenter
        self.copies = copies
        self.epoch = 0

    def set_epoch(self, epoch):
        """Moves to epoch `epoch` (int >= 0): its items are copies epoch*copies+1 .. epoch*copies+copies
        (new draws; what reverberate-data writes as those copies)."""
        self.epoch = _convert.number(epoch, "epoch", integer=True, minimum=0)

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
        """Item `index` without torch: the dict of __getitem__ with "audio" a float32 numpy array
        (samples,) at "fs" (int Hz), full scale 1.0."""
        copy, rid, rx = self.key(index)
        samples, fs = self.augmenter.augment(rid, copy)
        return {"id": self.augmenter.plan(rid, copy)["new_id"], "recording": rid, "copy": copy,
                "fs": fs, "audio": samples}

    def __getitem__(self, index):
        item = self.item_numpy(index)
        if torch is not None:
            item["audio"] = torch.from_numpy(np.ascontiguousarray(item["audio"]))
        return item


def pad_collate(items):
    """Batches items of different lengths: {"id": [str], "audio": float32 (batch, max samples), zero-padded,
    "lengths": int64 (batch,) samples, "fs": int Hz}."""
    lengths = [len(i["audio"]) for i in items]
    audio = torch.zeros(len(items), max(lengths))
    for row, i in enumerate(items):
        audio[row, : lengths[row]] = i["audio"]
    return {"id": [i["id"] for i in items], "audio": audio, "lengths": torch.tensor(lengths),
            "fs": items[0]["fs"]}
