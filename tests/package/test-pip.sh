#!/usr/bin/env bash
# Installs the Python package the way a Python user does (pip, offline, no build isolation) into a
# fresh venv that sees Debian's python3-* packages, then checks `import frictal` from an unrelated
# directory resolves to the installed copy.
# Usage: tests/package/test-pip.sh SOURCE_DIR VENV_DIR
set -euo pipefail
src=$1
venv=$2
rm -rf "$venv"
/usr/bin/python3 -m venv --system-site-packages "$venv"
export PIP_DISABLE_PIP_VERSION_CHECK=1 PIP_NO_INPUT=1
"$venv/bin/python" -m pip install --no-build-isolation --no-index --no-deps "$src" >"$venv/pip.log" 2>&1 ||
  { tail -n 60 "$venv/pip.log"; exit 1; }
cd "$(mktemp -d)"
"$venv/bin/python" - <<PY
import math, sys, frictal
assert frictal.__file__.startswith("$venv"), f"imported from {frictal.__file__}, not the venv"
print("frictal", frictal.__version__, "installed at", frictal.__file__)
sig = frictal.signature(frictal.koch_profile(iterations=3, alpha=math.radians(5)))
assert abs(math.degrees(sig["theta_max_forward"]) - 15) < 1e-9  # K3: 3 alpha (paper Fig. 4)
PY
