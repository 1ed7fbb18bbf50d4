#!/usr/bin/env python3
"""The map pairs of docs/mujoco.md, "The 0.2° target": writes OUT/<case>-lower.x3p and
OUT/<case>-upper.x3p for grooves (g30, g30m, g60, g60m, g90, g90-48, g90-20: in place), a flat
face with Gaussian bumps under five tips (bump1-3: in place), Fourier-filtered random pairs
(iso1-4, ani1-4: turned over by the CLI) and windows of the measured X3P map of the test data
(x3p1-3 as measured, x3ps1-3 heights x 2.5), and the speed pairs (big1-2, bigani1-2).
Usage: PYTHONPATH=build/release/python python3 bench/areal_tilt_pairs.py OUT"""
import os
import sys

import numpy as np

import frictal
from fourier_maps import fourier_map  # bench/, the script's folder

OUT = sys.argv[1]
os.makedirs(OUT, exist_ok=True)
HERE = os.path.dirname(os.path.abspath(__file__))

# Grooves: lower n x n, upper a w x w window in place (same coordinates).
def grooves(name, n, psi_deg, A, m, w, mirror=False, L=1e-3):
    a = L / (n - 1)
    across = abs(psi_deg - 90) < 1e-9
    dy = a if across else a * np.tan(np.radians(psi_deg))
    j, i = np.mgrid[0:n, 0:n]
    ph = i if across else (i + j if mirror else i - j)
    z = A * np.sin(2 * np.pi * ph / m)
    frictal.write_x3p(f"{OUT}/{name}-lower.x3p", z, dx=a, dy=dy)
    i0 = (n - w) // 2
    frictal.write_x3p(f"{OUT}/{name}-upper.x3p", z[i0:i0+w, i0:i0+w].copy(), dx=a, dy=dy, x0=i0*a, y0=i0*dy)
grooves("g90-20", 20, 90, 24e-6, 8, 6)
grooves("g90-48", 48, 90, 10e-6, 16, 16)
for psi in (30, 60):
    grooves(f"g{psi}", 30, psi, 20e-6, 10, 8)
    grooves(f"g{psi}m", 30, psi, 20e-6, 10, 8, mirror=True)
grooves("g90", 30, 90, 20e-6, 10, 8)

# Random Fourier-filtered map pairs.
def pair(name, n, w, seed, **kw):
    a = 1e-3 / (n - 1)
    f = fourier_map(n, a, seed, **kw)
    g = fourier_map(w, a, seed + 1000, **kw)
    frictal.write_x3p(f"{OUT}/{name}-lower.x3p", f, dx=a, dy=a)
    frictal.write_x3p(f"{OUT}/{name}-upper.x3p", g, dx=a, dy=a)
for s in range(1, 5):
    pair(f"iso{s}", 48, 12, s)
    pair(f"ani{s}", 48, 12, 100 + s, stretch=(1.0, 4.0))  # long correlation along y: lay along y
# Bumps: a flat lower face with isolated Gaussian bumps, an upper face of 3 x 3 tips.
def bumps(name, n, seed, count=14, height=3e-5, width_cells=2.0):
    rng = np.random.default_rng(seed)
    a = 1e-3 / (n - 1)
    j, i = np.mgrid[0:n, 0:n]
    z = np.zeros((n, n))
    for _ in range(count):
        ci, cj = rng.uniform(3, n - 4, 2)
        z += height * np.exp(-((i - ci) ** 2 + (j - cj) ** 2) / (2 * width_cells ** 2))
    frictal.write_x3p(f"{OUT}/{name}-lower.x3p", z, dx=a, dy=a)
    # upper in place: 9 x 9 nodes, tips at (1,1), (1,7), (7,1), (7,7), (4,4) at 0, others 4e-5 up
    w = 9
    g = np.full((w, w), 4e-5)
    for (p, q) in [(1, 1), (1, 7), (7, 1), (7, 7), (4, 4)]: g[q, p] = 0.0
    i0 = (n - w) // 2
    frictal.write_x3p(f"{OUT}/{name}-upper.x3p", g, dx=a, dy=a, x0=i0 * a, y0=i0 * a)
for s in range(1, 4): bumps(f"bump{s}", 40, s)
# Two windows of one measured scan (tests/data/x3p/x3p-2.x3p), plane removed later by the CLI
m = frictal.read_map(os.path.join(HERE, "..", "tests", "data", "x3p", "x3p-2.x3p"))
z = m["heights"]
for k, (li, lj, ui, uj) in enumerate([(20, 20, 380, 400), (300, 100, 100, 500), (500, 450, 250, 250)]):
    for tag, scale in (("x3p", 1.0), ("x3ps", 2.5)):
        frictal.write_x3p(f"{OUT}/{tag}{k+1}-lower.x3p", scale * z[lj:lj+48, li:li+48].copy(), dx=m["dx"], dy=m["dy"])
        frictal.write_x3p(f"{OUT}/{tag}{k+1}-upper.x3p", scale * z[uj:uj+12, ui:ui+12].copy(), dx=m["dx"], dy=m["dy"])
# speed cases: 32 x 32 upper on 96 x 96 lower
for s in (1, 2):
    pair(f"big{s}", 96, 32, 500 + s)
    pair(f"bigani{s}", 96, 32, 600 + s, stretch=(1.0, 4.0))
