#!/usr/bin/env bash
# Builds the benchmark in Release and runs it over CGAL's sample meshes; writes
# benchmark/results/latest.csv and latest.json, then the plots (see README.md).
#
# usage: benchmark/run_benchmark.sh [--quick] [--full] [--large] [--decimated] [--defects] [--tubes] [--isosurfaces]
#                                   [--knob] [--energies LIST] [--pipeline robust|paper] [--data DIR] [--build-dir DIR]
#   --quick          only the meshes under 15k faces, 1 repeat each
#   --full           also bunny00 Loop-subdivided once (300k faces) and twice (1.2M faces)
#   --large          instead, 15 other meshes Loop-subdivided to 90k-260k faces, 3 repeats
#                    (turned inputs, see benchmark/README.md), the default energy (balanced) unless --energies;
#                    results in benchmark/results/large/
#   --decimated      instead, 10 meshes decimated by edge collapse to 10%, 3% and 1% of their
#                    edges (MESH@decimateN: 56 to 7.5k faces), 3 repeats, the default energy
#                    (balanced) unless --energies; results in benchmark/results/decimated/
#   --defects        instead, meshes with nearly degenerate faces added (MESH@sliversN,
#                    MESH@needlesN), 1 repeat, the default energy (balanced) unless --energies; results in
#                    benchmark/results/defects/
#   --tubes          instead, tubes built by the benchmark (tube:capsuleL, tube:helixT, tube:cylinderN;
#                    no data needed), 1 repeat, the default energy (balanced) unless --energies; results in
#                    benchmark/results/tubes/
#   --isosurfaces    instead, isosurfaces by marching tetrahedra built by the benchmark
#                    (iso:metaballsN, iso:latticeR; no data needed), 1 repeat, all three
#                    energies unless --energies; results in benchmark/results/isosurfaces/
#   --knob           instead, the balanced energy's knob t from 0 (conformal) to 1 (equal-area)
#                    on camel, cow, man and bunny00, 1 repeat; results and the plot of angle
#                    against area distortion (knob.png) in benchmark/results/knob/
#   --energies LIST  comma-separated (NAME, NAME:A, NAME:A:B or balanced:A:B:C, C the sample
#                    spacing weight), default balanced,tutte,dirichlet,combined (balanced: the
#                    default energy)
#   --pipeline P     robust (default) or paper
#   --data DIR       a folder holding the .off meshes; default: CGAL's data tarball
#                    /usr/share/doc/libcgal-dev/data.tar.gz (Debian package libcgal-demo),
#                    extracted to a temporary folder
#   --build-dir DIR  default build (relative to the repository root)
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/.." && pwd)"

quick=0
full=0
large=0
decimated=0
defects=0
tubes=0
isosurfaces=0
knob=0
energies=""
pipeline="robust"
data=""
build_dir="build"
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) quick=1 ;;
    --full) full=1 ;;
    --large) large=1 ;;
    --decimated) decimated=1 ;;
    --defects) defects=1 ;;
    --tubes) tubes=1 ;;
    --isosurfaces) isosurfaces=1 ;;
    --knob) knob=1 ;;
    --energies) energies="$2"; shift ;;
    --pipeline) pipeline="$2"; shift ;;
    --data) data="$2"; shift ;;
    --build-dir) build_dir="$2"; shift ;;
    -h|--help) sed -n '2,33p' "$0"; exit 0 ;;
    *) echo "unknown option $1" >&2; exit 1 ;;
  esac
  shift
done

corpus=(hand blobby triceratops cow retinal homer bull camel bear fandisk_large man diplodocus armadillo bunny00)
# The size of the meshes the issue's held-out runs use (100k to 270k faces), from meshes whose
# own size the corpus covers: smooth ones, and the protrusions (legs, horns, tails) that are
# the slow case. MESH@loopN: N Loop subdivisions (done by the benchmark program).
large_corpus=(cow@loop2 triceratops@loop2 bear@loop1 retinal@loop2 dino@loop2 fandisk_large@loop1 man@loop1
              hand@loop3 homer@loop2 diplodocus@loop1 bull@loop2 ellipe0.003@loop3 fandisk@loop2
              armadillo@loop1 blobby@loop3)
# Low-poly models, as decimated scans and game assets are: obtuse and long faces, and curvature
# concentrated on a few sharp vertices (a leg's or a horn's tip), which a resampling cuts.
decimated_corpus=()
for m in cow bull camel man diplodocus dino armadillo triceratops homer bunny00; do
  decimated_corpus+=("$m@decimate10" "$m@decimate3" "$m@decimate1")
done
# Slivers and near-duplicate vertices (see mesh_defects.h), at corpus and held-out sizes.
defects_corpus=(cow@needles50 triceratops@needles50 bull@slivers50 man@slivers50 cow@loop2@needles200
                bull@loop2@slivers200 man@loop1@needles100)
# Long tubes, straight and coiled, 3k to 112k faces (see synthetic_shapes.h): their energies'
# infimum squeezes the tube to nothing, so their maps end on the fold barrier's floor. And
# short cylinders as CAD tessellations make them, 3k and 20k faces: needles and fan caps.
tubes_corpus=(tube:capsule10 tube:capsule40 tube:capsule150 tube:helix1 tube:helix2 tube:helix4
              tube:cylinder300 tube:cylinder2000)
# Isosurfaces of scans and segmentations (marching cubes or tetrahedra): clusters of
# near-coincident vertices where the surface passes close to a grid point, tiny faces and
# needles around them (see synthetic_shapes.h); the starfish's thin arms are protrusions too,
# the cortex's narrow creases a brain-like surface, the folded cortex's deeper, leaning folds
# one that is not star-shaped. 17k to 252k faces. With them, two brain surfaces as
# segmentations give them after smoothing, at a hemisphere's size (328k faces, no clusters):
# the thin gyri of a white matter surface and the narrow sulci of a pial one.
isosurfaces_corpus=(iso:lattice150 iso:lattice300 iso:metaballs60 iso:metaballs100 iso:metaballs130 iso:metaballs180
                    iso:starfish60 iso:starfish100 iso:starfish150 iso:cortex60 iso:cortex100 iso:folded80
                    iso:folded110 shape:white7 shape:pial7)
repeats=""  # the benchmark's default: 3, or 1 above 200k faces
if [ "$large" = 1 ]; then
  corpus=("${large_corpus[@]}")
  repeats=3  # the paths of the protrusion meshes follow the rounding: a median over 3
  : "${energies:=balanced}"
fi
if [ "$decimated" = 1 ]; then
  corpus=("${decimated_corpus[@]}")
  large=1  # the same treatment: every mesh, none added
  repeats=3  # turned inputs: a low-poly tip's resampling error depends on the samples' orientation
  : "${energies:=balanced}"
fi
if [ "$defects" = 1 ]; then
  corpus=("${defects_corpus[@]}")
  large=1  # the same treatment: every mesh, one repeat
  repeats=1
  : "${energies:=balanced}"
fi
if [ "$tubes" = 1 ]; then
  corpus=("${tubes_corpus[@]}")
  large=1
  repeats=1
  : "${energies:=balanced}"
fi
# The knob's range: t = B / (A + B) for balanced:A:B.
knob_corpus=(camel cow man bunny00)
knob_energies=balanced:1:0,balanced:0.95:0.05,balanced:0.9:0.1,balanced:0.75:0.25,balanced:0.5:0.5,balanced:0.25:0.75,balanced:0.1:0.9,balanced:0:1
if [ "$knob" = 1 ]; then
  corpus=("${knob_corpus[@]}")
  large=1
  repeats=1
  : "${energies:=$knob_energies}"
fi
if [ "$isosurfaces" = 1 ]; then
  corpus=("${isosurfaces_corpus[@]}")
  tubes=1  # built in code, like the tubes
  large=1
  repeats=1
fi
: "${energies:=balanced,tutte,dirichlet,combined}"

# The meshes.
tmp=""
cleanup() { if [ -n "$tmp" ]; then rm -rf "$tmp"; fi; }
trap cleanup EXIT
if [ "$tubes" = 1 ]; then
  data="."  # nothing to read
elif [ -z "$data" ]; then
  tarball=/usr/share/doc/libcgal-dev/data.tar.gz
  if [ ! -f "$tarball" ]; then
    echo "no $tarball: install the Debian package libcgal-demo, or pass --data DIR" >&2
    exit 1
  fi
  tmp="$(mktemp -d)"
  members=()
  for m in "${corpus[@]}"; do members+=("data/meshes/${m%%@*}.off"); done
  # Each file once: tar reports a member named twice as missing.
  mapfile -t members < <(printf '%s\n' "${members[@]}" | sort -u)
  tar -xzf "$tarball" -C "$tmp" "${members[@]}"
  data="$tmp/data/meshes"
fi
data="$(cd "$data" && pwd)"

# Number of faces from an OFF header (comments and blank lines skipped; "OFF" may share
# its line with the counts).
off_faces() {
  awk '{ sub(/#.*/, "") } { for(i = 1; i <= NF; ++i) t[n++] = $i } n >= 4 { exit }
       END { k = (t[0] ~ /OFF$/) ? 1 : 0; print t[k + 1] }' "$1"
}

meshes=()
for m in "${corpus[@]}"; do
  if [ "$tubes" = 1 ]; then meshes+=("$m"); continue; fi
  file="$data/${m%%@*}.off"
  case "$m" in *@*) subdivision="@${m#*@}" ;; *) subdivision="" ;; esac
  if [ ! -f "$file" ]; then
    echo "missing $file, skipped" >&2
    continue
  fi
  if [ "$quick" = 1 ] && [ "$large" = 0 ] && [ "$(off_faces "$file")" -ge 15000 ]; then
    continue
  fi
  meshes+=("$file$subdivision")
done
if [ "$full" = 1 ] && [ "$quick" = 0 ] && [ "$large" = 0 ] && [ -f "$data/bunny00.off" ]; then
  meshes+=("$data/bunny00.off@loop1" "$data/bunny00.off@loop2")
fi
if [ ${#meshes[@]} -eq 0 ]; then
  echo "no mesh to run" >&2
  exit 1
fi

# Build, one translation unit, in Release. Tests and examples are only configured when
# their folders have a CMakeLists.txt.
cd "$root"
config=(-DCMAKE_BUILD_TYPE=Release)
[ -f test/CMakeLists.txt ] || config+=(-DSPHERICAL_PARAMETERIZATION_BUILD_TESTS=OFF)
[ -f examples/CMakeLists.txt ] || config+=(-DSPHERICAL_PARAMETERIZATION_BUILD_EXAMPLES=OFF)
cmake -S . -B "$build_dir" "${config[@]}" >/dev/null
cmake --build "$build_dir" --target benchmark
binary="$build_dir/bin/benchmark"

# Run.
results="$here/results"
if [ "$knob" = 1 ]; then results="$results/knob"; elif [ "$isosurfaces" = 1 ]; then results="$results/isosurfaces"; elif [ "$tubes" = 1 ]; then results="$results/tubes"; elif [ "$decimated" = 1 ]; then results="$results/decimated"; elif [ "$defects" = 1 ]; then results="$results/defects"; elif [ "$large" = 1 ]; then results="$results/large"; fi
mkdir -p "$results"
args=(--energies "$energies" --pipeline "$pipeline" --csv "$results/latest.csv" --json "$results/latest.json")
if [ "$quick" = 1 ]; then repeats=1; fi
if [ -n "$repeats" ]; then args+=(--repeats "$repeats"); fi
status=0
"$binary" "${args[@]}" "${meshes[@]}" | tee "$results/latest.txt" || status=$?

# Plot, with a Python that has matplotlib (the Debian one if the first python3 has none).
python=""
for candidate in python3 /usr/bin/python3; do
  if command -v "$candidate" >/dev/null && "$candidate" -c 'import matplotlib' 2>/dev/null; then
    python="$candidate"
    break
  fi
done
if [ -z "$python" ]; then
  echo "no python3 with matplotlib (Debian package python3-matplotlib): no plots" >&2
  exit 1
fi
"$python" "$here/plot_results.py" "$results/latest.json" --out "$results"
if [ "$knob" = 1 ]; then "$python" "$here/plot_knob.py" "$results/latest.csv" "$results/knob.png"; fi
exit "$status"
