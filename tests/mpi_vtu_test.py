#!/usr/bin/python3
"""Parallel VTU output: each rank writes its piece, the pieces make the body.

Runs B2 (prm/b2-curved-beams.prm) on 2 x 2 x 2 knot spans per beam with
NURBS p = 2 and with FE_Q(2), once as one process and once under
`mpirun --oversubscribe -np 3`, each into a scratch folder, and checks:

  - one process writes one solution-BODY-0001.vtu per body, named by the
    body's .pvd (no .pvtu);
  - three ranks write solution-BODY-0001.R.vtu for R = 0, 1, 2 and the
    record solution-BODY-0001.pvtu naming exactly those three pieces; the
    body's .pvd names the .pvtu; every piece holds cells (8 cells split
    3, 3, 2 or so: none is empty);
  - the pieces read together with VTK's vtkXMLPUnstructuredGridReader are the
    one-process VTU: the same number of points and cells, the same point
    coordinates in the same order, and every point field equal to within
    1e-6 of its largest magnitude. Both files hold Float32 (deal.II 9.4's
    DataOutBase::write_vtu); the fields come from the same solution to 1e-10
    (tests/mpi_reproduce_test.py), so they differ at most by one single-
    precision rounding, 6e-8 relative; 1e-6 leaves room for that and for
    nothing else: a piece with the wrong cells moves points by the size of
    an element;
  - the pairs' contact-0001.vtu is written once (rank 0), with no pieces.

Cell counts alone would pass pieces that hold the right number of the wrong
cells; comparing coordinates in order catches that: run against a build whose
piece r wrote the cells of piece 2 - r (the right counts, the pieces in
reverse order), the test failed on every body's points and fields
(2026-11-26).

Exit status 77 (ctest SKIP_RETURN_CODE) when Python's vtk module (Debian's
python3-vtk9) or mpirun is missing.

Usage: tests/mpi_vtu_test.py IGABDE"""

import os
import re
import shutil
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ElementTree

try:
    import numpy
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOXML import (vtkXMLPUnstructuredGridReader,
                                     vtkXMLUnstructuredGridReader)
except ImportError as e:
    print("mpi_vtu_test: skipped: Python's vtk is missing (%s); install "
          "Debian's python3-vtk9" % e)
    sys.exit(77)

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENE = os.path.join(ROOT, "prm", "b2-curved-beams.prm")
RANKS = 3
BODIES = ("body1", "body2")
FIELD_TOLERANCE = 1e-6

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
    return condition


def run(igabde, folder, discretization, ranks):
    command = [igabde, SCENE, "--quiet",
               "--set", "Discretization/Type=%s" % discretization,
               "--set", "Body 1/Subdivisions=2,2,2",
               "--set", "Body 2/Subdivisions=2,2,2",
               "--set", "Output/Write vtu=true",
               "--set", "Output/Directory=%s" % folder]
    env = dict(os.environ)
    if ranks > 1:
        # As root too (CI runs as root); no inherited Open MPI job variables.
        env = {k: v for k, v in os.environ.items()
               if not k.startswith(("OMPI_", "PMIX_", "OPAL_"))}
        env["OMPI_ALLOW_RUN_AS_ROOT"] = "1"
        env["OMPI_ALLOW_RUN_AS_ROOT_CONFIRM"] = "1"
        command = ["mpirun", "--oversubscribe", "-np", str(ranks)] + command
    result = subprocess.run(command, stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True, env=env,
                            timeout=300)
    if result.returncode != 0:
        print(result.stdout)
        sys.exit("mpi_vtu_test: %s on %d rank(s) failed with status %d"
                 % (discretization, ranks, result.returncode))


def pvd_files(path):
    return [d.get("file") for d in ElementTree.parse(path).iter("DataSet")]


def read(reader_type, path):
    reader = reader_type()
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    check(reader.GetErrorCode() == 0 and grid is not None
          and grid.GetNumberOfPoints() > 0,
          "%s: VTK cannot read it" % path)
    return grid


def point_fields(grid):
    data = grid.GetPointData()
    return {data.GetArrayName(i): vtk_to_numpy(data.GetArray(i))
            for i in range(data.GetNumberOfArrays())}


def compare(label, serial, parallel):
    n_points, n_cells = serial.GetNumberOfPoints(), serial.GetNumberOfCells()
    if not check(parallel.GetNumberOfPoints() == n_points
                 and parallel.GetNumberOfCells() == n_cells,
                 "%s: the pieces hold %d points and %d cells, one process "
                 "%d and %d" % (label, parallel.GetNumberOfPoints(),
                                parallel.GetNumberOfCells(), n_points,
                                n_cells)):
        return
    xs = vtk_to_numpy(serial.GetPoints().GetData())
    xp = vtk_to_numpy(parallel.GetPoints().GetData())
    scale = float(numpy.abs(xs).max())
    worst = float(numpy.abs(xs - xp).max())
    check(worst <= FIELD_TOLERANCE * scale,
          "%s: the pieces' points are off the one-process points by %.3g "
          "(largest coordinate %.3g)" % (label, worst, scale))
    fs, fp = point_fields(serial), point_fields(parallel)
    check(sorted(fs) == sorted(fp), "%s: fields %s in the pieces, %s in one "
          "process" % (label, sorted(fp), sorted(fs)))
    for name in sorted(set(fs) & set(fp)):
        scale = max(float(numpy.abs(fs[name]).max()), 1e-300)
        worst = float(numpy.abs(fs[name] - fp[name]).max())
        check(worst <= FIELD_TOLERANCE * scale,
              "%s: field '%s' differs by %.3g (largest magnitude %.3g)"
              % (label, name, worst, scale))


def check_case(igabde, scratch, discretization):
    one = os.path.join(scratch, discretization + "-1")
    many = os.path.join(scratch, discretization + "-%d" % RANKS)
    run(igabde, one, discretization, 1)
    run(igabde, many, discretization, RANKS)
    for body in BODIES:
        label = "%s %s" % (discretization, body)
        serial_name = "solution-%s-0001.vtu" % body
        check(pvd_files(os.path.join(one, "solution-%s.pvd" % body))
              == [serial_name], "%s: one process's .pvd does not name %s"
              % (label, serial_name))
        record = "solution-%s-0001.pvtu" % body
        check(pvd_files(os.path.join(many, "solution-%s.pvd" % body))
              == [record], "%s: the %d-rank .pvd does not name %s"
              % (label, RANKS, record))
        pieces = [p.get("Source") for p in
                  ElementTree.parse(os.path.join(many, record)).iter("Piece")]
        expected = ["solution-%s-0001.%d.vtu" % (body, r)
                    for r in range(RANKS)]
        if not check(pieces == expected, "%s: %s names %s, expected %s"
                     % (label, record, pieces, expected)):
            continue
        for piece in pieces:
            grid = read(vtkXMLUnstructuredGridReader,
                        os.path.join(many, piece))
            check(grid.GetNumberOfCells() > 0, "%s: piece %s holds no cells"
                  % (label, piece))
        serial = read(vtkXMLUnstructuredGridReader,
                      os.path.join(one, serial_name))
        parallel = read(vtkXMLPUnstructuredGridReader,
                        os.path.join(many, record))
        compare(label, serial, parallel)
    contact = sorted(f for f in os.listdir(many) if f.startswith("contact-")
                     and f.endswith("vtu"))
    check(contact == ["contact-0001.vtu"], "%s: the pairs' files on %d ranks "
          "are %s, expected contact-0001.vtu once" % (discretization, RANKS,
                                                      contact))
    stray = [f for f in os.listdir(one) if re.search(r"\.\d+\.vtu$|pvtu$", f)]
    check(not stray, "%s: one process wrote pieces %s" % (discretization,
                                                           stray))


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    if shutil.which("mpirun") is None:
        print("mpi_vtu_test: skipped: no mpirun")
        sys.exit(77)
    igabde = os.path.abspath(sys.argv[1])
    with tempfile.TemporaryDirectory(prefix="igabde-mpi-vtu-") as scratch:
        for discretization in ("nurbs", "lagrange"):
            check_case(igabde, scratch, discretization)
    if failures:
        for f in failures:
            print("FAILED: " + f)
        sys.exit(1)
    print("mpi_vtu_test: one process and %d ranks write the same fields "
          "(NURBS and FE_Q(2), both bodies)" % RANKS)


if __name__ == "__main__":
    main()
