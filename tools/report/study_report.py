"""ahhs-report study STUDY_DIR -o OUT_DIR: a whole study (ahhs-study) against the paper.

Reads the complete runs of a study directory or of a study export (each config's
seed-<k>/summary.json), in the plan's order (study.toml), and writes into OUT_DIR:
  <task>/          ahhs-report of every complete run of the task (fitness, box plots, tests,
                   the best controller of the first run)
  <task>/box_robust.png   the robust fitness of each run's best, per configuration (rank-sum)
  <task>/neighbourhood-<config>/   35 single mutants of the configuration's best genome
  results.md       the paper's claims, one per row, with our figures beside them
  results.json     the numbers behind results.md
Every run's best genome is replayed once (rule activity, hormones in use, and whether this build
reproduces its stored fitness bit for bit) and 8 times with perturbed frictions (ahhs-replay
--robustness): its robust fitness is the median of those 8.
Each claim about runs' fitness is judged twice: on each run's best fitness (the paper's
statistic) and on the robust fitness of each run's best, since an evolved gait best is often a
knife-edge of deterministic chaos (docs/scenarios.md).
"""
import argparse
import json
import os
import sys
import tempfile
import tomllib
from collections import OrderedDict

import numpy as np

from report_lib import (ReportError, Run, UsageError, box_figure, find_bin, prepare_out,
                        rank_sum_test, rule_edges, rule_parts, run_replay)
from run_report import report_neighbourhood, report_runs

PAPER_FIXED_MAXIMUM = 1.7  # "the theoretical maximum fitness of about 1.7" (fixed docking)
SELDOM = 0.01  # a rule part active in fewer ticks than this triggers "seldom"
MUTANTS = 35
MIN_RUNS = 5  # fewer complete runs of a configuration give a claim no verdict yet
ROBUSTNESS = 8


class Config:
    def __init__(self, name, planned, runs):
        self.name, self.planned, self.runs = name, planned, runs
        self.task = runs[0].task if runs else None
        self.best = np.array([r.best_overall() for r in runs])
        self.robust = None  # per run: robust fitness of its best genome (None: a run has none)
        self.controllers = []  # per run: rule and hormone use of its best genome
        self.speed = []  # per run: the generation reaching 75 % of the task's maximum
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
        configs.append(Config(name, seeds, runs))
    return plan.get("name", os.path.basename(path)), configs


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
            "max": float(np.max(values)) if values else None}


def neighbourhood_of(bin_dir, config, out_dir):
    run = config.best_run()
    args = argparse.Namespace(genome=run.path, mutants=MUTANTS, mutant_seed=1, out=out_dir,
                              overwrite=True, bin=bin_dir, scenario=run.config["scenario"],
                              joints=run.config["joints"], modules=run.config["modules"],
                              duration=float(run.config["duration"]), seed=1)
    if run.exported:
        args.genome = os.path.join(run.path, "best.json")
        args.seed = int(summary_of(run)["best_eval_seed"])
    report_neighbourhood(args)
    data = np.genfromtxt(os.path.join(out_dir, "mutants.csv"), delimiter=",", names=True,
                         dtype=None, encoding="utf-8")
    original = float(data["fitness"][0])
    mutants = np.array([float(v) for v in data["fitness"][1:]])
    return {"run": run.path, "original": original, "median": float(np.median(mutants)),
            "below_0.2": float(np.mean(mutants < 0.2)),
            "keep_90": float(np.mean(mutants >= 0.9 * original)) if original > 0 else None}


# ---------------------------------------------------------------------------------------------
# Claims


def fmt(v, digits=3):
    return "-" if v is None else f"{v:.{digits}g}"


def pct(v):
    return "-" if v is None else f"{100 * v:.0f} %"


class Claims:
    """The claims on one per-run statistic: "best" (each run's best fitness) or "robust"."""

    def __init__(self, configs, maxima, stat="best"):
        self.by = {c.name: c for c in configs}
        self.maxima = maxima
        self.stat = stat
        self.rows = []

    def get(self, name):
        c = self.by.get(name)
        return c if c is not None and len(c.runs) > 0 else None

    def values(self, name):
        return getattr(self.get(name), self.stat)

    def test(self, a, b):
        ca, cb = self.get(a), self.get(b)
        if not ca or not cb or len(ca.runs) < 2 or len(cb.runs) < 2:
            return None
        return rank_sum_test(list(self.values(a)), list(self.values(b)))[1]

    def add(self, claim, paper, ours, verdict):
        self.rows.append((claim, paper, ours, verdict))

    def missing(self, claim, paper, *names, per_run=True):
        """True (and a row saying so) when a configuration has no run, or, for a claim about
        runs (per_run), fewer than MIN_RUNS."""
        absent = [n for n in names if not self.get(n)]
        if absent:
            self.add(claim, paper, "not run yet (" + ", ".join(absent) + ")", "open")
            return True
        if per_run and any(self.values(n) is None for n in names):
            self.add(claim, paper, "no robust fitness (a best genome's replays failed)", "open")
            return True
        few = [f"{n}: {len(self.get(n).runs)}" for n in names
               if per_run and len(self.get(n).runs) < MIN_RUNS]
        if few:
            self.add(claim, paper, "too few complete runs so far (" + ", ".join(few) + ")", "open")
            return True
        return False

    def speed_test(self, a, b):
        return rank_sum_test(list(self.get(a).speed), list(self.get(b).speed))[1]

    def median(self, name):
        return float(np.median(self.values(name)))

    def within(self, name, level):
        return float(np.mean(self.values(name) >= level))

    def iqr(self, name):
        return float(np.subtract(*np.percentile(self.values(name), [75, 25])))

    def not_fitness(self, claim, paper):
        """For a claim that is not about runs' fitness: True (and an empty row) unless this is
        the "best" pass, which judges it."""
        if self.stat == "best":
            return False
        self.add(claim, paper, None, None)
        return True


def make_claims(configs, maxima, stat="best"):
    """The paper's claims as rows (claim, paper, ours, verdict), judged on `stat`: "best" (each
    run's best fitness) or "robust" (its robust fitness). Claims that are not about runs'
    fitness (evolution speed, neighbourhoods, controllers) are the same for both."""
    c = Claims(configs, maxima, stat)
    # Pendulum (section 3.1).
    claim = "Pendulum: AHHS2-15 is better than AHHS1-60"
    paper = "yes, Wilcoxon p < 0.05 (n = 10 AHHS2, 8 AHHS1)"
    if not c.missing(claim, paper, "pendulum-ahhs2-15", "pendulum-ahhs1-60"):
        a, b = c.median("pendulum-ahhs2-15"), c.median("pendulum-ahhs1-60")
        p = c.test("pendulum-ahhs2-15", "pendulum-ahhs1-60")
        verdict = ("not tested (n < 2)" if p is None else "reproduced" if a > b and p < 0.05 else
                   "opposite: AHHS1-60 is better" if a < b and p < 0.05 else "not significant")
        c.add(claim, paper, f"medians {a:.3f} (AHHS2-15) vs {b:.3f} (AHHS1-60), p = {fmt(p)}",
              verdict)
    claim = "Pendulum: evolution speed (generation reaching 75 % of the maximum)"
    paper = "no significant difference"
    if not c.not_fitness(claim, paper) and not c.missing(claim, paper, "pendulum-ahhs2-15",
                                                         "pendulum-ahhs1-60"):
        p = c.speed_test("pendulum-ahhs2-15", "pendulum-ahhs1-60")
        a, b = (float(np.median(c.get(n).speed)) for n in ("pendulum-ahhs2-15", "pendulum-ahhs1-60"))
        c.add(claim, paper, f"medians {a:g} (AHHS2-15) vs {b:g} (AHHS1-60), p = {fmt(p)}",
              "reproduced" if p >= 0.05 else "differs: significant difference")
    # Damped docking (first simulator version).
    claim = "Damped gait: high fitness in every setting, no significant difference"
    paper = "yes (AHHS2-30 and AHHS1-120 among others; best 1.88)"
    if not c.missing(claim, paper, "gait-damped-ahhs2-30", "gait-damped-ahhs1-120"):
        p = c.test("gait-damped-ahhs2-30", "gait-damped-ahhs1-120")
        a, b = c.median("gait-damped-ahhs2-30"), c.median("gait-damped-ahhs1-120")
        verdict = ("not tested (n < 2)" if p is None else
                   "reproduced" if p >= 0.05 else "differs: significant difference")
        c.add(claim, paper, f"medians {a:.3f} (AHHS2-30) vs {b:.3f} (AHHS1-120), p = {fmt(p)}",
              verdict)
    claim, paper = "Damped gait: AHHS1 runs vary more", "yes (AHHS1-120 vs AHHS2-30)"
    if not c.missing(claim, paper, "gait-damped-ahhs2-30", "gait-damped-ahhs1-120"):
        iqr = {n: c.iqr(n) for n in ("gait-damped-ahhs1-120", "gait-damped-ahhs2-30")}
        c.add(claim, paper, f"interquartile range {iqr['gait-damped-ahhs1-120']:.3f} (AHHS1-120) "
              f"vs {iqr['gait-damped-ahhs2-30']:.3f} (AHHS2-30)",
              "reproduced" if iqr["gait-damped-ahhs1-120"] > iqr["gait-damped-ahhs2-30"]
              else "differs")
    # Fixed docking (second simulator version). Our maximum: the task's best fitness, or in the
    # robust pass the highest robust fitness of its runs.
    top = maxima.get("gait-fixed")
    if stat != "best":
        robust = [c.values(n) for n, x in c.by.items()
                  if x.task == "gait-fixed" and x.runs and c.values(n) is not None]
        top = max(float(np.max(v)) for v in robust) if robust else None
    ours_max = "our maximum" if stat == "best" else "our highest robust fitness"
    for name, share in (("gait-fixed-ahhs2-50", 0.55), ("gait-fixed-ahhs1-80", 0.38)):
        label = name.split("-", 2)[2].upper()
        claim = f"Fixed gait: share of {label} runs within 80 % of the maximum"
        paper = f"{share:.0%} (maximum about 1.7)"
        if not c.missing(claim, paper, name):
            ours = c.within(name, 0.8 * PAPER_FIXED_MAXIMUM)
            own = c.within(name, 0.8 * top)
            c.add(claim, paper, f"{ours:.0%} of {len(c.get(name).runs)} runs >= 1.36 (80 % of 1.7); "
                  f"{own:.0%} within 80 % of {ours_max} {top:.3f}",
                  "close" if abs(ours - share) <= 0.15 else "differs")
    claim = "Fixed gait: AHHS1-20 differs significantly from AHHS1-80 and from AHHS2-50"
    paper = "yes, and no other pair differs significantly"
    if not c.missing(claim, paper, "gait-fixed-ahhs1-20", "gait-fixed-ahhs1-80",
                     "gait-fixed-ahhs2-50"):
        p1 = c.test("gait-fixed-ahhs1-20", "gait-fixed-ahhs1-80")
        p2 = c.test("gait-fixed-ahhs1-20", "gait-fixed-ahhs2-50")
        p3 = c.test("gait-fixed-ahhs1-80", "gait-fixed-ahhs2-50")
        ok = None not in (p1, p2, p3)
        c.add(claim, paper, f"p = {fmt(p1)} (vs AHHS1-80), {fmt(p2)} (vs AHHS2-50); "
              f"AHHS1-80 vs AHHS2-50: {fmt(p3)}",
              "not tested (n < 2)" if not ok else "reproduced" if max(p1, p2) < 0.05 <= p3
              else "differs")
    claim, paper = "Fixed gait: AHHS2-20 performs badly", "yes, lowest best fitness and slowest"
    fixed = [n for n in ("gait-fixed-ahhs1-20", "gait-fixed-ahhs1-80", "gait-fixed-ahhs2-50",
                         "gait-fixed-ahhs2-20") if c.get(n)]
    if not c.missing(claim, paper, "gait-fixed-ahhs2-20"):
        medians = {n: c.median(n) for n in fixed}
        lowest = min(medians, key=medians.get)
        c.add(claim, paper, "medians " + ", ".join(f"{n.split('-', 2)[2].upper()} {m:.3f}"
                                                   for n, m in medians.items()),
              "reproduced" if lowest == "gait-fixed-ahhs2-20" else "differs: " +
              lowest.split("-", 2)[2].upper() + " is lowest")
    # Mutation neighbourhood (post-evaluation, fixed docking).
    for name, label, paper in (("gait-fixed-ahhs1-80", "AHHS1", "most below 0.2 (original 0.84)"),
                               ("gait-fixed-ahhs2-50", "AHHS2",
                                "most about as good as the original (0.81)")):
        claim = f"Mutation neighbourhood of a good {label} controller (35 single mutants)"
        if c.get(name) and c.get(name).neighbourhood and c.not_fitness(claim, paper):
            continue
        if not c.missing(claim, paper, name, per_run=False) and c.get(name).neighbourhood:
            n = c.get(name).neighbourhood
            ours = (f"original {n['original']:.3f}; mutants' median {n['median']:.3f}; "
                    f"{pct(n['below_0.2'])} below 0.2, {pct(n['keep_90'])} keep 90 %")
            if label == "AHHS1":
                verdict = "reproduced" if n["below_0.2"] > 0.5 else "differs"
            else:
                verdict = "reproduced" if (n["keep_90"] or 0) > 0.5 else "differs"
            c.add(claim, paper, ours, verdict)
    # Controllers.
    gait = [x for x in configs if x.runs and x.task.startswith("gait")]
    uses = [u for x in gait for u in x.controllers]
    claim, paper = "Gait: rules that never or seldom trigger", "about one third"
    if c.not_fitness(claim, paper):
        pass
    elif not uses:
        c.add(claim, paper, "not run yet (gait)", "open")
    else:
        share = [(u["never"] + u["seldom"]) / u["rules"] for u in uses]
        c.add(claim, paper, f"median {np.median(share):.0%} over {len(uses)} best genomes "
              f"(quartiles {np.percentile(share, 25):.0%} / {np.percentile(share, 75):.0%})",
              "close" if 0.2 <= np.median(share) <= 0.45 else "differs")
    damped = [u for x in gait if x.task == "gait-damped" for u in x.controllers]
    claim, paper = "Damped gait: hormones and rules a controller uses", "2-3 of 5 hormones, < 10 rules"
    if c.not_fitness(claim, paper):
        pass
    elif not damped:
        c.add(claim, paper, "not run yet (gait-damped)", "open")
    else:
        h = np.median([u["hormones_used"] for u in damped])
        r = np.median([u["active"] for u in damped])
        c.add(claim, paper, f"median {h:g} hormones touched by rules active in >= 1 % of ticks, "
              f"{r:g} such rules ({len(damped)} best genomes)",
              "reproduced" if h <= 3 and r < 10 else "differs")
    return c.rows


# ---------------------------------------------------------------------------------------------
# The command


def report_study(args):
    name, configs = load_study(args.study)
    done = [c for c in configs if c.runs]
    if not done:
        raise ReportError(f"{args.study}: no complete run yet")
    prepare_out(args.out, args.overwrite, allow_dirs=True)
    bin_dir = find_bin(args)
    tasks = OrderedDict()
    for c in done:
        tasks.setdefault(c.task, []).append(c)
    maxima = {t: float(max(np.max(c.best) for c in cs)) for t, cs in tasks.items()}
    for c in done:  # the paper's evolution speed; a run that never gets there counts its length
        c.speed = [r.first_generation_reaching(0.75 * maxima[c.task]) for r in c.runs]
        c.speed = [int(r.generation[-1]) + 1 if g is None else g for r, g in zip(c.runs, c.speed)]
    for task, cs in tasks.items():
        report_runs(argparse.Namespace(runs=[r for c in cs for r in c.runs],
                                       out=os.path.join(args.out, task), overwrite=True,
                                       no_replay=args.no_replay, bin=bin_dir))
    with tempfile.TemporaryDirectory() as scratch:
        for c in done:
            c.controllers = [controller_use(bin_dir, r, scratch) for r in c.runs]
            c.robustness_runs = [robustness_of(bin_dir, r, scratch) for r in c.runs]
            c.robustness = c.robustness_runs[int(np.argmax(c.best))]
            medians = [x["median"] for x in c.robustness_runs]
            c.robust = None if None in medians else np.array(medians)
            if not args.no_replay:
                c.neighbourhood = neighbourhood_of(
                    bin_dir, c, os.path.join(args.out, c.task, f"neighbourhood-{c.name}"))
    for task, cs in tasks.items():
        robust = [c for c in cs if c.robust is not None]
        if robust:
            box_figure({c.name: c.runs for c in robust}, {c.name: list(c.robust) for c in robust},
                       "robust fitness of the run's best", "Robust fitness of each run's best "
                       "genome (median of 8 replays, friction x 0.975-1.025), Wilcoxon rank-sum",
                       "box_robust", os.path.join(args.out, task), [])
    claims = merge_claims(make_claims(configs, maxima, "best"),
                          make_claims(configs, maxima, "robust"))
    write_results(args, name, configs, tasks, maxima, claims)


def merge_claims(best, robust):
    """Rows (claim, paper, ours, verdict, ours robust, verdict robust)."""
    assert [r[0] for r in best] == [r[0] for r in robust], (best, robust)
    return [b + (r[2], r[3]) for b, r in zip(best, robust)]


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


def write_results(args, name, configs, tasks, maxima, claims):
    complete = sum(len(c.runs) for c in configs)
    planned = sum(c.planned for c in configs)
    replayed, differ = reproduction(configs)
    if differ:
        print(f"ahhs-study report: warning: {len(differ)} of {complete} runs' best genomes do not "
              "replay to their stored fitness with this build (results.md)", file=sys.stderr)
    md = [f"# Results: study `{name}` against Hamann et al. (ALife 2010)", "",
          f"From {complete} complete runs of the {planned} planned "
          f"(`ahhs-study report {os.path.basename(os.path.normpath(args.study))}`). A row whose "
          "configurations have no complete run yet says so.", "", replayed, "",
          "## The paper's claims", "",
          "Judged twice: on each run's best fitness (the paper's statistic), and on the robust "
          "fitness of each run's best genome (the median of 8 replays with the friction scaled "
          "0.975-1.025). Claims that are not about runs' fitness are judged once.", "",
          "| claim | the paper | ours: each run's best | verdict | ours: robust | "
          "verdict (robust) |",
          "|---|---|---|---|---|---|"]
    md += [f"| {a} | {b} | {c} | {d} | {'-' if e is None else e} | {'-' if f is None else f} |"
           for a, b, c, d, e, f in claims]
    md += ["", "## Configurations", "",
           "Best fitness is each run's best (the paper's statistic). Robust: a best genome "
           "replayed with the friction scaled 0.975-1.025 (8 replays, median), for the "
           "configuration's best and for each run's; an evolved gait best is usually far above "
           "it (docs/findings.md, \"Physics step and deterministic chaos\"). Rules: share of the "
           "rules of the runs' best genomes that "
           "never or seldom (< 1 % of ticks) trigger; hormones: touched by a rule part active in "
           ">= 1 % of ticks (median over runs).", "",
           "| configuration | runs | best fitness: median (quartiles) | max | robust median of the max | "
           "robust fitness of the runs' bests: median (quartiles) | "
           "within 80 % of the task's maximum | generation to 75 %: median | rules never/seldom | "
           "hormones used |",
           "|---|---|---|---|---|---|---|---|---|---|"]
    results = {"study": name, "complete_runs": complete, "planned_runs": planned,
               "replay_differs": differ, "maxima": maxima, "configs": {}, "claims": claims}
    for c in configs:
        if not c.runs:
            md.append(f"| {c.name} | 0 of {c.planned} | not run yet | | | | | | | |")
            continue
        q1, med, q3 = np.percentile(c.best, [25, 50, 75])
        within = float(np.mean(c.best >= 0.8 * maxima[c.task]))
        quiet = np.median([(u["never"] + u["seldom"]) / u["rules"] for u in c.controllers])
        hormones = np.median([u["hormones_used"] for u in c.controllers])
        robust = "-" if c.robust is None else "{1:.3f} ({0:.3f} / {2:.3f})".format(
            *np.percentile(c.robust, [25, 50, 75]))
        md.append(f"| {c.name} | {len(c.runs)} of {c.planned} | {med:.3f} ({q1:.3f} / {q3:.3f}) | "
                  f"{np.max(c.best):.3f} | {fmt(c.robustness['median'])} | {robust} | "
                  f"{within:.0%} | "
                  f"{np.median(c.speed):g} | {quiet:.0%} | "
                  f"{hormones:g} of {c.controllers[0]['hormones']} |")
        results["configs"][c.name] = {
            "runs": len(c.runs), "planned": c.planned, "task": c.task,
            "best": [float(v) for v in c.best], "median": float(med),
            "within_80_percent": within, "speed": c.speed, "robustness": c.robustness,
            "robust": None if c.robust is None else [float(v) for v in c.robust],
            "robustness_runs": c.robustness_runs,
            "neighbourhood": c.neighbourhood, "controllers": c.controllers}
    md += ["", "## Figures", ""]
    for task in tasks:
        md += [f"- {task}: `{task}/fitness.png`, `{task}/box_best.png`, `{task}/box_robust.png`, "
               f"`{task}/box_speed.png`, `{task}/summary.md`"]
        md += [f"  - mutation neighbourhood of {c.name}'s best: "
               f"`{task}/neighbourhood-{c.name}/neighbourhood.png`"
               for c in tasks[task] if c.neighbourhood]
    with open(os.path.join(args.out, "results.md"), "w") as f:
        f.write("\n".join(md) + "\n")
    with open(os.path.join(args.out, "results.json"), "w") as f:
        json.dump(results, f, indent=1)
        f.write("\n")
    print(f"study report written to {args.out}: results.md, results.json and one directory "
          f"per task ({complete} of {planned} runs complete)")


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
