"""Accuracy against cost: error against wall time and unknowns for V5
(Hertz, a disc on a rigid plane), V6 (a disc on an elastic block) and B2
(curved beams), every contact method and degree, each against a converged
model of the same scene computed here, the Pareto front marked and the
time split per phase. Each scene is a sweep.Study (series: discretisation
and method; levels: the meshes; reference: one run made first), run and
compared by sweep.run_study, the code of `contrib/studies/run sweep`."""

import os

import common
import sweep
from common import g
from study_b2 import method_sets

V5 = common.scene("v5-hertz-2d.prm")
V6 = common.scene("v6-cylinder-on-block.prm")
B2 = common.scene("b2-curved-beams.prm")

# Spans of the Hertz quarter disc (circumferential, radial); the scene's own
# mesh is 64 x 16. The reference: NURBS p = 3 on twice the finest mesh.
V5_MESHES = [(16, 4), (32, 8), (64, 16), (128, 32), (256, 64)]
V5_REFERENCE_MESH = (512, 128)
# V6: the scene's spans (disc 116 x 16, block 140 x 32) times these scales;
# the reference: NURBS p = 3 at twice the finest.
V6_SCALES = [0.25, 0.5, 1, 2]
V6_REFERENCE_SCALE = 4

DISCRETISATIONS = [("NURBS p=2", "nurbs", 2), ("NURBS p=3", "nurbs", 3),
                   ("FE_Q(1)", "lagrange", 1), ("FE_Q(2)", "lagrange", 2)]
METHODS = [("BDE", "bde", "condensed", None),
           ("penalty FKN=1", "penalty", None, 1.),
           ("augmented Lagrange", "augmented-lagrange", None, None)]

# Largest mesh index per (discretisation, method): the full-system methods
# factorise the whole coupled matrix at every Newton step, so they stop one
# or two meshes earlier (the accuracy they reach there is already below the
# BDE's on the same mesh or equal to it).
V5_LAST = {"BDE": 4, "penalty FKN=1": 3, "augmented Lagrange": 3}
V6_LAST = {"BDE": 3, "penalty FKN=1": 2, "augmented Lagrange": 2}
B2_LAST = {("NURBS p=2", "BDE"): 3, ("NURBS p=3", "BDE"): 3,
           ("FE_Q(1)", "BDE"): 3, ("FE_Q(2)", "BDE"): 3,
           ("NURBS p=2", "penalty FKN=1"): 3,
           ("NURBS p=3", "penalty FKN=1"): 2,
           ("FE_Q(1)", "penalty FKN=1"): 3,
           ("FE_Q(2)", "penalty FKN=1"): 2,
           ("NURBS p=2", "augmented Lagrange"): 2,
           ("NURBS p=3", "augmented Lagrange"): 2,
           ("FE_Q(1)", "augmented Lagrange"): 2,
           ("FE_Q(2)", "augmented Lagrange"): 2}
B2_REFERENCE_MESH = (8, 32, 8)

COLUMNS = (["scene", "discretisation", "method", "config", "mesh", "n_dofs",
            "n_contact_pairs", "status", "error", "largest_deviation",
            "error_johnson", "pareto",
            "newton_iterations", "contact_s", "total_s", "process_s"] +
           common.PHASE_KEYS + ["diagnosis"])


def v6_mesh(scale):
    """(disc spans, block spans) of V6 at @p scale of the scene's."""
    return ((round(116 * scale), round(16 * scale)),
            (round(140 * scale), round(32 * scale)))


def v6_sets(scale):
    disc, block = v6_mesh(scale)
    return {"Body 1/Subdivisions": "%d, %d" % disc,
            "Body 2/Subdivisions": "%d, %d" % block}


def v6_label(scale):
    disc, block = v6_mesh(scale)
    return "%s+%s" % (common.mesh_label(disc), common.mesh_label(block))


def scene_study(args, name, scene, meshes, last, mesh_sets, mesh_label,
                reference_label, reference_sets, quantities, shown=(),
                error_mode="each"):
    """The study of one scene (sweep.Study): every discretisation with
    every method (BDE with degree 2 only under --quick) is a series, its
    meshes the levels up to @p last (index per method, or per
    (discretisation, method)), against one reference run made first."""
    series = []
    for dname, disc, degree in DISCRETISATIONS:
        for mname, algorithm, path, fkn in METHODS:
            if args.quick and not (mname == "BDE" and degree == 2):
                continue
            n = last.get((dname, mname), last.get(mname, 2))
            series.append(sweep.Series(
                "%s, %s" % (dname, mname),
                method_sets(disc, degree, algorithm, path, fkn),
                [sweep.Level(mesh_label(m), mesh_sets(m),
                             {"mesh": mesh_label(m)})
                 for m in meshes[:n + 1]],
                {"scene": name, "discretisation": dname, "method": mname,
                 "config": "%s, %s" % (dname, mname)},
                run_label="%s %s" % (dname, mname)))
    return sweep.Study(name, scene, {}, series, quantities,
                       sweep.ReferenceSpec("run", sets=reference_sets,
                                           label=reference_label),
                       shown=shown, error_mode=error_mode)


def pressure_study(args, name, scene, meshes, last, mesh_sets, mesh_label,
                   reference_mesh):
    """V5 and V6: the pair pressures of each run against those of NURBS
    p = 3 BDE on @p reference_mesh (pressure_reference.py), Johnson's
    distance (checks.pressure_l2_rel_error) beside them."""
    return scene_study(
        args, name, scene, meshes, last, mesh_sets, mesh_label,
        "reference NURBS p=3 BDE %s" % mesh_label(reference_mesh),
        dict(mesh_sets(reference_mesh),
             **method_sets("nurbs", 3, "bde", "condensed")),
        [sweep.PressureProfile("pressure_l2", largest="largest_deviation")],
        shown=[sweep.Quantity("checks.pressure_l2_rel_error",
                              "error_johnson")])


SCENES = ("V5", "V6", "B2")


def pressure_reference_text(name, reference_row, reference, rows):
    """What a pressure reference is, and how far the same configuration one
    mesh coarser lies from it (its own change under refinement)."""
    if reference is None:
        return "%s: the reference run %s: %s" % (
            name, reference_row["status"], reference_row["diagnosis"])
    coarser = [r for r in rows if r["scene"] == name and common.ok(r) and
               r["discretisation"] == "NURBS p=3" and r["method"] == "BDE"]
    change = ("; NURBS p=3 BDE one refinement coarser (%s) is %s from it" %
              (coarser[-1]["mesh"], g(coarser[-1]["error"], 3))
              if coarser else "")
    return "%s: NURBS p=3 BDE on %s, %d unknowns, %s s, half-width %s%s" % (
        name, reference_row["label"].split()[-1], reference_row["n_dofs"],
        g(reference_row["total_s"], 3), g(reference.half_width, 4), change)


def v5_sets(mesh):
    return {"Body 1/Subdivisions": "%d, %d" % mesh, "Body 1/Grading": ""}


def accuracy_cost(args, runner):
    # V5 and V6: the L2 distance of the pair pressures to a converged model
    # of the same scene (Johnson's distance beside it).
    v5 = pressure_study(
        args, "V5", V5, V5_MESHES[:2] if args.quick else V5_MESHES, V5_LAST,
        v5_sets, common.mesh_label,
        V5_MESHES[2] if args.quick else V5_REFERENCE_MESH)
    v6 = pressure_study(
        args, "V6", V6, V6_SCALES[:1] if args.quick else V6_SCALES, V6_LAST,
        v6_sets, v6_label, V6_SCALES[1] if args.quick else V6_REFERENCE_SCALE)
    # B2: the probe error against NURBS p = 2 with the B-Newton on a mesh
    # finer than every compared run: max over A-D of |u_z - u_z,ref| over
    # max |u_z,ref| (study_b2.b2_probe_error), the 'common' error.
    ref_mesh = common.B2_MESHES[1] if args.quick else B2_REFERENCE_MESH
    b2 = scene_study(
        args, "B2", B2, common.B2_MESHES[:1] if args.quick
        else common.B2_MESHES, B2_LAST, common.mesh_sets, common.mesh_label,
        "reference NURBS p=2 BDE %s" % common.mesh_label(ref_mesh),
        dict(common.mesh_sets(ref_mesh),
             **method_sets("nurbs", 2, "bde", "condensed")),
        [sweep.Quantity("points.%s.2" % p, "uz_" + p)
         for p in common.B2_PROBES], error_mode="common")

    results = {}
    rows = []
    for study in (v5, v6, b2):
        res = sweep.run_study(study, runner)
        for r in res.rows:
            r["scene"] = study.name
        results[study.name] = res
        rows += res.rows
    v5_ref_row = results["V5"].reference_row
    v6_ref_row = results["V6"].reference_row
    v5_ref = v5.quantities[0].reference
    v6_ref = v6.quantities[0].reference
    reference = results["B2"].reference_row
    common.write_csv(os.path.join(args.out, "accuracy-cost.csv"), rows,
                     COLUMNS)

    ref_text = ("NURBS p=2, BDE on %s (%d unknowns): u_z(A–D) = %s mm" % (
        common.mesh_label(ref_mesh), reference.get("n_dofs", 0),
        ", ".join(g(1e3 * reference.get("uz_" + p, float("nan")), 5)
                  for p in common.B2_PROBES))
        if common.ok(reference) else
        "the reference run %s: %s" % (reference["status"],
                                      reference["diagnosis"]))
    with open(os.path.join(args.out, "accuracy-cost.md"), "w") as f:
        f.write(common.stamp(args) + " Error: V5 and V6 — the L2 distance "
                "of the pair pressures to those of a converged model of the "
                "same scene (" + pressure_reference_text("V5", v5_ref_row,
                                                         v5_ref, rows) +
                "; " + pressure_reference_text("V6", v6_ref_row, v6_ref,
                                               rows) +
                "), weighted by the pairs' areas over |x| ≤ 2 a_ref, with "
                "the largest single-pair deviation in units of the "
                "reference's peak and, beside them, the L2 distance to "
                "Johnson's half-space profile over |x| ≤ 1.2a "
                "(`checks.pressure_l2_rel_error`; converged models of the "
                "finite bodies stay about 1 % from it); B2 — max over A–D "
                "of |u_z − u_z,ref| / max |u_z,ref| with the reference " +
                ref_text + ". Seconds: `timing.total` of summary.json (the "
                "phases; the process adds about 0.8 s of start-up). "
                "Pareto: no run is both faster and more accurate.\n")
        for scene in SCENES:
            pressure = scene != "B2"
            f.write("\n#### %s\n\n" % scene)
            sweep.write_table(
                f, [r for r in rows if r["scene"] == scene],
                [("configuration", lambda r: r["config"]),
                 ("mesh", lambda r: r["mesh"]),
                 ("DOFs", lambda r: g(r.get("n_dofs"))),
                 ("status", lambda r: r["status"]),
                 ("error", lambda r: g(r.get("error"), 3))] +
                ([("largest", lambda r: g(r.get("largest_deviation"), 3)),
                  ("vs Johnson", lambda r: g(r.get("error_johnson"), 3))]
                 if pressure else []) +
                [("Pareto", lambda r: r.get("pareto", "")),
                 ("iterations", lambda r: g(r.get("newton_iterations"))),
                 ("assembly s", lambda r: g(r.get("t_assembly_s"), 3)),
                 ("factorization s",
                  lambda r: g(r.get("t_factorization_s"), 3)),
                 ("contact s", lambda r: g(r.get("contact_s"), 3)),
                 ("total s", lambda r: g(r.get("total_s"), 3))])
        f.write(common.failure_notes(rows))

    plt = common.pyplot()
    if plt is None:
        return
    colours = {"NURBS p=2": "tab:blue", "NURBS p=3": "tab:purple",
               "FE_Q(1)": "tab:orange", "FE_Q(2)": "tab:red"}
    markers = {"BDE": "o-", "penalty FKN=1": "s--",
               "augmented Lagrange": "^:"}
    fig, axes = plt.subplots(3, 2, figsize=(11, 15))
    for row_axes, scene in zip(axes, SCENES):
        sub = [r for r in rows if r["scene"] == scene and common.ok(r) and
               r["error"] == r["error"] and r["error"] > 0.]
        for ax, key, xlabel in ((row_axes[0], "total_s", "wall seconds "
                                 "(sum of the phases)"),
                                (row_axes[1], "n_dofs", "unknowns")):
            for dname, *_ in DISCRETISATIONS:
                for mname in markers:
                    pts = sorted((r[key], r["error"]) for r in sub
                                 if r["discretisation"] == dname and
                                 r["method"] == mname)
                    if pts:
                        ax.loglog(*zip(*pts), markers[mname],
                                  color=colours[dname], ms=4,
                                  label="%s, %s" % (dname, mname))
            if key == "total_s":
                front = sorted((r[key], r["error"]) for r in sub
                               if r.get("pareto") == "yes")
                if front:
                    ax.step(*zip(*front), where="post", color="k", lw=1.5,
                            alpha=0.6, label="Pareto front")
                    ax.plot(*zip(*front), "ko", mfc="none", ms=9)
            ax.set_xlabel(xlabel)
            ax.set_ylabel("B2: probe u_z error" if scene == "B2" else
                          "%s: L2 pressure error vs converged model" % scene)
            ax.set_title(scene)
            ax.grid(True, which="both", alpha=0.3)
    # One legend below the panels, where it hides no point.
    handles, labels = axes[0][0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=4, fontsize=7)
    fig.tight_layout(rect=(0, 0.09, 1, 1))
    common.save_figure(fig, args.out, "accuracy-cost")

    # Where the time goes on the Pareto front.
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.5))
    shown = [p for p in common.PHASES if p not in ("output", "postprocess")]
    for ax, scene in zip(axes, SCENES):
        front = sorted((r for r in rows if r["scene"] == scene and
                        r.get("pareto") == "yes"),
                       key=lambda r: r["total_s"])
        common.phase_bars(ax, front, shown)
        ax.set_xticks(range(len(front)))
        ax.set_xticklabels(["%s %s\n%s" % (r["config"], r["mesh"],
                                           g(r["error"], 2))
                            for r in front], rotation=45, ha="right",
                           fontsize=6)
        ax.set_title("%s: seconds per phase on the Pareto front" % scene)
        ax.set_ylabel("wall seconds")
        ax.grid(True, axis="y", alpha=0.3)
    axes[2].legend(fontsize=7)
    fig.tight_layout()
    common.save_figure(fig, args.out, "accuracy-cost-phases")
