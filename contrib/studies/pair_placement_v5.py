#!/usr/bin/env python3
"""Where the pairs sit, on V5: Greville images, knot points and Gauss
points (node-to-surface), and weighted-gap pairs, for NURBS p = 2 and 3 on
the scene's 64 x 16 mesh and on 128 x 32, each against the converged model
of recovered_pressure_v5.py (pair pressures of NURBS p = 3 on 512 x 128,
Greville), with the pairs, unknowns and seconds of each run.

usage: pair_placement_v5.py IGABDE OUTDIR

Errors as in pressure_reference.py (area-weighted relative L2 over x
below twice the reference half-width, largest single-pair deviation in %
of the reference peak), of the pair pressures p_n / area."""

import json
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from recovered_pressure_v5 import (folder_of, reference_run,  # noqa: E402
                                   run)

PLACEMENTS = [("Greville", ["Contact/Pairing=node-to-surface",
                            "Contact/Pair placement=greville"]),
              ("knots", ["Contact/Pairing=node-to-surface",
                         "Contact/Pair placement=knots"]),
              ("Gauss", ["Contact/Pairing=node-to-surface",
                         "Contact/Pair placement=gauss"]),
              ("weighted gap", ["Contact/Pairing=weighted-gap",
                                "Contact/Pair placement=greville"])]


def failure_reason(error):
    """A table cell for a run that failed, from its summary.json error."""
    return ("Newton matrix singular: redundant pairs" if "singular" in error
            else "see its summary.json")


def write_table(path, rows, footer=""):
    """The placement table: rows (label, pairs, unknowns, seconds, L2,
    largest), with L2 None and the error in place of largest for a run that
    failed."""
    with open(path, "w") as f:
        f.write("| run | pairs | unknowns | seconds | L2 | largest |\n"
                "|---|---|---|---|---|---|\n")
        for label, n_pairs, n, seconds, l2, largest in rows:
            if l2 is None:
                f.write("| %s | %d | %d | | did not converge | %s |\n"
                        % (label, n_pairs, n, failure_reason(largest)))
                continue
            f.write("| %s | %d | %d | %.2f | %.2f %% | %.2f %% |\n"
                    % (label, n_pairs, n, seconds, 100. * l2,
                       100. * largest))
        f.write(footer)


def main():
    igabde, out = sys.argv[1], sys.argv[2]
    os.makedirs(out, exist_ok=True)
    _, _, reference = reference_run(igabde, out)
    rows = []
    for degree in (2, 3):
        for mesh in ("64, 16", "128, 32"):
            for name, settings in PLACEMENTS:
                label = "NURBS p=%d %s %s" % (degree,
                                               mesh.replace(", ", "x"), name)
                try:
                    summary, pairs = run(igabde, out, label, "nurbs",
                                         degree, mesh, settings)
                except subprocess.CalledProcessError:
                    # A run that fails keeps its summary.json: say why.
                    with open(os.path.join(folder_of(out, label),
                                           "summary.json")) as f:
                        failed = json.load(f)
                    rows.append((label, failed.get("n_contact_pairs", 0),
                                 failed.get("n_dofs", 0), None, None,
                                 failed.get("error", "failed")))
                    continue
                l2, largest = reference.errors(pairs, 2)
                rows.append((label, len(pairs), summary["n_dofs"],
                             summary["timing"]["total"], l2, largest))
    path = os.path.join(out, "pair_placement_v5.md")
    write_table(path, rows)
    print(open(path).read())


if __name__ == "__main__":
    main()
