#!/usr/bin/env python3
"""Graded meshes on V5: the pair pressures of the uniform 64 x 16 mesh, of
the scene's graded one and of coarser meshes graded toward the contact
point or a band over the contact zone, each against
a converged model of the same disc (NURBS p = 3 on 512 x 128), with the
unknowns and the seconds of each run.

usage: graded_v5.py IGABDE OUTDIR

The error is the relative L2 distance of the pair pressures p_i from the
reference profile interpolated at the pairs' x, weighted by the pairs'
tributary areas: sqrt(sum a_i (p_i - p_ref(x_i))^2 / sum a_i p_ref(x_i)^2),
over the pairs with x below twice the reference half-width (beyond, both
are zero)."""

import json
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pressure_reference import Reference, read_pairs  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__))))
SCENE = os.path.join(ROOT, "prm", "v5-hertz-2d.prm")

REFERENCE = ("reference NURBS p=3 512x128", 3, "512, 128", "")
RUNS = [("NURBS p=2 64x16 uniform", 2, "64, 16", ""),
        ("NURBS p=2 32x8", 2, "32, 8", ""),
        ("NURBS p=2 24x8", 2, "24, 8", "")]
# Every grading tried (arc spans x depth spans, the ratio toward the
# contact point along the arc and in depth), none left out.
for mesh, ratio, faces in [("32, 8", 4, "02"), ("32, 8", 8, "02"),
                           ("32, 8", 16, "02"), ("32, 12", 16, "02"),
                           ("28, 8", 16, "02"), ("26, 8", 16, "02"),
                           ("24, 6", 8, "02"), ("24, 8", 8, "02"),
                           ("24, 8", 16, "02"), ("24, 8", 32, "02"),
                           ("24, 10", 16, "02"), ("24, 8", 16, "0"),
                           ("20, 8", 16, "02")]:
    RUNS.append(("NURBS p=2 %s graded %d toward face%s %s"
                 % (mesh.replace(", ", "x"), ratio,
                    "s" if len(faces) > 1 else "", " and ".join(faces)),
                 2, mesh, "; ".join("%s: %d" % (f, ratio) for f in faces)))


# Every band grading tried ('band 0: from, to, ratio' along the arc, the
# contact zone's edge near 0.25 of it; 16 toward face 2 in depth).
for mesh, band in [("24, 8", "0, 0.16, 8"), ("24, 8", "0, 0.16, 16"),
                   ("24, 8", "0.08, 0.16, 16"), ("20, 8", "0, 0.16, 16"),
                   ("28, 8", "0, 0.16, 16"), ("32, 8", "0, 0.16, 16"),
                   ("24, 8", "0, 0.2, 16"), ("24, 8", "0, 0.13, 16"),
                   ("24, 8", "0, 0.3, 4"), ("24, 8", "0, 0.3, 8"),
                   ("24, 8", "0.2, 0.3, 8"), ("24, 8", "0.2, 0.3, 16"),
                   ("20, 8", "0, 0.3, 8"), ("28, 8", "0, 0.3, 8"),
                   ("32, 8", "0, 0.3, 8"), ("40, 8", "0, 0.3, 8"),
                   ("32, 8", "0.2, 0.3, 8"), ("40, 8", "0.2, 0.3, 8")]:
    RUNS.append(("NURBS p=2 %s band 0: %s; 2: 16"
                 % (mesh.replace(", ", "x"), band),
                 2, mesh, "band 0: %s; 2: 16" % band))


# The scene's mesh since 2026-11-26 (64 x 16, spans 4 times smaller over the
# first 0.3 of the arc and toward the contact face), its neighbours in span
# count and ratio, each half of it alone, and the same grading for p = 3 and
# FE_Q(2).
SCENE_GRADING = "band 0: 0, 0.3, 4; 2: 4"
for mesh in ["64, 16", "56, 16", "60, 16", "62, 16", "66, 16", "68, 16",
             "72, 16", "64, 12", "48, 12"]:
    RUNS.append(("NURBS p=2 %s %s%s" % (mesh.replace(", ", "x"),
                                        SCENE_GRADING,
                                        " (scene)" if mesh == "64, 16"
                                        else ""),
                 2, mesh, SCENE_GRADING))
for grading in ["band 0: 0, 0.3, 2; 2: 4", "band 0: 0, 0.3, 8; 2: 4",
                "band 0: 0, 0.3, 4", "2: 4"]:
    RUNS.append(("NURBS p=2 64x16 " + grading, 2, "64, 16", grading))
RUNS.append(("NURBS p=3 64x16 " + SCENE_GRADING, 3, "64, 16", SCENE_GRADING))
RUNS.append(("FE_Q(2) 64x16 uniform", 2, "64, 16", "", True))
RUNS.append(("FE_Q(2) 64x16 " + SCENE_GRADING, 2, "64, 16", SCENE_GRADING,
             True))


def run(igabde, out, label, degree, mesh, grading, lagrange=False):
    folder = os.path.join(out, "".join(c if c.isalnum() else "_"
                                       for c in label))
    subprocess.run([igabde, SCENE, "--quiet",
                    "--set", "Discretization/Degree=%d" % degree,
                    "--set", "Discretization/Type=%s" %
                    ("lagrange" if lagrange else "nurbs"),
                    "--set", "Body 1/Subdivisions=" + mesh,
                    "--set", "Body 1/Grading=" + grading,
                    "--set", "Output/Write vtu=false",
                    "--set", "Output/Directory=" + folder],
                   check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(folder, "summary.json")) as f:
        summary = json.load(f)
    return summary, read_pairs(folder)


def main():
    igabde, out = sys.argv[1], sys.argv[2]
    os.makedirs(out, exist_ok=True)
    ref_summary, ref_pairs = run(igabde, out, *REFERENCE)
    reference = Reference(ref_pairs)
    rows = []
    for label, degree, mesh, grading, *lagrange in RUNS:
        summary, pairs = run(igabde, out, label, degree, mesh, grading,
                             *lagrange)
        rows.append((label, summary["n_dofs"], reference.errors(pairs)[0],
                     summary["timing"]["total"]))
    with open(os.path.join(out, "graded_v5.md"), "w") as f:
        f.write("| mesh | unknowns | pressure error vs reference | "
                "seconds |\n|---|---|---|---|\n")
        for label, n, err, seconds in rows:
            f.write("| %s | %d | %.2f %% | %.3f |\n"
                    % (label, n, 100. * err, seconds))
        f.write("\nreference: %d unknowns, %.2f s, last loaded pair at "
                "x = %.4f\n" % (ref_summary["n_dofs"],
                                ref_summary["timing"]["total"],
                                reference.half_width))
    print(open(os.path.join(out, "graded_v5.md")).read())


if __name__ == "__main__":
    main()
