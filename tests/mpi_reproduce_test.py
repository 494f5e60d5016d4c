#!/usr/bin/python3
"""igabde under mpirun gives the one-process answer.

Runs scenes of prm/ once as a single process and once with
`mpirun --oversubscribe -np N` for each N asked (N ranks on the machine's
cores), each into a scratch folder removed afterwards, and compares each
N's summary.json with the one-process one using
contrib/utilities/compare-summaries at 1e-10 relative: every physical
figure (displacements, contact forces, pressures, gaps, probe values,
errors) must agree; timings, iteration counts and the process layout are
not compared, nor the bookkeeping that moves with the thread count even in
one process (BOOKKEEPING below).

Why 1e-10 and not equality: with N ranks MUMPS factorises each body on its
group of ranks, in another order of floating-point operations, so the Schur
complements differ from the one-process ones by round-off (1e-15 relative
times the growth of the factorisation); the contact solution is the root of
the same semismooth equations, converged to the same tolerance, and moves by
round-off times the problem's condition, far below 1e-10 for these scenes.
The same ranks also assert what the run reports of itself: summary.json's
mpi_ranks is N and its ranks list names which bodies each rank factorised
(with two bodies and N >= 2 no rank factorises both).

The full path with GMRES and AMG (path "gmres-amg" below) runs on the N
ranks with the matrix and the AMG distributed among them, so its Krylov
iterations differ from one process's (another aggregation); it is compared
with the one-process run of the direct solver (MUMPS) instead, at 1e-8,
both with Contact/Tolerance = 1e-12: both Newton iterations stop on that
test, the GMRES one with each linear solve to 1e-2 min(1, |F_k|/|F_0|) of
the Newton residual, which is the agreement the one-process test of GMRES
against MUMPS asks (FullSystem.KrylovAgreesWithTheDirectSolver; at a
scene's own, looser tolerance two converged answers may differ by more in a
single small pair's pressure). The largest pair deviation from Hertz, the
pressure uniformity and the largest slide are themselves differences or
ratios in units of a scale: they are compared absolutely, at the same
1e-8.

Usage: tests/mpi_reproduce_test.py IGABDE N[,N...] [--all] [--paths P,...]
                                   [--skip SCENE:DISC:PATH]...
                                   [--only SCENE:DISC:PATH]...
  --all: every scene of prm/ with both discretisations and the three
         paths (condensed, full, gmres-amg; minutes); without it a set that
         covers one and two bodies, 2D and 3D, friction with load steps,
         the paths, both discretisations and a geometry file.
  --paths: only these paths (e.g. condensed,full).
  --skip: leave out one case (repeatable).
  --only: run only this case (repeatable).
Several rank counts (e.g. 2,3) share each case's one-process run.
"""

import json
import os
import shutil
import subprocess
import sys
import tempfile

SOURCE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
COMPARE = os.path.join(SOURCE, "contrib", "utilities", "compare-summaries")

# (scene, discretisation, path)
QUICK = [
    ("v3-contact-patch-2d", "nurbs", "condensed"),
    ("v3-contact-patch-2d", "lagrange", "full"),
    ("v4-sliding-block", "lagrange", "condensed"),
    ("v5-hertz-2d", "nurbs", "condensed"),
    ("b1-cantilever-beams", "nurbs", "condensed"),
    ("v6-cylinder-on-block", "nurbs", "full"),
    # GMRES with AMG on the distributed Newton matrix, one and two bodies.
    ("v6-cylinder-on-block", "nurbs", "gmres-amg"),
    ("b2-curved-beams", "lagrange", "gmres-amg"),
    # A geometry file read by every rank (relative to the scene's folder).
    ("v7-sphere-on-block", "nurbs", "condensed"),
    # Three bodies: fewer ranks than bodies (one rank each, round robin)
    # and more; a body held between two contacts.
    ("three-block-stack", "nurbs", "full"),
    ("roller-between-plates", "nurbs", "condensed"),
]


# Bookkeeping that moves with the thread count even in one process (each
# rank runs on its share of the cores): a Lagrange pair weight that comes
# out 0 with one thread and 1e-17 with two moves one unknown into the Schur
# interface, and with it MUMPS' factor size and flop count, the path-cost
# inputs and estimates; the coupled matrix's count of exact zeros moves by
# round-off. None of them is a physical figure.
BOOKKEEPING = ["--ignore", "factor_entries",
               "--ignore", "factorization_flops",
               "--ignore", "contact_path_cost_inputs",
               "--ignore", "contact_path_estimated_seconds",
               "--ignore", "contact_path_reason",
               "--ignore", "coupled_matrix_nonzeros"]


# Scenes whose loads are self-equilibrated without contact: every body force
# of a step (the support reactions) is zero in exact arithmetic, and the
# figures compared are round-off (1e-15); compare-summaries judges them
# against the force the loads are made of. The Lame ring: pressure 1 on the
# unit inner radius.
FORCE_SCALE = {"v2-lame-ring": 1.0}


def every_scene():
    scenes = sorted(f[:-4] for f in os.listdir(os.path.join(SOURCE, "prm"))
                    if f.endswith(".prm"))
    return [(s, d, p) for s in scenes for d in ("nurbs", "lagrange")
            for p in ("condensed", "full", "gmres-amg")]


def mpirun_command(n):
    # As root too (CI runs as root); no inherited Open MPI job variables.
    env = {k: v for k, v in os.environ.items()
           if not k.startswith(("OMPI_", "PMIX_", "OPAL_"))}
    env["OMPI_ALLOW_RUN_AS_ROOT"] = "1"
    env["OMPI_ALLOW_RUN_AS_ROOT_CONFIRM"] = "1"
    return ["mpirun", "--oversubscribe", "-np", str(n)], env


# The one-process reference of a GMRES run: the direct solver, at 1e-8.
KRYLOV_COMPARISON = ["--rtol", "1e-8",
                     "--absolute", "hertz_max_pair_deviation=1e-8",
                     "--absolute", "pressure_uniformity=1e-8",
                     "--absolute", "largest_sliding=1e-8",
                     "--ignore", "size_estimate",
                     "--ignore", "full_system_solver"]


def run(command, env, scene, disc, path, out, extra=()):
    solver = ["--set", "Contact/Full system solver=gmres-amg"] \
        if path == "gmres-amg" else []
    solver += list(extra)
    args = command + [
        os.path.join(SOURCE, "prm", scene + ".prm"), "--quiet",
        "--set", f"Discretization/Type={disc}",
        "--set", f"Contact/Path={'full' if path == 'gmres-amg' else path}",
    ] + solver + [
        "--set", f"Output/Directory={out}",
        "--set", "Output/Write vtu=false"]
    r = subprocess.run(args, env=env, stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, text=True, timeout=900)
    return r.returncode, r.stdout


def main():
    if len(sys.argv) < 3:
        print(__doc__)
        return 2
    igabde = sys.argv[1]
    rank_counts = [int(n) for n in sys.argv[2].split(",")]
    options = sys.argv[3:]
    cases = every_scene() if "--all" in options else QUICK
    for k, option in enumerate(options[:-1]):
        if option == "--paths":
            keep = options[k + 1].split(",")
            cases = [c for c in cases if c[2] in keep]
        if option == "--skip":
            cases = [c for c in cases
                     if ":".join(c) != options[k + 1]]
    only = [options[k + 1] for k, o in enumerate(options[:-1])
            if o == "--only"]
    if only:
        cases = [c for c in cases if ":".join(c) in only]
    if shutil.which("mpirun") is None:
        print("mpirun not found")
        return 77
    _, env = mpirun_command(1)
    failures = 0
    with tempfile.TemporaryDirectory(prefix="igabde-mpi-reproduce-") as tmp:
        for scene, disc, path in cases:
            one = os.path.join(tmp, f"{scene}-{disc}-{path}-1")
            krylov = (path == "gmres-amg")
            tight = ["--set", "Contact/Tolerance=1e-12"] if krylov else []
            status1, log1 = run([igabde], env, scene, disc,
                                "full" if krylov else path, one, tight)
            for n in rank_counts:
                failures += compare(igabde, n, scene, disc, path, tmp, env,
                                    status1, log1, one, tight)
    count = len(cases) * len(rank_counts)
    print(f"{count - failures} of {count} cases agree with "
          f"{' and '.join(str(n) for n in rank_counts)} ranks")
    return 1 if failures else 0


def compare(igabde, n, scene, disc, path, tmp, env, status1, log1, one,
            tight):
    """Runs one case on n ranks and compares it with the one-process run
    in the folder one; returns the number of failures (0 or 1)."""
    name = f"{scene} {disc} {path} on {n} ranks"
    mpirun, _ = mpirun_command(n)
    many = os.path.join(tmp, f"{scene}-{disc}-{path}-{n}")
    krylov = (path == "gmres-amg")
    status_n, log_n = run(mpirun + [igabde], env, scene, disc, path,
                          many, tight)
    if status1 != status_n:
        print(f"FAIL {name}: exit status {status1} with one process, "
              f"{status_n} with {n} ranks\n{log1}\n{log_n}")
        return 1
    if status1 != 0:
        # A scene refused for this combination (e.g. a path the scene does
        # not allow) must be refused alike.
        print(f"both refused {name} (status {status1})")
        return 0
    with open(os.path.join(many, "summary.json")) as f:
        summary = json.load(f)
    layout_ok = summary.get("mpi_ranks") == n and \
        len(summary.get("ranks", [])) == n
    n_bodies = len(summary.get("bodies", []))
    if layout_ok and n_bodies == 2:
        layout_ok = all(len(r["factorises"]) == 1
                        for r in summary["ranks"])
    failures = 0
    if not layout_ok:
        print(f"FAIL {name}: summary.json's mpi_ranks/ranks do not "
              f"describe {n} ranks: {summary.get('mpi_ranks')}, "
              f"{summary.get('ranks')}")
        failures = 1
    c = subprocess.run(
        [sys.executable, COMPARE,
         os.path.join(one, "summary.json"),
         os.path.join(many, "summary.json")] + BOOKKEEPING +
        ["--force-scale", str(FORCE_SCALE.get(scene, 0.0))] +
        (KRYLOV_COMPARISON if krylov else []),
        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    print(f"{'ok  ' if c.returncode == 0 else 'FAIL'} {name}: "
          f"{c.stdout.strip()}", flush=True)
    return max(failures, int(c.returncode != 0))


if __name__ == "__main__":
    sys.exit(main())
