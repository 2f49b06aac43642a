#!/usr/bin/env bash
# The main job: install, build in Release, map data/triceratops.off onto the sphere, write
# triceratops_sphere.off and print the result and the quality figures.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/install_dependencies.sh
# build/ is also the test command's folder (tools/run_tests.sh): only the option this job needs
# is set, none is turned off, and only the tool is built, which keeps the job fast.
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DSPHERICAL_PARAMETERIZATION_BUILD_EXAMPLES=ON > /dev/null
cmake --build build --target spherical_parameterize -j 2
./build/bin/spherical_parameterize data/triceratops.off triceratops_sphere.off "$@"
