#!/bin/bash
# usage: freesurfer_io.sh TOOL MESH WORK_DIR CHECKER
# The command line tool on FreeSurfer triangle surfaces, checked against NiBabel's reader and
# writer of the format (an implementation apart from the tool's): MESH written by NiBabel as
# `lh.white` with a volume geometry; its map written as `lh.sphere` must read back in NiBabel
# with the input's faces, radius 100, the volume geometry kept and the points of the .off
# map, and so must the icosphere remesh; the FreeSurfer sphere must serve as --map-to's
# OTHER_SPHERE; broken files, a .ply OUTPUT and a missing folder are refused with nothing
# written; CHECKER (tools/check_sphere_map.py) reads the pair as FreeSurfer files and finds
# the default's bounds met. Exits 77 (a skip) without a Python with NiBabel, NumPy and SciPy.
tool=$1 mesh=$2 work=$3 checker=$4
source "$(dirname "$0")/python_with.sh"
python=$(python_with nibabel numpy scipy) || { echo "skipped: no python3 with NiBabel, NumPy and SciPy"; exit 77; }
mkdir -p "$work" && cd "$work" || exit 1
rm -f lh.* *.off *.err

"$python" - "$mesh" <<'EOF' || exit 1
import sys, numpy as np, nibabel.freesurfer.io as fio
tokens = open(sys.argv[1]).read().split()
nv, nf = int(tokens[1]), int(tokens[2])
points = np.array(tokens[4:4 + 3 * nv], float).reshape(-1, 3)
faces = np.array(tokens[4 + 3 * nv:4 + 3 * nv + 4 * nf], int).reshape(-1, 4)[:, 1:]
volume = {'head': [2, 0, 20], 'valid': '1  # volume info valid', 'filename': 'orig.mgz', 'volume': [256, 256, 256],
          'voxelsize': [1, 1, 1], 'xras': [-1, 0, 0], 'yras': [0, 0, -1], 'zras': [0, 1, 0], 'cras': [1, 2, 3]}
fio.write_geometry('lh.white', points, faces, create_stamp='created by the test', volume_info=volume)
EOF

"$tool" --quiet lh.white lh.sphere --remesh-icosphere 4 lh.ico4.white || { echo "no map of lh.white"; exit 1; }
"$tool" --quiet lh.white sphere.off --remesh-icosphere 4 ico4.off || { echo "no .off map of lh.white"; exit 1; }
"$tool" --quiet lh.white mapped.off --map-to lh.white lh.sphere mapped_onto.off || { echo "--map-to refused lh.sphere"; exit 1; }

"$python" - <<'EOF' || exit 1
import numpy as np, nibabel.freesurfer.io as fio
def diagonal_of(points):
    return np.linalg.norm(points.max(0) - points.min(0))
white, white_faces = fio.read_geometry('lh.white')
sphere, faces, meta = fio.read_geometry('lh.sphere', read_metadata=True)
assert np.array_equal(faces, white_faces), 'lh.sphere does not have the faces of lh.white'
radius = np.linalg.norm(sphere, axis=1)
assert np.all(np.abs(radius - 100) < 1e-4), f'radius {radius.min()} to {radius.max()}, not 100'
assert meta.get('filename') == 'orig.mgz' and list(meta['cras']) == [1, 2, 3], f'volume geometry lost: {meta}'
tokens = open('sphere.off').read().split()
exact = np.array(tokens[4:4 + 3 * len(sphere)], float).reshape(-1, 3)
assert np.max(np.abs(sphere / 100 - exact)) < 1e-6, 'lh.sphere is not the .off map'
ico, ico_faces, ico_meta = fio.read_geometry('lh.ico4.white', read_metadata=True)
tokens = open('ico4.off').read().split()
assert (len(ico), len(ico_faces)) == (2562, 5120) and (int(tokens[1]), int(tokens[2])) == (2562, 5120), 'not icosphere 4'
ico_exact = np.array(tokens[4:4 + 3 * len(ico)], float).reshape(-1, 3)
off_faces = np.array(tokens[4 + 3 * len(ico):4 + 3 * len(ico) + 4 * len(ico_faces)], int).reshape(-1, 4)[:, 1:]
assert np.array_equal(ico_faces, off_faces), 'the FreeSurfer remesh does not have the .off remesh faces'
assert np.max(np.abs(ico - ico_exact)) < 1e-6 * diagonal_of(white), 'the FreeSurfer remesh is not the .off remesh'
assert ico_meta.get('filename') == 'orig.mgz', 'volume geometry lost in the remesh'
tokens = open('mapped_onto.off').read().split()
onto = np.array(tokens[4:4 + 3 * len(white)], float).reshape(-1, 3)
assert np.max(np.linalg.norm(onto - white, axis=1)) < 1e-4 * diagonal_of(white), 'a surface mapped onto itself moved'
print('lh.sphere: the faces of lh.white, radius 100, its volume geometry, the .off map to float precision;')
print('lh.ico4.white: the .off remesh to float precision, the volume geometry')
EOF
"$python" "$checker" lh.white lh.sphere --bounds || exit 1

head -c 200 lh.white > lh.truncated
printf '\xff\xff\xff' > lh.quadrangles
printf '\xff\xff\xfd' > lh.new_quadrangles
for broken in lh.truncated lh.quadrangles lh.new_quadrangles; do
  "$tool" --quiet $broken broken.off 2> broken.err
  status=$?
  cat broken.err
  test $status -eq 1 && grep -q "cannot read $broken" broken.err && ! test -e broken.off || { echo "$broken not refused"; exit 1; }
done
"$tool" --quiet lh.white sphere.ply 2> ply.err
status=$?
test $status -eq 1 && ! test -e sphere.ply || { echo "a .ply OUTPUT was not refused"; exit 1; }
"$tool" --quiet lh.white lh.sphere2 --remesh-icosphere 3 no_folder/lh.ico3 2> folder.err
status=$?
test $status -eq 1 && grep -q "no folder no_folder" folder.err && ! test -e lh.sphere2 ||
  { echo "a FreeSurfer output in a missing folder was not refused before the solve"; exit 1; }
echo "broken FreeSurfer files, a .ply OUTPUT and a missing folder refused, nothing written"
