#!/usr/bin/env bash
# Builds the libFuzzer targets with clang++-14 (AddressSanitizer, UndefinedBehaviorSanitizer)
# and runs each for SECONDS (default 60), one after the other.
#   bash fuzz/run_fuzz.sh [SECONDS [TARGET...]]     (targets: fuzz_off_reader fuzz_small_meshes)
# Builds and working corpora go to $FUZZ_OUT (default /tmp/spherical_fuzz); crashing,
# leaking or slow inputs to $FUZZ_OUT/findings/<target>/ (copy them to fuzz/findings/).
set -euo pipefail
seconds="${1:-60}"
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(fuzz_off_reader fuzz_small_meshes)
here="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$here")"
out="${FUZZ_OUT:-/tmp/spherical_fuzz}"
cxx="${CXX_FUZZ:-clang++-14}"
mkdir -p "$out"

flags=(-std=c++17 -O1 -g1 -fno-omit-frame-pointer
       -fsanitize=fuzzer,address,undefined
       -I"$root/include" -isystem /usr/include/eigen3 -DCGAL_USE_GMPXX=1)
libs=(-lgmpxx -lmpfr -lgmp)
if [ -e /usr/include/suitesparse/cholmod.h ]; then  # the default solver, as in the CMake build
  flags+=(-I/usr/include/suitesparse -DCGAL_SPHERICAL_PARAMETERIZATION_USE_CHOLMOD)
  libs+=(-lcholmod)
fi

run() {  # target seed_corpus max_len
  local target="$1" seeds="$2" max_len="$3"
  echo "== $target: building"
  "$cxx" "${flags[@]}" "$here/$target.cpp" -o "$out/$target" "${libs[@]}"
  mkdir -p "$out/corpus_$target" "$out/findings/$target"
  echo "== $target: fuzzing for $seconds s"
  # Working corpus first (grows, kept between runs), then the seeds (read only).
  local status=0
  # UndefinedBehaviorSanitizer halts at the first report, except for the suppressed ones.
  ASAN_OPTIONS="detect_leaks=1" \
  UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:suppressions=$here/ubsan.supp" \
    "$out/$target" "$out/corpus_$target" "$seeds" -max_total_time="$seconds" -timeout=60 \
      -rss_limit_mb=4096 -max_len="$max_len" -print_final_stats=1 \
      -artifact_prefix="$out/findings/$target/" > "$out/$target.log" 2>&1 || status=$?
  grep -E "^#[0-9]+[[:space:]]+(INITED|DONE)|ERROR|SUMMARY|stat::|Test unit written" "$out/$target.log" || true
  echo "== $target: exit status $status (0: nothing found), log $out/$target.log"
  return 0
}

for target in "${targets[@]}"; do
  case "$target" in
    fuzz_off_reader) run fuzz_off_reader "$here/corpus" 4096 ;;
    fuzz_small_meshes) run fuzz_small_meshes "$here/corpus_small" 1024 ;;
    *) echo "unknown target $target" >&2; exit 1 ;;
  esac
done
ls -l "$out"/findings/*/ 2>/dev/null || true
