#!/usr/bin/env bash
# Checks that the README's test command, run after the main job, ran the whole suite: every
# test that a fresh configure with every option on defines, and every test named in the
# CMakeLists.txt files, passed in build/; the fast tests passed in build-asan; and the main job,
# run again, leaves build/ defining all of them. Reads the results that tools/run_tests.sh
# leaves (build/ctest_results.xml, build-asan/ctest_results.xml). .ci/run calls it after
#
#     bash tools/run_main.sh && bash tools/run_tests.sh
#
# as the README gives them; a developer can run it after the same two commands.
set -euo pipefail
cd "$(dirname "$0")/.."
problems=0
fail() { echo "FAIL $*"; problems=$((problems + 1)); }

names_of() { ctest --test-dir "$1" -N "${@:2}" | sed -n 's/^ *Test *#[0-9]*: //p' | sort; }

# What the suite is, from the sources alone: a fresh build folder, every option given.
fresh="$(mktemp -d)"
trap 'rm -rf "$fresh"' EXIT
cmake -S . -B "$fresh" -DCMAKE_BUILD_TYPE=Release -DSPHERICAL_PARAMETERIZATION_BUILD_TESTS=ON \
      -DSPHERICAL_PARAMETERIZATION_BUILD_EXAMPLES=ON -DSPHERICAL_PARAMETERIZATION_BUILD_BENCHMARK=ON \
      -DSPHERICAL_PARAMETERIZATION_BUILD_DOC=ON > /dev/null
names_of "$fresh" > "$fresh/expected"
# A floor that does not go through CMake: the tests that the CMakeLists.txt files name
# literally, and those of spherical_parameterization_test() whose source exists.
{
  grep -ohE 'add_test\(NAME [A-Za-z0-9_]+( |\)|$)' CMakeLists.txt test/CMakeLists.txt examples/CMakeLists.txt \
       doc/CMakeLists.txt | sed -E 's/add_test\(NAME ([A-Za-z0-9_]+).*/\1/'
  grep -ohE '^spherical_parameterization_test\([a-z0-9_]+\)' test/CMakeLists.txt | sed -E 's/.*\((.*)\)/\1/' |
    while read -r name; do [ -e "test/$name.cpp" ] && echo "$name"; done
} | sort -u > "$fresh/named"
if ! missing="$(comm -23 "$fresh/named" "$fresh/expected")" || [ -n "$missing" ]; then
  fail "named in a CMakeLists.txt but not defined by a fresh configure:" $missing
fi

# The test command's run in build/: all that build/ defines ran, which is at least the suite.
passed="$(python3 tools/count_tests.py --names passed build/ctest_results.xml | sort)"
run="$(python3 tools/count_tests.py --names passed build/ctest_results.xml
       python3 tools/count_tests.py --names failed build/ctest_results.xml
       python3 tools/count_tests.py --names skipped build/ctest_results.xml)"
defined="$(names_of build)"
[ "$(echo "$run" | grep -c .)" -eq "$(echo "$defined" | grep -c .)" ] ||
  fail "build/: CTest defines $(echo "$defined" | grep -c .) tests and the test command ran $(echo "$run" | grep -c .)"
not_passed="$(comm -23 "$fresh/expected" <(echo "$passed"))"
[ -z "$not_passed" ] || fail "build/: not run and passed:" $not_passed

# The sanitizer stage: every test labelled fast passed.
fast="$(names_of "$fresh" -L fast)"
not_passed="$(comm -23 <(echo "$fast") <(python3 tools/count_tests.py --names passed build-asan/ctest_results.xml | sort))"
[ -z "$not_passed" ] || fail "build-asan/: not run and passed:" $not_passed

# The main job once more: it must leave build/ defining the whole suite for a later test run.
bash tools/run_main.sh --quiet > /dev/null
not_defined="$(comm -23 "$fresh/expected" <(names_of build))"
[ -z "$not_defined" ] || fail "build/ after the main job: not defined:" $not_defined

echo "full suite check: $(grep -c . "$fresh/expected") tests in the suite, $(echo "$fast" | grep -c .) of them" \
     "under the sanitizers too; $problems problem(s)"
# The test command's closing count again, last, as CI reads the last such line of .ci/run.
python3 tools/count_tests.py build/ctest_results.xml build-asan/ctest_results.xml | tail -n 1
[ "$problems" -eq 0 ]
