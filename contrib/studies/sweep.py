"""The general study: a scene, the parameters to sweep, the quantities to
compare and a reference, giving the table (unknowns, quantities, error,
seconds per phase, memory) and the error-against-time plot with the Pareto
front marked.

A study is a list of series (one per combination of the swept values other
than the mesh), each a list of levels (the meshes, coarse to fine). Every
run is one igabde run of the scene with the study's, the series' and the
level's --set entries. A quantity is a number of summary.json named by its
path (`checks.hertz_peak_pressure`, `points.A.2`,
`load_steps.-1.newton_iterations`), or a distance computed against a
reference run (the pair-pressure profile, PressureProfile). The reference
of a quantity is a given value, the finest run (most unknowns), a run made
for it, or the Richardson extrapolation of each series' three finest runs.

`contrib/studies/run sweep` (main below) builds a study from the command
line; the shipped accuracy-cost study builds its V5, V6 and B2 studies in
Python and runs them through run_study and write_table here."""

import argparse
import json
import math
import os
import subprocess
import sys
import time

import common
from common import g
from pressure_reference import Reference as PressureReference, read_pairs

NAN = float("nan")


class UsageError(Exception):
    """Bad input to the driver: one line, exit status 2."""


def finite(x):
    return isinstance(x, (int, float)) and not isinstance(x, bool) and \
        math.isfinite(x)


# ------------------------------------------------------------ Richardson

def richardson(points):
    """The limit q* and observed order p of q(h) = q* + C h^p through the
    three (h, q) of @p points (the three finest runs of a series; h the
    mesh size, in any unit, the three different). The ratios of the h need
    not be equal: p solves (q1 - q2)/(q2 - q3) = (h1^p - h2^p)/(h2^p - h3^p)
    (h1 > h2 > h3), whose right side grows with p from
    ln(h1/h2)/ln(h2/h3) at p = 0. Returns (q*, p); raises ValueError with
    the reason when the three values admit no such fit (they do not change
    monotonically, or their change does not shrink under refinement)."""
    if len(points) != 3:
        raise ValueError("needs three runs, has %d" % len(points))
    (h1, q1), (h2, q2), (h3, q3) = sorted(points, reverse=True)
    if not (h1 > h2 > h3 > 0.):
        raise ValueError("needs three different mesh sizes")
    if not all(finite(q) for q in (q1, q2, q3)):
        raise ValueError("a value is missing")
    d1, d2 = q1 - q2, q2 - q3
    if d1 == 0. and d2 == 0.:
        return q3, NAN
    if d1 == 0. or d2 == 0. or d1 / d2 <= 0.:
        raise ValueError("not monotone (%s, %s, %s)" % (
            g(q1, 6), g(q2, 6), g(q3, 6)))
    ratio = d1 / d2
    a, b = h1 / h3, h2 / h3

    def growth(p):
        return (a ** p - b ** p) / (b ** p - 1.)

    lowest = math.log(a / b) / math.log(b)
    if ratio <= lowest:
        raise ValueError("the change does not shrink under refinement "
                         "(%s, %s, %s)" % (g(q1, 6), g(q2, 6), g(q3, 6)))
    lo, hi = 0., 1.
    while growth(hi) < ratio:
        lo, hi = hi, 2. * hi
        if hi > 64.:
            raise ValueError("observed order above 64")
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if growth(mid) < ratio:
            lo = mid
        else:
            hi = mid
    p = 0.5 * (lo + hi)
    c = d2 / (h2 ** p - h3 ** p)
    return q3 - c * h3 ** p, p


# ------------------------------------------------------------ quantities

def lookup(summary, path):
    """The value at the dotted @p path of @p summary ('checks.x',
    'points.A.2', 'load_steps.-1.residual'); KeyError with what is there
    when the path does not lead to a number."""
    node = summary
    done = []
    for part in path.split("."):
        if isinstance(node, list):
            try:
                node = node[int(part)]
            except (ValueError, IndexError):
                raise KeyError("%s: %s is a list of %d entries" % (
                    path, ".".join(done) or "summary.json", len(node)))
        elif isinstance(node, dict):
            if part not in node:
                raise KeyError("%s: %s has no '%s' (it has: %s)" % (
                    path, ".".join(done) or "summary.json", part,
                    ", ".join(sorted(node)) or "nothing"))
            node = node[part]
        else:
            raise KeyError("%s: %s is a value, not a list or object" % (
                path, ".".join(done)))
        done.append(part)
    if node is None:
        return NAN  # summary.json writes a non-finite value as null
    if isinstance(node, bool) or not isinstance(node, (int, float)):
        raise KeyError("%s is not a number" % path)
    return float(node)


def column_key(label):
    return "".join(c if c.isalnum() or c in "_-." else "_"
                   for c in label.strip())


class Quantity:
    """A number of summary.json, compared with its reference."""

    distance = False

    def __init__(self, path, label=None):
        self.path = path
        self.label = label or path
        self.key = column_key(self.label)

    def value(self, summary, row):
        return lookup(summary, self.path)


class PressureProfile:
    """The relative L2 distance of a run's pair pressures from the
    pair-pressure profile of the reference run (pressure_reference.py: 2D
    line contact), with the largest single-pair deviation beside it (in
    units of the reference's peak): a distance, its own error."""

    distance = True
    path = "pressure-profile"

    def __init__(self, label="pressure-profile", largest="largest_deviation"):
        self.label = label
        self.key = column_key(label)
        self.largest = largest
        self.reference = None
        self.failure = ""

    def prepare(self, reference_row):
        """Reads the profile of @p reference_row (None or not ok: none)."""
        self.reference, self.failure = None, ""
        if reference_row is None or not common.ok(reference_row):
            self.failure = "no reference run"
            return
        try:
            self.reference = PressureReference(
                read_pairs(reference_row["folder"]))
        except (OSError, ValueError, KeyError) as e:
            self.failure = "reference profile: %s" % e

    def measure(self, row):
        """(L2, largest) of @p row against the prepared profile."""
        if self.reference is None or not common.ok(row):
            return NAN, NAN
        return self.reference.errors(read_pairs(row["folder"]))


# ------------------------------------------------------------- the study

class Level:
    """One mesh of a series: its label and --set entries."""

    def __init__(self, label, sets, values=None):
        self.label = label
        self.sets = dict(sets)
        self.values = dict(values or {})


class Series:
    """Runs that differ only in the mesh: label, --set entries, the levels
    (coarse to fine) and the values it stands for (table columns)."""

    def __init__(self, label, sets, levels, values=None, run_label=None):
        self.label = label
        self.sets = dict(sets)
        self.levels = list(levels)
        self.values = dict(values or {})
        self.run_label = label if run_label is None else run_label


class ReferenceSpec:
    """What the quantities are compared with: kind 'finest' (the ok run
    with the most unknowns, among those whose values match @p match),
    'run' (a run made first with @p sets over the study's, labelled
    @p label), 'richardson' (each series' own extrapolation) or 'value'
    (only the given @p values). @p values (quantity label -> number)
    override the kind for those quantities."""

    def __init__(self, kind="finest", values=None, sets=None, label="",
                 match=None):
        if kind not in ("finest", "run", "richardson", "value"):
            raise UsageError("unknown reference kind %r" % kind)
        self.kind = kind
        self.values = dict(values or {})
        self.sets = dict(sets or {})
        self.label = label or "reference"
        self.match = dict(match or {})


class Study:
    """@p error_mode 'each': every quantity relative to its own reference,
    the row's error the largest of these; 'common': every difference over
    the largest reference magnitude of the quantities (one scale for
    components of one field, the B2 probe measure)."""

    def __init__(self, name, scene, sets, series, quantities, reference,
                 shown=(), error_mode="each", refine_name="mesh",
                 h_of=None):
        self.name = name
        self.scene = scene
        self.sets = dict(sets)
        self.series = list(series)
        self.quantities = list(quantities)
        self.shown = list(shown)
        self.reference = reference
        self.error_mode = error_mode
        self.refine_name = refine_name
        self.h_of = h_of or mesh_size


def mesh_size(row):
    """h of a run for Richardson: (elements of all bodies)^(-1/dim)."""
    n, dim = row.get("n_elements"), row.get("dim")
    if not finite(n) or not finite(dim) or n <= 0:
        return NAN
    return n ** (-1. / dim)


class Result:
    def __init__(self):
        self.rows = []
        self.reference_row = None
        self.references = {}     # quantity key -> reference value (fixed)
        self.series_references = {}  # (series, key) -> value
        self.richardson = []     # dicts: series, quantity, runs, limit,
        #                          order, reason
        self.notes = []


def load_summary(row):
    path = os.path.join(row["folder"], "summary.json")
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def fill_quantities(study, row, summary, check_paths):
    """The quantities' and shown columns' values of one run into @p row;
    with @p check_paths, a path that leads to no number in this (ok) run
    is bad input."""
    for q in study.quantities + study.shown:
        if q.distance:
            continue
        row[q.key] = NAN
        if summary is None or not common.ok(row):
            continue
        try:
            row[q.key] = q.value(summary, row)
        except KeyError as e:
            if check_paths:
                raise UsageError("quantity %s: not in summary.json of run "
                                 "'%s' (%s)" % (q.path, row["label"],
                                                e.args[0]))
            row[q.key] = NAN


def run_study(study, runner, folder_names=False):
    """Every run of @p study, one after the other; returns a Result with
    the rows (one per run: the Runner's figures, the series' and level's
    values, each quantity's value and error, the row's 'error' and
    'pareto'). @p folder_names: run folders numbered 'NNN-...' (else the
    Runner's, from the label)."""
    res = Result()
    checked = [False]
    count = [0]

    def one(label, sets):
        folder = None
        if folder_names:
            folder = "%03d" % count[0]
        count[0] += 1
        row = runner.run(label, study.scene, sets, folder=folder)
        summary = load_summary(row)
        fill_quantities(study, row, summary,
                        check_paths=not checked[0] and common.ok(row))
        if common.ok(row):
            checked[0] = True
        return row

    ref = study.reference
    if ref.kind == "run":
        res.reference_row = one("%s %s" % (study.name, ref.label),
                                dict(study.sets, **ref.sets))
        res.reference_row["series"] = "reference"
    for s in study.series:
        for lv in s.levels:
            sets = dict(study.sets)
            sets.update(s.sets)
            sets.update(lv.sets)
            row = one(" ".join(x for x in (study.name, s.run_label, lv.label)
                               if x), sets)
            row.update(s.values)
            row.update(lv.values)
            row["series"] = s.label
            row["level"] = lv.label
            res.rows.append(row)
    compare(study, res)
    return res


def compare(study, res):
    """Reference values, errors and the Pareto front of the rows of
    @p res (split from run_study so that it can run on given rows)."""
    ref = study.reference
    rows = res.rows
    if ref.kind == "finest":
        pool = [r for r in rows if common.ok(r) and
                all(str(r.get(k)) == str(v) for k, v in ref.match.items())]
        if pool:
            res.reference_row = max(pool, key=lambda r: r.get("n_dofs") or 0)
        else:
            res.notes.append("no run for the finest reference%s ended ok" % (
                " (%s)" % ", ".join("%s=%s" % kv for kv in ref.match.items())
                if ref.match else ""))
    for q in study.quantities:
        if q.distance:
            if ref.kind in ("richardson", "value"):
                raise UsageError("%s needs a reference run (--reference "
                                 "finest or run)" % q.label)
            q.prepare(res.reference_row)
            if q.failure:
                res.notes.append("%s: %s" % (q.label, q.failure))
            for r in rows:
                if r is res.reference_row:
                    r[q.key], extra = 0., 0.  # by definition, not round-off
                else:
                    r[q.key], extra = q.measure(r)
                if q.largest:
                    r[q.largest] = extra
            continue
        if q.label in ref.values:
            res.references[q.key] = ref.values[q.label]
        elif ref.kind in ("finest", "run"):
            rr = res.reference_row
            res.references[q.key] = (rr.get(q.key, NAN)
                                     if rr is not None and common.ok(rr)
                                     else NAN)
        elif ref.kind == "value":
            raise UsageError("no reference value for %s" % q.label)
        else:
            for s in study.series:
                pts = [(study.h_of(r), r[q.key]) for r in rows
                       if r["series"] == s.label and common.ok(r) and
                       finite(r.get(q.key)) and finite(study.h_of(r))]
                pts.sort(reverse=True)
                entry = {"series": s.label, "quantity": q.label,
                         "runs": pts[-3:], "limit": NAN, "order": NAN,
                         "reason": ""}
                try:
                    entry["limit"], entry["order"] = richardson(pts[-3:])
                except ValueError as e:
                    entry["reason"] = str(e)
                res.series_references[(s.label, q.key)] = entry["limit"]
                res.richardson.append(entry)

    def reference_of(r, q):
        if q.key in res.references:
            return res.references[q.key]
        return res.series_references.get((r["series"], q.key), NAN)

    values = [q for q in study.quantities if not q.distance]
    for r in rows:
        errors = []
        scale = max([abs(reference_of(r, q)) for q in values] or [NAN])
        for q in study.quantities:
            if q.distance:
                e = r.get(q.key, NAN)
            else:
                v, rv = r.get(q.key, NAN), reference_of(r, q)
                r[q.key + "_reference"] = rv
                if study.error_mode == "common":
                    e = abs(v - rv) / scale if finite(scale) and scale > 0 \
                        else NAN
                else:
                    e = abs(v - rv) / abs(rv) if rv != 0. else abs(v - rv)
            r[q.key + "_error"] = e if common.ok(r) else NAN
            errors.append(r[q.key + "_error"])
        r["error"] = (max(errors) if errors and all(finite(e)
                                                    for e in errors)
                      else NAN)
        r["pareto"] = ""
    if any(r is res.reference_row for r in rows):
        res.reference_row["pareto"] = "reference"
    sub = [r for r in rows if common.ok(r) and finite(r["error"]) and
           finite(r.get("total_s")) and r["pareto"] != "reference"]
    for i in common.pareto_front([(r["total_s"], r["error"]) for r in sub]):
        sub[i]["pareto"] = "yes"


# ---------------------------------------------------------------- output

def write_table(f, rows, columns):
    """A Markdown table of @p rows; @p columns: (header, cell(row))."""
    f.write("| " + " | ".join(h for h, _ in columns) + " |\n")
    f.write("|" + "---|" * len(columns) + "\n")
    for r in rows:
        f.write("| " + " | ".join(str(cell(r)) for _, cell in columns) +
                " |\n")


def phase_columns(rows):
    """(header, cell) of every timing phase that is not zero in some row."""
    cols = []
    for p, key in zip(common.PHASES + ["other"], common.PHASE_KEYS):
        if any(finite(r.get(key)) and r.get(key) > 0. for r in rows):
            cols.append(("%s s" % p.replace("contact: ", ""),
                         lambda r, key=key: g(r.get(key), 3)))
    return cols


def sweep_columns(study, rows, parameters):
    # The swept parameters are the columns that tell the series apart.
    cols = [(p, lambda r, p=p: r.get(p, "")) for p in parameters] or \
        [("series", lambda r: r["series"])]
    cols += [("unknowns", lambda r: g(r.get("n_dofs"))),
             ("status", lambda r: r["status"])]
    for q in study.quantities:
        if not q.distance:
            cols.append((q.label, lambda r, q=q: g(r.get(q.key), 6)))
        cols.append(("%s error" % q.label if not q.distance else q.label,
                     lambda r, q=q: g(r.get(q.key + "_error"), 3)))
        if q.distance and q.largest:
            cols.append((q.largest.replace("_", " "),
                         lambda r, q=q: g(r.get(q.largest), 3)))
    if len(study.quantities) > 1:
        cols.append(("error", lambda r: g(r.get("error"), 3)))
    cols += [(q.label, lambda r, q=q: g(r.get(q.key), 4))
             for q in study.shown]
    cols.append(("Pareto", lambda r: r.get("pareto", "")))
    cols += phase_columns(rows)
    cols += [("total s", lambda r: g(r.get("total_s"), 3)),
             ("process s", lambda r: g(r.get("process_s"), 3)),
             ("peak MiB", lambda r: g(r.get("peak_memory_mib"), 4))]
    return cols


def csv_columns(study, parameters):
    cols = ["series"] + list(parameters) + ["n_dofs", "n_elements",
                                            "status"]
    for q in study.quantities:
        cols += [q.key] + ([] if q.distance else [q.key + "_reference"]) + \
            [q.key + "_error"] + ([q.largest] if q.distance and q.largest
                                  else [])
    cols += [q.key for q in study.shown]
    cols += ["error", "pareto", "newton_iterations", "n_contact_pairs",
             "contact_s", "total_s", "process_s"] + common.PHASE_KEYS + \
        ["peak_memory_mib", "label", "diagnosis"]
    return cols


def reference_text(study, res):
    """One paragraph: what each quantity is compared with."""
    ref = study.reference
    rr = res.reference_row
    given, from_run, extrapolated, distances = [], [], [], []
    for q in study.quantities:
        if q.distance:
            distances.append(q.label)
        elif q.label in ref.values:
            given.append("%s = %s" % (q.label, g(ref.values[q.label], 8)))
        elif ref.kind in ("finest", "run"):
            from_run.append("%s = %s" % (q.label,
                                         g(res.references.get(q.key), 8)))
        else:
            extrapolated.append(q.label)
    parts = []
    if from_run or distances:
        who = ("the finest run (most unknowns%s)" % (
            ", among %s" % ", ".join("%s=%s" % kv for kv in ref.match.items())
            if ref.match else "") if ref.kind == "finest"
            else "a reference run")
        if rr is not None:
            what = "%s, %s, %s unknowns, %s s" % (
                who, rr["label"], g(rr.get("n_dofs")),
                g(rr.get("total_s"), 3))
            if not common.ok(rr):
                what += ": %s, %s" % (rr["status"], rr["diagnosis"])
        else:
            what = who + ": none"
        if from_run:
            what += ": " + ", ".join(from_run)
        if distances:
            what += "; %s: the L2 distance of the pair pressures to its " \
                "pair-pressure profile" % ", ".join(distances)
        parts.append(what)
    if extrapolated:
        parts.append("for %s the Richardson extrapolation of each series' "
                     "three finest runs (the table below)" %
                     ", ".join(extrapolated))
    if given:
        parts.append("given: " + ", ".join(given))
    mode = ("|q − q_ref| / |q_ref| per quantity" if study.error_mode ==
            "each" else "|q − q_ref| / max |q_ref| over the quantities")
    text = "Reference: " + "; ".join(parts) + ". Error: " + mode
    if len(study.quantities) > 1:
        text += ", the row's error the largest"
    return text + "."


def richardson_table(f, res):
    if not res.richardson:
        return
    f.write("\nRichardson extrapolation (q = q* + C h^p through the three "
            "finest runs of each series that ended ok, h = elements^(−1/dim)"
            "; p is the observed order):\n\n")
    write_table(f, res.richardson, [
        ("series", lambda e: e["series"]),
        ("quantity", lambda e: e["quantity"]),
        ("runs (h: value)", lambda e: "; ".join(
            "%s: %s" % (g(h, 3), g(q, 7)) for h, q in e["runs"])),
        ("limit q*", lambda e: g(e["limit"], 7) if not e["reason"] else "–"),
        ("order p", lambda e: g(e["order"], 3) if not e["reason"] else
         "none: " + e["reason"])])
    by_q = {}
    for e in res.richardson:
        if finite(e["limit"]):
            by_q.setdefault(e["quantity"], []).append(e["limit"])
    spread = ["%s %s" % (q, g((max(v) - min(v)) / abs(max(v, key=abs)), 2))
              for q, v in by_q.items() if len(v) > 1 and max(v, key=abs)]
    if spread:
        f.write("\nRelative spread of the series' limits (they share one "
                "continuum answer, so this bounds what the extrapolated "
                "errors can tell apart): " + ", ".join(spread) + ".\n")


def plot(study, res, out, name, ylabel="error against the reference"):
    plt = common.pyplot()
    if plt is None:
        return
    rows = [r for r in res.rows if common.ok(r) and
            r.get("pareto") != "reference"]
    panels = [("error", "total_s"), ("error", "n_dofs")]
    if len(study.quantities) > 1:
        panels += [(q.key + "_error", "total_s") for q in study.quantities]
    ncols = 2
    nrows = (len(panels) + 1) // 2
    fig, axes = plt.subplots(nrows, ncols, figsize=(11, 4.3 * nrows),
                             squeeze=False)
    styles = ["o-", "s--", "^:", "D-.", "v-", "x--", "P:", "*-."]
    titles = {"error": "error" if len(study.quantities) == 1 else
              "largest error of the quantities"}
    for q in study.quantities:
        titles[q.key + "_error"] = q.label
    for ax, (ekey, xkey) in zip(axes.flat, panels):
        for i, s in enumerate(study.series):
            pts = sorted((r[xkey], r[ekey]) for r in rows
                         if r["series"] == s.label and finite(r.get(ekey)) and
                         r[ekey] > 0. and finite(r.get(xkey)))
            if pts:
                ax.loglog(*zip(*pts), styles[i % len(styles)], ms=4,
                          label=s.label, color="C%d" % (i % 10))
        if ekey == "error" and xkey == "total_s":
            front = sorted((r[xkey], r[ekey]) for r in rows
                           if r.get("pareto") == "yes" and r[ekey] > 0.)
            if front:
                ax.step(*zip(*front), where="post", color="k", lw=1.5,
                        alpha=0.6, label="Pareto front")
                ax.plot(*zip(*front), "ko", mfc="none", ms=9)
        ax.set_xlabel("wall seconds (sum of the phases)" if xkey == "total_s"
                      else "unknowns")
        ax.set_ylabel(ylabel if ekey == "error" else "error")
        ax.set_title("%s: %s" % (study.name, titles[ekey]), fontsize=9)
        ax.grid(True, which="both", alpha=0.3)
    for ax in list(axes.flat)[len(panels):]:
        ax.set_visible(False)
    handles, labels = axes[0][0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=3, fontsize=7)
    fig.tight_layout(rect=(0, 0.06 + 0.02 * (len(labels) // 3), 1, 1))
    common.save_figure(fig, out, name)
    plt.close(fig)


def write_outputs(study, res, out, name, parameters, preamble):
    common.write_csv(os.path.join(out, name + ".csv"),
                     res.rows + ([res.reference_row]
                                 if study.reference.kind == "run" and
                                 res.reference_row is not None else []),
                     csv_columns(study, parameters))
    with open(os.path.join(out, name + ".md"), "w") as f:
        f.write(preamble + " " + reference_text(study, res) +
                " Seconds: `timing` of summary.json (total s = the sum of "
                "the phases; process s the whole igabde process); peak MiB: "
                "`ranks[].peak_memory_mib`. Pareto: no other run is both "
                "faster and more accurate.\n\n")
        write_table(f, res.rows, sweep_columns(study, res.rows, parameters))
        richardson_table(f, res)
        for n in res.notes:
            f.write("\n- " + n + "\n")
        f.write(common.failure_notes(res.rows + (
            [res.reference_row] if study.reference.kind == "run" and
            res.reference_row is not None else [])))
    plot(study, res, out, name)


# ---------------------------------------------------------- command line

# Short names: the section of a parameter named without one.
ALIASES = {
    "Type": "Discretization/Type",
    "Degree": "Discretization/Degree",
    "Refinements": "Discretization/Refinements",
    "Algorithm": "Contact/Algorithm",
    "Path": "Contact/Path",
}
BODIES = ("Body 1", "Body 2")
MESH_PARAMETERS = ("Refinements", "Subdivisions")


def parameter_tree(igabde):
    """igabde's parameters (--print-parameters json): section -> name ->
    {value, pattern_description, ...}."""
    try:
        text = subprocess.run([igabde, "--print-parameters", "json"],
                              capture_output=True, text=True, timeout=60,
                              check=True).stdout
        return json.loads(text)
    except (OSError, subprocess.SubprocessError, ValueError) as e:
        raise UsageError("cannot read igabde's parameters from %s "
                         "--print-parameters json: %s" % (igabde, e))


def flat_parameters(tree, prefix=""):
    """'Section/Name' -> its entry, for every parameter of @p tree."""
    out = {}
    for k, v in tree.items():
        if isinstance(v, dict) and "pattern_description" in v:
            out[prefix + k] = v
        elif isinstance(v, dict):
            out.update(flat_parameters(v, prefix + k + "/"))
    return out


def scene_entries(path):
    """'Section/Name' -> value of every `set` line of the scene file."""
    entries, sections = {}, []
    with open(path) as f:
        for line in f:
            line = line.split("#", 1)[0].strip()
            words = line.split(None, 1)
            if not words:
                continue
            if words[0] == "subsection" and len(words) > 1:
                sections.append(words[1].strip())
            elif words[0] == "end":
                if sections:
                    sections.pop()
            elif words[0] == "set" and len(words) > 1 and "=" in words[1]:
                name, value = words[1].split("=", 1)
                entries["/".join(sections + [name.strip()])] = value.strip()
    return entries


def resolve(name, parameters, scene):
    """The parameters a (possibly short) name stands for: 'Section/Name'
    as it is, a short name by ALIASES, a top-level parameter, a body
    parameter as every body of the scene that sets it, else the one
    section that has it."""
    name = name.strip()
    if "/" in name:
        if name not in parameters:
            raise UsageError("no parameter %s (igabde --print-parameters "
                             "lists them)" % name)
        return [name]
    if name in ALIASES:
        return [ALIASES[name]]
    if name in parameters:
        return [name]
    if "%s/%s" % (BODIES[0], name) in parameters:
        keys = ["%s/%s" % (b, name) for b in BODIES
                if "%s/%s" % (b, name) in scene]
        if not keys:
            raise UsageError("%s: no body of the scene sets it; write "
                             "'Body 1/%s' or 'Body 2/%s'" % (name, name,
                                                             name))
        return keys
    hits = [k for k in parameters if k.split("/")[-1] == name]
    if len(hits) == 1:
        return hits
    if not hits:
        raise UsageError("no parameter named %s (igabde --print-parameters "
                         "lists them)" % name)
    raise UsageError("%s is ambiguous: write one of %s" % (
        name, ", ".join(sorted(hits))))


def check_value(key, value, parameters):
    """One clear line when @p value does not fit the pattern of @p key."""
    pattern = parameters[key].get("pattern_description", "")
    v = value.strip()
    bad = False
    if pattern.startswith("[Selection"):
        choices = pattern[len("[Selection"):].strip(" ]").split("|")
        choices = [c.strip() for c in choices]
        bad = v not in choices
        hint = "one of " + ", ".join(choices)
    elif pattern.startswith("[Integer"):
        try:
            int(v)
        except ValueError:
            bad = True
        hint = "an integer"
    elif pattern.startswith("[Double"):
        try:
            float(v)
        except ValueError:
            bad = True
        hint = "a number"
    elif pattern.startswith("[Bool"):
        bad = v not in ("true", "false")
        hint = "true or false"
    if bad:
        raise UsageError("%s = %r: must be %s" % (key, v, hint))


def split_values(text):
    """A value list: separated by '|' when the text has one (values that
    hold commas or semicolons, such as Subdivisions or Grading; empty items
    dropped, so that 'a,b|' is the one value a,b), else by ','."""
    if "|" in text:
        return [v.strip() for v in text.split("|") if v.strip()]
    return [v.strip() for v in text.split(",")]


class Sweep:
    """One --sweep: names (short, as given), the parameters each stands
    for, and the values (one tuple per point, one entry per name)."""

    def __init__(self, text, parameters, scene):
        if "=" not in text:
            raise UsageError("--sweep %r: write NAME=VALUE1,VALUE2,..." %
                             text)
        names, values = text.split("=", 1)
        self.names = [n.strip() for n in names.split("+")]
        if not all(self.names):
            raise UsageError("--sweep %r: an empty name" % text)
        self.keys = [resolve(n, parameters, scene) for n in self.names]
        self.values = []
        if "|" not in values and "," in values:
            # Commas between the values of a parameter whose own value is
            # a list (Subdivisions = 64, 16) are most likely that list.
            for n, keys in zip(self.names, self.keys):
                lists = [scene[k] for k in keys if "," in scene.get(k, "")]
                if lists:
                    raise UsageError(
                        "--sweep %r: %s is a list in the scene (%s); "
                        "separate the values with '|' (%s=%s | ...), one "
                        "value as %s=%s|" % (text, n, lists[0], n, values,
                                             n, values))
        for v in split_values(values):
            parts = [p.strip() for p in v.split("+")] \
                if len(self.names) > 1 else [v]
            if len(parts) != len(self.names):
                raise UsageError("--sweep %r: value %r has %d parts for the "
                                 "%d names %s" % (text, v, len(parts),
                                                  len(self.names),
                                                  "+".join(self.names)))
            for keys, p in zip(self.keys, parts):
                for k in keys:
                    check_value(k, p, parameters)
            self.values.append(tuple(parts))
        if not self.values or self.values == [("",)]:
            raise UsageError("--sweep %r: no values" % text)
        if len(set(self.values)) != len(self.values):
            raise UsageError("--sweep %r: a value repeats" % text)

    def sets(self, point):
        out = {}
        for keys, v in zip(self.keys, point):
            for k in keys:
                out[k] = v
        return out

    def labels(self, point):
        return [(n, v) for n, v in zip(self.names, point)]


def parse_assignment(text, what):
    if "=" not in text:
        raise UsageError("%s %r: write NAME=VALUE" % (what, text))
    name, value = text.split("=", 1)
    return name.strip(), value.strip()


def parse_quantity(text, reference_values):
    path, _, label = text.partition("=")
    path = path.strip()
    if not path or any(not p for p in path.split(".")):
        raise UsageError("--quantity %r: write a summary.json path such as "
                         "checks.hertz_peak_pressure or points.A.2, "
                         "optionally =LABEL" % text)
    if path == "pressure-profile":
        return PressureProfile(label.strip() or "pressure-profile")
    return Quantity(path, label.strip() or None)


def build(args, parameters):
    """The Study of a `run sweep` command line."""
    if not os.path.isfile(args.scene):
        raise UsageError("no scene file %s" % args.scene)
    scene = scene_entries(args.scene)
    sweeps = [Sweep(t, parameters, scene) for t in args.sweep]
    names = [n for s in sweeps for n in s.names]
    if len(set(names)) != len(names):
        raise UsageError("a parameter is swept twice")
    base = {}
    for t in args.set:
        n, v = parse_assignment(t, "--set")
        for k in resolve(n, parameters, scene):
            check_value(k, v, parameters)
            base[k] = v

    # The mesh: the sweep named by --refine, else the first that sweeps
    # Refinements or Subdivisions.
    refine = None
    if args.refine:
        found = [s for s in sweeps if args.refine.strip() in s.names or
                 args.refine.strip() in [k for ks in s.keys for k in ks]]
        if not found:
            raise UsageError("--refine %s: no --sweep of that name" %
                             args.refine)
        refine = found[0]
    else:
        for s in sweeps:
            if any(k.split("/")[-1] in MESH_PARAMETERS
                   for ks in s.keys for k in ks):
                refine = s
                break
    others = [s for s in sweeps if s is not refine]

    if not args.quantity:
        raise UsageError("name at least one --quantity (a summary.json path "
                         "such as checks.hertz_peak_pressure)")
    quantities = [parse_quantity(t, {}) for t in args.quantity]
    shown = [parse_quantity(t, {}) for t in args.show]
    if any(q.distance for q in shown):
        raise UsageError("--show pressure-profile: use it as a --quantity")
    keys = [q.key for q in quantities + shown]
    if len(set(keys)) != len(keys):
        raise UsageError("two quantities have the same label")
    reserved = set(csv_columns(Study("", "", {}, [], [], None), names)) | \
        {"level", "dim"}
    for q in quantities + shown:
        if q.key in reserved:
            raise UsageError("the label %s is a column of the table: give "
                             "the quantity another (PATH=LABEL)" % q.key)

    values = {}
    for t in args.reference_value:
        p, v = parse_assignment(t, "--reference-value")
        match = [q for q in quantities if p in (q.path, q.label)]
        if not match:
            raise UsageError("--reference-value %s: no --quantity %s" % (t, p))
        try:
            values[match[0].label] = float(v)
        except ValueError:
            raise UsageError("--reference-value %s: %r is not a number" %
                             (t, v))
    kind, match = args.reference, {}
    try:
        number = float(kind)
    except ValueError:
        number = None
    if number is not None:
        if len(quantities) != 1:
            raise UsageError("--reference VALUE compares one quantity; with "
                             "several, give --reference-value PATH=VALUE "
                             "for each")
        values[quantities[0].label] = number
        kind = "value"
    elif kind.startswith("finest:"):
        for t in kind[len("finest:"):].split(","):
            n, v = parse_assignment(t, "--reference finest:")
            match[n] = v
        kind = "finest"
    elif kind not in ("finest", "richardson", "run"):
        raise UsageError("--reference %s: write finest, finest:NAME=VALUE, "
                         "richardson, run or a number" % kind)
    ref_sets = {}
    for t in args.reference_set:
        n, v = parse_assignment(t, "--reference-set")
        for k in resolve(n, parameters, scene):
            check_value(k, v, parameters)
            ref_sets[k] = v
    if ref_sets and kind != "run":
        raise UsageError("--reference-set needs --reference run")
    if kind == "run" and not ref_sets:
        raise UsageError("--reference run: give its parameters with "
                         "--reference-set NAME=VALUE")
    if kind == "value" and any(q.label not in values for q in quantities
                               if not q.distance):
        raise UsageError("no reference value for %s" % ", ".join(
            q.label for q in quantities if q.label not in values))
    if kind == "richardson":
        if refine is None:
            raise UsageError("--reference richardson needs a mesh sweep "
                             "(Refinements or Subdivisions, or --refine)")
        if len(refine.values) < 3:
            raise UsageError("--reference richardson needs three meshes or "
                             "more; the mesh sweep has %d" %
                             len(refine.values))
    if any(q.distance for q in quantities) and kind not in ("finest", "run"):
        raise UsageError("pressure-profile needs --reference finest or run")
    if match:
        swept = set(names)
        for n in match:
            if n not in swept:
                raise UsageError("--reference finest:%s=...: %s is not "
                                 "swept" % (n, n))

    # Series: every combination of the other sweeps; levels: the mesh.
    points = [[]]
    for s in others:
        points = [p + [(s, v)] for p in points for v in s.values]
    series = []
    for p in points:
        labels = [lv for s, v in p for lv in s.labels(v)]
        sets = {}
        for s, v in p:
            sets.update(s.sets(v))
        levels = ([Level("", {})] if refine is None else
                  [Level("+".join(v), refine.sets(v),
                         dict(refine.labels(v))) for v in refine.values])
        label = ", ".join("%s=%s" % lv for lv in labels) or "all"
        run_label = " ".join("%s=%s" % lv for lv in labels)
        if refine is not None:
            levels = [Level("%s=%s" % ("+".join(refine.names), lv.label),
                            lv.sets, lv.values) for lv in levels]
        series.append(Series(label, sets, levels, dict(labels), run_label))
    name = args.name or os.path.splitext(os.path.basename(args.scene))[0]
    study = Study(name, os.path.abspath(args.scene), base, series,
                  quantities, ReferenceSpec(kind, values, ref_sets,
                                            "reference", match),
                  shown=shown, error_mode=args.error,
                  refine_name="+".join(refine.names) if refine else "")
    parameters_shown = [n for s in others for n in s.names] + \
        (refine.names if refine else [])
    return study, parameters_shown


USAGE = """contrib/studies/run sweep SCENE [--sweep NAME=V1,V2,...]...
           [--set NAME=VALUE]... --quantity PATH[=LABEL]...
           [--show PATH[=LABEL]]...
           [--reference finest|finest:NAME=VALUE|richardson|run|VALUE]
           [--reference-value PATH=VALUE]... [--reference-set NAME=VALUE]...
           [--refine NAME] [--error each|common] [--name NAME]
           [--out DIR] [--igabde build/igabde] [--time-limit 600]
           [--dry-run]"""

DESCRIPTION = """A study of any scene: every combination of the --sweep
values is one igabde run (one at a time, timed), each quantity is compared
with its reference, and NAME.csv, NAME.md, NAME.png and NAME.svg go into
DIR (default output/studies/sweep-NAME, NAME the scene's file name).

NAME is a parameter as `--set` takes it (Section/Name) or short: Type,
Degree, Refinements (Discretization/), Algorithm, Path (Contact/), a body's
parameter such as Subdivisions or Grading (every body of the scene that sets
it), or any name one section has. Values are separated by commas, or by
bars when one of them holds commas ("Subdivisions=10,10,3 | 20,20,6").
NAME1+NAME2=a+b,c+d sweeps two parameters together. The mesh sweep
(Refinements or Subdivisions, or --refine NAME) orders each series coarse
to fine; a series is one combination of the other sweeps' values.

PATH is a path into summary.json (checks.hertz_peak_pressure,
points.A.2, total_contact_force.2, load_steps.-1.newton_iterations), or
pressure-profile: the pair pressures' L2 distance to the reference run's
profile (2D line contact). --show adds a column that is not compared.

Reference: finest (default: the run with the most unknowns;
finest:Type=nurbs among those runs), run (one more run, made first, with
the --reference-set entries), richardson (each series' three finest runs
extrapolated, with the observed order), or a number (one quantity);
--reference-value PATH=VALUE fixes one quantity's reference whatever the
kind. Error: each (default) |q - q_ref| / |q_ref| per quantity, the row's
error the largest; common: |q - q_ref| / max |q_ref| over the quantities.

A run that fails is a row with its diagnosis; bad input stops before the
first run (a quantity's path that the first run's summary.json lacks: after
it) with one line and exit status 2. --dry-run lists the runs."""


def main(argv):
    parser = argparse.ArgumentParser(
        prog="contrib/studies/run sweep", usage=USAGE,
        description=DESCRIPTION,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("scene")
    parser.add_argument("--sweep", action="append", default=[])
    parser.add_argument("--set", action="append", default=[])
    parser.add_argument("--quantity", action="append", default=[])
    parser.add_argument("--show", action="append", default=[])
    parser.add_argument("--reference", default="finest")
    parser.add_argument("--reference-value", action="append", default=[])
    parser.add_argument("--reference-set", action="append", default=[])
    parser.add_argument("--refine")
    parser.add_argument("--error", default="each")
    parser.add_argument("--name")
    parser.add_argument("--out")
    parser.add_argument("--igabde",
                        default=os.path.join(common.ROOT, "build", "igabde"))
    parser.add_argument("--time-limit", type=float, default=600.)
    parser.add_argument("--dry-run", action="store_true")

    def error(message):
        sys.stderr.write("run sweep: %s (see --help)\n" % message)
        sys.exit(2)
    parser.error = error
    args = parser.parse_args(argv)
    try:
        if args.error not in ("each", "common"):
            raise UsageError("--error %s: write each or common" % args.error)
        if not (args.time_limit > 0.):
            raise UsageError("--time-limit must be positive")
        if not os.access(args.igabde, os.X_OK):
            raise UsageError("no igabde executable at %s (build first, or "
                             "give --igabde)" % args.igabde)
        args.igabde = os.path.abspath(args.igabde)
        study, parameters = build(args, flat_parameters(
            parameter_tree(args.igabde)))
        n_runs = sum(len(s.levels) for s in study.series) + \
            (1 if study.reference.kind == "run" else 0)
        if args.dry_run:
            if study.reference.kind == "run":
                print("reference: " + " ".join(
                    "--set '%s=%s'" % kv for kv in dict(
                        study.sets, **study.reference.sets).items()))
            for s in study.series:
                for lv in s.levels:
                    sets = dict(study.sets, **s.sets)
                    sets.update(lv.sets)
                    print("%s %s: %s" % (s.label, lv.label, " ".join(
                        "--set '%s=%s'" % kv for kv in sets.items())))
            print("%d runs" % n_runs)
            return 0
        out = args.out or os.path.join("output", "studies",
                                       "sweep-" + study.name)
        os.makedirs(out, exist_ok=True)
        runner = common.Runner(args.igabde, out, args.time_limit,
                               study.name)
        start = time.monotonic()
        res = run_study(study, runner, folder_names=True)
        command = "contrib/studies/run sweep " + " ".join(
            quote(a) for a in argv)
        preamble = "Measured %s on %d cores with `%s`." % (
            time.strftime("%Y-%m-%d"), os.cpu_count(), command)
        write_outputs(study, res, out, study.name, parameters, preamble)
    except UsageError as e:
        sys.stderr.write("run sweep: %s\n" % e)
        return 2
    print("%s: %d runs in %.0f s; wrote %s" % (
        study.name, runner.count, time.monotonic() - start, out))
    return 0


def quote(a):
    safe = all(c.isalnum() or c in "-_./=:,+" for c in a)
    return a if safe and a else "'%s'" % a.replace("'", "'\\''")
