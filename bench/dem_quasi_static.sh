#!/bin/bash
# Issue 23: the quasi-static tilt protocol against the hold angle phi_qs from the rest offset, on
# WM pairs (D = 1.5, n_max = 6, L = 0.01 m, L_b = 0.2 m; rms 1e-5 and 1e-4 m) and a Fourier pair,
# rotation held, r = 2e-5 m, d = 0.01 m, over the normal stiffness. Writes one line per run:
# pair, k_n, simulated angle, phi_qs, rounded phi_qs, phi_in (deg), rest offset, the stops that hold
# in the prediction and in the run (m), increments, unrelaxed ones, steps, wall seconds, warnings.
# Usage: bench/dem_quasi_static.sh [path/to/frictal]  (about 1 min on one free core; the
# rows of docs/dem.md sec. 6 "The quasi-static protocol against the hold angle").
set -euo pipefail
F=${1:-build/release/apps/frictal/frictal}
F=$(readlink -f "$F")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
wm="wm -D 1.5 --n-max 6 --longest-wavelength 0.01 --length 0.2"
for s in 1 2 3 4; do
  "$F" surface $wm --rms-height 1e-5 --seed $s -o wm$s.csv 2> /dev/null
  "$F" surface $wm --rms-height 1e-4 --seed $s -o wmr$s.csv 2> /dev/null
done
for s in 1 2; do "$F" surface fourier --seed $s --rms-height 1e-5 -o fo$s.csv 2> /dev/null; done
run() {  # name lower upper k_n
  /usr/bin/time -f "%e" -o t.txt nice -n 19 "$F" tilt --lower "$2" --upper "$3" --protocol quasi-static \
    --hold-rotation --spheroradius 2e-5 --normal-stiffness "$4" --json > r.json 2> /dev/null
  /usr/bin/python3 - "$1" "$4" <<'PY'
import json, sys
j = json.load(open("r.json"))
wall = open("t.txt").read().split()[-1]
codes = ",".join(w["code"] for w in j["warnings"]) or "-"
print(f"{sys.argv[1]:8s} k_n={sys.argv[2]:5s} phi={j['friction_angle_deg']:.3f} phi_qs={j['predicted_hold_angle_deg']:.3f} "
      f"sphero={j['predicted_sphero_hold_angle_deg']:.3f} phi_in={j['predicted_inertial_hold_angle_deg']:.3f} "
      f"rest={j['rest_offset_m']:.6f} hold_stop={j['predicted_hold_offset_m']:.6f} run_stop={j['slide_start_offset_m']:.6f} "
      f"increments={j['increments']} unrelaxed={j['unrelaxed_increments']} steps={j['steps']} wall={wall}s warnings={codes}")
PY
}
for k in 6e7 6e8 6e9; do run wm12 wm1.csv wm2.csv $k; done
for k in 6e7 6e8; do run wm34 wm3.csv wm4.csv $k; done
for k in 6e7 6e8; do run fo12 fo1.csv fo2.csv $k; done
for k in 6e6 6e7 6e8; do run wmr12 wmr1.csv wmr2.csv $k; done
for k in 6e6 6e7 6e8; do run wmr34 wmr3.csv wmr4.csv $k; done
