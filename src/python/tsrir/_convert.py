"""Python conventions at the package's edge, in one place: every public function converts and checks
its arguments here before the C++ extension sees them, so that a wrong argument raises TypeError
(wrong kind) or ValueError (wrong value) naming the argument and what was expected, instead of
pybind11's "Unable to cast Python instance to C++ type"; torch tensors are accepted wherever arrays
are and results come back as tensors on the input's device and dtype; sampling rates come back as
int; warnings of the C++ library reach Python's `warnings` (category tsrir.TsrirWarning) instead of
stderr.
"""
import numbers as _numbers
import os
import warnings

import numpy as np

from . import _tsrir


class TsrirWarning(UserWarning):
    """A warning of the toolkit's library (the programs print these as '<program>: WARNING: ...')."""


def forward_warnings(stacklevel=3):
    """Re-issues the library's warnings collected during the last calls through `warnings`."""
    for message in _tsrir._take_warnings():
        warnings.warn(message, TsrirWarning, stacklevel=stacklevel)


def call(function, *args, **kwargs):
    """Calls the extension; its warnings are re-issued through `warnings` even when it raises."""
    try:
        return function(*args, **kwargs)
    finally:
        forward_warnings(stacklevel=4)


def _kind(value):
    return type(value).__name__ if not isinstance(value, str) else "str %r" % value


def is_tensor(value):
    return type(value).__module__.split(".")[0] == "torch" and hasattr(value, "detach")


class Like:
    """Remembers whether an input was a torch tensor (device and dtype) to return results the same way."""

    def __init__(self, value=None):
        self.device = self.dtype = None
        if value is not None and is_tensor(value):
            self.device = value.device
            self.dtype = value.dtype if value.is_floating_point() else None

    def __call__(self, array):
        if self.device is None:
            return array
        import torch
        out = torch.from_numpy(np.ascontiguousarray(array))
        return out.to(device=self.device, dtype=self.dtype or out.dtype)


def array(value, name, ndim=(1,), shape_text="(samples,)"):
    """A real-valued array as C-contiguous float32 numpy, from numpy, a list or a torch tensor.
    Raises TypeError naming `name` for non-numeric input, ValueError for a wrong number of dimensions."""
    if value is None:
        raise TypeError("%s: expected an array %s, got None" % (name, shape_text))
    if is_tensor(value):
        value = value.detach().cpu()
        if value.is_complex():
            raise TypeError("%s: expected a real-valued tensor, got %s" % (name, value.dtype))
        value = value.float().numpy()
    if isinstance(value, (str, bytes)) or not hasattr(value, "__len__") and not isinstance(value, np.ndarray):
        raise TypeError("%s: expected an array %s of numbers, got %s" % (name, shape_text, _kind(value)))
    try:
        out = np.asarray(value)
    except (ValueError, TypeError) as e:
        raise TypeError("%s: expected an array %s of numbers (%s)" % (name, shape_text, e)) from None
    if out.dtype.kind not in "biuf":
        raise TypeError("%s: expected an array %s of real numbers, got dtype %s" % (name, shape_text, out.dtype))
    if out.ndim not in ndim:
        raise ValueError("%s: expected an array %s, got %d dimension(s) of shape %s"
                         % (name, shape_text, out.ndim, out.shape))
    return np.ascontiguousarray(out, dtype=np.float32)


def number(value, name, unit="", integer=False, minimum=None, above=None):
    """A real number (int for `integer`); bools and strings are TypeErrors, out-of-range values ValueErrors."""
    unit_text = " (%s)" % unit if unit else ""
    if is_tensor(value) and value.numel() == 1:
        value = value.item()
    if isinstance(value, np.generic):
        value = value.item()
    wanted = _numbers.Integral if integer else _numbers.Real
    if isinstance(value, bool) or not isinstance(value, wanted):
        raise TypeError("%s: expected %s%s, got %s" % (name, "an integer" if integer else "a number", unit_text,
                                                       _kind(value)))
    if not integer and not np.isfinite(value):
        raise ValueError("%s: expected a finite number%s, got %r" % (name, unit_text, value))
    if minimum is not None and value < minimum:
        raise ValueError("%s: must be >= %g%s, got %r" % (name, minimum, unit_text, value))
    if above is not None and not value > above:
        raise ValueError("%s: must be > %g%s, got %r" % (name, above, unit_text, value))
    return int(value) if integer else float(value)


def numbers(value, name, unit="", count=None):
    """One number or a sequence of numbers: a list of floats (`count`: how many are allowed)."""
    if isinstance(value, (str, bytes)):
        raise TypeError("%s: expected a number or a sequence of numbers%s, got %s"
                        % (name, " (%s)" % unit if unit else "", _kind(value)))
    if is_tensor(value) or isinstance(value, np.ndarray):
        value = np.asarray(value.detach().cpu() if is_tensor(value) else value).reshape(-1).tolist()
    if isinstance(value, (_numbers.Real, np.generic)) and not isinstance(value, bool):
        out = [number(value, name, unit)]
    else:
        try:
            items = list(value)
        except TypeError:
            raise TypeError("%s: expected a number or a sequence of numbers%s, got %s"
                            % (name, " (%s)" % unit if unit else "", _kind(value))) from None
        out = [number(v, "%s[%d]" % (name, i), unit) for i, v in enumerate(items)]
    if count is not None and len(out) not in count:
        raise ValueError("%s: expected %s value(s), got %d" % (name, " or ".join(str(c) for c in count), len(out)))
    return out


def positions(value, name):
    """A point (x, y, z) in metres, or a microphone array's points ((x, y, z), ...)."""
    if not isinstance(value, (str, bytes)) and hasattr(value, "__len__") and np.ndim(
            np.asarray(value.detach().cpu()) if is_tensor(value) else np.asarray(value, dtype=object)) == 2:
        items = list(value)
        if not 1 <= len(items) <= 64:
            raise ValueError("%s: an array has 1 to 64 microphones, got %d" % (name, len(items)))
        return tuple(position(v, "%s[%d]" % (name, i)) for i, v in enumerate(items))
    return position(value, name)


def position(value, name):
    """A point (x, y, z) in metres."""
    if isinstance(value, (str, bytes)) or not hasattr(value, "__len__") and not is_tensor(value):
        raise TypeError("%s: expected 3 numbers (x, y, z) in metres, got %s" % (name, _kind(value)))
    items = list(np.asarray(value.detach().cpu()) if is_tensor(value) else value)
    if len(items) != 3:
        raise ValueError("%s: expected 3 numbers (x, y, z) in metres, got %d item(s): %r" % (name, len(items), value))
    return tuple(number(v, "%s[%d]" % (name, i), "m") for i, v in enumerate(items))


def sample_rate(value, name="fs"):
    """A sampling rate in Hz (int or float), positive."""
    return number(value, name, "Hz", above=0)


def rate_out(fs):
    """A sampling rate as returned to Python: int when whole (always, for files), else float."""
    return int(fs) if float(fs).is_integer() else float(fs)


def text(value, name, choices=None):
    if not isinstance(value, str):
        raise TypeError("%s: expected a str%s, got %s" % (name, " (one of %s)" % ", ".join(choices) if choices else "",
                                                       _kind(value)))
    if choices is not None and value not in choices:
        raise ValueError("%s: expected one of %s, got %r" % (name, ", ".join(repr(c) for c in choices), value))
    return value


def path(value, name):
    """A file name: str or os.PathLike."""
    if isinstance(value, os.PathLike):
        value = os.fspath(value)
    if not isinstance(value, str):
        raise TypeError("%s: expected a path (str or os.PathLike), got %s" % (name, _kind(value)))
    return value


def flag(value, name):
    if not isinstance(value, (bool, np.bool_)):
        raise TypeError("%s: expected True or False, got %s" % (name, _kind(value)))
    return bool(value)


def channel(value, name):
    return number(value, name, integer=True, minimum=0)
