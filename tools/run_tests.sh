#!/usr/bin/env bash
# Installs, builds and runs all tests through CTest; then builds the fast tests again with
# AddressSanitizer and UndefinedBehaviorSanitizer in build-asan and runs them (ctest -L fast).
# Set SKIP_SANITIZERS=1 to skip the second stage. Arguments go to the first ctest.
#
# Ends with the line `tests: N passed, N failed, N skipped` over both stages. A test skipped
# because something it needs is missing (CGAL's meshes, Doxygen, OpenMesh) fails the run, since
# tools/install_dependencies.sh installs all of it; with SKIP_APT=1 (no install) skips pass.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/install_dependencies.sh

# Every option the suite relies on, given each time: build/ is shared with the main job
# (tools/run_main.sh) and with developers, and CMake keeps an option's last value in its cache,
# so a value left there by an earlier configure must not decide what this run builds.
options=(-DSPHERICAL_PARAMETERIZATION_BUILD_TESTS=ON -DSPHERICAL_PARAMETERIZATION_BUILD_EXAMPLES=ON
         -DSPHERICAL_PARAMETERIZATION_WITH_TBB=ON -DSPHERICAL_PARAMETERIZATION_WITH_CHOLMOD=ON)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "${options[@]}" -DSPHERICAL_PARAMETERIZATION_BUILD_BENCHMARK=ON \
      -DSPHERICAL_PARAMETERIZATION_BUILD_DOC=ON -DSPHERICAL_PARAMETERIZATION_SANITIZE=OFF > /dev/null
cmake --build build -j 2

# A failing stage does not stop the other: the closing count covers both, and the exit status
# says whether any failed.
status=0
results=(build/ctest_results.xml)
rm -f build/ctest_results.xml build-asan/ctest_results.xml
ctest --test-dir build --output-on-failure --output-junit ctest_results.xml "$@" || status=1

if [ "${SKIP_SANITIZERS:-0}" != 1 ]; then
  # Debug (CGAL and Eigen assertions on) at -O1; -g1 (line tables) is enough for the stack
  # traces and compiles about 40% faster than -g. Compile time dominates this stage.
  cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g1" "${options[@]}" \
        -DSPHERICAL_PARAMETERIZATION_BUILD_BENCHMARK=OFF -DSPHERICAL_PARAMETERIZATION_BUILD_DOC=OFF \
        -DSPHERICAL_PARAMETERIZATION_SANITIZE=ON > /dev/null
  cmake --build build-asan -j 2 --target fast_tests
  ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
    ctest --test-dir build-asan --output-on-failure --output-junit ctest_results.xml -L fast || status=1
  results+=(build-asan/ctest_results.xml)
fi

strict=()
[ "${SKIP_APT:-0}" = 1 ] || strict=(--fail-on-skip)
python3 tools/count_tests.py "${strict[@]}" "${results[@]}" || status=1
exit "$status"
