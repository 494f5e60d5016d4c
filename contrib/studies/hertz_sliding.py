#!/usr/bin/env python3
"""Finite sliding of a Hertz cylinder (prm/hertz-cylinder-sliding.prm):
every step's peak pair pressure against Hertz's p0 = 2 P / (pi a),
a = sqrt(4 P R / (pi E*)), for that step's contact force P (Johnson,
Contact Mechanics, eq. 5.39; 1/E* = 2 (1 - nu^2) / E for the two bodies of
one material), where the peak sits against where the cylinder's lowest
point is, and the Newton iterations of each step; then per run the
unknowns, the seconds and the spread of the deviation over the steps.

usage: hertz_sliding.py IGABDE OUTDIR

Runs: NURBS p = 2 with Sliding = finite (the scene), the same with
Sliding = small (pairs formed once: the contact stays at the start), and
FE_Q(2) on the same spans with Sliding = finite."""

import csv
import json
import math
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__))))
SCENE = os.path.join(ROOT, "prm", "hertz-cylinder-sliding.prm")
E, NU, R = 1000., 0.3, 8.
E_STAR = E / (2. * (1. - NU * NU))
STEPS = 11
RUNS = [("NURBS p=2, Sliding = finite", []),
        ("NURBS p=2, Sliding = small", ["Contact/Sliding=small"]),
        ("FE_Q(2), Sliding = finite", ["Discretization/Type=lagrange"])]


def run(igabde, folder, sets):
    arguments = [igabde, SCENE, "--quiet", "--set", "Output/Directory=" +
                 folder]
    for s in sets:
        arguments += ["--set", s]
    subprocess.run(arguments, check=True)
    with open(os.path.join(folder, "summary.json")) as f:
        return json.load(f)


def main():
    igabde, out = sys.argv[1], sys.argv[2]
    os.makedirs(out, exist_ok=True)
    print("| run | step | lowest point x | P | peak | Hertz p0 | "
          "peak / p0 - 1 | peak at x | Newton it. |")
    print("|---|---|---|---|---|---|---|---|---|")
    totals = []
    for k, (name, sets) in enumerate(RUNS):
        folder = os.path.join(out, "run%d" % k)
        summary = run(igabde, folder, sets)
        deviations = []
        for step in range(1, STEPS + 1):
            with open(os.path.join(folder, "contact-%04d.csv" % step)) as f:
                rows = list(csv.DictReader(f))
            P = sum(float(r["p_n"]) for r in rows)
            top = max(rows, key=lambda r: float(r["pressure"]))
            a = math.sqrt(4. * P * R / (math.pi * E_STAR))
            p0 = 2. * P / (math.pi * a)
            deviation = float(top["pressure"]) / p0 - 1.
            deviations.append(deviation)
            iterations = summary["load_steps"][step - 1]["newton_iterations"]
            print("| %s | %d | %.2f | %.4f | %.4f | %.4f | %+.3f %% | %.3f | "
                  "%s |" % (name, step, -1.6 + 0.32 * (step - 1), P,
                            float(top["pressure"]), p0, 100. * deviation,
                            float(top["x"]), iterations))
        totals.append((name, summary["n_dofs"], summary["timing"]["total"],
                       min(deviations), max(deviations)))
    print()
    print("| run | unknowns | seconds | peak / p0 - 1, lowest | highest |")
    print("|---|---|---|---|---|")
    for name, dofs, seconds, low, high in totals:
        print("| %s | %d | %.1f | %+.3f %% | %+.3f %% |"
              % (name, dofs, seconds, 100. * low, 100. * high))


if __name__ == "__main__":
    main()
