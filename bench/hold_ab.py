#!/usr/bin/python3
"""`frictal signature --json` with the hold analysis (default) against `--no-hold`, on three
10^7-point pairs (self-affine H = 0.8 and 0.3, a 12-scale WM pair), for two builds A and B, runs
alternating (A default, A --no-hold, B default, B --no-hold, repeated), and whether B prints the
same numbers as A.

Pairs (made when missing, under --data): self-affine H = 0.8 and H = 0.3 (bench/make_pairs.py's
self_affine: Fourier-filtered white noise, spacing 1 nm, rms 1 um, seeds 1 and 2; written as .npy,
read with --spacing 1nm) and the 12-scale WM pair (`frictal surface wm -D 1.5 --n-max 11
--longest-wavelength 0.01 --length 0.2 --rms-height 1e-5 --spacing 2e-8`, seeds 1 and 2, X3P).

Wall and cpu: medians over --reps; peak: the largest resident set (wait4). --cores 0,1 pins every
run to those cores (taskset), e.g. two cores of a larger machine. Identity: every key of A's and
B's default JSON, but the wall times and `hold_events` (the lift's offset count), compared as
printed. Writes a Markdown table to --out.

  bench/hold_ab.py --a A_BIN --b B_BIN --out table.md [--reps 3] [--start-offset 0.002] [--cores 0,1]
"""
import argparse
import json
import os
import statistics
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from commands import machine, run_once  # noqa: E402

SKIP = {"wall_time_s", "hold_wall_time_s", "hold_events"}


def make_pairs(binary, data, n):
    os.makedirs(data, exist_ok=True)
    pairs = {}
    for h in (0.8, 0.3):
        files = [os.path.join(data, f"sa-H{h:g}-N{n}-{s}.npy") for s in (1, 2)]
        for seed, path in zip((1, 2), files):
            if not os.path.exists(path):
                code = ("import sys, numpy as np; sys.path.insert(0, sys.argv[1]); from make_pairs import self_affine; "
                        "x, z = self_affine(int(sys.argv[2]), float(sys.argv[3]), int(sys.argv[4])); "
                        "np.save(sys.argv[5], z)")
                subprocess.run([sys.executable, "-c", code, os.path.dirname(os.path.abspath(__file__)), str(n), str(h),
                                str(seed), path], check=True)
        pairs[f"self-affine H = {h:g}"] = files + ["--spacing", "1nm"]
    files = [os.path.join(data, f"wm-12-{s}.x3p") for s in (1, 2)]
    for seed, path in zip((1, 2), files):
        if not os.path.exists(path):
            subprocess.run([binary, "surface", "-o", path, "wm", "-D", "1.5", "--n-max", "11", "--longest-wavelength",
                            "0.01", "--length", "0.2", "--rms-height", "1e-5", "--spacing", "2e-8", "--seed", str(seed)],
                           check=True, stdout=subprocess.DEVNULL)
    pairs["WM, 12 scales"] = files
    return pairs


def flat(j, prefix=""):
    out = {}
    for k, v in j.items():
        if k in SKIP:
            continue
        if isinstance(v, dict):
            out.update(flat(v, prefix + k + "."))
        elif k == "warnings":  # a set: builds before commit e1f6b93 print the two readers' warnings in either order
            out[prefix + k] = sorted(json.dumps(w, sort_keys=True) for w in v)
        else:
            out[prefix + k] = v
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--a", required=True, help="CLI A (before)")
    ap.add_argument("--b", required=True, help="CLI B (after)")
    ap.add_argument("--out", required=True)
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--n", type=int, default=10_000_000, help="points of the self-affine profiles")
    ap.add_argument("--data", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "data", "hold-ab"))
    ap.add_argument("--start-offset", help="also with --start-offset X (m)")
    ap.add_argument("--cores", help="taskset CPU list for every run, e.g. 0,1")
    ap.add_argument("--only", help="comma-separated pair names' first word (self-affine,WM)")
    a = ap.parse_args()
    pin = ["taskset", "-c", a.cores] if a.cores else []
    pairs = make_pairs(a.b, a.data, a.n)
    if a.only:
        pairs = {k: v for k, v in pairs.items() if any(k.startswith(o) for o in a.only.split(","))}
    variants = [[]] + ([["--start-offset", a.start_offset]] if a.start_offset else [])
    lines = [f"# `frictal signature` with and without the hold analysis, A/B ({machine()}"
             + (f"; runs pinned to cores {a.cores}" if a.cores else "") + ")", "",
             f"A = {a.a}, B = {a.b}; wall and cpu medians of {a.reps} runs, A and B and both modes alternating; "
             "peak = largest resident set; ratios of the least runs (each mode's least disturbed run, on a shared "
             "machine the steadier figure). Produced by bench/hold_ab.py.", "",
             "| pair | A default wall / cpu / peak | A --no-hold | B default | B --no-hold | A ratio wall / memory "
             "| B ratio wall / cpu / memory | least runs: A wall / B wall / B cpu | B's numbers = A's |",
             "|---|---|---|---|---|---|---|---|---|"]
    for name, files in pairs.items():
        for extra in variants:
            res = {(t, m): [] for t in "AB" for m in ("default", "no-hold")}
            out_json = {}
            for r in range(a.reps):
                for tag, binary in (("A", a.a), ("B", a.b)):
                    for mode in ("default", "no-hold"):
                        # --no-hold takes no --start-offset: the plain signature is the reference
                        # --detrend none: the same surfaces for builds whose default form differs (none
                        # or a line; the hold analysis is the same either way)
                        argv = ["signature"] + files + ["--json", "--detrend", "none"] + \
                            (["--no-hold"] if mode == "no-hold" else extra)
                        keep = os.path.join(a.data, f"out-{tag}.json") if r == 0 and mode == "default" else None
                        w, m, cpu, err = run_once(pin[0] if pin else binary, (pin[1:] + [binary] if pin else []) + argv,
                                                  3600, keep)
                        if err:
                            sys.exit(f"{tag} {mode} {name}: {err}")
                        if keep:
                            out_json[tag] = json.load(open(keep))
                        res[(tag, mode)].append((w, cpu, m))
                        print(f"  {name:<22} {' '.join(extra):<22} {tag} {mode:<8} run {r + 1}: wall {w:6.2f} s  "
                              f"cpu {cpu:6.2f} s  peak {m:6.0f} MB", flush=True)
            med = {k: (statistics.median(x[0] for x in v), statistics.median(x[1] for x in v), max(x[2] for x in v))
                   for k, v in res.items()}
            # The least of each mode's runs: on a shared machine the least disturbed run of each.
            low = {k: (min(x[0] for x in v), min(x[1] for x in v)) for k, v in res.items()}
            fa, fb = flat(out_json["A"]), flat(out_json["B"])
            diff = sorted(k for k in set(fa) | set(fb) if fa.get(k) != fb.get(k))
            same = "yes" if not diff else f"no: {', '.join(diff[:6])}{' ...' if len(diff) > 6 else ''}"
            cell = lambda k: f"{med[k][0]:.2f} s / {med[k][1]:.2f} s / {med[k][2]:.0f} MB"  # noqa: E731
            ad, an, bd, bn = med[("A", "default")], med[("A", "no-hold")], med[("B", "default")], med[("B", "no-hold")]
            label = name + (f", {' '.join(extra)}" if extra else "")
            lines.append(f"| {label} | {cell(('A', 'default'))} | {cell(('A', 'no-hold'))} | {cell(('B', 'default'))} "
                         f"| {cell(('B', 'no-hold'))} | {ad[0] / an[0]:.2f} / {ad[2] / an[2]:.2f} "
                         f"| {bd[0] / bn[0]:.2f} / {bd[1] / bn[1]:.2f} / {bd[2] / bn[2]:.2f} "
                         f"| {low[('A', 'default')][0] / low[('A', 'no-hold')][0]:.2f} / "
                         f"{low[('B', 'default')][0] / low[('B', 'no-hold')][0]:.2f} / "
                         f"{low[('B', 'default')][1] / low[('B', 'no-hold')][1]:.2f} | {same} |")
            open(a.out, "w").write("\n".join(lines) + "\n")  # each pair's row as soon as it is measured
    print("\n".join(lines))


if __name__ == "__main__":
    main()
