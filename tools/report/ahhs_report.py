#!/usr/bin/python3
"""ahhs-report: figures and a Markdown summary for ahhs-evolve runs (docs/analysis.md).

  ahhs-report RUN_DIR... -o OUT_DIR [--no-replay]
  ahhs-report neighbourhood GENOME_OR_RUN_DIR [--mutants 35] -o OUT_DIR [scenario options]

Reads each run's SQLite database directly (Python's sqlite3), replays the best genome of the
first run with ahhs-replay for the per-tick figures, and writes every figure as PNG and SVG.
Statistics: two-sided Wilcoxon rank-sum (Mann-Whitney U) tests from scipy, exact for small
samples without ties.
"""
import argparse
import json
import math
import os
import shutil
import sqlite3
import subprocess
import sys
from collections import OrderedDict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from scipy import stats  # noqa: E402


class ReportError(Exception):
    """A problem with the input; the message is for the user."""


class UsageError(Exception):
    """A usage error: exit 2."""


# ---------------------------------------------------------------------------------------------
# Reading runs


class Run:
    def __init__(self, path):
        self.path = path
        if not os.path.isdir(path):
            raise ReportError(f"{path} is not a directory")
        db = os.path.join(path, "run.sqlite")
        if not os.path.isfile(db):
            raise ReportError(f"{path} is not a run directory (no run.sqlite)")
        try:
            con = sqlite3.connect(f"file:{db}?mode=ro", uri=True)
            if con.execute("PRAGMA quick_check").fetchone()[0] != "ok":
                raise ReportError(f"{path}: the run database fails its integrity check")
            meta = dict(con.execute("SELECT key, value FROM run").fetchall())
            if meta.get("format") != "ahhs-run":
                raise ReportError(f"{path}: the database is not an ahhs run")
            self.config = json.loads(meta["config"])
            self.run_id = meta.get("run_id", "")
            rows = con.execute(
                "SELECT generation, best, mean, median, worst, best_index FROM generations "
                "ORDER BY generation").fetchall()
            con.close()
        except sqlite3.DatabaseError as e:
            raise ReportError(f"{path}: not a readable run database ({e})")
        except (KeyError, ValueError) as e:
            raise ReportError(f"{path}: damaged run table ({e})")
        if not rows:
            raise ReportError(f"{path}: the run has no committed generation yet")
        self.generation = np.array([r[0] for r in rows])
        self.best = np.array([r[1] for r in rows])
        self.mean = np.array([r[2] for r in rows])
        self.median = np.array([r[3] for r in rows])

    @property
    def task(self):
        c = self.config
        return c["scenario"] + ("-" + c["joints"] if c["scenario"] == "gait" else "")

    @property
    def label(self):
        c = self.config
        task = c["scenario"] + ("-" + c["joints"] if c["scenario"] == "gait" else "")
        return f"{task} {c['variant'].upper()}-{c['rules']}"

    def best_overall(self):
        return float(np.max(self.best))

    def first_generation_reaching(self, level):
        hits = np.nonzero(self.best >= level)[0]
        return int(self.generation[hits[0]]) if len(hits) else None


def rank_sum_test(x, y):
    """Two-sided Wilcoxon rank-sum test; returns (U of x, p). Exact when scipy can be."""
    result = stats.mannwhitneyu(x, y, alternative="two-sided", method="auto")
    return float(result.statistic), float(result.pvalue)


# ---------------------------------------------------------------------------------------------
# Figures


def save(fig, out_dir, name, written):
    for ext in ("png", "svg"):
        path = os.path.join(out_dir, f"{name}.{ext}")
        fig.savefig(path, dpi=110, bbox_inches="tight")
        written.append(path)
    plt.close(fig)


def fitness_figure(groups, out_dir, written):
    fig, ax = plt.subplots(figsize=(8, 4.5))
    for label, runs in groups.items():
        if len(runs) == 1:
            r = runs[0]
            line, = ax.plot(r.generation, r.best, label=f"{label}: best")
            ax.plot(r.generation, r.mean, "--", color=line.get_color(), label=f"{label}: mean")
        else:
            n = min(len(r.best) for r in runs)
            best = np.array([r.best[:n] for r in runs])
            g = runs[0].generation[:n]
            q1, med, q3 = np.percentile(best, [25, 50, 75], axis=0)
            line, = ax.plot(g, med, label=f"{label}: median best (n={len(runs)})")
            ax.fill_between(g, q1, q3, color=line.get_color(), alpha=0.25)
    ax.set_xlabel("generation")
    ax.set_ylabel("fitness")
    ax.set_title("Fitness per generation" + (" (band: quartiles)" if any(
        len(r) > 1 for r in groups.values()) else ""))
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    save(fig, out_dir, "fitness", written)


def box_figure(groups, values, ylabel, title, name, out_dir, written, task_of):
    labels = list(groups.keys())
    data = [values[l] for l in labels]
    fig, ax = plt.subplots(figsize=(max(4, 2.2 * len(labels)), 4.5))
    ax.boxplot(data, labels=[f"{l}\nn={len(d)}" for l, d in zip(labels, data)])
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=10)
    ax.grid(alpha=0.3, axis="y")
    tests = []
    top = max(max(d) for d in data if len(d)) if any(len(d) for d in data) else 1
    span = (top - min(min(d) for d in data if len(d))) or 1
    k = 0
    for i in range(len(labels)):
        for j in range(i + 1, len(labels)):
            # Only configurations of one task are comparable (fitness scales differ by task).
            if len(data[i]) and len(data[j]) and task_of[labels[i]] == task_of[labels[j]]:
                u, p = rank_sum_test(data[i], data[j])
                tests.append((labels[i], labels[j], len(data[i]), len(data[j]), u, p))
                y = top + span * (0.08 + 0.1 * k)
                ax.plot([i + 1, j + 1], [y, y], color="black", lw=0.8)
                ax.text((i + j + 2) / 2, y, f"p = {p:.3g}", ha="center", va="bottom", fontsize=8)
                k += 1
    save(fig, out_dir, name, written)
    return tests


def replay_figures(trace_csv, rules_csv, out_dir, written):
    data = np.genfromtxt(trace_csv, delimiter=",", names=True)
    names = data.dtype.names
    modules = sorted(set(int(m) for m in data["module"]))
    hormones = [n for n in names if n[0] == "h" and n[1:].isdigit()]
    sensors = [n for n in names if n[0] == "s" and n[1:].isdigit()]
    actuators = [n for n in names if n[0] == "a" and n[1:].isdigit()]
    used = [h for h in hormones if np.max(data[h]) > 1e-3]
    # Hormone concentrations through the organism: one panel per hormone, a line per module.
    shown = used or hormones[:1]
    fig, axes = plt.subplots(len(shown), 1, figsize=(8, 1.9 * len(shown) + 0.6), sharex=True,
                             squeeze=False)
    for ax, h in zip(axes[:, 0], shown):
        for m in modules:
            rows = data["module"] == m
            ax.plot(data["time"][rows], data[h][rows], lw=0.9, label=f"module {m}")
        ax.set_ylabel(h.upper())
        ax.set_ylim(-0.02, 1.02)
        ax.grid(alpha=0.3)
    axes[0, 0].legend(fontsize=7, ncol=len(modules))
    axes[-1, 0].set_xlabel("simulated time (s)")
    fig.suptitle(f"Hormone concentrations in every module ({len(used)} of {len(hormones)} "
                 f"hormones ever above 0.001)", fontsize=10)
    save(fig, out_dir, "hormones", written)
    # Hinge angles and actuator values.
    fig, axes = plt.subplots(2, 1, figsize=(8, 5), sharex=True)
    for m in modules:
        rows = data["module"] == m
        axes[0].plot(data["time"][rows], np.degrees(data["hinge_angle"][rows]), lw=0.9,
                     label=f"module {m}")
        for a in actuators:
            axes[1].plot(data["time"][rows], data[a][rows], lw=0.9, label=f"module {m} {a}")
    axes[0].set_ylabel("hinge angle (deg)")
    axes[1].set_ylabel("actuator value")
    axes[1].set_xlabel("simulated time (s)")
    axes[0].legend(fontsize=7, ncol=len(modules))
    for ax in axes:
        ax.grid(alpha=0.3)
    save(fig, out_dir, "hinges", written)
    # Sensors: one panel per module.
    fig, axes = plt.subplots(len(modules), 1, figsize=(8, 1.6 * len(modules) + 0.6),
                             sharex=True, squeeze=False)
    for ax, m in zip(axes[:, 0], modules):
        rows = data["module"] == m
        for s in sensors:
            if np.max(data[s][rows]) > 0:
                ax.plot(data["time"][rows], data[s][rows], lw=0.7, label=s.upper())
        ax.set_ylabel(f"module {m}")
        ax.set_ylim(-0.02, 1.02)
        ax.legend(fontsize=6, ncol=5, loc="upper right")
    axes[-1, 0].set_xlabel("simulated time (s)")
    fig.suptitle("Sensor values", fontsize=10)
    save(fig, out_dir, "sensors", written)
    # Rule activity: share of ticks in which each rule triggered, per module.
    rules = np.genfromtxt(rules_csv, delimiter=",", names=True, dtype=None)
    ticks = len(data) / len(modules)
    n_rules = int(np.max(rules["rule"])) + 1 if len(rules) else 0
    share = np.zeros((len(modules), n_rules))
    for row in np.atleast_1d(rules):
        share[int(row["module"]), int(row["rule"])] = row["ticks_active"] / ticks
    fig, ax = plt.subplots(figsize=(max(6, 0.25 * n_rules + 2), 4))
    width = 0.8 / max(1, len(modules))
    for k, m in enumerate(modules):
        ax.bar(np.arange(n_rules) + k * width, share[k], width=width, label=f"module {m}")
    ax.axhline(0.01, color="gray", lw=0.8, ls="--")
    ax.set_xlabel("rule")
    ax.set_ylabel("share of ticks triggered")
    ax.set_title("Rule activity (dashed: 1 %, below it a rule triggers 'seldom')", fontsize=10)
    ax.legend(fontsize=7, ncol=len(modules))
    save(fig, out_dir, "rules", written)
    overall = share.max(axis=0) if n_rules else np.array([])
    return {
        "hormones_used": len(used),
        "hormones": len(hormones),
        "rules": n_rules,
        "never": int(np.sum(overall == 0)),
        "seldom": int(np.sum((overall > 0) & (overall < 0.01))),
    }


def controller_graph(genome, out_dir, written, name="controller"):
    """Sensors -> hormones -> actuators, one edge per rule's dominant part."""
    lines = ["digraph controller {", "  rankdir=LR; node [fontsize=10]; edge [fontsize=8];"]
    ns, nh, na = genome["sensors"], len(genome["hormones"]), genome["actuators"]
    lines.append("  { rank=same; " + " ".join(f"S{j} [shape=box, color=blue];" for j in range(ns)) + " }")
    lines.append("  " + " ".join(f"H{h} [shape=ellipse, color=darkgreen];" for h in range(nh)))
    lines.append("  { rank=same; " + " ".join(f"A{a} [shape=box, color=red];" for a in range(na)) + " }")
    edges = 0
    for r, rule in enumerate(genome["rules"]):
        if genome["variant"] == "ahhs2":
            w = rule["weights"]
            part = max(("sensor", "linear", "nonlinear", "actuator", "idle"), key=lambda k: w[k])
            if part == "idle":
                continue
            lo, hi = rule["zeta"] - rule["eta"], rule["zeta"] + rule["eta"]
            window = f"({lo:.2f}, {hi:.2f})"
            s, i = int(math.floor(rule["sensor"])), int(math.floor(rule["input"]))
            o, a = int(math.floor(rule["output"])), int(math.floor(rule["actuator"]))
            src = {"sensor": f"S{s}", "linear": f"H{i}", "nonlinear": f"H{i}", "actuator": f"H{i}"}[part]
            dst = f"A{a}" if part == "actuator" else f"H{o}"
            tag = {"sensor": "S", "linear": "L", "nonlinear": "N", "actuator": "A"}[part]
            label = f"r{r} {tag} {window} w={w[part]:.2f}"
        else:
            kind = rule["type"]
            if kind == "idle":
                continue
            sign = ">" if rule["direction"] == "above" else "<"
            src = f"S{rule['input']}" if kind == "sensor" else f"H{rule['input']}"
            dst = f"A{rule['output']}" if kind == "actuator" else f"H{rule['output']}"
            label = f"r{r} {kind} {sign} {rule['tau']:.2f}"
        color = "black" if rule["lambda"] >= 0 else "firebrick"
        lines.append(f'  {src} -> {dst} [label="{label}", color={color}];')
        edges += 1
    lines.append("}")
    dot_path = os.path.join(out_dir, f"{name}.dot")
    with open(dot_path, "w") as f:
        f.write("\n".join(lines) + "\n")
    written.append(dot_path)
    dot = shutil.which("dot")
    if not dot:
        raise ReportError("Graphviz 'dot' not found (install graphviz: tools/install-deps)")
    for ext in ("png", "svg"):
        path = os.path.join(out_dir, f"{name}.{ext}")
        subprocess.run([dot, f"-T{ext}", dot_path, "-o", path], check=True)
        written.append(path)
    return edges


# ---------------------------------------------------------------------------------------------
# Commands


def find_bin(args):
    for d in (args.bin, os.environ.get("AHHS_BIN"), os.path.dirname(os.path.abspath(sys.argv[0]))):
        if d and os.path.isfile(os.path.join(d, "ahhs-replay")):
            return d
    raise ReportError("cannot find ahhs-replay: give --bin BUILD/bin")


def run_replay(bin_dir, argv):
    proc = subprocess.run([os.path.join(bin_dir, "ahhs-replay")] + argv, capture_output=True,
                          text=True)
    if proc.returncode != 0:
        raise ReportError("ahhs-replay failed: " + (proc.stderr or proc.stdout).strip())
    return proc.stdout


REPORT_FILES = (".png", ".svg", ".dot", ".md", ".csv", ".json", ".lcm", ".mp4")


def prepare_out(out, overwrite):
    """Makes the output directory. An old report in it is replaced only with --overwrite (so
    that no stale figure survives); a directory holding anything else is never emptied."""
    if os.path.isdir(out) and os.listdir(out):
        if not overwrite:
            raise UsageError(f"{out} holds files; pass --overwrite to replace the report in it")
        foreign = [f for f in os.listdir(out)
                   if not (os.path.isfile(os.path.join(out, f)) and f.endswith(REPORT_FILES))]
        if foreign:
            raise UsageError(f"{out} holds {foreign[0]}, which is not part of a report; "
                             "give an empty or new directory")
        for f in os.listdir(out):
            os.remove(os.path.join(out, f))
    os.makedirs(out, exist_ok=True)


def report_runs(args):
    runs = [Run(p) for p in args.runs]
    prepare_out(args.out, args.overwrite)
    written = []
    groups = OrderedDict()
    for r in runs:
        groups.setdefault(r.label, []).append(r)
    fitness_figure(groups, args.out, written)
    task_of = {l: rs[0].task for l, rs in groups.items()}
    # 75 % of the maximum over all runs of the same task.
    overall = {}
    for r in runs:
        overall[r.task] = max(overall.get(r.task, -math.inf), r.best_overall())
    level = {t: 0.75 * m for t, m in overall.items()}
    best = {l: [r.best_overall() for r in rs] for l, rs in groups.items()}
    speed = {}
    censored = 0
    for l, rs in groups.items():
        speed[l] = []
        for r in rs:
            g = r.first_generation_reaching(level[r.task])
            if g is None:
                g, censored = int(r.generation[-1]) + 1, censored + 1
            speed[l].append(g)
    best_tests = box_figure(groups, best, "best fitness of the run",
                            "Best fitness per configuration (two-sided Wilcoxon rank-sum)",
                            "box_best", args.out, written, task_of)
    speed_tests = box_figure(groups, speed, "generation",
                             "Generation reaching 75 % of the task's maximum fitness",
                             "box_speed", args.out, written, task_of)
    md = ["# AHHS run report", ""]
    md += ["| configuration | runs | best fitness: median | min | max | generation to 75 %: median |",
           "|---|---|---|---|---|---|"]
    for l in groups:
        b, s = best[l], speed[l]
        md.append(f"| {l} | {len(b)} | {np.median(b):.4f} | {min(b):.4f} | {max(b):.4f} | "
                  f"{np.median(s):g} |")
    md += [""] + [f"Maximum fitness over all {t} runs: {m:.4f}; 75 % of it is {level[t]:.4f}."
                  for t, m in overall.items()]
    md += ["Tests compare configurations of the same task only."]
    if censored:
        md.append(f"{censored} run(s) never reached it and count as their number of generations.")
    for title, tests in (("Best fitness", best_tests), ("Evolution speed", speed_tests)):
        if tests:
            md += ["", f"## {title}: two-sided Wilcoxon rank-sum tests", "",
                   "| A | B | n_A | n_B | U | p |", "|---|---|---|---|---|---|"]
            md += [f"| {a} | {b} | {na} | {nb} | {u:g} | {p:.4g} |" for a, b, na, nb, u, p in tests]
    md += ["", "## Runs", ""] + [f"- `{r.path}`: {r.label}, seed {r.config['seed']}, "
                                 f"{len(r.generation)} generations, best {r.best_overall():.4f}"
                                 for r in runs]
    if not args.no_replay:
        bin_dir = find_bin(args)
        first = runs[0]
        trace = os.path.join(args.out, "replay-trace.csv")
        rules = os.path.join(args.out, "replay-rules.csv")
        log = os.path.join(args.out, "replay.lcm")
        out = run_replay(bin_dir, [first.path, "--csv", trace, "--rules-csv", rules, "--log", log])
        written += [trace, rules, log]
        info = replay_figures(trace, rules, args.out, written)
        with open(os.path.join(first.path, "best.json")) as f:
            genome = json.load(f)
        edges = controller_graph(genome, args.out, written)
        check = [l for l in out.splitlines() if l.startswith("stored fitness")]
        md += ["", f"## The best controller of `{first.path}`", "",
               "Replayed with `ahhs-replay` (log: `replay.lcm`): " + (check[0] if check else out.strip()),
               "",
               f"- hormones ever above 0.001: {info['hormones_used']} of {info['hormones']}",
               f"- rules that never trigger: {info['never']} of {info['rules']}; seldom (< 1 % of "
               f"ticks): {info['seldom']}",
               f"- controller graph: {edges} edges (one per non-idle rule, by its dominant part)"]
    md += ["", "## Figures", ""] + [f"- `{os.path.basename(p)}`" for p in written
                                    if p.endswith(".png")]
    summary = os.path.join(args.out, "summary.md")
    with open(summary, "w") as f:
        f.write("\n".join(md) + "\n")
    print(f"report written to {args.out}: summary.md and {len(written)} files")


def report_neighbourhood(args):
    prepare_out(args.out, args.overwrite)
    bin_dir = find_bin(args)
    csv = os.path.join(args.out, "mutants.csv")
    if os.path.isdir(args.genome):
        Run(args.genome)  # a clear error for a directory that is not a run
        argv = [args.genome]
        genome_path = os.path.join(args.genome, "best.json")
    else:
        if not os.path.isfile(args.genome):
            raise ReportError(f"{args.genome}: no such genome file or run directory")
        argv = ["--genome", args.genome, "--scenario", args.scenario, "--joints", args.joints,
                "--modules", str(args.modules), "--duration", str(args.duration),
                "--seed", str(args.seed)]
        genome_path = args.genome
    run_replay(bin_dir, argv + ["--mutants", str(args.mutants), "--mutants-csv", csv,
                                "--mutant-seed", str(args.mutant_seed)])
    data = np.genfromtxt(csv, delimiter=",", names=True, dtype=None, encoding="utf-8")
    original = float(data["fitness"][0])
    mutants = np.array([float(v) for v in data["fitness"][1:]])
    written = [csv]
    fig, ax = plt.subplots(figsize=(7, 4))
    ax.hist(mutants, bins=min(20, max(5, len(mutants) // 2)), color="steelblue",
            label=f"{len(mutants)} single mutants")
    ax.axvline(original, color="firebrick", lw=2, label=f"original {original:.3f}")
    ax.set_xlabel("fitness")
    ax.set_ylabel("mutants")
    ax.set_title("Mutation neighbourhood", fontsize=10)
    ax.legend(fontsize=8)
    save(fig, args.out, "neighbourhood", written)
    with open(genome_path) as f:
        controller_graph(json.load(f), args.out, written)
    keep = np.mean(mutants >= 0.9 * original) if original > 0 else float("nan")
    md = ["# Mutation neighbourhood", "", f"Genome: `{genome_path}`; {len(mutants)} single mutants "
          f"(mutation seed {args.mutant_seed}), each evaluated with the same episode seed.", "",
          f"- original fitness: {original:.4f}",
          f"- mutants: median {np.median(mutants):.4f}, min {mutants.min():.4f}, max {mutants.max():.4f}",
          f"- share keeping at least 90 % of the original fitness: {keep:.0%}",
          f"- share below 0.2: {np.mean(mutants < 0.2):.0%}", "",
          "Figures: `neighbourhood.png`, `controller.png`."]
    with open(os.path.join(args.out, "summary.md"), "w") as f:
        f.write("\n".join(md) + "\n")
    print(f"neighbourhood written to {args.out}: summary.md, neighbourhood.png")


def main(argv):
    if len(argv) >= 2 and argv[0] == "--bin":  # the build's wrapper passes its bin directory
        os.environ.setdefault("AHHS_BIN", argv[1])
        argv = argv[2:]
    if argv and argv[0] == "neighbourhood":
        p = argparse.ArgumentParser(prog="ahhs-report neighbourhood",
                                    description="fitness of single mutants of a genome")
        p.add_argument("genome", help="genome file, or a run directory (its best genome)")
        p.add_argument("--mutants", type=int, default=35)
        p.add_argument("--mutant-seed", type=int, default=1)
        p.add_argument("--scenario", default="gait", choices=["gait", "pendulum"])
        p.add_argument("--joints", default="damped", choices=["damped", "fixed"])
        p.add_argument("--modules", type=int, default=5)
        p.add_argument("--duration", type=float, default=0)
        p.add_argument("--seed", type=int, default=1, help="episode seed (genome files)")
        p.add_argument("-o", "--out", required=True)
        p.add_argument("--overwrite", action="store_true", help="replace a report in --out")
        p.add_argument("--bin", help="directory of ahhs-replay")
        args = p.parse_args(argv[1:])
        report_neighbourhood(args)
        return 0
    p = argparse.ArgumentParser(prog="ahhs-report",
                                description="figures and a summary for ahhs-evolve runs")
    p.add_argument("runs", nargs="+", help="run directories")
    p.add_argument("-o", "--out", required=True, help="output directory")
    p.add_argument("--overwrite", action="store_true", help="replace a report in --out")
    p.add_argument("--no-replay", action="store_true",
                   help="skip the replay of the best genome (and its per-tick figures)")
    p.add_argument("--bin", help="directory of ahhs-replay")
    report_runs(p.parse_args(argv))
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv[1:]))
    except UsageError as e:
        print(f"ahhs-report: {e}", file=sys.stderr)
        sys.exit(2)
    except ReportError as e:
        print(f"ahhs-report: {e}", file=sys.stderr)
        sys.exit(1)
