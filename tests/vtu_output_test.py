#!/usr/bin/python3
"""The VTU and PVD files a run writes, read back with VTK's own readers.

Runs B2 (prm/b2-curved-beams.prm) on the coarsest mesh, 2 x 2 x 2 knot spans
per beam, once with NURBS p = 2 and once with FE_Q(2), each into a scratch
folder that is removed afterwards, and checks for each run:

  - every .pvd parses, every file it names exists and is one of the folder's
    solution VTUs (contact.pvd: its pair VTUs), and every solution VTU is
    named by its body's .pvd;
  - every .vtu of the folder opens with vtkXMLUnstructuredGridReader (the
    bodies' solution-*.vtu and the pairs' contact-*.vtu);
  - the point and cell data fields each file must have are there, with the
    right number of components, and finite;
  - the point and cell counts: a body VTU has one patch per element, each
    with (s + 1)^3 points and s^3 hexahedra (s = Output subdivisions: auto
    gives 4 on 2 x 2 x 2 cells; at least the FE_Q degree), the element count derived from the mesh
    (2 x 2 x 2) and equal to summary.json's; a contact VTU has one vertex
    per pair, the pair count derived from the mesh (NURBS: Greville points
    of Body 1's face r = 5, (2 + 2) x (2 + 2); FE_Q(2): face nodes,
    (2·2 + 1) x (2·2 + 1)) minus the clamped edge theta = 0 that B2 leaves
    out, and equal to summary.json's n_contact_pairs;
  - the contact surface is curved: the points with |r - 5| < 1e-3 (r the
    distance from the beams' axis, the y axis) are the whole sampled
    surface r = 5 of each body, 2 x 2 patches of 5 x 5 points, and for NURBS
    they lie on r = 5 within 1e-10 (the output samples the exact NURBS map);
    for FE_Q(2) the points at the element nodes lie on r = 5 within 1e-10
    and the points between them within the interpolation error of the
    quadratic geometry (1e-3 for 45 degrees per element).

The VTU points are the undeformed geometry (the 'displacement' field is
written beside them, not added): the test says so when the points minus the
displacement lie on r = 5 and the points themselves do not.

The test checks that it can fail: the same curvature check is run on a
flat-faceted copy of the NURBS output (each patch's points replaced by the
trilinear interpolation of its 8 corner points, what a straight-sided
output would give) and must reject it: a chord midpoint of a 45 degree
element is at r = 5 cos(22.5 deg) = 4.62.

It also runs V5 (prm/v5-hertz-2d.prm, a disc on a rigid plane under a
distributed load) and checks that no sample of the von Mises stress
exceeds Hertz's peak pressure p0 (summary.json's hertz_peak_pressure_exact,
Johnson's closed form): in line contact the von Mises stress peaks below
the surface at about 0.56 p0 (nu = 0.3), and the rest of the disc carries
the applied traction, far less. The sample at the patch corner where the
NURBS map is singular once read 1.6e5 against p0 = 102.

Exit status 77 (ctest SKIP_RETURN_CODE) when Python's vtk module (Debian's
python3-vtk9) is missing.

Usage: tests/vtu_output_test.py IGABDE"""

import json
import os
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ElementTree

try:
    import numpy
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
except ImportError as e:
    print("vtu_output_test: skipped: Python's vtk is missing (%s); install "
          "Debian's python3-vtk9" % e)
    sys.exit(77)

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENE = os.path.join(ROOT, "prm", "b2-curved-beams.prm")

SPANS = (2, 2, 2)         # radial x circumferential x width, per beam
OUTPUT_SUBDIVISIONS = 4   # Output subdivisions = auto on 8 cells per body
DEGREE = 2
RADIUS = 5.0              # the contact surface of both beams
VTK_HEXAHEDRON = 12
VTK_VERTEX = 1

BODY_FIELDS = {"displacement": 3, "von_mises": 1}
for _kind in ("strain_", "stress_"):
    for _ij in ("xx", "xy", "xz", "yy", "yz", "zz"):
        BODY_FIELDS[_kind + _ij] = 1
# mu = 0.5 in B2: the slip vector is written
CONTACT_FIELDS = {"pressure": 1, "gap": 1, "status": 1, "contact_force": 3,
                  "slip": 3}

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
    return condition


def read_vtu(path):
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    check(reader.GetErrorCode() == 0 and grid is not None
          and grid.GetNumberOfPoints() > 0,
          "%s: VTK cannot read it (error code %d)"
          % (path, reader.GetErrorCode()))
    return grid


def point_fields(grid):
    data = grid.GetPointData()
    return {data.GetArrayName(i): vtk_to_numpy(data.GetArray(i))
            for i in range(data.GetNumberOfArrays())}


def check_fields(name, grid, expected):
    fields = point_fields(grid)
    for field, components in expected.items():
        if not check(field in fields, "%s: no point field '%s' (has %s)"
                     % (name, field, sorted(fields))):
            continue
        values = fields[field]
        n = 1 if values.ndim == 1 else values.shape[1]
        check(n == components, "%s: '%s' has %d components, not %d"
              % (name, field, n, components))
        check(len(values) == grid.GetNumberOfPoints(),
              "%s: '%s' has %d values for %d points"
              % (name, field, len(values), grid.GetNumberOfPoints()))
        check(numpy.all(numpy.isfinite(values)),
              "%s: '%s' is not finite everywhere" % (name, field))
    cells = grid.GetCellData()
    for i in range(cells.GetNumberOfArrays()):
        values = vtk_to_numpy(cells.GetArray(i))
        check(numpy.all(numpy.isfinite(values)), "%s: cell field '%s' is "
              "not finite everywhere" % (name, cells.GetArrayName(i)))
    return fields


def cell_types(grid):
    return {grid.GetCellType(i) for i in range(grid.GetNumberOfCells())}


def radius(points):
    return numpy.hypot(points[:, 0], points[:, 2])


def surface_errors(points, label, tolerance, expected, window=1e-3,
                   node_stride=None, between=None):
    """What is wrong with the sampled surface r = RADIUS in points: [] when
    there are expected points with |r - 5| < window, sampled at enough
    angles, and each is within tolerance of r = 5. With node_stride (FE_Q),
    only the points on a node row in both surface directions are held to
    tolerance, the others to between."""
    errors = []
    distance = numpy.abs(radius(points) - RADIUS)
    on = numpy.nonzero(distance < window)[0]
    if len(on) != expected:
        errors.append("%s: %d points with |r - 5| < %g, expected %d (the "
                      "sampled surface r = 5)"
                      % (label, len(on), window, expected))
    if len(on) == 0:
        return errors
    nodes = on
    if node_stride is not None:
        n1 = OUTPUT_SUBDIVISIONS + 1
        local = on % n1**3
        ijk = numpy.stack([local % n1, (local // n1) % n1, local // n1**2])
        at_node = numpy.all(ijk % node_stride == 0, axis=0)
        nodes = on[at_node]
        others = on[~at_node]
        worst = float(distance[others].max()) if len(others) else 0.0
        if worst > between:
            errors.append("%s: a point of the surface r = 5 between the "
                          "nodes is %.3g off it (tolerance %.0e)"
                          % (label, worst, between))
    worst = float(distance[nodes].max()) if len(nodes) else 0.0
    if worst > tolerance:
        errors.append("%s: a point of the surface r = 5 is %.3g off it "
                      "(tolerance %.0e)" % (label, worst, tolerance))
    # points between the patch corners, i.e. between the knots
    theta = numpy.unique(numpy.round(numpy.arctan2(points[on, 2],
                                                   points[on, 0]), 6))
    if len(theta) < SPANS[1] * OUTPUT_SUBDIVISIONS + 1:
        errors.append("%s: the surface r = 5 is sampled at %d angles, "
                      "fewer than %d" % (label, len(theta),
                                         SPANS[1] * OUTPUT_SUBDIVISIONS + 1))
    return errors


def on_surface_tolerance(dtype, where):
    """How far from r = 5 a written surface point may be: 1e-10 for double
    precision points. deal.II 9.4's DataOutBase::write_vtu writes the points
    as Float32 whatever they were; then the tolerance is the rounding of x and
    z (coordinates below 8) to single precision, |dr| <= sqrt(2) ulp(4) / 2
    = 3.4e-7, still nine orders of magnitude below a chord's distance."""
    if dtype == numpy.float64:
        return 1e-10
    print("  note: %s has %s points: r = 5 to single precision, not 1e-10"
          % (where, dtype))
    return 4e-7


def geometry_errors(points, where, discretization, tolerance):
    """The sampled surfaces r = 5. NURBS: every point on it to tolerance.
    FE_Q(2): the nodes to tolerance, the points between them within the
    interpolation error of a quadratic on 45 degrees (0.014; 0.02 allowed);
    the next sample layer is 0.11 away, so the window is 0.05."""
    surface = SPANS[1] * SPANS[2] * (OUTPUT_SUBDIVISIONS + 1)**2
    if discretization == "nurbs":
        return surface_errors(points, where, tolerance, surface)
    return surface_errors(points, where, tolerance, surface, window=0.05,
                          node_stride=OUTPUT_SUBDIVISIONS // DEGREE,
                          between=0.02)


def faceted(points):
    """Each patch's points replaced by the trilinear interpolation of its 8
    corners: the output a straight-sided (flat-faceted) writer would give.
    deal.II writes a patch's (s + 1)^3 points together, lexicographically."""
    n1 = OUTPUT_SUBDIVISIONS + 1
    s = OUTPUT_SUBDIVISIONS
    out = numpy.empty_like(points)
    for start in range(0, len(points), n1**3):
        patch = points[start:start + n1**3].reshape(n1, n1, n1, 3)
        corner = patch[::s, ::s, ::s]          # [k][j][i]
        t = numpy.linspace(0.0, 1.0, n1)
        k, j, i = numpy.meshgrid(t, t, t, indexing="ij")
        flat = numpy.zeros_like(patch)
        for a in (0, 1):
            for b in (0, 1):
                for c in (0, 1):
                    w = ((k if a else 1 - k) * (j if b else 1 - j)
                         * (i if c else 1 - i))
                    flat += w[..., None] * corner[a, b, c]
        out[start:start + n1**3] = flat.reshape(-1, 3)
    return out


def run(igabde, folder, discretization):
    command = [igabde, SCENE, "--quiet",
               "--set", "Discretization/Type=%s" % discretization,
               "--set", "Body 1/Subdivisions=%d,%d,%d" % SPANS,
               "--set", "Body 2/Subdivisions=%d,%d,%d" % SPANS,
               "--set", "Output/Write vtu=true",
               "--set", "Output/Directory=%s" % folder]
    result = subprocess.run(command, stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True,
                            timeout=120)
    if result.returncode != 0:
        print(result.stdout)
        sys.exit("vtu_output_test: igabde failed on B2 %s (status %d)"
                 % (discretization, result.returncode))
    with open(os.path.join(folder, "summary.json")) as f:
        return json.load(f)


def check_run(folder, discretization, summary):
    label = "B2 %s" % discretization
    check(summary.get("status") == "ok", "%s: status %s"
          % (label, summary.get("status")))
    files = sorted(os.listdir(folder))
    vtus = [f for f in files if f.endswith(".vtu")]
    pvds = [f for f in files if f.endswith(".pvd")]
    solution_vtus = {f for f in vtus if f.startswith("solution-")}
    contact_vtus = [f for f in vtus if f.startswith("contact-")]
    check(vtus == sorted(solution_vtus) + contact_vtus or
          set(vtus) == solution_vtus | set(contact_vtus),
          "%s: VTU files other than solution-* and contact-*: %s"
          % (label, vtus))
    check(pvds == ["contact.pvd", "solution-body1.pvd",
                   "solution-body2.pvd"],
          "%s: PVD files %s, expected contact.pvd, solution-body1.pvd and "
          "solution-body2.pvd" % (label, pvds))
    n_steps = len(summary.get("load_steps", []))
    check(n_steps >= 1, "%s: no load step in summary.json" % label)
    check(len(contact_vtus) == n_steps, "%s: %d contact VTUs for %d load "
          "steps" % (label, len(contact_vtus), n_steps))

    # PVD: XML, every data set exists, one per step, all solution VTUs named
    named = set()
    for pvd in pvds:
        root = ElementTree.parse(os.path.join(folder, pvd)).getroot()
        check(root.get("type") == "Collection", "%s: %s is not a VTK "
              "Collection" % (label, pvd))
        sets = root.findall("./Collection/DataSet")
        check(len(sets) == n_steps, "%s: %s names %d data sets for %d load "
              "steps" % (label, pvd, len(sets), n_steps))
        prefix = ("contact-" if pvd == "contact.pvd" else
                  "solution-%s-" % pvd[len("solution-"):-len(".pvd")])
        for s in sets:
            name = s.get("file")
            check(os.path.exists(os.path.join(folder, name)),
                  "%s: %s names %s, which does not exist"
                  % (label, pvd, name))
            check(name.startswith(prefix),
                  "%s: %s names %s, another series' file"
                  % (label, pvd, name))
            if pvd != "contact.pvd":
                named.add(name)
    check(named == solution_vtus, "%s: solution VTUs not named by a PVD: "
          "%s; named but absent: %s" % (label, sorted(solution_vtus - named),
                                        sorted(named - solution_vtus)))

    # Body VTUs: fields, counts, geometry
    n1 = OUTPUT_SUBDIVISIONS + 1
    elements = SPANS[0] * SPANS[1] * SPANS[2]
    check(summary.get("n_elements") == 2 * elements,
          "%s: summary.json has %s elements, the mesh %d"
          % (label, summary.get("n_elements"), 2 * elements))
    last = {}
    for name in sorted(solution_vtus):
        grid = read_vtu(os.path.join(folder, name))
        fields = check_fields("%s %s" % (label, name), grid, BODY_FIELDS)
        check(grid.GetNumberOfPoints() == elements * n1**3,
              "%s %s: %d points, expected %d elements x %d"
              % (label, name, grid.GetNumberOfPoints(), elements, n1**3))
        check(grid.GetNumberOfCells() == elements * OUTPUT_SUBDIVISIONS**3,
              "%s %s: %d cells, expected %d" % (
                  label, name, grid.GetNumberOfCells(),
                  elements * OUTPUT_SUBDIVISIONS**3))
        check(cell_types(grid) == {VTK_HEXAHEDRON}, "%s %s: cell types %s, "
              "expected hexahedra only" % (label, name, cell_types(grid)))
        body = name.split("-")[1]
        last[body] = (name, vtk_to_numpy(grid.GetPoints().GetData()),
                      fields.get("displacement"))

    for body, (name, points, u) in sorted(last.items()):
        where = "%s %s" % (label, name)
        tolerance = on_surface_tolerance(points.dtype, where)
        points = numpy.asarray(points, dtype=float)
        if u is not None:
            check(numpy.abs(u).max() > 1e-9, "%s: zero displacement" % where)
        errors = geometry_errors(points, where, discretization, tolerance)
        if errors and u is not None and not geometry_errors(
                points - u, where, discretization, tolerance):
            errors.append("%s: the points minus the displacement lie on "
                          "r = 5: the points are the deformed geometry"
                          % where)
        for e in errors:
            check(False, e)
        # the negative control: a straight-sided output must be rejected
        flat = geometry_errors(faceted(points), where + " faceted",
                               discretization, tolerance)
        if check(flat, "%s: the curvature check accepts a flat-faceted copy "
                 "of the output: it cannot fail" % where):
            print("  negative control, faceted copy rejected: %s" % flat[0])
        distance = numpy.abs(radius(points) - RADIUS)
        print("  %s: %d points, on r = 5: %d, max |r - 5| there %.2e"
              % (where, len(points), int(numpy.sum(distance < 0.05)),
                 distance[distance < 0.05].max()))

    # Contact VTUs: one vertex per pair
    per_direction = (SPANS[1] + DEGREE if discretization == "nurbs"
                     else DEGREE * SPANS[1] + 1,
                     SPANS[2] + DEGREE if discretization == "nurbs"
                     else DEGREE * SPANS[2] + 1)
    # the clamped edge theta = 0 (one row across the width) is left out
    pairs = per_direction[0] * per_direction[1] - per_direction[1]
    check(summary.get("n_contact_pairs") == pairs,
          "%s: summary.json has %s contact pairs, the mesh gives %d"
          % (label, summary.get("n_contact_pairs"), pairs))
    check(summary.get("effects", {}).get("pairs_left_out_supported")
          == per_direction[1], "%s: summary.json left out %s supported "
          "pairs, the clamped edge has %d" % (
              label, summary.get("effects", {}).get(
                  "pairs_left_out_supported"), per_direction[1]))
    for name in contact_vtus:
        grid = read_vtu(os.path.join(folder, name))
        where = "%s %s" % (label, name)
        fields = check_fields(where, grid, CONTACT_FIELDS)
        check(grid.GetNumberOfPoints() == pairs, "%s: %d points for %d "
              "pairs" % (where, grid.GetNumberOfPoints(), pairs))
        check(cell_types(grid) == {VTK_VERTEX}, "%s: cell types %s, "
              "expected vertices" % (where, cell_types(grid)))
        points = vtk_to_numpy(grid.GetPoints().GetData())
        tolerance = on_surface_tolerance(points.dtype, where)
        off = numpy.abs(radius(points.astype(float)) - RADIUS).max()
        check(off < tolerance, "%s: a pair is off the contact surface r = 5 "
              "by %.2e" % (where, off))
        if "status" in fields:
            check(set(numpy.unique(fields["status"])) <= {0.0, 1.0, 2.0},
                  "%s: status values %s, expected 0 (open), 1 (stick), "
                  "2 (slip)" % (where, numpy.unique(fields["status"])))
        if "pressure" in fields and "status" in fields:
            p, status = fields["pressure"], fields["status"]
            check(numpy.all(p >= -1e-9 * max(p.max(), 1.0)),
                  "%s: negative pressure %g" % (where, p.min()))
            check(p.max() > 0 and numpy.any(status > 0),
                  "%s: no pair carries load" % where)
        print("  %s: %d pairs" % (where, grid.GetNumberOfPoints()))


def check_v5(igabde, folder):
    """No von Mises sample of V5 above Hertz's p0 (see the module text)."""
    scene = os.path.join(ROOT, "prm", "v5-hertz-2d.prm")
    result = subprocess.run([igabde, scene, "--quiet",
                             "--set", "Output/Directory=%s" % folder],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            text=True, timeout=120)
    if not check(result.returncode == 0, "V5: igabde failed (status %d): %s"
                 % (result.returncode, result.stdout[-500:])):
        return
    with open(os.path.join(folder, "summary.json")) as f:
        p0 = json.load(f)["checks"]["hertz_peak_pressure_exact"]
    vtus = [f for f in sorted(os.listdir(folder))
            if f.startswith("solution-") and f.endswith(".vtu")]
    check(len(vtus) > 0, "V5: no solution VTU")
    for name in vtus:
        grid = read_vtu(os.path.join(folder, name))
        vm = point_fields(grid)["von_mises"]
        points = vtk_to_numpy(grid.GetPoints().GetData())
        worst = int(numpy.argmax(vm))
        check(vm[worst] <= p0, "V5 %s: von Mises %.4g at (%.4g, %.4g) above "
              "Hertz's p0 = %.4g" % (name, vm[worst], points[worst][0],
                                     points[worst][1], p0))
        print("V5 %s: largest von Mises %.4g = %.2f p0" % (name, vm[worst],
                                                          vm[worst] / p0))


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__.split("\n\n")[-1])
    igabde = os.path.abspath(sys.argv[1])
    with tempfile.TemporaryDirectory(prefix="vtu-output-") as scratch:
        for discretization in ("nurbs", "lagrange"):
            folder = os.path.join(scratch, discretization)
            summary = run(igabde, folder, discretization)
            print("B2 %s, %d x %d x %d per beam:" % ((discretization,)
                                                      + SPANS))
            check_run(folder, discretization, summary)
        check_v5(igabde, os.path.join(scratch, "v5"))
    if failures:
        print("vtu_output_test: %d failure(s):" % len(failures))
        for f in failures:
            print("  " + f)
        sys.exit(1)
    print("vtu_output_test: all checks passed")


if __name__ == "__main__":
    main()
