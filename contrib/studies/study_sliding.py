"""Finite sliding (doc/studies.md, "Finite sliding"): the ironing set-up of
prm/ironing-2d.prm (a stiff half ring pressed 1.4 into a soft neo-Hookean
block, then moved 4 along it, frictionless), and the same with friction
(prm/ironing-2d-friction.prm, mu = 0.3, the die kept off the block's end),
on NURBS p = 2, 3 and FE_Q(1), FE_Q(2) at the same block unknowns, on two
meshes. Per run: the die's reaction forces over the slide, their
oscillation (the step-to-step second difference, and the distance from a
quartic fitted to the same steps, in per cent of the mean vertical force),
the unknowns, the Newton iterations per step and the seconds.

The block's top carries the slave functions; the die is the master, so
that the die's surface (exact on NURBS, faceted on FE_Q) is what the
pairs slide over. The die keeps its 2 x 16 cells (NURBS: two patches of
16 spans each, given by the geometry file) on every block mesh."""

import math
import os

import common
from common import g

# (label, Discretization/Type, degree)
CONFIGS = [("NURBS p=2", "nurbs", 2), ("NURBS p=3", "nurbs", 3),
           ("FE_Q(1)", "lagrange", 1), ("FE_Q(2)", "lagrange", 2)]

# Block meshes by their unknowns per direction (control points or nodes):
# 47 x 17 is the shipped scene's (45 x 15 spans of degree 2), 33 x 12 about
# 1.4 times coarser.
MESHES = [(33, 12), (47, 17)]
QUICK_MESHES = [(19, 8)]

# --quick: half the press in 3 steps, a slide of the whole length in 12.
QUICK_PATH = {"Load path/Number of steps": 15,
              "Load path/Histories": "press: ramp 0 0.5 3, hold 0.5 12; "
              "slide: hold 0 3, ramp 0 1 12"}

# (label, scene, length of the slide, the part of the slide from which
# on the forces are compared): frictionless from a slide of 1 on (the
# contact has settled after the press), with friction from 1.25 on, where
# every closed pair slips.
SCENES = [("frictionless", "ironing-2d.prm", 4., 0.25),
          ("mu = 0.3", "ironing-2d-friction.prm", 2.5, 0.5)]


def spans(points, discretization, degree):
    """Spans (NURBS) or cells (FE_Q) giving @p points unknowns per
    direction: n + p control points, p n + 1 nodes."""
    if discretization == "nurbs":
        return points - degree
    return (points - 1) // degree


def fit(xs, ys, degree=4):
    """Least-squares polynomial of @p degree through (xs, ys), evaluated at
    xs (normal equations on x scaled to [-1, 1])."""
    lo, hi = min(xs), max(xs)
    ts = [(2. * x - lo - hi) / (hi - lo) for x in xs]
    n = degree + 1
    A = [[sum(t ** (i + j) for t in ts) for j in range(n)] for i in range(n)]
    b = [sum(y * t ** i for t, y in zip(ts, ys)) for i in range(n)]
    # Gaussian elimination with partial pivoting.
    for k in range(n):
        p = max(range(k, n), key=lambda r: abs(A[r][k]))
        A[k], A[p], b[k], b[p] = A[p], A[k], b[p], b[k]
        for r in range(k + 1, n):
            f = A[r][k] / A[k][k]
            for c in range(k, n):
                A[r][c] -= f * A[k][c]
            b[r] -= f * b[k]
    c = [0.] * n
    for k in reversed(range(n)):
        c[k] = (b[k] - sum(A[k][j] * c[j] for j in range(k + 1, n))) / A[k][k]
    return [sum(c[i] * t ** i for i in range(n)) for t in ts]


def forces(row, slide_length, slide_from):
    """(slide, F_x, F_y) of the die (Body 2's support reaction) at every
    converged step from the part @p slide_from of the slide on."""
    history = []
    for step in row.get("_steps", []):
        if step.get("status") == "failed":
            continue
        factors = step.get("history_factors") or {}
        slide = factors.get("slide", 0.)
        bodies = step.get("bodies") or []
        if slide < slide_from - 1e-12 or len(bodies) < 2:
            continue
        reaction = bodies[1].get("support_reaction")
        if reaction is None:
            continue
        history.append((slide * slide_length, reaction[0], reaction[1]))
    return history


def oscillation(history):
    """Mean F_x and F_y, the second differences' rms and largest value of
    both and the largest distance of F_y from a quartic, the last three in
    per cent of the mean |F_y|."""
    if len(history) < 8:
        return {}
    xs = [h[0] for h in history]
    result = {"steps": len(history)}
    mean_fy = sum(h[2] for h in history) / len(history)
    result["mean_fx"] = sum(h[1] for h in history) / len(history)
    result["mean_fy"] = mean_fy
    scale = 100. / abs(mean_fy)
    for c, name in ((1, "fx"), (2, "fy")):
        d2 = [abs(history[k + 1][c] - 2. * history[k][c] + history[k - 1][c])
              for k in range(1, len(history) - 1)]
        result[name + "_jitter_rms"] = scale * math.sqrt(
            sum(v * v for v in d2) / len(d2))
        result[name + "_jitter_max"] = scale * max(d2)
    smooth = fit(xs, [h[2] for h in history])
    result["fy_fit_max"] = scale * max(abs(h[2] - s)
                                       for h, s in zip(history, smooth))
    return result


def sliding(args, runner):
    meshes = QUICK_MESHES if args.quick else MESHES
    rows = []
    for scene_label, scene_file, slide_length, slide_from in SCENES:
        for points in meshes:
            for label, discretization, degree in CONFIGS:
                sets = {
                    "Discretization/Type": discretization,
                    "Discretization/Degree": degree,
                    "Body 1/Subdivisions": "%d, %d" % (
                        spans(points[0], discretization, degree),
                        spans(points[1], discretization, degree)),
                }
                if args.quick:
                    sets.update(QUICK_PATH)
                run_label = "%s, %s, block %dx%d" % (
                    scene_label, label, points[0], points[1])
                row = runner.run(run_label, common.scene(scene_file), sets)
                row["scene"] = scene_label
                row["config"] = label
                row["block"] = "%dx%d" % points
                row["_steps"] = read_steps(row)
                row["slide_from"] = slide_from * slide_length
                row.update(oscillation(forces(row, slide_length,
                                              slide_from)))
                done = [s for s in row["_steps"]
                        if s.get("status") != "failed"]
                its = [s.get("newton_iterations", 0) for s in done]
                row["iterations_mean"] = sum(its) / len(its) if its else \
                    float("nan")
                row["iterations_max"] = max(its) if its else 0
                row["steps_done"] = len(done)
                rows.append(row)
    write(args, rows)


def read_steps(row):
    """The load steps of the run's summary.json."""
    import json
    path = os.path.join(row["folder"], "summary.json")
    if not os.path.exists(path):
        return []
    with open(path) as f:
        return json.load(f).get("load_steps", [])


COLUMNS = ["scene", "config", "block", "status", "n_dofs", "steps_done",
           "slide_from",
           "mean_fx", "mean_fy", "fx_jitter_rms", "fx_jitter_max",
           "fy_jitter_rms", "fy_jitter_max", "fy_fit_max", "iterations_mean",
           "iterations_max", "step_cuts", "total_s", "diagnosis"]


def write(args, rows):
    common.write_csv(os.path.join(args.out, "sliding.csv"), rows, COLUMNS)
    table = [[r["scene"], r["config"], r["block"], r.get("n_dofs", "–"),
              "%d%s" % (r.get("steps_done", 0),
                        "" if r["status"] == "ok" else " (%s)" % r["status"]),
              g(r.get("mean_fx")), g(r.get("mean_fy")),
              "%s / %s" % (g(r.get("fx_jitter_rms"), 3),
                           g(r.get("fx_jitter_max"), 3)),
              "%s / %s" % (g(r.get("fy_jitter_rms"), 3),
                           g(r.get("fy_jitter_max"), 3)),
              g(r.get("fy_fit_max"), 3),
              "%s / %s" % (g(r.get("iterations_mean"), 3),
                           r.get("iterations_max", "–")),
              r.get("step_cuts", "–"), g(r.get("total_s"), 4)]
             for r in rows]
    common.write_markdown(
        os.path.join(args.out, "sliding.md"),
        ["scene", "discretisation", "block unknowns per direction",
         "unknowns", "steps done", "mean F_x", "mean F_y", "F_x jitter rms / max (%)",
         "F_y jitter rms / max (%)", "F_y about a quartic, max (%)",
         "Newton it. per step, mean / max", "step cuts", "seconds"],
        table,
        preamble=common.stamp(args) + " The die's support reaction over "
        "the slide from 1 on (frictionless) or 1.25 (mu = 0.3, every "
        "closed pair slipping); jitter: |F(k+1) - 2 F(k) + F(k-1)|, in "
        "per cent of the mean |F_y|; seconds: timing.total of the run "
        "(every phase).",
        notes=common.failure_notes(rows))
    plot(args, rows)


def plot(args, rows):
    plt = common.pyplot()
    if plt is None:
        return
    for scene_label, _, slide_length, _ in SCENES:
        fig, axes = plt.subplots(2, 1, figsize=(8, 7), sharex=True)
        for r in rows:
            if r["scene"] != scene_label:
                continue
            # The slide (the press steps sit at slide 0).
            history = forces(r, slide_length, 1e-9)
            if not history:
                continue
            xs = [h[0] for h in history]
            axes[0].plot(xs, [-h[2] for h in history],
                         label="%s, %s" % (r["config"], r["block"]))
            axes[1].plot(xs, [h[1] for h in history])
        axes[0].set_ylabel("-F_y of the die")
        axes[1].set_ylabel("F_x of the die")
        axes[1].set_xlabel("slide")
        axes[0].legend(fontsize=7)
        axes[0].set_title("Ironing, %s" % scene_label)
        fig.tight_layout()
        common.save_figure(fig, args.out, "ironing-" + (
            "frictionless" if scene_label == "frictionless" else "friction"))
        plt.close(fig)
