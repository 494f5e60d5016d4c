"""Accuracy against cost: error against wall time and unknowns for V5
(Hertz, exact pressure profile) and B2 (curved beams, finest NURBS mesh as
reference), every contact method and degree, the Pareto front marked and
the time split per phase."""

import os

import common
from common import g
from study_b2 import b2_probe_error, method_sets

V5 = common.scene("v5-hertz-2d.prm")
B2 = common.scene("b2-curved-beams.prm")

# Spans of the Hertz quarter disc (circumferential, radial); the scene's own
# mesh is 64 x 16.
V5_MESHES = [(16, 4), (32, 8), (64, 16), (128, 32), (256, 64)]
# The Hertz floor of the finite disc (scenes.md): converged finite models sit
# about 1.0 % from Johnson's half-space profile.
V5_FLOOR = 0.010

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
            "n_contact_pairs", "status", "error", "pareto",
            "newton_iterations", "contact_s", "total_s", "process_s"] +
           common.PHASE_KEYS + ["diagnosis"])


def accuracy_cost(args, runner):
    rows = []

    # V5: the scene's L2 relative pressure error against Johnson's profile.
    v5_meshes = V5_MESHES[:2] if args.quick else V5_MESHES
    for dname, disc, degree in DISCRETISATIONS:
        for mname, algorithm, path, fkn in METHODS:
            if args.quick and not (mname == "BDE" and degree == 2):
                continue
            for mesh in v5_meshes[:V5_LAST[mname] + 1]:
                sets = dict(method_sets(disc, degree, algorithm, path, fkn),
                            **{"Body 1/Subdivisions":
                               "%d, %d" % mesh})
                row = runner.run("V5 %s %s %s" % (dname, mname,
                                                  common.mesh_label(mesh)),
                                 V5, sets)
                row.update({"scene": "V5", "discretisation": dname,
                            "method": mname, "mesh": common.mesh_label(mesh),
                            "error": row.get("check_pressure_l2_rel_error",
                                             float("nan"))
                            if common.ok(row) else float("nan")})
                rows.append(row)

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
    for scene in ("V5", "B2"):
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
        f.write(common.stamp(args) + " Error: V5 — the L2 distance of the "
                "pair-pressure profile to Johnson's over |x| ≤ 1.2a "
                "(`checks.pressure_l2_rel_error`; the finite disc's floor is "
                "about 1.0 %); B2 — max over A–D of |u_z − u_z,ref| / "
                "max |u_z,ref| with the reference " + ref_text + ". Seconds: "
                "`timing.total` of summary.json (the phases; the process "
                "adds about 0.8 s of start-up). Pareto: no run is both "
                "faster and more accurate.\n")
        for scene in ("V5", "B2"):
            f.write("\n#### %s\n\n" % scene)
            f.write("| configuration | mesh | DOFs | status | error | "
                    "Pareto | iterations | assembly s | factorization s | "
                    "contact s | total s |\n")
            f.write("|" + "---|" * 11 + "\n")
            for r in rows:
                if r["scene"] != scene:
                    continue
                f.write("| %s |\n" % " | ".join([
                    r["config"], r["mesh"], g(r.get("n_dofs")), r["status"],
                    g(r.get("error"), 3), r.get("pareto", ""),
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
    fig, axes = plt.subplots(2, 2, figsize=(11, 10.5))
    for row_axes, scene in zip(axes, ("V5", "B2")):
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
            if scene == "V5":
                ax.axhline(V5_FLOOR, color="grey", ls="--", lw=0.8,
                           label="finite-disc floor ≈ 1.0 %")
            ax.set_xlabel(xlabel)
            ax.set_ylabel("V5: L2 pressure error" if scene == "V5"
                          else "B2: probe u_z error")
            ax.set_title(scene)
            ax.grid(True, which="both", alpha=0.3)
    # One legend below the panels, where it hides no point.
    handles, labels = axes[0][0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=4, fontsize=7)
    fig.tight_layout(rect=(0, 0.09, 1, 1))
    common.save_figure(fig, args.out, "accuracy-cost")

    # Where the time goes on the Pareto front.
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5))
    shown = [p for p in common.PHASES if p not in ("output", "postprocess")]
    for ax, scene in zip(axes, ("V5", "B2")):
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
    axes[1].legend(fontsize=7)
    fig.tight_layout()
    common.save_figure(fig, args.out, "accuracy-cost-phases")
