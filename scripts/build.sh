#!/usr/bin/env bash
# Configures and builds boomdyn (Release) in build/ (or $BOOMDYN_BUILD_DIR).
#   scripts/build.sh              # every target: boomdyn, the test programs, boomdyn_schema_docs (scripts/test.sh)
#   scripts/build.sh boomdyn      # only the named targets and what they need (scripts/main.sh)
# The log goes to build.log (or $BOOMDYN_BUILD_DIR.log).
set -euo pipefail
cd "$(dirname "$0")/.."
dir=${BOOMDYN_BUILD_DIR:-build}
log=$dir.log
targets=()
[ $# -gt 0 ] && targets=(--target "$@")
cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=Release > "$log" 2>&1 || { cat "$log"; exit 1; }
cmake --build "$dir" -j"$(nproc)" "${targets[@]}" >> "$log" 2>&1 || { tail -50 "$log"; exit 1; }
echo "build: ${*:-all targets} ok (log in $log)"
