#!/usr/bin/env bash
# libFuzzer targets of tests/fuzz/ (spec reader, Gmsh reader, every proto/ unpack), in a
# clang build of their own with ASan and UBSan (CMake option FE2_FUZZ; the main build
# stays gcc).
#   tools/fuzz.sh build                 configure and build the fuzzers
#   tools/fuzz.sh TARGET SECONDS        fuzz TARGET (spec, msh, proto, ...) that long; the
#                                       corpus grows in $FE2_FUZZ_BUILD/corpus/TARGET
#   tools/fuzz.sh all SECONDS           every target in turn
#   tools/fuzz.sh TARGET SECONDS --ci   from the seed corpus only, fresh (the CTest tests)
#   tools/fuzz.sh list                  the targets
# Seeds: tests/fuzz/corpus/TARGET/ (and, if the build has make_TARGET_seeds, what it
# writes from the current code). A crash, leak, UB report, an allocation over 512 MB, an
# input slower than 10 s or an escaped exception stops the run with exit != 0 and leaves
# the input in $FE2_FUZZ_BUILD/findings/TARGET/ (reproduce: fuzz_TARGET FILE).
set -euo pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
build=${FE2_FUZZ_BUILD:-$top/build/fuzz-clang}
targets() { ls "$top"/tests/fuzz/fuzz_*.cpp | sed 's|.*/fuzz_||; s|\.cpp$||'; }
usage() { sed -n '2,14p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }

cmd=${1:-}
case $cmd in
  build)
    launcher=()
    command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
    # -O1 with line tables: readable sanitizer reports at a useful speed.
    cmake -S "$top" -B "$build" -DFE2_FUZZ=ON -DCMAKE_BUILD_TYPE=Release \
          -DCMAKE_CXX_FLAGS_RELEASE="-O1 -gline-tables-only -DNDEBUG" \
          -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ "${launcher[@]}" >/dev/null
    cmake --build "$build" -j"$(env -u OMP_NUM_THREADS -u OMP_THREAD_LIMIT nproc)" --target fuzzers
    exit 0 ;;
  list) targets; exit 0 ;;
  all)
    [[ ${2:-} =~ ^[0-9]+$ ]] || usage
    for t in $(targets); do "$0" "$t" "$2" "${@:3}"; done
    exit 0 ;;
  ''|-h|--help) usage ;;
esac

target=$cmd
seconds=${2:-}
ci=${3:-}
targets | grep -qx "$target" || { echo "fuzz.sh: unknown target '$target', expected one of: $(targets | tr '\n' ' ')" >&2; exit 2; }
[[ $seconds =~ ^[0-9]+$ && $seconds -gt 0 ]] || { echo "fuzz.sh: SECONDS '$seconds', expected a positive integer" >&2; exit 2; }
[[ -z $ci || $ci == --ci ]] || usage
bin=$build/tests/fuzz/fuzz_$target
[[ -x $bin ]] || { echo "fuzz.sh: $bin missing; run: tools/fuzz.sh build" >&2; exit 2; }

corpus=$build/corpus/$target
[[ -n $ci ]] && corpus=$build/ci/$target && rm -rf "$corpus"
findings=$build/findings/$target
mkdir -p "$corpus" "$findings"
dirs=("$corpus" "$top/tests/fuzz/corpus/$target")
if [[ -x $build/tests/fuzz/make_${target}_seeds ]]; then
  mkdir -p "$build/seeds/$target"
  "$build/tests/fuzz/make_${target}_seeds" "$build/seeds/$target"
  dirs+=("$build/seeds/$target")
fi
opts=(-max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=512
      -artifact_prefix="$findings/" -print_final_stats=1)
[[ -f $top/tests/fuzz/$target.dict ]] && opts+=(-dict="$top/tests/fuzz/$target.dict")
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:allocator_may_return_null=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
echo "fuzz_$target for $seconds s; corpus $corpus; findings $findings"
rc=0
"$bin" "${opts[@]}" "${dirs[@]}" 2>&1 | grep -v -E '^#[0-9]+\s+(NEW|REDUCE|pulse)|^\s+NEW_FUNC|^".*# Uses: ' || rc=${PIPESTATUS[0]}
if ((rc != 0)); then
  echo "fuzz_$target FAILED (exit $rc): the input is in $findings/; reproduce with $bin FILE," \
       "fix the reader, and add the input to tests/fuzz/corpus/$target/ as a regression seed" >&2
  exit 1
fi
