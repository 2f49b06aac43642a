#!/usr/bin/python3
"""Figures of a spherical parameterization, with Debian's matplotlib and numpy only.

    /usr/bin/python3 doc/render_figures.py INPUT.off SPHERE.off OUTPUT_PREFIX [--title TEXT]

SPHERE.off is the map of INPUT.off as spherical_parameterize writes it: the same vertices in
the same order, on the unit sphere. Writes two PNGs:

- OUTPUT_PREFIX_area.png: the sphere, each face coloured by log(spherical area share / input
  area share), seen from two opposite sides; blue faces were shrunk, red ones grown.
- OUTPUT_PREFIX_checker.png: the input model, each face coloured by the checker of a
  22.5-degree longitude/latitude grid on the sphere that its (subdivided) sphere centroid
  falls in: how the map squeezes and shears shows in the checks, as in Figure 2 of
  Friedel et al. Blue and red checks are the two hemispheres. The grid's poles are put at
  the images of the model's extreme points along its longest axis (see grid_frame()).

Rendering is a flat orthographic projection drawn back to front (painter's algorithm), with
Lambert shading: exact for the convex sphere, good enough for a model.
"""

import argparse
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402


def read_off(path):
    """Points (n x 3) and triangles (m x 3) of an OFF file; polygons are split into fans."""
    with open(path) as f:
        tokens = []
        for line in f:
            line = line.split("#", 1)[0].split()
            tokens.extend(line)
    if not tokens[0].endswith("OFF"):
        raise SystemExit(f"{path}: not an OFF file")
    nv, nf = int(tokens[1]), int(tokens[2])
    at = 4
    points = np.array(tokens[at:at + 3 * nv], dtype=float).reshape(nv, 3)
    at += 3 * nv
    triangles = []
    for _ in range(nf):
        k = int(tokens[at])
        face = [int(t) for t in tokens[at + 1:at + 1 + k]]
        at += 1 + k
        triangles.extend([face[0], face[i], face[i + 1]] for i in range(1, k - 1))
    return points, np.array(triangles, dtype=int)


def flat_areas(points, triangles):
    a, b, c = (points[triangles[:, i]] for i in range(3))
    return 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)


def spherical_areas(points, triangles):
    """Signed area of the geodesic triangles (Van Oosterom and Strackee)."""
    a, b, c = (points[triangles[:, i]] for i in range(3))
    det = np.einsum("ij,ij->i", a, np.cross(b, c))
    den = 1 + np.einsum("ij,ij->i", a, b) + np.einsum("ij,ij->i", b, c) + np.einsum("ij,ij->i", c, a)
    return 2 * np.arctan2(det, den)


def log_area_ratio(points, sphere, triangles):
    flat = flat_areas(points, triangles)
    sph = spherical_areas(sphere, triangles)
    if sph.sum() < 0:  # inward-oriented input: its map has degree -1 in these terms
        sph = -sph
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.log((sph / (4 * np.pi)) / (flat / flat.sum()))


def subdivide(points, sphere, triangles, levels):
    """Midpoint subdivision of both meshes, the new sphere points pushed back onto the sphere,
    so that the checks of the pulled-back texture have finer edges than the faces."""
    for _ in range(levels):
        edges = {}
        new_points, new_sphere = list(points), list(sphere)

        def midpoint(i, j):
            key = (min(i, j), max(i, j))
            if key not in edges:
                edges[key] = len(new_points)
                new_points.append((points[i] + points[j]) / 2)
                s = sphere[i] + sphere[j]
                new_sphere.append(s / np.linalg.norm(s))
            return edges[key]

        out = []
        for a, b, c in triangles:
            ab, bc, ca = midpoint(a, b), midpoint(b, c), midpoint(c, a)
            out += [(a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)]
        points, sphere, triangles = np.array(new_points), np.array(new_sphere), np.array(out)
    return points, sphere, triangles


def rotation(azimuth, elevation, up):
    """Rows: screen x, screen y and the direction towards the viewer."""
    up = np.asarray(up, float)
    up /= np.linalg.norm(up)
    side = np.cross(up, [1.0, 0, 0]) if abs(up[0]) < 0.9 else np.cross(up, [0, 1.0, 0])
    side /= np.linalg.norm(side)
    front = np.cross(side, up)
    az, el = math.radians(azimuth), math.radians(elevation)
    horizontal = math.cos(az) * front + math.sin(az) * side
    towards = math.cos(el) * horizontal + math.sin(el) * up
    x = np.cross(up, towards)
    x /= np.linalg.norm(x)
    return np.array([x, np.cross(towards, x), towards])


def draw(ax, points, triangles, colors, view, cull=False, light=0.65):
    """Orthographic view of the triangles, back to front, shaded by their normal."""
    p = points @ view.T
    a, b, c = (p[triangles[:, i]] for i in range(3))
    normal = np.cross(b - a, c - a)
    length = np.linalg.norm(normal, axis=1)
    facing = normal[:, 2] / np.where(length > 0, length, 1)
    keep = facing > 0 if cull else np.ones(len(triangles), bool)
    depth = (a[:, 2] + b[:, 2] + c[:, 2])[keep]
    order = np.argsort(depth)
    shade = (1 - light + light * np.abs(facing[keep]))[order, None]
    rgb = np.asarray(colors)[keep][order][:, :3] * shade
    polygons = np.stack([a[keep], b[keep], c[keep]], axis=1)[order][:, :, :2]
    ax.add_collection(PolyCollection(polygons, facecolors=np.clip(rgb, 0, 1), edgecolors="none",
                                     antialiased=False))
    lo, hi = p[:, :2].min(0), p[:, :2].max(0)
    pad = 0.03 * (hi - lo).max()
    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_aspect("equal")
    ax.axis("off")


def grid_frame(points, sphere, up):
    """Rows of a rotation of the sphere that puts the grid's poles at the images of the model's
    two extreme points along its longest axis (so the checks run in bands around the body) and
    longitude 0 at the image of its highest point. Falls back to the sphere's own axes."""
    centred = points - points.mean(0)
    axis = np.linalg.eigh(centred.T @ centred)[1][:, -1]
    pole = sphere[np.argmax(centred @ axis)] - sphere[np.argmin(centred @ axis)]
    top = sphere[np.argmax(centred @ np.asarray(up, float))]
    if np.linalg.norm(pole) < 1e-6:
        return np.eye(3)
    pole /= np.linalg.norm(pole)
    x = top - (top @ pole) * pole
    if np.linalg.norm(x) < 1e-6:
        return np.eye(3)
    x /= np.linalg.norm(x)
    return np.array([x, np.cross(pole, x), pole])


def checker_colors(sphere, triangles):
    centroid = sphere[triangles].mean(axis=1)
    centroid /= np.linalg.norm(centroid, axis=1)[:, None]
    longitude = np.arctan2(centroid[:, 1], centroid[:, 0])
    colatitude = np.arccos(np.clip(centroid[:, 2], -1, 1))
    step = np.pi / 8
    dark = (np.floor(longitude / step) + np.floor(colatitude / step)).astype(int) % 2 == 1
    north = centroid[:, 2] > 0
    colors = np.tile([0.92, 0.92, 0.88], (len(triangles), 1))
    colors[dark & north] = [0.16, 0.27, 0.63]
    colors[dark & ~north] = [0.63, 0.20, 0.16]
    return colors


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("input")
    parser.add_argument("sphere")
    parser.add_argument("prefix")
    parser.add_argument("--title", default="")
    parser.add_argument("--up", type=float, nargs=3, default=[0, 1, 0], help="the model's up direction")
    parser.add_argument("--limit", type=float, default=4, help="colour range of the log area ratio is +-LIMIT")
    parser.add_argument("--subdivision", type=int, default=2, help="levels of subdivision for the checks")
    parser.add_argument("--dpi", type=int, default=100)
    args = parser.parse_args()

    points, triangles = read_off(args.input)
    sphere, sphere_triangles = read_off(args.sphere)
    if len(points) != len(sphere) or not np.array_equal(triangles, sphere_triangles):
        raise SystemExit(f"{args.sphere} does not have the vertices and faces of {args.input}")

    sphere = sphere @ grid_frame(points, sphere, args.up).T

    # (a) the sphere coloured by the log area ratio, seen from above and from below the
    # model's image (the grid frame's x axis, the image of the model's top, points up).
    ratio = log_area_ratio(points, sphere, triangles)
    finite = np.isfinite(ratio)
    cmap = plt.get_cmap("RdBu_r")
    norm = matplotlib.colors.Normalize(-args.limit, args.limit)
    colors = cmap(norm(np.where(finite, ratio, -args.limit)))
    fig, axes = plt.subplots(1, 2, figsize=(8, 3.7))
    fig.subplots_adjust(left=0.01, right=0.86, bottom=0.02, top=0.86, wspace=0.03)
    for ax, elevation, label in zip(axes, (55, -55), ("facing the image of the model's top", "the opposite side")):
        draw(ax, sphere, triangles, colors, rotation(0, elevation, [1, 0, 0]), cull=True, light=0.25)
        ax.set_title(label, fontsize=9)
    bar = fig.colorbar(matplotlib.cm.ScalarMappable(norm, cmap), cax=fig.add_axes([0.87, 0.1, 0.02, 0.7]),
                       extend="both")
    bar.set_label("log(sphere area share / input area share)")
    weights = flat_areas(points, triangles)[finite]
    mean = np.sum(weights * np.abs(ratio[finite])) / weights.sum()
    fig.suptitle(f"{args.title}  mean |log area ratio| {mean:.2f}".strip(), fontsize=11)
    fig.savefig(f"{args.prefix}_area.png", dpi=args.dpi)
    plt.close(fig)

    # (b) the model with the checkerboard pulled back from the sphere, two views.
    fine_points, fine_sphere, fine_triangles = subdivide(points, sphere, triangles, args.subdivision)
    colors = checker_colors(fine_sphere, fine_triangles)
    fig, axes = plt.subplots(1, 2, figsize=(10, 4.0))
    for ax, azimuth, elevation in zip(axes, (-60, 120), (20, 20)):
        draw(ax, fine_points, fine_triangles, colors, rotation(azimuth, elevation, args.up))
    fig.suptitle(f"{args.title}  checkerboard pulled back from the sphere".strip(), fontsize=11)
    fig.subplots_adjust(left=0.01, right=0.99, bottom=0.01, top=0.9, wspace=0.02)
    fig.savefig(f"{args.prefix}_checker.png", dpi=args.dpi)
    plt.close(fig)


if __name__ == "__main__":
    main()
