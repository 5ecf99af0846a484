"""ahhs-report RUN_DIR... and ahhs-report neighbourhood: figures and a Markdown summary for
ahhs-evolve runs, and the mutation neighbourhood of a genome (docs/analysis.md)."""
import json
import math
import os
from collections import OrderedDict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.ticker import MaxNLocator  # noqa: E402

from report_lib import (RHYTHM_BAND, SWING_WINDOW, ReportError, Run, box_figure,  # noqa: E402
                        controller_graph, envelope_argv, filmstrip, find_bin, fitness_figure,
                        gait_motion, median_episode, prepare_out, replay_figures, rule_parts,
                        run_replay, save, stored_post_eval)


def report_runs(args):
    runs = [p if isinstance(p, Run) else Run(p) for p in args.runs]
    prepare_out(args.out, args.overwrite)
    written = []
    groups = OrderedDict()
    for r in runs:
        groups.setdefault(r.label, []).append(r)
    fitness_figure(groups, args.out, written)
    # 75 % of the maximum over all runs of the same setting (scenario and task choices).
    overall = {}
    for r in runs:
        overall[r.setting_label] = max(overall.get(r.setting_label, -math.inf), r.best_overall())
    level = {t: 0.75 * m for t, m in overall.items()}
    best = {l: [r.best_overall() for r in rs] for l, rs in groups.items()}
    speed = {}
    censored = 0
    for l, rs in groups.items():
        speed[l] = []
        for r in rs:
            g = r.first_generation_reaching(level[r.setting_label])
            if g is None:
                g, censored = int(r.generation[-1]) + 1, censored + 1
            speed[l].append(g)
    best_tests = box_figure(groups, best, "best fitness of the run",
                            "Best fitness per configuration, a point per run "
                            "(two-sided Wilcoxon rank-sum, n >= 2)",
                            "box_best", args.out, written)
    speed_tests = box_figure(groups, speed, "generation",
                             "Generation reaching 75 % of its setting's maximum fitness, a point "
                             "per run",
                             "box_speed", args.out, written, integer=True)
    md = ["# AHHS run report", ""]
    md += ["| configuration | runs | best fitness: median | min | max | generation to 75 %: median |",
           "|---|---|---|---|---|---|"]
    for l in groups:
        b, s = best[l], speed[l]
        md.append(f"| {l} | {len(b)} | {np.median(b):.4f} | {min(b):.4f} | {max(b):.4f} | "
                  f"{np.median(s):g} |")
    md += [""] + [f"Maximum fitness over all {t} runs: {m:.4f}; 75 % of it is {level[t]:.4f}."
                  for t, m in overall.items()]
    md += ["Tests compare configurations of the same scenario only (a pendulum at gain 10 with "
           "one at the defaults, too)."]
    if censored:
        md.append(f"{censored} run(s) never reached it and count as their number of generations.")
    for title, tests in (("Best fitness", best_tests), ("Evolution speed", speed_tests)):
        if tests:
            md += ["", f"## {title}: two-sided Wilcoxon rank-sum tests", "",
                   "| A | B | n_A | n_B | U | p |", "|---|---|---|---|---|---|"]
            md += [f"| {a} | {b} | {na} | {nb} | {u:g} | {p:.4g} |" for a, b, na, nb, u, p in tests]
    md += ["", "## Runs", ""] + [f"- `{r.path}`: {r.label}, seed {r.config['seed']}, "
                                 f"{len(r.generation)} generations, best {r.best_overall():.4f}"
                                 + (f" ({r.config['optimizer']})" if "optimizer" in r.config else "")
                                 for r in runs]
    for r in runs:  # MAP-Elites runs (examples/optimizers/map_elites.py) keep an archive
        md += archive_heatmap(r, args.out, written)
    if not args.no_replay:
        bin_dir = find_bin(args)
        first = runs[0]
        trace = os.path.join(args.out, "replay-trace.csv")
        rules = os.path.join(args.out, "replay-rules.csv")
        log = os.path.join(args.out, "replay.lcm")
        body = os.path.join(args.out, "replay-body.csv")
        post = stored_post_eval(first)
        episode = median_episode(post) if post else None
        chosen = (["--seed", str(episode["seed"])] + envelope_argv(post)) if episode else []
        out = run_replay(bin_dir, first.replay_argv() + chosen + [
            "--csv", trace, "--rules-csv", rules, "--log", log, "--body-csv", body])
        written += [trace, rules, log, body]
        info = replay_figures(trace, rules, body, first.scenario_label, args.out, written)
        with open(os.path.join(first.path, "best.json")) as f:
            genome = json.load(f)
        edges = controller_graph(genome, info["parts"], args.out, written,
                                 scenario=first.scenario_label)
        check = [l for l in out.splitlines() if l.startswith("stored fitness")]
        if episode:
            check = [held_out_check(out, episode, post)]
        strip = filmstrip(bin_dir, log, os.path.join(args.out, "best-filmstrip.png"), written)
        md += ["", f"## The best controller of `{first.path}`", "",
               "Replayed with `ahhs-replay` (log: `replay.lcm`): " + (check[0] if check else out.strip()),
               "",
               f"- hormones ever above 0.001: {info['hormones_used']} of {info['hormones']}",
               f"- rules that never trigger: {info['never']} of {info['rules']}; seldom (< 1 % of "
               f"ticks): {info['seldom']}",
               f"- controller graph: {edges} edges (one per rule part that triggered in the replay, "
               "its width by the share of ticks)",
               f"- {strip}"]
        said = [l[len("behaviour: "):] for l in out.splitlines() if l.startswith("behaviour: ")]
        if said:
            md.append(f"- what `ahhs-replay` says the episode did: {said[-1]}")
        if first.scenario_label != "pendulum":
            md += motion_lines(gait_motion(trace, body))
    md += ["", "## Figures", ""] + [f"- `{os.path.basename(p)}`" for p in written
                                    if p.endswith(".png")]
    summary = os.path.join(args.out, "summary.md")
    with open(summary, "w") as f:
        f.write("\n".join(md) + "\n")
    print(f"report written to {args.out}: summary.md and {len(written)} files")


def held_out_check(out, episode, post):
    """The summary's line for a replay of the held-out episode nearest the median; an error when
    the replay does not give the episode's stored fitness bit for bit."""
    last = [l for l in out.splitlines() if l.startswith("fitness: ")]
    got = float(last[-1].split()[1]) if last else None
    if got != float(episode["fitness"]):
        raise ReportError(f"the replay of held-out episode {episode['seed']} gives {got}, the run "
                          f"stored {episode['fitness']!r}: another build or physics?")
    n = len(post["per_episode"])
    return (f"held-out episode {episode['seed']}, the one nearest the median of the best's {n} "
            f"held-out episodes (envelope {post.get('envelope', '?')}): fitness {got:.4f}, the "
            "stored one bit for bit.")


def motion_lines(motion):
    """summary.md's section on how the replayed gait moves (report_lib.gait_motion)."""
    def num(v, fmt):
        return "-" if v is None else format(v, fmt)
    md = ["", "### How it moves", "",
          f"Hinge angles after the first {motion['settle']:g} s, from every tick of the replay. "
          f"The swing is the angle around its running median over {SWING_WINDOW:g} s (a change "
          "of posture moves the mean and standard deviation, not the swing); its rhythm is the "
          "largest peak of the swing's spectrum, and the share is the swing's power within "
          f"{RHYTHM_BAND:g} Hz of it: 1 for a pure swing, about 0.5 for a regular kick, 0.1-0.3 "
          "for an irregular jitter (`-` for a swing under 0.5 degree):", "",
          "| module | mean (deg) | standard deviation | min | max | swing: standard deviation "
          "| rhythm (Hz) | share there |",
          "|---|---|---|---|---|---|---|---|"]
    md += [f"| {h['module']} | {h['mean']:.1f} | {h['sd']:.1f} | {h['min']:.1f} | {h['max']:.1f} | "
           f"{h['swing_sd']:.1f} | {num(h['frequency'], '.2f')} | {num(h['share'], '.2f')} |"
           for h in motion["hinges"]]
    md += ["", "Neighbours (the lag at which they correlate best, within half the first one's "
           "rhythm period, shown where they correlate there at 0.5 or more; positive: the second "
           "follows):", "",
           "| modules | correlation at zero lag | best lag (s) | correlation there |",
           "|---|---|---|---|"]
    md += [f"| {a}-{b} | {num(p['correlation'], '.2f')} | "
           f"{num(p['lag'] if (p['lag_correlation'] or 0) >= 0.5 else None, '+.2f')} | "
           f"{num(p['lag_correlation'], '.2f')} |" for p in motion["neighbours"]
           for a, b in [p["modules"]]]
    x, y = motion["end"]
    md += ["", "The centroid's distance from where it was at the first tick: " +
           ", ".join(f"{d:.2f} m at {t:.1f} s" for t, d in motion["distance"]) +
           f"; at the end x {x:+.2f}, y {y:+.2f} m."]
    return md


def archive_heatmap(run, out_dir, written):
    """A run's MAP-Elites archive (RUN/archive.json) as a heatmap of its cells' fitness over the
    two descriptor values; the Markdown lines that describe it. Nothing when there is none."""
    path = os.path.join(run.path, "archive.json")
    if not os.path.exists(path):
        return []
    try:
        with open(path) as f:
            a = json.load(f)
        dims, ranges, names = a["dims"], a["ranges"], a["descriptor"]
        grid = np.full((dims[1], dims[0]), np.nan)
        for c in a["cells"]:
            grid[c["cell"][1], c["cell"][0]] = c["fitness"]
    except (OSError, ValueError, KeyError, IndexError, TypeError) as e:
        raise ReportError(f"{path}: not a readable archive ({e})")
    fig, ax = plt.subplots(figsize=(6.4, 5.2))
    image = ax.imshow(grid, origin="lower", aspect="auto", cmap="viridis",
                      extent=[ranges[0][0], ranges[0][1], ranges[1][0], ranges[1][1]])
    fig.colorbar(image, ax=ax, label="fitness of the cell's elite")
    ax.set_xlabel(names[0])
    ax.set_ylabel(names[1])
    ax.set_title(f"MAP-Elites archive after generation {a['generation']}: "
                 f"{len(a['cells'])} of {dims[0] * dims[1]} cells (empty: white)")
    name = "archive-" + os.path.basename(os.path.normpath(run.path))
    save(fig, out_dir, name, written)
    best = max(a["cells"], key=lambda c: c["fitness"]) if a["cells"] else None
    md = ["", f"## The archive of `{run.path}`", "",
          f"`{name}.png`: {len(a['cells'])} of {dims[0] * dims[1]} cells filled, "
          f"QD score {a['stats']['qd_score']:.4f}."]
    if best:
        md.append(f"Its best cell {best['cell']} ({names[0]} {best['descriptor'][0]:.3f}, "
                  f"{names[1]} {best['descriptor'][1]:.3f}, fitness {best['fitness']:.4f}) replays "
                  f"with `ahhs-replay {run.path} --generation {best['generation']} --individual "
                  f"{best['individual']}`; so does every cell, with its own generation and "
                  "individual.")
    return md


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
        argv = ["--genome", args.genome, "--scenario", args.scenario, "--docking", args.docking,
                "--modules", str(args.modules), "--duration", str(args.duration),
                "--seed", str(args.seed)]
        if getattr(args, "physics", ""):
            argv += ["--physics", args.physics]
        genome_path = args.genome
    rules = os.path.join(args.out, "rules.csv")
    body = os.path.join(args.out, "body.csv")
    run_replay(bin_dir, argv + ["--mutants", str(args.mutants), "--mutants-csv", csv,
                                "--mutant-seed", str(args.mutant_seed), "--rules-csv", rules,
                                "--body-csv", body])
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
    ax.yaxis.set_major_locator(MaxNLocator(integer=True))
    ax.set_title("Mutation neighbourhood", fontsize=10)
    ax.legend(fontsize=8)
    save(fig, args.out, "neighbourhood", written)
    written += [rules, body]
    ticks = max(1, len(np.atleast_1d(np.genfromtxt(body, delimiter=",", names=True))))
    scenario = "pendulum" if args.scenario == "pendulum" and not os.path.isdir(args.genome) else (
        Run(args.genome).scenario_label if os.path.isdir(args.genome) else f"gait-{args.docking}")
    with open(genome_path) as f:
        controller_graph(json.load(f), rule_parts(rules, ticks), args.out, written,
                         scenario=scenario)
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
