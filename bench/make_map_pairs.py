#!/usr/bin/env python3
"""Random map pairs for the map prediction's benchmark (bench/map-predict.sh): Fourier-filtered
self-affine maps (flat spectrum below the roll-off wavelength, q^-(1+H) above it up to 2.5 cells,
rms slope 0.2), cut n x n from a periodic 2n x 2n field, lower and upper from independent seeds.
Writes OUT/<name>-lower.x3p and OUT/<name>-upper.x3p (heights and spacings in metres, 1 mm side).
Usage: PYTHONPATH=build/release/python python3 bench/make_map_pairs.py OUT N ROLLOFF_CELLS
Pairs: iso1 (H 0.8), iso2 (H 0.5), ani1 (H 0.8, correlated 4x longer along y), ani2 (H 0.5, 4x
longer along x)."""
import os
import sys

import numpy as np

import frictal
from fourier_maps import fourier_map  # bench/, the script's folder


def main():
    out, n, rolloff = sys.argv[1], int(sys.argv[2]), float(sys.argv[3])
    os.makedirs(out, exist_ok=True)
    a = 1e-3 / (n - 1)
    pairs = {"iso1": (11, {}), "iso2": (12, {"H": 0.5}), "ani1": (13, {"stretch": (1.0, 4.0)}),
             "ani2": (14, {"stretch": (4.0, 1.0), "H": 0.5})}
    for name, (seed, kw) in pairs.items():
        for side, s in (("lower", seed), ("upper", seed + 1000)):
            z = fourier_map(n, a, s, qmin_cells=rolloff, **kw)
            frictal.write_x3p(os.path.join(out, f"{name}-n{n}-r{rolloff:g}-{side}.x3p"), z, dx=a, dy=a)


if __name__ == "__main__":
    main()
