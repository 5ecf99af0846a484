"""ahhs-report study STUDY_DIR -o OUT_DIR: a whole study (ahhs-study) against the paper.

Reads the complete runs of a study directory or of a study export (each config's
seed-<k>/summary.json), in the plan's order (study.toml), and writes into OUT_DIR:
  <scenario>/      ahhs-report of every complete run of the scenario (pendulum, gait-damped,
                   gait-fixed: the gait's docking is part of it; fitness, box plots, tests,
                   the best controller of the first run)
  <scenario>/box_robust.png   the robust fitness of each run's best, per configuration (rank-sum)
  <scenario>/neighbourhood-<config>/   35 single mutants of the configuration's best genome
  results.md       the paper's claims, one per row, with our figures beside them
  results.json     the numbers behind results.md
Every run's best genome is replayed once (rule activity, hormones in use, and whether this build
reproduces its stored fitness bit for bit) and 8 times with perturbed frictions (ahhs-replay
--robustness). Its robust fitness is the median of its post-evaluation (held-out episodes under
the run's envelope, in summary.json) when every run of the configuration has one, else of those
8 replays; the interquartile range of the same episodes is its spread. For the gait, the share of
its held-out episodes that end wholly beyond the wall is read from the post-evaluation, or counted
by post-evaluating the best again when the stored fitnesses replay bit for bit (beyond_wall_of).
Each claim about runs' fitness is judged twice: on each run's best fitness (the paper's
statistic) and on the robust fitness of each run's best, since an evolved gait best is often a
knife-edge of deterministic chaos (docs/scenarios.md).
"""
import argparse
import importlib.util
import json
import os
import sys
import tempfile
import tomllib
from collections import OrderedDict

import numpy as np

from claims_lib import VERDICTS, fmt, merge_claims
from report_lib import (ReportError, Run, UsageError, beyond_wall_share, box_figure, find_bin,
                        prepare_out, robust_sources_text, rule_edges, rule_parts, run_replay,
                        scenario_label_of)
from run_report import report_neighbourhood, report_runs

SELDOM = 0.01  # a rule part active in fewer ticks than this triggers "seldom"
MUTANTS = 35
ROBUSTNESS = 8


class Config:
    def __init__(self, name, planned, runs, task=None):
        self.name, self.planned, self.runs = name, planned, runs
        self.scenario_label = runs[0].scenario_label if runs else None
        # pendulum, gait-fixed or gait-damped: of its runs, or of its resolved configuration in
        # the study (STUDY/configs/NAME.json) before it has any; None when neither says
        self.task = self.scenario_label or task
        self.setting_label = runs[0].setting_label if runs else None
        self.best = np.array([r.best_overall() for r in runs])
        self.robust = None  # per run: robust fitness of its best genome (None: a run has none)
        self.robust_source = ""  # what the robust fitness is the median of
        self.spread = None  # per run: interquartile range of its best genome's robust episodes
        self.spread_source = ""
        # per run: the share of its best genome's held-out episodes that succeed (the gait: over
        # the wall; the pendulum: the bob above the pivot in >= 20 % of ticks), None without a
        # post-evaluation for every run. A two-humped distribution's median moves with sampling;
        # this share does not (docs/findings.md, "The warm-started chain solver ...").
        self.success = None
        # per run (gait): the share of its best's held-out episodes that end with every module
        # half beyond the wall, whatever the fitness (beyond_wall_of); None when a run has none
        self.beyond = None
        self.beyond_source = []  # per run: "stored", "replayed" or why it has none
        self.controllers = []  # per run: rule and hormone use of its best genome
        # per run: the generation reaching 75 % of its setting's maximum, or its length
        self.speed = []
        self.reached = []  # per run: whether it reached that level (else censored at its length)
        self.robustness = None  # of the configuration's best genome
        self.robustness_runs = []  # per run: ahhs-replay --robustness of its best genome
        self.neighbourhood = None

    @property
    def variant(self):
        return self.runs[0].config["variant"] if self.runs else None

    def best_run(self):
        return self.runs[int(np.argmax(self.best))]


def load_study(path):
    plan_file = os.path.join(path, "study.toml")
    if not os.path.isfile(plan_file):
        raise ReportError(f"{path} is not a study directory or export (no study.toml)")
    try:
        with open(plan_file, "rb") as f:
            plan = tomllib.load(f)
        entries = [(c["name"], int(c["seeds"])) for c in plan["config"]]
    except (tomllib.TOMLDecodeError, KeyError, TypeError, ValueError) as e:
        raise ReportError(f"{plan_file}: not a study plan ({e})")
    configs = []
    for name, seeds in entries:
        runs = [Run(os.path.join(path, name, f"seed-{k}"), prefer_summary=True)
                for k in range(1, seeds + 1)
                if os.path.isfile(os.path.join(path, name, f"seed-{k}", "summary.json"))]
        configs.append(Config(name, seeds, runs, planned_task(path, name)))
    return plan.get("name", os.path.basename(path)), configs


def planned_task(path, name):
    """The task of a configuration from its resolved config in the study (None if absent)."""
    try:
        with open(os.path.join(path, "configs", name + ".json")) as f:
            return scenario_label_of(json.load(f))
    except (OSError, ValueError, KeyError, TypeError):
        return None


def summary_of(run):
    with open(os.path.join(run.path, "summary.json")) as f:
        return json.load(f)


def controller_use(bin_dir, run, scratch):
    """Replays the run's best genome: which rules trigger, which hormones active rules touch."""
    rules_csv = os.path.join(scratch, "rules.csv")
    body_csv = os.path.join(scratch, "body.csv")
    out = run_replay(bin_dir, run.replay_argv() + ["--rules-csv", rules_csv, "--body-csv",
                                                   body_csv, "--overwrite"])
    ticks = max(1, len(np.atleast_1d(np.genfromtxt(body_csv, delimiter=",", names=True))))
    parts = rule_parts(rules_csv, ticks)
    with open(os.path.join(run.path, "best.json")) as f:
        genome = json.load(f)
    share = parts.max(axis=1) if len(parts) else np.zeros(0)
    hormones = {n for _, _, src, dst, _, _ in rule_edges(genome, parts, SELDOM)
                for n in (src, dst) if n[0] == "H"}
    return {"rules": len(genome["rules"]), "never": int(np.sum(share == 0)),
            "seldom": int(np.sum((share > 0) & (share < SELDOM))),
            "active": int(np.sum(share >= SELDOM)), "hormones": len(genome["hormones"]),
            "hormones_used": len(hormones), "reproduced": replay_reproduced(out)}


def replay_reproduced(out):
    """ahhs-replay's verdict on the stored fitness: True (bit for bit), False, None (none)."""
    if ": reproduced exactly" in out:
        return True
    return False if "stored fitness" in out else None


def robustness_of(bin_dir, run, scratch):
    csv = os.path.join(scratch, "robustness.csv")
    run_replay(bin_dir, run.replay_argv() + ["--robustness", str(ROBUSTNESS), "--robustness-csv",
                                             csv, "--overwrite"])
    rows = np.atleast_1d(np.genfromtxt(csv, delimiter=",", names=True, dtype=None,
                                       encoding="utf-8"))
    values = [float(v) for v in rows["fitness"] if v != "failed"]
    return {"replays": len(rows), "failed": len(rows) - len(values),
            "median": float(np.median(values)) if values else None,
            "max": float(np.max(values)) if values else None,
            "iqr": iqr(values) if len(values) > 1 else None}


def iqr(values):
    return float(np.subtract(*np.percentile(values, [75, 25])))


def post_eval_of(run):
    """A run's post-evaluation (ahhs-evolve --post-eval: held-out episodes of its best genome)
    from its summary: {"median", "iqr", "episodes", "envelope", "success_share"}, or None when it
    has none."""
    if not os.path.isfile(os.path.join(run.path, "summary.json")):
        return None
    post = summary_of(run).get("post_eval")
    if not post or not post.get("per_episode"):
        return None
    valid = [e for e in post["per_episode"] if isinstance(e.get("fitness"), (int, float))]
    values = [float(e["fitness"]) for e in valid]
    if len(values) < 2:
        return None
    return {"median": float(np.median(values)), "iqr": iqr(values), "episodes": len(values),
            "envelope": post.get("envelope", ""),
            "success_share": float(np.mean([bool(e.get("succeeded")) for e in valid]))}


def robust_fitness(config):
    """Sets the configuration's robust fitness and per-genome spread: from every run's
    post-evaluation when all have one, else from the friction replays (robustness_runs)."""
    post = [post_eval_of(r) for r in config.runs]
    if post and all(p is not None for p in post):
        config.robust = np.array([p["median"] for p in post])
        config.spread = [p["iqr"] for p in post]
        config.success = [p["success_share"] for p in post]
        episodes = sorted({p["episodes"] for p in post})
        config.robust_source = config.spread_source = (
            f"{'-'.join(map(str, episodes))} held-out episodes (envelope {post[0]['envelope']})")
        return
    medians = [x["median"] for x in config.robustness_runs]
    config.robust = None if None in medians else np.array(medians)
    spreads = [x.get("iqr") for x in config.robustness_runs]
    config.spread = None if None in spreads else spreads
    config.robust_source = config.spread_source = f"{ROBUSTNESS} friction-perturbed replays"


def beyond_wall_of(bin_dir, run, scratch):
    """(share, source) for a gait run's best: the share of its held-out episodes that end with
    every module half beyond the wall's outer face (docs/evolution.md, "Held-out post-evaluation").
    From its post-evaluation when that counted them ("stored"); else the best is post-evaluated
    again by this build on the same held-out episodes and the count is taken only if every
    episode's seed and fitness equal the stored ones bit for bit ("replayed"). (None, why)
    without a post-evaluation or when the replay differs."""
    post = summary_of(run).get("post_eval") if os.path.isfile(
        os.path.join(run.path, "summary.json")) else None
    if not post or not post.get("per_episode"):
        return None, "no post-evaluation"
    return beyond_wall_share(bin_dir, run.replay_argv(), post,
                             os.path.join(scratch, "post-eval.json"))


def beyond_wall(bin_dir, config, scratch):
    """Sets config.beyond (every run's share, or None) and config.beyond_source (gait only)."""
    if config.task not in ("gait-fixed", "gait-damped"):
        return
    shares = [beyond_wall_of(bin_dir, r, scratch) for r in config.runs]
    config.beyond_source = [how for _, how in shares]
    values = [v for v, _ in shares]
    config.beyond = None if None in values else values


NEIGHBOURHOOD_ORIGINALS = 3
# The robust fitness of the originals the paper's neighbourhoods start from, per scenario label:
# 0.84 (AHHS1-80) and 0.81 (AHHS2-50), fixed docking. Elsewhere the originals are the best.
NEIGHBOURHOOD_REFERENCE = {"gait-fixed": 0.8}


def neighbourhood_originals(config):
    """Up to NEIGHBOURHOOD_ORIGINALS runs whose best genomes start mutation neighbourhoods: those
    whose robust fitness is nearest the paper's originals (a good controller, not the setting's
    highest knife-edge), else the highest."""
    values = config.robust if config.robust is not None else config.best
    reference = NEIGHBOURHOOD_REFERENCE.get(config.scenario_label)
    key = ((lambda i: (abs(values[i] - reference), i)) if reference is not None else
           (lambda i: (-values[i], i)))
    return [config.runs[i] for i in sorted(range(len(config.runs)), key=key)
            [:NEIGHBOURHOOD_ORIGINALS]]


def neighbourhood_of(bin_dir, config, out_dir):
    """35 single mutants of each original's best genome (neighbourhood_originals), each in
    OUT/<run>/; their shares pooled: below 0.2, and keeping 90 % of their own original."""
    originals, below, keep, everything = [], [], [], []
    for run in neighbourhood_originals(config):
        sub = os.path.join(out_dir, os.path.basename(os.path.normpath(run.path)))
        args = argparse.Namespace(genome=run.path, mutants=MUTANTS, mutant_seed=1, out=sub,
                                  overwrite=True, bin=bin_dir, scenario=run.config["scenario"],
                                  docking=run.config["joints"], modules=run.config["modules"],
                                  duration=float(run.config["duration"]), seed=1, physics="")
        if run.exported:  # its best genome, episode seed and physics (Run.replay_argv)
            args.genome = os.path.join(run.path, "best.json")
            args.seed = int(summary_of(run)["best_eval_seed"])
            args.physics = run.physics
        report_neighbourhood(args)
        data = np.genfromtxt(os.path.join(sub, "mutants.csv"), delimiter=",", names=True,
                             dtype=None, encoding="utf-8")
        original = float(data["fitness"][0])
        mutants = np.array([float(v) for v in data["fitness"][1:]])
        index = config.runs.index(run)
        originals.append({"run": run.path, "original": original,
                          "robust": None if config.robust is None else
                          float(config.robust[index]),
                          "median": float(np.median(mutants)),
                          "below_0.2": float(np.mean(mutants < 0.2)),
                          "keep_90": float(np.mean(mutants >= 0.9 * original))
                          if original > 0 else None})
        everything += list(mutants)
        below += list(mutants < 0.2)
        if original > 0:
            keep += list(mutants >= 0.9 * original)
    return {"originals": originals, "mutants": len(everything),
            "median": float(np.median(everything)), "below_0.2": float(np.mean(below)),
            "keep_90": float(np.mean(keep)) if keep else None}


# ---------------------------------------------------------------------------------------------
# The command


def claims_of(study_name):
    """The make_claims function of a study's claims, from studies/<name>-claims.py beside its plan
    (a name's longest '-'-prefix that has one: paper-2010-robust uses paper-2010's). A study
    without claims of its own is judged against the paper's (studies/paper-2010-claims.py)."""
    studies = os.environ.get("AHHS_STUDIES_DIR") or os.path.join(
        os.path.dirname(os.path.abspath(__file__)), "..", "..", "studies")
    parts = study_name.split("-")
    names = ["-".join(parts[:n]) for n in range(len(parts), 0, -1)] + ["paper-2010"]
    for name in names:
        path = os.path.join(studies, name + "-claims.py")
        if os.path.isfile(path):
            spec = importlib.util.spec_from_file_location("study_claims", path)
            module = importlib.util.module_from_spec(spec)
            spec.loader.exec_module(module)
            return module.make_claims
    raise ReportError(f"no claims for study {study_name} in {studies} (paper-2010-claims.py)")


def report_study(args):
    name, configs = load_study(args.study)
    done = [c for c in configs if c.runs]
    if not done:
        raise ReportError(f"{args.study}: no complete run yet")
    prepare_out(args.out, args.overwrite, allow_dirs=True)
    bin_dir = find_bin(args)
    scenarios = OrderedDict()
    for c in done:
        scenarios.setdefault(c.scenario_label, []).append(c)
    # The maximum of each setting (a scenario with its task's choices): the defaults' is the
    # scenario's, the key the paper's claims read.
    maxima = {}
    for c in done:
        maxima[c.setting_label] = max(maxima.get(c.setting_label, 0.0), float(np.max(c.best)))
    for c in done:  # the paper's evolution speed; a run that never gets there is censored
        speed = [r.first_generation_reaching(0.75 * maxima[c.setting_label]) for r in c.runs]
        c.reached = [g is not None for g in speed]
        c.speed = [int(r.generation[-1]) + 1 if g is None else g for r, g in zip(c.runs, speed)]
    for scenario, cs in scenarios.items():
        report_runs(argparse.Namespace(runs=[r for c in cs for r in c.runs],
                                       out=os.path.join(args.out, scenario), overwrite=True,
                                       no_replay=args.no_replay, bin=bin_dir))
    with tempfile.TemporaryDirectory() as scratch:
        for c in done:
            c.controllers = [controller_use(bin_dir, r, scratch) for r in c.runs]
            c.robustness_runs = [robustness_of(bin_dir, r, scratch) for r in c.runs]
            c.robustness = c.robustness_runs[int(np.argmax(c.best))]
            robust_fitness(c)
            beyond_wall(bin_dir, c, scratch)
            if not args.no_replay:
                c.neighbourhood = neighbourhood_of(
                    bin_dir, c, os.path.join(args.out, c.scenario_label, f"neighbourhood-{c.name}"))
    for scenario, cs in scenarios.items():
        robust = [c for c in cs if c.robust is not None]
        if robust:
            box_figure({c.name: c.runs for c in robust}, {c.name: list(c.robust) for c in robust},
                       "robust fitness of the run's best", "Robust fitness of each run's best "
                       f"genome, the median of {robust[0].robust_source}; a point per run; "
                       "two-sided Wilcoxon rank-sum",
                       "box_robust", os.path.join(args.out, scenario), [])
    make_claims = claims_of(name)
    claims = merge_claims(make_claims(configs, maxima, "best"),
                          make_claims(configs, maxima, "robust"))
    write_results(args, name, configs, scenarios, maxima, claims)



def reproduction(configs):
    """(sentence for results.md, runs whose best genome this build does not reproduce)."""
    verdicts = [(r.path, u["reproduced"]) for c in configs for r, u in zip(c.runs, c.controllers)]
    differ = [p for p, v in verdicts if v is False]
    exact = sum(1 for _, v in verdicts if v)
    if exact == len(verdicts):
        return (f"Every run's best genome replays to its stored fitness bit for bit with this "
                f"build ({exact} of {len(verdicts)}).", differ)
    if not differ:
        return (f"{exact} of {len(verdicts)} runs' best genomes replay to their stored fitness "
                "bit for bit with this build; the others store no fitness to compare.", differ)
    return (f"**{len(differ)} of {len(verdicts)} runs' best genomes do not replay to their "
            "stored fitness with this build** (" + ", ".join(differ) + "): the study was "
            "evaluated by a build whose physics or controller differ, so the replays below (robust "
            "fitness, mutation neighbourhoods, rules) describe other behaviour than its fitness.",
            differ)


def reaching(c):
    """"7 of 10 (40)": runs reaching the speed level, and the median generation of those."""
    gens = [g for g, hit in zip(c.speed, c.reached) if hit]
    return f"{len(gens)} of {len(c.speed)}" + (f" ({np.median(gens):g})" if gens else "")


def success_cell(c):
    """"14 % (1 of 3)": the share of all the runs' held-out episodes that succeed (each run
    post-evaluated on as many), and how many runs have any; "-" without post-evaluations."""
    if c.success is None:
        return "-"
    return f"{np.mean(c.success):.0%} ({sum(x > 0 for x in c.success)} of {len(c.success)})"


def beyond_cell(c):
    """"12 % (2 of 3)" like success_cell, for the episodes wholly beyond the wall (gait)."""
    if c.beyond is None:
        return "-"
    return f"{np.mean(c.beyond):.0%} ({sum(x > 0 for x in c.beyond)} of {len(c.beyond)})"


def beyond_sentence(configs):
    """What results.md says of the beyond-the-wall counts that were not stored: how many were
    replayed, and which runs' post-evaluations this build does not reproduce."""
    sources = [(r.path, how) for c in configs for r, how in zip(c.runs, c.beyond_source)]
    replayed = sum(1 for _, how in sources if how == "replayed")
    differ = [p for p, how in sources if how not in ("stored", "replayed", "no post-evaluation")]
    words = []
    if replayed:
        words.append(f"Post-evaluations made before episodes wholly beyond the wall were "
                     f"counted: {replayed}. Their bests were post-evaluated again by this build on "
                     "the same held-out episodes, every fitness bit for bit the stored one.")
    if differ:
        words.append(f"**Post-evaluations this build does not replay bit for bit: {len(differ)}** "
                     "(" + ", ".join(differ) + "); their configurations have no count of episodes "
                     "wholly beyond the wall.")
    return " ".join(words), differ


def robust_sources(configs):
    """What each configuration's robust fitness is the median of, in words."""
    return robust_sources_text((c.name, c.robust_source) for c in configs if c.runs)


def write_results(args, name, configs, scenarios, maxima, claims):
    complete = sum(len(c.runs) for c in configs)
    planned = sum(c.planned for c in configs)
    replayed, differ = reproduction(configs)
    if differ:
        print(f"ahhs-study report: warning: {len(differ)} of {complete} runs' best genomes do not "
              "replay to their stored fitness with this build (results.md)", file=sys.stderr)
    beyond, beyond_differ = beyond_sentence(configs)
    if beyond_differ:
        print("ahhs-study report: warning: post-evaluations this build does not replay bit for "
              f"bit: {len(beyond_differ)} (results.md)", file=sys.stderr)
    if beyond:
        replayed += " " + beyond
    md = [f"# Results: study `{name}` against Hamann et al. (ALife 2010)", "",
          f"From {complete} complete runs of the {planned} planned "
          f"(`ahhs-study report {os.path.basename(os.path.normpath(args.study))}`). A row whose "
          "configurations have no complete run yet says so.", "", replayed, "",
          "## The paper's claims", "",
          "Judged twice: on each run's best fitness (the paper's statistic), and on the robust "
          "fitness of each run's best genome (" + robust_sources(configs) + "). Claims that are "
          "not about runs' fitness are judged once. The verdicts:", ""] + [
              f"- {v}" for v in VERDICTS] + ["",
          "| claim | the paper | ours: each run's best | verdict | ours: robust | "
          "verdict (robust) |",
          "|---|---|---|---|---|---|"]
    md += [f"| {a} | {b} | {c} | {d} | {'-' if e is None else e} | {'-' if f is None else f} |"
           for a, b, c, d, e, f in claims]
    md += ["", "## Configurations", "",
           "Best fitness is each run's best (the paper's statistic). Robust median of the max: "
           "the robust fitness (as in the next column) of the run with the highest best fitness. "
           "Robust fitness of the runs' bests: " + robust_sources(configs) +
           "; an evolved gait best is usually far above "
           "it (docs/findings.md, \"Physics step and deterministic chaos\"). Held-out episodes "
           "succeeding (post-evaluated runs only): over the wall (gait) or the bob above the "
           "pivot in at least 20 % of ticks (pendulum), the mean of the runs' shares, and how "
           "many runs have any; where a best's held-out fitness has two humps (at the wall or "
           "over it), its median moves with sampling and this share does not. Held-out episodes "
           "wholly beyond the wall (gait, post-evaluated runs only): every module half beyond the "
           "wall's outer face at the end, whatever the fitness (a chain that tumbles over it ends "
           "beyond it at fitness below 1, and one over 1 may still straddle it); the mean of the "
           "runs' shares, and how many runs have any. Rules: share of the "
           "rules of the runs' best genomes that "
           "never or seldom (< 1 % of ticks) trigger; hormones: touched by a rule part active in "
           ">= 1 % of ticks (median over runs).", "",
           "| configuration | runs | best fitness: median (quartiles) | max | robust median of the max | "
           "robust fitness of the runs' bests: median (quartiles) | "
           "held-out episodes succeeding: all runs' (runs with any) | "
           "held-out episodes wholly beyond the wall: all runs' (runs with any) | "
           "within 80 % of its setting's maximum | runs reaching 75 % of it (median generation of those) | "
           "rules never/seldom | "
           "hormones used |",
           "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    results = {"study": name, "complete_runs": complete, "planned_runs": planned,
               "replay_differs": differ, "post_eval_differs": beyond_differ, "maxima": maxima, "configs": {}, "claims": claims}
    for c in configs:
        if not c.runs:
            md.append(f"| {c.name} | 0 of {c.planned} | not run yet | | | | | | | | | |")
            continue
        q1, med, q3 = np.percentile(c.best, [25, 50, 75])
        within = float(np.mean(c.best >= 0.8 * maxima[c.setting_label]))
        quiet = np.median([(u["never"] + u["seldom"]) / u["rules"] for u in c.controllers])
        hormones = np.median([u["hormones_used"] for u in c.controllers])
        robust = "-" if c.robust is None else "{1:.3f} ({0:.3f} / {2:.3f})".format(
            *np.percentile(c.robust, [25, 50, 75]))
        # The same measure as the runs' robust fitness: held-out episodes where every run was
        # post-evaluated, else the friction replays (then it is c.robustness's median).
        robust_of_max = "-" if c.robust is None else fmt(c.robust[int(np.argmax(c.best))])
        md.append(f"| {c.name} | {len(c.runs)} of {c.planned} | {med:.3f} ({q1:.3f} / {q3:.3f}) | "
                  f"{np.max(c.best):.3f} | {robust_of_max} | {robust} | "
                  f"{success_cell(c)} | {beyond_cell(c)} | {within:.0%} | "
                  f"{reaching(c)} | {quiet:.0%} | "
                  f"{hormones:g} of {c.controllers[0]['hormones']} |")
        results["configs"][c.name] = {
            # (key "task": the name results.json has always had; docs/reference.md, "words")
            "runs": len(c.runs), "planned": c.planned, "task": c.task,
            "best": [float(v) for v in c.best], "median": float(med),
            "within_80_percent": within, "speed": c.speed, "reached": c.reached,
            "robustness": c.robustness, "robust_source": c.robust_source,
            "robust": None if c.robust is None else [float(v) for v in c.robust],
            "spread": c.spread, "success": c.success,
            "beyond_wall": c.beyond, "beyond_wall_source": c.beyond_source,
            "robustness_runs": c.robustness_runs,
            "neighbourhood": c.neighbourhood, "controllers": c.controllers}
    md += ["", "## Figures", ""]
    for scenario in scenarios:
        md += [f"- {scenario}: `{scenario}/fitness.png`, `{scenario}/box_best.png`, "
               f"`{scenario}/box_robust.png`, `{scenario}/box_speed.png`, `{scenario}/summary.md`"]
        md += [f"  - mutation neighbourhood of {c.name}'s "
               f"{os.path.basename(os.path.normpath(o['run']))}: "
               f"`{scenario}/neighbourhood-{c.name}/{os.path.basename(os.path.normpath(o['run']))}"
               "/neighbourhood.png`" for c in scenarios[scenario] if c.neighbourhood
               for o in c.neighbourhood["originals"]]
    with open(os.path.join(args.out, "results.md"), "w") as f:
        f.write("\n".join(md) + "\n")
    with open(os.path.join(args.out, "results.json"), "w") as f:
        json.dump(results, f, indent=1)
        f.write("\n")
    print(f"study report written to {args.out}: results.md, results.json and one directory "
          f"per scenario ({complete} of {planned} runs complete)")


def main(argv):
    p = argparse.ArgumentParser(prog="ahhs-report study",
                                description="a study (ahhs-study) against the paper's claims")
    p.add_argument("study", help="study directory or study export")
    p.add_argument("-o", "--out", required=True, help="output directory")
    p.add_argument("--overwrite", action="store_true", help="replace a report in --out")
    p.add_argument("--no-replay", action="store_true",
                   help="no replay figures and no mutation neighbourhoods (faster)")
    p.add_argument("--bin", help="directory of ahhs-replay")
    args = p.parse_args(argv)
    if not os.path.isdir(args.study):
        raise UsageError(f"{args.study} is not a directory")
    report_study(args)
    return 0
