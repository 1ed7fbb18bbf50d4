#!/bin/bash
# The prediction against the simulation, statistically (bench/results/predict-vs-sim.md). Random pairs not tuned
# on (bench/predict_vs_sim_pairs.py), N x N drops each over the prediction's drop range; from every
# drop the simulated tilt test and the prediction from the same drop.
#   bash bench/predict_vs_sim.sh maps [BIN] [OUT] [N]       (MuJoCo, `frictal areal-tilt`)
#   SIM_ARGS="--settle-damping 100 --relaxation quench --quench-speed 1e-2" bash bench/predict_vs_sim.sh maps ...
#                           (settings of the simulation only; use a new OUT for each). This is the
#                           check's protocol (the quasi-static tilt: the drop settled under a
#                           viscous damping, the tilt quenched; bench/results/predict-vs-sim.md)
#   bash bench/predict_vs_sim.sh profiles [BIN] [OUT] [N]   (spheropolygons, `frictal tilt`)
#   MAP_SEEDS="211 261" ...  maps: another set of pairs (isotropic seeds 211-214, anisotropic 261-264)
#   JOBS=16 ...             processes at a time (default 2)
#   SIM_ONLY=1 ... maps ... only the simulations of an OUT that a NO_RUN=1 run prepared (its in/ and
#                           jobs.txt): no Python, no prediction, no table (a machine without numpy)
#   NO_RUN=1 ... maps ...   no new simulation: the tables over the simulations OUT holds (a pair
#                           not complete is left out and named), e.g. of a run stopped part way
# BIN default build/release/apps/frictal/frictal, OUT default /tmp/frictal-predict-vs-sim, N 4.
# JOBS processes at a time (xargs -P). Prints the tables (bench/results/predict-vs-sim.md).
#
# Maps, settings shared by both sides (the defaults of both commands, passed explicitly where the
# command takes them): sliding along +x, plane removed from both maps, the upper map turned over,
# free lateral motion, run-away distance D = 5% of the lower map along d (read from
# `predict --json`), spheres of radius a fifth of the lower map's smaller spacing, tilt steps 1 deg
# then 0.1 deg, mu_a = 0. Per drop: `frictal areal-tilt --start-offset X,Y` (the simulation),
# `frictal predict --start-offset X,Y` (the prediction) and `frictal areal-tilt --predict-only
# --start-offset X,Y` (the same prediction with its spread: each slip's end moved by a sphere
# radius). The drops are those of `frictal predict --drops N` (its distribution is checked to be
# the per-drop predictions). The rule is read two ways: "its spread" is the per-drop spread above,
# "over drops" the prediction's distribution over the drops (q05-q95 of `predict --drops N`).
set -euo pipefail
cd "$(dirname "$0")/.."
MODE=${1:?maps or profiles}
BIN=$(realpath "${2:-build/release/apps/frictal/frictal}")
OUT=${3:-/tmp/frictal-predict-vs-sim}
N=${4:-4}
PY=/usr/bin/python3
SIM_ARGS=${SIM_ARGS:-}
export PYTHONPATH=${PYTHONPATH:-build/release/python}

if [ "$MODE" = maps ]; then
  D=$OUT/maps
  mkdir -p "$D/in" "$D/runs"
  # The simulations kept in OUT are reused: they must have been run with the same SIM_ARGS.
  if [ -e "$D/sim-args.txt" ] && [ "$(cat "$D/sim-args.txt")" != "$SIM_ARGS" ]; then
    echo "$D holds simulations run with SIM_ARGS='$(cat "$D/sim-args.txt")': use another OUT" >&2; exit 2
  fi
  echo "$SIM_ARGS" > "$D/sim-args.txt"
  if [ -z "${SIM_ONLY:-}" ]; then
  $PY bench/predict_vs_sim_pairs.py maps "$D/in" ${MAP_SEEDS:-} > "$D/pairs.txt"
  for p in $(cat "$D/pairs.txt"); do
    "$BIN" predict "$D/in/$p-lower.x3p" "$D/in/$p-upper.x3p" --detrend plane --drops "$N" --json -q > "$D/$p-predict.json"
    RA=$($PY -c 'import json,sys; print(repr(json.load(open(sys.argv[1]))["runaway_distance_m"]))' "$D/$p-predict.json")
    k=0
    for xy in $($PY bench/predict_vs_sim_pairs.py offsets "$D/$p-predict.json" "$N" "$N"); do
      echo "$p $k $xy $RA"; k=$((k + 1))
    done
  done > "$D/jobs.txt"
  fi
  xargs -P "${JOBS:-2}" -L 1 bash -c '
    p=$0; k=$1; xy=$2; ra=$3; d='"$D"'; bin='"$BIN"'
    common=("$d/in/$p-lower.x3p" "$d/in/$p-upper.x3p" --detrend plane --runaway-distance "$ra" -q --json)
    if [ ! -s "$d/runs/$p-$k-sim.json" ]; then  # kept from an earlier run of the same OUT
      [ -z "'"${NO_RUN:-}"'" ] || exit 0          # NO_RUN: tables over what OUT holds
      "$bin" areal-tilt "${common[@]}" --start-offset="$xy" --lateral free '"$SIM_ARGS"' > "$d/runs/$p-$k-sim.json.tmp"
      mv "$d/runs/$p-$k-sim.json.tmp" "$d/runs/$p-$k-sim.json"
    fi
    # An increment that did not settle (its wait, 40 relaxation chunks, ran out: the block still
    # creeping, no quasi-static reading): once more with chunks 8 times as long; the first run is
    # kept as -sim-unsettled.json.
    if grep -q "\"unsettled_increments\": [1-9]" "$d/runs/$p-$k-sim.json" && [ ! -e "$d/runs/$p-$k-sim-unsettled.json" ] \
       && [ -z "'"${NO_RUN:-}"'" ]; then
      "$bin" areal-tilt "${common[@]}" --start-offset="$xy" --lateral free '"$SIM_ARGS"' --relax-chunk 4 > "$d/runs/$p-$k-sim.json.tmp"
      mv "$d/runs/$p-$k-sim.json" "$d/runs/$p-$k-sim-unsettled.json"
      mv "$d/runs/$p-$k-sim.json.tmp" "$d/runs/$p-$k-sim.json"
    fi
    [ -z "'"${SIM_ONLY:-}"'" ] || exit 0
    "$bin" areal-tilt "${common[@]}" --start-offset="$xy" --lateral free --predict-only > "$d/runs/$p-$k-spread.json"
    "$bin" predict "${common[@]}" --start-offset="$xy" > "$d/runs/$p-$k-predict.json"
  ' < "$D/jobs.txt"
  [ -z "${SIM_ONLY:-}" ] || exit 0
  $PY - "$D" <<'PY'
import json, os, statistics, sys
d = sys.argv[1]
incomplete = []
pairs = open(f"{d}/pairs.txt").read().split()
jobs = [l.split() for l in open(f"{d}/jobs.txt")]
TOL = 0.3
print("| pair | drop | offset (µm) | MuJoCo (runs at) | predicted | its spread | rule (its spread) | rule (over drops) | rests apart (µm) | matched from the simulated rest | CPU s |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
summary = []
unsettled = 0
nsame = 0  # drops whose simulated rest lies within a sphere radius of the predicted rest
for p in pairs:
    pd = json.load(open(f"{d}/{p}-predict.json"))
    sims, preds, npass, nrest, nover = [], [], 0, 0, 0
    q5, q95 = pd["friction_angle_q05_deg"], pd["friction_angle_q95_deg"]
    mine = [j for j in jobs if j[0] == p]
    if not all(os.path.exists(f"{d}/runs/{p}-{k}-{w}.json") and os.path.getsize(f"{d}/runs/{p}-{k}-{w}.json") > 0
               for (_, k, _, _) in mine for w in ("sim", "spread", "predict")):
        incomplete.append(p)
        continue
    for (q, k, xy, ra) in mine:
        s = json.load(open(f"{d}/runs/{p}-{k}-sim.json"))
        sp = json.load(open(f"{d}/runs/{p}-{k}-spread.json"))
        pr = json.load(open(f"{d}/runs/{p}-{k}-predict.json"))
        fa, x = s["friction_angle_deg"], pr["friction_angle_deg"]
        lo, hi = sp["continuous_hold_angle_range_deg"]
        assert abs(sp["predicted_hold_angle_deg"] - x) < 1e-9, (p, k, "predict and areal-tilt --predict-only differ")
        assert abs(pd["drop_friction_angles_deg"][int(k)] - x) < 1e-9, (p, k, "predict --drops differs from --start-offset")
        ok = abs(fa - x) <= TOL or lo <= fa <= hi
        over = abs(fa - x) <= TOL or q5 <= fa <= q95  # the prediction's spread over the drops
        npass += ok
        nover += over
        unsettled += s["unsettled_increments"]
        nrest += abs(fa - s["predicted_hold_angle_deg"]) <= TOL
        sims.append(fa); preds.append(x)
        # Where the block came to rest at zero tilt: MuJoCo's against the prediction's.
        apart = 1e6 * ((s["rest_offset_m"][0] - pr["rest_offset_m"][0]) ** 2 + (s["rest_offset_m"][1] - pr["rest_offset_m"][1]) ** 2) ** 0.5
        nsame += apart <= s["sphere_radius_m"] * 1e6
        ox, oy = (float(v) * 1e6 for v in xy.split(","))
        print(f"| {p} | {k} | {ox:.0f}, {oy:.0f} | {fa:.1f}{'' if s['ran_away'] else ' (held)'} | {x:.3f} | {lo:.3f}–{hi:.3f} "
              f"| {'pass' if ok else 'FAIL'} | {'pass' if over else 'FAIL'} | {apart:.2f} | {s['predicted_hold_angle_deg']:.3f} | {s['seconds']:.1f} |")
    ms, mp = statistics.median(sims), statistics.median(preds)
    summary.append((p, len(sims), npass, ms, mp, pd["friction_angle_deg"], min(sims), max(sims), min(preds), max(preds), nrest, nover, q5, q95))
print()
print("| pair | drops | drops passing (its spread) | drops passing (over drops: q05–q95) | simulated median | predicted median (`predict --drops`) | difference | rule (0.3°) | simulated range | predicted range | within 0.3° from the simulated rest |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
for (p, n, k, ms, mp, mq, s0, s1, p0, p1, nr, no, a5, a95) in summary:
    print(f"| {p} | {n} | {k} / {n} | {no} / {n} ({a5:.2f}–{a95:.2f}) | {ms:.2f} | {mp:.3f} ({mq:.3f}) | {ms - mp:+.2f} | {'pass' if abs(ms - mp) <= TOL else 'FAIL'} "
          f"| {s0:.1f}–{s1:.1f} | {p0:.2f}–{p1:.2f} | {nr} / {n} |")
tot = sum(s[1] for s in summary); ok = sum(s[2] for s in summary)
print(f"\ndrops passing: {ok} / {tot} (its spread), {sum(s[11] for s in summary)} / {tot} (over drops); "
      f"pairs whose medians agree within {TOL}°: "
      f"{sum(abs(s[3] - s[4]) <= TOL for s in summary)} / {len(summary)}; pairs with every drop passing: "
      f"{sum(s[1] == s[2] for s in summary)} / {len(summary)} (its spread), "
      f"{sum(s[1] == s[11] for s in summary)} / {len(summary)} (over drops); drops within {TOL}° of the matched prediction "
      f"from the simulated rest: {sum(s[10] for s in summary)} / {tot}; simulated rest within a sphere radius of the "
      f"predicted rest: {nsame} / {tot}; unsettled increments: {unsettled}")
if incomplete:
    print(f"not run to the end (left out above): {' '.join(incomplete)}")
PY
elif [ "$MODE" = profiles ]; then
  # Profiles: `frictal tilt --protocol quasi-static --hold-rotation --initial-offset X` (the
  # spheropolygon engine, its scaled defaults: k_n, r, time step from the blocks' length and point
  # spacing; rule closest; increments of 0.01 deg) against `frictal predict --start-offset X` (the
  # quasi-static hold angle of the rigid profiles), both with the run-away distance of
  # `predict --json` (L_b / 20); N * N drops evenly over the prediction's drop range. Convergence,
  # measured at the middle drop of every pair: 10 k_n (and k_t), half the time-step safety factor,
  # half the spheroradius, half the tilt increment.
  D=$OUT/profiles
  mkdir -p "$D/in" "$D/runs"
  $PY bench/predict_vs_sim_pairs.py profiles "$D/in" > "$D/pairs.txt"
  ND=$((N * N))
  for p in $(cat "$D/pairs.txt"); do
    "$BIN" predict "$D/in/$p-lower.csv" "$D/in/$p-upper.csv" --detrend line --json -q > "$D/$p-predict.json"
    RA=$($PY -c 'import json,sys; print(repr(json.load(open(sys.argv[1]))["runaway_distance_m"]))' "$D/$p-predict.json")
    k=0
    for x in $($PY bench/predict_vs_sim_pairs.py offsets-along "$D/$p-predict.json" "$ND"); do
      echo "$p $k $x $RA"; k=$((k + 1))
    done
  done > "$D/jobs.txt"
  tilt='"$bin" tilt --lower "$d/in/$p-lower.csv" --upper "$d/in/$p-upper.csv" --detrend line --protocol quasi-static --hold-rotation --runaway-distance "$ra" --initial-offset="$x" --json -q'
  xargs -P "${JOBS:-2}" -L 1 bash -c '
    p=$0; k=$1; x=$2; ra=$3; shift 3; d='"$D"'; bin='"$BIN"'
    '"$tilt"' "$@" > "$d/runs/$p-$k-tilt.json"
    [ "${k#c}" = "$k" ] || exit 0  # a convergence run: no prediction
    "$bin" predict "$d/in/$p-lower.csv" "$d/in/$p-upper.csv" --detrend line --runaway-distance "$ra" --start-offset="$x" --json -q > "$d/runs/$p-$k-predict.json"
  ' < "$D/jobs.txt"
  # Convergence at the middle drop, from the settings the run used there.
  M=$((ND / 2))
  for p in $(cat "$D/pairs.txt"); do
    read -r kn kt r inc < <($PY -c 'import json,sys; s=json.load(open(sys.argv[1]))["settings"]; print(s["normal_stiffness"], s["tangential_stiffness"], s["spheroradius"], s["tilt_increment"])' "$D/runs/$p-$M-tilt.json")
    x=$(awk -v p="$p" -v m="$M" '$1 == p && $2 == m {print $3}' "$D/jobs.txt")
    ra=$(awk -v p="$p" -v m="$M" '$1 == p && $2 == m {print $4}' "$D/jobs.txt")
    k10=$($PY -c "print(10 * $kn, 10 * $kt)")
    echo "$p c-kn10 $x $ra --normal-stiffness ${k10% *} --tangential-stiffness ${k10#* }"
    echo "$p c-dt $x $ra --time-step-safety 0.25"
    echo "$p c-r $x $ra --spheroradius $($PY -c "print(0.5 * $r)")"
    echo "$p c-inc $x $ra --tilt-increment $($PY -c "print(0.5 * $inc)")"
  done > "$D/conv-jobs.txt"
  xargs -P "${JOBS:-2}" -L 1 bash -c '
    p=$0; k=$1; x=$2; ra=$3; shift 3; d='"$D"'; bin='"$BIN"'
    '"$tilt"' "$@" > "$d/runs/$p-$k-tilt.json"
  ' < "$D/conv-jobs.txt"
  $PY - "$D" "$M" <<'PY'
import json, statistics, sys
d, M = sys.argv[1], sys.argv[2]
pairs = open(f"{d}/pairs.txt").read().split()
jobs = [l.split() for l in open(f"{d}/jobs.txt")]
TOL = 0.3
def codes(j):
    return ",".join(sorted({w["code"] for w in j["warnings"]})) or "–"
print("| pair | drop | offset (µm) | DEM quasi-static | predicted | difference | rule (0.3°) | rule (over drops) | rest DEM / predicted (µm) | phi_qs from the DEM's rest | warnings | wall s |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|")
summary = []
for p in pairs:
    pd = json.load(open(f"{d}/{p}-predict.json"))
    sims, preds, npass, nover = [], [], 0, 0
    q5, q95 = pd["friction_angle_q05_deg"], pd["friction_angle_q95_deg"]
    for (q, k, x, ra) in (j for j in jobs if j[0] == p):
        t = json.load(open(f"{d}/runs/{p}-{k}-tilt.json"))
        pr = json.load(open(f"{d}/runs/{p}-{k}-predict.json"))
        fa, phi = t["friction_angle_deg"], pr["friction_angle_deg"]
        ok = abs(fa - phi) <= TOL
        over = ok or q5 <= fa <= q95  # the prediction's spread over the drops
        npass += ok
        nover += over
        sims.append(fa); preds.append(phi)
        print(f"| {p} | {k} | {float(x) * 1e6:.2f} | {fa:.2f}{'' if t['slid'] else ' (held)'} | {phi:.3f} | {fa - phi:+.3f} "
              f"| {'pass' if ok else 'FAIL'} | {'pass' if over else 'FAIL'} | {t['rest_offset_m'] * 1e6:.2f} / {pr['rest_offset_m'][0] * 1e6:.2f} "
              f"| {t['predicted_hold_angle_deg']:.3f} | {codes(t)} | {t['wall_time_s']:.1f} |")
    ms, mp = statistics.median(sims), statistics.median(preds)
    summary.append((p, len(sims), npass, ms, mp, pd["friction_angle_deg"], pd["friction_angle_q05_deg"], pd["friction_angle_q95_deg"], min(sims), max(sims), min(preds), max(preds), nover))
print()
print("| pair | drops | drops passing | drops passing (over drops: q05–q95) | simulated median | predicted median | difference | rule (0.3°) | simulated range | predicted range | `predict` (basins): median, q05–q95 |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
for (p, n, k, ms, mp, mq, q5, q95, s0, s1, p0, p1, no) in summary:
    print(f"| {p} | {n} | {k} / {n} | {no} / {n} | {ms:.3f} | {mp:.3f} | {ms - mp:+.3f} | {'pass' if abs(ms - mp) <= TOL else 'FAIL'} "
          f"| {s0:.2f}–{s1:.2f} | {p0:.3f}–{p1:.3f} | {mq:.3f}, {q5:.3f}–{q95:.3f} |")
tot = sum(s[1] for s in summary); ok = sum(s[2] for s in summary)
print(f"\ndrops passing: {ok} / {tot} (within {TOL}°), {sum(s[12] for s in summary)} / {tot} (over drops); "
      f"pairs whose medians agree within {TOL}°: {sum(abs(s[3] - s[4]) <= TOL for s in summary)} / {len(summary)}")
print()
print(f"Convergence at drop {M} of each pair (degrees; largest change from the run at the defaults):")
print()
print("| pair | defaults (k_n N/m, r m) | reading | 10 k_n, 10 k_t | time-step safety 0.25 | r / 2 | increment / 2 | largest change |")
print("|---|---|---|---|---|---|---|---|")
for p in pairs:
    b = json.load(open(f"{d}/runs/{p}-{M}-tilt.json"))
    vals = [json.load(open(f"{d}/runs/{p}-{c}-tilt.json")) for c in ("c-kn10", "c-dt", "c-r", "c-inc")]
    ch = max(abs(v["friction_angle_deg"] - b["friction_angle_deg"]) for v in vals)
    s = b["settings"]
    print(f"| {p} | {s['normal_stiffness']:.4g}, {s['spheroradius']:.3g} | {b['friction_angle_deg']:.3f} | "
          + " | ".join(f"{v['friction_angle_deg']:.3f}" + ("" if not v["warnings"] else f" ({codes(v)})") for v in vals)
          + f" | {ch:.3f} |")
PY
else
  echo "mode: maps or profiles" >&2; exit 2
fi
