#!/usr/bin/env python3
"""The paper's GA, CMA-ES and MAP-Elites with equal evaluation budgets, 10 runs each, every run's
best judged on held-out episodes (docs/results.md, "Searches beyond the GA"), in two settings:

- `pendulum` (AHHS2-15): 200 genomes x 200 generations = 40,000 episodes per run. The GA's runs
  are the first study's (studies/paper-2010/pendulum-ahhs2-15, seeds 1-10: the same preset, the
  same physics); every best is post-evaluated here on 50 held-out episodes under the `paper`
  envelope (ahhs-replay --post-eval 50).
- `gait-fixed` (AHHS2-50, the robust gait): 20 genomes x 200 generations x 5 trials (their
  median) under the `paper` envelope, 20,000 episodes per run, each run's best chosen among its
  leaders on 20 validation episodes and post-evaluated on 50 held-out ones when it ends, the GA
  by ahhs-evolve and the others by ahhs-evaluate --validation 20 --post-eval 50: the same
  candidates, seeds and rules. The GA's runs are the robust study's
  (studies/paper-2010-robust/gait-fixed-ahhs2-50, the same preset and settings), taken as that
  study exports them; about 17 min per run on 2 cores (physics 2026-12-05).

    /usr/bin/python3 studies/search-comparison.py run OUT_DIR --bin build/bin [--setting gait-fixed]     # resumable
    /usr/bin/python3 studies/search-comparison.py report OUT_DIR --bin build/bin [--setting gait-fixed]

CMA-ES and MAP-Elites run with examples/optimizers/, each run seeded by its number (optimizer and
evaluation seeds). `run` is resumable: stop it with Ctrl-C or `kill -INT PID` (it passes the
signal on to its run), run it again and every run goes on from its checkpoint. `--finish-by
HH:MM|DURATION` starts or resumes no run that would end after that time at the mean run time of
its search's exported runs (for machines that go away at a known time). A finished run is exported to studies/search-comparison/[SETTING/]runs/SEARCH/seed-N/
(its best.json, generations.csv, post-eval.json and, for MAP-Elites, archive.json: tens of kB,
committed), and a run with an export is not run again, so a fresh machine goes on where the last
one stopped. `report` reads the exports, tests the held-out medians with two-sided Wilcoxon
rank-sum tests, gives each search's share of held-out episodes that succeed (gait: over the wall,
fitness > 1, and wholly beyond it at the end, counted by this build's post-evaluation where an
export's did not count it and taken only if it replays bit for bit), and writes results.json,
results.md and a figure beside them.
"""
import argparse
import json
import os
import signal
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(SOURCE, "python"))
sys.path.insert(0, os.path.join(SOURCE, "tools", "report"))
from ahhs.search import parse_finish_by  # noqa: E402
import report_lib  # noqa: E402
SEEDS = range(1, 11)
GENERATIONS = 200
POST_EVAL = 50
SETTINGS = {
    "pendulum": {
        "configuration": ["--scenario", "pendulum", "--variant", "ahhs2", "--hormones", "15",
                          "--rules", "15"],
        "searches": {
            "cma-es": ["cmaes.py", "--population", "200", "--sigma", "0.2"],
            "map-elites": ["map_elites.py", "--batch", "200", "--cells", "10", "--sigma", "0.1"],
        },
        "out": os.path.join(HERE, "search-comparison"),
        "ga": os.path.join(HERE, "paper-2010", "pendulum-ahhs2-15"),
        "budget": 40000,
        "title": "Pendulum, AHHS2-15: 40,000 episodes per run",
    },
    "gait-fixed": {
        # --physics: the robust study's (the GA's runs), so later runs stay comparable with it.
        "configuration": ["--scenario", "gait", "--docking", "fixed", "--physics", "2026-12-05",
                          "--variant", "ahhs2",
                          "--hormones", "5", "--rules", "50", "--trials", "5", "--aggregate",
                          "median", "--envelope", "paper", "--validation", "20", "--post-eval",
                          str(POST_EVAL)],
        "searches": {
            "cma-es": ["cmaes.py", "--population", "20", "--sigma", "0.2"],
            "map-elites": ["map_elites.py", "--batch", "20", "--cells", "10", "--sigma", "0.1"],
        },
        # ahhs-replay's arguments for the same scenario and physics (the crossing count, below).
        "replay": ["--scenario", "gait", "--docking", "fixed", "--physics", "2026-12-05"],
        "out": os.path.join(HERE, "search-comparison", "gait-fixed"),
        "ga": os.path.join(HERE, "paper-2010-robust", "gait-fixed-ahhs2-50"),
        "budget": 20000,
        "title": "Robust fixed gait, AHHS2-50: 20,000 episodes per run",
    },
}
EXPORTED = ["best.json", "generations.csv", "post-eval.json", "archive.json"]


def complete(run_dir, setting):
    """All generations in, and for a setting whose runs end with a post-evaluation, that too."""
    csv = os.path.join(run_dir, "generations.csv")
    if not os.path.exists(csv) or sum(1 for _ in open(csv)) != GENERATIONS + 1:
        return False
    return "--post-eval" not in setting["configuration"] or \
        os.path.exists(os.path.join(run_dir, "post-eval.json"))


def export(run_dir, setting, name, seed):
    """Copies a finished run's small files to OUT/runs/name/seed-N/ (each file atomically)."""
    target = os.path.join(setting["out"], "runs", name, "seed-%d" % seed)
    os.makedirs(target, exist_ok=True)
    for f in EXPORTED:
        if os.path.exists(os.path.join(run_dir, f)):
            with open(os.path.join(run_dir, f), "rb") as src:
                data = src.read()
            with open(os.path.join(target, f + ".tmp"), "wb") as dst:
                dst.write(data)
            os.replace(os.path.join(target, f + ".tmp"), os.path.join(target, f))


def generations_done(run_dir):
    csv = os.path.join(run_dir, "generations.csv")
    return max(0, sum(1 for _ in open(csv)) - 1) if os.path.exists(csv) else 0


def run_time(setting, name):
    """The mean wall time of a search's exported runs in this setting (None without one)."""
    times = []
    for seed in SEEDS:
        csv = os.path.join(setting["out"], "runs", name, "seed-%d" % seed, "generations.csv")
        if os.path.exists(csv):
            with open(csv) as f:
                rows = f.read().splitlines()
            column = rows[0].split(",").index("wall_time_s")
            times.append(sum(float(r.split(",")[column]) for r in rows[1:]))
    return sum(times) / len(times) if times else None


def run(args):
    setting = SETTINGS[args.setting]
    deferred = 0
    for seed in SEEDS:
        for name, (script, *options) in setting["searches"].items():
            run_dir = os.path.join(args.out, args.setting, name, "seed-%d" % seed)
            os.makedirs(os.path.dirname(run_dir), exist_ok=True)
            argv = [sys.executable, os.path.join(SOURCE, "examples", "optimizers", script),
                    run_dir, "--bin", args.bin, "--seed", str(seed), "--generations",
                    str(GENERATIONS), "--farm",
                    "--workers %d --lcm-url %s" % (args.workers, args.lcm_url)] + options + \
                ["--"] + setting["configuration"] + ["--seed", str(seed)]
            if complete(os.path.join(setting["out"], "runs", name, "seed-%d" % seed), setting):
                continue
            if not complete(run_dir, setting):
                estimate = run_time(setting, name)
                if args.finish_by is not None and estimate is not None:
                    left = estimate * (1 - generations_done(run_dir) / GENERATIONS)
                    if time.time() + left > args.finish_by:
                        print("%s %s seed %d: not starting, about %.0f min left, it would end "
                              "after %s (--finish-by)" % (
                                  args.setting, name, seed, left / 60,
                                  time.strftime("%H:%M", time.localtime(args.finish_by))),
                              flush=True)
                        deferred += 1
                        continue
                print("%s %s seed %d" % (args.setting, name, seed), flush=True)
                search = subprocess.Popen(argv, stdout=subprocess.DEVNULL)
                try:
                    code = search.wait()
                except KeyboardInterrupt:  # perhaps this process's alone: pass it on
                    signal.signal(signal.SIGINT, signal.SIG_IGN)
                    search.send_signal(signal.SIGINT)
                    search.wait()
                    print("interrupted: the same command resumes every run", file=sys.stderr)
                    sys.exit(130)
                if code != 0:
                    sys.exit("%s %s seed %d failed (exit %d)" % (args.setting, name, seed, code))
            export(run_dir, setting, name, seed)
    if deferred:
        print("%d %s not started (--finish-by); the same command goes on"
              % (deferred, "run" if deferred == 1 else "runs"))


def post_eval(bin_dir, genome, out_json):
    """A genome's post-evaluation by ahhs-replay, kept in out_json."""
    if not os.path.exists(out_json):
        os.makedirs(os.path.dirname(out_json), exist_ok=True)
        subprocess.run([os.path.join(bin_dir, "ahhs-replay"), "--genome", genome, "--scenario",
                        "pendulum", "--post-eval", str(POST_EVAL), "--post-eval-json",
                        out_json + ".tmp"], check=True, stdout=subprocess.DEVNULL)
        os.replace(out_json + ".tmp", out_json)
    with open(out_json) as f:
        return json.load(f)


def held_out(args, setting, run_dir, seed, name, stored):
    """A run's post-evaluation: `stored` when the run post-evaluated its best, else ahhs-replay's
    (pendulum, kept under OUT). For the gait with the share of held-out episodes that end with
    every module half beyond the wall: from the post-evaluation when that counted them, else
    from this build's post-evaluation on the same episodes (kept under OUT), taken only when
    every episode's seed and fitness equal the stored ones bit for bit (as ahhs-study report
    does); exits otherwise."""
    genome = os.path.join(run_dir, "best.json")
    def kept(kind):
        return os.path.join(args.out, args.setting, kind, "%s-seed-%d.json" % (name, seed))
    evaluation = stored if stored is not None else post_eval(args.bin, genome, kept("post-eval"))
    if "replay" not in setting:
        return evaluation
    share, source = report_lib.beyond_wall_share(
        args.bin, ["--genome", genome] + setting["replay"], evaluation, kept("beyond-wall"),
        reuse=True)
    if share is None:
        raise SystemExit("%s: %s (%s)" % (genome, source, args.bin))
    return dict(evaluation, beyond_wall_share=share)


def report(args):
    import numpy as np
    from scipy.stats import mannwhitneyu
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    setting = SETTINGS[args.setting]
    out = setting["out"]
    os.makedirs(out, exist_ok=True)
    searches = ["ga"] + list(setting["searches"])
    evaluations = {n: [] for n in searches}  # per search: (seed, training best, post-evaluation)
    for seed in SEEDS:
        ga = os.path.join(setting["ga"], "seed-%d" % seed)
        if not os.path.exists(os.path.join(ga, "summary.json")):
            raise SystemExit("%s: not exported yet by its study" % ga)
        with open(os.path.join(ga, "summary.json")) as f:
            summary = json.load(f)
        stored = None
        if "--post-eval" in setting["configuration"]:  # the GA run post-evaluated its best
            if "post_eval" not in summary:
                raise SystemExit("%s: its export has no post-evaluation" % ga)
            stored = summary["post_eval"]
        evaluation = held_out(args, setting, ga, seed, "ga", stored)
        evaluations["ga"].append((seed, summary["best_fitness"], evaluation))
        for name in setting["searches"]:
            run_dir = os.path.join(out, "runs", name, "seed-%d" % seed)
            if not complete(run_dir, setting):
                raise SystemExit("%s: not exported yet; finish it with `run`" % run_dir)
            with open(os.path.join(run_dir, "generations.csv")) as f:
                rows = list(f)[1:]
            training = max(float(r.split(",")[1]) for r in rows)
            stored = None
            if "--post-eval" in setting["configuration"]:
                with open(os.path.join(run_dir, "post-eval.json")) as f:
                    stored = json.load(f)
            evaluation = held_out(args, setting, run_dir, seed, name, stored)
            evaluations[name].append((seed, training, evaluation))
    results = {"setting": args.setting, "post_eval_episodes": POST_EVAL, "envelope": "paper",
               "budget": setting["budget"], "searches": {}}
    for name, runs in evaluations.items():
        results["searches"][name] = [
            {"seed": seed, "training_best": training, "post_eval_median": d["median"],
             "post_eval_q25": d["lower_quartile"], "post_eval_q75": d["upper_quartile"],
             "success_share": d.get("success_share"),
             "beyond_wall_share": d.get("beyond_wall_share")}
            for seed, training, d in runs]
    medians = {n: [r["post_eval_median"] for r in rows]
               for n, rows in results["searches"].items()}
    tests = []
    names = list(medians)
    for i in range(len(names)):
        for j in range(i + 1, len(names)):
            a, b = names[i], names[j]
            u, p = mannwhitneyu(medians[a], medians[b], alternative="two-sided")
            tests.append({"a": a, "b": b, "u": float(u), "p": float(p)})
    results["tests"] = tests
    with open(os.path.join(out, "results.json"), "w") as f:
        json.dump(results, f, indent=1)
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    ax.boxplot([medians[n] for n in names], labels=names)
    for k, n in enumerate(names):
        ax.scatter(np.full(len(medians[n]), k + 1.0), medians[n], s=12, color="k", zorder=3)
    ax.set_ylabel("held-out median fitness of the run's best")
    ax.set_title(setting["title"] + ", 10 runs each")
    fig.savefig(os.path.join(out, "post_eval.png"), dpi=110, bbox_inches="tight")
    success = "over the wall (fitness > 1)" if "replay" in setting else "succeeding"
    md = ["| search | runs | training best: median | held-out median: median | q25 | q75 "
          "| held-out episodes %s: mean share (runs with any) |%s" %
          (success, " wholly beyond the wall at the end |" if "replay" in setting else ""),
          "|---|---|---|---|---|---|---|%s" % ("---|" if "replay" in setting else "")]

    def shares(rows, key):
        v = [r[key] for r in rows]
        return "%.0f %% (%d of %d)" % (100 * np.mean(v), sum(x > 0 for x in v), len(v))
    for n in names:
        rows = results["searches"][n]
        t = [r["training_best"] for r in rows]
        m = medians[n]
        md.append("| %s | %d | %.4f | %.4f | %.4f | %.4f | %s |%s" %
                  (n, len(m), np.median(t), np.median(m), np.percentile(m, 25),
                   np.percentile(m, 75), shares(rows, "success_share"),
                   " %s |" % shares(rows, "beyond_wall_share") if "replay" in setting else ""))
    md += ["", "| A | B | U | p (two-sided rank-sum) |", "|---|---|---|---|"]
    md += ["| %s | %s | %g | %.4g |" % (t["a"], t["b"], t["u"], t["p"]) for t in tests]
    with open(os.path.join(out, "results.md"), "w") as f:
        f.write("\n".join(md) + "\n")
    print("\n".join(md))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("command", choices=["run", "report"])
    p.add_argument("--setting", choices=sorted(SETTINGS), default="pendulum")
    p.add_argument("out", help="where the runs go (large; not committed)")
    p.add_argument("--bin", default=os.path.join(SOURCE, "build", "bin"))
    p.add_argument("--workers", type=int, default=2)
    p.add_argument("--lcm-url", default="udpm://239.255.42.90:7795?ttl=0")
    p.add_argument("--finish-by", metavar="HH:MM|DURATION",
                   help="run: start or resume no run that would end after this, at the mean run "
                   "time of its search's exported runs (as ahhs-study run --finish-by)")
    a = p.parse_args()
    if a.finish_by is not None:
        try:
            a.finish_by = parse_finish_by(a.finish_by, time.time())
        except ValueError as e:
            p.error(str(e))
    # Stopped by `kill -INT` or `kill` even when a script started it in the background (its shell
    # has it ignore SIGINT): each run stops in order and resumes.
    signal.signal(signal.SIGINT, signal.default_int_handler)
    signal.signal(signal.SIGTERM, signal.default_int_handler)
    run(a) if a.command == "run" else report(a)


if __name__ == "__main__":
    main()
