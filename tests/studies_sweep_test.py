#!/usr/bin/python3
"""Test of the general study driver with igabde (contrib/studies/run
sweep): a tiny sweep of V5 (NURBS p = 2 and FE_Q(2) on three coarse
meshes, about 3 s) into a scratch folder that is removed afterwards. Checks
the files, the CSV columns (kept here, apart from the driver), that every
run converged, that against the finest run the finest row's error is
exactly 0 (and it is marked as the reference, off the Pareto front) while
every other row's is positive, that a Richardson reference gives one entry
per series and quantity, and that bad input stops with one line and exit
status 2 before any run, or after the first run for a summary.json path
that is not there.

Usage: tests/studies_sweep_test.py IGABDE"""

import csv
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RUN = os.path.join(ROOT, "contrib", "studies", "run")
V5 = os.path.join(ROOT, "prm", "v5-hertz-2d.prm")

SWEEP = ["--sweep", "Type+Degree=nurbs+2,lagrange+2",
         "--sweep", "Subdivisions=16,4 | 32,8 | 64,16",
         "--set", "Body 1/Grading="]

COLUMNS = ["series", "Type", "Degree", "Subdivisions", "n_dofs",
           "n_elements", "status", "p0", "p0_reference", "p0_error",
           "a", "a_reference", "a_error", "pressure-profile",
           "pressure-profile_error", "largest_deviation", "vs_Johnson",
           "error", "pareto", "newton_iterations", "contact_s", "total_s",
           "process_s", "t_assembly_s", "t_factorization_s", "t_pairs_s",
           "t_condensation_s", "t_bnewton_s", "peak_memory_mib", "label",
           "diagnosis"]

failures = []


def run(igabde, out, extra):
    proc = subprocess.run([RUN, "sweep", V5, "--igabde", igabde, "--out",
                           out] + extra, capture_output=True, text=True)
    sys.stdout.write(proc.stdout)
    return proc


def read(path):
    with open(path) as f:
        reader = csv.DictReader(f)
        return reader.fieldnames or [], list(reader)


def main():
    igabde = sys.argv[1]
    with tempfile.TemporaryDirectory(prefix="igabde-sweep-") as tmp:
        # 1. Against the finest run.
        out = os.path.join(tmp, "finest")
        proc = run(igabde, out, SWEEP + [
            "--quantity", "checks.hertz_peak_pressure=p0",
            "--quantity", "checks.hertz_half_width_moment=a",
            "--quantity", "pressure-profile",
            "--show", "checks.pressure_l2_rel_error=vs_Johnson",
            "--name", "v5"])
        if proc.returncode != 0:
            failures.append("finest sweep exited with %d: %s" % (
                proc.returncode, proc.stderr.strip()))
        for ext in ("csv", "md", "png", "svg"):
            if not os.path.isfile(os.path.join(out, "v5." + ext)):
                failures.append("missing v5." + ext)
        if os.path.isfile(os.path.join(out, "v5.csv")):
            header, rows = read(os.path.join(out, "v5.csv"))
            missing = [c for c in COLUMNS if c not in header]
            if missing:
                failures.append("v5.csv lacks columns %s" % missing)
            if len(rows) != 6:
                failures.append("v5.csv has %d rows, not 6" % len(rows))
            for r in rows:
                if r.get("status") != "ok":
                    failures.append("%s: %s (%s)" % (r.get("label"),
                                                     r.get("status"),
                                                     r.get("diagnosis")))
                for c in ("n_dofs", "total_s", "peak_memory_mib",
                          "t_assembly_s", "error"):
                    if r.get(c, "") == "":
                        failures.append("%s: no %s" % (r.get("label"), c))
            if rows and not missing:
                finest = max(rows, key=lambda r: int(r["n_dofs"] or 0))
                if finest["Type"] != "lagrange" or \
                        finest["Subdivisions"] != "64,16":
                    failures.append("the finest run is %s" % finest["label"])
                for c in ("error", "p0_error", "a_error",
                          "pressure-profile_error"):
                    if finest[c] != "0.0":
                        failures.append("finest row: %s = %r, not 0" % (
                            c, finest[c]))
                if finest["pareto"] != "reference":
                    failures.append("finest row: pareto = %r" %
                                    finest["pareto"])
                for r in rows:
                    if r is not finest and not (r["error"] and
                                                float(r["error"]) > 0.):
                        failures.append("%s: error %r" % (r["label"],
                                                          r["error"]))
                if not any(r["pareto"] == "yes" for r in rows):
                    failures.append("no run on the Pareto front")
        md = os.path.join(out, "v5.md")
        if os.path.isfile(md):
            with open(md) as f:
                text = f.read()
            for word in ("| Type | Degree | Subdivisions | unknowns |",
                         "peak MiB", "Reference: the finest run"):
                if word not in text:
                    failures.append("v5.md lacks %r" % word)

        # 2. Richardson: one entry per series and quantity, each with a
        # limit and order or the reason there is none.
        out = os.path.join(tmp, "richardson")
        proc = run(igabde, out, SWEEP + [
            "--quantity", "checks.hertz_half_width_moment=a",
            "--reference", "richardson", "--name", "v5"])
        if proc.returncode != 0:
            failures.append("Richardson sweep exited with %d: %s" % (
                proc.returncode, proc.stderr.strip()))
        md = os.path.join(out, "v5.md")
        if os.path.isfile(md):
            with open(md) as f:
                lines = [l for l in f if l.startswith("| Type=")]
            if len(lines) != 2:
                failures.append("Richardson table: %d series rows, not 2" %
                                len(lines))
            for l in lines:
                cells = [c.strip() for c in l.strip().strip("|").split("|")]
                if cells[3] == "–" and not cells[4].startswith("none: "):
                    failures.append("Richardson row without limit or "
                                    "reason: " + l.strip())
        else:
            failures.append("no v5.md from the Richardson sweep")

        # 3. Bad input: one line on stderr, exit status 2, no run.
        for extra, word in (
                (["--sweep", "Type=iga", "--quantity", "checks.x"],
                 "nurbs, lagrange"),
                (["--sweep", "Type=nurbs", "--quantity", "checks.x",
                  "--reference", "richardson"], "mesh sweep"),
                (["--reference", "finest"], "--quantity"),
                (["--sweep", "Subdivisions=16,4", "--quantity",
                  "checks.x"], "separate the values with '|'"),
                (["--sweep", "Subdivisions=16,4|", "--quantity",
                  "checks.no_such_check"], "checks.no_such_check")):
            out = os.path.join(tmp, "bad")
            proc = run(igabde, out, extra)
            lines = proc.stderr.strip().splitlines()
            if proc.returncode != 2 or len(lines) != 1 or \
                    word not in proc.stderr:
                failures.append("%s: exit %d, stderr %r (want status 2 "
                                "and one line naming %r)" % (
                                    " ".join(extra), proc.returncode,
                                    proc.stderr, word))
            runs = proc.stdout.count(": run ")
            if runs > ("no_such" in word):
                failures.append("%s: %d runs before the error" % (
                    " ".join(extra), runs))
    for f in failures:
        print("FAILED: " + f)
    print("studies sweep: %s" % ("passed" if not failures else
                                 "%d failures" % len(failures)))
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
