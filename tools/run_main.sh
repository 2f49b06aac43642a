#!/usr/bin/env bash
# The main job: install, build in Release, map data/triceratops.off onto the sphere, write
# triceratops_sphere.off and print the result and the quality figures.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/install_dependencies.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DSPHERICAL_PARAMETERIZATION_BUILD_TESTS=OFF > /dev/null
cmake --build build --target spherical_parameterize -j 2
./build/bin/spherical_parameterize data/triceratops.off triceratops_sphere.off "$@"
