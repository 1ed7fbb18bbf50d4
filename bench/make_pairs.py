#!/usr/bin/python3
"""Writes the 10^7-point bench pairs of bench/hold_ab.py into bench/data/ (git-ignored): two self-affine profiles per
Hurst exponent, Fourier-filtered white noise (numpy), spacing 1 nm, rms 1 um, as CSV x_m,z_m.

Usage: bench/make_pairs.py [N] [--hurst 0.8 0.3] [--out bench/data]
Files: sa-H{H}-N{N}-{1,2}.csv (seeds 1 and 2). Existing files are kept.
With --wm FRICTAL also the 12-scale WM pair, by the CLI itself:
wm-12-{1,2}.csv = `FRICTAL surface wm -D 1.5 --n-max 11 --longest-wavelength 0.01 --length 0.2
--rms-height 1e-5 --spacing 2e-8 --seed {1,2}` (10^7 points).
"""
import argparse
import os
import subprocess

import numpy as np


def self_affine(n, hurst, seed, dx=1e-9, rms=1e-6):
    rng = np.random.default_rng(seed)
    k = np.fft.rfftfreq(n, d=dx)
    amp = np.zeros_like(k)
    amp[1:] = k[1:] ** (-(0.5 + hurst))  # PSD ~ k^-(1 + 2H)
    spec = amp * (rng.standard_normal(k.size) + 1j * rng.standard_normal(k.size))
    z = np.fft.irfft(spec, n=n)
    z -= z.mean()
    z *= rms / z.std()
    return np.arange(n) * dx, z


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("n", nargs="?", type=int, default=10_000_000)
    ap.add_argument("--hurst", nargs="+", type=float, default=[0.8, 0.3])
    ap.add_argument("--out", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "data"))
    ap.add_argument("--wm", metavar="FRICTAL", help="also write the 12-scale WM pair with this CLI")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    for h in a.hurst:
        for seed in (1, 2):
            path = os.path.join(a.out, f"sa-H{h:g}-N{a.n}-{seed}.csv")
            if os.path.exists(path):
                continue
            x, z = self_affine(a.n, h, seed)
            with open(path + ".tmp", "w") as f:
                f.write("x_m,z_m\n")
                np.savetxt(f, np.column_stack([x, z]), fmt="%.10e", delimiter=",")
            os.replace(path + ".tmp", path)
            print(path)
    if a.wm:
        for seed in (1, 2):
            path = os.path.join(a.out, f"wm-12-{seed}.csv")
            if not os.path.exists(path):
                subprocess.run([a.wm, "surface", "wm", "-D", "1.5", "--n-max", "11", "--longest-wavelength", "0.01",
                                "--length", "0.2", "--rms-height", "1e-5", "--spacing", "2e-8", "--seed", str(seed),
                                "-o", path], check=True)
                print(path)


if __name__ == "__main__":
    main()
