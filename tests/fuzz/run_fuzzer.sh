#!/usr/bin/env bash
# Builds and runs the scene-reader fuzzer (tests/fuzz/scene_fuzzer.cpp).
#
#   tests/fuzz/run_fuzzer.sh [SOURCE_DIR [BUILD_DIR]]        (CTest: fuzz.scene_parser)
#
# (a) builds BUILD_DIR/fuzz/scene_fuzzer with clang++ -fsanitize=fuzzer,address,undefined
#     from the reader's own sources and the physics types whose schemas it reads
#     (src/io/{scene_reader,checked_yaml,component_reader}.cpp, the registry, every
#     file that defines a PhysicsType, time_function.cpp), all
#     instrumented; the types' builders need the kernels, which come uninstrumented
#     from BUILD_DIR/libboomdyn_core.a (build it first) with PETSc and MPI linked
#     but never initialized: the reader does not call a builder. Rebuilt when
#     any source it depends on is newer than the executable;
# (b) runs it for FUZZ_TIME seconds (default 60) on the seeds (inputs/*.yaml,
#     tests/bad_input/*.yaml, tests/bad_model/*.yaml, tests/fuzz/seeds/*.yaml:
#     valid scenes with the features the examples lack) plus the corpus kept in
#     BUILD_DIR/fuzz/corpus from earlier runs;
# (c) exits 1 if libFuzzer reports a crash, a sanitizer error, a leak, an
#     out-of-memory or a timeout (the input goes to BUILD_DIR/fuzz/artifacts/).
# Exits 77 (CTest SKIP) if there is no clang++.
#
# Environment: FUZZ_TIME (s), FUZZ_JOBS (parallel fuzzing processes, default 1),
# FUZZ_FRESH=1 (forget the kept corpus), CLANGXX (compiler, default clang++),
# FUZZ_ARGS (extra libFuzzer flags).
set -uo pipefail
src=$(cd "${1:-$(dirname "$0")/../..}" && pwd)
build=$(mkdir -p "${2:-$src/build}" && cd "${2:-$src/build}" && pwd)
time_limit=${FUZZ_TIME:-60}
jobs=${FUZZ_JOBS:-1}
cxx=${CLANGXX:-clang++}

if ! command -v "$cxx" > /dev/null 2>&1; then
  echo "fuzz: $cxx not found (install clang and libclang-rt-14-dev: scripts/install-deps.sh --tests); skipping"
  exit 77
fi

dir=$build/fuzz
exe=$dir/scene_fuzzer
mkdir -p "$dir/corpus" "$dir/artifacts"

# (a) build if any dependency is newer than the executable
reader_sources=("$src/src/io/scene_reader.cpp" "$src/src/io/checked_yaml.cpp" "$src/src/io/component_reader.cpp"
                "$src/src/model/time_function.cpp" "$src/src/model/scene.cpp"
                "$src/src/model/component_spec.cpp" "$src/src/model/physics_types.cpp")
# Every file that defines a physics type (its schema is what the reader reads).
mapfile -t type_sources < <(grep -l '^PhysicsType [A-Za-z]*Type()' "$src/src"/*/*.cpp)
reader_sources+=("${type_sources[@]}")
core=$build/libboomdyn_core.a
if [ ! -f "$core" ]; then
  echo "fuzz: $core not found: build the boomdyn_core target first"
  exit 1
fi
deps=("$src/tests/fuzz/scene_fuzzer.cpp" "$src/tests/fuzz/run_fuzzer.sh" "${reader_sources[@]}" "$core"
      "$src/include/boomdyn"/*.hpp "$src/src/io/checked_yaml.hpp")
stale=0
[ -x "$exe" ] || stale=1
for d in "${deps[@]}"; do [ "$d" -nt "$exe" ] && stale=1; done
if [ $stale -eq 1 ]; then
  echo "fuzz: building $exe with $cxx"
  # -fno-sanitize-recover: a UBSan report stops the run (by default it only prints).
  if ! "$cxx" -std=c++17 -g -O1 -fno-omit-frame-pointer \
       -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all \
       -I"$src/include" $(pkg-config --cflags petsc eigen3 mpi-cxx yaml-cpp) \
       "$src/tests/fuzz/scene_fuzzer.cpp" "${reader_sources[@]}" "$core" \
       $(pkg-config --libs slepc petsc hdf5 yaml-cpp mpi-cxx) -lmetis \
       -o "$exe.tmp" > "$dir/build.log" 2>&1; then
    cat "$dir/build.log"
    echo "fuzz: FAILED to build the fuzzer (is libclang-rt-14-dev installed? scripts/install-deps.sh --tests)"
    exit 1
  fi
  mv -f "$exe.tmp" "$exe"
fi

# (b) seeds, fresh each run (the kept corpus holds what the fuzzer found)
[ "${FUZZ_FRESH:-0}" = 1 ] && rm -rf "$dir/corpus" && mkdir -p "$dir/corpus"
rm -rf "$dir/seeds" && mkdir -p "$dir/seeds"
for f in "$src"/inputs/*.yaml "$src"/tests/bad_input/*.yaml "$src"/tests/bad_model/*.yaml "$src"/tests/fuzz/seeds/*.yaml; do
  [ -f "$f" ] && cp "$f" "$dir/seeds/$(basename "$(dirname "$f")")__$(basename "$f")"
done
# The kept corpus grows a little with every run; past 4000 inputs, keep only
# a minimal set with the same coverage.
if [ "$(ls "$dir/corpus" | wc -l)" -gt 4000 ]; then
  rm -rf "$dir/corpus.min" && mkdir -p "$dir/corpus.min"
  if "$exe" -merge=1 -rss_limit_mb=2048 -timeout=10 "$dir/corpus.min" "$dir/corpus" > "$dir/merge.log" 2>&1; then
    rm -rf "$dir/corpus" && mv "$dir/corpus.min" "$dir/corpus"
  fi
fi
echo "fuzz: $(ls "$dir/seeds" | wc -l) seeds, $(ls "$dir/corpus" | wc -l) kept inputs, ${time_limit} s, $jobs job(s)"

log=$dir/fuzz.log
rm -f "$dir"/fuzz-*.log
touch "$dir/.run-start" # artifacts newer than this come from this run
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=0:handle_abort=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
# libFuzzer's default -error_exitcode is 77, which CTest would take for SKIP.
args=(-max_total_time="$time_limit" -rss_limit_mb=2048 -timeout=10 -max_len=8192
      -error_exitcode=1 -timeout_exitcode=1 -print_final_stats=1
      -dict="$src/tests/fuzz/scene.dict" -artifact_prefix="$dir/artifacts/")
if [ "$jobs" -gt 1 ]; then args+=(-jobs="$jobs" -workers="$jobs"); fi
(cd "$dir" && "$exe" "${args[@]}" ${FUZZ_ARGS:-} "$dir/corpus" "$dir/seeds") > "$log" 2>&1
rc=$?
[ "$jobs" -gt 1 ] && cat "$dir"/fuzz-*.log >> "$log" 2> /dev/null

# (c) verdict
grep -E '^#[0-9]+[[:space:]]+DONE|^stat::|^Done [0-9]+ runs' "$log" | tail -8
if [ $rc -ne 0 ] || grep -qE '^==[0-9]+==ERROR|^SUMMARY: |FINDING:|runtime error:|ERROR: libFuzzer' "$log"; then
  echo "fuzz: FAILED (exit $rc); the end of $log:"
  tail -60 "$log"
  echo "fuzz: inputs that failed:"
  find "$dir/artifacts" -type f -newer "$dir/.run-start" | sed 's|^|  |'
  echo "fuzz: reproduce with: $exe <input>"
  exit 1
fi
echo "fuzz: ok (no crash, leak, sanitizer report or timeout in ${time_limit} s; log in $log)"
exit 0
