"""Converts Blender's CC0 lat-long world EXRs into the small Radiance .hdr fixtures of Q4.

Provenance (run once; the outputs are committed under docs/data/q4/):
    apt-get download blender-data && dpkg -x blender-data_*.deb extract
    python -m venv venv && venv/bin/pip install openexr numpy
    venv/bin/python docs/data/q4/convert_exr.py extract/usr/share/blender/datafiles/studiolights/world docs/data/q4

Each 1024x512 map is box-filtered 4x4 down to 256x128 (a mean, so every texel keeps the average
radiance over its footprint and a sub-texel sun keeps its energy) and written as uncompressed
(flat) RGBE, which the `image` crate's HDR decoder reads. Also prints each map's "hardness": the
share of the solid-angle-weighted luminance in its brightest 0.1 % of solid angle.
"""

import sys
from pathlib import Path

import numpy as np
import OpenEXR


def read_rgb(path):
    with OpenEXR.File(str(path)) as f:
        channels = f.channels()
        if "RGB" in channels:
            rgb = np.asarray(channels["RGB"].pixels, dtype=np.float64)
        else:
            rgb = np.stack([np.asarray(channels[c].pixels, dtype=np.float64) for c in "RGB"], axis=-1)
    return rgb


def box_down(rgb, factor):
    h, w, _ = rgb.shape
    return rgb.reshape(h // factor, factor, w // factor, factor, 3).mean(axis=(1, 3))


def write_rgbe(path, rgb):
    h, w, _ = rgb.shape
    peak = rgb.max(axis=-1)
    mantissa, exponent = np.frexp(peak)
    scale = np.where(peak > 1e-32, mantissa * 256.0 / np.where(peak > 0, peak, 1.0), 0.0)
    rgbe = np.zeros((h, w, 4), dtype=np.uint8)
    rgbe[..., :3] = np.clip(np.floor(rgb * scale[..., None]), 0, 255).astype(np.uint8)
    rgbe[..., 3] = np.where(peak > 1e-32, exponent + 128, 0).astype(np.uint8)
    header = f"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y {h} +X {w}\n".encode()
    Path(path).write_bytes(header + rgbe.tobytes())


def hardness(rgb):
    h, w, _ = rgb.shape
    theta = (np.arange(h) + 0.5) / h * np.pi
    weight = np.sin(theta)[:, None] * np.ones((1, w))
    lum = rgb @ np.array([0.2126, 0.7152, 0.0722])
    power = (lum * weight).ravel()
    order = np.argsort(lum.ravel())[::-1]
    cumulative_area = np.cumsum(weight.ravel()[order]) / weight.sum()
    top = order[: max(1, np.searchsorted(cumulative_area, 0.001))]
    return power[top].sum() / power.sum()


def main(source, target):
    Path(target).mkdir(parents=True, exist_ok=True)
    for exr in sorted(Path(source).glob("*.exr")):
        rgb = read_rgb(exr)
        small = box_down(rgb, rgb.shape[1] // 256)
        print(f"{exr.stem:10} {rgb.shape[1]}x{rgb.shape[0]} hardness {hardness(small):.3f} max {small.max():.1f}")
        if exr.stem in sys.argv[3:]:
            write_rgbe(Path(target) / f"{exr.stem}_256x128.hdr", small)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
