"""Renders the pictures of doc/studies.md ("Pictures") from igabde runs, with
ParaView's pvbatch. Called by contrib/pictures/render, which runs the scenes
first; by hand:

  pvbatch contrib/pictures/render.py WORK OUT SCENE...

WORK holds one run folder per SCENE (b1, b2, v5), each as igabde writes it
(solution-body1.pvd, solution-body2.pvd, contact-NNNN.vtu, summary.json);
OUT receives SCENE-von-mises.png and SCENE-contact.png:

  SCENE-von-mises.png  the bodies of the last load step, deformed (the
                       displacement magnified by the factor in the title),
                       coloured by von Mises stress;
  SCENE-contact.png    the contact pairs of the last step at their places on
                       Body 1's contact face (undeformed), left coloured by
                       status (open, stick, slip), right by the normal
                       pressure; the master body's edges for orientation.
"""

import json
import math
import os
import sys
import xml.etree.ElementTree as ElementTree

try:
    from paraview import servermanager
    from paraview import simple as pv
except ImportError:
    print("render.py: ParaView's Python modules are missing: install Debian's "
          "python3-paraview (apt-get install python3-paraview)",
          file=sys.stderr)
    sys.exit(2)

import numpy
from vtk.util import numpy_support

WIDTH, HEIGHT = 1200, 700

# status values of the pair VTU (contact::ContactStatus) and their colours
STATUS = [("open", [0.75, 0.75, 0.75]), ("stick", [0.12, 0.47, 0.71]),
          ("slip", [0.89, 0.10, 0.11]),
          ("closed", [0.20, 0.63, 0.17])]

# Per scene: the camera (direction from the focal point to the camera, view
# up), for the von Mises picture and for the contact picture; which body
# gives the context in the contact picture; a zoom box for 2D contact.
SCENES = {
    "b1": {
        "name": "B1 cantilever beams",
        "camera": ([-1.0, -1.6, 0.9], [0, 0, 1]),
        "contact_camera": ([0, 0, 1], [0, 1, 0]),
        "zoom": None,
        "stack": True,
        "clip": 99,
    },
    "b2": {
        "name": "B2 curved beams",
        "camera": ([0.9, -1.6, 0.7], [0, 0, 1]),
        "contact_camera": ([1, -0.3, 1], [0, 1, 0]),
        "zoom": None,
        "stack": True,
        "clip": 99,
    },
    "v5": {
        "name": "V5 Hertz contact (quarter cylinder on a rigid flat)",
        "camera": ([0, 0, 1], [0, 1, 0]),
        "contact_camera": ([0, 0, 1], [0, 1, 0]),
        # x, y range of the contact picture: the contact zone (a = 1.49)
        "zoom": (0.0, 3.6, -0.1, 0.9),
        "stack": True,
        # no point load: the scale spans the whole field
        "clip": 100.0,
    },
}


def last_dataset(pvd):
    """The file of the last time step a PVD record names."""
    root = ElementTree.parse(pvd).getroot()
    sets = root.findall("./Collection/DataSet")
    if not sets:
        raise RuntimeError("%s names no data set" % pvd)
    last = max(sets, key=lambda s: float(s.get("timestep")))
    return os.path.join(os.path.dirname(pvd), last.get("file"))


def point_locations(source):
    data = servermanager.Fetch(source)
    return numpy_support.vtk_to_numpy(data.GetPoints().GetData()).astype(
        float)


def point_array(source, name):
    data = servermanager.Fetch(source)
    return numpy_support.vtk_to_numpy(data.GetPointData().GetArray(name))


def nice(x):
    """1, 2 or 5 times a power of ten, at most x."""
    e = math.floor(math.log10(x))
    for m in (5, 2, 1):
        if m * 10**e <= x:
            return m * 10**e
    return 10**e


def white_view(size):
    view = pv.CreateView("RenderView")
    view.ViewSize = size
    view.OrientationAxesVisibility = 1
    try:
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    view.Background = [1, 1, 1]
    return view


def title(view, text, size=16):
    source = pv.Text(Text=text)
    display = pv.Show(source, view)
    display.WindowLocation = "Upper Center"
    display.FontSize = size
    display.Color = [0, 0, 0]
    return source


def scalar_bar(lut, view, text):
    bar = pv.GetScalarBar(lut, view)
    bar.Title = text
    bar.ComponentTitle = ""
    bar.TitleColor = [0, 0, 0]
    bar.LabelColor = [0, 0, 0]
    bar.TitleFontSize = 14
    bar.LabelFontSize = 13
    bar.Visibility = 1
    bar.WindowLocation = "Any Location"
    bar.Orientation = "Vertical"
    bar.Position = [0.88, 0.1]
    bar.ScalarBarLength = 0.7
    return bar


def place_camera(view, bounds, direction, up, zoom=None):
    if zoom is not None:
        bounds = [zoom[0], zoom[1], zoom[2], zoom[3], 0, 0]
    centre = [(bounds[2 * i] + bounds[2 * i + 1]) / 2 for i in range(3)]
    norm = math.sqrt(sum(d * d for d in direction))
    view.CameraFocalPoint = centre
    view.CameraPosition = [c + 10 * d / norm
                           for c, d in zip(centre, direction)]
    view.CameraViewUp = up
    view.CameraParallelProjection = 1 if zoom is not None else 0
    view.ResetCamera(bounds)
    if zoom is None:
        view.CameraParallelScale = view.CameraParallelScale
        pv.GetActiveCamera().Dolly(1.15)


def fit_camera(view, points, direction, up, aspect):
    """Parallel projection along direction, up as view up, framing points
    (an n x 3 array) with a margin and room for the title."""
    d = numpy.asarray(direction, float)
    d /= numpy.linalg.norm(d)
    u = numpy.asarray(up, float)
    u = u - u.dot(d) * d
    u /= numpy.linalg.norm(u)
    r = numpy.cross(u, d)
    pr, pu, pd = points.dot(r), points.dot(u), points.dot(d)
    centre = ((pr.min() + pr.max()) / 2 * r + (pu.min() + pu.max()) / 2 * u
              + pd.mean() * d)
    half = max(numpy.ptp(pu) / 2, numpy.ptp(pr) / (2 * aspect), 1e-12)
    view.CameraParallelProjection = 1
    view.CameraFocalPoint = list(centre)
    view.CameraPosition = list(centre + 100 * half * d)
    view.CameraViewUp = list(u)
    view.CameraParallelScale = 1.3 * half
    # the title takes the top of the picture
    view.CameraFocalPoint = list(centre + 0.15 * half * u)
    view.CameraPosition = list(centre + 0.15 * half * u + 100 * half * d)


def describe(summary):
    """One line on the run from its summary.json: discretisation, size."""
    kind = summary.get("discretization")
    if not kind:
        return ""
    text = ("NURBS p = %s" if kind == "nurbs" else "FE_Q(%s)") % summary.get(
        "degree", "?")
    text += ", %s elements, %s DOFs" % (summary.get("n_elements", "?"),
                                       summary.get("n_dofs", "?"))
    return text


def load_summary(folder):
    try:
        with open(os.path.join(folder, "summary.json")) as f:
            return json.load(f)
    except (OSError, ValueError):
        return {}


def von_mises_picture(scene, folder, out):
    setup = SCENES[scene]
    summary = load_summary(folder)
    view = white_view([WIDTH, HEIGHT])
    bodies = []
    for body in ("body1", "body2"):
        pvd = os.path.join(folder, "solution-%s.pvd" % body)
        if os.path.exists(pvd):
            bodies.append(pv.XMLUnstructuredGridReader(
                FileName=[last_dataset(pvd)]))
    if not bodies:
        raise RuntimeError("%s: no solution-body*.pvd" % folder)
    bounds = [math.inf, -math.inf] * 3
    max_u, stresses = 0.0, []
    for reader in bodies:
        reader.UpdatePipeline()
        b = reader.GetDataInformation().GetBounds()
        for i in range(3):
            bounds[2 * i] = min(bounds[2 * i], b[2 * i])
            bounds[2 * i + 1] = max(bounds[2 * i + 1], b[2 * i + 1])
        u = point_array(reader, "displacement")
        max_u = max(max_u, float(numpy.max(numpy.linalg.norm(u, axis=1))))
        stresses.append(point_array(reader, "von_mises"))
    diagonal = math.sqrt(sum((bounds[2 * i + 1] - bounds[2 * i])**2
                             for i in range(3)))
    # magnify the displacement to a twentieth of the bodies' size
    scale = nice(0.05 * diagonal / max_u) if max_u > 0 else 1
    scale = max(scale, 1)
    stress = numpy.concatenate(stresses)
    # B1's and B2's point loads make singular stress peaks that would wash
    # out the rest: the colour scale ends at a percentile (magenta above)
    top = float(numpy.percentile(stress, setup["clip"]))
    lut = pv.GetColorTransferFunction("von_mises")
    lut.ApplyPreset("Turbo", True)
    lut.RescaleTransferFunction(0.0, top)
    lut.AutomaticRescaleRangeMode = "Never"
    lut.UseAboveRangeColor = 1
    lut.AboveRangeColor = [1.0, 0.0, 1.0]
    for reader in bodies:
        warp = pv.WarpByVector(Input=reader)
        warp.Vectors = ["POINTS", "displacement"]
        warp.ScaleFactor = scale
        display = pv.Show(warp, view)
        pv.ColorBy(display, ("POINTS", "von_mises"))
        display.LookupTable = lut
        display.SetScalarBarVisibility(view, False)
    # ColorBy rescaled the map to the data: set the range again
    lut.RescaleTransferFunction(0.0, top)
    scalar_bar(lut, view, "von Mises\nstress (Pa)" + (
        "\nmagenta > %gth pct" % setup["clip"] if setup["clip"] < 100 else ""))
    text = "%s: von Mises stress, displacement x %g" % (setup["name"], scale)
    line = describe(summary)
    title(view, text + ("\n" + line if line else ""))
    direction, up = setup["camera"]
    place_camera(view, bounds, direction, up)
    pv.Render(view)
    path = os.path.join(out, "%s-von-mises.png" % scene)
    pv.SaveScreenshot(path, view, ImageResolution=[WIDTH, HEIGHT],
                      CompressionLevel="9")
    print("render.py: wrote %s (displacement x %g, colour scale 0 .. %.3g)"
          % (path, scale, top))
    pv.Delete(view)


def contact_picture(scene, folder, out):
    setup = SCENES[scene]
    files = sorted(f for f in os.listdir(folder)
                   if f.startswith("contact-") and f.endswith(".vtu"))
    if not files:
        raise RuntimeError("%s: no contact-NNNN.vtu" % folder)
    pairs = pv.XMLUnstructuredGridReader(
        FileName=[os.path.join(folder, files[-1])])
    pairs.UpdatePipeline()
    master = None
    for body in ("body2", "body1"):
        pvd = os.path.join(folder, "solution-%s.pvd" % body)
        if os.path.exists(pvd):
            # one point per place: the outer surface only, no patch faces
            master = pv.CleantoGrid(Input=pv.XMLUnstructuredGridReader(
                FileName=[last_dataset(pvd)]))
            break
    locations = point_locations(pairs)
    if setup["zoom"] is not None:
        x0, x1, y0, y1 = setup["zoom"]
        locations = numpy.array([[x0, y0, 0], [x1, y1, 0]])
    n_pairs = pairs.GetDataInformation().GetNumberOfPoints()
    pressure = point_array(pairs, "pressure")
    status = point_array(pairs, "status").astype(int)
    counts = ", ".join("%d %s" % (int(numpy.sum(status == i)), name)
                       for i, (name, _) in enumerate(STATUS))

    # wide contact surfaces one above the other, tall ones side by side
    stack = setup["stack"]
    size = [WIDTH, HEIGHT // 2] if stack else [WIDTH // 2, HEIGHT]
    layout = pv.CreateLayout("contact")
    views = [white_view(size), white_view(size)]
    pv.AssignViewToLayout(view=views[0], layout=layout, hint=0)
    if stack:
        layout.SplitVertical(0, 0.5)
    else:
        layout.SplitHorizontal(0, 0.5)
    pv.AssignViewToLayout(view=views[1], layout=layout, hint=2)
    layout.SetSize(WIDTH, HEIGHT)

    status_lut = pv.GetColorTransferFunction("status")
    status_lut.InterpretValuesAsCategories = 1
    status_lut.Annotations = sum(([str(i), name]
                                  for i, (name, _) in enumerate(STATUS)), [])
    status_lut.IndexedColors = sum((c for _, c in STATUS), [])
    pressure_lut = pv.GetColorTransferFunction("pressure")
    pressure_lut.ApplyPreset("Inferno (matplotlib)", True)
    # open pairs (zero pressure) in the status picture's grey
    top = max(float(pressure.max()), 1e-300)
    pressure_lut.RescaleTransferFunction(1e-6 * top, top)
    pressure_lut.AutomaticRescaleRangeMode = "Never"
    pressure_lut.UseBelowRangeColor = 1
    pressure_lut.BelowRangeColor = STATUS[0][1]

    radius = 12 if n_pairs < 200 else 8
    for view, (field, lut, label) in zip(views, [
            ("status", status_lut, "status"),
            ("pressure", pressure_lut, "pressure (Pa)")]):
        if master is not None:
            context = pv.Show(master, view)
            if scene == "v5":
                context.ColorArrayName = ["POINTS", ""]
                context.Representation = "Surface With Edges"
                context.AmbientColor = [0.85, 0.85, 0.85]
                context.DiffuseColor = [0.85, 0.85, 0.85]
                context.EdgeColor = [0.6, 0.6, 0.6]
            else:
                context.Representation = "Feature Edges"
                context.ColorArrayName = ["POINTS", ""]
                context.AmbientColor = [0.3, 0.3, 0.3]
                context.DiffuseColor = [0.3, 0.3, 0.3]
        display = pv.Show(pairs, view)
        display.Representation = "Points"
        display.RenderPointsAsSpheres = 1
        display.PointSize = radius
        pv.ColorBy(display, ("POINTS", field))
        display.LookupTable = lut
        display.InterpolateScalarsBeforeMapping = 0
        display.SetScalarBarVisibility(view, False)
        bar = scalar_bar(lut, view, label)
        if stack:
            bar.Position = [0.89, 0.05]
            bar.ScalarBarLength = 0.8
        else:
            bar.Orientation = "Horizontal"
            bar.Position = [0.2, 0.03]
            bar.ScalarBarLength = 0.6
        direction, up = setup["contact_camera"]
        fit_camera(view, locations, direction, up, size[0] / size[1])
    # ColorBy rescaled the map to the data: set the range again
    pressure_lut.RescaleTransferFunction(1e-6 * top, top)
    title(views[0], "%s: %d contact pairs by status\n%s"
          % (setup["name"].split(" (")[0], n_pairs, counts), 14)
    title(views[1], "normal pressure, max %.3g Pa" % pressure.max(), 14)
    for view in views:
        pv.Render(view)
    path = os.path.join(out, "%s-contact.png" % scene)
    pv.SaveScreenshot(path, layout, SaveAllViews=1,
                      ImageResolution=[WIDTH, HEIGHT], CompressionLevel="9")
    print("render.py: wrote %s (%d pairs: %s)" % (path, n_pairs, counts))


def main():
    if len(sys.argv) < 4:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    work, out, scenes = sys.argv[1], sys.argv[2], sys.argv[3:]
    os.makedirs(out, exist_ok=True)
    for scene in scenes:
        if scene not in SCENES:
            print("render.py: unknown scene %s (%s)"
                  % (scene, ", ".join(SCENES)), file=sys.stderr)
            sys.exit(2)
        folder = os.path.join(work, scene)
        von_mises_picture(scene, folder, out)
        contact_picture(scene, folder, out)


main()
