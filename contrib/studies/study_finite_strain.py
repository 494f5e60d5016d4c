"""Large-deformation benchmarks (doc/studies.md, "Finite strain"):

- elastica: a slender cantilever (L = 10, h = 0.1, nu = 0) under a dead
  end load P = k EI / L^2, against the inextensible Euler-Bernoulli
  elastica (Mattiasson 1981, Table 1; recomputed here by shooting);
- inflation: a thick compressible neo-Hookean cylinder (a = 1, b = 2,
  plane strain) under an internal follower pressure, against the radial
  ODE of the same law (solved here by shooting);
- contact: F3, frictional contact at finite strain on the full path (a
  neo-Hookean half disc pressed onto a neo-Hookean block, then shifted),
  NURBS p = 2 and FE_Q(2) on two meshes against the finest NURBS run, and
  the same scene at small strain beside each: how far the linear answer
  is.

Each runs NURBS p = 2, 3 and FE_Q(2) on a sequence of meshes and tabulates
unknowns, error, Newton iterations and seconds, next to the same mesh's
linear solve (Kinematics = small) for the cost of one linear solve."""

import json
import math
import os

import common
from common import g

ELASTICA = common.scene("f1-elastica.prm")
INFLATION = common.scene("f2-neo-hookean-inflation.prm")
CONTACT = common.scene("f3-finite-partial-slip.prm")

# (label, Discretization/Type, degree)
CONFIGS = [("NURBS p=2", "nurbs", 2), ("NURBS p=3", "nurbs", 3),
           ("FE_Q(2)", "lagrange", 2)]

# Mattiasson (1981), Table 1: (k = P L^2 / EI, horizontal u/L, vertical
# w/L) of the tip of a cantilever under a dead end load.
MATTIASSON = {1.: (0.05643, 0.30172), 2.: (0.16064, 0.49346),
              5.: (0.38763, 0.71379), 10.: (0.55500, 0.81061)}


def rk4(f, y, s0, s1, n):
    """y(s1) of y' = f(s, y), y(s0) = y, by n classical Runge-Kutta
    steps."""
    h = (s1 - s0) / n
    s = s0
    for _ in range(n):
        k1 = f(s, y)
        k2 = f(s + h / 2, [a + h / 2 * b for a, b in zip(y, k1)])
        k3 = f(s + h / 2, [a + h / 2 * b for a, b in zip(y, k2)])
        k4 = f(s + h, [a + h * b for a, b in zip(y, k3)])
        y = [a + h / 6 * (b + 2 * c + 2 * d + e)
             for a, b, c, d, e in zip(y, k1, k2, k3, k4)]
        s += h
    return y


def bisect(f, low, high, n=200):
    """A root of f in [low, high] where f changes sign."""
    f_low = f(low)
    for _ in range(n):
        mid = 0.5 * (low + high)
        if (f(mid) > 0.) == (f_low > 0.):
            low, f_low = mid, f(mid)
        else:
            high = mid
    return 0.5 * (low + high)


def elastica_tip(k):
    """(u/L, w/L) of the tip of the inextensible cantilever under the dead
    end load k = P L^2 / EI: theta'' = -k cos(theta) on s in [0, 1],
    theta(0) = 0, theta'(1) = 0, shooting on theta'(0)."""
    def end(kappa0, n):
        def f(_, y):
            return [y[1], -k * math.cos(y[0]), math.cos(y[0]),
                    math.sin(y[0])]
        return rk4(f, [0., kappa0, 0., 0.], 0., 1., n)
    kappa0 = bisect(lambda c: end(c, 400)[1], 0., k)
    y = end(kappa0, 4000)
    return 1. - y[2], y[3]


def inflation_radii(E, nu, a, b, p):
    """(r(a) - a, r(b) - b) of the plane-strain compressible neo-Hookean
    cylinder a <= R <= b with the pressure p on the current inner surface
    and a free outer one: W = mu/2 (l1^2 + l2^2 - 2) - mu ln J
    + lambda/2 (ln J)^2, l1 = dr/dR, l2 = r/R, J = l1 l2; the nominal
    stresses P_i = dW/dl_i satisfy dP_1/dR + (P_1 - P_2)/R = 0, with
    P_1(a) = -p l2(a) (the Cauchy sigma_rr = -p) and P_1(b) = 0."""
    mu = E / (2. * (1. + nu))
    lam = E * nu / ((1. + nu) * (1. - 2. * nu))

    def P(l1, l2):
        lnJ = math.log(l1 * l2)
        return (mu * (l1 - 1. / l1) + lam * lnJ / l1,
                mu * (l2 - 1. / l2) + lam * lnJ / l2)

    def dP1(l1, l2):
        lnJ = math.log(l1 * l2)
        return (mu * (1. + 1. / l1 ** 2) + lam * (1. - lnJ) / l1 ** 2,
                lam / (l1 * l2))

    def outer(r_a, n=2000):
        l2 = r_a / a
        l1 = bisect(lambda x: P(x, l2)[0] + p * l2, 1e-3, 10.)

        def f(R, y):
            r, l1 = y
            l2 = r / R
            P1, P2 = P(l1, l2)
            d11, d12 = dP1(l1, l2)
            dl2 = (l1 - l2) / R
            return [l1, (-(P1 - P2) / R - d12 * dl2) / d11]
        r_b, l1_b = rk4(f, [r_a, l1], a, b, n)
        return r_b, P(l1_b, r_b / b)[0]

    r_a = bisect(lambda x: outer(x, 400)[1], a, a * 4.)
    r_b = outer(r_a)[0]
    return r_a - a, r_b - b


def newton_iterations(summary_steps):
    return sum(s.get("finite_strain", {}).get("newton_iterations", 0)
               for s in summary_steps)


def run_family(args, runner, name, scene, meshes, sets_of, error_of,
               reference_text, columns, quantity):
    """Every configuration on every mesh, finite and (the same mesh) small
    strain; rows with the error and the costs."""
    rows = []
    for label, disc, degree in CONFIGS:
        for mesh in meshes:
            sets = dict(sets_of(mesh))
            sets["Discretization/Type"] = disc
            sets["Discretization/Degree"] = str(degree)
            row = runner.run("%s %s %s" % (name, label, mesh), scene, sets)
            linear = runner.run(
                "%s %s %s linear" % (name, label, mesh), scene,
                dict(sets, **{"Body 1/Kinematics": "small",
                              "Body 1/Material": "linear",
                              "Load path/Number of steps": "1"}))
            row.update({"config": label, "mesh": mesh})
            if common.ok(row):
                row.update(error_of(row))
                summary_steps = runner_steps(row)
                row["newton_iterations"] = newton_iterations(summary_steps)
                row["load_steps"] = len(summary_steps)
                row["t_newton_s"] = row.get("t_newton_s", 0.)
                row["s_per_iteration"] = (row["t_newton_s"] /
                                          max(row["newton_iterations"], 1))
            if common.ok(linear):
                row["linear_solve_s"] = (linear.get("t_assembly_s", 0.) +
                                         linear.get("t_factorization_s", 0.))
                row["iteration_per_linear"] = (
                    row.get("s_per_iteration", float("nan")) /
                    row["linear_solve_s"] if row["linear_solve_s"] > 0.
                    else float("nan"))
            rows.append(row)
    common.write_csv(os.path.join(args.out, name + ".csv"), rows, columns)
    header = ["discretisation", "mesh", "unknowns", quantity,
              "error", "load steps", "Newton iterations", "Newton s",
              "s per iteration", "one linear solve s", "total s"]
    table = []
    for r in rows:
        table.append([r["config"], r["mesh"], g(r.get("n_dofs")),
                      g(r.get("value"), 6), g(r.get("error"), 3),
                      g(r.get("load_steps")), g(r.get("newton_iterations")),
                      g(r.get("t_newton_s"), 3),
                      g(r.get("s_per_iteration"), 3),
                      g(r.get("linear_solve_s"), 3),
                      g(r.get("total_s"), 3)])
    common.write_markdown(
        os.path.join(args.out, name + ".md"), header, table,
        preamble=common.stamp(args) + " " + reference_text,
        notes="Newton s: the phase 'newton' of summary.json (residual and "
              "tangent assembly on all cores, UMFPACK factorisations and "
              "solves). One linear solve: the phases 'assembly' and "
              "'factorization' of the same mesh at Kinematics = small "
              "(MUMPS, with its load cases)." +
              common.failure_notes(rows))
    plot(args, rows, name, quantity)
    return rows


def runner_steps(row):
    """The load steps of a finished run, read back from its folder."""
    with open(os.path.join(row["folder"], "summary.json")) as f:
        return json.load(f).get("load_steps", [])


def plot(args, rows, name, quantity):
    plt = common.pyplot()
    if plt is None:
        return
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    for label, _, _ in CONFIGS:
        mine = [r for r in rows if r["config"] == label and common.ok(r)]
        if not mine:
            continue
        left.loglog([r["n_dofs"] for r in mine],
                    [max(r["error"], 1e-16) for r in mine], "o-",
                    label=label)
        right.loglog([r["total_s"] for r in mine],
                     [max(r["error"], 1e-16) for r in mine], "o-",
                     label=label)
    left.set_xlabel("unknowns")
    right.set_xlabel("wall seconds (whole run)")
    for ax in (left, right):
        ax.set_ylabel("relative error of " + quantity)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
    fig.tight_layout()
    common.save_figure(fig, args.out, name)
    plt.close(fig)


COLUMNS = ["config", "discretization", "degree", "mesh", "n_dofs",
           "status", "value", "reference", "error", "load_steps",
           "newton_iterations", "step_cuts", "t_newton_s",
           "s_per_iteration", "linear_solve_s", "iteration_per_linear",
           "total_s", "process_s", "diagnosis"]


def elastica(args, runner):
    k = 5.
    u_ref, w_ref = elastica_tip(k)
    published = MATTIASSON[k]
    meshes = ["16,1", "32,2"] if args.quick else \
        ["16,1", "32,2", "64,2", "128,4"]

    def error_of(row):
        w = -row["uy_tip"] / 10.
        return {"value": w, "reference": w_ref,
                "error": abs(w - w_ref) / w_ref}
    run_family(
        args, runner, "elastica", ELASTICA, meshes,
        lambda mesh: {"Body 1/Subdivisions": mesh}, error_of,
        "Cantilever L = 10, h = 0.1, E = 1.2e7, nu = 0 (plane strain, "
        "neo-Hookean), dead end load P = %g (k = PL²/EI = %g) in 10 load "
        "steps; the tip's deflection w/L at mid-height against the "
        "inextensible elastica, w/L = %.5f by shooting here (Mattiasson "
        "1981, Table 1: %.5f; u/L = %.5f here, %.5f there)."
        % (k * 1000. / 100., k, w_ref, published[1], u_ref, published[0]),
        COLUMNS, "w/L")


def inflation(args, runner):
    p = 150.
    ua, ub = inflation_radii(1000., 0.3, 1., 2., p)
    meshes = ["1", "2"] if args.quick else ["1", "2", "3", "4"]

    def error_of(row):
        u = row["ux_inner"]
        return {"value": u, "reference": ua, "error": abs(u - ua) / ua,
                "outer_error": abs(row["ux_outer"] - ub) / ub}
    run_family(
        args, runner, "inflation", INFLATION, meshes,
        lambda mesh: {"Discretization/Refinements": mesh}, error_of,
        "Thick cylinder a = 1, b = 2, E = 1000, nu = 0.3 (plane strain, "
        "compressible neo-Hookean), internal follower pressure p = %g in "
        "10 load steps; the inner radial displacement against the radial "
        "ODE of the same law solved by shooting here: u(a) = %.6f, "
        "u(b) = %.6f; mesh = Discretization/Refinements of the quarter "
        "annulus." % (p, ua, ub),
        COLUMNS, "u(a)")


CONTACT_COLUMNS = ["config", "refinements", "n_dofs", "status",
                   "contact_force_x", "contact_force_y", "difference",
                   "linear_force_y", "linear_departure", "min_det_F",
                   "largest_stretch", "largest_sliding",
                   "newton_iterations", "linear_newton_iterations",
                   "contact_s", "linear_contact_s", "total_s",
                   "diagnosis"]

SMALL_STRAIN = {"Body 1/Kinematics": "small", "Body 1/Material": "linear",
                "Body 2/Kinematics": "small", "Body 2/Material": "linear"}


def contact(args, runner):
    """F3 at finite and at small strain, NURBS p = 2 and FE_Q(2); the final
    normal force against the finest NURBS run at finite strain."""
    refinements = ["0"] if args.quick else ["0", "1"]
    configs = [("NURBS p=2", "nurbs"), ("FE_Q(2)", "lagrange")]
    rows = []
    for label, disc in configs:
        for r in refinements:
            sets = {"Discretization/Type": disc,
                    "Discretization/Refinements": r}
            row = runner.run("contact %s %s" % (label, r), CONTACT, sets)
            linear = runner.run("contact %s %s linear" % (label, r),
                                CONTACT, dict(sets, **SMALL_STRAIN))
            row.update({"config": label, "refinements": r})
            if common.ok(row):
                steps = runner_steps(row)
                last = steps[-1]
                row["min_det_F"] = min(
                    s.get("finite_strain", {}).get("min_det_F", 1.)
                    for s in steps)
                row["largest_sliding"] = last.get("largest_sliding")
                with open(os.path.join(row["folder"], "summary.json")) as f:
                    stresses = json.load(f).get("point_stresses", {})
                row["largest_stretch"] = stresses.get("contact", {}).get(
                    "largest_stretch")
            if common.ok(linear):
                row["linear_force_y"] = linear["contact_force_y"]
                row["linear_newton_iterations"] = \
                    linear["newton_iterations"]
                row["linear_contact_s"] = linear["contact_s"]
            rows.append(row)
    finest = [r for r in rows if r["config"] == configs[0][0] and
              r["refinements"] == refinements[-1] and common.ok(r)]
    reference = finest[0]["contact_force_y"] if finest else float("nan")
    for r in rows:
        if common.ok(r):
            r["difference"] = abs(r["contact_force_y"] - reference) / \
                reference
            if "linear_force_y" in r:
                r["linear_departure"] = (r["linear_force_y"] -
                                         r["contact_force_y"]) / \
                    r["contact_force_y"]
    common.write_csv(os.path.join(args.out, "contact.csv"), rows,
                     CONTACT_COLUMNS)
    header = ["discretisation", "refinements", "unknowns", "F_x", "F_y",
              "F_y against the finest NURBS", "F_y small strain",
              "small against finite", "smallest det F",
              "largest stretch at (0, 0.1)", "largest sliding",
              "Newton iterations (finite / small)",
              "contact s (finite / small)", "total s"]
    table = []
    for r in rows:
        table.append([r["config"], r["refinements"], g(r.get("n_dofs")),
                      g(r.get("contact_force_x"), 6),
                      g(r.get("contact_force_y"), 6),
                      g(r.get("difference"), 3),
                      g(r.get("linear_force_y"), 6),
                      g(r.get("linear_departure"), 3),
                      g(r.get("min_det_F"), 4),
                      g(r.get("largest_stretch"), 4),
                      g(r.get("largest_sliding"), 3),
                      "%s / %s" % (g(r.get("newton_iterations")),
                                   g(r.get("linear_newton_iterations"))),
                      "%s / %s" % (g(r.get("contact_s"), 3),
                                   g(r.get("linear_contact_s"), 3)),
                      g(r.get("total_s"), 3)])
    common.write_markdown(
        os.path.join(args.out, "contact.md"), header, table,
        preamble=common.stamp(args) + " F3: neo-Hookean half disc R = 8 "
        "on a neo-Hookean block, E = 1000, nu = 0.3, mu = 0.5, "
        "weighted-gap pairs, the diameter pushed down by 1.2 in two steps "
        "then shifted by 0.16 in four; the forces on the disc at the last "
        "step. Reference: the finest NURBS run at finite strain (no "
        "published value for this scene).",
        notes="Newton iterations: the contact solves' (at finite strain "
        "one iteration solves contact and material together). contact s: "
        "the phases 'contact: *' of summary.json, which at finite strain "
        "include the bodies' residual and tangent assembly in every "
        "iteration." + common.failure_notes(rows))
    return rows


def finite_strain(args, runner):
    elastica(args, runner)
    inflation(args, runner)
    contact(args, runner)
