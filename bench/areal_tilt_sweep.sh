#!/bin/bash
# The 48 (pair, lateral) cases of docs/mujoco.md, "The 0.2° target": MuJoCo's tilt test against
# the continuous matched prediction and its spread (a slip's end moved by a sphere radius).
#   bash bench/areal_tilt_sweep.sh [BIN] [OUT]   (BIN default build/release/apps/frictal/frictal)
# Writes OUT/maps (bench/areal_tilt_pairs.py), OUT/runs/<case>-<lateral>.json and prints the table.
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=$(realpath "${1:-build/release/apps/frictal/frictal}")
OUT=${2:-/tmp/frictal-areal-sweep}
mkdir -p "$OUT/maps" "$OUT/runs"
PYTHONPATH=${PYTHONPATH:-build/release/python} /usr/bin/python3 bench/areal_tilt_pairs.py "$OUT/maps"
{
  for c in g30 g30m g60 g60m g90 g90-48 g90-20 bump1 bump2 bump3; do
    for lat in free locked; do echo "$c $lat --in-place --detrend none"; done
  done
  for c in iso1 iso2 iso3 iso4 ani1 ani2 ani3 ani4 x3p1 x3p2 x3p3 x3ps1 x3ps2 x3ps3; do
    for lat in free locked; do echo "$c $lat"; done
  done
} | xargs -P2 -L1 bash -c 'c=$0; lat=$1; shift; "'"$BIN"'" areal-tilt "'"$OUT"'/maps/$c-lower.x3p" "'"$OUT"'/maps/$c-upper.x3p" --lateral $lat --json "$@" > "'"$OUT"'/runs/$c-$lat.json"'
/usr/bin/python3 - "$OUT/runs" <<'PY'
import glob, json, os, sys
rows, tot = [], {"free": [0, 0, 0], "locked": [0, 0, 0]}
def miss(fa, lo, hi):  # distance from the simulated bracket (reading - 0.1, reading]
    return lo - fa if lo > fa else max(0.0, fa - 0.1 - hi)
print("| pair | lateral | MuJoCo (runs at) | continuous matched | its spread | ambiguous slips / slips | CPU s |")
print("|---|---|---|---|---|---|---|")
for f in sorted(glob.glob(os.path.join(sys.argv[1], "*.json"))):
    j = json.load(open(f))
    case, lat = os.path.basename(f)[:-5].rsplit("-", 1)
    fa = j["friction_angle_deg"]
    x = j["predicted_hold_angle_deg" if lat == "free" else "predicted_hold_angle_locked_deg"]
    lo, hi = j["continuous_hold_angle_range_deg"]
    m, mr = miss(fa, x, x), miss(fa, lo, hi)
    t = tot[lat]; t[0] += 1; t[1] += m <= 0.2; t[2] += mr <= 0.2
    print(f"| {case} | {lat} | {fa:.1f} | {x:.3f}{' ✗' if m > 0.2 else ''} | {lo:.3f}–{hi:.3f}{' ✗' if mr > 0.2 else ''} "
          f"| {j['continuous_ambiguous_slips']} / {j['continuous_slips']} | {j['seconds']:.1f} |")
for lat, (n, a, b) in tot.items():
    print(f"\n{lat}: within 0.2° of the continuous matched prediction {a}/{n}, of its spread {b}/{n}")
PY
