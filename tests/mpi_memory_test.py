#!/usr/bin/python3
"""What each rank holds: replicated data the same on every rank, divided data
shared out, nothing counted twice.

summary.json's ranks[].held lists, per rank, the bytes of each kind of data
the rank holds (a body's mesh, tables, sparsity pattern, K, vectors,
factorisation; the contact pairs, W, the coupled system's pieces) and
whether the ranks divide it. This test runs B2 (prm/b2-curved-beams.prm,
4 x 8 x 4 knot spans per beam) on the condensed and the full path, once as
one process and once under `mpirun --oversubscribe -np N` (N = 2, 3), and
checks the classification by what it claims:

  - an item marked replicated holds on every one of the N ranks the bytes
    the one process holds for it (within 2 % and 64 KiB: the same data
    structures of the same sizes; a vector's capacity may differ by its
    growth). An item that one rank holds and another does not, marked
    replicated, fails here;
  - an item marked divided holds, summed over the N ranks, at most 1.3 times
    the one-process bytes plus 1 MiB (a share of a factor with the same
    pivot order, or a body factorised by its own ranks; MUMPS' workspace per
    rank adds a little). Data that every rank holds whole, marked divided,
    sum to N times the one-process bytes and fail here for N >= 2;
    A factorisation counts its factor (MUMPS' INFO(9) and INFO(10)), not
    its workspace, which grows per rank at small sizes;
  - every rank's counted bytes are at most its peak memory (a unit slip
    between bytes and MiB fails here).

Exit status 77 (ctest SKIP_RETURN_CODE) when mpirun is missing.

Usage: tests/mpi_memory_test.py IGABDE [N,...]"""

import json
import os
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENE = os.path.join(ROOT, "prm", "b2-curved-beams.prm")
MIB = 1024.0 * 1024.0

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)


def run(igabde, folder, path, ranks):
    command = [igabde, SCENE, "--quiet",
               "--set", "Body 1/Subdivisions=4,8,4",
               "--set", "Body 2/Subdivisions=4,8,4",
               "--set", "Contact/Path=%s" % path,
               "--set", "Output/Write vtu=false",
               "--set", "Output/Directory=%s" % folder]
    # As root too (CI runs as root); no inherited Open MPI job variables.
    env = {k: v for k, v in os.environ.items()
           if not k.startswith(("OMPI_", "PMIX_", "OPAL_"))}
    env["OMPI_ALLOW_RUN_AS_ROOT"] = "1"
    env["OMPI_ALLOW_RUN_AS_ROOT_CONFIRM"] = "1"
    if ranks > 1:
        command = ["mpirun", "--oversubscribe", "-np", str(ranks)] + command
    result = subprocess.run(command, stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True, env=env,
                            timeout=600)
    if result.returncode != 0:
        print(result.stdout)
        sys.exit("mpi_memory_test: the %s path on %d rank(s) failed with "
                 "status %d" % (path, ranks, result.returncode))
    with open(os.path.join(folder, "summary.json")) as f:
        return json.load(f)["ranks"]


def items_of(rank):
    return {item["name"]: item for item in rank["held"]["items"]}


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    igabde = os.path.abspath(sys.argv[1])
    counts = [int(n) for n in (sys.argv[2] if len(sys.argv) > 2
                               else "2,3").split(",")]
    if shutil.which("mpirun") is None:
        print("mpi_memory_test: skipped: mpirun not found")
        sys.exit(77)
    scratch = tempfile.mkdtemp(prefix="igabde-mpi-memory-")
    try:
        for path in ("condensed", "full"):
            one = run(igabde, os.path.join(scratch, path + "-1"), path, 1)
            check(len(one) == 1, "%s: one process gave %d rank records"
                  % (path, len(one)))
            reference = items_of(one[0])
            check(len(reference) > 0, "%s: no held items" % path)
            for n in counts:
                ranks = run(igabde, os.path.join(scratch, "%s-%d" % (path, n)),
                            path, n)
                check(len(ranks) == n, "%s, %d ranks: %d rank records"
                      % (path, n, len(ranks)))
                per_rank = [items_of(r) for r in ranks]
                for name, ref in reference.items():
                    held = [r.get(name) for r in per_rank]
                    if any(h is None for h in held):
                        failures.append("%s, %d ranks: '%s' missing on a rank"
                                        % (path, n, name))
                        continue
                    divided = {h["divided"] for h in held}
                    check(len(divided) == 1,
                          "%s, %d ranks: '%s' marked divided on some ranks "
                          "and replicated on others" % (path, n, name))
                    ref_bytes = ref["mib"] * MIB
                    if True in divided:
                        total = sum(h["mib"] for h in held) * MIB
                        check(total <= 1.3 * ref_bytes + MIB,
                              "%s, %d ranks: '%s' is marked divided but the "
                              "ranks hold %.3f MiB between them against %.3f "
                              "MiB in one process" % (path, n, name,
                                                      total / MIB,
                                                      ref_bytes / MIB))
                    else:
                        for r, h in enumerate(held):
                            diff = abs(h["mib"] * MIB - ref_bytes)
                            check(diff <= 0.02 * ref_bytes + 64 * 1024,
                                  "%s, %d ranks: '%s' is marked replicated "
                                  "but rank %d holds %.3f MiB against %.3f "
                                  "MiB in one process" % (path, n, name, r,
                                                          h["mib"],
                                                          ref["mib"]))
                for r, rank in enumerate(ranks):
                    counted = (rank["held"]["replicated_mib"] +
                               rank["held"]["divided_mib"])
                    check(counted <= rank["peak_memory_mib"],
                          "%s, %d ranks: rank %d counts %.1f MiB, above its "
                          "peak %.1f MiB" % (path, n, r, counted,
                                             rank["peak_memory_mib"]))
                print("mpi_memory_test: %s path, %d ranks: replicated %s MiB, "
                      "divided %s MiB per rank (one process: %.1f and %.1f)"
                      % (path, n,
                         "/".join("%.1f" % r["held"]["replicated_mib"]
                                  for r in ranks),
                         "/".join("%.1f" % r["held"]["divided_mib"]
                                  for r in ranks),
                         one[0]["held"]["replicated_mib"],
                         one[0]["held"]["divided_mib"]))
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
    for f in failures:
        print("mpi_memory_test: " + f)
    if failures:
        sys.exit(1)
    print("mpi_memory_test: passed")


if __name__ == "__main__":
    main()
