#!/usr/bin/env bash
# Configures (Release, -DBOOMDYN_BENCHMARKS=ON), builds and runs the Google
# Benchmark micro-benchmarks of benchmarks/kernels/ (element kernels, single
# work items, Assembler::evaluate on 16 ... 65536-element cantilevers) and
# prints the results. Uses its own build directory (default build-bench).
#
#   benchmarks/run_kernels.sh [--benchmark_filter=REGEX] [--benchmark_repetitions=5] [...]
#
# Extra arguments go to the benchmark executable. Environment: BUILD_DIR
# (default <repo>/build-bench), JOBS (default 2). On a shared machine read
# the CPU column (and the per_element counter, which is CPU time per element).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${BUILD_DIR:-$root/build-bench}
jobs=${JOBS:-2}
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DBOOMDYN_BENCHMARKS=ON >/dev/null
cmake --build "$build" -j"$jobs" --target kernel_benchmarks
if [ $# -eq 0 ]; then
  set -- --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
fi
exec "$build/benchmarks/kernel_benchmarks" "$@"
