#!/usr/bin/env python3
"""An independent check of the spheropolygon engine's quasi-static tilt (docs/dem.md sec. 1,
"Contact rule"): the compliant blocks' energy minimised with scipy, no frictal engine code.

The upper block (rotation held) at offset s and height z on the lower one; every vertex-edge pair
of the two faces within 2r pushes with k_n * overlap along the shortest segment (the paper's
`pairs` rule), so the energy is W (z cos b - s sin b) + sum k_n overlap^2 / 2. From a start
offset the tilt b grows in 0.01 deg steps; at each the block relaxes to the local minimum
(L-BFGS-B in steps of at most 2 um, the contact window recentred on the highest contact). Prints
each slip and the tilt at which the block runs away (a slip of 0.5 mm, or 1.5 mm from the start).

Usage (the issue-23 WM pair, files from `frictal surface wm ... --seed 1|2`):
  PYTHONPATH=build/release/python bench/compliant_model.py wm1.csv wm2.csv 6e7 0.0246 1.50
  -> holds at 24.667 mm up to 1.85 deg, runs away at 1.86 deg (engine, --contact-rule pairs:
     1.85 deg; phi_qs of the rigid blocks: 1.549 deg). Minutes per run.
"""
import sys

import numpy as np
from scipy.optimize import minimize

import frictal

lower_file, upper_file, kn, s0, b0 = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4]), float(sys.argv[5])
r = float(sys.argv[6]) if len(sys.argv) > 6 else 2e-5   # spheroradius of both blocks (m)
W = float(sys.argv[7]) if len(sys.argv) > 7 else 0.981  # weight of the upper block (N/m): ~0.1 kg
lo = frictal.read_profile(lower_file)
up = frictal.rotate180(frictal.read_profile(upper_file))  # the upper face turned over, as the signature
fx, fz = np.asarray(lo.x), np.asarray(lo.z)
gx, gz = np.asarray(up.x), np.asarray(up.z)
win = 6e-4  # contact window half-width (m)


def lift(s):
    return frictal.lift_direct(lo, up, s)


def seg_dist(px, pz, ax, az, bx, bz):
    dx, dz = bx - ax, bz - az
    t = np.clip(((px - ax) * dx + (pz - az) * dz) / (dx * dx + dz * dz), 0, 1)
    sx, sz = px - (ax + t * dx), pz - (az + t * dz)
    return np.hypot(sx, sz), sx, sz


def energy(q, beta, xc):
    s, z = q
    ux, uz = gx + s, gz + z
    L = np.nonzero((fx > xc - win) & (fx < xc + win))[0]
    U = np.nonzero((ux > xc - win) & (ux < xc + win))[0]
    E = W * (z * np.cos(beta) - s * np.sin(beta))
    g = np.array([-W * np.sin(beta), W * np.cos(beta)])
    for px, pz, sign, ex, ez, idx in ((fx[L][:, None], fz[L][:, None], -1, ux, uz, U),
                                      (ux[U][:, None], uz[U][:, None], +1, fx, fz, L)):
        i = idx[:-1]
        d, sx, sz = seg_dist(px, pz, ex[i][None, :], ez[i][None, :], ex[i + 1][None, :], ez[i + 1][None, :])
        ov = 2 * r - d
        mk = ov > 0
        if mk.any():
            E += 0.5 * kn * np.sum(ov[mk] ** 2)
            g -= sign * kn * np.array([np.sum(ov[mk] * sx[mk] / d[mk]), np.sum(ov[mk] * sz[mk] / d[mk])])
    return E, g


def relax(q, beta):
    scale = np.array([1e-6, 1e-9])
    for _ in range(400):
        gi = np.interp(fx - q[0], gx, gz, left=np.nan, right=np.nan)
        xc = fx[np.nanargmax(fz - gi)]
        f = lambda y: (lambda e: (e[0] / (W * 1e-9), e[1] * scale / (W * 1e-9)))(energy(q + y * scale, beta, xc))
        res = minimize(f, np.zeros(2), jac=True, method="L-BFGS-B", bounds=[(-2, 2), (-1e5, 1e5)],
                       options={"gtol": 1e-13, "ftol": 1e-17})
        q = q + res.x * scale
        if abs(res.x[0]) < 1.99:
            return q
    return q


q = np.array([s0, lift(s0) + 2 * r])
for b in np.arange(b0, 30.0, 0.01):
    q0 = q[0]
    q = relax(q, np.radians(b))
    if q[0] - q0 > 5e-4 or q[0] - s0 > 1.5e-3:
        print(f"runs away at {b:.2f} deg from {q0 * 1e3:.5f} mm")
        break
    if q[0] - q0 > 1e-7:
        print(f"tilt {b:.2f} deg: slips {1e6 * (q[0] - q0):.2f} um to {q[0] * 1e3:.5f} mm", flush=True)
