#!/usr/bin/env bash
# Builds the Debian package with CPack from a configured build tree, inspects its file list and
# runs what it installs (CLI and Python module) from an extracted copy.
# Usage: tests/package/test-deb.sh BUILD_DIR WORK_DIR
set -euo pipefail
build=$1
work=$2
rm -rf "$work"
mkdir -p "$work"
cpack --config "$build/CPackConfig.cmake" -B "$work" >"$work/cpack.log" 2>&1 || { cat "$work/cpack.log"; exit 1; }
deb=$(ls "$work"/frictal_*.deb | head -n1)
echo "package: $deb ($(stat -c %s "$deb") bytes)"
dpkg-deb -c "$deb" | awk '{print $6}' >"$work/contents.txt"
fail=0
need() {
  if ! grep -Eq "$1" "$work/contents.txt"; then echo "MISSING in .deb: $1"; fail=1; fi
}
need '^\./usr/bin/frictal$'
need '^\./usr/include/frictal/signature\.hpp$'
need '^\./usr/include/frictal/version\.hpp$'
need '^\./usr/lib/(.*/)?libfrictal\.(a|so)$'
need '^\./usr/lib/(.*/)?cmake/frictal/frictalConfig\.cmake$'
need '^\./usr/lib/(.*/)?cmake/frictal/frictalConfigVersion\.cmake$'
need '^\./usr/lib/(.*/)?cmake/frictal/frictalTargets\.cmake$'
need '^\./usr/lib/python3/dist-packages/frictal/__init__\.py$'
need '^\./usr/lib/python3/dist-packages/frictal/_core\..*\.so$'
need '^\./usr/share/doc/frictal/copyright$'
dpkg-deb -f "$deb" Package Version Depends
[[ $fail == 0 ]] || exit 1
# Run the CLI and the Python module from the extracted package (not from the build tree).
root="$work/root"
dpkg-deb -x "$deb" "$root"
# The copyright file: machine-readable (DEP-5), frictal's own files under GPL-3.0-or-later.
copyright="$root/usr/share/doc/frictal/copyright"
head -n1 "$copyright" | grep -q '^Format: https://www.debian.org/doc/packaging-manuals/copyright-format/1.0/' ||
  { echo "copyright: not in the DEP-5 format"; exit 1; }
grep -Pzq 'Files: \*\nCopyright: [^\n]*\nLicense: GPL-3.0-or-later\n' "$copyright" ||
  { echo "copyright: no 'Files: *' stanza with License: GPL-3.0-or-later"; exit 1; }
"$root/usr/bin/frictal" --version
# K2 Koch surface at alpha = 10 deg: the signature maximum is 2 alpha (paper Fig. 4).
"$root/usr/bin/frictal" surface koch --iterations 2 --alpha 10 -o "$work/k2.csv" 2>/dev/null
theta=$("$root/usr/bin/frictal" signature "$work/k2.csv" --period 0.01 --json | /usr/bin/python3 -c 'import json,sys; print(json.load(sys.stdin)["theta_max_forward_deg"])')
/usr/bin/python3 -c "import sys; t=float('$theta'); sys.exit(0 if abs(t-20)<1e-9 else 1)" || { echo "CLI from .deb: theta_max $theta, expected 20"; exit 1; }
cd "$work"
PYTHONPATH="$root/usr/lib/python3/dist-packages" /usr/bin/python3 -c '
import math, frictal
assert frictal.__file__.startswith("'"$root"'"), frictal.__file__
sig = frictal.signature(frictal.koch_profile(iterations=1, alpha=math.radians(15)))
assert abs(math.degrees(sig["theta_max_forward"]) - 15) < 1e-9, sig["theta_max_forward"]
print("python from .deb:", frictal.__file__, "K1 theta_max", math.degrees(sig["theta_max_forward"]))
'
echo "deb: ok"
