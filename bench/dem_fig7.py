#!/usr/bin/env python3
"""Paper Fig. 7 data: atan(F_t/F_n)/alpha against relative displacement / L_b for K0..K3 at
alpha = 20 deg (mu_a = 0, Table I/II), from `frictal tilt -o`. Writes OUT (default
out/dem-fig7.csv, git-ignored; one row per 10 ms of simulated time).
Usage: bench/dem_fig7.py [path/to/frictal] [OUT]"""
import csv, os, subprocess, sys, tempfile


def default_cli():
    """The CLI of the release build, from scripts/frictal-path (the one place that names it)."""
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
    rel = subprocess.run([os.path.join(root, "scripts", "frictal-path")], capture_output=True, text=True, check=True)
    return os.path.join(root, rel.stdout.strip())


cli = sys.argv[1] if len(sys.argv) > 1 else default_cli()
alpha, Lb = 20.0, 0.2
out = sys.argv[2] if len(sys.argv) > 2 else "out/dem-fig7.csv"
os.makedirs(os.path.dirname(out) or ".", exist_ok=True)
with open(out, "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["surface", "time_s", "tilt_deg", "displacement_over_Lb", "force_angle_over_alpha", "contacts"])
    for n in range(4):
        with tempfile.NamedTemporaryFile(suffix=".csv", delete=False) as tmp:
            path = tmp.name
        subprocess.run([cli, "tilt", "koch", "--iterations", str(n), "--alpha", str(alpha), "-o", path,
                        "--series-interval", "0.01"], check=True, stdout=subprocess.DEVNULL)
        for r in csv.DictReader(open(path)):
            w.writerow([f"K{n}", r["time_s"], r["tilt_deg"], f"{float(r['displacement_m']) / Lb:.6g}",
                        f"{float(r['force_angle_deg']) / alpha:.6g}", r["contacts"]])
        os.unlink(path)
print("wrote", out)
