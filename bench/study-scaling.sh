#!/usr/bin/env bash
# Times the full fig14-18-wm-statistics grid (11 D x 11 n_max x 20 pairs = 2420 tasks) on 1 and
# 2 threads (also pinned to cores) and on 1 and 2 MPI ranks, and checks that the stores hold identical rows.
# Usage: bench/study-scaling.sh [BUILD_DIR=build/release] [REPEATS=2]
# Results: docs/performance.md, "Studies and the reproduction". Every run computes every task (--cache none:
# the result cache would otherwise give the second configuration the first one's results).
set -euo pipefail
cd "$(dirname "$0")/.."
F="${1:-build/release}/frictal"
R="${2:-2}"
S=studies/fig14-18-wm-statistics.toml
OUT=$(mktemp -d)
ROOT=""
if [[ $(id -u) -eq 0 ]]; then ROOT="--allow-run-as-root"; fi
echo "machine: $(nproc) cores, $(uname -sr), $(g++ --version | head -1)"
for rep in $(seq "$R"); do
  for cfg in t1 t2 t2pin n1 n2; do
    rm -f "$OUT/$cfg.sqlite"*
    echo -n "$cfg rep $rep (load $(cut -d' ' -f1 /proc/loadavg)): "
    case $cfg in
      t1) cmd=("$F" study run $S --store "$OUT/$cfg.sqlite" --threads 1 --cache none --progress none) ;;
      t2) cmd=("$F" study run $S --store "$OUT/$cfg.sqlite" --threads 2 --cache none --progress none) ;;
      t2pin) cmd=("$F" study run $S --store "$OUT/$cfg.sqlite" --threads 2 --pin --cache none --progress none) ;;
      n1) cmd=(mpirun -n 1 $ROOT "$F" study run $S --store "$OUT/$cfg.sqlite" --cache none --progress none) ;;
      n2) cmd=(mpirun -n 2 --oversubscribe $ROOT "$F" study run $S --store "$OUT/$cfg.sqlite" --cache none --progress none) ;;
    esac
    /usr/bin/time -f "wall %e s, user %U s" "${cmd[@]}" 2>&1 >/dev/null | tail -1
  done
done
q="SELECT task_id, status, seed FROM tasks ORDER BY 1; SELECT * FROM scalars ORDER BY 1, 2; SELECT task_id, name, json FROM arrays ORDER BY 1, 2"
if command -v sqlite3 >/dev/null; then
  for cfg in t1 t2 t2pin n1 n2; do echo "$cfg rows: $(sqlite3 "$OUT/$cfg.sqlite" "$q" | md5sum | cut -c1-32)"; done
fi
rm -rf "$OUT"
