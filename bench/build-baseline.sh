#!/usr/bin/env bash
# Builds the CLI of another commit (default HEAD~1: the previous commit) for the A/B of
# bench/commands.py: a detached git worktree in build/bench-prev-src (git-ignored, reused, moved
# to REV each time) and a Release build of its CLI alone in build/bench-prev (ccache shares the
# objects that did not change). Prints the build tree.
#   bench/build-baseline.sh [REV]
set -euo pipefail
cd "$(dirname "$0")/.."
REV=${1:-HEAD~1}
SRC=build/bench-prev-src
OUT=build/bench-prev
commit=$(git rev-parse --verify --quiet "$REV^{commit}") || {
  echo "bench/build-baseline.sh: '$REV' is no commit of this repository (a clone with history is needed)" >&2
  exit 2
}
if [[ -d $SRC/.git || -f $SRC/.git ]]; then
  git -C "$SRC" checkout -q --detach "$commit"
else
  rm -rf "$SRC"
  git worktree prune
  git worktree add -q --detach "$SRC" "$commit"
fi
export CCACHE_BASEDIR=$PWD
cmake -S "$SRC" -B "$OUT" -DCMAKE_BUILD_TYPE=Release -DFRICTAL_BUILD_TESTS=OFF \
  -DFRICTAL_BUILD_PYTHON=OFF -DFRICTAL_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build "$OUT" -j "$(nproc)" --target frictal_cli >&2
echo "$OUT"
