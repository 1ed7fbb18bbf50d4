#!/usr/bin/env python3
"""Nearly flat maps with a few spikes, for the cost of the map prediction on nearly flat faces.

Writes DIR/NAME-spk.x3p for five surfaces of 563 x 484 nodes (an optical instrument's grid), each
with 12 spikes (+-200 nm on `wave`, +-1 um on the others, seed 7):
  wave      2 nm sin(i/40) cos(j/55) + 0.5 nm white noise, 0.2 um spacing
  noise     1 nm white noise, 1 um spacing
  tilt      a plane of slope 1e-4 along x and 3e-5 along y + 0.5 nm noise, 1 um spacing
  quant     white noise quantised to 1 nm steps (a few levels), 1 um spacing
  longwave  20 nm over one wavelength of the map along x and 1.5 along y, no noise, 1 um spacing
`frictal predict FILE` and `frictal predict FILE --remove-spikes` (bench/flat-cost.sh) then give
the cost of the spiky pair and of the nearly flat pair the spike filter leaves.

    PYTHONPATH=build/release/python /usr/bin/python3 bench/flat_maps.py DIR
"""
import sys

import numpy as np

import frictal

NX, NY = 563, 484


def spiked(z, amp, seed=7, n=12):
    r = np.random.default_rng(seed)
    z = z.copy()
    for k in range(n):
        i, j = r.integers(5, NX - 5), r.integers(5, NY - 5)
        z[j, i] += amp * (1 if k % 2 == 0 else -1)
    return z


def main(out):
    rng = np.random.default_rng(7)
    x = np.arange(NX)[None, :]
    y = np.arange(NY)[:, None]
    cases = {
        "wave": (2e-9 * np.sin(x / 40) * np.cos(y / 55) + 0.5e-9 * rng.standard_normal((NY, NX)), 0.2e-6, 200e-9),
        "noise": (1e-9 * rng.standard_normal((NY, NX)), 1e-6, 1e-6),
        "tilt": (1e-4 * (x * 1e-6) + 0.3e-4 * (y * 1e-6) + 0.5e-9 * rng.standard_normal((NY, NX)), 1e-6, 1e-6),
        "quant": (np.round(rng.standard_normal((NY, NX)) * 0.7) * 1e-9, 1e-6, 1e-6),
        "longwave": (20e-9 * np.sin(2 * np.pi * x / NX) * np.sin(2 * np.pi * y / NY * 1.5), 1e-6, 1e-6),
    }
    for name, (z, d, amp) in cases.items():
        frictal.write_x3p(f"{out}/{name}-spk.x3p", np.ascontiguousarray(spiked(z, amp), dtype=float), dx=d, dy=d)


if __name__ == "__main__":
    main(sys.argv[1])
