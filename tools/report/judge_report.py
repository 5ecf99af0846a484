"""ahhs-report judge: do a study's robust bests hold when the world changes beyond their envelope?

Every run's best gait genome (the runs of a study export, or directories holding best.json and
post-eval.json, as studies/robust-evidence) is post-evaluated again on the held-out episodes its
run stored (the same seeds and envelope), each time with one thing changed:

- the physics step: a quarter, half and twice the scenario's step h (docs/scenarios.md, "Physics
  step"). A step agrees with half of it when its median is within 10 % and its over-the-wall share
  within 0.15 (the rule of ahhs-report steps);
- a command delay of up to a quarter and up to half a tick (envelope.command-delay);
- a bent start of up to 0.1 and 0.3 rad (envelope.start-hinge).

The scenario's own step is replayed too and must give the stored episodes bit for bit, so every
column is about the same episodes. A median that moves by more than 10 % from the one as evolved
is marked in bold. Replays take minutes per genome, so each genome's results are kept in --cache
(one JSON file per genome, physics and episode count, written whole or not at all); with every
genome in it the report is rebuilt offline in seconds. Writes judged.md (tables and counts, one
set per docking) and judged.csv (one row per genome and condition).
"""
import argparse
import concurrent.futures
import csv
import json
import os
import re
import tempfile

import report_lib as report
from scipy import stats
from step_report import DOCKING_STEP, MEDIAN_TOLERANCE, agrees, bootstrap_interval

CACHE_FORMAT = "ahhs-judged"
CACHE_VERSION = 1
# (name, physics step as a multiple of h, command delay in ticks, start hinge half-width in rad)
CONDITIONS = [("h/4", 0.25, 0.0, 0.0), ("h/2", 0.5, 0.0, 0.0), ("h", 1.0, 0.0, 0.0),
              ("2h", 2.0, 0.0, 0.0), ("delay 0.25", 1.0, 0.25, 0.0),
              ("delay 0.5", 1.0, 0.5, 0.0), ("bent 0.1", 1.0, 0.0, 0.1),
              ("bent 0.3", 1.0, 0.0, 0.3)]


def label_of(root, path):
    """A run's name: its path from the folder above its export (the nearest folder with a
    study.toml or README.md), else from the folder above the root given."""
    top = os.path.abspath(path)
    while top != os.path.dirname(top):
        if any(os.path.isfile(os.path.join(top, f)) for f in ("study.toml", "README.md")):
            return os.path.relpath(path, os.path.dirname(top))
        top = os.path.dirname(top)
    return os.path.relpath(path, os.path.dirname(os.path.abspath(root).rstrip("/")))


class Genome:
    """One run's best: where it is, how to replay it, and its stored held-out episodes."""

    def __init__(self, root, path):
        self.path = path
        self.label = label_of(root, path)
        summary = os.path.join(path, "summary.json")
        if os.path.isfile(summary):  # a run of a study export
            run = report.Run(path, prefer_summary=True)
            if run.config.get("scenario") != "gait":
                raise report.ReportError(f"{path}: not a gait run")
            with open(summary) as f:
                self.post = json.load(f).get("post_eval")
            self.docking, self.physics = run.config["joints"], run.physics
            self.argv = run.replay_argv()
        else:  # best.json and post-eval.json, the docking in the directory's name
            m = re.search(r"gait-(damped|fixed)-", path)
            try:
                with open(os.path.join(path, "best.json")) as f:
                    meta = json.load(f).get("meta") or {}
                with open(os.path.join(path, "post-eval.json")) as f:
                    self.post = json.load(f)
            except (OSError, ValueError) as e:
                raise report.ReportError(f"{path}: not a judged run ({e})")
            if not m:
                raise report.ReportError(f"{path}: no gait-damped- or gait-fixed- in its path")
            self.docking, self.physics = m.group(1), str(meta.get("physics", ""))
            self.argv = ["--genome", os.path.join(path, "best.json"), "--scenario", "gait",
                         "--docking", self.docking]
            self.argv += ["--physics", self.physics] if self.physics else []
        if not self.post or not self.post.get("per_episode"):
            raise report.ReportError(f"{path}: its best has no held-out post-evaluation")
        self.step = DOCKING_STEP[self.docking]

    def cache_name(self, episodes):
        return f"{self.post['genome_hash']}-{self.physics or 'build'}-{episodes}.json"


def natural_key(path):
    """seed-2 before seed-10."""
    return [int(t) if t.isdigit() else t for t in re.split(r"(\d+)", path)]


def find_genomes(roots):
    """Every judged run under the roots, in path order (numbers by value)."""
    found = []
    for root in roots:
        if not os.path.isdir(root):
            raise report.ReportError(f"{root}: no such directory")
        dirs = sorted((d for d, _, files in os.walk(root) if "best.json" in files
                       and ("summary.json" in files or "post-eval.json" in files)), key=natural_key)
        found += [Genome(root, d) for d in dirs]
    if not found:
        raise report.ReportError("no run with a best genome and a post-evaluation under "
                                 + ", ".join(roots))
    return found


def replay_condition(bin_dir, g, episodes, condition, tmp):
    """The genome on its first `episodes` stored held-out episodes under one condition."""
    name, factor, delay, hinge = condition
    out = os.path.join(tmp, re.sub(r"[^a-z0-9.]", "_", name) + ".json")
    widths = dict(g.post.get("envelope_half_widths") or {})
    widths["envelope.command-delay"] = delay
    widths["envelope.start-hinge"] = hinge
    argv = list(g.argv) + ["--post-eval", str(episodes), "--post-eval-json", out,
                           "--overwrite", "--envelope", "none"]
    if factor != 1.0:
        argv += ["--physics-step", repr(g.step * factor)]
    for key, width in sorted(widths.items()):
        if width:
            argv += ["--" + key, repr(float(width))]
    report.run_replay(bin_dir, argv)
    with open(out) as f:
        p = json.load(f)
    stored = g.post["per_episode"][:episodes]
    if [e.get("seed") for e in p["per_episode"]] != [e.get("seed") for e in stored]:
        raise report.ReportError(f"{g.path}: {name}: the replay's held-out seeds are not the "
                                 "stored ones")
    if name == "h" and [e.get("fitness") for e in p["per_episode"]] != \
            [e.get("fitness") for e in stored]:
        raise report.ReportError(f"{g.path}: the best does not replay its stored held-out "
                                 "episodes bit for bit (another physics or build?)")
    return {"step": g.step * factor, "command_delay": delay, "start_hinge": hinge,
            "failed": p["failed"], "median": p["median"],
            "lower_quartile": p["lower_quartile"], "upper_quartile": p["upper_quartile"],
            "min": p["min"], "success_share": p["success_share"],
            "beyond_wall_share": p.get("beyond_wall_share"),
            "fitness": [e.get("fitness") for e in p["per_episode"]]}


def judge(bin_dir, g, episodes, jobs):
    if episodes > len(g.post["per_episode"]):
        raise report.ReportError(f"{g.path}: its run stored {len(g.post['per_episode'])} "
                                 f"held-out episodes, not {episodes}")
    with tempfile.TemporaryDirectory(prefix="ahhs-judge-") as tmp:
        with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
            futures = {c[0]: pool.submit(replay_condition, bin_dir, g, episodes, c, tmp)
                       for c in CONDITIONS}
            results = {name: f.result() for name, f in futures.items()}
    return {"format": CACHE_FORMAT, "version": CACHE_VERSION, "run": g.label,
            "genome_hash": g.post["genome_hash"], "physics": g.physics, "docking": g.docking,
            "episodes": episodes, "conditions": results}


def load_or_judge(args, genomes):
    """Each genome's results: from the cache, or replayed now and written to it."""
    os.makedirs(args.cache, exist_ok=True)
    results, missing = {}, []
    for g in genomes:
        path = os.path.join(args.cache, g.cache_name(args.episodes))
        if os.path.isfile(path):
            with open(path) as f:
                r = json.load(f)
            if r.get("format") != CACHE_FORMAT or r.get("version") != CACHE_VERSION or \
                    set(r.get("conditions", {})) != {c[0] for c in CONDITIONS}:
                raise report.ReportError(f"{path}: not a judged genome of this version; "
                                         "remove it to judge the genome again")
            results[g.path] = r
        else:
            missing.append((g, path))
    if missing:
        bin_dir = report.find_bin(args)
        for i, (g, path) in enumerate(missing):
            print(f"judging {g.label} ({i + 1} of {len(missing)})", flush=True)
            r = judge(bin_dir, g, args.episodes, args.jobs)
            with open(path + ".tmp", "w") as f:
                json.dump(r, f, separators=(",", ":"))
                f.write("\n")
            os.replace(path + ".tmp", path)
            results[g.path] = r
    return results


def fmt(v):
    return "failed" if v is None else f"{v:.3f}"


def cell(c, bold=False):
    median = f"**{fmt(c['median'])}**" if bold else fmt(c["median"])
    return (f"{median} ({fmt(c['lower_quartile'])} / {fmt(c['upper_quartile'])}), "
            f"{c['success_share']:.0%}")


def moved(c, base):
    """Whether a median moved by more than 10 % from the one as evolved."""
    if c["median"] is None or base["median"] is None:
        return True
    return abs(c["median"] - base["median"]) > MEDIAN_TOLERANCE * max(abs(base["median"]), 1e-9)


def higher_at_own_step(r):
    """Whether the median at the scenario's step, the one a genome was evolved at, is above the
    one at half of it."""
    h, half = r["conditions"]["h"]["median"], r["conditions"]["h/2"]["median"]
    return h is not None and half is not None and h > half


def halving_test(step_ok, half_ok):
    """McNemar's exact test, genome by genome, of whether halving the step changes the share of
    genomes that agree: (agree at h only, agree at h/2 only, two-sided p). The genomes that agree
    at both or at neither say nothing about it."""
    h_only = sum(1 for a, b in zip(step_ok, half_ok) if a and not b)
    half_only = sum(1 for a, b in zip(step_ok, half_ok) if b and not a)
    n = h_only + half_only
    p = stats.binomtest(h_only, n, 0.5).pvalue if n else 1.0
    return h_only, half_only, min(1.0, float(p))


def docking_section(docking, rows):
    """judged.md's tables and counts for the genomes of one docking."""
    h = DOCKING_STEP[docking] * 1e3
    ms = {n: f"{h * f:g} ms" for n, f, _, _ in CONDITIONS[:4]}
    n = len(rows)
    c = lambda r, name: r["conditions"][name]
    step_ok = [agrees(c(r, "h"), c(r, "h/2")) for r in rows]
    half_ok = [agrees(c(r, "h/2"), c(r, "h/4")) for r in rows]
    double_ok = [agrees(c(r, "2h"), c(r, "h")) for r in rows]
    differing = [r for r, ok in zip(rows, step_ok) if not ok]
    own = sum(1 for r in differing if higher_at_own_step(r))
    h_only, half_only, p = halving_test(step_ok, half_ok)
    md = [f"## {docking.capitalize()} docking ({n} genomes; the scenario's step h = {ms['h']})", "",
          "### The physics step", "",
          f"| run | {ms['h/4']} | {ms['h/2']} | {ms['h']} | {ms['2h']} | {ms['h']} agrees with "
          f"{ms['h/2']} | {ms['h/2']} with {ms['h/4']} | {ms['2h']} with {ms['h']} |",
          "|---|---|---|---|---|---|---|---|"]
    def verdict(r, step, half, ok):
        ci = bootstrap_interval({"fitnesses": c(r, step)["fitness"]},
                                {"fitnesses": c(r, half)["fitness"]})
        return ("yes" if ok else "**no**") + (f" ({ci[0]:+.3f} to {ci[1]:+.3f})" if ci else "")

    for r, a, b, d in zip(rows, step_ok, half_ok, double_ok):
        md.append(f"| {r['run']} | " + " | ".join(cell(c(r, k)) for k in ("h/4", "h/2", "h", "2h"))
                  + f" | {verdict(r, 'h', 'h/2', a)} | {verdict(r, 'h/2', 'h/4', b)} | "
                  f"{verdict(r, '2h', 'h', d)} |")
    md += ["", f"- {ms['h']} agrees with {ms['h/2']} for **{sum(step_ok)} of {n}**, "
               f"{ms['h/2']} with {ms['h/4']} for **{sum(half_ok)} of {n}**, "
               f"{ms['2h']} with {ms['h']} for {sum(double_ok)} of {n}.",
           f"- Of the {len(differing)} whose {ms['h']} differs from {ms['h/2']}, {own} score "
           f"higher at {ms['h']}, the step they were evolved at.",
           f"- Genome by genome: {h_only} agree at {ms['h']} (with {ms['h/2']}) and not at "
           f"{ms['h/2']} (with {ms['h/4']}), {half_only} the other way; McNemar's exact test "
           f"of whether halving the step changes the share that agrees: p = {p:.3g}."]
    for title, names, what in (
            ("A command delay", ("delay 0.25", "delay 0.5"),
             ("up to a quarter of a tick", "up to half a tick")),
            ("A bent start", ("bent 0.1", "bent 0.3"), ("up to 0.1 rad", "up to 0.3 rad"))):
        kept = [sum(1 for r in rows if not moved(c(r, k), c(r, "h"))) for k in names]
        md += ["", f"### {title}", "",
               f"| run | as evolved | {what[0]} | {what[1]} |", "|---|---|---|---|"]
        for r in rows:
            md.append(f"| {r['run']} | {cell(c(r, 'h'))} | "
                      + " | ".join(cell(c(r, k), moved(c(r, k), c(r, "h"))) for k in names) + " |")
        md += ["", f"- Keep their median within 10 %: **{kept[0]} of {n}** {what[0]}, "
                   f"**{kept[1]} of {n}** {what[1]}."]
    return md


def report_judged(args):
    report.prepare_out(args.out, args.overwrite)
    genomes = find_genomes(args.roots)
    results = load_or_judge(args, genomes)
    rows = [results[g.path] for g in genomes]
    md = ["# How the robust bests hold", "",
          f"{len(rows)} genomes, each post-evaluated again on the first {args.episodes} of its "
          "run's held-out episodes (the same seeds and envelope), with the physics step, a "
          "command delay or a bent start changed (ahhs-report judge; docs/analysis.md). A step "
          "agrees with half of it when its median is within 10 % and its over-the-wall share "
          "within 0.15; in brackets after a step's verdict, the 90 % paired bootstrap interval "
          "of the difference of medians (how much sampling alone could move it); a median in bold "
          "moved by more than 10 % from the one as evolved. Cells: median (quartiles), share of "
          "the episodes over the wall.", ""]
    for docking in ("fixed", "damped"):
        these = [r for r in rows if r["docking"] == docking]
        if these:
            md += docking_section(docking, these) + [""]
    with open(os.path.join(args.out, "judged.md"), "w") as f:
        f.write("\n".join(md))
    with open(os.path.join(args.out, "judged.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["run", "genome_hash", "physics", "docking", "condition", "step",
                    "command_delay", "start_hinge", "episodes", "failed", "median",
                    "lower_quartile", "upper_quartile", "min", "success_share",
                    "beyond_wall_share"])
        for r in rows:
            for name, _, _, _ in CONDITIONS:
                c = r["conditions"][name]
                w.writerow([r["run"], r["genome_hash"], r["physics"], r["docking"], name,
                            c["step"], c["command_delay"], c["start_hinge"], r["episodes"],
                            c["failed"], c["median"], c["lower_quartile"], c["upper_quartile"],
                            c["min"], c["success_share"], c["beyond_wall_share"]])
    print(f"judged {len(rows)} genomes; written to {args.out}: judged.md, judged.csv")
    return 0


def main(argv):
    p = argparse.ArgumentParser(prog="ahhs-report judge", description=__doc__.split("\n")[0])
    p.add_argument("roots", nargs="+", help="study exports, or directories of best.json and "
                                            "post-eval.json (searched below)")
    p.add_argument("--cache", required=True, help="where each genome's results are kept")
    p.add_argument("--episodes", type=int, default=50,
                   help="the first N of each run's stored held-out episodes")
    p.add_argument("--jobs", type=int, default=os.cpu_count() or 1, help="replays at once")
    p.add_argument("-o", "--out", required=True)
    p.add_argument("--overwrite", action="store_true", help="replace a report in --out")
    p.add_argument("--bin", help="directory of ahhs-replay (only when a genome is not cached)")
    args = p.parse_args(argv)
    if args.episodes < 1 or args.jobs < 1:
        raise report.UsageError("--episodes and --jobs must be at least 1")
    return report_judged(args)
