#!/bin/bash
# The issue-14 WM pair (D = 1.5, n_max = 6, seeds 1 and 2, L = 0.01 m, L_b = 0.2 m, rms 1e-5 m)
# on the tilt test over the spheroradius, with the default 0.1 s of settling and with 1 s: the
# simulated angle, the block's sliding speed when the tilt starts (settled_speed_m_s) and the
# warnings. Writes the markdown rows of docs/dem.md sec. 6 ("Which scale is the cause") to
# standard output. Usage: bench/dem_wm_settle.sh [path/to/frictal]  (about 1 min on 2 cores)
set -euo pipefail
F=${1:-$(cd "$(dirname "$0")/.." && readlink -f "$(scripts/frictal-path)")}
F=$(readlink -f "$F")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
wm="wm -D 1.5 --n-max 6 --longest-wavelength 0.01 --length 0.2 --rms-height 1e-5"
"$F" surface $wm --seed 1 -o wm1.csv 2> /dev/null
"$F" surface $wm --seed 2 -o wm2.csv 2> /dev/null
echo "| r (m) | simulated, settle 0.1 s | speed at the tilt start (mm/s) | simulated, settle 1 s | warnings (settle 0.1 s) |"
echo "|---|---|---|---|---|"
for r in 1e-4 5e-5 2e-5 1e-5 5e-6 1e-6; do
  nice -n 19 "$F" tilt --lower wm1.csv --upper wm2.csv --detrend none --spheroradius $r --json > a.json 2> /dev/null
  nice -n 19 "$F" tilt --lower wm1.csv --upper wm2.csv --detrend none --spheroradius $r --settle-time 1 --json > b.json 2> /dev/null
  /usr/bin/python3 - "$r" <<'PY'
import json, sys
a, b = json.load(open("a.json")), json.load(open("b.json"))
codes = lambda j: ", ".join(w["code"] for w in j["warnings"]) or "-"
print(f"| {sys.argv[1]} | {a['friction_angle_deg']:.3f} | {a['settled_speed_m_s'] * 1e3:.2f} | "
      f"{b['friction_angle_deg']:.3f} (speed {b['settled_speed_m_s']:.1e} m/s; {codes(b)}) | {codes(a)} |")
PY
done
