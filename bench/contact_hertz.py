#!/usr/bin/env python3
"""Convergence of `frictal contact` with resolution against Hertz's solutions (docs/contact.md).

Sphere on a flat (map, not periodic: padded to 2N): a paraboloid z = -r^2 / (2R), R = 10 mm,
E* = 1 GPa, at the force that gives Hertz's contact radius a = 20 um, on grids whose spacing puts
a/dx = 5 ... 80 points across the radius (the map spans 5 a). Hertz: a = (3 F R / (4 E*))^(1/3),
p0 = 3 F / (2 pi a^2), approach a^2 / R, stiffness 2 E* a. The contact radius is sqrt(A / pi)
from the contact area (points with p > 0 times dx^2).
Cylinder on a flat (profile, plane strain, padded): z = -x^2 / (2R), R = 20 mm, at the force per
unit length that gives a = 200 um, a/dx = 10 ... 1000 (the profile spans 8 a). Hertz:
a = sqrt(4 F' R / (pi E*)), p0 = 2 F' / (pi a); the half-width is half the contact length.

Usage: PYTHONPATH=build/release/python python3 bench/contact_hertz.py [OUT.md]
Prints (and writes) a Markdown table of the relative errors."""
import datetime
import math
import platform
import sys
import time

import numpy as np

import frictal


def sphere_rows():
    Es, R, a = 1e9, 0.01, 20e-6
    F = 4 * Es * a ** 3 / (3 * R)
    p0 = 3 * F / (2 * math.pi * a * a)
    rows = []
    for per_radius in (5, 10, 20, 40, 80):
        dx = a / per_radius
        n = 5 * per_radius
        x = (np.arange(n) - n // 2) * dx
        X, Y = np.meshgrid(x, x)
        t = time.perf_counter()
        r = frictal.contact(-(X ** 2 + Y ** 2) / (2 * R), spacing=dx, load=F, modulus=Es, poisson=0.0,
                            detrend="none")
        wall = time.perf_counter() - t
        rows.append((per_radius, f"{n} x {n}", math.sqrt(r["contact_area"] / math.pi) / a - 1,
                     r["max_pressure"] / p0 - 1, r["approach"] / (a * a / R) - 1,
                     r["contact_stiffness"] / (2 * Es * a) - 1, r["iterations"], wall))
    return rows


def cylinder_rows():
    Es, R, a = 1e9, 0.02, 200e-6
    Fp = math.pi * Es * a * a / (4 * R)
    p0 = 2 * Fp / (math.pi * a)
    rows = []
    for per_radius in (10, 30, 100, 300, 1000):
        dx = a / per_radius
        n = 8 * per_radius
        x = (np.arange(n) - n // 2) * dx
        t = time.perf_counter()
        r = frictal.contact(-x ** 2 / (2 * R), spacing=dx, load=Fp, modulus=Es, poisson=0.0, detrend="none")
        wall = time.perf_counter() - t
        rows.append((per_radius, f"{n}", r["contact_length"] / 2 / a - 1, r["max_pressure"] / p0 - 1,
                     r["iterations"], wall))
    return rows


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else None
    lines = [f"# Hertz convergence of `frictal contact` ({datetime.date.today()}, {platform.node()}, "
             f"{platform.processor() or platform.machine()})", "",
             "Relative error of each quantity against Hertz's closed form (bench/contact_hertz.py).", "",
             "## Sphere on a flat (map, padded)", "",
             "| a/dx | grid | contact radius | peak pressure | approach | stiffness | iterations | wall s |",
             "|---|---|---|---|---|---|---|---|"]
    for pr, g, ea, ep, ed, ek, it, w in sphere_rows():
        lines.append(f"| {pr} | {g} | {ea:+.2%} | {ep:+.3%} | {ed:+.3%} | {ek:+.3%} | {it} | {w:.2f} |")
    lines += ["", "## Cylinder on a flat (profile, plane strain, padded)", "",
              "| a/dx | points | half-width | peak pressure | iterations | wall s |", "|---|---|---|---|---|---|"]
    for pr, g, ea, ep, it, w in cylinder_rows():
        lines.append(f"| {pr} | {g} | {ea:+.2%} | {ep:+.3%} | {it} | {w:.2f} |")
    text = "\n".join(lines) + "\n"
    print(text)
    if out:
        with open(out, "w") as f:
            f.write(text)


if __name__ == "__main__":
    main()
