#!/usr/bin/python3
"""Angle against area distortion along the balanced energy's knob, from a benchmark CSV.

    /usr/bin/python3 benchmark/plot_knob.py RESULTS.csv OUTPUT.png

RESULTS.csv holds runs of the energies balanced:A:B (run_benchmark.sh --knob writes it);
the knob is t = B / (A + B). One line per mesh: mean quasi-conformal ratio against mean
|log area ratio|, each point labelled with its t; hollow points are maps that a resampling
on the icosphere of level 6 does not keep (mean distance over 0.2% or largest over 2% of the
bounding box's diagonal).
"""

import csv
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def knob(energy):
    parts = energy.split(":")
    if parts[0] != "balanced" or len(parts) != 3:
        return None
    a, b = float(parts[1]), float(parts[2])
    return b / (a + b)


def main():
    if len(sys.argv) != 3:
        raise SystemExit(__doc__)
    runs = defaultdict(list)
    with open(sys.argv[1]) as f:
        for row in csv.DictReader(f):
            t = knob(row["energy"])
            if t is None or row["valid"] != "1":
                continue
            kept = 0 <= float(row["resampling_mean"]) <= 2e-3 and float(row["resampling_max"]) <= 2e-2
            runs[row["mesh"]].append((t, float(row["log_area_mean"]), float(row["qc_mean"]), kept))
    fig, ax = plt.subplots(figsize=(7, 5))
    for mesh, points in sorted(runs.items()):
        points.sort()
        line, = ax.plot([p[1] for p in points], [p[2] for p in points], "-", label=mesh)
        for t, area, angle, kept in points:
            ax.plot(area, angle, "o", color=line.get_color(), markerfacecolor=line.get_color() if kept else "white")
            ax.annotate(f"{t:g}", (area, angle), textcoords="offset points", xytext=(4, 4), fontsize=7)
    ax.set_xlabel("mean |log area ratio| (0: equal-area)")
    ax.set_ylabel("mean quasi-conformal ratio (1: conformal)")
    ax.set_yscale("log")
    ax.set_title("balanced energy, knob t from conformal (0) to equal-area (1);\n"
                 "hollow: a resampling on the level-6 icosphere loses part of the surface")
    ax.legend()
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=120)


if __name__ == "__main__":
    main()
