#!/usr/bin/env python3
"""How often the spike rule fires on clean data, and what removing the spikes does to the answer.

Runs `frictal predict --json` with and without `--remove-spikes` on every profile and map in
tests/data and on generated self-affine profiles (clean by construction: the rule must leave them
alone), and prints one Markdown row per surface: points, points the rule flags (spikes_removed),
the prediction (median and 5-95 %) without and with the removal, and whether the spikes warning
fired. The numbers behind the default of the spike filter (docs/analysis.md, "Spikes").

    bench/spike_default.py build/release/apps/frictal/frictal [--timeout 60]
"""
import argparse
import json
import pathlib
import subprocess
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]


def predict(cli, path, extra, timeout):
    t0 = time.time()
    try:
        r = subprocess.run([cli, "predict", str(path), "--json", "-q", *extra], capture_output=True, text=True,
                           timeout=timeout)
    except subprocess.TimeoutExpired:
        return None, f"timeout {timeout} s"
    if r.returncode != 0:
        return None, r.stderr.strip().splitlines()[-1][:80] if r.stderr.strip() else f"exit {r.returncode}"
    j = json.loads(r.stdout)
    j["_seconds"] = time.time() - t0
    return j, ""


def row(cli, path, label, timeout):
    a, why_a = predict(cli, path, [], timeout)
    b, why_b = predict(cli, path, ["--remove-spikes"], timeout)
    if a is None and b is None:
        return f"| {label} | - | - | {why_a} | {why_b} | - |"

    def fmt(j, why):
        if j is None:
            return why
        return (f"{j['friction_angle_deg']:.4g} ({j['friction_angle_q05_deg']:.3g}-{j['friction_angle_q95_deg']:.3g})"
                f" [{j['_seconds']:.1f} s]")

    flagged = b["spikes_removed"] if b else "-"
    warned = "yes" if a and any(w["code"] == "spikes" for w in a["warnings"]) else "no"
    return f"| {label} | {flagged} | {warned} | {fmt(a, why_a)} | {fmt(b, why_b)} |"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("cli")
    ap.add_argument("--timeout", type=int, default=60)
    a = ap.parse_args()
    print("| surface | points flagged | spikes warning | phi without removal, deg (5-95 %) [time] | "
          "phi with --remove-spikes, deg (5-95 %) [time] |")
    print("|---|---|---|---|---|")
    data = ROOT / "tests" / "data"
    for sub in ("profiles", "maps", "x3p", "instruments"):
        for f in sorted((data / sub).iterdir()):
            if f.is_file() and f.suffix not in (".md",):
                print(row(a.cli, f, f"{sub}/{f.name}", a.timeout), flush=True)
    with tempfile.TemporaryDirectory() as tmp:
        for hurst in (0.3, 0.5, 0.8):
            for seed in (1, 2, 3):
                out = pathlib.Path(tmp) / f"sa-{hurst}-{seed}.csv"
                subprocess.run([a.cli, "surface", "self-affine", "--points", "4096", "--length", "1e-3", "--hurst",
                                str(hurst), "--rms-height", "1e-6", "--seed", str(seed), "-o", str(out)],
                               check=True, capture_output=True)
                print(row(a.cli, out, f"self-affine H = {hurst}, seed {seed} (4096 points)", a.timeout), flush=True)


if __name__ == "__main__":
    main()
