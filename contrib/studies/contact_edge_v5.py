#!/usr/bin/env python3
"""The contact edge on V5: where the pair pressures' error sits, why, and
how it falls with the mesh.

usage: contact_edge_v5.py IGABDE OUTDIR

V5 is run under a sweep of loads (the scene's traction times 1, 1.04, ...,
1.28: Hertz's half-width a grows with the square root of the load, by
about one knot span of the scene's 64 x 16 mesh over the sweep), so that
the edge of the contact zone passes once across the pairs of each mesh.
Every run is measured against a converged model of the same disc under
the same load (the pair pressures of NURBS p = 3 on 512 x 128, as in the
other V5 studies; pressure_reference.py), over two sets of pairs:

- all pairs with |x| <= 2 a_ref (the other studies' measure);
- the interior of the zone, |x| <= 0.8 a_ref, away from the edge.

Per mesh: L2 and largest deviation (in % of the reference's peak) for
both sets, each as its range over the sweep, and where the largest
deviation sits (|x| / a_ref, mean over the sweep). The reference's own
change from one refinement coarser (NURBS p = 3 on 256 x 64) is in the
table too: differences below it mean little."""

import json
import os
import statistics
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pressure_reference import Reference, read_pairs  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__))))
SCENE = os.path.join(ROOT, "prm", "v5-hertz-2d.prm")

TRACTION = 15.  # the scene's: Body 1/Tractions = 3: vector 0, -15
FACTORS = [1. + 0.04 * k for k in range(8)]
INTERIOR = 0.8  # |x| / a_ref below which a pair counts as interior

REFERENCE = ("NURBS p=3 512x128", "nurbs", 3, "512, 128", None)
SELF_CHECK = ("NURBS p=3 256x64", "nurbs", 3, "256, 64", None)
SCENE_GRADING = "band 0: 0, 0.3, 4; 2: 4"
RUNS = [("NURBS p=2 32x8", "nurbs", 2, "32, 8", None),
        ("NURBS p=2 64x16", "nurbs", 2, "64, 16", None),
        ("NURBS p=2 128x32", "nurbs", 2, "128, 32", None),
        ("NURBS p=2 256x64", "nurbs", 2, "256, 64", None),
        ("NURBS p=2 64x16 graded (scene)", "nurbs", 2, "64, 16",
         SCENE_GRADING),
        ("FE_Q(2) 64x16", "lagrange", 2, "64, 16", None),
        ("FE_Q(2) 128x32", "lagrange", 2, "128, 32", None),
        ("FE_Q(2) 64x16 graded (scene)", "lagrange", 2, "64, 16",
         SCENE_GRADING)]


def run(igabde, out, label, kind, degree, mesh, grading, factor):
    """V5 with @p mesh (uniform unless @p grading) under the scene's
    traction times @p factor: summary.json and the pairs."""
    folder = os.path.join(out, "".join(c if c.isalnum() else "_"
                                       for c in label) + "_%.2f" % factor)
    load = TRACTION * factor
    command = [igabde, SCENE, "--quiet",
               "--set", "Discretization/Degree=%d" % degree,
               "--set", "Discretization/Type=" + kind,
               "--set", "Body 1/Subdivisions=" + mesh,
               "--set", "Body 1/Grading=" + (grading or ""),
               "--set", "Body 1/Tractions=3: vector 0, -%.10g" % load,
               "--set", "Checks/Hertz line load=%.10g" % (16. * load),
               "--set", "Output/Write vtu=false",
               "--set", "Output/Directory=" + folder]
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(folder, "summary.json")) as f:
        summary = json.load(f)
    return summary, read_pairs(folder)


def measures(reference, pairs):
    """(L2, largest, |x| of the largest / a_ref) over all pairs with
    |x| <= 2 a_ref, and (L2, largest) over the interior ones."""
    a = reference.half_width
    l2, largest = reference.errors(pairs)
    worst_x, worst = 0., -1.
    for x, _, p, _ in pairs:
        if abs(x) <= 2. * a and abs(p - reference.at(x)) > worst:
            worst, worst_x = abs(p - reference.at(x)), abs(x) / a
    interior = [q for q in pairs if abs(q[0]) <= INTERIOR * a]
    return (l2, largest, worst_x), reference.errors(interior)


def span(values):
    """'lo-hi' of percentages."""
    return "%.2f-%.2f" % (100. * min(values), 100. * max(values))


def main():
    igabde, out = sys.argv[1], sys.argv[2]
    os.makedirs(out, exist_ok=True)
    references = []
    for factor in FACTORS:
        summary, pairs = run(igabde, out, *REFERENCE, factor)
        references.append((summary, Reference(pairs)))
        print("reference at %.2f x load: a_ref %.4f, %.1f s" %
              (factor, references[-1][1].half_width,
               summary["timing"]["total"]), flush=True)
    rows = []
    for spec in [SELF_CHECK] + RUNS:
        results = []
        for factor, (_, reference) in zip(FACTORS, references):
            summary, pairs = run(igabde, out, *spec, factor)
            results.append((summary, measures(reference, pairs)))
        rows.append((spec[0], results))
        print(spec[0], "done", flush=True)
    path = os.path.join(out, "contact_edge_v5.md")
    with open(path, "w") as f:
        f.write("| mesh | unknowns | seconds | L2 | largest | largest at "
                "\\|x\\|/a | interior L2 | interior largest |\n"
                "|---|---|---|---|---|---|---|---|\n")
        for label, results in rows:
            f.write("| %s | %d | %.3f | %s %% | %s %% | %.2f | %s %% | "
                    "%s %% |\n" % (
                        label, results[0][0]["n_dofs"],
                        statistics.median(s["timing"]["total"]
                                          for s, _ in results),
                        span([m[0][0] for _, m in results]),
                        span([m[0][1] for _, m in results]),
                        statistics.mean(m[0][2] for _, m in results),
                        span([m[1][0] for _, m in results]),
                        span([m[1][1] for _, m in results])))
        f.write("\nL2 / largest (%) under each load:\n\n| mesh | " +
                " | ".join("%.2f x" % k for k in FACTORS) + " |\n|---|" +
                "---|" * len(FACTORS) + "\n")
        for label, results in rows:
            f.write("| %s | " % label + " | ".join(
                "%.2f / %.2f" % (100. * m[0][0], 100. * m[0][1])
                for _, m in results) + " |\n")
        f.write("\nloads: the scene's traction times %s; reference half-"
                "widths %.4f to %.4f (%d unknowns, %.1f s each)\n" % (
                    ", ".join("%.2f" % k for k in FACTORS),
                    references[0][1].half_width,
                    references[-1][1].half_width,
                    references[0][0]["n_dofs"],
                    statistics.median(s["timing"]["total"]
                                      for s, _ in references)))
    print(open(path).read())


if __name__ == "__main__":
    main()
