"""ahhs-report steps: is the gait's physics step fine enough, judged by distributions?

A chaotic system has no converged trajectory, so the step is judged by whether the *post-evaluated
distribution* of each genome converges (docs/scenarios.md, "Physics step"): every
genome is replayed on the same N held-out episodes (ahhs-replay --post-eval N) at the scenario's step
h, at h / 2 and at 2 h. A step passes when, for every genome, its median and its over-the-wall
share agree with those at h / 2 within 10 % and 0.15. The episodes are the same at every step,
so the table also gives a paired bootstrap interval of each difference of medians: how much of a
difference sampling alone could make. Writes steps.csv (one row per genome and step) and
summary.md (the table and the verdicts).
"""
import argparse
import concurrent.futures
import csv
import json
import os
import random
import statistics
import tempfile

import report_lib as report

# The scenarios' steps (sim/core/constants.h, GaitConstants::physics_step_*).
DOCKING_STEP = {"damped": 0.00625, "fixed": 0.0125}
MEDIAN_TOLERANCE = 0.10  # relative, against h / 2
SHARE_TOLERANCE = 0.15   # absolute, against h / 2
BOOTSTRAP_RESAMPLES = 2000
BOOTSTRAP_SEED = 2026    # the interval is the same every time


def bootstrap_interval(row, half):
    """The 90 % paired bootstrap interval of median(step) - median(h / 2) over the same episodes
    (None when an episode failed at either step)."""
    a, b = row["fitnesses"], half["fitnesses"]
    if None in a or None in b or len(a) != len(b) or not a:
        return None
    rng = random.Random(BOOTSTRAP_SEED)
    n = len(a)
    diffs = []
    for _ in range(BOOTSTRAP_RESAMPLES):
        idx = [rng.randrange(n) for _ in range(n)]
        diffs.append(statistics.median(a[i] for i in idx) - statistics.median(b[i] for i in idx))
    diffs.sort()
    return diffs[int(0.05 * len(diffs))], diffs[int(0.95 * len(diffs)) - 1]


def post_evaluate(bin_dir, genome, args, step, tmp):
    """One genome at one step: the post-evaluation's JSON."""
    out = os.path.join(tmp, f"{abs(hash((genome, step)))}.json")
    if os.path.isdir(genome):
        report.Run(genome)  # a clear error for a directory that is not a run
        argv = [genome]
    else:
        if not os.path.isfile(genome):
            raise report.ReportError(f"{genome}: no such genome file or run directory")
        argv = ["--genome", genome, "--scenario", "gait", "--docking", args.docking,
                "--modules", str(args.modules)]
    argv += ["--physics-step", repr(step), "--post-eval", str(args.episodes),
             "--post-eval-json", out]
    if args.envelope:
        argv += ["--envelope", args.envelope]
    if args.physics:
        argv += ["--physics", args.physics]
    report.run_replay(bin_dir, argv)
    with open(out) as f:
        return json.load(f)


def agrees(row, half):
    """Whether a step's distribution agrees with the one at half the step."""
    if row["median"] is None or half["median"] is None:
        return False
    scale = max(abs(half["median"]), 1e-9)
    return (abs(row["median"] - half["median"]) <= MEDIAN_TOLERANCE * scale
            and abs(row["success_share"] - half["success_share"]) <= SHARE_TOLERANCE)


def quartiles_moved(row, half):
    """The quartiles of a step's distribution that moved by more than MEDIAN_TOLERANCE of the
    median at half the step: [(name, at this step, at half of it)]. Not part of the rule (it
    judges medians and over-the-wall shares), but a second hump that appears or goes with the
    step moves a quartile and not the median."""
    if half["median"] is None:
        return []
    scale = max(abs(half["median"]), 1e-9)
    return [(name, row[key], half[key])
            for name, key in (("lower quartile", "lower_quartile"),
                              ("upper quartile", "upper_quartile"))
            if row[key] is not None and half[key] is not None
            and abs(row[key] - half[key]) > MEDIAN_TOLERANCE * scale]


def report_steps(args):
    report.prepare_out(args.out, args.overwrite)
    bin_dir = report.find_bin(args)
    h = args.step or DOCKING_STEP[args.docking]
    steps = [h / 2, h, 2 * h]
    rows = []
    with tempfile.TemporaryDirectory(prefix="ahhs-steps-") as tmp:
        with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
            jobs = {(g, s): pool.submit(post_evaluate, bin_dir, g, args, s, tmp)
                    for g in args.genomes for s in steps}
            for (g, s), job in jobs.items():
                p = job.result()
                rows.append({"genome": g, "step": s, "episodes": p["episodes"],
                             "failed": p["failed"], "median": p["median"],
                             "lower_quartile": p["lower_quartile"],
                             "upper_quartile": p["upper_quartile"], "min": p["min"],
                             "success_share": p["success_share"],
                             "fitnesses": [e["fitness"] if e.get("fitness") is not None else None
                                           for e in p["per_episode"]]})
    path = os.path.join(args.out, "steps.csv")
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=[k for k in rows[0] if k != "fitnesses"])
        w.writeheader()
        w.writerows({k: v for k, v in r.items() if k != "fitnesses"} for r in rows)
    by = {(r["genome"], r["step"]): r for r in rows}
    verdict = {}
    for s in steps[1:]:
        verdict[s] = all(agrees(by[(g, s)], by[(g, steps[0])]) for g in args.genomes)
    fmt = lambda v: "failed" if v is None else f"{v:.3f}"
    md = ["# Physics step by distribution", "",
          f"{len(args.genomes)} genomes, each post-evaluated on the same {args.episodes} held-out "
          f"episodes (envelope {args.envelope or 'of the run, or paper'}), {args.docking} docking, "
          f"physics {args.physics or 'of each genome (else this build)'}, "
          f"at {steps[0] * 1e3:g} ms, {steps[1] * 1e3:g} ms (the scenario's) and {steps[2] * 1e3:g} ms.",
          f"A step passes when every genome's median and over-the-wall share agree with those at "
          f"{steps[0] * 1e3:g} ms within {MEDIAN_TOLERANCE:.0%} and {SHARE_TOLERANCE}; in brackets "
          f"after the verdict, the 90 % paired bootstrap interval of the difference of medians.", "",
          "| genome | " + " | ".join(f"{s * 1e3:g} ms: median (quartiles), over the wall"
                                     for s in steps) + " |",
          "|---|" + "---|" * len(steps)]
    for g in args.genomes:
        cells = []
        for s in steps:
            r = by[(g, s)]
            mark = ""
            if s != steps[0]:
                mark = " (agrees" if agrees(r, by[(g, steps[0])]) else " (differs"
                ci = bootstrap_interval(r, by[(g, steps[0])])
                mark += f"; {ci[0]:+.3f} to {ci[1]:+.3f})" if ci else ")"
            cells.append(f"{fmt(r['median'])} ({fmt(r['lower_quartile'])} / "
                         f"{fmt(r['upper_quartile'])}), {r['success_share']:.0%}{mark}")
        md.append(f"| `{g}` | " + " | ".join(cells) + " |")
    md.append("")
    verdicts = [f"- {s * 1e3:g} ms: {'passes' if verdict[s] else 'does not pass'}"
                for s in steps[1:]]
    md += verdicts
    moved = [f"`{g}` at {s * 1e3:g} ms: {name} {fmt(v)} against {fmt(v_half)}"
             for g in args.genomes for s in steps[1:]
             for name, v, v_half in quartiles_moved(by[(g, s)], by[(g, steps[0])])]
    if moved:
        md += ["", f"Quartiles that moved by more than {MEDIAN_TOLERANCE:.0%} of the median at "
               f"{steps[0] * 1e3:g} ms (not judged by the rule; a second hump of the distribution "
               f"that comes or goes with the step moves them):"]
        md += [f"- {m}" for m in moved]
    with open(os.path.join(args.out, "summary.md"), "w") as f:
        f.write("\n".join(md) + "\n")
    print("\n".join(verdicts))
    if moved:
        print(f"quartiles moved: {len(moved)} (summary.md)")
    print(f"steps written to {args.out}: summary.md, steps.csv")
    return 0


def main(argv):
    p = argparse.ArgumentParser(prog="ahhs-report steps", description=__doc__.split("\n")[0])
    p.add_argument("genomes", nargs="+", help="genome files, or run directories (their best)")
    report.add_docking_option(p)
    p.add_argument("--modules", type=int, default=5)
    p.add_argument("--step", type=float, help="the step to judge, s (default: the scenario's)")
    p.add_argument("--episodes", type=int, default=50, help="held-out episodes per genome and step")
    p.add_argument("--envelope", choices=["none", "paper", "wide"],
                   help="default: a run's own envelope, else paper")
    p.add_argument("--physics", help="the physics version (ahhs-replay --physics; default: the "
                                      "genome's, else this build's)")
    p.add_argument("--jobs", type=int, default=os.cpu_count() or 1, help="replays at once")
    p.add_argument("-o", "--out", required=True)
    p.add_argument("--overwrite", action="store_true", help="replace a report in --out")
    p.add_argument("--bin", help="directory of ahhs-replay")
    args = p.parse_args(argv)
    if args.episodes < 1 or args.jobs < 1:
        raise report.UsageError("--episodes and --jobs must be at least 1")
    return report_steps(args)
