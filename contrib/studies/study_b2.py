"""The B2 curved-beam studies: DOFs against elements (the seed's Fig. 11),
probe displacements against DOFs (Fig. 12) and mesh 4 per method (Table
3)."""

import math
import os

import common
from common import g

B2 = common.scene("b2-curved-beams.prm")


def method_sets(discretization, degree, algorithm, path=None, fkn=None):
    """--set entries of one discretisation and contact method."""
    sets = {"Discretization/Type": discretization,
            "Discretization/Degree": str(degree),
            "Contact/Algorithm": algorithm}
    if path is not None:
        sets["Contact/Path"] = path
    if fkn is not None:
        sets["Contact/Penalty factor"] = repr(fkn)
    return sets


def serendipity_dofs(mesh):
    """Unknowns of the 20-node serendipity hexahedron (ANSYS SOLID186/95) on
    a structured nr x nt x ny mesh of one beam: a node at every vertex and
    at the midpoint of every edge, three components each."""
    nr, nt, ny = mesh
    vertices = (nr + 1) * (nt + 1) * (ny + 1)
    edges = (nr * (nt + 1) * (ny + 1) + (nr + 1) * nt * (ny + 1) +
             (nr + 1) * (nt + 1) * ny)
    return 3 * (vertices + edges)


# ---------------------------------------------------------------- b2-dofs

DOFS_COLUMNS = ["mesh", "elements_per_beam", "elements", "nurbs_p2_dofs",
                "fe_q2_dofs", "serendipity20_dofs", "fe_q2_over_nurbs",
                "serendipity20_over_nurbs", "nurbs_status", "fe_q2_status"]


def dofs(args, runner):
    meshes = common.B2_MESHES[:2] if args.quick else common.B2_MESHES
    rows = []
    for mesh in meshes:
        m = common.mesh_label(mesh)
        # The counts do not depend on contact: these runs solve the two
        # beams' elasticity only, which keeps FE_Q(2) on 8x32x8 cheap.
        found = {}
        for disc in ("nurbs", "lagrange"):
            sets = dict(common.mesh_sets(mesh),
                        **{"Discretization/Type": disc,
                           "Discretization/Degree": "2",
                           "Contact/Enabled": "false"})
            found[disc] = runner.run("%s-p2-%s" % (disc, m), B2, sets)
        n_nurbs = found["nurbs"].get("n_dofs", float("nan"))
        n_feq = found["lagrange"].get("n_dofs", float("nan"))
        n_ser = 2 * serendipity_dofs(mesh)
        rows.append({
            "mesh": m,
            "elements_per_beam": mesh[0] * mesh[1] * mesh[2],
            "elements": found["nurbs"].get("n_elements", float("nan")),
            "nurbs_p2_dofs": n_nurbs, "fe_q2_dofs": n_feq,
            "serendipity20_dofs": n_ser,
            "fe_q2_over_nurbs": n_feq / n_nurbs,
            "serendipity20_over_nurbs": n_ser / n_nurbs,
            "nurbs_status": found["nurbs"]["status"],
            "fe_q2_status": found["lagrange"]["status"]})
    common.write_csv(os.path.join(args.out, "b2-dofs.csv"), rows,
                     DOFS_COLUMNS)
    common.write_markdown(
        os.path.join(args.out, "b2-dofs.md"),
        ["mesh per beam (r x θ x y)", "elements (both beams)",
         "NURBS p=2 DOFs", "FE_Q(2) DOFs", "20-node serendipity DOFs",
         "FE_Q(2) / NURBS", "serendipity / NURBS"],
        [[r["mesh"], r["elements"], r["nurbs_p2_dofs"], r["fe_q2_dofs"],
          r["serendipity20_dofs"], "%.2f" % r["fe_q2_over_nurbs"],
          "%.2f" % r["serendipity20_over_nurbs"]] for r in rows],
        preamble=common.stamp(args) + " Both beams; NURBS and FE_Q(2) "
        "from summary.json (`n_dofs`), serendipity in closed form: "
        "3 (V + E) per beam, V = (nr+1)(nθ+1)(ny+1) vertices and "
        "E = nr(nθ+1)(ny+1) + (nr+1)nθ(ny+1) + (nr+1)(nθ+1)ny edges.")

    plt = common.pyplot()
    if plt is None:
        return
    fig, ax = plt.subplots(figsize=(6, 4.5))
    x = [r["elements"] for r in rows]
    for key, style, label in (
            ("nurbs_p2_dofs", "o-", "NURBS p = 2"),
            ("fe_q2_dofs", "s-", "FE_Q(2) (27-node)"),
            ("serendipity20_dofs", "^--", "20-node serendipity")):
        ax.loglog(x, [r[key] for r in rows], style, label=label)
    for r in rows:
        ax.annotate(r["mesh"], (r["elements"], r["nurbs_p2_dofs"]),
                    textcoords="offset points", xytext=(4, -12), fontsize=7)
    ax.set_xlabel("elements (both beams)")
    ax.set_ylabel("unknowns (both beams)")
    ax.set_title("B2: unknowns against elements")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    common.save_figure(fig, args.out, "b2-dofs")


# ------------------------------------------------------- b2-displacements

# (label, discretisation, degree, algorithm, path, FKN, largest mesh index)
DISPLACEMENT_CONFIGS = [
    ("NURBS p=2, BDE", "nurbs", 2, "bde", "condensed", None, 4),
    ("FE_Q(2), BDE", "lagrange", 2, "bde", "condensed", None, 4),
    ("FE_Q(2), penalty FKN=1", "lagrange", 2, "penalty", None, 1., 3),
    ("FE_Q(2), augmented Lagrange", "lagrange", 2, "augmented-lagrange",
     None, None, 2),
]

DISPLACEMENT_COLUMNS = (
    ["config", "discretization", "degree", "algorithm", "mesh", "n_dofs",
     "status", "diagnosis"] +
    ["uz_" + p for p in common.B2_PROBES] +
    ["rel_diff_" + p for p in common.B2_PROBES] +
    ["max_rel_diff", "newton_iterations", "total_s", "process_s"])


def b2_probe_error(row, reference):
    """Largest |u_z - u_z,ref| over A-D relative to the largest |u_z,ref|:
    the B2 error measure of the displacement and accuracy-cost studies."""
    scale = max(abs(reference["uz_" + p]) for p in common.B2_PROBES)
    return max(abs(row.get("uz_" + p, float("nan")) -
                   reference["uz_" + p]) for p in common.B2_PROBES) / scale


def displacements(args, runner):
    n_meshes = 2 if args.quick else len(common.B2_MESHES)
    rows = []
    for label, disc, degree, algorithm, path, fkn, last in \
            DISPLACEMENT_CONFIGS:
        for mesh in common.B2_MESHES[:min(last + 1, n_meshes)]:
            sets = dict(common.mesh_sets(mesh),
                        **method_sets(disc, degree, algorithm, path, fkn))
            row = runner.run("%s %s" % (label, common.mesh_label(mesh)),
                             B2, sets)
            row.update({"config": label, "mesh": common.mesh_label(mesh),
                        "algorithm": algorithm})
            rows.append(row)
    # The reference: NURBS p = 2 with the B-Newton on the finest mesh run.
    nurbs = [r for r in rows if r["config"] == DISPLACEMENT_CONFIGS[0][0]
             and common.ok(r)]
    reference = max(nurbs, key=lambda r: r["n_dofs"]) if nurbs else None
    for r in rows:
        if reference is None or not common.ok(r):
            continue
        for p in common.B2_PROBES:
            r["rel_diff_" + p] = (r["uz_" + p] - reference["uz_" + p]) / \
                abs(reference["uz_" + p])
        r["max_rel_diff"] = b2_probe_error(r, reference)
    common.write_csv(os.path.join(args.out, "b2-displacements.csv"), rows,
                     DISPLACEMENT_COLUMNS)
    ref_text = ("reference: %s on %s" % (reference["config"],
                                        reference["mesh"])
                if reference else "no reference (the NURBS runs failed)")
    common.write_markdown(
        os.path.join(args.out, "b2-displacements.md"),
        ["configuration", "mesh", "DOFs", "status"] +
        ["u_z(%s) mm" % p for p in common.B2_PROBES] +
        ["max rel. diff."],
        [[r["config"], r["mesh"], g(r.get("n_dofs")), r["status"]] +
         [g(1e3 * r.get("uz_" + p, float("nan")), 5)
          for p in common.B2_PROBES] +
         [g(r.get("max_rel_diff"), 2)] for r in rows],
        preamble=common.stamp(args) + " B2, μ = 0.5; z-displacement in mm "
        "at A, B (θ = 45°) and C, D (θ = 90°) on the outer beam's contact "
        "face; max rel. diff. = max over A–D of |u_z − u_z,ref| / "
        "max |u_z,ref|, " + ref_text + ".",
        notes="\n".join("- %s: %s" % (r["label"], r["diagnosis"])
                        for r in rows if r["status"] != "ok"))

    plt = common.pyplot()
    if plt is None:
        return
    fig, axes = plt.subplots(2, 2, figsize=(9, 7), sharex=True)
    styles = ["o-", "s-", "^--", "x:"]
    for ax, p in zip(axes.flat, common.B2_PROBES):
        for (label, *_), style in zip(DISPLACEMENT_CONFIGS, styles):
            pts = [(r["n_dofs"], 1e3 * r["uz_" + p]) for r in rows
                   if r["config"] == label and common.ok(r)]
            if pts:
                ax.semilogx(*zip(*pts), style, label=label)
        if reference:
            ax.axhline(1e3 * reference["uz_" + p], color="k", lw=0.8,
                       ls="--", label="reference (%s)" % reference["mesh"])
        ax.set_title("probe " + p)
        ax.set_ylabel("u_z [mm]")
        ax.grid(True, which="both", alpha=0.3)
    for ax in axes[1]:
        ax.set_xlabel("unknowns (both beams)")
    axes[0][0].legend(fontsize=7)
    fig.suptitle("B2, μ = 0.5: z-displacement at A–D against unknowns")
    fig.tight_layout()
    common.save_figure(fig, args.out, "b2-displacements")


# --------------------------------------------------------------- b2-mesh4

# (label, algorithm, path, FKN)
MESH4_METHODS = [
    ("BDE, condensed", "bde", "condensed", None),
    ("BDE, full", "bde", "full", None),
    ("penalty FKN=0.01", "penalty", None, 0.01),
    ("penalty FKN=1", "penalty", None, 1.),
    ("penalty FKN=10", "penalty", None, 10.),
    ("augmented Lagrange", "augmented-lagrange", None, None),
]

MESH4_COLUMNS = (
    ["discretization", "method", "mesh", "n_dofs", "n_contact_pairs",
     "status", "converged", "newton_iterations", "contact_solves",
     "step_cuts", "contact_s", "total_s", "process_s"] + common.PHASE_KEYS +
    ["max_penetration", "uz_C", "rel_diff_uz_C", "diagnosis"])


def mesh4(args, runner):
    mesh = (2, 2, 2) if args.quick else (8, 16, 8)
    rows = []
    for disc in ("nurbs", "lagrange"):
        for label, algorithm, path, fkn in MESH4_METHODS:
            sets = dict(common.mesh_sets(mesh),
                        **method_sets(disc, 2, algorithm, path, fkn))
            row = runner.run("%s-p2 %s %s" % (disc, label,
                                              common.mesh_label(mesh)),
                             B2, sets)
            row.update({"discretization": disc, "method": label,
                        "mesh": common.mesh_label(mesh),
                        "converged": "yes" if common.ok(row) else "no"})
            rows.append(row)
        # Deviation of each method from the condensed BDE answer of the
        # same discretisation (the penalty's error; the others' agreement).
        base = rows[-len(MESH4_METHODS)]
        for r in rows[-len(MESH4_METHODS):]:
            if common.ok(r) and common.ok(base):
                r["rel_diff_uz_C"] = (r["uz_C"] - base["uz_C"]) / \
                    abs(base["uz_C"])
    common.write_csv(os.path.join(args.out, "b2-mesh4.csv"), rows,
                     MESH4_COLUMNS)
    names = {"nurbs": "NURBS p=2", "lagrange": "FE_Q(2)"}
    common.write_markdown(
        os.path.join(args.out, "b2-mesh4.md"),
        ["discretisation", "method", "DOFs", "pairs", "converged",
         "Newton iterations", "contact s", "total s", "assembly s",
         "factorization s", "max penetration", "u_z(C) vs BDE"],
        [[names[r["discretization"]], r["method"], g(r.get("n_dofs")),
          g(r.get("n_contact_pairs")), r["converged"],
          g(r.get("newton_iterations")), g(r.get("contact_s"), 3),
          g(r.get("total_s"), 3), g(r.get("t_assembly_s"), 3),
          g(r.get("t_factorization_s"), 3),
          g(r.get("max_penetration"), 2) if r.get("max_penetration") else "–",
          ("%+.2g" % r["rel_diff_uz_C"]) if "rel_diff_uz_C" in r else "–"]
         for r in rows],
        preamble=common.stamp(args) + " B2, mesh %s per beam, μ = 0.5. "
        "contact s = pairs + condensation + B-Newton (condensed path) or "
        "coupled system + full-system Newton solves (full path, penalty, "
        "augmented Lagrange); total s = sum of the phases (the process adds "
        "about 0.8 s of start-up)." % common.mesh_label(mesh),
        notes="\n".join("- %s: %s, %s" % (r["label"], r["status"],
                                          r["diagnosis"])
                        for r in rows if r["status"] != "ok"))

    plt = common.pyplot()
    if plt is None:
        return
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5), sharey=True)
    shown = [p for p in common.PHASES if p not in ("output", "postprocess")]
    for ax, disc in zip(axes, ("nurbs", "lagrange")):
        sub = [r for r in rows if r["discretization"] == disc]
        bottom = common.phase_bars(ax, sub, shown)
        for i, r in enumerate(sub):
            if not common.ok(r):
                ax.text(i, bottom[i], r["status"], ha="center",
                        va="bottom", fontsize=7, color="red")
        ax.set_xticks(range(len(sub)))
        ax.set_xticklabels([r["method"] for r in sub], rotation=30,
                           ha="right", fontsize=8)
        ax.set_title("%s, %s" % (names[disc], common.mesh_label(mesh)))
        ax.grid(True, axis="y", alpha=0.3)
    axes[0].set_ylabel("wall seconds per phase")
    axes[1].legend(fontsize=7)
    fig.tight_layout()
    common.save_figure(fig, args.out, "b2-mesh4")
