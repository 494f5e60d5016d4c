"""B1 cantilever beams: total contact force per method, discretisation,
mesh and friction coefficient (the seed's Table 1)."""

import math
import os

import common
from common import g
from study_b2 import method_sets

B1 = common.scene("b1-cantilever-beams.prm")
B1_MESHES = [(12, 2, 2), (24, 4, 4), (48, 8, 8)]

# (label, discretisation, algorithm, path, FKN, largest mesh index). FE_Q(2)
# on 48x8x8 has 168 198 unknowns (5 min and 5.6 GiB for the BDE alone): out.
CONFIGS = [
    ("NURBS p=2, BDE", "nurbs", "bde", "condensed", None, 2),
    ("NURBS p=2, penalty FKN=1", "nurbs", "penalty", None, 1., 1),
    ("NURBS p=2, augmented Lagrange", "nurbs", "augmented-lagrange", None,
     None, 1),
    ("FE_Q(2), BDE", "lagrange", "bde", "condensed", None, 1),
    ("FE_Q(2), penalty FKN=1", "lagrange", "penalty", None, 1., 1),
    ("FE_Q(2), augmented Lagrange", "lagrange", "augmented-lagrange", None,
     None, 1),
]

COLUMNS = ["mu", "config", "discretization", "algorithm", "mesh", "n_dofs",
           "n_contact_pairs", "status", "newton_iterations",
           "contact_force_x", "contact_force_y", "contact_force_z",
           "rel_diff_x", "rel_diff_y", "rel_diff_z", "rel_diff_norm",
           "max_penetration", "contact_s", "total_s", "process_s",
           "diagnosis"]


def forces(args, runner):
    mus = [0.5] if args.quick else [0., 0.5, 1.]
    n_meshes = 1 if args.quick else len(B1_MESHES)
    rows = []
    for mu in mus:
        block = []
        for label, disc, algorithm, path, fkn, last in CONFIGS:
            for mesh in B1_MESHES[:min(last + 1, n_meshes)]:
                sets = dict(common.mesh_sets(mesh),
                            **method_sets(disc, 2, algorithm, path, fkn))
                sets["Contact/Friction coefficient"] = repr(mu)
                row = runner.run("mu=%g %s %s" % (mu, label,
                                                  common.mesh_label(mesh)),
                                 B1, sets)
                row.update({"mu": mu, "config": label,
                            "mesh": common.mesh_label(mesh),
                            "algorithm": algorithm})
                block.append(row)
        # Reference: NURBS-BDE on the finest mesh run at this mu.
        nurbs = [r for r in block if r["config"] == CONFIGS[0][0] and
                 common.ok(r)]
        if nurbs:
            ref = max(nurbs, key=lambda r: r["n_dofs"])
            f_ref = [ref["contact_force_" + c] for c in "xyz"]
            norm = math.sqrt(sum(x * x for x in f_ref))
            for r in block:
                r["reference"] = "%s %s" % (ref["config"], ref["mesh"])
                if not common.ok(r):
                    continue
                f = [r["contact_force_" + c] for c in "xyz"]
                for c, x, x_ref in zip("xyz", f, f_ref):
                    # A component that vanishes (mu = 0) has no relative
                    # difference.
                    r["rel_diff_" + c] = ((x - x_ref) / abs(x_ref)
                                          if abs(x_ref) > 1e-9 * norm
                                          else float("nan"))
                r["rel_diff_norm"] = math.sqrt(sum(
                    (x - x_ref) ** 2 for x, x_ref in zip(f, f_ref))) / norm
        rows += block
    common.write_csv(os.path.join(args.out, "b1-forces.csv"), rows, COLUMNS)

    with open(os.path.join(args.out, "b1-forces.md"), "w") as f:
        f.write(common.stamp(args) + " B1, total contact force on the upper "
                "beam (N); relative differences to the finest NURBS-BDE "
                "answer of the same μ, per component and of the vector "
                "(|F − F_ref| / |F_ref|).\n")
        for mu in mus:
            block = [r for r in rows if r["mu"] == mu]
            ref = block[0].get("reference", "none (NURBS-BDE failed)")
            f.write("\n#### μ = %g (reference: %s)\n\n" % (mu, ref))
            f.write("| configuration | mesh | DOFs | pairs | status | "
                    "iterations | F_x | F_y | F_z | ΔF_x | ΔF_y | ΔF_z | "
                    "\\|ΔF\\| | total s |\n")
            f.write("|" + "---|" * 14 + "\n")
            for r in block:
                f.write("| %s |\n" % " | ".join([
                    r["config"], r["mesh"], g(r.get("n_dofs")),
                    g(r.get("n_contact_pairs")), r["status"],
                    g(r.get("newton_iterations"))] +
                    [force(r, c) for c in "xyz"] +
                    [pct(r.get("rel_diff_" + c)) for c in "xyz"] +
                    [pct(r.get("rel_diff_norm"), signed=False),
                     g(r.get("total_s"), 3)]))
        f.write(common.failure_notes(rows))

    plt = common.pyplot()
    if plt is None:
        return
    fig, axes = plt.subplots(1, len(mus), figsize=(4.5 * len(mus), 4.2),
                             sharey=True, squeeze=False)
    styles = ["o-", "o--", "o:", "s-", "s--", "s:"]
    for ax, mu in zip(axes[0], mus):
        for (label, *_), style in zip(CONFIGS, styles):
            pts = [(r["n_dofs"], r["rel_diff_norm"]) for r in rows
                   if r["mu"] == mu and r["config"] == label and
                   common.ok(r) and r.get("rel_diff_norm", 0.) > 0.]
            if pts:
                ax.loglog(*zip(*pts), style, label=label)
        ax.set_title("B1, μ = %g" % mu)
        ax.set_xlabel("unknowns (both beams)")
        ax.grid(True, which="both", alpha=0.3)
    axes[0][0].set_ylabel("|F − F_ref| / |F_ref|")
    axes[0][0].legend(fontsize=7)
    fig.tight_layout()
    common.save_figure(fig, args.out, "b1-forces")


def force(row, component):
    """A force component in N for a Markdown cell; rounding noise of a
    component that vanishes (mu = 0) shows as 0."""
    f = [row.get("contact_force_" + c, float("nan")) for c in "xyz"]
    if any(x != x for x in f):
        return "–"
    x = row["contact_force_" + component]
    return "0" if abs(x) < 1e-9 * math.sqrt(sum(y * y for y in f)) \
        else g(x, 6)


def pct(x, signed=True):
    """A relative difference in per cent for a Markdown cell."""
    if x is None or x == "" or (isinstance(x, float) and math.isnan(x)):
        return "–"
    return ("%+.2f %%" if signed else "%.2f %%") % (100. * x)
