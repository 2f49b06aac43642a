#!/usr/bin/env python3
"""An independent check of a sphere map, written apart from the package's C++ code.

    check_sphere_map.py INPUT.off SPHERE.off [--level L] [--rotation SEED]
                        [--cli-report REPORT] [--bounds]

SPHERE.off is the map as the command line tool writes it: INPUT's vertices, in the same order,
moved onto the unit sphere, and the same faces. Both may be FreeSurfer triangle surfaces
instead (`lh.white lh.sphere`), the sphere's radius 100 scaled to 1. Prints, from the two files alone:
- validity: the largest | |x| - 1 |, the faces whose orientation differs from the input's, and
  the map's degree (the sum of the faces' signed solid angles over 4 pi);
- the smallest area ratio (a face's share of the sphere over its share of the input's area)
  and the faces under 1e-3, the mean |log area ratio| and the mean quasi-conformal ratio
  (weighted by input area);
- an icosphere resampling: each point of a geodesic icosphere of subdivision L (default 6,
  turned by a random rotation if SEED is given) is located in the map and given the input
  position interpolated there; the distances from the input's vertices and face centroids to
  that surface, in % of the input's bounding-box diagonal (mean and max).
With --cli-report, the figures are compared with those the command line tool printed (its
standard output with --remesh-icosphere L); with --bounds, with the package's promise for its
default energy (valid, smallest area ratio at least 1e-3, resampling at most 0.2% on average
and 2% at most). The exit status is 1 if any comparison fails. Needs NumPy and SciPy.
"""
import argparse
import re
import sys

import numpy as np
from scipy.spatial import cKDTree


def read_off(path):
    with open(path) as f:
        lines = [line.split('#')[0].split() for line in f]
    lines = [line for line in lines if line]
    if not lines or not lines[0][0].endswith('OFF'):
        sys.exit(f'{path}: not an OFF file')
    counts, body = (lines[0][1:], lines[1:]) if len(lines[0]) > 1 else (lines[1], lines[2:])
    nv, nf = int(counts[0]), int(counts[1])
    points = np.array([[float(t) for t in line[:3]] for line in body[:nv]])  # colours ignored
    faces = []
    for line in body[nv:nv + nf]:
        if int(line[0]) != 3:
            sys.exit(f'{path}: a face is not a triangle')
        faces.append([int(t) for t in line[1:4]])
    return points, np.array(faces, dtype=np.int64)


def read_freesurfer(path):
    """A FreeSurfer triangle surface (big-endian: magic, two text lines, counts, points, faces)."""
    data = open(path, 'rb').read()
    at = 3
    for _ in range(2):
        at = data.index(b'\n', at) + 1
    nv, nf = np.frombuffer(data, '>i4', 2, at)
    at += 8
    points = np.frombuffer(data, '>f4', 3 * nv, at).reshape(-1, 3).astype(float)
    faces = np.frombuffer(data, '>i4', 3 * nf, at + 12 * nv).reshape(-1, 3).astype(np.int64)
    return points, faces


def read_mesh(path, on_sphere=False):
    """OFF, or a FreeSurfer triangle surface by its magic number; a FreeSurfer sphere (radius
    100) is scaled to the unit sphere."""
    with open(path, 'rb') as f:
        is_freesurfer = f.read(3) == b'\xff\xff\xfe'
    if not is_freesurfer:
        return read_off(path)
    points, faces = read_freesurfer(path)
    if on_sphere:
        points /= np.linalg.norm(points, axis=1)[:, None]
    return points, faces


def icosphere(level):
    t = (1 + 5 ** 0.5) / 2
    points = [np.array(p, float) / np.linalg.norm(p) for p in
              [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
               (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
             (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
             (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(level):
        midpoint = {}

        def middle(a, b):
            key = (min(a, b), max(a, b))
            if key not in midpoint:
                p = points[a] + points[b]
                points.append(p / np.linalg.norm(p))
                midpoint[key] = len(points) - 1
            return midpoint[key]

        finer = []
        for a, b, c in faces:
            ab, bc, ca = middle(a, b), middle(b, c), middle(c, a)
            finer += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = finer
    return np.array(points), np.array(faces, dtype=np.int64)


def random_rotation(seed):
    q, r = np.linalg.qr(np.random.default_rng(seed).normal(size=(3, 3)))
    q *= np.sign(np.diag(r))
    if np.linalg.det(q) < 0:
        q[:, 0] *= -1
    return q


def triple(a, b, c):
    return np.einsum('ij,ij->i', a, np.cross(b, c))


def corners(points, faces):
    return points[faces[:, 0]], points[faces[:, 1]], points[faces[:, 2]]


def holds(p, a, b, c):
    """Whether the spherical triangle (a, b, c), counterclockwise seen from outside, holds p."""
    slack = -1e-14  # a point on an edge belongs to both faces
    return (triple(p, a, b) >= slack) & (triple(p, b, c) >= slack) & (triple(p, c, a) >= slack)


def locate(sphere, faces, queries):
    """A face of the map holding each unit vector of `queries`: candidates among the faces
    with the nearest centroids first, then all faces."""
    centroids = sum(corners(sphere, faces)) / 3
    tree = cKDTree(centroids / np.linalg.norm(centroids, axis=1)[:, None])
    found = -np.ones(len(queries), dtype=np.int64)
    todo = np.arange(len(queries))
    for k in (16, 128, 1024, len(faces)):
        if len(todo) == 0:
            break
        k = min(k, len(faces))
        candidates = tree.query(queries[todo], k=k)[1].reshape(len(todo), k)
        p = np.repeat(queries[todo], k, axis=0)
        inside = holds(p, *corners(sphere, faces[candidates.ravel()])).reshape(len(todo), k)
        hit = inside.any(axis=1)
        found[todo[hit]] = candidates[hit, inside[hit].argmax(axis=1)]
        todo = todo[~hit]
    if len(todo):
        sys.exit(f'{len(todo)} icosphere points lie in no face: the map does not cover the sphere')
    return found


def resample(points, sphere, faces, queries):
    """The input positions at `queries`, interpolated linearly on the chord triangle that the
    ray through each query crosses."""
    face = locate(sphere, faces, queries)
    a, b, c = corners(sphere, faces[face])
    normal = np.cross(b - a, c - a)
    on_chord = queries * (np.einsum('ij,ij->i', normal, a) / np.einsum('ij,ij->i', normal, queries))[:, None]
    norm2 = np.einsum('ij,ij->i', normal, normal)
    u = np.einsum('ij,ij->i', normal, np.cross(c - b, on_chord - b)) / norm2
    v = np.einsum('ij,ij->i', normal, np.cross(a - c, on_chord - c)) / norm2
    pa, pb, pc = corners(points, faces[face])
    return u[:, None] * pa + v[:, None] * pb + (1 - u - v)[:, None] * pc


def closest_points(p, a, b, c):
    """The point of each triangle (a, b, c) closest to p, row by row (Voronoi regions of the
    vertices, then of the edges, then the inside)."""
    ab, ac = b - a, c - a
    d1, d2 = (ab * (p - a)).sum(1), (ac * (p - a)).sum(1)
    d3, d4 = (ab * (p - b)).sum(1), (ac * (p - b)).sum(1)
    d5, d6 = (ab * (p - c)).sum(1), (ac * (p - c)).sum(1)
    va, vb, vc = d3 * d6 - d5 * d4, d5 * d2 - d1 * d6, d1 * d4 - d3 * d2
    out = np.full_like(p, np.nan)
    free = np.ones(len(p), bool)

    def assign(mask, value):
        mask = mask & free
        out[mask] = value[mask]
        free[mask] = False

    with np.errstate(divide='ignore', invalid='ignore'):
        assign((d1 <= 0) & (d2 <= 0), a)
        assign((d3 >= 0) & (d4 <= d3), b)
        assign((d6 >= 0) & (d5 <= d6), c)
        assign((vc <= 0) & (d1 >= 0) & (d3 <= 0), a + (d1 / (d1 - d3))[:, None] * ab)
        assign((vb <= 0) & (d2 >= 0) & (d6 <= 0), a + (d2 / (d2 - d6))[:, None] * ac)
        assign((va <= 0) & (d4 >= d3) & (d5 >= d6),
               b + ((d4 - d3) / ((d4 - d3) + (d5 - d6)))[:, None] * (c - b))
        total = va + vb + vc
        assign(np.ones(len(p), bool), a + (vb / total)[:, None] * ab + (vc / total)[:, None] * ac)
    degenerate = ~np.isfinite(out).all(axis=1)  # a triangle of no area: its nearest corner
    if degenerate.any():
        options = np.stack([a[degenerate], b[degenerate], c[degenerate]], axis=1)
        nearest = np.linalg.norm(options - p[degenerate][:, None], axis=2).argmin(axis=1)
        out[degenerate] = options[np.arange(len(nearest)), nearest]
    return out


def distances_to_mesh(queries, points, faces):
    """Exact distance from each query to the triangle mesh: a bound from the triangles of the
    8 nearest centroids, then every triangle whose bounding ball comes closer than it."""
    a, b, c = corners(points, faces)
    centres = (a + b + c) / 3
    radii = np.max([np.linalg.norm(x - centres, axis=1) for x in (a, b, c)], axis=0)
    tree = cKDTree(centres)
    best = np.full(len(queries), np.inf)
    for f in tree.query(queries, k=min(8, len(faces)))[1].reshape(len(queries), -1).T:
        best = np.minimum(best, np.linalg.norm(closest_points(queries, a[f], b[f], c[f]) - queries, axis=1))
    reach = np.quantile(radii, 0.99)
    large = np.nonzero(radii > reach)[0]  # always candidates: their balls reach further
    for i, q in enumerate(queries):
        near = np.asarray(tree.query_ball_point(q, best[i] + reach), dtype=np.int64)
        f = np.concatenate([near, large])
        if len(f):
            p = np.repeat(q[None], len(f), axis=0)
            best[i] = min(best[i], np.linalg.norm(closest_points(p, a[f], b[f], c[f]) - p, axis=1).min())
    return best


def quasi_conformal_ratios(points, sphere, faces):
    """sigma_max / sigma_min of the affine map from each input triangle to its chord triangle."""
    def edge_frames(x):
        a, b, c = corners(x, faces)
        e1, e2 = b - a, c - a
        u = e1 / np.linalg.norm(e1, axis=1)[:, None]
        n = np.cross(e1, e2)
        w = np.cross(n / np.linalg.norm(n, axis=1)[:, None], u)
        return np.stack([np.stack([(e1 * u).sum(1), (e1 * w).sum(1)], 1),
                         np.stack([(e2 * u).sum(1), (e2 * w).sum(1)], 1)], 2)

    with np.errstate(all='ignore'):
        jacobian = edge_frames(sphere) @ np.linalg.inv(edge_frames(points))
        singular = np.linalg.svd(jacobian, compute_uv=False)
        return singular[:, 0] / singular[:, 1]


def figures(points, sphere, faces, level, seed):
    out = {'radius error': np.abs(np.linalg.norm(sphere, axis=1) - 1).max()}
    sphere = sphere / np.linalg.norm(sphere, axis=1)[:, None]
    if triple(*corners(points, faces)).sum() < 0:  # an inward-oriented input
        faces = faces[:, ::-1].copy()
    a, b, c = corners(sphere, faces)
    # Signed solid angles (Van Oosterom and Strackee).
    solid = 2 * np.arctan2(triple(a, b, c), 1 + (a * b).sum(1) + (b * c).sum(1) + (c * a).sum(1))
    out['flipped'] = int((triple(a, b, c) <= 0).sum())
    out['degree'] = solid.sum() / (4 * np.pi)
    pa, pb, pc = corners(points, faces)
    area = 0.5 * np.linalg.norm(np.cross(pb - pa, pc - pa), axis=1)
    kept = area > 1e-12 * area.max()  # faces of no area have no ratio
    ratio = (solid[kept] / solid.sum()) / (area[kept] / area.sum())
    weight = area[kept] / area[kept].sum()
    out['smallest area ratio'] = ratio.min()
    out['faces under 1e-3'] = int((ratio < 1e-3).sum())
    with np.errstate(invalid='ignore'):  # a flipped face has a negative ratio: no mean
        out['mean |log area ratio|'] = (np.abs(np.log(ratio)) * weight).sum()
    qc = quasi_conformal_ratios(points, sphere, faces)[kept]
    finite = np.isfinite(qc)
    out['mean quasi-conformal'] = (qc[finite] * weight[finite]).sum() / weight[finite].sum()
    grid, grid_faces = icosphere(level)
    if seed is not None:
        grid = grid @ random_rotation(seed).T
    resampled = resample(points, sphere, faces, grid)
    samples = np.concatenate([points, (pa + pb + pc) / 3])
    distance = distances_to_mesh(samples, resampled, grid_faces)
    diagonal = np.linalg.norm(points.max(axis=0) - points.min(axis=0))
    out['resampling mean %'] = 100 * distance.mean() / diagonal
    out['resampling max %'] = 100 * distance.max() / diagonal
    return out


def cli_figures(report_path):
    """The figures the command line tool printed, by the same names."""
    text = open(report_path).read()
    patterns = {'smallest area ratio': r'smallest area ratio ([0-9.eE+-]+)',
                'mean |log area ratio|': r'\|log area ratio\| mean ([0-9.eE+-]+)',
                'mean quasi-conformal': r'quasi-conformal\s+mean ([0-9.eE+-]+)',
                'resampling mean %': r'distance to the input: mean ([0-9.eE+-]+)%',
                'resampling max %': r'distance to the input: mean [0-9.eE+-]+%, max ([0-9.eE+-]+)%'}
    found = {}
    for name, pattern in patterns.items():
        match = re.search(pattern, text)
        if not match:
            sys.exit(f'{report_path}: no "{name}" in the report')
        found[name] = float(match.group(1))
    return found


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('input')
    parser.add_argument('sphere')
    parser.add_argument('--level', type=int, default=6)
    parser.add_argument('--rotation', type=int, default=None, metavar='SEED')
    parser.add_argument('--cli-report', metavar='REPORT')
    parser.add_argument('--bounds', action='store_true')
    args = parser.parse_args()
    points, faces = read_mesh(args.input)
    sphere, sphere_faces = read_mesh(args.sphere, on_sphere=True)
    if len(sphere) != len(points) or not np.array_equal(faces, sphere_faces):
        sys.exit('the map does not have the input\'s vertices and faces')
    found = figures(points, sphere, faces, args.level, args.rotation)
    for name, value in found.items():
        print(f'{name:24s} {value:.6g}')
    failures = []
    if args.cli_report:
        # The tool prints 4 significant digits: a rounding of at most 5e-4 of the value.
        for name, printed in cli_figures(args.cli_report).items():
            if abs(found[name] - printed) > 6e-4 * abs(printed) + 1e-12:
                failures.append(f'{name}: {found[name]:.6g} here, {printed:.6g} in the report')
    if args.bounds:
        checks = [('valid', found['radius error'] < 1e-9 and found['flipped'] == 0 and abs(found['degree'] - 1) < 1e-6),
                  ('smallest area ratio >= 1e-3', found['smallest area ratio'] >= 1e-3),
                  ('resampling mean <= 0.2%', found['resampling mean %'] <= 0.2),
                  ('resampling max <= 2%', found['resampling max %'] <= 2)]
        failures += [name for name, ok in checks if not ok]
    for failure in failures:
        print('FAILED: ' + failure)
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
