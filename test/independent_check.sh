#!/bin/bash
# usage: independent_check.sh TOOL MESH CHECKER WORK_DIR
# The command line tool's map of MESH, with its printed figures, checked by CHECKER
# (tools/check_sphere_map.py, the same figures computed apart from the package's code): both
# must agree, and the map must meet the default energy's bounds. Exits 77 (a skip) without
# MESH or without a Python that has NumPy and SciPy.
tool=$1 mesh=$2 checker=$3 work=$4
test -e "$mesh" || { echo "skipped: no $mesh"; exit 77; }
source "$(dirname "$0")/python_with.sh"
python=$(python_with numpy scipy) || { echo "skipped: no python3 with NumPy and SciPy"; exit 77; }
mkdir -p "$work" && cd "$work" || exit 1
rm -f sphere.off icosphere.off report.txt
"$tool" "$mesh" sphere.off --remesh-icosphere 6 icosphere.off > report.txt || { cat report.txt; exit 1; }
"$python" "$checker" "$mesh" sphere.off --cli-report report.txt --bounds
