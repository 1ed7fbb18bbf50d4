#!/usr/bin/env bash
# The map prediction on nearly flat maps with spikes (bench/flat_maps.py: five 563 x 484 maps,
# 12 spikes each), with and without --remove-spikes: user CPU, wall, peak memory and the median
# (5-95 %) per map and build, one Markdown row each; with a second build B, A's and B's JSON
# compared (largest drop difference). The filled (spikes removed) pair must not cost more than
# the spiky one (bench/results/map-predict.md, "Nearly flat maps").
# A run over TIMEOUT seconds of wall time is stopped and its row says so (the smooth `longwave`
# map with its spikes removed is conformal to itself turned over: every sphere touches at once).
#   bench/flat-cost.sh [BUILD_A [BUILD_B]]     THREADS=1 TIMEOUT=600
set -euo pipefail
cd "$(dirname "$0")/.."
A=$(scripts/frictal-path "${1:-build/release}")
B=${2:+$(scripts/frictal-path "$2")}
THREADS=${THREADS:-1}
TIMEOUT=${TIMEOUT:-600}
DATA=bench/data/flat
mkdir -p "$DATA"
PYTHONPATH=$(dirname "$A")/../../python:${PYTHONPATH:-} /usr/bin/python3 bench/flat_maps.py "$DATA"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "| map | spikes | build | user s | wall s | peak MiB | median (5-95 %) deg |"
echo "|---|---|---|---|---|---|---|"
for name in wave noise tilt quant longwave; do
  f=$DATA/$name-spk.x3p
  for mode in kept removed; do
    extra=()
    [[ $mode == removed ]] && extra=(--remove-spikes)
    for build in A B; do
      bin=$A
      [[ $build == B ]] && { [[ -n "$B" ]] || continue; bin=$B; }
      if ! /usr/bin/time -f '%U %e %M' -o "$tmp/time" timeout "$TIMEOUT" "$bin" predict "$f" "${extra[@]}" \
        --threads "$THREADS" --quiet --json >"$tmp/$name-$mode-$build.json"; then
        echo "| $name | $mode | $build | $(tail -1 "$tmp/time" | cut -d' ' -f1) | stopped at $TIMEOUT s | | |"
        continue
      fi
      read -r user wall peak <"$tmp/time"
      /usr/bin/python3 - "$tmp/$name-$mode-$build.json" "$name" "$mode" "$build" "$user" "$wall" "$peak" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
print(f"| {sys.argv[2]} | {sys.argv[3]} | {sys.argv[4]} | {sys.argv[5]} | {sys.argv[6]} | {int(sys.argv[7]) // 1024} | "
      f"{j['friction_angle_deg']:.4f} ({j['friction_angle_q05_deg']:.4f}-{j['friction_angle_q95_deg']:.4f}) |")
PY
    done
    if [[ -n "$B" && -s "$tmp/$name-$mode-A.json" && -s "$tmp/$name-$mode-B.json" ]]; then
      /usr/bin/python3 - "$tmp/$name-$mode-A.json" "$tmp/$name-$mode-B.json" "$name" "$mode" <<'PY'
import json, sys
a = json.load(open(sys.argv[1]))["drop_friction_angles_deg"]
b = json.load(open(sys.argv[2]))["drop_friction_angles_deg"]
d = max(abs(x - y) for x, y in zip(a, b))
print(f"<!-- {sys.argv[3]} {sys.argv[4]}: {sum(x == y for x, y in zip(a, b))} of {len(a)} drops identical, largest difference {d:.3g} deg -->")
PY
    fi
  done
done
