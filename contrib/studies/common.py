"""What every study shares: running igabde one run at a time with a time
limit, reading its summary.json into one flat row, and writing CSV,
Markdown, PNG and SVG into the study folder."""

import csv
import json
import math
import os
import signal
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))

# summary.json "timing" phases, in the order a run takes them.
# The condensed path times condensation and B-Newton, the full path its
# coupled system and its Newton solves (penalty and augmented Lagrange too).
PHASES = ["assembly", "factorization", "newton", "contact: pairs",
          "contact: condensation", "contact: B-Newton",
          "contact: coupled system", "contact: full-system solve",
          "contact: fields", "output", "postprocess"]
# The contact iteration: everything between the bodies' factorisations and
# the contact fields (the seed's "contact-iteration time").
CONTACT_PHASES = ["contact: pairs", "contact: condensation",
                  "contact: B-Newton", "contact: coupled system",
                  "contact: full-system solve"]

B2_MESHES = [(2, 2, 2), (4, 4, 4), (8, 8, 8), (8, 16, 8), (8, 32, 8)]
B2_PROBES = ["A", "B", "C", "D"]


def scene(name):
    """Path of a scene of prm/."""
    return os.path.join(ROOT, "prm", name)


def mesh_sets(mesh):
    """--set entries giving both bodies the mesh (per beam)."""
    m = ",".join(str(n) for n in mesh)
    return {"Body 1/Subdivisions": m, "Body 2/Subdivisions": m}


def mesh_label(mesh):
    return "x".join(str(n) for n in mesh)


class Runner:
    """Runs igabde, strictly one run after the other (the studies time
    them), each with a wall-clock limit, into <out>/runs/<label>/."""

    def __init__(self, igabde, out, time_limit, study):
        self.igabde = igabde
        self.out = out
        self.time_limit = time_limit
        self.study = study
        self.count = 0

    def run(self, label, scene_file, sets, folder=None):
        """One run; returns a row (dict) that always has 'label', 'status'
        ('ok', 'failed', 'timeout', 'crashed') and 'diagnosis', and the
        figures of summary.json when there is one. Its folder is
        <out>/runs/@p folder, by default a name made from @p label."""
        if folder is None:
            folder = label.replace(" ", "_").replace(",", "") \
                .replace("=", "").replace("/", "-")
        run_dir = os.path.join(self.out, "runs", folder)
        os.makedirs(run_dir, exist_ok=True)
        summary_file = os.path.join(run_dir, "summary.json")
        if os.path.exists(summary_file):
            os.remove(summary_file)
        cmd = [self.igabde, scene_file, "--quiet"]
        for key, value in sets.items():
            cmd += ["--set", "%s=%s" % (key, value)]
        cmd += ["--set", "Output/Write vtu=false",
                "--set", "Output/Print timing=false",
                "--set", "Output/Directory=" + run_dir]
        self.count += 1
        sys.stdout.write("%s: run %d: %s ... " % (self.study, self.count,
                                                  label))
        sys.stdout.flush()
        start = time.monotonic()
        # A session of its own, so that a run past its limit is ended with
        # everything it started (MPI, threads), and only that.
        proc = subprocess.Popen(cmd, stdout=subprocess.PIPE,
                                stderr=subprocess.STDOUT, text=True,
                                start_new_session=True)
        timed_out = False
        try:
            output, _ = proc.communicate(timeout=self.time_limit)
        except subprocess.TimeoutExpired:
            timed_out = True
            os.killpg(proc.pid, signal.SIGKILL)
            output, _ = proc.communicate()
        seconds = time.monotonic() - start
        with open(os.path.join(run_dir, "screen.txt"), "w") as f:
            f.write(output)

        row = {"label": label, "process_s": seconds, "folder": run_dir}
        summary = None
        if os.path.exists(summary_file):
            try:
                with open(summary_file) as f:
                    summary = json.load(f)
            except ValueError:
                summary = None
        if timed_out:
            row["status"] = "timeout"
            row["diagnosis"] = "stopped after the time limit of %g s" % \
                self.time_limit
        elif summary is None:
            row["status"] = "crashed"
            lines = [l for l in output.splitlines() if l.strip()]
            row["diagnosis"] = "exit %d, no summary.json: %s" % (
                proc.returncode, lines[-1] if lines else "no output")
        else:
            row["status"] = summary.get("status", "crashed")
            row["diagnosis"] = summary.get("error", "")
            if row["status"] == "running":
                row["status"] = "crashed"
                row["diagnosis"] = "exit %d while running" % proc.returncode
        if summary is not None:
            row.update(flatten(summary))
            if not row["diagnosis"]:
                row["diagnosis"] = step_diagnosis(summary)
        sys.stdout.write("%s, %s unknowns, %.2f s%s\n" % (
            row["status"], row.get("n_dofs", "?"), seconds,
            (": " + row["diagnosis"]) if row["diagnosis"] else ""))
        sys.stdout.flush()
        return row


def step_diagnosis(summary):
    """The solver's diagnosis of the first failed load step, if any."""
    for step in summary.get("load_steps", []):
        if step.get("status") == "failed":
            return "step %d: %s" % (step.get("step", 0),
                                    step.get("diagnosis", "failed"))
    return ""


def flatten(summary):
    """The figures the studies use, from one summary.json."""
    row = {
        "discretization": summary.get("discretization"),
        "degree": summary.get("degree"),
        "n_dofs": summary.get("n_dofs"),
        "n_elements": summary.get("n_elements"),
        "n_contact_pairs": summary.get("n_contact_pairs", 0),
        "n_contact_unknowns": summary.get("n_contact_unknowns", 0),
        "contact_algorithm": summary.get("contact_algorithm", ""),
        "contact_path": summary.get("contact_path", ""),
        "penalty_factor_fkn": summary.get("penalty_factor_fkn", ""),
    }
    steps = summary.get("load_steps", [])
    row["newton_iterations"] = sum(s.get("newton_iterations", 0)
                                   for s in steps)
    row["contact_solves"] = sum(s.get("contact_solves", 0) for s in steps)
    row["step_cuts"] = sum(s.get("step_cuts", 0) for s in steps)
    row["residual"] = max([s.get("residual") or 0. for s in steps] or [0.])
    row["max_penetration"] = max([s.get("max_penetration") or 0.
                                  for s in steps] or [0.])
    force = summary.get("total_contact_force") or [float("nan")] * 3
    for c, name in enumerate("xyz"[:len(force)]):
        row["contact_force_" + name] = nan_if_none(force[c])
    for name, u in (summary.get("points") or {}).items():
        for c, comp in enumerate("xyz"[:len(u)]):
            row["u%s_%s" % (comp, name)] = nan_if_none(u[c])
    for key, value in (summary.get("checks") or {}).items():
        if isinstance(value, (int, float)):
            row["check_" + key] = nan_if_none(value)
    timing = summary.get("timing") or {}
    for p in PHASES:
        row[phase_key(p)] = timing.get(p, 0.)
    row["t_other_s"] = sum(v for k, v in timing.items()
                           if k not in PHASES and k != "total")
    row["total_s"] = timing.get("total", float("nan"))
    row["contact_s"] = sum(timing.get(p, 0.) for p in CONTACT_PHASES)
    peaks = [r.get("peak_memory_mib") for r in summary.get("ranks") or []
             if isinstance(r.get("peak_memory_mib"), (int, float))]
    row["peak_memory_mib"] = max(peaks) if peaks else float("nan")
    row["dim"] = summary.get("dim")
    return row


def nan_if_none(x):
    return float("nan") if x is None else x


def phase_key(phase):
    """CSV column of a timing phase: 'contact: B-Newton' -> 't_bnewton_s'."""
    return "t_" + phase.replace("contact: ", "").replace("-", "") \
        .replace(" ", "_").lower() + "_s"


PHASE_KEYS = [phase_key(p) for p in PHASES] + ["t_other_s"]


def ok(row):
    return row.get("status") == "ok"


def write_csv(path, rows, columns):
    """Rows as CSV with exactly these columns (missing values empty)."""
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=columns, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow({c: fmt_csv(r.get(c, "")) for c in columns})


def fmt_csv(x):
    if isinstance(x, float):
        return "" if math.isnan(x) else repr(x)
    return x


def read_csv(path):
    """Rows of a CSV written by write_csv, numbers converted back."""
    rows = []
    with open(path) as f:
        for r in csv.DictReader(f):
            for k, v in r.items():
                try:
                    r[k] = int(v)
                except ValueError:
                    try:
                        r[k] = float(v)
                    except ValueError:
                        pass
            rows.append(r)
    return rows


def write_markdown(path, header, table_rows, preamble="", notes=""):
    """A Markdown table; table_rows are lists of already formatted cells."""
    with open(path, "w") as f:
        if preamble:
            f.write(preamble.rstrip() + "\n\n")
        f.write("| " + " | ".join(header) + " |\n")
        f.write("|" + "---|" * len(header) + "\n")
        for cells in table_rows:
            f.write("| " + " | ".join(str(c) for c in cells) + " |\n")
        if notes:
            f.write("\n" + notes.rstrip() + "\n")


def g(x, digits=4):
    """A number for a Markdown cell."""
    if x is None or x == "" or (isinstance(x, float) and math.isnan(x)):
        return "–"
    if isinstance(x, int):
        return str(x)
    return "%.*g" % (digits, x)


def stamp(args):
    """Date, core count and the command, for every table's preamble."""
    return "Measured %s on %d cores with `%s`." % (
        time.strftime("%Y-%m-%d"), os.cpu_count(), args.command)


def pyplot():
    """matplotlib's pyplot without a display, or None (then no plots)."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        return plt
    except ImportError:
        print("matplotlib missing (Debian python3-matplotlib, installed by "
              "contrib/setup): no plots")
        return None


def save_figure(fig, out, name):
    for ext in ("png", "svg"):
        fig.savefig(os.path.join(out, name + "." + ext), dpi=120)


def pareto_front(points):
    """Indices of the points (cost, error) that no other point beats in
    both (lower cost and lower error), sorted by cost."""
    order = sorted(range(len(points)), key=lambda i: (points[i][0],
                                                      points[i][1]))
    front, best = [], float("inf")
    for i in order:
        if points[i][1] < best:
            front.append(i)
            best = points[i][1]
    return front


def failure_notes(rows):
    """Markdown list of the runs that did not end ok, with their
    diagnosis; empty when every run did."""
    failed = [r for r in rows if r["status"] != "ok"]
    if not failed:
        return ""
    return "\n" + "\n".join("- %s: %s, %s" % (
        r["label"], r["status"], r["diagnosis"]) for r in failed) + "\n"


def phase_bars(ax, rows, phases):
    """Stacked bars of the seconds per phase, one bar per row; phases
    that are zero in every row are left out. Returns the bar heights."""
    bottom = [0.] * len(rows)
    for p in phases:
        v = [r.get(phase_key(p), 0.) or 0. for r in rows]
        if not any(v):
            continue
        ax.bar(range(len(rows)), v, bottom=bottom, label=p)
        bottom = [b + x for b, x in zip(bottom, v)]
    return bottom
