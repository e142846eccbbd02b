"""tsrir.Augmenter: reverberate-data's choices and far-field copies, one utterance at a time (the C++
class _tsrir.Augmenter, with the package's argument conventions: tsrir/_convert.py)."""
from . import _convert as _c
from . import _tsrir


def _checked_option(name, value, default):
    """An Augmenter keyword option, checked against the kind of reverberate-data's default."""
    if isinstance(default, list):
        if isinstance(value, str):
            raise TypeError("%s: expected a list of str (one per --%s), got a str; write [%r]"
                            % (name, name.replace("_", "-"), value))
        try:
            items = list(value)
        except TypeError:
            raise TypeError("%s: expected a list of str, got %s" % (name, type(value).__name__)) from None
        return [_c.path(v, "%s[%d]" % (name, i)) for i, v in enumerate(items)]
    if isinstance(default, bool):
        return _c.flag(value, name)
    if isinstance(default, int):
        return _c.number(value, name, integer=True)
    if isinstance(default, float):
        return _c.number(value, name)
    return _c.text(value, name)


class Augmenter:
    """reverberate-data's choices and reverberation for one utterance at a time.

    Augmenter(data_dir=None, recordings=None, durations=None, **options)

    data_dir: a Kaldi data dir (its wav.scp and reco2dur), or recordings: {id: rxfilename} (a path
    or a Kaldi pipe 'command |'); durations: {id: seconds}, else measured. These are the
    recordings reverberate-data would be given: its choices are made over all of them.
    options: reverberate-data's options with '_' for '-' (seed = --random-seed), e.g.
    rir_set_parameters=["0.5, rirs/rir_list"] (a list: the option is repeatable),
    noise_set_parameters=[...], foreground_snrs="20:10:0" (dB), prefix="rvb", sample_rate=16000
    (Hz: the data dir's rate; default the first recording's, see .sample_rate);
    Augmenter.option_defaults() lists them with reverberate-data's defaults. A wrong option name
    or kind is a TypeError, a bad value a ValueError (tsrir.Error).

    aug(speech, fs, id, copy=1) and aug.augment(id, copy=1) equal the wav that
    `reverberate-data --num-replications>=copy --write-wavs` writes for copy `copy` of recording
    `id` (before its 16-bit encoding). It pickles (to DataLoader workers) as its options and
    recordings. With a microphone array's RIRs, multi_channel_output=True gives (channels,
    samples), and split_channels=True (reverberate-data --split-channels) gives a dict
    {entry id: (samples,)} keyed as that data dir's entries: "<new_id>.CH<c>" (c from 1) per RIR
    channel, new_id alone for a copy without an RIR; entry .CH<c> is channel c - 1 of the former.
    (For several copies reverberate-data forces prefix="rvb"; give it here too for its ids.)
    """

    def __init__(self, data_dir=None, recordings=None, durations=None, **options):
        defaults = _tsrir.Augmenter.option_defaults()
        checked = {}
        for name, value in options.items():
            if name not in defaults:
                raise TypeError("Augmenter() got an unexpected keyword argument %r (reverberate-data's options "
                                "here: %s)" % (name, ", ".join(sorted(defaults))))
            checked[name] = _checked_option(name, value, defaults[name])
        if data_dir is not None:
            data_dir = _c.path(data_dir, "data_dir")
        if recordings is not None:
            if not isinstance(recordings, dict):
                raise TypeError("recordings: expected a dict {id: rxfilename}, got %s" % type(recordings).__name__)
            recordings = {_c.text(k, "recordings key"): _c.path(v, "recordings[%r]" % k) for k, v in recordings.items()}
        if durations is not None:
            if not isinstance(durations, dict):
                raise TypeError("durations: expected a dict {id: seconds}, got %s" % type(durations).__name__)
            durations = {_c.text(k, "durations key"): _c.number(v, "durations[%r]" % k, "s", above=0)
                         for k, v in durations.items()}
        self._impl = _c.call(_tsrir.Augmenter, data_dir=data_dir, recordings=recordings, durations=durations,
                             **checked)

    @staticmethod
    def option_defaults():
        """{option: reverberate-data's default} for every keyword option Augmenter takes."""
        return _tsrir.Augmenter.option_defaults()

    @property
    def options(self):
        """{option: value} as this Augmenter uses them."""
        return self._impl.options

    @property
    def recordings(self):
        """[(id, rxfilename)] in wav.scp (byte) order, reverberate-data's order."""
        return self._impl.recordings

    @property
    def sample_rate(self):
        """The data dir's rate, int Hz: the sample_rate option (reverberate-data --sample-rate) when
        given, else the first recording's. Every output is at this rate. A recording at another rate
        is resampled to it when sample_rate was given, and refused (tsrir.Error) otherwise."""
        return _c.rate_out(self._impl.sample_rate)

    @property
    def num_rirs(self):
        return self._impl.num_rirs

    @property
    def num_noises(self):
        return self._impl.num_noises

    def plan(self, id, copy=1):
        """What reverberate-data does to copy `copy` (>= 1) of recording `id`: a dict with new_id,
        rir_id, room_id, rir_rxfilename and noises [{noise_id, snr_db (dB), start_time_s, offset_s
        (s), loop, ...}]."""
        return _c.call(self._impl.plan, _c.text(id, "id"), _c.number(copy, "copy", integer=True, minimum=1))

    def __call__(self, speech, fs, id, copy=1):
        """The far-field copy of one utterance given its samples: speech (samples,) at fs Hz (a
        (channels, samples) input uses channel 0, with a TsrirWarning). Returns float32 (samples,),
        or with multi_channel_output=True (channels, samples), one channel per channel of the
        recording's RIR (a microphone array's), or with split_channels=True {"<new_id>.CH<c>":
        (samples,)}; tensors for a tensor input."""
        like = _c.Like(speech)
        x = _c.array(speech, "speech", (1, 2), "(samples,)")
        if x.ndim == 2:
            if x.shape[0] > 1 and (self.options.get("multi_channel_output") or self.options.get("split_channels")):
                # The array's channels come from one speech channel through the RIR's channels; a
                # multichannel speech would silently lose all but one of its channels.
                raise ValueError("speech: %s makes one output channel per RIR channel from one speech channel, "
                                 "but speech has %d channels; pass speech[c]"
                                 % ("multi_channel_output" if self.options.get("multi_channel_output")
                                    else "split_channels", x.shape[0]))
            if x.shape[0] > 1:
                _c.warnings.warn("speech has %d channels; using channel 0 (pass speech[c] to choose another)"
                                 % x.shape[0], _c.TsrirWarning, stacklevel=2)
            x = _c.np.ascontiguousarray(x[0])
        y = _c.call(self._impl, x, _c.sample_rate(fs), _c.text(id, "id"),
                    _c.number(copy, "copy", integer=True, minimum=1))
        if isinstance(y, dict):
            return {k: like(v) for k, v in y.items()}
        return like(y)

    def augment(self, id, copy=1):
        """Reads recording `id`'s wav.scp entry (a path or 'command |') and returns
        (far-field copy float32 numpy (samples,) -- (channels, samples) with multi_channel_output,
        {"<new_id>.CH<c>": (samples,)} with split_channels --, fs int Hz)."""
        y, fs = _c.call(self._impl.augment, _c.text(id, "id"), _c.number(copy, "copy", integer=True, minimum=1))
        return y, _c.rate_out(fs)

    def __getstate__(self):
        return {"impl": self._impl}

    def __setstate__(self, state):
        self._impl = state["impl"]
