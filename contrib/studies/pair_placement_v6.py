#!/usr/bin/env python3
"""Where the pairs sit, on V6 (an elastic half disc on an elastic block,
mu = 0.5): node-to-surface pairs at the Greville images, at the knot points
or at the Gauss points of the disc's face, and weighted-gap pairs (the
scene's), for NURBS p = 2 and 3 on the scene's meshes (disc 116 x 16, block
140 x 32) and on twice their spans, each against a converged model of the
same scene (the pair pressures of NURBS p = 3 weighted-gap at four times the
scene's spans, the accuracy-cost study's reference), with the pairs,
unknowns and seconds of each run.

usage: pair_placement_v6.py IGABDE OUTDIR

Errors as in pressure_reference.py (area-weighted relative L2 over |x|
below twice the reference half-width, largest single-pair deviation in %
of the reference peak), of the pair pressures p_n / area."""

import json
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pair_placement_v5 import PLACEMENTS, write_table  # noqa: E402
from pressure_reference import Reference, read_pairs  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__))))
SCENE = os.path.join(ROOT, "prm", "v6-cylinder-on-block.prm")

def meshes(scale):
    """--set values of the disc's and the block's spans at @p scale of the
    scene's."""
    return ("%d, %d" % (116 * scale, 16 * scale),
            "%d, %d" % (140 * scale, 32 * scale))


def run(igabde, out, label, degree, scale, settings):
    """Runs V6; returns (summary.json, pairs) or (summary.json, None) when
    the run failed."""
    folder = os.path.join(out, "".join(c if c.isalnum() else "_"
                                       for c in label))
    disc, block = meshes(scale)
    command = [igabde, SCENE, "--quiet",
               "--set", "Discretization/Degree=%d" % degree,
               "--set", "Body 1/Subdivisions=" + disc,
               "--set", "Body 2/Subdivisions=" + block,
               "--set", "Output/Write vtu=false",
               "--set", "Output/Directory=" + folder]
    for setting in settings:
        command += ["--set", setting]
    status = subprocess.run(command, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL).returncode
    with open(os.path.join(folder, "summary.json")) as f:
        summary = json.load(f)
    return summary, (read_pairs(folder) if status == 0 else None)


def main():
    igabde, out = sys.argv[1], sys.argv[2]
    os.makedirs(out, exist_ok=True)
    ref_summary, ref_pairs = run(igabde, out, "reference NURBS p=3 x4", 3, 4,
                                 PLACEMENTS[3][1])
    reference = Reference(ref_pairs)
    rows = []
    for degree in (2, 3):
        for scale in (1, 2):
            for name, settings in PLACEMENTS:
                disc, block = meshes(scale)
                label = "NURBS p=%d %s+%s %s" % (
                    degree, disc.replace(", ", "x"),
                    block.replace(", ", "x"), name)
                summary, pairs = run(igabde, out, label, degree, scale,
                                     settings)
                if pairs is None:
                    rows.append((label, summary.get("n_contact_pairs", 0),
                                 summary.get("n_dofs", 0), None, None,
                                 summary.get("error", "failed")))
                    continue
                l2, largest = reference.errors(pairs)
                rows.append((label, len(pairs), summary["n_dofs"],
                             summary["timing"]["total"], l2, largest))
    path = os.path.join(out, "pair_placement_v6.md")
    write_table(path, rows,
                "\nreference: %d unknowns, %.2f s, half-width %.4f\n"
                % (ref_summary["n_dofs"], ref_summary["timing"]["total"],
                   reference.half_width))
    print(open(path).read())


if __name__ == "__main__":
    main()
