#!/usr/bin/env python3
"""The recovered contact pressure on V5: for NURBS and FE_Q(2) meshes, the
pair pressures p_i = p_n / area and the pressures recovered from the
stress field, -n . sigma(u_h) . n at the pairs, each against a converged
model of the same disc (the pair pressures of NURBS p = 3 on 512 x 128),
with the unknowns and seconds of each run.

usage: recovered_pressure_v5.py IGABDE OUTDIR

Errors (pressure_reference.py): the relative L2 distance from the
reference profile interpolated at the pairs' x, weighted by the tributary
areas, over the pairs with x below twice the reference half-width; and the
largest single-pair deviation over the same pairs, in % of the
reference's peak pressure."""

import json
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pressure_reference import Reference, read_pairs  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__))))
SCENE = os.path.join(ROOT, "prm", "v5-hertz-2d.prm")

REFERENCE = ("reference NURBS p=3 512x128", "nurbs", 3, "512, 128")
RUNS = [("NURBS p=2 64x16 uniform", "nurbs", 2, "64, 16"),
        ("NURBS p=2 128x32", "nurbs", 2, "128, 32"),
        ("NURBS p=2 256x64", "nurbs", 2, "256, 64"),
        ("FE_Q(2) 64x16", "lagrange", 2, "64, 16"),
        ("FE_Q(2) 128x32", "lagrange", 2, "128, 32"),
        ("FE_Q(2) 256x64", "lagrange", 2, "256, 64")]


def folder_of(out, label):
    """The output folder of the run named @p label."""
    return os.path.join(out, "".join(c if c.isalnum() else "_"
                                     for c in label))


def run(igabde, out, label, kind, degree, mesh, settings=()):
    """Runs V5 with the uniform mesh @p mesh (the scene's grading left out)
    and the further --set @p settings; returns
    summary.json and the pairs (x, area, pressure, recovered pressure)
    sorted by x."""
    folder = folder_of(out, label)
    command = [igabde, SCENE, "--quiet",
               "--set", "Discretization/Degree=%d" % degree,
               "--set", "Discretization/Type=" + kind,
               "--set", "Body 1/Subdivisions=" + mesh,
               "--set", "Body 1/Grading=",
               "--set", "Output/Write vtu=false",
               "--set", "Output/Directory=" + folder]
    for setting in settings:
        command += ["--set", setting]
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(folder, "summary.json")) as f:
        summary = json.load(f)
    return summary, read_pairs(folder)


def reference_run(igabde, out):
    """The converged model: its summary, its pairs and its Reference."""
    ref_summary, ref_pairs = run(igabde, out, *REFERENCE)
    return ref_summary, ref_pairs, Reference(ref_pairs)


def main():
    igabde, out = sys.argv[1], sys.argv[2]
    os.makedirs(out, exist_ok=True)
    ref_summary, ref_pairs, reference = reference_run(igabde, out)
    _, ref_recovered = reference.errors(ref_pairs, 3)
    rows = []
    for label, kind, degree, mesh in RUNS:
        summary, pairs = run(igabde, out, label, kind, degree, mesh)
        rows.append((label, summary["n_dofs"], summary["timing"]["total"],
                     reference.errors(pairs, 2),
                     reference.errors(pairs, 3)))
    path = os.path.join(out, "recovered_pressure_v5.md")
    with open(path, "w") as f:
        f.write("| mesh | unknowns | seconds | pair pressure L2 | "
                "pair largest | recovered L2 | recovered largest |\n"
                "|---|---|---|---|---|---|---|\n")
        for label, n, seconds, (l2, big), (rl2, rbig) in rows:
            f.write("| %s | %d | %.2f | %.2f %% | %.2f %% | %.2f %% | "
                    "%.2f %% |\n" % (label, n, seconds, 100. * l2,
                                     100. * big, 100. * rl2, 100. * rbig))
        f.write("\nreference: %d unknowns, %.2f s, last loaded pair at "
                "x = %.4f, peak %.4f; its own recovered pressure's largest "
                "deviation from its pair pressures: %.2f %% of the peak\n"
                % (ref_summary["n_dofs"], ref_summary["timing"]["total"],
                   reference.half_width, reference.peak,
                   100. * ref_recovered))
    print(open(path).read())


if __name__ == "__main__":
    main()
