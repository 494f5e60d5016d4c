#!/usr/bin/python3
"""Unit test of the general study driver's arithmetic
(contrib/studies/sweep.py), without igabde: the Richardson extrapolation
against sequences q(h) = q* + C h^p of known limit and order (equal and
unequal mesh ratios), the cases it must refuse, the summary.json paths,
the value lists of --sweep, the parameter names, and the errors, reference
and Pareto marks of compare() on made-up rows whose answers are known by
hand.

Usage: tests/studies_sweep_unit_test.py"""

import math
import os
import random
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "contrib", "studies"))

import common  # noqa: E402
import sweep  # noqa: E402

failures = []


def check(condition, what):
    if not condition:
        failures.append(what)


def close(a, b, tol):
    return abs(a - b) <= tol * max(1., abs(b))


def refuses(points, word):
    try:
        sweep.richardson(points)
    except ValueError as e:
        return word in str(e)
    return False


def test_richardson():
    # Halving h: q = 2.5 + 0.7 h^2 at h = 0.4, 0.2, 0.1.
    pts = [(h, 2.5 + 0.7 * h * h) for h in (0.4, 0.2, 0.1)]
    limit, p = sweep.richardson(pts)
    check(close(limit, 2.5, 1e-12), "h-halving limit %r, want 2.5" % limit)
    check(close(p, 2., 1e-9), "h-halving order %r, want 2" % p)
    # The order of the points does not matter.
    limit2, p2 = sweep.richardson(list(reversed(pts)))
    check(limit2 == limit and p2 == p, "point order changes the answer")
    # Unequal ratios (V7's spans 10, 14, 20) and a decreasing sequence.
    pts = [(1. / n, 35.25 - 4. * (1. / n) ** 1.7) for n in (10, 14, 20)]
    limit, p = sweep.richardson(pts)
    check(close(limit, 35.25, 1e-10), "unequal-ratio limit %r" % limit)
    check(close(p, 1.7, 1e-8), "unequal-ratio order %r" % p)
    # Many random sequences of known limit and order.
    rnd = random.Random(75)
    worst_limit = worst_order = 0.
    for _ in range(500):
        h3 = rnd.uniform(1e-3, 1.)
        h2 = h3 * rnd.uniform(1.15, 3.)
        h1 = h2 * rnd.uniform(1.15, 3.)
        p = rnd.uniform(0.5, 6.)
        c = rnd.choice((-1., 1.)) * 10. ** rnd.uniform(-3., 3.)
        q = rnd.uniform(-100., 100.)
        pts = [(h, q + c * h ** p) for h in (h1, h2, h3)]
        limit, order = sweep.richardson(pts)
        scale = abs(c) * h1 ** p + abs(q)
        worst_limit = max(worst_limit, abs(limit - q) / scale)
        worst_order = max(worst_order, abs(order - p) / p)
    check(worst_limit < 1e-9, "random sequences: limit off by %g" %
          worst_limit)
    # The order is found from differences of the q, which lose the digits
    # of |q| / |C h^p| (up to 1e5 here): 1e-5, not round-off.
    check(worst_order < 1e-5, "random sequences: order off by %g" %
          worst_order)
    # What it must refuse.
    check(refuses([(0.4, 1.), (0.2, 1.2), (0.1, 1.1)], "not monotone"),
          "a non-monotone sequence is not refused")
    check(refuses([(0.4, 1.), (0.2, 1.1), (0.1, 1.3)], "does not shrink"),
          "a sequence whose change grows is not refused")
    check(refuses([(0.4, 1.), (0.2, 1.1)], "three"), "two points accepted")
    check(refuses([(0.2, 1.), (0.2, 1.1), (0.1, 1.3)], "different"),
          "equal mesh sizes accepted")
    limit, p = sweep.richardson([(0.4, 3.), (0.2, 3.), (0.1, 3.)])
    check(limit == 3. and math.isnan(p), "a constant sequence: %r, %r" %
          (limit, p))


def test_lookup():
    s = {"checks": {"hertz_peak_pressure": 35.1, "bad": None},
         "points": {"A": [0., -1., -2.5]},
         "load_steps": [{"residual": 1e-9}, {"residual": 3e-12}],
         "scene": "x"}
    check(sweep.lookup(s, "checks.hertz_peak_pressure") == 35.1,
          "checks path")
    check(sweep.lookup(s, "points.A.2") == -2.5, "probe component path")
    check(sweep.lookup(s, "load_steps.-1.residual") == 3e-12,
          "negative index path")
    check(math.isnan(sweep.lookup(s, "checks.bad")), "null is not nan")
    for path, word in (("checks.nope", "hertz_peak_pressure"),
                       ("points.A.7", "3 entries"), ("scene", "number"),
                       ("checks.hertz_peak_pressure.x", "value")):
        try:
            sweep.lookup(s, path)
            failures.append("%s did not fail" % path)
        except KeyError as e:
            check(word in e.args[0], "%s: message %r lacks %r" % (
                path, e.args[0], word))


def test_grammar():
    check(sweep.split_values("nurbs, lagrange") == ["nurbs", "lagrange"],
          "comma list")
    check(sweep.split_values("10,10,3 | 20,20,6") == ["10,10,3",
                                                      "20,20,6"],
          "bar list")
    check(sweep.split_values("10,10,3|") == ["10,10,3"], "one list value")
    check(sweep.split_values("band 0: 0, 0.15, 8; 5: 4 | 5: 4") ==
          ["band 0: 0, 0.15, 8; 5: 4", "5: 4"], "values with semicolons")
    parameters = {"Discretization/Type": {
        "pattern_description": "[Selection nurbs|lagrange ]"},
        "Discretization/Degree": {
            "pattern_description": "[Integer range 1...6 (inclusive)]"},
        "Body 1/Subdivisions": {"pattern_description": "[Anything]"},
        "Body 2/Subdivisions": {"pattern_description": "[Anything]"},
        "Exact solution/Type": {
            "pattern_description": "[Selection none|kirsch ]"},
        "Checks/Hertz radius": {"pattern_description": "[Double 0...1]"}}
    scene = {"Body 1/Subdivisions": "20, 20, 6",
             "Body 2/Subdivisions": "20, 20, 6"}
    s = sweep.Sweep("Type+Degree=nurbs+2,lagrange+1", parameters, scene)
    check(s.values == [("nurbs", "2"), ("lagrange", "1")], "joint sweep")
    check(s.sets(s.values[1]) == {"Discretization/Type": "lagrange",
                                  "Discretization/Degree": "1"},
          "joint sweep sets")
    s = sweep.Sweep("Subdivisions=10,10,3 | 14,14,4", parameters, scene)
    check(s.keys == [["Body 1/Subdivisions", "Body 2/Subdivisions"]],
          "a body parameter is every body that sets it: %r" % s.keys)
    check(sweep.resolve("Hertz radius", parameters, scene) ==
          ["Checks/Hertz radius"], "a name one section has")
    for text, word in (("Type=iga", "one of nurbs, lagrange"),
                       ("Degree=two", "integer"),
                       ("Type+Degree=nurbs", "parts"),
                       ("Type=nurbs,nurbs", "repeats"),
                       ("Typo=1", "no parameter"),
                       ("Subdivisions=10,10,3", "separate the values"),
                       ("Type", "NAME=VALUE")):
        try:
            sweep.Sweep(text, parameters, scene)
            failures.append("--sweep %s accepted" % text)
        except sweep.UsageError as e:
            check(word in str(e), "--sweep %s: message %r lacks %r" % (
                text, str(e), word))
    try:
        sweep.resolve("Subdivisions", parameters, {})
        failures.append("a body parameter no body sets accepted")
    except sweep.UsageError:
        pass


def made_up_study(kind, error_mode="each", values=None):
    """Two series of three meshes; q1 = 2 + s h^2, q2 = -1 + s h (s = 1,
    2), h = n_elements^(-1/2)."""
    series = [sweep.Series(name, {}, [sweep.Level(str(n), {})
                                      for n in (4, 8, 16)])
              for name in ("a", "b")]
    study = sweep.Study("t", "scene", {}, series,
                        [sweep.Quantity("q1"), sweep.Quantity("q2")],
                        sweep.ReferenceSpec(kind, values=values),
                        error_mode=error_mode)
    res = sweep.Result()
    for k, name in enumerate(("a", "b")):
        for n in (4, 8, 16):
            h = 1. / n
            res.rows.append({
                "series": name, "level": str(n), "status": "ok",
                "label": "%s %d" % (name, n), "n_dofs": 10 * n * n + k,
                "n_elements": n * n, "dim": 2, "total_s": n * (1. + k),
                "q1": 2. + (k + 1) * h * h, "q2": -1. + (k + 1) * h})
    return study, res


def test_compare():
    # Finest: the run with most unknowns (b 16) is the reference, its
    # error exactly 0, marked as such and not on the front.
    study, res = made_up_study("finest")
    sweep.compare(study, res)
    ref = res.rows[-1]
    check(res.reference_row is ref, "finest picks the most unknowns")
    check(ref["error"] == 0. and ref["pareto"] == "reference",
          "finest row: error %r, pareto %r" % (ref["error"], ref["pareto"]))
    a16 = res.rows[2]
    want = max(abs(a16["q1"] - ref["q1"]) / abs(ref["q1"]),
               abs(a16["q2"] - ref["q2"]) / abs(ref["q2"]))
    check(close(a16["error"], want, 1e-14), "each-mode error of a 16")
    # Pareto by hand (reference q1 = 2 + 2/256, q2 = -0.875): a 4 costs 4
    # at error 0.143 (q2), a 8 costs 8 at 0.0039 (q1; its q2 is exactly
    # the reference's), a 16 costs 16 at 0.071, b 4 costs 8 at 0.43, b 8
    # 16 at 0.143: the front is a 4 and a 8.
    check([r["pareto"] for r in res.rows] ==
          ["yes", "yes", "", "", "", "reference"],
          "Pareto marks %r" % [r["pareto"] for r in res.rows])
    # Common: differences over the largest reference magnitude.
    study, res = made_up_study("finest", "common")
    sweep.compare(study, res)
    ref, a4 = res.rows[-1], res.rows[0]
    scale = max(abs(ref["q1"]), abs(ref["q2"]))
    want = max(abs(a4["q1"] - ref["q1"]), abs(a4["q2"] - ref["q2"])) / scale
    check(close(a4["error"], want, 1e-14), "common-mode error")
    # Richardson: each series' limit is 2 and -1 exactly, orders 2 and 1.
    study, res = made_up_study("richardson")
    sweep.compare(study, res)
    for e in res.richardson:
        want_limit, want_p = {"q1": (2., 2.), "q2": (-1., 1.)}[e["quantity"]]
        check(close(e["limit"], want_limit, 1e-10) and
              close(e["order"], want_p, 1e-7),
              "Richardson %s %s: %r, %r" % (e["series"], e["quantity"],
                                            e["limit"], e["order"]))
    b16 = res.rows[-1]
    want = max(2. / 256 / 2., 2. / 16)
    check(close(b16["error"], want, 1e-8), "Richardson error of b 16: %r, "
          "want %r" % (b16["error"], want))
    # A given value overrides the kind for its quantity.
    study, res = made_up_study("richardson", values={"q2": -0.5})
    sweep.compare(study, res)
    check(res.rows[0]["q2_reference"] == -0.5, "--reference-value ignored")
    # A failed run has no error and stays off the front.
    study, res = made_up_study("finest")
    res.rows[0]["status"] = "failed"
    sweep.compare(study, res)
    check(math.isnan(res.rows[0]["error"]) and res.rows[0]["pareto"] == "",
          "a failed row has an error or a Pareto mark")


def test_pareto():
    pts = [(1., 0.5), (2., 0.6), (3., 0.1), (0.5, 0.9), (4., 0.1)]
    check(common.pareto_front(pts) == [3, 0, 2], "pareto_front %r" %
          common.pareto_front(pts))


def main():
    for t in (test_richardson, test_lookup, test_grammar, test_compare,
              test_pareto):
        t()
    for f in failures:
        print("FAILED: " + f)
    print("studies sweep unit test: %s" % (
        "passed" if not failures else "%d failures" % len(failures)))
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
