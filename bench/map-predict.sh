#!/usr/bin/env bash
# The map prediction (`frictal predict` on two maps: the continuous free block over an N x N grid
# of drops) on random map pairs (bench/make_map_pairs.py: isotropic and anisotropic, H 0.8 and
# 0.5): user CPU, wall and peak memory per pair, and, with a second build B, every drop's hold
# angle against B's (identical, or how far and whether inside the drop's spread). Writes
# bench/results/map-predict-DATE.tsv.
#   bench/map-predict.sh [BUILD_A [BUILD_B]]     N=160 ROLLOFF=32 DROPS=8 THREADS=2
set -euo pipefail
cd "$(dirname "$0")/.."
A=$(scripts/frictal-path "${1:-build/release}")
B=${2:+$(scripts/frictal-path "$2")}
N=${N:-160}
ROLLOFF=${ROLLOFF:-32}
DROPS=${DROPS:-8}
THREADS=${THREADS:-2}
DATA=bench/data/maps
mkdir -p "$DATA" bench/results
PYTHONPATH=$(dirname "$A")/../../python:${PYTHONPATH:-} /usr/bin/python3 bench/make_map_pairs.py "$DATA" "$N" "$ROLLOFF"
out=bench/results/map-predict-$(date -u +%Y-%m-%d).tsv
printf 'pair\tbuild\tdrops\tuser_s\twall_s\tpeak_MB\tmedian_deg\tq05_deg\tq95_deg\n' >"$out"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for pair in iso1 iso2 ani1 ani2; do
  lo=$DATA/$pair-n$N-r$ROLLOFF-lower.x3p up=$DATA/$pair-n$N-r$ROLLOFF-upper.x3p
  for build in A B; do
    bin=$A
    [[ $build == B ]] && { [[ -n "$B" ]] || continue; bin=$B; }
    /usr/bin/time -f '%U %e %M' -o "$tmp/time" "$bin" predict "$lo" "$up" --drops "$DROPS" --threads "$THREADS" \
      --quiet --json >"$tmp/$pair-$build.json"
    read -r user wall peak <"$tmp/time"
    /usr/bin/python3 - "$tmp/$pair-$build.json" "$pair" "$build" "$user" "$wall" "$peak" >>"$out" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
print("\t".join([sys.argv[2], sys.argv[3], str(j["drops"]), sys.argv[4], sys.argv[5], str(int(sys.argv[6]) // 1024),
                 f'{j["friction_angle_deg"]:.4f}', f'{j["friction_angle_q05_deg"]:.4f}', f'{j["friction_angle_q95_deg"]:.4f}']))
PY
  done
  if [[ -n "$B" ]]; then
    /usr/bin/python3 - "$tmp/$pair-A.json" "$tmp/$pair-B.json" "$pair" <<'PY'
import json, sys
a = json.load(open(sys.argv[1]))["drop_friction_angles_deg"]
b = json.load(open(sys.argv[2]))["drop_friction_angles_deg"]
diff = [i for i, (x, y) in enumerate(zip(a, b)) if x != y]
print(f"{sys.argv[3]}: {len(a)} drops, {len(a) - len(diff)} identical;",
      ", ".join(f"drop {i}: {a[i]:.4f} vs {b[i]:.4f} deg" for i in diff) or "all identical")
PY
  fi
done
column -t -s $'\t' "$out"
