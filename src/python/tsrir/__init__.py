"""tsrir: far-field speech augmentation from Python.

Thin wrappers over the C++ extension ``tsrir._tsrir``, which calls the same library functions as
the programs (rir-simulate, rir-metrics, wav-reverberate, rir-eq apply, reverberate-data): there
is no second implementation here, only argument conversion (tsrir/_convert.py).

Conventions of every function:
  * signals are float32, full scale 1.0 (an int16 sample s is s / 32768); shapes are written
    (samples,) for one channel and (channels, samples) for several;
  * arrays may be numpy arrays, sequences or torch tensors; a function given a tensor returns
    tensors on the same device, with the same floating dtype;
  * sampling rates (fs, in Hz) are returned as int;
  * a wrong kind of argument raises TypeError, a wrong value ValueError (tsrir.Error, a subclass, for
    what the library rejects: a bad file, list line or option), both naming the argument;
  * the library's warnings go through Python's `warnings` as tsrir.TsrirWarning.
PyTorch: tsrir.data.FarFieldDataset (imports torch; `import tsrir` does not).
"""
import json as _json

from . import _tsrir
from ._convert import TsrirWarning
from . import _convert as _c
from ._tsrir import Error

__all__ = ["Augmenter", "Error", "TsrirWarning", "audio_info", "encode_wav", "eq_apply", "format_rir_list_line",
           "metrics", "model_components_help", "read_audio", "read_data_dir", "read_noise_list", "read_rir_list",
           "read_room_list", "resample", "reverberate", "rir_onset_index", "rir_shift_index", "room_list_keys_help",
           "room_list_line", "simulate", "simulate_line", "write_wav"]


# ---- audio ---------------------------------------------------------------------------------

def read_audio(rxfilename):
    """Reads audio as the programs do: a file (WAV, FLAC, Ogg, ... any rate), '-' (stdin) or a Kaldi
    pipe 'command |'.

    Returns (samples, fs): samples float32 numpy (channels, samples), full scale 1.0; fs int, Hz.
    """
    samples, fs = _c.call(_tsrir.read_audio, _c.path(rxfilename, "rxfilename"))
    return samples, _c.rate_out(fs)


def audio_info(path):
    """The header of an audio file: {"sample_rate": int Hz, "channels": int, "frames": int, "format": str}."""
    info = _c.call(_tsrir.audio_info, _c.path(path, "path"))
    info["sample_rate"] = _c.rate_out(info["sample_rate"])
    return info


def encode_wav(samples, fs, format="int16"):
    """The WAV file the programs would write, as bytes.

    samples: (samples,) or (channels, samples), full scale 1.0; fs: Hz; format: 'int16' (rounded to
    nearest and clipped, as every program writes) or 'float' (32-bit float WAV)."""
    x = _c.array(samples, "samples", (1, 2), "(samples,) or (channels, samples)")
    return _c.call(_tsrir.encode_wav, x, _c.sample_rate(fs), _c.text(format, "format", ("int16", "float")))


def write_wav(path, samples, fs, format="int16"):
    """Writes a WAV file atomically (a temporary name, then renamed), as the programs do.

    samples: (samples,) or (channels, samples), full scale 1.0; fs: Hz; format: 'int16' or 'float'."""
    x = _c.array(samples, "samples", (1, 2), "(samples,) or (channels, samples)")
    _c.call(_tsrir.write_wav, _c.path(path, "path"), x, _c.sample_rate(fs),
            _c.text(format, "format", ("int16", "float")))


def resample(samples, from_hz, to_hz):
    """Resamples one channel with libsox's 'rate -v' (the resampler every program uses).

    samples: (samples,) at from_hz; from_hz, to_hz: rates in Hz. Returns (round(samples * to_hz /
    from_hz),) float32 (a tensor for a tensor input)."""
    like = _c.Like(samples)
    x = _c.array(samples, "samples")
    return like(_c.call(_tsrir.resample, x, _c.sample_rate(from_hz, "from_hz"), _c.sample_rate(to_hz, "to_hz")))


# ---- simulation ----------------------------------------------------------------------------

def _length_text(length):
    if isinstance(length, str):
        return _c.text(length, "length", ("auto",))
    return repr(_c.number(length, "length", "s", above=0))


def _band_values(value, name, unit):
    if value is None:
        return None
    return _c.numbers(value, name, unit, count=(1, 8))


def room_list_line(room, src, mic, t60=None, absorption=None, scattering=None, rir_id="rir", extra=None):
    """The rir-simulate room-list line that simulate() renders for these arguments (see simulate)."""
    extra = {} if extra is None else extra
    if not isinstance(extra, dict):
        raise TypeError("extra: expected a dict of room-list keys, got %s" % type(extra).__name__)
    for key, value in extra.items():
        _c.text(key, "extra key")
        if not isinstance(value, str):
            _c.numbers(value, "extra[%r]" % key)
    return _c.call(_tsrir.room_list_line, _c.position(room, "room"), _c.position(src, "src"),
                   _c.positions(mic, "mic"), _band_values(t60, "t60", "s"),
                   _band_values(absorption, "absorption", "energy coefficient"),
                   _band_values(scattering, "scattering", "coefficient"), _c.text(rir_id, "rir_id"), extra)


def simulate(room, src, mic, fs=16000, t60=None, absorption=None, scattering=None, model="gas",
             seed=0, length=1.0, rir_id="rir", extra=None):
    """One room impulse response from rir-simulate's geometric model.

    room: (x, y, z) room size in metres; src, mic: (x, y, z) source and microphone positions in
    metres, inside the room; mic may be an array's positions ((x, y, z), ...), channels in that
    order. fs: sampling rate, Hz. t60: reverberation time in seconds, or
    absorption: energy absorption coefficient in [0, 1]; each one value or 8 octave-band values
    (62.5 Hz .. 8 kHz); neither: absorption 0.2. scattering: one or 8 coefficients (default 0.1).
    model: rir-simulate --model ('gas' = image sources + diffuse tail; '+modes', '+air', ... see
    tsrir.model_components_help()). seed: int, with rir_id seeds the stochastic tail as
    rir-simulate does. length: seconds, or "auto" (until the decay is 60 dB down). extra: more
    room-list keys, e.g. {"absorption.floor": 0.5, "temperature": 25, "room-id": "r1"}
    (tsrir.room_list_keys_help()); polar patterns: {"mic_pattern": "cardioid", "mic_dir": (90, 0),
    "src_pattern": ..., "src_dir": ...}; a loudspeaker's per octave band:
    {"src_pattern_bands": "omni,omni,omni,omni,cardioid,cardioid,cardioid,cardioid"}.

    Returns float32 numpy (samples,) with samples = round(length * fs) for one microphone,
    (microphones, samples) for an array: the samples `rir-simulate --format=float` writes for the
    same room-list line, fs, model, length and seed.
    """
    line = room_list_line(room, src, mic, t60, absorption, scattering, rir_id, extra)
    return simulate_line(line, fs, model, seed, length)


def simulate_line(line, fs=16000, model="gas", seed=0, length=1.0):
    """Renders one rir-simulate room-list line ('<rir-id> room=.. src=.. mic=.. [key=value ...]').
    fs: Hz; length: seconds or "auto". Returns float32 numpy (samples,), or (microphones, samples)
    for a line with a microphone array."""
    return _c.call(_tsrir.simulate_line, _c.text(line, "line"), _c.sample_rate(fs), _c.text(model, "model"),
                   _c.number(seed, "seed", integer=True), _length_text(length))


def read_room_list(path):
    """An rir-simulate room list, parsed by the simulator's own parser: one dict per RIR with
    rir_id, room_id, room_m, src_m, mic_m, mics_m (every microphone of an array; metres) and line."""
    return _c.call(_tsrir.read_room_list, _c.path(path, "path"))


def model_components_help():
    """The simulator's model components (rir-simulate --help), as text."""
    return _tsrir.model_components_help()


def room_list_keys_help():
    """The room-list keys (rir-simulate --help), as text."""
    return _tsrir.room_list_keys_help()


# ---- measurement ---------------------------------------------------------------------------

_METRIC_OPTIONS = {"lundeby": None, "direct_pre_ms": "ms", "direct_post_ms": "ms", "clarity_ms": "ms", "onset_db": "dB"}


def metrics(rir, fs, definition="iso", rir_id="rir", **options):
    """rir-metrics of one RIR: the dict `rir-metrics --format=json` prints for it.

    rir: (samples,) at fs Hz. definition: 'iso' (ISO 3382) or 'irstats' (the paper's irStats).
    Keys: T60, EDT (s), DRR, C50 (dB), per-band T20/T30/EDT/RT/level, broadband, warnings; NaN where
    a value cannot be measured. options: lundeby (bool), direct_pre_ms, direct_post_ms, clarity_ms
    (ms), onset_db (dB)."""
    x = _c.array(rir, "rir")
    checked = {}
    for key, value in options.items():
        if key not in _METRIC_OPTIONS:
            raise TypeError("metrics() got an unexpected keyword argument %r (options: %s)"
                            % (key, ", ".join(sorted(_METRIC_OPTIONS))))
        unit = _METRIC_OPTIONS[key]
        checked[key] = _c.flag(value, key) if unit is None else _c.number(value, key, unit)
    text = _c.call(_tsrir.metrics_json, x, _c.sample_rate(fs), _c.text(definition, "definition", ("iso", "irstats")),
                   rir_id=_c.text(rir_id, "rir_id"), **checked)
    row = _json.loads(text)["rirs"][0]
    return _nan_for_null(row)


def _nan_for_null(value):
    if value is None:
        return float("nan")
    if isinstance(value, dict):
        return {k: (_nan_for_null(v) if k != "warnings" else v) for k, v in value.items()}
    return value


def rir_onset_index(rir, fs, onset_db=None):
    """The direct sound's arrival, a sample index (int), as rir-metrics (iso) finds it: the first
    sample whose energy is within onset_db (dB, default rir-metrics') of the peak's (ISO 3382-1).
    Unlike the largest sample (rir_shift_index), a reflection stronger than the direct sound does
    not move it. rir: (samples,) at fs Hz."""
    x = _c.array(rir, "rir")
    if onset_db is None:
        return _c.call(_tsrir.rir_onset_index, x, _c.sample_rate(fs))
    return _c.call(_tsrir.rir_onset_index, x, _c.sample_rate(fs), _c.number(onset_db, "onset_db", "dB"))


def rir_shift_index(rir, fs):
    """The sample index (int) wav-reverberate --shift-output=true advances its output by: the RIR's
    signed maximum (Kaldi's direct-path estimate). rir: (samples,) at fs Hz."""
    return _c.call(_tsrir.rir_shift_index, _c.array(rir, "rir"), _c.sample_rate(fs))


# ---- reverberation -------------------------------------------------------------------------

def _per_noise(value, name, unit, count):
    if value is None:
        return None
    values = _c.numbers(value, name, unit)
    if len(values) not in (1, count):
        raise ValueError("%s: %d values for %d noise signal(s) (give one, or one per noise)" % (name, len(values), count))
    return values[0] if len(values) == 1 else values


def _channel_choice(value, array_, name, what, used_by_all=False):
    """The channel to use (int); a multichannel input without a choice gets a warning naming it."""
    if value is not None:
        return _c.channel(value, name)
    if array_ is not None and array_.ndim == 2 and array_.shape[0] > 1 and not used_by_all:
        _c.warnings.warn("%s has %d channels; using channel 0 (give %s= to choose another)"
                         % (what, array_.shape[0], name), TsrirWarning, stacklevel=3)
    return 0


def reverberate(speech, rir, fs, noise=None, snr_db=None, shift="peak", normalize=True, volume=0.0,
                duration_s=0.0, start_time_s=None, offset_s=None, snr_reference="early",
                loop_noise=False, multi_channel_output=False, input_channel=None, rir_channel=None,
                noise_channel=None, rir_fs=None, noise_fs=None):
    """wav-reverberate on arrays: y = (x * h) + sum_i g_i n_i, then shifted and normalised.

    speech: (samples,) or (channels, samples) at fs Hz. rir: None (no reverberation), (taps,) or
    (channels, taps), at fs or at rir_fs Hz (then resampled as the program does). noise: None, one
    array or a list of arrays ((samples,) or (channels, samples)) at fs or noise_fs Hz.
    snr_db: dB, one number or one per noise, relative to the speech through the RIR's early part
    (snr_reference='early', Kaldi's; 'direct' or 'full' are tsrir's). start_time_s, offset_s:
    seconds, one or one per noise (where each noise starts in the output; where in the noise to
    start). loop_noise: repeat each noise to the end. shift: 'peak' (wav-reverberate
    --shift-output=true: advance by the RIR's signed maximum, Kaldi's direct-path estimate, which a
    reflection stronger than the direct sound moves), 'direct' (the same output advanced to the
    direct sound's onset instead: tsrir.rir_onset_index) or None (the full convolution).
    normalize: rescale to the input's power (else volume, a gain, if > 0). duration_s: output
    length in seconds (0: the input's). input_channel, rir_channel, noise_channel: the channel of
    a multichannel input to use (default 0, with a TsrirWarning when there was a choice);
    multi_channel_output: one output channel per RIR channel.

    Returns float32 (samples,) (or (channels, samples) with multi_channel_output), a tensor for a
    tensor speech. tsrir.encode_wav(result, fs) is the program's output file byte for byte.
    """
    like = _c.Like(speech)
    x = _c.array(speech, "speech", (1, 2), "(samples,) or (channels, samples)")
    fs = _c.sample_rate(fs)
    h = None if rir is None else _c.array(rir, "rir", (1, 2), "(taps,) or (channels, taps)")
    if noise is None:
        noises = None
    elif isinstance(noise, (list, tuple)):
        noises = [_c.array(n, "noise[%d]" % i, (1, 2), "(samples,) or (channels, samples)") for i, n in enumerate(noise)]
    else:
        noises = _c.array(noise, "noise", (1, 2), "(samples,) or (channels, samples)")
    count = 0 if noises is None else len(noises) if isinstance(noises, list) else 1
    if count and snr_db is None:
        raise TypeError("snr_db: needed with noise (a number in dB, or one per noise)")
    snr = _per_noise(snr_db, "snr_db", "dB", max(count, 1))
    starts = _per_noise(start_time_s, "start_time_s", "s", max(count, 1))
    offsets = _per_noise(offset_s, "offset_s", "s", max(count, 1))
    multi = _c.flag(multi_channel_output, "multi_channel_output")
    if multi and x.ndim == 2 and x.shape[0] > 1 and (h is None or h.ndim == 1 or h.shape[0] == 1):
        # wav-reverberate's rule: one output channel per RIR channel, from one speech channel. A
        # (1, n) result for multichannel speech would look like a lost array.
        raise ValueError("multi_channel_output: gives one output channel per RIR channel, but the RIR has one "
                         "channel and speech has %d; reverberate each speech channel (speech[c]) or give a "
                         "multichannel RIR (e.g. rir-simulate with mic=x,y,z;x,y,z;...)" % x.shape[0])
    input_channel = _channel_choice(input_channel, x, "input_channel", "speech")
    rir_channel = _channel_choice(rir_channel, h, "rir_channel", "rir", used_by_all=multi)
    first_noise = noises[0] if isinstance(noises, list) and noises else noises
    noise_channel = _channel_choice(noise_channel, first_noise, "noise_channel", "noise")
    rir_fs = None if rir_fs is None else _c.sample_rate(rir_fs, "rir_fs")
    noise_fs = None if noise_fs is None else _c.sample_rate(noise_fs, "noise_fs")
    if shift not in ("peak", "direct", "none", None, True, False):
        raise ValueError("shift: expected 'peak', 'direct' or None, got %r" % (shift,))
    direct = shift == "direct"
    shift_output = shift in ("peak", True)
    if direct and h is not None:
        if duration_s:
            raise ValueError("duration_s: not supported with shift='direct' (use shift='peak' or trim the result)")
        if rir_fs and rir_fs != fs:  # the same resampler the library would apply inside
            h = (resample(h, rir_fs, fs) if h.ndim == 1 else _c.np.stack([resample(c, rir_fs, fs) for c in h]))
            rir_fs = None
    out = _c.call(
        _tsrir.reverberate_channels, x, h, fs, noises, snr, starts, offsets, shift_output,
        _c.flag(normalize, "normalize"), _c.number(volume, "volume", minimum=0),
        _c.number(duration_s, "duration_s", "s", minimum=0), _c.text(snr_reference, "snr_reference"),
        _c.flag(loop_noise, "loop_noise"), multi, input_channel, rir_channel, noise_channel,
        float(rir_fs or 0), float(noise_fs or 0))
    if direct and h is not None:
        # wav-reverberate's output with its shift moved from the RIR's largest sample to the
        # direct sound's onset (rir-metrics' ISO onset): the same full-length signal and gain
        # (the library normalises over the whole convolution either way), another window of it.
        n = x.shape[-1]
        rirs = _c.np.atleast_2d(h)
        windows = []
        for c in range(out.shape[0]):
            onset = rir_onset_index(rirs[c] if multi else rirs[rir_channel], fs)
            windows.append(out[c, onset:onset + n])
        out = _c.np.stack(windows)
    return like(out if multi else out[0])


# ---- equalization --------------------------------------------------------------------------

def eq_apply(model_path, rir, fs, seed=0, rir_id="rir", taps=None, window="hamming", refine_iterations=None,
             max_boost_db=None, max_cut_db=None, level=None):
    """rir-eq apply for one RIR: target relative gains drawn from the EQ model with the stream
    (seed, rir_id), as the program draws them, then the equalizing FIR.

    model_path: an rir-eq fit model file; rir: (taps,) at fs Hz (the model's rate). taps: FIR length
    (odd, >= 3; default automatic); max_boost_db, max_cut_db: dB; level: rir-eq's --level.
    Returns (equalized float32 (taps,) -- a tensor for a tensor rir --, info): info holds before_db,
    target_db, predicted_db, after_db ({band centre Hz: dB re 1 kHz}), clamped, filters_designed."""
    like = _c.Like(rir)
    kwargs = {}
    if taps is not None:
        kwargs["taps"] = _c.number(taps, "taps", integer=True, minimum=0)
    if refine_iterations is not None:
        kwargs["refine_iterations"] = _c.number(refine_iterations, "refine_iterations", integer=True, minimum=0)
    if max_boost_db is not None:
        kwargs["max_boost_db"] = _c.number(max_boost_db, "max_boost_db", "dB", above=0)
    if max_cut_db is not None:
        kwargs["max_cut_db"] = _c.number(max_cut_db, "max_cut_db", "dB", above=0)
    if level is not None:
        kwargs["level"] = _c.text(level, "level")
    y, info = _c.call(_tsrir.eq_apply, _c.path(model_path, "model_path"), _c.array(rir, "rir"), _c.sample_rate(fs),
                      seed=_c.number(seed, "seed", integer=True), rir_id=_c.text(rir_id, "rir_id"),
                      window=_c.text(window, "window"), **kwargs)
    return like(y), info


# ---- Kaldi lists and data dirs -------------------------------------------------------------

def read_rir_list(path):
    """A Kaldi rir_list (or '<id> <rxfilename>' scp), parsed as reverberate-data parses it: one dict
    per RIR (rir_id, room_id, receiver/source_position_id, rt60 (s), drr (dB), cte, probability,
    rxfilename)."""
    return _c.call(_tsrir.read_rir_list, _c.path(path, "path"))


def read_noise_list(path):
    """A Kaldi noise_list (or scp), parsed as reverberate-data parses it: one dict per noise
    (noise_id, noise_type, bg_fg_type, room_linkage, probability, rxfilename)."""
    return _c.call(_tsrir.read_noise_list, _c.path(path, "path"))


def read_data_dir(dir):
    """A Kaldi data dir, read and checked as the programs do: {wav_scp, utt2spk, text, reco2dur
    (s), segments {utt: (recording, start_s, end_s)}}."""
    return _c.call(_tsrir.read_data_dir, _c.path(dir, "dir"))


def format_rir_list_line(rir_id, room_id, rxfilename):
    """One Kaldi rir_list line (the writers' format, quoted where needed)."""
    return _tsrir.format_rir_list_line(_c.text(rir_id, "rir_id"), _c.text(room_id, "room_id"),
                                       _c.path(rxfilename, "rxfilename"))


from ._augmenter import Augmenter  # noqa: E402  (uses the functions above)
