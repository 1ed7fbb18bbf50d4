#!/usr/bin/env bash
# The map prediction's scaling over threads (drops run in parallel) on a many-core machine:
# x3p-2.x3p against itself, 4 x 4 drops at 16, 8, 4 threads, and 2 x 2 drops on 1 thread for the
# cost of one drop. Usage: bench/device-predict.sh FRICTAL OUTDIR (results: OUTDIR/*.json, times.txt).
set -euo pipefail
F=$1; OUT=$2
mkdir -p "$OUT"
{ echo "machine: $(nproc) cores; $(lscpu | grep 'Model name' | sed 's/  */ /g')"; date -u; "$F" --version; } > "$OUT/times.txt"
TIMEFORMAT="%R s wall, %U s user"
run() {
  local name=$1; shift
  { echo "== $name: $*"; time "$F" predict tests/data/x3p/x3p-2.x3p "$@" --json --quiet > "$OUT/$name.json"; } 2>> "$OUT/times.txt"
  /usr/bin/python3 -c "import json,sys; j=json.load(open('$OUT/$name.json')); print('   median %.4f deg, q05 %.4f, q95 %.4f, drops %d' % (j['friction_angle_deg'], j['friction_angle_q05_deg'], j['friction_angle_q95_deg'], j['drops']))" >> "$OUT/times.txt" 2>/dev/null || true
}
run d4-t16 --drops 4 --threads 16
run d4-t8 --drops 4 --threads 8
run d4-t4 --drops 4 --threads 4
run d2-t1 --drops 2 --threads 1
run d5-t16-locked --drops 5 --threads 16 --locked
cat "$OUT/times.txt"
