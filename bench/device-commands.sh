#!/usr/bin/env bash
# bench/commands.py on another (e.g. many-core) machine, with the CLI copied into the
# git-ignored .device/ (the binary and the shared libraries `ldd` names, not libc/libm/libstdc++/
# libgcc). The inputs are made there (profiles by the CLI, maps by that machine's numpy).
#   bench/device-commands.sh OUTDIR [extra bench/commands.py options]
set -euo pipefail
cd "$(dirname "$0")/.."
OUTDIR=$1; shift
export LD_LIBRARY_PATH=$PWD/.device/lib PYTHONUNBUFFERED=1
python3 bench/commands.py --build .device/frictal --data /tmp/frictal-bench-data \
  --out "$OUTDIR/commands-device.md" --recorded "$OUTDIR/commands-device.tsv" --record "$@"
