#!/usr/bin/env python3
"""Friction under load: `frictal predict --load` (the Hertzian-asperity loaded lift, docs/load.md)
on generated Weierstrass-Mandelbrot pairs and on the measured dektak-1 scan against itself, over
three decades of load, for aluminium (E = 70 GPa, nu = 0.3) and a polymer (E = 3 GPa, nu = 0.35),
both blocks of the material; the dimension trend at one load; and the time of one prediction
(its load curve included) against the number of points.

The WM profiles: `frictal surface wm`, longest wavelength 100 um, 2 mm long, rms height 1 um,
gamma 1.5; n_max 10 (11,534 points) unless stated; each pair two seeds. The test is the default
stated test of the lower scan (d = 12.5 slope correlation lengths, a block of 20 d).

Usage: python3 bench/load_predict.py FRICTAL [OUT.md]"""
import datetime
import json
import os
import platform
import resource
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
DEKTAK = os.path.join(HERE, "..", "tests", "data", "profiles", "dektak-1.csv")
MATERIALS = [("aluminium", "70GPa", "0.3"), ("polymer", "3GPa", "0.35")]


def run(cli, *args):
    r = subprocess.run([cli, *args], capture_output=True, text=True, check=True)
    return r.stdout


def wm(cli, tmp, dimension, seed, n_max=10):
    path = os.path.join(tmp, f"wm-{dimension}-{seed}-{n_max}.csv")
    if not os.path.exists(path):
        run(cli, "surface", "wm", "-D", str(dimension), "--n-max", str(n_max), "--longest-wavelength", "1e-4",
            "--length", "2e-3", "--rms-height", "1e-6", "--seed", str(seed), "-o", path)
    return path


def predict(cli, files, loads, modulus, poisson):
    args = ["predict", *files, "--json", "--threads", "1"]
    if loads:
        args += ["--load", ",".join(f"{w:g}N" for w in loads), "--modulus", modulus, "--poisson", poisson]
    def cpu():
        r = resource.getrusage(resource.RUSAGE_CHILDREN)
        return r.ru_utime + r.ru_stime
    t0 = cpu()
    j = json.loads(run(cli, *args))
    return j, cpu() - t0


def points(path):
    with open(path, encoding="latin-1") as f:
        return sum(1 for line in f if line.strip() and not line.startswith("#")) - 1


def main():
    cli = sys.argv[1]
    out = open(sys.argv[2], "w") if len(sys.argv) > 2 else sys.stdout
    p = lambda *a: print(*a, file=out)
    p("# Friction under load (bench/load_predict.py)\n")
    p(f"{datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC, {platform.node()}, "
      f"{os.cpu_count()} cores (shared), `frictal predict --threads 1`\n")
    with tempfile.TemporaryDirectory() as tmp:
        cases = [(f"WM D = {D}, seeds {2 * k + 1}/{2 * k + 2}", [wm(cli, tmp, D, 2 * k + 1), wm(cli, tmp, D, 2 * k + 2)],
                  [1e-6, 1e-5, 1e-4, 1e-3]) for k, D in enumerate([1.3, 1.5, 1.5, 1.7])]
        cases.append(("dektak-1 against itself", [DEKTAK], [1e-8, 1e-7, 1e-6, 1e-5]))
        p("## Friction angle against load\n")
        p("Median [5 %, 95 %] of the hold angle over drops, in degrees; `*`: the load breaks an assumption "
          "of the asperity model (load-* warnings: contacts merging, interference beyond R/10, steep "
          "contacts).\n")
        for name, material_modulus, material_poisson in MATERIALS:
            p(f"### {name}: E = {material_modulus}, nu = {material_poisson} (both blocks)\n")
            p("| pair | rigid | " + " | ".join(["load 1", "load 2", "load 3", "load 4"]) + " | contacts / approach at load 3 |")
            p("|---|---|---|---|---|---|---|")
            for label, files, loads in cases:
                rigid, _ = predict(cli, files, [], "", "")
                j, _ = predict(cli, files, loads[2:3] + loads[:2] + loads[3:], material_modulus, material_poisson)
                beyond = {w["message"] for w in j["warnings"] if w["code"].startswith("load-")}
                cells = []
                for w, q05, q50, q95 in zip(j["load_curve_n"], j["load_curve_q05_deg"], j["load_curve_median_deg"],
                                            j["load_curve_q95_deg"]):
                    flag = "*" if any(f"{w:.4g} N" in m for m in beyond) else ""
                    cells.append(f"{w:g} N: {q50:.2f} [{q05:.2f}, {q95:.2f}]{flag}")
                p(f"| {label} | {rigid['friction_angle_deg']:.2f} [{rigid['friction_angle_q05_deg']:.2f}, "
                  f"{rigid['friction_angle_q95_deg']:.2f}] | " + " | ".join(cells) +
                  f" | {j['load_contacts_mean']:.2f} / {j['load_approach_m']:.3g} m |")
            p("")
        p("## The dimension at one load\n")
        p("WM pairs (seeds 1/2), 10 uN, aluminium; median [5 %, 95 %] in degrees.\n")
        p("| D | rigid | 10 uN | contacts | largest delta/R | merged share |")
        p("|---|---|---|---|---|---|")
        for D in [1.1, 1.3, 1.5, 1.7, 1.9]:
            files = [wm(cli, tmp, D, 1), wm(cli, tmp, D, 2)]
            rigid, _ = predict(cli, files, [], "", "")
            j, _ = predict(cli, files, [1e-5, 1e-6], "70GPa", "0.3")
            p(f"| {D} | {rigid['friction_angle_deg']:.2f} [{rigid['friction_angle_q05_deg']:.2f}, "
              f"{rigid['friction_angle_q95_deg']:.2f}] | {j['friction_angle_deg']:.2f} [{j['friction_angle_q05_deg']:.2f}, "
              f"{j['friction_angle_q95_deg']:.2f}] | {j['load_contacts_mean']:.2f} | "
              f"{j['load_interference_ratio_max']:.3g} | {j['load_merged_share']:.3f} |")
        p("")
        p("## Time\n")
        p("One prediction with a curve of 7 loads (`--load 10uN`: 0.1 uN .. 100 uN), aluminium, against the "
          "rigid prediction of the same pair (CPU seconds of the process, one thread; the machine is shared, so its wall time is not the cost).\n")
        p("| pair | points | rigid s | loaded s |")
        p("|---|---|---|---|")
        for n_max in [8, 10, 12, 14, 15]:
            files = [wm(cli, tmp, 1.5, 1, n_max), wm(cli, tmp, 1.5, 2, n_max)]
            _, tr = predict(cli, files, [], "", "")
            _, tl = predict(cli, files, [1e-5], "70GPa", "0.3")
            p(f"| WM D = 1.5, n_max {n_max} | {points(files[0])} | {tr:.2f} | {tl:.2f} |")
        _, tr = predict(cli, [DEKTAK], [], "", "")
        _, tl = predict(cli, [DEKTAK], [1e-6], "70GPa", "0.3")
        p(f"| dektak-1 | {points(DEKTAK)} | {tr:.2f} | {tl:.2f} |")


if __name__ == "__main__":
    main()
