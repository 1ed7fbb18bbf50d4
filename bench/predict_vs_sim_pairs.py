#!/usr/bin/env python3
"""The random pairs of bench/predict_vs_sim.sh (the prediction against the
simulation, statistically), on seeds not used or tuned on anywhere else.

  maps OUT      OUT/<pair>-lower.x3p, OUT/<pair>-upper.x3p: Fourier-filtered maps as the iso/ani
                pairs of bench/areal_tilt_pairs.py (lower 48 x 48, upper 12 x 12 from another seed,
                1 mm wide, Hurst 0.8, rolloff at 8 cells, cut-off at 2.5, rms slope 0.2; ani:
                correlation 4 times longer along y). Seeds: iso 201-204, ani 251-254 (upper +1000).
  maps OUT ISO ANI  the same with seeds ISO..ISO+3 and ANI..ANI+3 (a second set of pairs, e.g.
                211 261: the check rerun on pairs no setting of the prediction was tuned on).
  profiles OUT  OUT/<pair>-lower.csv, OUT/<pair>-upper.csv: Fourier-filtered profiles (see
                fourier_profile; lower 200 points, upper 50, spacing 1 mm / 199, best line removed).
                Seeds 301-304 (upper +1000).
  offsets-along PREDICT_JSON N   profiles: N drop offsets "x" evenly over the drop range.
  offsets PREDICT_JSON N M   prints N x M drop offsets "x,y" over the prediction's drop range
                (maps: the grid of `frictal predict --drops N` when N = M, i = fastest).

Usage: PYTHONPATH=build/release/python /usr/bin/python3 bench/predict_vs_sim_pairs.py maps OUT"""
import json
import os
import sys

import numpy as np

from fourier_maps import fourier_map  # noqa: E402  (bench/, the script's folder)


# The same filter in one dimension: periodic on 2n, cut n (not periodic), rms slope fixed.
def fourier_profile(n, a, seed, H=0.8, rms_slope=0.2, qmin_cells=8, qmax_cells=2.5):
    rng = np.random.default_rng(seed)
    N = 2 * n
    q = np.abs(np.fft.fftfreq(N, a)) * 2 * np.pi
    qr = 2 * np.pi / (qmin_cells * a); qs = 2 * np.pi / (qmax_cells * a)
    amp = np.where(q < qr, qr ** (-(0.5 + H)), np.where(q > qs, 0.0, np.maximum(q, 1e-30) ** (-(0.5 + H))))
    amp[0] = 0
    z = np.real(np.fft.ifft(amp * (rng.normal(size=N) + 1j * rng.normal(size=N))))[:n]
    z -= z.mean()
    s = np.sqrt(np.mean(np.gradient(z, a) ** 2))
    return z * rms_slope / s


def maps(out, iso=201, ani=251):
    import frictal
    os.makedirs(out, exist_ok=True)
    n, w = 48, 12
    a = 1e-3 / (n - 1)
    cases = []  # isotropic and anisotropic in turn (bench/predict_vs_sim.sh runs them in this order)
    for k in range(4):
        cases += [(f"iso{iso + k}", iso + k, {}), (f"ani{ani + k}", ani + k, {"stretch": (1.0, 4.0)})]
    for name, seed, kw in cases:
        frictal.write_x3p(f"{out}/{name}-lower.x3p", fourier_map(n, a, seed, **kw), dx=a, dy=a)
        frictal.write_x3p(f"{out}/{name}-upper.x3p", fourier_map(w, a, seed + 1000, **kw), dx=a, dy=a)
        print(name)


def profiles(out, n=200, w=50, length=1e-3):
    os.makedirs(out, exist_ok=True)
    a = length / (n - 1)
    for seed in range(301, 305):
        name = f"prof{seed}"
        for side, s, m in (("lower", seed, n), ("upper", seed + 1000, w)):
            z = fourier_profile(m, a, s)
            x = np.arange(m) * a
            z = z - np.polyval(np.polyfit(x, z, 1), x)  # the line removed here: `tilt` takes files as they are
            np.savetxt(f"{out}/{name}-{side}.csv", np.column_stack([x, z]), delimiter=",",
                       header="x_m,z_m", comments="")
        print(name)


def offsets_along(pred_json, n):  # profiles: n drops evenly over [drop_min, drop_max]
    r = json.load(open(pred_json))["drop_range_m"]
    for i in range(n):
        print(repr(r[0] + (r[1] - r[0]) * i / (n - 1)))


def offsets(pred_json, n, m):
    r = json.load(open(pred_json))["drop_range_m"]
    for j in range(m):
        for i in range(n):
            x = r[0] + (r[1] - r[0]) * i / (n - 1) if n > 1 else 0.5 * (r[0] + r[1])
            y = r[2] + (r[3] - r[2]) * j / (m - 1) if m > 1 else 0.5 * (r[2] + r[3])
            print(f"{x!r},{y!r}")


if __name__ == "__main__":
    what = sys.argv[1]
    if what == "maps":
        maps(sys.argv[2], *(int(v) for v in sys.argv[3:5]))
    elif what == "profiles":
        profiles(sys.argv[2])
    elif what == "offsets-along":
        offsets_along(sys.argv[2], int(sys.argv[3]))
    elif what == "offsets":
        offsets(sys.argv[2], int(sys.argv[3]), int(sys.argv[4]))
    else:
        sys.exit(__doc__)
