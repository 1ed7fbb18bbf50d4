#!/bin/bash
# example.measured_pair: runs the README's worked example (the block between
# "<!-- example: measured-pair -->" and "<!-- end example -->") as a user would, from a copy of
# the files it reads, then checks by a second path that the tilt's rigid prediction is the
# signature's theta_max (both of the whole files: `tilt --block-length whole`). Arguments: source dir, frictal executable, build tree's python dir.
set -euo pipefail
src=$1 cli=$2 pydir=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/bin" "$work/tests/data/profiles"
cp "$src/tests/data/profiles/dektak-1.csv" "$work/tests/data/profiles/"
ln -s "$cli" "$work/bin/frictal"
ln -s /usr/bin/python3 "$work/bin/python3"  # Debian's python3 (numpy), as scripts/install-deps installs
awk '/<!-- example: measured-pair -->/{on=1; next} /<!-- end example -->/{on=0} on && !/^```/' "$src/README.md" \
  > "$work/example.sh"
test -s "$work/example.sh" || { echo "README.md: no measured-pair example block" >&2; exit 1; }
cd "$work"
export PATH="$work/bin:$PATH" PYTHONPATH="$pydir"
bash -euo pipefail example.sh > out.txt 2>&1 || { cat out.txt; echo "the README example failed" >&2; exit 1; }
cat out.txt
grep -q "theta_max forward" out.txt
frictal signature dektak-a.csv dektak-b.csv --json > sig.json
frictal tilt --lower dektak-a.csv --upper dektak-b.csv --block-length whole --max-tilt 0.05 --json > tilt.json 2> /dev/null
python3 - <<'PY'
import json
sig = json.load(open("sig.json"))
tilt = json.load(open("tilt.json"))
a, b = sig["theta_max_forward_deg"], tilt["predicted_theta_max_deg"]
print(f"signature theta_max {a:.10f} deg, tilt rigid prediction {b:.10f} deg")
assert abs(a - b) <= 1e-9 * max(1.0, abs(a)), (a, b)
assert 1.0 < a < 10.0, a  # slopes of a polished scan: a few degrees
print(tilt["rest_offset_m"])
PY
# The tilt's hold-angle prediction from where its block rests, against `signature --start-offset`
# at that rest with the tilt's run-away distance (a second path through the CLI: the signature's
# own widened lift).
rest=$(python3 -c 'import json; print(json.load(open("tilt.json"))["rest_offset_m"])')
d=$(python3 -c 'import json; print(json.load(open("tilt.json"))["surface"]["runaway_distance_m"])')
frictal signature dektak-a.csv dektak-b.csv --start-offset "$rest" --runaway-distance "$d" --json > hold.json
python3 - <<'PY'
import json
tilt = json.load(open("tilt.json"))
hold = json.load(open("hold.json"))
a, b = hold["hold_angle_deg"], tilt["predicted_hold_angle_deg"]
print(f"signature hold angle {a:.10f} deg, tilt hold prediction {b:.10f} deg")
assert abs(a - b) <= 1e-9 * max(1.0, abs(a)), (a, b)
assert hold["inertial_hold_angle_deg"] <= a, hold  # the bracket [phi_in, phi_qs]
PY
# The dynamic test from rest (the README's last command) lies inside its own bracket
# [phi_in, phi_qs] from where it rests (0.1 deg slack), and is not flagged.
frictal tilt --lower dektak-a.csv --upper dektak-b.csv --block-length whole --protocol constant-rate --settling relax --turn gravity --tilt-rate 0.0005 \
  --hold-rotation --spheroradius 2e-5 --normal-stiffness 6e7 --contact-rule closest --json > rest.json 2> /dev/null
python3 - <<'PY'
import json
r = json.load(open("rest.json"))
phi, lo, hi = r["friction_angle_deg"], r["predicted_inertial_hold_angle_deg"], r["predicted_sphero_hold_angle_deg"]
print(f"dynamic from rest {phi:.3f} deg in [{lo:.3f}, {hi:.3f}]")
assert lo - 0.1 <= phi <= hi + 0.1, (phi, lo, hi)
assert not any(w["code"] == "unsettled" for w in r["warnings"]), r["warnings"]
PY
