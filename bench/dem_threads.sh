#!/bin/sh
# Whole-command timing of the tilt test with 1 and 2 threads (docs/dem.md sec. 7, "Threads"):
# K3 at alpha = 20 deg and K2 at alpha = 25 deg, the CLI's defaults, `--threads N`, pinned to
# CPUs 0 and 1, runs interleaved. Prints one line per run: case, threads, wall s (whole
# process), user s, setup s, stepping s, us per step, split steps, friction angle, load average.
# Usage: bench/dem_threads.sh [frictal binary] [repeats]
set -eu
BIN=${1:-$(dirname "$0")/../$("$(dirname "$0")/../scripts/frictal-path")}
REPEATS=${2:-3}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for rep in $(seq "$REPEATS"); do
  for case in "3 20" "2 25"; do
    set -- $case
    for t in 1 2; do
      load=$(cut -d' ' -f1 /proc/loadavg)
      /usr/bin/time -f "%e %U" -o "$tmp/time" taskset -c 0,1 "$BIN" tilt --json --threads "$t" koch -n "$1" --alpha "$2" \
        > "$tmp/out.json" 2>/dev/null
      python3 - "$tmp/out.json" "$tmp/time" "K$1 alpha=$2" "$t" "$load" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
wall, user = open(sys.argv[2]).read().split()[-2:]
print(f"{sys.argv[3]:<14} threads={sys.argv[4]} wall={float(wall):.2f} user={float(user):.2f} "
      f"setup={d['setup_time_s']:.3f} stepping={d['wall_time_s']:.3f} us/step={d['us_per_step']:.2f} "
      f"split={d['split_steps']}/{d['steps']} phi={d['friction_angle_deg']!r} load={sys.argv[5]}")
PY
    done
  done
done
