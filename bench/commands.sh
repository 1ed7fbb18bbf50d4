#!/usr/bin/env bash
# Whole-command timings of `frictal signature` on self-affine pairs (H = 0.8, spacing 1 nm, rms
# 1 um; bench/make_pairs.py) of 10^5, 10^6 and 10^7 points: wall time (median of REPS runs), peak
# memory (largest resident set, /usr/bin/time -v), with and without the hold analysis, and the
# scaling exponent fitted to wall ~ N^p. Writes bench/results/commands-DATE.md (machine: lscpu,
# nproc) and prints each time and memory against the recorded table bench/results/commands.tsv
# (RECORD=1 replaces that table with this run).
#   bench/commands.sh [BUILD_DIR]     SIZES="100000 1000000" REPS=3 bench/commands.sh
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build/release}
BIN=$(scripts/frictal-path "$BUILD")
[[ -x "$BIN" ]] || { echo "bench/commands.sh: no CLI at $BIN (build first)" >&2; exit 2; }
SIZES=${SIZES:-"100000 1000000 10000000"}
REPS=${REPS:-3}
DATA=bench/data
RES=bench/results
mkdir -p "$RES"
stamp=$(date -u +%Y-%m-%d)
out_md="$RES/commands-$stamp.md"
tsv=$(mktemp)
trap 'rm -f "$tsv" "$tsv".*' EXIT
for n in $SIZES; do /usr/bin/python3 bench/make_pairs.py "$n" --hurst 0.8 --out "$DATA" >/dev/null; done

# One row per (mode, N): median wall (s), max peak RSS (MB) over REPS runs.
run() {  # run MODE N ARGS...
  local mode=$1 n=$2
  shift 2
  local walls=() peak=0
  for ((r = 0; r < REPS; r++)); do
    /usr/bin/time -v "$BIN" signature "$DATA/sa-H0.8-N$n-1.csv" "$DATA/sa-H0.8-N$n-2.csv" --json "$@" \
      >/dev/null 2>"$tsv.err"
    local w m
    w=$(awk -F': ' '/Elapsed \(wall clock\)/ {n = split($2, p, ":"); s = 0; for (i = 1; i <= n; i++) s = s * 60 + p[i]; print s}' "$tsv.err")
    m=$(awk -F': ' '/Maximum resident set size/ {print $2}' "$tsv.err")
    walls+=("$w")
    ((m > peak)) && peak=$m
  done
  local med
  med=$(printf '%s\n' "${walls[@]}" | sort -g | awk '{a[NR] = $1} END {print a[int((NR + 1) / 2)]}')
  printf '%s\t%s\t%s\t%s\n' "$mode" "$n" "$med" "$((peak / 1024))" >>"$tsv"
  printf '  %-8s N = %-9s wall %6.2f s  peak %6d MB\n' "$mode" "$n" "$med" "$((peak / 1024))"
}
echo "frictal signature, $REPS runs each ($BIN)"
for n in $SIZES; do
  run default "$n"
  run no-hold "$n" --no-hold
done

/usr/bin/python3 - "$tsv" "$out_md" "$RES/commands.tsv" "${RECORD:-0}" "$REPS" <<'PY'
import math, os, subprocess, sys, datetime
tsv, out_md, recorded, record, reps = sys.argv[1:6]
rows = [l.split("\t") for l in open(tsv).read().split("\n") if l]
data = {(m, int(n)): (float(w), int(p)) for m, n, w, p in rows}
def fit(mode):
    pts = [(math.log(n), math.log(w)) for (m, n), (w, _) in data.items() if m == mode and w > 0]
    if len(pts) < 2: return float("nan")
    mx = sum(x for x, _ in pts) / len(pts); my = sum(y for _, y in pts) / len(pts)
    return sum((x - mx) * (y - my) for x, y in pts) / sum((x - mx) ** 2 for x, _ in pts)
lscpu = subprocess.run(["lscpu"], capture_output=True, text=True).stdout
model = next((l.split(":", 1)[1].strip() for l in lscpu.splitlines() if l.startswith("Model name")), "?")
nproc = subprocess.run(["nproc"], capture_output=True, text=True).stdout.strip()
now = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
old = {}
if os.path.exists(recorded):
    for l in open(recorded):
        if l.startswith("#") or not l.strip(): continue
        m, n, w, p = l.split("\t")[:4]
        old[(m, int(n))] = (float(w), int(p))
lines = [f"# `frictal signature`: whole-command time and memory ({now})", "",
         f"Machine: {model}, nproc {nproc}. Pairs: bench/make_pairs.py (self-affine H = 0.8, spacing 1 nm, rms 1 um, "
         f"seeds 1 and 2, CSV). Wall: median of {reps} runs; peak: largest resident set (/usr/bin/time -v). "
         "Produced by bench/commands.sh.", "",
         "| N | wall (s) | peak (MB) | wall --no-hold (s) | peak --no-hold (MB) | time ratio | memory ratio |",
         "|---|---|---|---|---|---|---|"]
for n in sorted({n for _, n in data}):
    d, h = data.get(("default", n)), data.get(("no-hold", n))
    if d and h:
        lines.append(f"| {n:.0e} | {d[0]:.2f} | {d[1]} | {h[0]:.2f} | {h[1]} | {d[0] / h[0]:.2f} | {d[1] / h[1]:.2f} |")
lines += ["", f"Scaling exponent (wall ~ N^p, least squares over the sizes): default p = {fit('default'):.2f}, "
          f"--no-hold p = {fit('no-hold'):.2f}."]
if old:
    lines += ["", "Against the recorded table (bench/results/commands.tsv): this run / recorded.", "",
              "| mode | N | wall ratio | memory ratio |", "|---|---|---|---|"]
    for k in sorted(data):
        if k in old:
            lines.append(f"| {k[0]} | {k[1]:.0e} | {data[k][0] / old[k][0]:.2f} | {data[k][1] / old[k][1]:.2f} |")
text = "\n".join(lines) + "\n"
open(out_md, "w").write(text)
print(text)
if record == "1" or not old:
    with open(recorded, "w") as f:
        f.write(f"# mode\tN\twall_s\tpeak_MB\t({now}; {model}, nproc {nproc})\n")
        for (m, n), (w, p) in sorted(data.items()):
            f.write(f"{m}\t{n}\t{w}\t{p}\n")
    print(f"recorded as {recorded}")
PY
echo "wrote $out_md"
