#!/usr/bin/env bash
# Installs, builds and runs all tests through CTest; then builds the fast tests again with
# AddressSanitizer and UndefinedBehaviorSanitizer in build-asan and runs them (ctest -L fast).
# Set SKIP_SANITIZERS=1 to skip the second stage.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/install_dependencies.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j 2
ctest --test-dir build --output-on-failure "$@"

[ "${SKIP_SANITIZERS:-0}" = 1 ] && exit 0
# Debug (CGAL and Eigen assertions on) at -O1; -g1 (line tables) is enough for the stack
# traces and compiles about 40% faster than -g. Compile time dominates this stage.
fast_tests=(test_energies test_input_checks test_measure_distortion test_robustness test_coarse_to_fine)
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g1" \
      -DSPHERICAL_PARAMETERIZATION_SANITIZE=ON -DSPHERICAL_PARAMETERIZATION_BUILD_BENCHMARK=OFF > /dev/null
cmake --build build-asan -j 2 --target "${fast_tests[@]}"
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --test-dir build-asan --output-on-failure -L fast
