#!/usr/bin/env python3
"""The 3D shallow ironing (prm/ironing-3d.prm) against the published
reaction-force curves (contrib/studies/data/shallow-ironing-3d-reference.csv):
per finished load step the time t of the published plots (0.2 + 0.8 press
while pressing, 1 + slide while sliding), the die's F_x and F_y (Body 2's
support reaction; F_y the downward force it presses with), the reference
interpolated linearly between its points at t, and the difference in per
cent of the reference's largest F_y.

usage: ironing_3d.py RUN_FOLDER [--friction] [--log LOG]

RUN_FOLDER holds the run's summary.json. A run stopped before it wrote its
summary gives its steps through --log (the terminal output: the lines
'Load step ...: ..., press P, slide S' and 'total contact force on Body 1:
Fx Fy Fz', the force on the block, which is the die's support reaction).
Writes ironing-3d.csv and ironing-3d.md into RUN_FOLDER."""

import argparse
import csv
import json
import os
import re

HERE = os.path.dirname(os.path.abspath(__file__))
REFERENCE = os.path.join(HERE, "data", "shallow-ironing-3d-reference.csv")


def reference(curve):
    """The (t, F) points of one reference curve, in t order."""
    with open(REFERENCE) as f:
        rows = csv.DictReader(line for line in f if not line.startswith("#"))
        points = [(float(r["t"]), float(r["force"])) for r in rows
                  if r["curve"] == curve]
    return sorted(points)


def interpolate(points, t):
    for (t0, f0), (t1, f1) in zip(points, points[1:]):
        if t0 <= t <= t1:
            return f0 + (f1 - f0) * (t - t0) / (t1 - t0)
    return float("nan")


def steps_of_summary(folder):
    with open(os.path.join(folder, "summary.json")) as f:
        summary = json.load(f)
    steps = []
    for step in summary.get("load_steps", []):
        if step.get("status") == "failed":
            continue
        factors = step.get("history_factors") or {}
        reaction = (step.get("bodies") or [{}, {}])[1].get("support_reaction")
        if reaction is None:
            continue
        steps.append((step["step"], factors.get("press", 0.),
                      factors.get("slide", 0.), reaction[0], reaction[1],
                      step.get("newton_iterations")))
    return steps


def steps_of_log(path):
    steps, current = [], None
    step_line = re.compile(r"^Load step (\d+)/\d+:.*press ([-0-9.e+]+), "
                           r"slide ([-0-9.e+]+)")
    for line in open(path):
        m = step_line.match(line)
        if m:
            current = (int(m.group(1)), float(m.group(2)),
                       float(m.group(3)))
        elif "total contact force on Body 1:" in line and current:
            fx, fy = map(float, line.split(":")[1].split()[:2])
            steps.append(current + (fx, fy, None))
            current = None
    return steps


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("folder")
    parser.add_argument("--friction", action="store_true",
                        help="compare with the mu = 0.3 curves")
    parser.add_argument("--log")
    args = parser.parse_args()
    steps = steps_of_log(args.log) if args.log else \
        steps_of_summary(args.folder)
    case = "friction" if args.friction else "frictionless"
    ref_y, ref_x = reference("fy_" + case), reference("fx_" + case)
    scale = max(f for _, f in ref_y)
    rows = []
    for step, press, slide, fx, fy, iterations in steps:
        t = 1. + slide if slide > 0. else 0.2 + 0.8 * press
        # The die is pushed up by the block: its support pulls it down.
        fy = -fy
        ry, rx = interpolate(ref_y, t), interpolate(ref_x, t)
        rows.append({"step": step, "t": "%.4f" % t,
                     "F_y": "%.5g" % fy, "F_y ref": "%.5g" % ry,
                     "dF_y %": "%+.2f" % (100. * (fy - ry) / scale),
                     "F_x": "%.5g" % fx, "F_x ref": "%.5g" % rx,
                     "dF_x %": "%+.2f" % (100. * (fx - rx) / scale),
                     "Newton": "" if iterations is None else iterations})
    columns = list(rows[0]) if rows else ["step"]
    with open(os.path.join(args.folder, "ironing-3d.csv"), "w") as f:
        writer = csv.DictWriter(f, columns)
        writer.writeheader()
        writer.writerows(rows)
    with open(os.path.join(args.folder, "ironing-3d.md"), "w") as f:
        f.write("| " + " | ".join(columns) + " |\n")
        f.write("|" + "---|" * len(columns) + "\n")
        for r in rows:
            f.write("| " + " | ".join(str(r[c]) for c in columns) + " |\n")
    with open(os.path.join(args.folder, "ironing-3d.md")) as f:
        print(f.read(), end="")
    print("differences in per cent of the reference's largest F_y, %.4g"
          % scale)


if __name__ == "__main__":
    main()
