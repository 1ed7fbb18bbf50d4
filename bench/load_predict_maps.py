#!/usr/bin/env python3
"""Friction under load for maps: `frictal predict LOWER UPPER --load W` (the half-space's loaded
lift on lines along d, the block locked to d; docs/load.md, "Maps") on Fourier-filtered map pairs
(bench/fourier_maps.py: rms slope 0.2, roll-off at 32 cells, 1 mm side, lower and upper from two
seeds) of 128 x 128 and 256 x 256 nodes, aluminium (E = 70 GPa, nu = 0.3, both blocks), 5 x 5
drops: the CPU time of one prediction (its three-load curve included) against the rigid one, the
medians, the solver's work, and how the answer moves with the drops' count.

Usage: PYTHONPATH=build/release/python python3 bench/load_predict_maps.py FRICTAL [OUT.md]"""
import datetime
import json
import os
import platform
import resource
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import frictal  # noqa: E402
from fourier_maps import fourier_map  # noqa: E402


def cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def predict(cli, files, *extra):
    t0 = cpu()
    r = subprocess.run([cli, "predict", *files, "--json", "--threads", "1", *extra], capture_output=True, text=True,
                       check=True)
    return json.loads(r.stdout), cpu() - t0


def main():
    cli = sys.argv[1]
    out = open(sys.argv[2], "w") if len(sys.argv) > 2 else sys.stdout
    p = lambda *a: print(*a, file=out)
    p(f"{datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC, {platform.node()}, "
      f"{os.cpu_count()} cores (shared), `frictal predict --threads 1`, aluminium (70 GPa, 0.3, both blocks)\n")
    p("| pair | drops | rigid (free) median [5-95 %] | rigid CPU | load (N) | loaded median [5-95 %] | "
      "curve medians (W/10, W, 10 W) | patches / approach (m) / largest contact fraction | warnings | loaded CPU |")
    p("|---|---|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for n in (128, 256):
            a = 1e-3 / (n - 1)
            files = []
            for side, seed in (("lower", 21), ("upper", 1021)):
                path = os.path.join(tmp, f"n{n}-{side}.x3p")
                frictal.write_x3p(path, fourier_map(n, a, seed, qmin_cells=32), dx=a, dy=a)
                files.append(path)
            for drops in (5, 3):
                rigid, t_rigid = predict(cli, files, "--drops", str(drops))
                for w in ("0.1N", "10N"):
                    j, t = predict(cli, files, "--drops", str(drops), "--load", w, "--modulus", "70GPa", "--poisson",
                                   "0.3")
                    codes = sorted({x["code"] for x in j["warnings"] if x["code"].startswith(("load", "contact"))})
                    curve = ", ".join(f"{m:.2f}" for m in j["load_curve_median_deg"])
                    p(f"| {n} x {n} | {drops} x {drops} | {rigid['friction_angle_deg']:.2f} "
                      f"[{rigid['friction_angle_q05_deg']:.2f}-{rigid['friction_angle_q95_deg']:.2f}] | "
                      f"{t_rigid:.1f} s | {j['load_n']:g} | {j['friction_angle_deg']:.2f} "
                      f"[{j['friction_angle_q05_deg']:.2f}-{j['friction_angle_q95_deg']:.2f}] | {curve} | "
                      f"{j['load_contacts_mean']:.2f} / {j['load_approach_m']:.3g} / "
                      f"{j['load_contact_fraction_max']:.3g} | {', '.join(codes) or '-'} | {t:.1f} s |")
                    out.flush()


if __name__ == "__main__":
    main()
