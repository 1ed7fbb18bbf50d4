#!/usr/bin/env bash
# CTest report.pages: builds the pages a person reads and checks them in headless Chromium
# (tests/report/check_page.py): a measured X3P scan report, a profile-pair report, a map-pair report, and an
# index.html built from a quick subset of the reproduction (Fig. 3, 4, 9, 11, 12, 13, 16).
# Screenshots are left in OUTDIR/*.png to look at.
#   tests/report/test-pages.sh FRICTAL OUTDIR CHROMIUM
set -euo pipefail
BIN=$1
OUT=$2
CHROME=$3
SRC=$(cd "$(dirname "$0")/../.." && pwd)
PY=/usr/bin/python3
rm -rf "$OUT"
mkdir -p "$OUT/index-out/fig04" "$OUT/index-out/studies"
fail=0

# 1. measured areal map (Sensofar confocal scan, NaN holes) and a profile pair
"$BIN" report "$SRC/tests/data/x3p/sample-land.x3p" --atomic-friction 0.2 --threads 2 -o "$OUT/x3p-report.html" 2>/dev/null
"$BIN" surface wm --dimension 1.5 --seed 1 -o "$OUT/wm-a.csv" 2>/dev/null
"$BIN" surface wm --dimension 1.5 --seed 2 -o "$OUT/wm-b.csv" 2>/dev/null
"$BIN" report "$OUT/wm-a.csv" "$OUT/wm-b.csv" --atomic-friction 0.3 --threads 2 -o "$OUT/pair-report.html" 2>/dev/null
# two measured maps of one spacing (AFM scans, a 2 um window of each): both maps, the pair's polar plots
"$BIN" report "$SRC/tests/data/instruments/mi-1.mi" "$SRC/tests/data/instruments/nid-1.nid" --crop 0,2um,0,2um \
  --directions 6 --drops 3 --resolution-steps 4 --threads 2 -q -o "$OUT/map-pair-report.html" 2>/dev/null
# (a 12.5 um stylus tip: its short reliability cutoff is drawn on the resolution plot)
"$BIN" report "$SRC/tests/data/profiles/dektak-1.csv" --tip-radius 12.5um --threads 2 -o "$OUT/dektak-report.html" 2>/dev/null
grep -q "reliable above" "$OUT/dektak-report.html" || { echo "test-pages: no tip cutoff line on dektak-report.html" >&2; fail=1; }
$PY "$SRC/tests/report/check_page.py" "$CHROME" "$OUT/x3p-report.html" "$OUT/x3p-report.png" --min-figures 5 || fail=1
$PY "$SRC/tests/report/check_page.py" "$CHROME" "$OUT/pair-report.html" "$OUT/pair-report.png" --min-figures 4 || fail=1
$PY "$SRC/tests/report/check_page.py" "$CHROME" "$OUT/map-pair-report.html" "$OUT/map-pair-report.png" --min-figures 9 || fail=1
$PY "$SRC/tests/report/check_page.py" "$CHROME" "$OUT/dektak-report.html" "$OUT/dektak-report.png" --min-figures 4 || fail=1

# 2. index.html from a quick subset: Fig. 4 as scripts/reproduce makes it, one real study (Fig. 9)
I="$OUT/index-out"
for n in 0 1 2 3; do
  "$BIN" surface koch --iterations $n --alpha 5 --wavelength 0.01 --length 0.2 -o "$I/fig04/k$n.csv" 2>/dev/null
  "$BIN" signature "$I/fig04/k$n.csv" --period 0.01 -o "$I/fig04/k$n-signature.csv" --json > "$I/fig04/k$n.json"
done
$PY "$SRC/scripts/plot_fig04.py" "$I/fig04"
# (the study files and plot_studies.py's options may change with the study registry: a missing plot
# shows as "not produced", which the page check accepts; the six figures computed here are required)
if [[ -f "$SRC/studies/fig09-divider.toml" ]]; then
  "$BIN" study run "$SRC/studies/fig09-divider.toml" --store "$I/studies/fig09-divider.sqlite" --quick >/dev/null 2>&1 || true
  "$BIN" study report "$I/studies/fig09-divider.sqlite" -o "$I/studies/fig09-divider-report.md" >/dev/null 2>&1 || true
  $PY "$SRC/scripts/plot_studies.py" "$I" --frictal "$BIN" --study "$SRC/studies/fig09-divider.toml" "$I/studies/fig09-divider.sqlite" >/dev/null 2>&1 || true
fi
(cd "$SRC" && $PY scripts/make_index.py "$BIN" "$I" --quick --only 3,4,9,11,12,13,16)
grep -q "SUPPORTED" "$I/index.html" || { echo "test-pages: index.html has no verdict" >&2; fail=1; }
if grep -q "NOT SUPPORTED" "$I/index.html"; then echo "test-pages: a computed figure's verdict is NOT SUPPORTED" >&2; fail=1; fi
$PY "$SRC/tests/report/check_page.py" "$CHROME" "$I/index.html" "$OUT/index.png" --width 1250 --min-figures 6 || fail=1
exit $fail
