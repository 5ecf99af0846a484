"""ahhs-report compare REPORT_DIR... -o OUT_DIR: the paper's claims side by side across studies.

Reads the results.json that `ahhs-report study` (`ahhs-study report`) wrote into each REPORT_DIR
and writes into OUT_DIR:
  compare.md    one table per task (pendulum, fixed docking, damped docking, both dockings): a
                row per claim, the paper's statement, then each study's verdict on its runs'
                best fitness and, where it judged the claim twice, on their robust fitness
  compare.json  the same rows
Each study's line says what its robust fitness is the median of (friction-perturbed replays, or
held-out episodes under an envelope), from its configurations' `robust_source`.
Nothing is recomputed: every verdict is the one its study's report gave (with its n), so the
tables can be rebuilt from the studies' exports alone (`ahhs-study report EXPORT -o DIR` each,
then this). A claim that a study does not make is "-" in its columns; a study that makes none of
a task's claims has no columns in that task's table. A pendulum-choices study
names the paper's setting "task defaults"; its claims in that setting share the paper's rows.
"""
import argparse
import json
import os

from report_lib import ReportError, UsageError, prepare_out, robust_sources_text

# (key, heading, the claims it holds: by how their text starts)
TASKS = [
    ("pendulum", "Pendulum", ("Pendulum",)),
    ("gait-fixed", "Gait, fixed docking", ("Fixed gait", "Mutation neighbourhood")),
    ("gait-damped", "Gait, damped docking", ("Damped gait",)),
    ("gait", "Gait, both dockings", ("Gait",)),
]


def task_of(claim):
    """The key of the task a claim is about (the first of TASKS whose prefix it starts with)."""
    for key, _, prefixes in TASKS:
        if claim.startswith(prefixes):
            return key
    return "other"


def canonical(claim):
    """The claim's row: the pendulum choices' "task defaults" are the paper's setting."""
    return claim.replace("Pendulum, task defaults:", "Pendulum:")


def load_report(directory):
    """A study report's results.json: (study name, complete runs, planned runs, claim rows, what
    its robust fitness is in words or None)."""
    path = os.path.join(directory, "results.json")
    try:
        with open(path) as f:
            results = json.load(f)
    except FileNotFoundError:
        raise ReportError(f"{path}: no such file (make it with ahhs-study report)") from None
    except (OSError, json.JSONDecodeError) as e:
        raise ReportError(f"{path}: not readable as JSON ({e})") from None
    claims = results.get("claims") if isinstance(results, dict) else None
    if not isinstance(claims, list) or not all(
            isinstance(r, list) and len(r) == 6 and isinstance(r[0], str) for r in claims):
        raise ReportError(f"{path}: not a study report's results.json (no claim rows)")
    configs = results.get("configs")
    sources = [(str(name), c.get("robust_source")) for name, c in configs.items()
               if isinstance(c, dict) and c.get("runs") and c.get("robust_source")
               ] if isinstance(configs, dict) else []
    return (str(results.get("study", os.path.basename(os.path.normpath(directory)))),
            results.get("complete_runs"), results.get("planned_runs"), claims,
            robust_sources_text(sources) if sources else None)


def compare(reports):
    """Rows per task from load_report's tuples: {"task": [{"claim", "paper",
    "verdicts": [[best, robust] per study]}]}, claims in the order first seen."""
    rows = {}
    for k, (_, _, _, claims, _) in enumerate(reports):
        for claim, paper, _, verdict, _, verdict_robust in claims:
            key = canonical(claim)
            row = rows.get(key)
            if row is None:
                row = rows[key] = {"claim": key, "paper": paper,
                                   "verdicts": [[None, None] for _ in reports]}
            row["verdicts"][k] = [verdict, verdict_robust]
    tasks = {}
    for row in rows.values():
        tasks.setdefault(task_of(row["claim"]), []).append(row)
    return tasks


def cell(verdict):
    return "-" if verdict is None else str(verdict).replace("|", "/")


def write_compare(out, reports, labels, tasks):
    md = ["# The paper's claims across studies", "",
          "Each study's verdicts as its own report gave them (`ahhs-study report`, "
          "docs/analysis.md): on each run's best fitness and, where the claim is about runs' "
          "fitness, on the robust fitness of each run's best genome. \"-\": the study does not "
          "judge that claim.", ""]
    md += [f"- **{label}**: study `{name}`, {done} of {planned} runs complete"
           + (f"; robust fitness: {robust}" if robust else "")
           for label, (name, done, planned, _, robust) in zip(labels, reports)]
    headings = {key: heading for key, heading, _ in TASKS}
    headings["other"] = "Other claims"
    for key in [k for k, _, _ in TASKS] + ["other"]:
        rows = tasks.get(key)
        if not rows:
            continue
        # A study's columns only where it judges one of this task's claims, its robust column
        # only where it judged one twice.
        judged = [any(r["verdicts"][k][0] is not None for r in rows) for k in range(len(labels))]
        robust = [any(r["verdicts"][k][1] is not None for r in rows) for k in range(len(labels))]
        head = ["claim", "the paper"]
        for label, once, twice in zip(labels, judged, robust):
            head += ([f"{label}: best"] if once else []) + ([f"{label}: robust"] if twice else [])
        md += ["", f"## {headings[key]}", "", "| " + " | ".join(head) + " |",
               "|" + "---|" * len(head)]
        for r in rows:
            cells = [cell(r["claim"]), cell(r["paper"])]
            for (best, rob), once, twice in zip(r["verdicts"], judged, robust):
                cells += ([cell(best)] if once else []) + ([cell(rob)] if twice else [])
            md.append("| " + " | ".join(cells) + " |")
    with open(os.path.join(out, "compare.md"), "w") as f:
        f.write("\n".join(md) + "\n")
    with open(os.path.join(out, "compare.json"), "w") as f:
        json.dump({"studies": [{"label": label, "study": name, "complete_runs": done,
                                "planned_runs": planned, "robust_fitness": robust}
                               for label, (name, done, planned, _, robust)
                               in zip(labels, reports)],
                   "tasks": tasks}, f, indent=1)
        f.write("\n")


def main(argv):
    p = argparse.ArgumentParser(prog="ahhs-report compare",
                                description="the paper's claims side by side across study "
                                            "reports (each made by ahhs-study report)")
    p.add_argument("reports", nargs="+", help="directories of study reports (results.json)")
    p.add_argument("-o", "--out", required=True, help="output directory")
    p.add_argument("--label", action="append", default=[],
                   help="a study's column heading, once per report in their order (default: "
                        "the study's name)")
    p.add_argument("--overwrite", action="store_true", help="replace a comparison in --out")
    args = p.parse_args(argv)
    if args.label and len(args.label) != len(args.reports):
        raise UsageError(f"{len(args.label)} --label for {len(args.reports)} reports: give one "
                         "per report, or none")
    reports = [load_report(d) for d in args.reports]
    labels = args.label or [name for name, *_ in reports]
    if len(set(labels)) != len(labels):
        raise UsageError("two reports have the same label; name them with --label")
    prepare_out(args.out, args.overwrite)
    tasks = compare(reports)
    write_compare(args.out, reports, labels, tasks)
    print(f"comparison written to {args.out}: compare.md and compare.json "
          f"({sum(len(r) for r in tasks.values())} claims, {len(reports)} studies)")
    return 0
