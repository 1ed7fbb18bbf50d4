#!/usr/bin/env python3
"""Smooth nearly flat maps: 20 nm sines at 1 um spacing, for the cost of the map prediction's
descents on smooth faces (bench/results/map-predict.md, "Nearly flat maps").

Writes DIR/sine-sym-N.x3p and DIR/sine-asym-N.x3p for each N given (N x N nodes, L = N um):
  sym   20 nm sin(2 pi x / L) sin(3 pi y / L): conformal to itself turned over (the upper face of
        `frictal predict FILE`, turned over about the axis across the sliding direction, fits it)
  asym  20 nm sin(2 pi 0.7 x / L + 0.3) sin(3 pi y / L + 0.2): not conformal

    PYTHONPATH=build/release/python /usr/bin/python3 bench/sine_maps.py DIR [N ...]   (default 60)
"""
import sys

import numpy as np

import frictal


def main(out, sizes):
    for n in sizes:
        x = np.arange(n)[None, :] * 1e-6
        y = np.arange(n)[:, None] * 1e-6
        L = n * 1e-6
        maps = {
            "sym": 20e-9 * np.sin(2 * np.pi * x / L) * np.sin(3 * np.pi * y / L),
            "asym": 20e-9 * np.sin(2 * np.pi * 0.7 * x / L + 0.3) * np.sin(3 * np.pi * y / L + 0.2),
        }
        for name, z in maps.items():
            frictal.write_x3p(f"{out}/sine-{name}-{n}.x3p", np.ascontiguousarray(z, dtype=float), dx=1e-6, dy=1e-6)


if __name__ == "__main__":
    main(sys.argv[1], [int(a) for a in sys.argv[2:]] or [60])
