"""What the ahhs-report commands share: the run reader, statistics, figures, replays through
ahhs-replay and the output folder's rules (docs/analysis.md). Imports no other report module."""
import argparse
import json
import math
import os
import re
import shutil
import sqlite3
import subprocess
import sys
import textwrap
from collections import OrderedDict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.ticker import MaxNLocator  # noqa: E402
from scipy import stats  # noqa: E402
from scipy.ndimage import median_filter  # noqa: E402


class ReportError(Exception):
    """A problem with the input; the message is for the user."""


class UsageError(Exception):
    """A usage error: exit 2."""


# ---------------------------------------------------------------------------------------------
# Reading runs


def scenario_label_of(config):
    """pendulum, gait-damped or gait-fixed, of a run's resolved configuration."""
    return config["scenario"] + ("-" + config["joints"] if config["scenario"] == "gait" else "")


class Run:
    def __init__(self, path, prefer_summary=False):
        """prefer_summary: a complete run of a study is read from its summary and exports
        (summary.json, generations.csv, best.json) without opening its database."""
        self.path = path
        if not os.path.isdir(path):
            raise ReportError(f"{path} is not a directory")
        db = os.path.join(path, "run.sqlite")
        summary = os.path.join(path, "summary.json")
        self.exported = os.path.isfile(summary) and (prefer_summary or not os.path.isfile(db))
        if self.exported:  # a run of a study export: summary.json, generations.csv, best.json
            self._load_export(summary)
            return
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

    def _load_export(self, summary):
        try:
            with open(summary) as f:
                meta = json.load(f)
            if meta.get("format") != "ahhs-study-run":
                raise ReportError(f"{self.path}: summary.json is not an ahhs-study run summary")
            self.config = meta["evolve_config"]
            self.run_id = meta.get("run_id", "")
            self.physics = meta.get("physics", "")
            rows = np.atleast_1d(np.genfromtxt(os.path.join(self.path, "generations.csv"),
                                               delimiter=",", names=True))
        except (OSError, ValueError, KeyError) as e:
            raise ReportError(f"{self.path}: not a readable exported run ({e})")
        if len(rows) == 0:
            raise ReportError(f"{self.path}: the exported run has no generation")
        self.generation = rows["generation"].astype(int)
        self.best = rows["best"]
        self.mean = rows["mean"]
        self.median = rows["median"]

    def replay_argv(self):
        """ahhs-replay's arguments for this run's best genome (a run directory, or an exported
        best.json with its configuration)."""
        if not self.exported:
            return [self.path]
        c = self.config
        argv = ["--genome", os.path.join(self.path, "best.json"), "--scenario", c["scenario"],
                "--docking", c["joints"], "--modules", str(c["modules"]),
                "--duration", repr(float(c["duration"]))]
        # The physics the run was made with (an export's best.json may not name it).
        return argv + (["--physics", self.physics] if self.physics else [])

    @property
    def scenario_label(self):
        """The scenario with the gait's docking: pendulum, gait-damped or gait-fixed. Runs of
        different ones never share a fitness axis."""
        return scenario_label_of(self.config)

    @property
    def setting_label(self):
        """The scenario label with the task's choices that are not their defaults (docs/scenarios.md,
        "Choices the paper leaves open"): "pendulum gain 10", "pendulum soft walls"; the scenario
        label itself for the defaults. Runs of one setting share a maximum (evolution speed, the
        share within 80 % of it)."""
        choices = self.config.get("pendulum") or {}
        extra = []
        gain = float(choices.get("actuator_gain", 1.0))
        if gain != 1.0:
            extra.append(f"gain {gain:g}")
        if choices.get("walls", "rigid") != "rigid":
            extra.append(f"{choices['walls']} walls")
        return " ".join([self.scenario_label] + extra)

    @property
    def label(self):
        c = self.config
        return f"{self.setting_label} {c['variant'].upper()}-{c['rules']}"

    def best_overall(self):
        return float(np.max(self.best))

    def first_generation_reaching(self, level):
        hits = np.nonzero(self.best >= level)[0]
        return int(self.generation[hits[0]]) if len(hits) else None


def rank_sum_test(x, y):
    """Two-sided Wilcoxon rank-sum test; returns (U of x, p). Exact (the permutation
    distribution of U) when the pooled sample has no ties; with ties, the normal approximation
    with the tie correction and a continuity correction, as R's wilcox.test."""
    tied = len(set(map(float, x)) | set(map(float, y))) < len(x) + len(y)
    result = stats.mannwhitneyu(x, y, alternative="two-sided",
                                method="asymptotic" if tied else "exact")
    p = float(result.pvalue)
    # Every value the same: no evidence of a difference (the approximation divides by zero).
    return float(result.statistic), p if math.isfinite(p) else 1.0


def logrank_test(times_a, reached_a, times_b, reached_b):
    """Log-rank test of two groups of times to an event (Mantel's form; Kalbfleisch & Prentice):
    a time whose event did not happen (reached False) is censored there. Returns (observed
    events of a, expected events of a under no difference, two-sided p from chi-square with 1
    degree of freedom); p is None when no event happened at all."""
    a = [(float(t), bool(e)) for t, e in zip(times_a, reached_a)]
    b = [(float(t), bool(e)) for t, e in zip(times_b, reached_b)]
    observed = expected = variance = 0.0
    for t in sorted({t for t, e in a + b if e}):
        n_a = sum(1 for s, _ in a if s >= t)
        n_b = sum(1 for s, _ in b if s >= t)
        d_a = sum(1 for s, e in a if e and s == t)
        d = d_a + sum(1 for s, e in b if e and s == t)
        n = n_a + n_b
        observed += d_a
        expected += d * n_a / n
        if n > 1:
            variance += d * (n_a / n) * (n_b / n) * (n - d) / (n - 1)
    if not any(e for _, e in a + b):
        return observed, expected, None
    if variance == 0:  # every event at one time, and every run had it: no difference to see
        return observed, expected, 1.0
    return observed, expected, float(stats.chi2.sf((observed - expected) ** 2 / variance, 1))


# ---------------------------------------------------------------------------------------------
# Figures


def save(fig, out_dir, name, written):
    for ext in ("png", "svg"):
        path = os.path.join(out_dir, f"{name}.{ext}")
        fig.savefig(path, dpi=110, bbox_inches="tight")
        written.append(path)
    plt.close(fig)


def scenarios_of(groups):
    """Configuration labels grouped by scenario label, in order: they never share a fitness axis."""
    scenarios = OrderedDict()
    for label, runs in groups.items():
        scenarios.setdefault(runs[0].scenario_label, []).append(label)
    return scenarios


def fitness_figure(groups, out_dir, written):
    scenarios = scenarios_of(groups)
    fig, axes = plt.subplots(len(scenarios), 1, figsize=(8, 3.6 * len(scenarios) + 0.4),
                             squeeze=False)
    for ax, (scenario, labels) in zip(axes[:, 0], scenarios.items()):
        for label in labels:
            runs = groups[label]
            if len(runs) == 1:
                r = runs[0]
                line, = ax.plot(r.generation, r.best, label=f"{label}: best (n=1)")
                ax.plot(r.generation, r.mean, "--", color=line.get_color(), label=f"{label}: mean")
            else:
                n = min(len(r.best) for r in runs)
                best = np.array([r.best[:n] for r in runs])
                g = runs[0].generation[:n]
                q1, med, q3 = np.percentile(best, [25, 50, 75], axis=0)
                line, = ax.plot(g, med, label=f"{label}: median best (n={len(runs)})")
                ax.fill_between(g, q1, q3, color=line.get_color(), alpha=0.25)
        ax.set_xlabel("generation")
        ax.set_ylabel(f"fitness ({scenario})")
        ax.xaxis.set_major_locator(MaxNLocator(integer=True))
        ax.set_title(f"{scenario}: fitness per generation" + (" (band: quartiles)" if any(
            len(groups[l]) > 1 for l in labels) else ""), fontsize=10)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    save(fig, out_dir, "fitness", written)


def box_figure(groups, values, ylabel, title, name, out_dir, written, integer=False):
    """One panel per scenario label: a box per configuration and every run as a point over it
    (spread sideways by a fixed golden-ratio sequence, so the same data give the same figure). A
    configuration with fewer than 2 runs has no box and takes part in no test; tests compare
    configurations of one scenario label only."""
    scenarios = scenarios_of(groups)
    width = max(4, 2.2 * max(len(l) for l in scenarios.values()))
    fig, axes = plt.subplots(1, len(scenarios), figsize=(width * len(scenarios), 4.8),
                             squeeze=False)
    tests = []
    for ax, (scenario, labels) in zip(axes[0, :], scenarios.items()):
        data = [values[l] for l in labels]
        boxed = [i for i, d in enumerate(data) if len(d) >= 2]
        if boxed:
            ax.boxplot([data[i] for i in boxed], positions=[i + 1 for i in boxed], widths=0.5,
                       showfliers=False)
        for i, d in enumerate(data):
            spread = [((k * 0.6180339887) % 1.0 - 0.5) * 0.3 for k in range(len(d))]
            ax.plot([i + 1 + x for x in spread], d, "o", color="black", alpha=0.45,
                    markersize=4, zorder=3, gid="runs-" + re.sub(r"[^\w-]", "_", labels[i]))
        ax.set_xticks(range(1, len(labels) + 1))
        ax.set_xticklabels([f"{l}\nn={len(d)}" for l, d in zip(labels, data)], fontsize=8)
        ax.set_xlim(0.5, len(labels) + 0.5)
        ax.set_ylabel(ylabel)
        ax.set_title(scenario, fontsize=10)
        ax.grid(alpha=0.3, axis="y")
        if integer:
            ax.yaxis.set_major_locator(MaxNLocator(integer=True))
        flat = [v for d in data for v in d]
        top, span = max(flat), (max(flat) - min(flat)) or 1
        k = 0
        for i in boxed:
            for j in boxed:
                if j <= i:
                    continue
                u, p = rank_sum_test(data[i], data[j])
                tests.append((labels[i], labels[j], len(data[i]), len(data[j]), u, p))
                y = top + span * (0.08 + 0.1 * k)
                ax.plot([i + 1, j + 1], [y, y], color="black", lw=0.8)
                ax.text((i + j + 2) / 2, y, f"p = {p:.3g}", ha="center", va="bottom", fontsize=8)
                k += 1
    # Wrapped to the figure's width (about 11 characters per inch at 10 points): unwrapped, a
    # long title widened a figure of two boxes into mostly white space.
    fig.suptitle(textwrap.fill(title, int(11 * width * len(scenarios))), fontsize=10)
    fig.tight_layout()
    save(fig, out_dir, name, written)
    return tests


SENSOR_NAMES = {
    "gait": ["up", "forward", "down", "back"],
    "pendulum": ["upper left", "upper right", "lower left", "lower right", "wall left",
                 "wall right", "speed left", "speed right", "spin ccw", "spin cw"],
}


def sensor_name(scenario, j):
    names = SENSOR_NAMES["pendulum" if scenario == "pendulum" else "gait"]
    return f"S{j} {names[j]}" if j < len(names) else f"S{j}"


def replay_figures(trace_csv, rules_csv, body_csv, scenario, out_dir, written):
    data = np.genfromtxt(trace_csv, delimiter=",", names=True)
    names = data.dtype.names
    modules = sorted(set(int(m) for m in data["module"]))
    hormones = [n for n in names if n[0] == "h" and n[1:].isdigit()]
    sensors = [n for n in names if n[0] == "s" and n[1:].isdigit()]
    actuators = [n for n in names if n[0] == "a" and n[1:].isdigit()]
    used = [h for h in hormones if np.max(data[h]) > 1e-3]
    pendulum = scenario == "pendulum"
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
    fig.tight_layout(rect=(0, 0, 1, 0.98))
    save(fig, out_dir, "hormones", written)
    # The body and the commands: the pendulum's angle and cart, or the gait's hinges; then every
    # module's own actuator values.
    body = np.genfromtxt(body_csv, delimiter=",", names=True)
    fig, axes = plt.subplots(3 if pendulum else 2, 1, figsize=(8, 7.5 if pendulum else 5),
                             sharex=True)
    if pendulum:
        angle = np.degrees(np.angle(np.exp(1j * body["pole_angle"])))
        # Break the line where the angle wraps at +-180 (a pass through the bottom), so that no
        # vertical stroke suggests a swing through the top.
        time = body["time"].astype(float)
        jumps = np.nonzero(np.abs(np.diff(angle)) > 180)[0] + 1
        angle = np.insert(angle, jumps, np.nan)
        time = np.insert(time, jumps, np.nan)
        axes[0].plot(time, angle, lw=0.8, color="tab:purple")
        axes[0].set_ylabel("pole angle (deg)\n0 = upright")
        axes[0].set_ylim(-185, 185)
        axes[0].set_yticks([-180, -90, 0, 90, 180])
        axes[1].plot(body["time"], body["cart_x"], lw=0.9, color="tab:brown")
        axes[1].set_ylabel("cart position (m)")
        command_ax = axes[2]
        for m in modules:
            rows = data["module"] == m
            a = actuators[m] if m < len(actuators) else actuators[0]
            command_ax.plot(data["time"][rows], data[a][rows], lw=0.9,
                            label=f"module {m} ({'left' if m == 0 else 'right'}): {a.upper()}")
        title = "Pendulum: angle, cart and the two compartments' commands"
        name = "trace"
    else:
        for m in modules:
            rows = data["module"] == m
            axes[0].plot(data["time"][rows], np.degrees(data["hinge_angle"][rows]), lw=0.9,
                         label=f"module {m}")
        axes[0].set_ylabel("hinge angle (deg)")
        axes[0].legend(fontsize=7, ncol=len(modules))
        command_ax = axes[1]
        for m in modules:
            rows = data["module"] == m
            command_ax.plot(data["time"][rows], data[actuators[0]][rows], lw=0.9,
                            label=f"module {m}")
        title = (f"Gait: hinge angles and commands (centroid moved "
                 f"{np.hypot(body['centroid_x'][-1] - body['centroid_x'][0], body['centroid_y'][-1] - body['centroid_y'][0]):.2f} m)")
        name = "hinges"
    command_ax.set_ylabel("actuator value")
    command_ax.set_ylim(-1.05, 1.05)
    command_ax.legend(fontsize=7, ncol=len(modules))
    command_ax.set_xlabel("simulated time (s)")
    for ax in axes:
        ax.grid(alpha=0.3)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    save(fig, out_dir, name, written)
    # Sensors: one panel per module, one colour per sensor in every panel, named.
    colours = plt.get_cmap("tab10")
    fig, axes = plt.subplots(len(modules), 1, figsize=(8, 1.6 * len(modules) + 0.8),
                             sharex=True, squeeze=False)
    for ax, m in zip(axes[:, 0], modules):
        rows = data["module"] == m
        for j, s in enumerate(sensors):
            if np.max(data[s][rows]) > 0:
                ax.plot(data["time"][rows], data[s][rows], lw=0.7, color=colours(j % 10),
                        label=sensor_name(scenario, j))
        ax.set_ylabel(f"module {m}")
        ax.set_ylim(-0.02, 1.02)
        ax.legend(fontsize=6, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    axes[-1, 0].set_xlabel("simulated time (s)")
    fig.suptitle("Sensor values (absent slots not drawn)", fontsize=10)
    fig.tight_layout(rect=(0, 0, 1, 0.97))
    save(fig, out_dir, "sensors", written)
    # Rule activity: share of ticks in which each rule triggered, per module.
    rules = np.atleast_1d(np.genfromtxt(rules_csv, delimiter=",", names=True, dtype=None))
    ticks = len(data) / len(modules)
    n_rules = int(np.max(rules["rule"])) + 1 if len(rules) else 0
    share = np.zeros((len(modules), n_rules))
    parts = np.zeros((n_rules, 4))  # per part: the largest share over the modules
    for row in rules:
        r = int(row["rule"])
        share[int(row["module"]), r] = row["ticks_active"] / ticks
        for k, part in enumerate(("sensor", "linear", "nonlinear", "actuator")):
            parts[r, k] = max(parts[r, k], row[part] / ticks)
    fig, ax = plt.subplots(figsize=(max(6, 0.25 * n_rules + 2), 4))
    width = 0.8 / max(1, len(modules))
    for k, m in enumerate(modules):
        ax.bar(np.arange(n_rules) + k * width, share[k], width=width, label=f"module {m}")
    ax.axhline(0.01, color="gray", lw=0.8, ls="--")
    ax.set_xlabel("rule")
    ax.set_ylabel("share of ticks triggered")
    ax.xaxis.set_major_locator(MaxNLocator(integer=True))
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
        "parts": parts,
    }


def rule_parts(rules_csv, ticks):
    """Per rule and part (sensor, linear, nonlinear, actuator): the largest share of ticks it
    triggered in any module."""
    rules = np.atleast_1d(np.genfromtxt(rules_csv, delimiter=",", names=True, dtype=None))
    n_rules = int(np.max(rules["rule"])) + 1 if len(rules) else 0
    parts = np.zeros((n_rules, 4))
    for row in rules:
        for k, part in enumerate(("sensor", "linear", "nonlinear", "actuator")):
            parts[int(row["rule"]), k] = max(parts[int(row["rule"]), k], row[part] / ticks)
    return parts


def rule_edges(genome, parts, threshold=0.0):
    """The rule parts that triggered in more than `threshold` of the ticks (parts: rule_parts):
    (rule, part, source, target, positive, share), sources and targets named S<i>, H<i>, A<i>."""
    kinds = ("sensor", "linear", "nonlinear", "actuator")
    for r, rule in enumerate(genome["rules"]):
        for k, part in enumerate(kinds):
            active = parts[r, k] if r < len(parts) else 0
            if active <= threshold:
                continue
            if genome["variant"] == "ahhs2":
                s, i = int(math.floor(rule["sensor"])), int(math.floor(rule["input"]))
                o, a = int(math.floor(rule["output"])), int(math.floor(rule["actuator"]))
                src = f"S{s}" if part == "sensor" else f"H{i}"
                dst = f"A{a}" if part == "actuator" else f"H{o}"
            else:
                if rule["type"] != part:
                    continue
                src = f"S{rule['input']}" if part == "sensor" else f"H{rule['input']}"
                dst = f"A{rule['output']}" if part == "actuator" else f"H{rule['output']}"
            yield r, part, src, dst, rule["lambda"] >= 0, active


def controller_graph(genome, parts, out_dir, written, name="controller", scenario="gait"):
    """Sensors -> hormones -> actuators: one edge per rule part that triggered in the replay,
    its width by the share of ticks it triggered (the most active module); parts that never
    triggered are not drawn."""
    lines = ["digraph controller {", "  rankdir=LR; node [fontsize=10]; edge [fontsize=8];"]
    edge_lines, used = [], set()
    edges = 0
    for r, part, src, dst, positive, active in rule_edges(genome, parts):
        tag = {"sensor": "S", "linear": "L", "nonlinear": "N", "actuator": "A"}[part]
        colour = "black" if positive else "firebrick"
        pct = f"{100 * active:.0f}%" if active >= 0.01 else f"{100 * active:.1g}%"
        edge_lines.append(f'  {src} -> {dst} [label="r{r} {tag} {pct}", '
                          f'color={colour}, penwidth={0.6 + 4 * active:.2f}];')
        used.update((src, dst))
        edges += 1
    # Only the sensors, hormones and actuators that an active rule part touches.
    pick = lambda p: sorted((n for n in used if n[0] == p), key=lambda n: int(n[1:]))
    if pick("S"):
        lines.append("  { rank=same; " + " ".join(
            f'{n} [shape=box, color=blue, label="{sensor_name(scenario, int(n[1:]))}"];'
            for n in pick("S")) + " }")
    if pick("H"):
        lines.append("  " + " ".join(f"{n} [shape=ellipse, color=darkgreen];" for n in pick("H")))
    if pick("A"):
        lines.append("  { rank=same; " + " ".join(f"{n} [shape=box, color=red];"
                                                    for n in pick("A")) + " }")
    lines += edge_lines
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


class _DeprecatedJoints(argparse.Action):
    def __call__(self, parser, namespace, values, option_string=None):
        print(f"{parser.prog}: --joints is deprecated and will go; use --docking", file=sys.stderr)
        setattr(namespace, self.dest, values)


def add_docking_option(parser):
    """--docking damped|fixed (args.docking), and --joints, its old name, for one release."""
    parser.add_argument("--docking", default="damped", choices=["damped", "fixed"],
                        help="gait docking")
    parser.add_argument("--joints", dest="docking", choices=["damped", "fixed"],
                        action=_DeprecatedJoints, help="deprecated: use --docking")


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


def envelope_argv(post):
    """ahhs-replay's options for the envelope of a stored post-evaluation (a summary's post_eval,
    or a run's post-eval.json): `none` with its stored half-widths, so that a preset that changes
    later cannot change the episodes."""
    argv = ["--envelope", "none"]
    for key, width in sorted((post.get("envelope_half_widths") or {}).items()):
        argv += ["--" + key, repr(float(width))]
    return argv


def stored_post_eval(run):
    """A run's stored held-out post-evaluation of its best (an export's summary.json post_eval,
    a run directory's post-eval.json), or None when it has none."""
    try:
        if run.exported:
            with open(os.path.join(run.path, "summary.json")) as f:
                post = json.load(f).get("post_eval")
        elif os.path.isfile(os.path.join(run.path, "post-eval.json")):
            with open(os.path.join(run.path, "post-eval.json")) as f:
                post = json.load(f)
        else:
            return None
    except (OSError, ValueError) as e:
        raise ReportError(f"{run.path}: an unreadable post-evaluation ({e})")
    return post if post and post.get("per_episode") else None


def median_episode(post):
    """The held-out episode a report replays as the one nearest the median: of the episodes with
    a fitness, sorted by it, the one at n // 2 (of an even n the upper of the two middle ones,
    which are equally near)."""
    valid = [e for e in post["per_episode"] if isinstance(e.get("fitness"), (int, float))]
    if not valid:
        raise ReportError("the post-evaluation has no episode with a fitness")
    return sorted(valid, key=lambda e: e["fitness"])[len(valid) // 2]


SWING_WINDOW = 5.0  # s: the running median a hinge's swing is taken around
RHYTHM_BAND = 0.1  # Hz: either side of the rhythm, for its share of the swing


def hinge_swing(a, dt):
    """A hinge trace's swing (degrees, one value per tick) around its running median over
    SWING_WINDOW s, which follows a change of posture without smearing it; half a window is
    left off at each end. (swing's standard deviation, rhythm, share): the rhythm is the largest peak of the
    swing's spectrum (per tick, so no swing up to half the tick rate aliases), its share the
    swing's power within RHYTHM_BAND of it (1 for a sine, about 0.5 for a regular kick, a few
    hundredths for noise); rhythm and share are None for a swing under 0.5 degree."""
    n = (max(1, min(int(round(SWING_WINDOW / dt)), len(a) // 3)) if dt > 0 else 1) | 1
    h = n // 2
    swing = (a - median_filter(a, size=n, mode="nearest"))[h:len(a) - h]
    swing = swing - np.mean(swing)
    sd = float(np.std(swing))
    if sd < 0.5 or len(swing) < 4:
        return sd, None, None
    power = np.abs(np.fft.rfft(swing))**2
    freqs = np.fft.rfftfreq(len(swing), d=dt)
    k = 1 + int(np.argmax(power[1:]))
    band = (np.abs(freqs - freqs[k]) <= RHYTHM_BAND) & (freqs > 0)
    return sd, float(freqs[k]), float(np.sum(power[band]) / np.sum(power[1:]))


def gait_motion(trace_csv, body_csv, settle=5.0):
    """How a gait replay moves, in numbers to read beside its filmstrip (docs/analysis.md). Per
    module, after the first `settle` s (a quarter of an episode shorter than 20 s): the hinge
    angle's mean, standard deviation, min and max (degrees), which a change of posture moves,
    and its swing around a running median (hinge_swing: standard deviation, rhythm and the
    rhythm's share). Per pair of neighbours: the correlation at zero lag, and the lag within
    half the first one's rhythm period at which they correlate best (positive: the second
    follows). The centroid's distance from its start at each quarter of the episode and its
    displacement at the end (m)."""
    data = np.atleast_1d(np.genfromtxt(trace_csv, delimiter=",", names=True))
    body = np.atleast_1d(np.genfromtxt(body_csv, delimiter=",", names=True))
    settle = min(settle, 0.25 * float(body["time"][-1]))
    modules = sorted(set(int(m) for m in data["module"]))
    dt = float(np.median(np.diff(body["time"]))) if len(body) > 1 else 0.0
    angles, rows = [], []
    for m in modules:
        sel = (data["module"] == m) & (data["time"] >= settle)
        a = np.degrees(data["hinge_angle"][sel])
        if len(a) < 4:
            raise ReportError(f"{trace_csv}: under 4 ticks after the first {settle:g} s")
        angles.append(a)
        swing_sd, freq, share = hinge_swing(a, dt)
        rows.append({"module": m, "mean": float(np.mean(a)), "sd": float(np.std(a)),
                     "min": float(np.min(a)), "max": float(np.max(a)), "swing_sd": swing_sd,
                     "frequency": freq, "share": share})
    pairs = []
    for i in range(len(modules) - 1):
        a, b = angles[i], angles[i + 1]
        pair = {"modules": (modules[i], modules[i + 1]), "correlation": None, "lag": None,
                "lag_correlation": None}
        if rows[i]["sd"] >= 0.5 and rows[i + 1]["sd"] >= 0.5:
            pair["correlation"] = float(np.corrcoef(a, b)[0, 1])
            if rows[i]["frequency"]:
                best = None
                reach = min(len(a) // 4, int(0.5 / rows[i]["frequency"] / dt))
                for k in range(-reach, reach + 1):  # b[t + k] against a[t]
                    x, y = (a[:len(a) - k], b[k:]) if k >= 0 else (a[-k:], b[:len(b) + k])
                    c = float(np.corrcoef(x, y)[0, 1])
                    if best is None or c > best[0]:
                        best = (c, k * dt)
                pair["lag_correlation"], pair["lag"] = best
        pairs.append(pair)
    t = body["time"]
    dx, dy = body["centroid_x"] - body["centroid_x"][0], body["centroid_y"] - body["centroid_y"][0]
    d = np.hypot(dx, dy)
    at = [max(0, int(round(q * len(t))) - 1) for q in (0.25, 0.5, 0.75, 1.0)]
    quarters = [(float(t[i]), float(d[i])) for i in at]
    end = (float(dx[-1]), float(dy[-1]))
    return {"settle": settle, "hinges": rows, "neighbours": pairs, "distance": quarters,
            "end": end}


def replay_post_eval(bin_dir, replay_argv, post, out_json, reuse=False):
    """This build's post-evaluation of a genome on the held-out episodes of a stored one (`post`,
    a summary's post_eval): as many episodes, envelope `none` with the stored half-widths
    (replay_argv names the genome, scenario, docking and physics). Written to out_json (kept and
    read again with reuse=True). Returns it when every episode's seed and fitness equal the
    stored ones bit for bit, else None."""
    if not (reuse and os.path.exists(out_json)):
        os.makedirs(os.path.dirname(os.path.abspath(out_json)), exist_ok=True)
        argv = list(replay_argv) + ["--post-eval", str(len(post["per_episode"])),
                                    "--post-eval-json", out_json + ".tmp",
                                    "--overwrite"] + envelope_argv(post)
        run_replay(bin_dir, argv)
        os.replace(out_json + ".tmp", out_json)
    with open(out_json) as f:
        again = json.load(f)
    stored = [(e.get("seed"), e.get("fitness")) for e in post["per_episode"]]
    replayed = [(e.get("seed"), e.get("fitness")) for e in again.get("per_episode", [])]
    return again if stored == replayed else None


def beyond_wall_share(bin_dir, replay_argv, post, out_json, reuse=False):
    """(share, source) for a post-evaluated gait genome: the share of its held-out episodes that
    end with every module half beyond the wall's outer face (docs/evolution.md, "Held-out
    post-evaluation"). From the post-evaluation `post` when that counted them ("stored"); else
    from this build's post-evaluation on the same episodes (replay_post_eval), taken only when it
    replays bit for bit ("replayed"). (None, why) when it does not."""
    if "beyond_wall_share" in post:
        return float(post["beyond_wall_share"]), "stored"
    again = replay_post_eval(bin_dir, replay_argv, post, out_json, reuse)
    if again is None or "beyond_wall_share" not in again:
        return None, "its post-evaluation does not replay bit for bit with this build"
    return float(again["beyond_wall_share"]), "replayed"


def filmstrip(bin_dir, log, png, written):
    """8 frames of the replayed episode in one PNG (ahhs-view with headless Chromium); what was
    done, for summary.md."""
    if not shutil.which("chromium"):
        return "filmstrip: not made, chromium is not installed (tools/install-deps)"
    proc = subprocess.run([os.path.join(bin_dir, "ahhs-view"), log, "--filmstrip", png,
                           "--overwrite"], capture_output=True, text=True)
    if proc.returncode != 0:
        raise ReportError("ahhs-view --filmstrip failed: " + (proc.stderr or proc.stdout).strip())
    written.append(png)
    return "filmstrip of the replay, 8 frames across the episode: `best-filmstrip.png`"


REPORT_FILES = (".png", ".svg", ".dot", ".md", ".csv", ".json", ".lcm", ".mp4")


def is_report_file(path, allow_dirs):
    if os.path.isdir(path) and not os.path.islink(path):
        return allow_dirs and all(is_report_file(os.path.join(path, f), True)
                                  for f in os.listdir(path))
    return os.path.isfile(path) and path.endswith(REPORT_FILES)


def robust_sources_text(pairs):
    """What robust fitness is the median of, in words, from (configuration, source) pairs: one
    source alone, or each with the configurations it holds for."""
    sources = OrderedDict()
    for name, source in pairs:
        if source:
            sources.setdefault(source, []).append(name)
    if len(sources) <= 1:
        return "the median of " + (next(iter(sources)) if sources else "its replays")
    return "the median of " + "; ".join(f"{s} ({', '.join(n)})" for s, n in sources.items())


def prepare_out(out, overwrite, allow_dirs=False):
    """Makes the output directory. An old report in it is replaced only with --overwrite (so
    that no stale figure survives); a directory holding anything else is never emptied. A study
    report (allow_dirs) has subdirectories of report files."""
    if os.path.isdir(out) and os.listdir(out):
        if not overwrite:
            raise UsageError(f"{out} holds files; pass --overwrite to replace the report in it")
        foreign = [f for f in os.listdir(out)
                   if not is_report_file(os.path.join(out, f), allow_dirs)]
        if foreign:
            raise UsageError(f"{out} holds {foreign[0]}, which is not part of a report; "
                             "give an empty or new directory")
        for f in os.listdir(out):
            path = os.path.join(out, f)
            shutil.rmtree(path) if os.path.isdir(path) else os.remove(path)
    os.makedirs(out, exist_ok=True)
