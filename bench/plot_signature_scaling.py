#!/usr/bin/env python3
"""Plots the signature scaling benchmark (BM_SignatureScaling, bench/bench_signature.cpp):
CPU time per offset vs number of points, before and after, for both surface kinds.

Usage: bench/plot_signature_scaling.py BEFORE.json AFTER.json OUT.png
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

KINDS = {0: "self-affine (H = 0.8)", 1: "WM, 12 scales"}


def series(path):
    d = json.load(open(path))
    out = {}
    for b in d["benchmarks"]:
        if not b["name"].startswith("BM_SignatureScaling/"):
            continue
        parts = dict(p.split(":") for p in b["name"].split("/")[1:3])
        kind, n = int(parts["kind"]), int(parts["points"])
        out.setdefault(kind, []).append((n, b["cpu_seconds_per_offset"] * 1e6))
    return {k: sorted(v) for k, v in out.items()}, d["context"]


def main():
    before, ctx = series(sys.argv[1])
    after, _ = series(sys.argv[2])
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    colors = {0: "tab:blue", 1: "tab:red"}
    for kind, label in KINDS.items():
        for data, style, when in ((before, "--o", "before"), (after, "-s", "after")):
            if kind in data:
                n, t = zip(*data[kind])
                ax.plot(n, t, style, color=colors[kind], label=f"{label}, {when}")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("points per profile N")
    ax.set_ylabel("CPU time per offset (µs, one thread)")
    ax.set_title("Signature: cost per offset vs N (offsets one point spacing apart)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.text(0.01, 0.01, f"{ctx.get('host_name', '')}, {ctx.get('num_cpus', '?')} CPUs, {ctx['date'][:10]}",
             fontsize=7, color="gray")
    fig.tight_layout()
    fig.savefig(sys.argv[3], dpi=120)


if __name__ == "__main__":
    main()
