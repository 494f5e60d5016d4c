"""Accuracy against cost: error against wall time and unknowns for V5
(Hertz, a disc on a rigid plane), V6 (a disc on an elastic block) and B2
(curved beams), every contact method and degree, each against a converged
model of the same scene computed here, the Pareto front marked and the
time split per phase."""

import os

import common
from common import g
from pressure_reference import Reference, read_pairs
from study_b2 import b2_probe_error, method_sets

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


def pressure_rows(args, runner, scene, name, meshes, last, mesh_sets,
                  mesh_label, reference_mesh):
    """Every discretisation and method of @p scene on @p meshes, the pair
    pressures of each run against those of NURBS p = 3 BDE on
    @p reference_mesh (run first); returns (rows, reference row,
    Reference or None)."""
    reference_row = runner.run(
        "%s reference NURBS p=3 BDE %s" % (name, mesh_label(reference_mesh)),
        scene, dict(mesh_sets(reference_mesh),
                    **method_sets("nurbs", 3, "bde", "condensed")))
    reference = (Reference(read_pairs(reference_row["folder"]))
                 if common.ok(reference_row) else None)
    rows = []
    for dname, disc, degree in DISCRETISATIONS:
        for mname, algorithm, path, fkn in METHODS:
            if args.quick and not (mname == "BDE" and degree == 2):
                continue
            for mesh in meshes[:last[mname] + 1]:
                sets = dict(method_sets(disc, degree, algorithm, path, fkn),
                            **mesh_sets(mesh))
                row = runner.run("%s %s %s %s" % (name, dname, mname,
                                                  mesh_label(mesh)),
                                 scene, sets)
                row.update({"scene": name, "discretisation": dname,
                            "method": mname, "mesh": mesh_label(mesh),
                            "error": float("nan"),
                            "largest_deviation": float("nan"),
                            "error_johnson": float("nan")})
                if common.ok(row):
                    row["error_johnson"] = row.get(
                        "check_pressure_l2_rel_error", float("nan"))
                    if reference is not None:
                        row["error"], row["largest_deviation"] = \
                            reference.errors(read_pairs(row["folder"]))
                rows.append(row)
    return rows, reference_row, reference


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


def accuracy_cost(args, runner):
    rows = []

    # V5 and V6: the L2 distance of the pair pressures to a converged model
    # of the same scene (Johnson's distance beside it).
    v5_meshes = V5_MESHES[:2] if args.quick else V5_MESHES
    v5_rows, v5_ref_row, v5_ref = pressure_rows(
        args, runner, V5, "V5", v5_meshes, V5_LAST,
        lambda mesh: {"Body 1/Subdivisions": "%d, %d" % mesh,
                      "Body 1/Grading": ""},
        common.mesh_label, V5_MESHES[2] if args.quick else V5_REFERENCE_MESH)
    rows += v5_rows
    v6_scales = V6_SCALES[:1] if args.quick else V6_SCALES
    v6_rows, v6_ref_row, v6_ref = pressure_rows(
        args, runner, V6, "V6", v6_scales, V6_LAST, v6_sets, v6_label,
        V6_SCALES[1] if args.quick else V6_REFERENCE_SCALE)
    rows += v6_rows

    # B2: the probe error against NURBS p = 2 with the B-Newton on a mesh
    # finer than every compared run.
    b2_meshes = common.B2_MESHES[:1] if args.quick else common.B2_MESHES
    ref_mesh = common.B2_MESHES[1] if args.quick else B2_REFERENCE_MESH
    reference = runner.run(
        "B2 reference NURBS p=2 BDE %s" % common.mesh_label(ref_mesh), B2,
        dict(common.mesh_sets(ref_mesh),
             **method_sets("nurbs", 2, "bde", "condensed")))
    b2_rows = []
    for dname, disc, degree in DISCRETISATIONS:
        for mname, algorithm, path, fkn in METHODS:
            if args.quick and not (mname == "BDE" and degree == 2):
                continue
            last = B2_LAST.get((dname, mname), 2)
            for mesh in b2_meshes[:last + 1]:
                sets = dict(common.mesh_sets(mesh),
                            **method_sets(disc, degree, algorithm, path, fkn))
                row = runner.run("B2 %s %s %s" % (dname, mname,
                                                  common.mesh_label(mesh)),
                                 B2, sets)
                row.update({"scene": "B2", "discretisation": dname,
                            "method": mname,
                            "mesh": common.mesh_label(mesh)})
                b2_rows.append(row)
    for row in b2_rows:
        row["error"] = (b2_probe_error(row, reference)
                        if common.ok(row) and common.ok(reference)
                        else float("nan"))
    rows += b2_rows

    for r in rows:
        r["config"] = "%s, %s" % (r["discretisation"], r["method"])
    for scene in SCENES:
        sub = [r for r in rows if r["scene"] == scene and common.ok(r) and
               r["error"] == r["error"]]
        for i in common.pareto_front([(r["total_s"], r["error"])
                                      for r in sub]):
            sub[i]["pareto"] = "yes"
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
            f.write("| configuration | mesh | DOFs | status | error | " +
                    ("largest | vs Johnson | " if pressure else "") +
                    "Pareto | iterations | assembly s | factorization s | "
                    "contact s | total s |\n")
            f.write("|" + "---|" * (13 if pressure else 11) + "\n")
            for r in rows:
                if r["scene"] != scene:
                    continue
                f.write("| %s |\n" % " | ".join([
                    r["config"], r["mesh"], g(r.get("n_dofs")), r["status"],
                    g(r.get("error"), 3)] + ([
                        g(r.get("largest_deviation"), 3),
                        g(r.get("error_johnson"), 3)] if pressure else []) + [
                    r.get("pareto", ""),
                    g(r.get("newton_iterations")),
                    g(r.get("t_assembly_s"), 3),
                    g(r.get("t_factorization_s"), 3),
                    g(r.get("contact_s"), 3), g(r.get("total_s"), 3)]))
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
