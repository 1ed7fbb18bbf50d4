#!/usr/bin/python3
"""Plots Fig. 4 (theta/alpha against x_ofs/lambda for K0..K3) from scripts/reproduce's CSVs."""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

out = sys.argv[1]
alpha, lam = 5.0, 0.01
fig, axes = plt.subplots(4, 1, figsize=(6, 8), sharex=True)
for n, ax in enumerate(axes):
    with open(f"{out}/k{n}-signature.csv") as f:
        rows = list(csv.DictReader(f))
    # theta is piecewise constant between events: draw each interval from its two one-sided values.
    xs, ys = [], []
    for a, b in zip(rows, rows[1:]):
        s0, s1 = float(a["offset_m"]) / lam, float(b["offset_m"]) / lam
        xs += [s0, s1]
        ys += [float(a["theta_right_deg"]) / alpha, float(b["theta_left_deg"]) / alpha]
    ax.plot(xs, ys, lw=1)
    ax.set_ylabel(f"K{n}: θ/α")
    ax.axhline([1, 1, 2, 3][n], color="grey", ls=":", lw=0.8)
    ax.axhline(-[1, 1, 2, 3][n], color="grey", ls=":", lw=0.8)
axes[-1].set_xlabel("x_ofs / λ")
fig.suptitle("Signature functions of Koch surfaces, α = 5° (paper Fig. 4)")
fig.tight_layout()
fig.savefig(f"{out}/fig04.png", dpi=120)
