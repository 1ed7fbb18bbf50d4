#!/usr/bin/python3
"""Random small profile pairs for checking the hold analysis' one pass against the lift over the
whole overlap. Writes a.csv and b.csv (x_m,z_m) in the current folder; prints
"n nu kind_a kind_b". Kinds: 0 triangle wave, 1 trapezoid grooves, 2 random integers (ties),
3 sawtooth, 4 steps, 5 sampled sine, 6 rounded sine, 7 Gaussian noise; spacing 1 um, heights
scaled by 0.3, 1 or 5 um; the upper either its own kind or a window of the lower.
  bench/hold_small_pairs.py SEED
Check: `frictal signature a.csv b.csv --json` of this build against one built with
HoldOptions::whole_lift_offsets = inf (or m_lo = m_hi = inf in one_pass), every *_deg key
within 1e-9 (seeds 291 and 301-900 pass, measured at commit cc4dc09; at the commit before it
seeds 291, 349, 483 and 485 did not).
"""
import os
import sys

import numpy as np

rng = np.random.default_rng(int(sys.argv[1]))
def prof(kind, n):
    x = np.arange(n)
    if kind == 0: p = int(rng.integers(2, 40)); z = np.abs((x % p) - p/2) * rng.choice([1, 0.5, 2, 3])
    elif kind == 1:
        p = int(rng.integers(4, 40)); t = x % p; w = p//4; z = np.clip(np.minimum(t, p - t), 0, w).astype(float)
    elif kind == 2: z = rng.integers(0, int(rng.integers(2, 6)), n).astype(float)
    elif kind == 3: p = int(rng.integers(3, 30)); z = (x % p).astype(float)
    elif kind == 4: z = np.cumsum(rng.integers(-1, 2, n)).astype(float)
    elif kind == 5: m = int(rng.integers(3, 17)); z = np.sin(2*np.pi*x/m)
    elif kind == 6: m = int(rng.integers(3, 17)); z = np.round(8*np.sin(2*np.pi*x/m))
    else: z = rng.standard_normal(n)
    return z
n = int(rng.integers(20, 600)); nu = int(rng.integers(8, n+1))
k1, k2 = rng.integers(0, 8, 2)
dx = 1e-6
z1 = prof(k1, n); z2 = prof(k2, n)[:nu] if rng.random() < 0.5 else z1[int(rng.integers(0, n-nu+1)):][:nu]
s = float(rng.choice([0.3, 1, 5]))*dx
for name, z in (("a", z1), ("b", z2)):
    with open(name + ".csv", "w") as f:
        f.write("x_m,z_m\n")
        for i, zz in enumerate(z): f.write(f"{i*dx:.12g},{zz*s:.12g}\n")
print(n, nu, k1, k2)
