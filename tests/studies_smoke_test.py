#!/usr/bin/python3
"""Smoke test of one study driver (contrib/studies/run STUDY --quick): runs it
into a scratch folder that is removed afterwards, and checks that its CSV,
Markdown and PNG/SVG files exist, that the CSV has the columns below (kept
here, apart from the driver, so that a column the driver stops writing is
caught), that every run converged on these coarse meshes, and the figures
that have a closed form.

Usage: tests/studies_smoke_test.py IGABDE STUDY"""

import csv
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

PHASES = ["t_assembly_s", "t_factorization_s", "t_pairs_s",
          "t_condensation_s", "t_bnewton_s", "t_coupled_system_s",
          "t_fullsystem_solve_s", "t_fields_s", "t_output_s",
          "t_postprocess_s", "t_other_s"]

# study -> (files without extension, {csv file: columns}, status columns,
# columns that must hold a value in every row)
EXPECTED = {
    "b2-dofs": (
        ["b2-dofs"],
        {"b2-dofs.csv": ["mesh", "elements_per_beam", "elements",
                         "nurbs_p2_dofs", "fe_q2_dofs", "serendipity20_dofs",
                         "fe_q2_over_nurbs", "serendipity20_over_nurbs",
                         "nurbs_status", "fe_q2_status"]},
        ["nurbs_status", "fe_q2_status"],
        ["nurbs_p2_dofs", "fe_q2_dofs", "serendipity20_dofs", "elements"]),
    "b2-displacements": (
        ["b2-displacements"],
        {"b2-displacements.csv":
         ["config", "discretization", "degree", "algorithm", "mesh",
          "n_dofs", "status", "diagnosis", "uz_A", "uz_B", "uz_C", "uz_D",
          "rel_diff_A", "rel_diff_B", "rel_diff_C", "rel_diff_D",
          "max_rel_diff", "newton_iterations", "total_s", "process_s"]},
        ["status"],
        ["n_dofs", "uz_A", "uz_B", "uz_C", "uz_D", "max_rel_diff",
         "total_s"]),
    "b2-mesh4": (
        ["b2-mesh4"],
        {"b2-mesh4.csv":
         ["discretization", "method", "mesh", "n_dofs", "n_contact_pairs",
          "status", "converged", "newton_iterations", "contact_solves",
          "step_cuts", "contact_s", "total_s", "process_s"] + PHASES +
         ["max_penetration", "uz_C", "rel_diff_uz_C", "diagnosis"]},
        ["status"],
        ["n_dofs", "newton_iterations", "contact_s", "total_s",
         "rel_diff_uz_C"]),
    "b1-forces": (
        ["b1-forces"],
        {"b1-forces.csv":
         ["mu", "config", "discretization", "algorithm", "mesh", "n_dofs",
          "n_contact_pairs", "status", "newton_iterations",
          "contact_force_x", "contact_force_y", "contact_force_z",
          "rel_diff_x", "rel_diff_y", "rel_diff_z", "rel_diff_norm",
          "max_penetration", "contact_s", "total_s", "process_s",
          "diagnosis"]},
        ["status"],
        ["n_dofs", "contact_force_x", "contact_force_y", "contact_force_z",
         "rel_diff_norm"]),
    "accuracy-cost": (
        ["accuracy-cost", "accuracy-cost-phases"],
        {"accuracy-cost.csv":
         ["scene", "discretisation", "method", "config", "mesh", "n_dofs",
          "n_contact_pairs", "status", "error", "pareto",
          "newton_iterations", "contact_s", "total_s", "process_s"] +
         PHASES + ["diagnosis"]},
        ["status"],
        ["n_dofs", "error", "total_s"]),
}


def serendipity(nr, nt, ny):
    """By hand: vertices plus edge midpoints of a structured hex mesh."""
    v = (nr + 1) * (nt + 1) * (ny + 1)
    e = nr * (nt + 1) * (ny + 1) + (nr + 1) * nt * (ny + 1) + \
        (nr + 1) * (nt + 1) * ny
    return 3 * (v + e)


def main():
    igabde, study = sys.argv[1], sys.argv[2]
    files, csvs, status_columns, filled = EXPECTED[study]
    failures = []
    with tempfile.TemporaryDirectory(prefix="igabde-studies-") as out:
        proc = subprocess.run(
            [os.path.join(ROOT, "contrib", "studies", "run"), study,
             "--quick", "--igabde", igabde, "--out", out],
            capture_output=True, text=True)
        sys.stdout.write(proc.stdout)
        if proc.returncode != 0:
            sys.stdout.write(proc.stderr)
            failures.append("the driver exited with %d" % proc.returncode)
        for name in files:
            for ext in ("png", "svg", "md"):
                if name == "accuracy-cost-phases" and ext == "md":
                    continue
                if not os.path.isfile(os.path.join(out, name + "." + ext)):
                    failures.append("missing %s.%s" % (name, ext))
        for name, columns in csvs.items():
            path = os.path.join(out, name)
            if not os.path.isfile(path):
                failures.append("missing " + name)
                continue
            with open(path) as f:
                reader = csv.DictReader(f)
                header = reader.fieldnames or []
                rows = list(reader)
            missing = [c for c in columns if c not in header]
            if missing:
                failures.append("%s lacks columns %s" % (name, missing))
            if not rows:
                failures.append(name + " has no rows")
            for i, r in enumerate(rows):
                for c in status_columns:
                    if r.get(c) != "ok":
                        failures.append("%s row %d: %s = %r (%s)" % (
                            name, i + 1, c, r.get(c), r.get("diagnosis")))
                for c in filled:
                    if r.get(c, "") == "":
                        failures.append("%s row %d: no %s" % (name, i + 1,
                                                              c))
            if study == "b2-dofs":
                # One patch per beam: (n + p)^3 control points for NURBS,
                # (2n + 1)^3 nodes for FE_Q(2), two beams of 3 components.
                for r in rows:
                    n = [int(x) for x in r["mesh"].split("x")]
                    want = {"nurbs_p2_dofs": 6 * (n[0] + 2) * (n[1] + 2) *
                            (n[2] + 2),
                            "fe_q2_dofs": 6 * (2 * n[0] + 1) *
                            (2 * n[1] + 1) * (2 * n[2] + 1),
                            "serendipity20_dofs": 2 * serendipity(*n)}
                    for c, v in want.items():
                        if r.get(c) != str(v):
                            failures.append("b2-dofs %s: %s = %s, by hand "
                                            "%d" % (r["mesh"], c, r.get(c),
                                                    v))
    for f in failures:
        print("FAILED: " + f)
    print("%s: %s" % (study, "passed" if not failures else
                      "%d failures" % len(failures)))
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
