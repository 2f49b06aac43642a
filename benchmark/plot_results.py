#!/usr/bin/env python3
"""Plots of a benchmark result file (the JSON written by `benchmark --json`).

usage: plot_results.py [RESULTS.json] [--out DIR]

Writes DIR/time_vs_faces.png (time against faces, log-log, one series per energy, with the
Cholesky yardstick and 10x the yardstick) and DIR/distortion.png (per energy, the mean
|log area ratio| and the mean quasi-conformal ratio of every mesh). Invalid maps are marked
with a red x. Defaults: benchmark/results/latest.json, the folder of the results file.
"""

import argparse
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the backend)


def load(path):
    with open(path) as f:
        data = json.load(f)
    runs = [r for r in data.get("runs", []) if r.get("time_s") is not None]
    return data, runs


def energies_of(runs):
    names = []
    for r in runs:
        if r["energy"] not in names:
            names.append(r["energy"])
    return names


def meshes_of(runs):
    """Mesh names in order of increasing faces."""
    faces = {}
    for r in runs:
        faces[r["mesh"]] = r["faces"]
    return sorted(faces, key=lambda m: faces[m])


def plot_time(data, runs, out):
    fig, ax = plt.subplots(figsize=(8, 5.5))
    markers = "osD^v<>p"
    invalid_labelled = False
    for k, energy in enumerate(energies_of(runs)):
        rows = sorted((r for r in runs if r["energy"] == energy and r["status"] != "CRASHED"),
                      key=lambda r: r["faces"])
        if not rows:
            continue
        x = [r["faces"] for r in rows]
        y = [r["time_s"] for r in rows]
        ax.plot(x, y, marker=markers[k % len(markers)], label=energy)
        bad = [r for r in rows if not r["valid"]]
        if bad:
            ax.scatter([r["faces"] for r in bad], [r["time_s"] for r in bad], marker="x", s=120, color="red",
                       linewidths=2.5, zorder=5, label=None if invalid_labelled else "invalid map")
            invalid_labelled = True

    yard = {}
    for r in runs:
        if r.get("yardstick_s") and r["yardstick_s"] > 0:
            yard[r["faces"]] = r["yardstick_s"]
    if yard:
        x = sorted(yard)
        y = [yard[f] for f in x]
        solver = data.get("yardstick_solver", "Cholesky")
        ax.plot(x, y, color="black", linewidth=1.5, label="yardstick: %s factor+solve" % solver)
        ax.plot(x, [10 * v for v in y], color="black", linestyle="--", linewidth=1, label="10x yardstick")

    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("faces")
    ax.set_ylabel("wall time (s), median of the repeats")
    pipeline = runs[0].get("pipeline", "") if runs else ""
    ax.set_title("spherical_parameterize: time vs faces (%s pipeline)" % pipeline)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    path = os.path.join(out, "time_vs_faces.png")
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def plot_distortion(runs, out):
    energies = energies_of(runs)
    meshes = meshes_of(runs)
    fig, axes = plt.subplots(len(energies), 1, figsize=(max(8, 0.7 * len(meshes) + 3), 3.2 * len(energies)),
                             squeeze=False, sharex=True)
    width = 0.38
    for k, energy in enumerate(energies):
        ax = axes[k][0]
        by_mesh = {r["mesh"]: r for r in runs if r["energy"] == energy}
        xs = list(range(len(meshes)))
        log_area = [by_mesh[m]["log_area_mean"] if m in by_mesh else 0 for m in meshes]
        qc = [by_mesh[m]["qc_mean"] if m in by_mesh else 0 for m in meshes]
        ax.bar([x - width / 2 for x in xs], log_area, width, label="mean |log area ratio|", color="tab:blue")
        ax.bar([x + width / 2 for x in xs], qc, width, label="mean quasi-conformal", color="tab:orange")
        top = max(log_area + qc + [1.0])
        bad = [x for x, m in zip(xs, meshes) if m in by_mesh and not by_mesh[m]["valid"]]
        if bad:
            ax.scatter(bad, [1.05 * top] * len(bad), marker="x", s=120, color="red", linewidths=2.5, zorder=5,
                       label="invalid map")
        missing = [x for x, m in zip(xs, meshes) if m not in by_mesh]
        for x in missing:
            ax.text(x, 0.02 * top, "n/a", ha="center", fontsize=7)
        ax.set_ylim(0, 1.15 * top)
        ax.set_ylabel(energy)
        ax.grid(True, axis="y", alpha=0.3)
        ax.legend(fontsize=7, loc="upper left")
    axes[-1][0].set_xticks(list(range(len(meshes))))
    axes[-1][0].set_xticklabels(meshes, rotation=40, ha="right")
    axes[0][0].set_title("distortion per mesh (area-weighted means; quasi-conformal = 1 for a similarity)")
    fig.tight_layout()
    path = os.path.join(out, "distortion.png")
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("results", nargs="?", default=os.path.join(here, "results", "latest.json"))
    parser.add_argument("--out", default=None, help="output folder (default: that of the results)")
    args = parser.parse_args()
    out = args.out or os.path.dirname(os.path.abspath(args.results))
    os.makedirs(out, exist_ok=True)
    data, runs = load(args.results)
    if not runs:
        print("no runs in %s" % args.results, file=sys.stderr)
        return 1
    for path in (plot_time(data, runs, out), plot_distortion(runs, out)):
        print("wrote %s" % path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
