"""Manifests for the Python speech toolkits: Lhotse JSONL, ESPnet scp, SpeechBrain CSV.

Written from Lhotse's documented and source-defined formats (no Lhotse is installable here; the
tests check the schema and round trips, not Lhotse itself):
  - Recording (lhotse/audio/recording.py, docs/corpus.rst): {"id", "sources": [{"type": "file" |
    "command", "channels": [...], "source": ...}], "sampling_rate", "num_samples", "duration",
    "channel_ids"}. Lhotse builds it with Recording(**dict), so it takes no other keys: a
    RecordingSet of RIRs stays exactly that (usable as CutSet.reverb_rir(rir_recordings=...)).
  - MonoCut (lhotse/cut/mono.py, data.py): {"id", "start", "duration", "channel", "supervisions",
    "recording", "custom", "type": "MonoCut"}. Its free-form "custom" dict is where Lhotse keeps
    extra metadata, so the RIR metadata (room id, positions, T60/EDT/DRR/C50 from tsrir.metrics,
    the direct-path index (rir-metrics' ISO onset) and the peak index wav-reverberate and Lhotse
    shift by, which a reflection stronger than the direct sound moves) goes into a CutSet of one
    cut per RIR.
  - SupervisionSegment: {"id", "recording_id", "start", "duration", "channel", "text", "speaker"}.
Kaldi lists are read by the library's own parsers (tsrir.read_rir_list / read_noise_list /
read_data_dir). Files are written to a temporary name and renamed; an existing file is replaced
only with overwrite=True.
"""
import json
import math
import os
import shlex
import tempfile

import numpy as np

from . import _tsrir

RECORDING_KEYS = {"id", "sources", "sampling_rate", "num_samples", "duration", "channel_ids", "transforms"}
SOURCE_KEYS = {"type", "channels", "source", "video"}


def _write_lines(path, lines, overwrite):
    if os.path.exists(path) and not overwrite:
        raise _tsrir.Error("%s exists (pass overwrite=True to replace it)" % path)
    directory = os.path.dirname(os.path.abspath(path))
    os.makedirs(directory, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=os.path.basename(path) + ".tmp.", dir=directory)
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            for line in lines:
                f.write(line + "\n")
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.remove(tmp)
        raise
    return path


def _json_line(d):
    return json.dumps(d, ensure_ascii=False, allow_nan=False)


def _finite_or_none(v):
    return v if isinstance(v, (int, float)) and math.isfinite(v) else None


def recording_dict(rec_id, rxfilename):
    """A Lhotse Recording for a Kaldi rxfilename: a file ("file" source, absolute path) or a pipe
    ("command" source, the command without its '|')."""
    rx = rxfilename.strip()
    if rx.endswith("|"):
        samples, fs = _tsrir.read_audio(rx)
        channels, frames = samples.shape[0], samples.shape[1]
        source = {"type": "command", "channels": list(range(channels)), "source": rx[:-1].strip()}
    else:
        info = _tsrir.audio_info(rx)
        fs, channels, frames = info["sample_rate"], info["channels"], info["frames"]
        source = {"type": "file", "channels": list(range(channels)), "source": os.path.abspath(rx)}
    if fs != int(fs):
        raise _tsrir.Error("%s: sample rate %r is not an integer (Lhotse needs one)" % (rx, fs))
    return {"id": rec_id, "sources": [source], "sampling_rate": int(fs), "num_samples": int(frames),
            "duration": frames / fs, "channel_ids": list(range(channels))}


def check_recording(d, where):
    """Raises Error (naming `where`) unless `d` is a Lhotse Recording dict this module can use."""
    if not isinstance(d, dict):
        raise _tsrir.Error("%s: not a JSON object" % where)
    extra = set(d) - RECORDING_KEYS
    if extra:
        raise _tsrir.Error("%s: keys Lhotse's Recording does not have: %s" % (where, ", ".join(sorted(extra))))
    for key, kind in (("id", str), ("sources", list), ("sampling_rate", int), ("num_samples", int),
                      ("duration", (int, float))):
        if not isinstance(d.get(key), kind) or isinstance(d.get(key), bool):
            raise _tsrir.Error("%s: '%s' missing or not %s" % (where, key, getattr(kind, "__name__", "a number")))
    if not d["sources"]:
        raise _tsrir.Error("%s: no sources" % where)
    for s in d["sources"]:
        if not isinstance(s, dict) or set(s) - SOURCE_KEYS or not {"type", "channels", "source"} <= set(s):
            raise _tsrir.Error("%s: a source must be {type, channels, source}" % where)
    return d


def recording_rxfilename(d, where):
    """The Kaldi rxfilename of a single-source Recording ("file" -> path, "command" -> "cmd |")."""
    if len(d["sources"]) != 1:
        raise _tsrir.Error("%s: %d sources; only single-source recordings map to a Kaldi list entry"
                           % (where, len(d["sources"])))
    s = d["sources"][0]
    if s["type"] == "file":
        return s["source"]
    if s["type"] == "command":
        return s["source"] + " |"
    raise _tsrir.Error("%s: source type '%s' has no Kaldi rxfilename (file and command do)" % (where, s["type"]))


def read_jsonl(path):
    """[(dict, "path:line")] of a JSONL manifest (blank lines skipped)."""
    out = []
    with open(path, encoding="utf-8") as f:
        for n, line in enumerate(f, 1):
            if not line.strip():
                continue
            where = "%s:%d" % (path, n)
            try:
                out.append((json.loads(line), where))
            except ValueError as e:
                raise _tsrir.Error("%s: not JSON (%s)" % (where, e))
    return out


def read_recordings(path):
    """A Lhotse RecordingSet JSONL as a list of checked Recording dicts."""
    return [check_recording(d, where) for d, where in read_jsonl(path)]


def export_rir_set(rir_list, out_dir, room_list=None, definition="iso", overwrite=False):
    """A Kaldi rir_list (e.g. rir-simulate's) as <out_dir>/recordings.jsonl (Lhotse RecordingSet)
    and <out_dir>/cuts.jsonl (one MonoCut per RIR, metadata in "custom": room_id, T60_s, EDT_s,
    DRR_db, C50_db (tsrir.metrics with `definition`), direct_path_index (ISO onset), peak_index
    (largest sample), and with the room list
    rir-simulate was given: room_m, src_m, mic_m, room_list_line). Returns the two paths."""
    rooms = {r["rir_id"]: r for r in _tsrir.read_room_list(room_list)} if room_list else {}
    recordings, cuts = [], []
    for e in _tsrir.read_rir_list(rir_list):
        rec = recording_dict(e["rir_id"], e["rxfilename"])
        h, fs = _tsrir.read_audio(e["rxfilename"])
        from . import metrics  # the package's metrics(): rir-metrics' JSON row
        m = metrics(h[0], fs, definition=definition, rir_id=e["rir_id"])
        custom = {"room_id": e["room_id"], "T60_s": _finite_or_none(m["T60"]), "EDT_s": _finite_or_none(m["EDT"]),
                  "DRR_db": _finite_or_none(m["DRR"]), "C50_db": _finite_or_none(m["C50"]),
                  "metrics_definition": definition,
                  "direct_path_index": int(_tsrir.rir_onset_index(h[0], fs)),
                  "peak_index": int(_tsrir.rir_shift_index(h[0], fs))}
        r = rooms.get(e["rir_id"])
        if r:
            custom.update(room_m=list(r["room_m"]), src_m=list(r["src_m"]), mic_m=list(r["mic_m"]),
                          room_list_line=r["line"])
        recordings.append(_json_line(rec))
        cuts.append(_json_line({"id": e["rir_id"], "start": 0.0, "duration": rec["duration"], "channel": 0,
                                "supervisions": [], "recording": rec, "custom": custom, "type": "MonoCut"}))
    return (_write_lines(os.path.join(out_dir, "recordings.jsonl"), recordings, overwrite),
            _write_lines(os.path.join(out_dir, "cuts.jsonl"), cuts, overwrite))


def export_data_dir(data_dir, out_dir, overwrite=False):
    """A Kaldi data dir (e.g. reverberate-data's output) as <out_dir>/recordings.jsonl and
    <out_dir>/supervisions.jsonl (Lhotse RecordingSet and SupervisionSet). Pipes in wav.scp become
    "command" sources. Returns the two paths."""
    d = _tsrir.read_data_dir(data_dir)
    recordings = {rid: recording_dict(rid, rx) for rid, rx in sorted(d["wav_scp"].items())}
    sups = []
    for utt, spk in sorted(d["utt2spk"].items()):
        if d["segments"]:
            rid, start, end = d["segments"][utt]
            duration = end - start
        else:
            rid, start, duration = utt, 0.0, recordings[utt]["duration"]
        s = {"id": utt, "recording_id": rid, "start": start, "duration": duration, "channel": 0, "speaker": spk}
        if utt in d["text"]:
            s["text"] = d["text"][utt]
        sups.append(_json_line(s))
    return (_write_lines(os.path.join(out_dir, "recordings.jsonl"),
                         [_json_line(r) for r in recordings.values()], overwrite),
            _write_lines(os.path.join(out_dir, "supervisions.jsonl"), sups, overwrite))


def import_rir_recordings(recordings_jsonl, rir_list, cuts_jsonl=None, overwrite=False):
    """A Lhotse RecordingSet of RIRs as a Kaldi rir_list for reverberate-data / tsrir.Augmenter.
    Room ids come from the "room_id" custom field of `cuts_jsonl` (export_rir_set's) when given,
    else each RIR is its own room."""
    rooms = {}
    if cuts_jsonl:
        for c, where in read_jsonl(cuts_jsonl):
            rooms[c["id"]] = (c.get("custom") or {}).get("room_id", c["id"])
    lines = []
    for rec, (_, where) in zip(read_recordings(recordings_jsonl), read_jsonl(recordings_jsonl)):
        lines.append(_tsrir.format_rir_list_line(rec["id"], rooms.get(rec["id"], rec["id"]),
                                                 recording_rxfilename(rec, where)))
    return _write_lines(rir_list, lines, overwrite)


def import_noise_recordings(recordings_jsonl, noise_list, noise_type="point-source", bg_fg_type="background",
                            room_linkage=None, overwrite=False):
    """A Lhotse RecordingSet of noises as a Kaldi noise_list (Kaldi's options: --noise-type,
    --bg-fg-type, --room-linkage for isotropic noises)."""
    if noise_type == "isotropic" and not room_linkage:
        raise _tsrir.Error("isotropic noises need room_linkage (the room they were recorded in)")
    lines = []
    for rec, (_, where) in zip(read_recordings(recordings_jsonl), read_jsonl(recordings_jsonl)):
        words = ["--noise-id", rec["id"], "--noise-type", noise_type, "--bg-fg-type", bg_fg_type]
        if room_linkage:
            words += ["--room-linkage", room_linkage]
        words.append(recording_rxfilename(rec, where))
        lines.append(" ".join(shlex.quote(w) for w in words))
    path = _write_lines(noise_list, lines, overwrite)
    _tsrir.read_noise_list(path)  # the library reads back what was written
    return path


def _at_corpus_rate(recordings_jsonl, sampling_rate, resample_dir, what):
    """[(id, file path, duration s)] of a RecordingSet for a toolkit that uses the files as they are
    (ESPnet's and SpeechBrain's reverberation and noise addition do not resample them).

    sampling_rate (Hz): the corpus's rate. Recordings at another rate are written, resampled with
    the programs' resampler, as 16-bit WAVs <resample_dir>/<id>.wav and listed instead; without
    resample_dir they are an error naming them. sampling_rate None: the files are listed as they are,
    and a TsrirWarning says at which rates (so a 48 kHz RIR list for a 16 kHz corpus never goes
    unremarked)."""
    import warnings
    from . import TsrirWarning, read_audio, resample, write_wav
    rows, rates, other = [], {}, []
    for rec, (_, where) in zip(read_recordings(recordings_jsonl), read_jsonl(recordings_jsonl)):
        path = recording_rxfilename(rec, where)
        if path.endswith("|"):
            raise _tsrir.Error("%s: %s needs a file, not a command" % (where, what))
        rates.setdefault(rec["sampling_rate"], []).append(rec["id"])
        if sampling_rate is not None and rec["sampling_rate"] != sampling_rate:
            other.append((rec, path))
        rows.append([rec["id"], path, rec["duration"]])
    if sampling_rate is None:
        warnings.warn("%s lists %s as they are, at %s: %s does not resample them; give sampling_rate=<the "
                      "corpus's rate> to have them checked or resampled"
                      % (os.path.basename(recordings_jsonl), what,
                         ", ".join("%d Hz (%d)" % (r, len(ids)) for r, ids in sorted(rates.items())), what),
                      TsrirWarning, stacklevel=3)
        return rows
    if other and resample_dir is None:
        raise _tsrir.Error("%s: %d recording(s) not at the corpus rate %d Hz (e.g. '%s' at %d Hz): give "
                           "resample_dir= to write %d Hz copies, or list recordings at the corpus rate"
                           % (recordings_jsonl, len(other), sampling_rate, other[0][0]["id"],
                              other[0][0]["sampling_rate"], sampling_rate))
    resampled = {}
    for rec, path in other:
        samples, fs = read_audio(path)
        out = os.path.join(resample_dir, rec["id"] + ".wav")
        os.makedirs(resample_dir, exist_ok=True)
        write_wav(out, np.stack([resample(c, fs, sampling_rate) for c in samples]), sampling_rate)
        resampled[rec["id"]] = os.path.abspath(out)
    return [[i, resampled.get(i, p), d] for i, p, d in rows]


def write_espnet_scp(recordings_jsonl, scp, sampling_rate=None, resample_dir=None, overwrite=False):
    """ESPnet's --rir_scp / --noise_scp: '<id> <path>' per line, at the corpus's sampling_rate (Hz):
    recordings at another rate are resampled into resample_dir (see _at_corpus_rate); without
    sampling_rate they are listed as they are, with a TsrirWarning naming their rates."""
    rows = _at_corpus_rate(recordings_jsonl, sampling_rate, resample_dir, "ESPnet's scp")
    return _write_lines(scp, ["%s %s" % (i, p) for i, p, _ in rows], overwrite)


def write_speechbrain_csv(recordings_jsonl, csv_path, sampling_rate=None, resample_dir=None, overwrite=False):
    """SpeechBrain's RIR / noise CSV for AddReverb / AddNoise: ID,duration,wav, at the corpus's
    sampling_rate (Hz) as write_espnet_scp."""
    import csv
    import io
    rows = []
    for i, p, duration in _at_corpus_rate(recordings_jsonl, sampling_rate, resample_dir, "SpeechBrain's CSV"):
        buf = io.StringIO()
        csv.writer(buf, lineterminator="").writerow([i, repr(duration), p])
        rows.append(buf.getvalue())
    return _write_lines(csv_path, ["ID,duration,wav"] + rows, overwrite)
