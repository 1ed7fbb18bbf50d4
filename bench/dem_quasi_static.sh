#!/bin/bash
# The quasi-static tilt protocol against the hold angle phi_qs from the rest offset, on
# WM pairs (D = 1.5, n_max = 6, L = 0.01 m, L_b = 0.2 m; rms 1e-5 and 1e-4 m), Fourier pairs, and
# two measured pairs (the README's Dektak halves; two rows of the X3P map tests/data/x3p/x3p-2.x3p),
# rotation held, r = 2e-5 m, d = 0.01 m, over the normal stiffness and both contact rules.
# Writes one line per run: pair, k_n, rule, simulated angle, phi_qs, rounded phi_qs, phi_in (deg),
# rest offset, the stops that hold in the prediction and in the run (m), increments, unrelaxed
# ones, steps, wall seconds, warnings.
# Usage: bench/dem_quasi_static.sh [path/to/frictal] [rules]   (rules: "pairs closest" by default;
# about 2 min per rule on one free core; the rows of docs/dem.md sec. 6).
set -euo pipefail
F=${1:-build/release/apps/frictal/frictal}
F=$(readlink -f "$F")
RULES=${2:-pairs closest}
repo=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
wm="wm -D 1.5 --n-max 6 --longest-wavelength 0.01 --length 0.2"
for s in 1 2 3 4 5 6; do
  "$F" surface $wm --rms-height 1e-5 --seed $s -o wm$s.csv 2> /dev/null
  "$F" surface $wm --rms-height 1e-4 --seed $s -o wmr$s.csv 2> /dev/null
done
for s in 1 2 3 4; do "$F" surface fourier --seed $s --rms-height 1e-5 -o fo$s.csv 2> /dev/null; done
# Measured pairs, each scaled isotropically to the Table I block (0.2 m) and its form removed.
PYTHONPATH="$repo/build/release/python" /usr/bin/python3 - "$repo" <<'PY'
import sys, numpy as np, frictal
repo = sys.argv[1]
scan = frictal.read_profile(f"{repo}/tests/data/profiles/dektak-1.csv")   # the README's pair
z = np.asarray(scan.z)[::4]
x = np.linspace(0, scan.x[-1], len(scan.z))[::4]
n = len(x) // 2
scale = 0.2 / (x[n - 1] - x[0])
for name, part in (("dk-a.csv", slice(0, n)), ("dk-b.csv", slice(n, 2 * n))):
    half = frictal.Profile(scale * (x[part] - x[part][0]), scale * z[part])
    frictal.write_profile_csv(name, frictal.detrend(half, "poly:2"))
m = frictal.read_map(f"{repo}/tests/data/x3p/x3p-2.x3p")                  # rows 150 and 450
h = np.asarray(m["heights"]); dx = m["dx"]
for name, row in (("x3-a.csv", 150), ("x3-b.csv", 450)):
    zr = h[row]; xr = dx * np.arange(len(zr)); s = 0.2 / xr[-1]
    frictal.write_profile_csv(name, frictal.detrend(frictal.Profile(s * xr, s * zr), "poly:2"))
PY
run() {  # name lower upper k_n rule
  /usr/bin/time -f "%e" -o t.txt nice -n 19 "$F" tilt --lower "$2" --upper "$3" --detrend none --protocol quasi-static \
    --hold-rotation --spheroradius 2e-5 --normal-stiffness "$4" --contact-rule "$5" --json > r.json 2> /dev/null
  /usr/bin/python3 - "$1" "$4" "$5" <<'PY'
import json, sys
j = json.load(open("r.json"))
wall = open("t.txt").read().split()[-1]
codes = ",".join(w["code"] for w in j["warnings"]) or "-"
print(f"{sys.argv[1]:6s} k_n={sys.argv[2]:5s} {sys.argv[3]:7s} phi={j['friction_angle_deg']:.3f} "
      f"phi_qs={j['predicted_hold_angle_deg']:.3f} sphero={j['predicted_sphero_hold_angle_deg']:.3f} "
      f"phi_in={j['predicted_inertial_hold_angle_deg']:.3f} rest={j['rest_offset_m']:.6f} "
      f"hold_stop={j['predicted_hold_offset_m']:.6f} run_stop={j['slide_start_offset_m']:.6f} "
      f"increments={j['increments']} unrelaxed={j['unrelaxed_increments']} steps={j['steps']} wall={wall}s "
      f"warnings={codes}", flush=True)
PY
}
for rule in $RULES; do
  for k in 6e7 6e8 6e9; do
    run wm12 wm1.csv wm2.csv $k $rule
    run wm34 wm3.csv wm4.csv $k $rule
    run wm56 wm5.csv wm6.csv $k $rule
    run fo12 fo1.csv fo2.csv $k $rule
    run fo34 fo3.csv fo4.csv $k $rule
    run dektak dk-a.csv dk-b.csv $k $rule
    run x3p x3-a.csv x3-b.csv $k $rule
  done
  for k in 6e6 6e7 6e8; do
    run wmr12 wmr1.csv wmr2.csv $k $rule
    run wmr34 wmr3.csv wmr4.csv $k $rule
    run wmr56 wmr5.csv wmr6.csv $k $rule
  done
done
