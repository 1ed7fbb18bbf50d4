#!/usr/bin/env python3
"""How stable is the answer? One surface presented in different ways, through `frictal predict`.

Each row presents a measured scan (tests/data) or a generated pair differently: cropped, rounded
in x, in other units, mirrored, with the blocks swapped, with spikes added and removed, read from
another export of the same measurement. It prints the median and the 5-95 % range of the hold
angle over drops for the reference and for the presentation, and whether the presentation's
median lies within the reference's own spread. The table of docs/site/stability.md is this
script's output (python3 scripts/stability.py --frictal PATH > table.md).
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.path.join(ROOT, "tests", "data")


def predict(frictal, *args):
    out = subprocess.run([frictal, "predict", *args, "--json"], capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(f"frictal predict {' '.join(args)} failed: {out.stderr.strip()}")
    return json.loads(out.stdout)


def cell(p):
    c = f"{p['friction_angle_deg']:.3f} [{p['friction_angle_q05_deg']:.3f}, {p['friction_angle_q95_deg']:.3f}]"
    return c if p.get("trust", "ok") == "ok" else f"{c}, doubtful ({p['trust_codes']})"


def write_csv(path, x, z, header="x_m,z_m", fmt="%.17g"):
    np.savetxt(path, np.c_[x, z], delimiter=",", header=header, comments="", fmt=fmt)
    return path


def read_xz(frictal, path, tmp):
    """The profile as frictal reads it (metres), through `frictal convert`."""
    out = os.path.join(tmp, "read.csv")
    subprocess.run([frictal, "convert", path, out], check=True, capture_output=True)
    d = np.loadtxt(out, delimiter=",", skiprows=1)
    return d[:, 0], d[:, 1]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--frictal", required=True, help="path of the frictal CLI")
    a = ap.parse_args()
    f = a.frictal
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        dektak = os.path.join(DATA, "profiles", "dektak-1.csv")
        ref = predict(f, dektak)
        x, z = read_xz(f, dektak, tmp)

        def row(what, p, r=ref):
            inside = r["friction_angle_q05_deg"] <= p["friction_angle_deg"] <= r["friction_angle_q95_deg"]
            rows.append((what, cell(r), cell(p), "yes" if inside else "**no**"))

        row("crop 0.1-0.9 mm", predict(f, dektak, "--crop", "0.1mm,0.9mm"))
        row("first half", predict(f, dektak, "--crop", "0mm,0.75mm"))
        row("second half", predict(f, dektak, "--crop", "0.75mm,1.5mm"))
        # x written with 6 significant digits in um (steps of 0.15625 um printed to 0.01 um past
        # 1000 um), the heights in full.
        with open(os.path.join(tmp, "x6.csv"), "w") as fh:
            fh.write("x_um,z_um\n")
            for a_, b_ in zip(x * 1e6, z * 1e6):
                fh.write(f"{a_:.6g},{b_!r}\n")
        row("x written with 6 significant digits (um)", predict(f, os.path.join(tmp, "x6.csv")))
        row("in micrometres (x, z)", predict(f, write_csv(os.path.join(tmp, "um.csv"), x * 1e6, z * 1e6, "x_um,z_um")))
        xm = (x[0] + x[-1] - x)[::-1]
        row("mirrored, sliding the other way",
            predict(f, write_csv(os.path.join(tmp, "m.csv"), xm, z[::-1]), "--direction", "180"))
        zs = z.copy()
        rng = np.random.default_rng(3)
        for i in rng.choice(len(z), 3, replace=False):
            zs[i] += 20 * np.std(z)
        spiky = write_csv(os.path.join(tmp, "spiky.csv"), x, zs)
        row("3 spikes of 20 Rq added", predict(f, spiky))
        row("3 spikes added, --remove-spikes", predict(f, spiky, "--remove-spikes"))

        # Another export of the same measurement: the profilometer's text (x with 8 digits) and binary file.
        opdx = predict(f, os.path.join(DATA, "instruments", "opdx-3.opdx"))
        row("opdx-3: text export (8-digit x) vs binary", predict(f, os.path.join(DATA, "instruments", "opdx-3.txt")),
            opdx)

        # A pair of generated self-affine profiles: the blocks swapped.
        for seed in (1, 2):
            subprocess.run([f, "surface", "-o", os.path.join(tmp, f"s{seed}.csv"), "self-affine", "--points", "8192",
                            "--seed", str(seed)], check=True, capture_output=True)
        s1, s2 = os.path.join(tmp, "s1.csv"), os.path.join(tmp, "s2.csv")
        pair = predict(f, s1, s2)
        row("self-affine pair: blocks swapped", predict(f, s2, s1), pair)
        row("self-affine pair: whole blocks swapped (same lift)",
            predict(f, s2, s1, "--block-length", "whole", "--runaway-distance", "20um"),
            predict(f, s1, s2, "--block-length", "whole", "--runaway-distance", "20um"))

    print("| presented as | reference: median [5 %, 95 %] (deg) | presented: median [5 %, 95 %] (deg) | "
          "median within the reference's 5-95 % |")
    print("|---|---|---|---|")
    for r in rows:
        print("| " + " | ".join(r) + " |")


if __name__ == "__main__":
    main()
