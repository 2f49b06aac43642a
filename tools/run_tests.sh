#!/usr/bin/env bash
# Installs, builds and runs all tests through CTest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/install_dependencies.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j 2
ctest --test-dir build --output-on-failure "$@"
