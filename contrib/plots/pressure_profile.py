#!/usr/bin/python3
"""Plot the contact pressure of one load step against Johnson's Hertz profile.

Usage: contrib/plots/pressure_profile.py OUTPUT_DIR [STEP] [PNG]
  OUTPUT_DIR  a run's output folder (holds contact-NNNN.csv, summary.json)
  STEP        load step (default: the last one written)
  PNG         image to write (default OUTPUT_DIR/pressure-NNNN.png)

With a Hertz check in summary.json (Checks/Hertz line load), Johnson's
p(x) = p0 sqrt(1 - x^2/a^2) is drawn beside the pair pressures. In 3D
(Checks/Hertz point load) the pairs are plotted against their distance
from the z axis through the origin (V7's axis), with Hertz's
p(r) = p0 sqrt(1 - r^2/a^2), and a second panel shows the pairs seen
along the axis, coloured by pressure.
"""
import csv
import glob
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    folder = sys.argv[1]
    files = sorted(glob.glob(os.path.join(folder, "contact-*.csv")))
    if not files:
        sys.exit(f"{folder}: no contact-NNNN.csv (not a contact run?)")
    step = int(sys.argv[2]) if len(sys.argv) > 2 else int(files[-1][-8:-4])
    name = os.path.join(folder, f"contact-{step:04d}.csv")
    png = sys.argv[3] if len(sys.argv) > 3 else os.path.join(
        folder, f"pressure-{step:04d}.png")

    with open(name) as f:
        rows = list(csv.DictReader(f))
    three_d = "z" in rows[0]
    if three_d:
        xs = [math.hypot(float(r["x"]), float(r["y"])) for r in rows]
    else:
        xs = [abs(float(r["x"])) for r in rows]
    ps = [float(r["pressure"]) for r in rows]
    order = sorted(range(len(xs)), key=lambda i: xs[i])

    summary = json.load(open(os.path.join(folder, "summary.json")))
    checks = summary.get("checks", {})
    if three_d:
        fig, (ax, top) = plt.subplots(1, 2, figsize=(11, 4.2))
        ax.plot(xs, ps, "o", ms=3, label="pairs (force / tributary area)")
    else:
        fig, ax = plt.subplots(figsize=(6, 4))
        ax.plot([xs[i] for i in order], [ps[i] for i in order], "o-", ms=3,
                label="pairs (force / tributary area)")
    a = None
    for key, name in (("hertz_half_width_exact", "Johnson"),
                      ("hertz_contact_radius_exact", "Hertz")):
        if key in checks:
            a = checks[key]
            p0 = checks["hertz_peak_pressure_exact"]
            x = [1.3 * a * k / 400 for k in range(401)]
            ax.plot(x,
                    [p0 * math.sqrt(max(0.0, 1 - t * t / (a * a))) for t in x],
                    "k--", label=name)
            ax.set_xlim(0, 1.5 * a)
    if three_d:
        near = [i for i in range(len(rows)) if a is None or xs[i] < 1.5 * a]
        picture = top.scatter([float(rows[i]["x"]) for i in near],
                              [float(rows[i]["y"]) for i in near],
                              c=[ps[i] for i in near], s=14, cmap="viridis")
        if a is not None:
            t = [0.5 * math.pi * k / 100 for k in range(101)]
            top.plot([a * math.cos(u) for u in t], [a * math.sin(u) for u in t],
                     "k--", lw=1, label="Hertz's contact circle")
            top.legend(loc="upper right", framealpha=1.0)
        top.set_aspect("equal")
        top.set_xlabel("x")
        top.set_ylabel("y")
        top.set_title("pairs seen along the axis")
        fig.colorbar(picture, ax=top, label="contact pressure")
    ax.set_xlabel("distance from the symmetry axis")
    ax.set_ylabel("contact pressure")
    ax.set_title(f"{summary.get('scene', '')}, step {step} "
                 f"({summary.get('discretization', '')}, "
                 f"{summary.get('n_contact_pairs', '?')} pairs)")
    ax.legend()
    fig.tight_layout()
    fig.savefig(png, dpi=120)
    print(png)


if __name__ == "__main__":
    main()
