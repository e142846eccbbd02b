"""tsrir: far-field speech augmentation from Python.

Thin wrappers over the C++ extension ``tsrir._tsrir``, which calls the same library functions as
the programs (rir-simulate, rir-metrics, wav-reverberate, rir-eq apply, reverberate-data): there
is no second implementation here, only argument conversion. Arrays are float32, full scale 1.0.
PyTorch: tsrir.data.FarFieldDataset (imports torch; `import tsrir` does not).
"""
import json as _json

from . import _tsrir
from ._tsrir import (Augmenter, Error, audio_info, encode_wav, eq_apply, format_rir_list_line,
                     model_components_help, read_audio, read_noise_list, read_rir_list, read_data_dir,
                     read_room_list, resample, rir_onset_index, rir_shift_index, room_list_keys_help, room_list_line,
                     write_wav)

__all__ = ["Augmenter", "Error", "audio_info", "format_rir_list_line", "read_noise_list",
           "read_rir_list", "read_room_list", "read_data_dir", "rir_onset_index", "rir_shift_index", "encode_wav", "eq_apply", "metrics", "read_audio", "resample",
           "reverberate", "simulate", "write_wav", "room_list_line", "model_components_help",
           "room_list_keys_help"]


def _length_text(length):
    if isinstance(length, str):
        return length
    return repr(float(length))


def simulate(room, src, mic, fs=16000, t60=None, absorption=None, scattering=None, model="gas",
             seed=0, length=1.0, rir_id="rir", extra=None):
    """One RIR from rir-simulate's geometric model, as a float32 array.

    room, src, mic: (x, y, z) in metres. t60 (s) or absorption (energy coefficient), each one
    value or 8 octave-band values (62.5 Hz .. 8 kHz); neither: absorption 0.2. extra: more
    room-list keys, e.g. {"absorption.floor": 0.5, "temperature": 25, "room-id": "r1"}.
    length: seconds or "auto". The stochastic part is seeded by (seed, rir_id), as in
    rir-simulate, so the same line, fs, model, length and seed give rir-simulate's samples.
    """
    line = _tsrir.room_list_line(room, src, mic, t60, absorption, scattering, rir_id, extra or {})
    return _tsrir.simulate_line(line, float(fs), model, int(seed), _length_text(length))


def simulate_line(line, fs=16000, model="gas", seed=0, length=1.0):
    """Renders one rir-simulate room-list line ('<rir-id> room=.. src=.. mic=.. [key=value ...]')."""
    return _tsrir.simulate_line(line, float(fs), model, int(seed), _length_text(length))


def metrics(rir, fs, definition="iso", rir_id="rir", **options):
    """rir-metrics of one RIR: the dict that `rir-metrics --format=json` prints for it
    (T60, EDT, DRR, C50, per-band T20/T30/EDT/RT/level, broadband, warnings); NaN where a value
    cannot be measured. options: lundeby, direct_pre_ms, direct_post_ms, clarity_ms, onset_db."""
    text = _tsrir.metrics_json(rir, float(fs), definition, rir_id=rir_id, **options)
    row = _json.loads(text)["rirs"][0]
    return _nan_for_null(row)


def _nan_for_null(value):
    if value is None:
        return float("nan")
    if isinstance(value, dict):
        return {k: (_nan_for_null(v) if k != "warnings" else v) for k, v in value.items()}
    return value


def reverberate(speech, rir, fs, noise=None, snr_db=None, shift="peak", normalize=True, volume=0.0,
                duration_s=0.0, start_time_s=None, offset_s=None, snr_reference="early",
                loop_noise=False, multi_channel_output=False, input_channel=0, rir_channel=0,
                noise_channel=0, rir_fs=None, noise_fs=None):
    """wav-reverberate on arrays: x_f = (x * h) + sum_i scale_i n_i, then shift and normalise.

    speech: 1-D or (channels, n); rir: None (no reverberation), 1-D or (channels, n); noise:
    None, one array or a list of arrays; snr_db, start_time_s, offset_s: one number or one per
    noise. shift: "peak" (wav-reverberate --shift-output=true: advance by the RIR's signed
    maximum, Kaldi's direct-path estimate, which a reflection stronger than the direct sound
    moves), "direct" (the same output advanced to the direct sound's onset instead:
    tsrir.rir_onset_index, rir-metrics' ISO onset) or None (--shift-output=false: the full
    convolution).
    rir_fs / noise_fs: their rates when they differ from fs (resampled as the program does).
    Returns 1-D float32 (2-D with multi_channel_output). tsrir.encode_wav(result, fs) is the
    program's output file byte for byte.
    """
    direct = shift == "direct"
    if shift in ("peak", True):
        shift_output = True
    elif shift in (None, False, "none") or direct:
        shift_output = False
    else:
        raise Error("shift must be 'peak', 'direct' or None, got %r" % (shift,))
    if direct and rir is not None:
        if duration_s:
            raise Error("shift='direct' with duration_s is not supported (use shift='peak' or trim the result)")
        import numpy as _np
        rir = _np.asarray(rir, dtype=_np.float32)
        if rir_fs and rir_fs != fs:  # the same resampler the library would apply inside
            rir = (resample(rir, rir_fs, fs) if rir.ndim == 1
                   else _np.stack([resample(c, rir_fs, fs) for c in rir]))
            rir_fs = None
    out = _tsrir.reverberate_channels(
        speech, rir, float(fs), noise, snr_db, start_time_s, offset_s, shift_output, normalize,
        float(volume), float(duration_s), snr_reference, loop_noise, multi_channel_output,
        input_channel, rir_channel, noise_channel, float(rir_fs or 0), float(noise_fs or 0))
    if direct and rir is not None:
        # wav-reverberate's output with its shift moved from the RIR's largest sample to the
        # direct sound's onset (rir-metrics' ISO onset): the same full-length signal and gain
        # (the library normalises over the whole convolution either way), another window of it.
        import numpy as _np
        n = _np.atleast_2d(_np.asarray(speech)).shape[1]
        rirs = _np.atleast_2d(rir)
        windows = []
        for c in range(out.shape[0]):
            h = rirs[c] if multi_channel_output else rirs[rir_channel]
            onset = rir_onset_index(h, fs)
            windows.append(out[c, onset:onset + n])
        out = _np.stack(windows)
    return out if multi_channel_output else out[0]
