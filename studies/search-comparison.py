#!/usr/bin/env python3
"""The paper's GA, CMA-ES and MAP-Elites on the pendulum (AHHS2-15), with equal evaluation
budgets (200 genomes x 200 generations = 40,000 episodes per run), 10 runs each, every run's
best judged on held-out episodes (docs/results.md, "Searches beyond the GA").

    /usr/bin/python3 studies/search-comparison.py run OUT_DIR --bin build/bin     # resumable
    /usr/bin/python3 studies/search-comparison.py report OUT_DIR --bin build/bin  # -> studies/search-comparison/

The GA's runs are the first study's (studies/paper-2010/pendulum-ahhs2-15, seeds 1-10: the
same preset, the same physics); CMA-ES and MAP-Elites run with examples/optimizers/, each run
seeded by its number (optimizer and evaluation seeds). `run` is resumable: run it again after a
stop and every run goes on from its checkpoint. A finished run is exported to
studies/search-comparison/runs/SEARCH/seed-N/ (its best.json, generations.csv and, for
MAP-Elites, archive.json: about 35 kB, committed), and a run with an export is not run again, so
a fresh machine goes on where the last one stopped. `report` reads the exports and post-evaluates every best genome on 50
held-out episodes under the `paper` envelope (ahhs-replay --post-eval 50), tests the medians
with two-sided Wilcoxon rank-sum tests, and writes results.json, results.md and a figure to
studies/search-comparison/.
"""
import argparse
import json
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.dirname(HERE)
SEEDS = range(1, 11)
CONFIGURATION = ["--scenario", "pendulum", "--variant", "ahhs2", "--hormones", "15", "--rules", "15"]
SEARCHES = {
    "cma-es": ["cmaes.py", "--population", "200", "--generations", "200", "--sigma", "0.2"],
    "map-elites": ["map_elites.py", "--batch", "200", "--generations", "200", "--cells", "10",
                   "--sigma", "0.1"],
}
POST_EVAL = 50
EXPORT = os.path.join(HERE, "search-comparison", "runs")
EXPORTED = ["best.json", "generations.csv", "archive.json"]


def complete(run_dir):
    csv = os.path.join(run_dir, "generations.csv")
    return os.path.exists(csv) and sum(1 for _ in open(csv)) == 201


def export(run_dir, name, seed):
    """Copies a finished run's small files to EXPORT/name/seed-N/ (each file atomically)."""
    target = os.path.join(EXPORT, name, "seed-%d" % seed)
    os.makedirs(target, exist_ok=True)
    for f in EXPORTED:
        if os.path.exists(os.path.join(run_dir, f)):
            with open(os.path.join(run_dir, f), "rb") as src:
                data = src.read()
            with open(os.path.join(target, f + ".tmp"), "wb") as dst:
                dst.write(data)
            os.replace(os.path.join(target, f + ".tmp"), os.path.join(target, f))


def run(args):
    for seed in SEEDS:
        for name, (script, *options) in SEARCHES.items():
            run_dir = os.path.join(args.out, name, "seed-%d" % seed)
            os.makedirs(os.path.dirname(run_dir), exist_ok=True)
            argv = [sys.executable, os.path.join(SOURCE, "examples", "optimizers", script),
                    run_dir, "--bin", args.bin, "--seed", str(seed), "--farm",
                    "--workers %d --lcm-url %s" % (args.workers, args.lcm_url)] + options + \
                ["--"] + CONFIGURATION + ["--seed", str(seed)]
            if complete(os.path.join(EXPORT, name, "seed-%d" % seed)):
                continue
            if not complete(run_dir):
                print("%s seed %d" % (name, seed), flush=True)
                subprocess.run(argv, check=True, stdout=subprocess.DEVNULL)
            export(run_dir, name, seed)


def post_eval(bin_dir, genome, out_json):
    if not os.path.exists(out_json):
        subprocess.run([os.path.join(bin_dir, "ahhs-replay"), "--genome", genome, "--scenario",
                        "pendulum", "--post-eval", str(POST_EVAL), "--post-eval-json",
                        out_json + ".tmp"], check=True, stdout=subprocess.DEVNULL)
        os.replace(out_json + ".tmp", out_json)
    with open(out_json) as f:
        return json.load(f)


def report(args):
    import numpy as np
    from scipy.stats import mannwhitneyu
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out = os.path.join(HERE, "search-comparison")
    os.makedirs(out, exist_ok=True)
    bests = {"ga": [], "cma-es": [], "map-elites": []}
    for seed in SEEDS:
        ga = os.path.join(HERE, "paper-2010", "pendulum-ahhs2-15", "seed-%d" % seed)
        with open(os.path.join(ga, "summary.json")) as f:
            training = json.load(f)["best_fitness"]
        bests["ga"].append((seed, os.path.join(ga, "best.json"), training))
        for name in SEARCHES:
            run_dir = os.path.join(EXPORT, name, "seed-%d" % seed)
            if not complete(run_dir):
                raise SystemExit("%s: not exported yet; finish it with `run`" % run_dir)
            with open(os.path.join(run_dir, "generations.csv")) as f:
                rows = list(f)[1:]
            training = max(float(r.split(",")[1]) for r in rows)
            bests[name].append((seed, os.path.join(run_dir, "best.json"), training))
    results = {"post_eval_episodes": POST_EVAL, "envelope": "paper", "budget": 40000,
               "searches": {}}
    for name, runs in bests.items():
        rows = []
        for seed, genome, training in runs:
            cache = os.path.join(args.out, "post-eval", "%s-seed-%d.json" % (name, seed))
            os.makedirs(os.path.dirname(cache), exist_ok=True)
            d = post_eval(args.bin, genome, cache)
            rows.append({"seed": seed, "training_best": training, "post_eval_median": d["median"],
                         "post_eval_q25": d["lower_quartile"],
                         "post_eval_q75": d["upper_quartile"]})
        results["searches"][name] = rows
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
    ax.set_title("Pendulum, AHHS2-15: 40,000 episodes per run, 10 runs each")
    fig.savefig(os.path.join(out, "post_eval.png"), dpi=110, bbox_inches="tight")
    md = ["| search | runs | training best: median | held-out median: median | q25 | q75 |",
          "|---|---|---|---|---|---|"]
    for n in names:
        t = [r["training_best"] for r in results["searches"][n]]
        m = medians[n]
        md.append("| %s | %d | %.4f | %.4f | %.4f | %.4f |" %
                  (n, len(m), np.median(t), np.median(m), np.percentile(m, 25),
                   np.percentile(m, 75)))
    md += ["", "| A | B | U | p (two-sided rank-sum) |", "|---|---|---|---|"]
    md += ["| %s | %s | %g | %.4g |" % (t["a"], t["b"], t["u"], t["p"]) for t in tests]
    with open(os.path.join(out, "results.md"), "w") as f:
        f.write("\n".join(md) + "\n")
    print("\n".join(md))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("command", choices=["run", "report"])
    p.add_argument("out", help="where the runs go (large; not committed)")
    p.add_argument("--bin", default=os.path.join(SOURCE, "build", "bin"))
    p.add_argument("--workers", type=int, default=2)
    p.add_argument("--lcm-url", default="udpm://239.255.42.90:7795?ttl=0")
    a = p.parse_args()
    run(a) if a.command == "run" else report(a)


if __name__ == "__main__":
    main()
