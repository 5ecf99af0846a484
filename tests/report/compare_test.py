#!/usr/bin/python3
"""ahhs-report compare on made-up study reports whose tables are known: one table per task, the
claims of the pendulum choices' "task defaults" on the paper's rows, every verdict as its study
gave it, a study's robust column only where it judged a claim twice, "-" for a claim a study does
not make; bad input is one line and exit 1 or 2, nothing half-written."""
import json
import os
import subprocess
import sys
import tempfile

SOURCE = os.environ["AHHS_SOURCE_DIR"]
sys.path.insert(0, os.path.join(SOURCE, "tools", "report"))
import compare_report as cr  # noqa: E402

BETTER = "Pendulum: AHHS2-15 is better than AHHS1-60"
PAPER = "yes, Wilcoxon p < 0.05 (n = 10 AHHS2, 8 AHHS1)"
HIGH = "Damped gait: high fitness in every setting (each median over the wall, fitness > 1)"
NEIGHBOURS = "Mutation neighbourhood of a good AHHS1 controller (35 single mutants each)"
RULES = "Gait: rules that never or seldom trigger"
first = {"study": "paper-2010", "complete_runs": 130, "planned_runs": 130, "claims": [
    [BETTER, PAPER, "medians ...", "differs, reversed: AHHS1-60 is higher (n = 20, 20)", "...",
     "differs, reversed: AHHS1-60 is higher (n = 20, 20)"],
    [HIGH, "yes (best 1.88)", "...", "reproduced (n = 10, 10)", "...", "differs: at the wall"],
    [NEIGHBOURS, "most below 0.2", "...", "differs (n = 3 originals, 105 mutants)", None, None],
    [RULES, "many | most", "...", "reproduced (n = 60 genomes)", None, None]]}
robust = {"study": "paper-2010-robust", "complete_runs": 3, "planned_runs": 60, "configs": {
    "gait-damped-ahhs2-30": {"runs": 2, "robust_source": "50 held-out episodes (envelope paper)"},
    "gait-damped-ahhs1-120": {"runs": 1, "robust_source": "50 held-out episodes (envelope paper)"},
    "gait-fixed-ahhs1-80": {"runs": 0, "robust_source": "8 friction-perturbed replays"}},
    "claims": [
    [HIGH, "yes (best 1.88)", "...", "open", "...", "open"],
    [NEIGHBOURS, "most below 0.2", "...", "open", None, None]]}
choices = {"study": "pendulum-choices", "complete_runs": 120, "planned_runs": 120, "claims": [
    ["Pendulum, task defaults: AHHS2-15 is better than AHHS1-60", PAPER, "...",
     "differs, reversed: AHHS1-60 is higher (n = 20, 20)", None, None],
    ["Pendulum, soft walls: AHHS2-15 is better than AHHS1-60", PAPER, "...",
     "not significant (n = 20, 20)", None, None]]}


def run(*args):
    r = subprocess.run([sys.executable, os.path.join(SOURCE, "tools", "report", "ahhs_report.py"),
                        "compare", *args], capture_output=True, text=True)
    return r.returncode, r.stdout + r.stderr


with tempfile.TemporaryDirectory() as tmp:
    dirs = []
    for results in (first, robust, choices):
        d = os.path.join(tmp, results["study"])
        os.makedirs(d)
        with open(os.path.join(d, "results.json"), "w") as f:
            json.dump(results, f)
        dirs.append(d)
    out = os.path.join(tmp, "out")
    code, text = run(*dirs, "-o", out, "--label", "first", "--label", "robust",
                     "--label", "choices")
    assert code == 0, text
    assert text.startswith(f"comparison written to {out}: compare.md and compare.json "
                           "(5 claims, 3 studies)"), text
    md = open(os.path.join(out, "compare.md")).read()
    # Tables in the tasks' order, each with its own columns.
    sections = [line for line in md.splitlines() if line.startswith("## ")]
    assert sections == ["## Pendulum", "## Gait, fixed docking", "## Gait, damped docking",
                        "## Gait, both dockings"], sections
    pend = md.split("## Pendulum")[1].split("## ")[0]
    # The choices judged the pendulum once: no robust column of theirs; the robust study makes
    # no pendulum claim: no column of its own; a claim the first study does not make: "-".
    assert "| claim | the paper | first: best | first: robust | choices: best |" in pend, pend
    assert (f"| {BETTER} | {PAPER} | differs, reversed: AHHS1-60 is higher (n = 20, 20) | "
            "differs, reversed: AHHS1-60 is higher (n = 20, 20) | "
            "differs, reversed: AHHS1-60 is higher (n = 20, 20) |") in pend, pend
    assert ("| Pendulum, soft walls: AHHS2-15 is better than AHHS1-60 | " + PAPER +
            " | - | - | not significant (n = 20, 20) |") in pend, pend
    damped = md.split("## Gait, damped docking")[1].split("## ")[0]
    assert (f"| {HIGH} | yes (best 1.88) | reproduced (n = 10, 10) | differs: at the wall | open "
            "| open |") in damped, damped
    fixed = md.split("## Gait, fixed docking")[1].split("## ")[0]
    assert "| claim | the paper | first: best | robust: best |\n" in fixed, fixed
    assert (f"| {NEIGHBOURS} | most below 0.2 | differs (n = 3 originals, 105 mutants) | open "
            "|") in fixed, fixed
    # A "|" inside a cell would split the table's row.
    assert "| many / most |" in md, md
    # Each study says what its robust fitness is the median of (a configuration without runs
    # does not count); a study whose report has no configurations says nothing of it.
    assert ("- **robust**: study `paper-2010-robust`, 3 of 60 runs complete; robust fitness: the "
            "median of 50 held-out episodes (envelope paper)\n") in md, md
    assert "- **first**: study `paper-2010`, 130 of 130 runs complete\n" in md, md
    data = json.load(open(os.path.join(out, "compare.json")))
    assert [s["label"] for s in data["studies"]] == ["first", "robust", "choices"], data
    assert data["studies"][0]["robust_fitness"] is None, data
    assert data["tasks"]["pendulum"][0]["verdicts"][1] == [None, None], data

    # Without labels the studies' names head the columns; an existing comparison is replaced only
    # with --overwrite.
    code, text = run(*dirs, "-o", out)
    assert code == 2 and "pass --overwrite" in text, text
    code, text = run(*dirs, "-o", out, "--overwrite")
    assert code == 0, text
    md = open(os.path.join(out, "compare.md")).read()
    assert "| paper-2010: best | paper-2010: robust |" in md, md

    # Bad input: one line naming the problem; no output directory made.
    bad = os.path.join(tmp, "bad-out")
    for args, want, exit_code in [
            ((dirs[0], os.path.join(tmp, "none")), "results.json: no such file (make it with "
             "ahhs-study report)", 1),
            ((dirs[0], dirs[0]), "two reports have the same label; name them with --label", 2),
            ((dirs[0], dirs[1], "--label", "a"), "1 --label for 2 reports", 2)]:
        code, text = run(*args, "-o", bad)
        assert code == exit_code and want in text and len(text.strip().splitlines()) == 1, \
            (args, code, text)
        assert not os.path.exists(bad), args
    with open(os.path.join(tmp, "paper-2010", "results.json"), "w") as f:
        f.write('{"study": "x", "claims": [["only", "three", "cells"]]}')
    code, text = run(dirs[0], "-o", bad)
    assert code == 1 and "not a study report's results.json (no claim rows)" in text, text
    with open(os.path.join(tmp, "paper-2010", "results.json"), "w") as f:
        f.write("{")
    code, text = run(dirs[0], "-o", bad)
    assert code == 1 and "not readable as JSON" in text, text
    assert not os.path.exists(bad)

assert cr.task_of("Gait: rules that never or seldom trigger") == "gait"
assert cr.task_of("Fixed gait: AHHS2-20 has the lowest best fitness") == "gait-fixed"
assert cr.task_of("Something else") == "other"
# Two sources in one study: each with the configurations it holds for.
assert cr.robust_sources_text([("a", "8 replays"), ("b", "50 held-out episodes"),
                               ("c", "8 replays")]) == \
    "the median of 8 replays (a, c); 50 held-out episodes (b)"
print("compare: PASS")
