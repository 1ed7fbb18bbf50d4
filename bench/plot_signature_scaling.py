#!/usr/bin/env python3
"""Plots the signature scaling benchmarks (BM_SignatureScaling and BM_SignatureScalingNonAligned,
bench/bench_signature.cpp): CPU time per offset vs number of points, for both surface kinds.

Usage: bench/plot_signature_scaling.py BEFORE.json NOW.json OUT.png

BEFORE: a run of a build whose BM_SignatureScaling has no `tilted` argument (block maxima only,
without the index search's tilted lines), e.g. one built by bench/build-baseline.sh.
NOW: a run with BM_SignatureScaling/kind/points/tilted (tilted 1: the default, 0: block maxima
only) and BM_SignatureScalingNonAligned/kind/points/grid (grids that do not align, sampled).
Left: everything on log axes. Right: the aligned runs of NOW on a linear axis, where a flat cost
per offset shows as a horizontal line.
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

KINDS = {0: "self-affine (H = 0.8)", 1: "WM, 12 scales"}
COLORS = {0: "tab:blue", 1: "tab:red"}


def load(path):
    """{(benchmark, kind, variant): [(N, us per offset)]}, context."""
    d = json.load(open(path))
    out = {}
    for b in d["benchmarks"]:
        name = b["name"].split("/")
        if name[0] not in ("BM_SignatureScaling", "BM_SignatureScalingNonAligned"):
            continue
        parts = dict(p.split(":") for p in name[1:] if ":" in p and not p.startswith(("iterations", "real_time")))
        kind, n = int(parts["kind"]), int(parts["points"])
        variant = int(parts.get("tilted", parts.get("grid", -1)))
        out.setdefault((name[0], kind, variant), []).append((n, b["cpu_seconds_per_offset"] * 1e6))
    return {k: sorted(v) for k, v in out.items()}, d["context"]


def main():
    before, _ = load(sys.argv[1])
    now, ctx = load(sys.argv[2])
    fig, (ax, lin) = plt.subplots(1, 2, figsize=(11.5, 6.6))
    for kind, label in KINDS.items():
        c = COLORS[kind]
        series = [
            (before.get(("BM_SignatureScaling", kind, -1)), ":", "o", f"{label}: BEFORE"),
            (now.get(("BM_SignatureScaling", kind, 0)), "--", "^", f"{label}: block maxima only"),
            (now.get(("BM_SignatureScaling", kind, 1)), "-", "s", f"{label}: NOW (tilted lines)"),
            (now.get(("BM_SignatureScalingNonAligned", kind, 1)), "-.", "x",
             f"{label}: offsets between lattice offsets (sampled)"),
            (now.get(("BM_SignatureScalingNonAligned", kind, 2)), "-.", "+",
             f"{label}: 0.7 N upper points (sampled)"),
        ]
        for data, ls, mk, lab in series:
            if data:
                n, t = zip(*data)
                ax.plot(n, t, ls=ls, marker=mk, color=c, label=lab, lw=1.2, ms=5)
        for variant, ls, mk, lab in ((1, "-", "s", "now (tilted lines)"), (0, "--", "^", "block maxima only")):
            data = now.get(("BM_SignatureScaling", kind, variant))
            if data:
                n, t = zip(*data)
                lin.plot(n, t, ls=ls, marker=mk, color=c, label=f"{label}: {lab}")
                for x, y in data:
                    if variant == 1:
                        lin.annotate(f"{y:.2f}", (x, y), textcoords="offset points",
                                     xytext=(4, 6 if kind == 1 else -13), fontsize=8, color=c)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("points per profile N")
    ax.set_ylabel("CPU time per offset (µs, one thread)")
    ax.set_title("all runs (log scale)", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    lin.set_xscale("log")
    lin.set_ylim(0, None)
    lin.set_xlabel("points per profile N")
    lin.set_ylabel("CPU time per offset (µs, one thread)")
    lin.set_title("aligned grids, exact (every event), linear scale", fontsize=10)
    lin.grid(True, which="both", alpha=0.3)
    fig.suptitle("Signature: cost per offset vs N (offsets one point spacing apart)")
    fig.text(0.01, 0.01, f"{ctx.get('host_name', '')}, {ctx.get('num_cpus', '?')} CPUs, {ctx['date'][:10]}",
             fontsize=7, color="gray")
    handles, labels = ax.get_legend_handles_labels()  # the right panel's lines are among them
    fig.legend(handles, labels, loc="lower center", ncol=2, fontsize=8)
    fig.tight_layout(rect=(0, 0.2, 1, 1))
    fig.savefig(sys.argv[3], dpi=120)


if __name__ == "__main__":
    main()
