#!/usr/bin/env python3
"""A figure of one microphone array's RIRs (a multichannel WAV: PCM 16/24/32-bit or float32) as an
SVG: one trace per channel, stacked, each scaled to the array's peak, over a window of time in ms
(left panel: the first `--early-ms` after the earliest arrival, where the arrival-time differences
across the array show; right panel: the whole RIR, the level in dB of each channel's smoothed
energy). Python's standard library only (the demo machines have no plotting packages).

usage: plot_array_rirs.py [--early-ms 12] [--title T] <rir.wav> <out.svg>
"""
import argparse
import math
import os
import struct
import sys


def riff_chunks(data):
    """(id, body) of each chunk of a RIFF file's bytes."""
    pos = 12
    while pos + 8 <= len(data):
        size = struct.unpack_from("<I", data, pos + 4)[0]
        yield data[pos:pos + 4], data[pos + 8:pos + 8 + size]
        pos += 8 + size + (size & 1)


def read_wav(path):
    """(sample rate, [channel][sample] floats) of a RIFF/WAVE file."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:4] != b"RIFF" or data[8:12] != b"WAVE":
        sys.exit(f"{path}: not a RIFF/WAVE file")
    chunks = dict(riff_chunks(data))
    if b"fmt " not in chunks or b"data" not in chunks:
        sys.exit(f"{path}: no fmt or data chunk")
    header, frames = chunks[b"fmt "], chunks[b"data"]
    tag, channels, rate = struct.unpack_from("<HHI", header)
    bits = struct.unpack_from("<H", header, 14)[0]
    if tag == 0xFFFE:  # WAVE_FORMAT_EXTENSIBLE: the sub-format's tag
        tag = struct.unpack_from("<H", header, 24)[0]
    width = bits // 8
    n = len(frames) // (width * channels)
    if tag == 3 and bits == 32:
        values = struct.unpack(f"<{n * channels}f", frames[:n * channels * 4])
    elif tag == 1 and bits in (16, 32):
        code = "h" if bits == 16 else "i"
        scale = 2.0 ** (bits - 1)
        values = [v / scale for v in struct.unpack(f"<{n * channels}{code}", frames[:n * channels * width])]
    elif tag == 1 and bits == 24:
        values = [int.from_bytes(frames[i:i + 3], "little", signed=True) / 8388608.0
                  for i in range(0, n * channels * 3, 3)]
    else:
        sys.exit(f"{path}: unsupported sample format (tag {tag}, {bits} bits)")
    return rate, [list(values[c::channels]) for c in range(channels)]


def nice_step(span, target_ticks=6):
    raw = span / target_ticks
    magnitude = 10 ** math.floor(math.log10(raw))
    for m in (1, 2, 5, 10):
        if m * magnitude >= raw:
            return m * magnitude
    return 10 * magnitude


def ticks(lo, hi):
    step = nice_step(hi - lo)
    first = math.ceil(lo / step) * step
    out, t = [], first
    while t <= hi + 1e-9 * step:
        out.append(round(t, 10))
        t += step
    return out


COLOURS = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f",
           "#bcbd22", "#17becf"]


class Panel:
    """One plot frame at (x0, y0) of size (w, h) mapping data (x, y) ranges to pixels."""

    def __init__(self, x0, y0, w, h, x_range, y_range):
        self.x0, self.y0, self.w, self.h = x0, y0, w, h
        self.x_lo, self.x_hi = x_range
        self.y_lo, self.y_hi = y_range

    def px(self, x):
        return self.x0 + (x - self.x_lo) / (self.x_hi - self.x_lo) * self.w

    def py(self, y):
        return self.y0 + self.h - (y - self.y_lo) / (self.y_hi - self.y_lo) * self.h

    def frame(self, title, x_label, y_label, y_ticks):
        out = [f'<rect x="{self.x0}" y="{self.y0}" width="{self.w}" height="{self.h}" fill="none" stroke="#000"/>',
               f'<text x="{self.x0 + self.w / 2}" y="{self.y0 - 10}" text-anchor="middle" font-size="14">{title}</text>',
               f'<text x="{self.x0 + self.w / 2}" y="{self.y0 + self.h + 38}" text-anchor="middle" font-size="13">'
               f'{x_label}</text>',
               f'<text transform="translate({self.x0 - 52},{self.y0 + self.h / 2}) rotate(-90)" text-anchor="middle" '
               f'font-size="13">{y_label}</text>']
        for t in ticks(self.x_lo, self.x_hi):
            x = self.px(t)
            out.append(f'<line x1="{x:.1f}" y1="{self.y0 + self.h}" x2="{x:.1f}" y2="{self.y0 + self.h + 5}" stroke="#000"/>')
            out.append(f'<text x="{x:.1f}" y="{self.y0 + self.h + 19}" text-anchor="middle" font-size="11">{t:g}</text>')
        for value, label in y_ticks:
            y = self.py(value)
            out.append(f'<line x1="{self.x0 - 5}" y1="{y:.1f}" x2="{self.x0}" y2="{y:.1f}" stroke="#000"/>')
            out.append(f'<text x="{self.x0 - 8}" y="{y + 4:.1f}" text-anchor="end" font-size="11">{label}</text>')
        return out

    def trace(self, xs, ys, colour):
        points = " ".join(f"{self.px(x):.1f},{self.py(y):.1f}" for x, y in zip(xs, ys))
        return f'<polyline points="{points}" fill="none" stroke="{colour}" stroke-width="1"/>'


def early_panel(rate, channels, early_ms):
    """Stacked traces from 1 ms before the earliest arrival, each channel offset by 1."""
    peak = max(max(abs(v) for v in c) for c in channels) or 1.0
    onset = min(next(i for i, v in enumerate(c) if abs(v) >= 0.1 * peak) for c in channels)
    start = max(0, onset - int(0.001 * rate))
    stop = min(len(channels[0]), start + int(early_ms * 1e-3 * rate))
    m = len(channels)
    panel = Panel(80, 60, 420, 420, (1000.0 * start / rate, 1000.0 * stop / rate), (-0.8, m - 0.2))
    y_ticks = [(m - 1 - c, f"mic {c + 1}") for c in range(m)]
    out = panel.frame("Early part (direct sound and first reflections)", "time (ms)",
                      "microphone (all scaled by the array's peak)", y_ticks)
    xs = [1000.0 * i / rate for i in range(start, stop)]
    for c, samples in enumerate(channels):
        ys = [m - 1 - c + 0.45 * v / peak for v in samples[start:stop]]
        out.append(panel.trace(xs, ys, COLOURS[c % len(COLOURS)]))
    return out


def level_panel(rate, channels):
    """Each channel's energy smoothed over 2 ms, in dB re the array's largest value."""
    window = max(1, int(0.002 * rate))
    curves = []
    for samples in channels:
        energy = [v * v for v in samples]
        smoothed = [sum(energy[i:i + window]) / window for i in range(0, len(energy), window)]
        curves.append(smoothed)
    top = max(max(c) for c in curves) or 1.0
    n = len(channels[0])
    panel = Panel(600, 60, 420, 420, (0.0, 1000.0 * n / rate), (-80.0, 0.0))
    y_ticks = [(v, f"{v:g}") for v in ticks(-80.0, 0.0)]
    out = panel.frame("Whole RIR, energy per 2 ms", "time (ms)", "level (dB re the array's maximum)", y_ticks)
    for c, curve in enumerate(curves):
        xs = [1000.0 * (k * window + window / 2) / rate for k in range(len(curve))]
        ys = [max(-80.0, 10 * math.log10(e / top)) if e > 0 else -80.0 for e in curve]
        out.append(panel.trace(xs, ys, COLOURS[c % len(COLOURS)]))
    for c in range(len(channels)):  # legend, right of the panel
        y = 75 + 18 * c
        out.append(f'<line x1="1035" y1="{y}" x2="1055" y2="{y}" stroke="{COLOURS[c % len(COLOURS)]}" stroke-width="2"/>')
        out.append(f'<text x="1060" y="{y + 4}" font-size="11">mic {c + 1}</text>')
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--early-ms", type=float, default=12.0)
    parser.add_argument("--title", default="")
    parser.add_argument("wav")
    parser.add_argument("svg")
    args = parser.parse_args()
    rate, channels = read_wav(args.wav)
    body = early_panel(rate, channels, args.early_ms) + level_panel(rate, channels)
    title = args.title or args.wav
    svg = ['<svg xmlns="http://www.w3.org/2000/svg" width="1120" height="540" font-family="sans-serif">',
           '<rect width="100%" height="100%" fill="#fff"/>',
           f'<text x="560" y="24" text-anchor="middle" font-size="15">{title}</text>'] + body + ["</svg>"]
    tmp = args.svg + ".tmp"
    with open(tmp, "w") as f:
        f.write("\n".join(svg) + "\n")
    os.replace(tmp, args.svg)


if __name__ == "__main__":
    main()
