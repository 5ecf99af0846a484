"""The claims of Hamann, Stradner, Schmickl & Crailsheim (ALife 2010) about their runs, as
ahhs-report study judges them on a study of the plan studies/paper-2010.toml (and of
paper-2010-robust.toml): a row per claim, with the paper's figure, ours, and a verdict whose
words claims_lib.VERDICTS defines. A compound statement of the paper is split into its parts;
a comparison says its direction; every verdict names its n. docs/results.md is the report of the
first study."""
import numpy as np

from claims_lib import ALPHA, CLOSE, MIN_RUNS, Claims, fmt, pct

PAPER_FIXED_MAXIMUM = 1.7  # "the theoretical maximum fitness of about 1.7" (fixed docking)
OVER_THE_WALL = 1.0  # "a fitness of above 1 is reached, if the wall is overcome"
FIXED = ("gait-fixed-ahhs1-20", "gait-fixed-ahhs1-80", "gait-fixed-ahhs2-50", "gait-fixed-ahhs2-20")


def label(name):
    return name.split("-", 2)[2].upper() if name.startswith("gait") else \
        name.split("-", 1)[1].upper()


def make_claims(configs, maxima, stat="best"):
    """The paper's claims as rows (claim, paper, ours, verdict), judged on `stat`: "best" (each
    run's best fitness) or "robust" (its robust fitness). Claims that are not about runs'
    fitness (evolution speed, per-genome spread, neighbourhoods, controllers) are judged in the
    "best" pass only."""
    c = Claims(configs, maxima, stat)
    # A study without a task has no claims of it (a configuration whose task is unknown yet
    # could be any).
    tasks = {x.task for x in configs}
    if None in tasks:
        tasks |= {"pendulum", "gait-fixed", "gait-damped"}
    if "pendulum" in tasks:
        pendulum(c)
    if "gait-damped" in tasks:
        damped(c)
    if "gait-fixed" in tasks:
        fixed(c, maxima)
        neighbourhoods(c)
    if tasks & {"gait-fixed", "gait-damped"}:
        controllers(c, configs)
    return c.rows


def pendulum(c, suffix="", setting=""):
    """The pendulum's claims on pendulum-ahhs2-15<suffix> against pendulum-ahhs1-60<suffix>;
    `setting` names a task setting other than the paper's in the claims' text."""
    a, b = "pendulum-ahhs2-15" + suffix, "pendulum-ahhs1-60" + suffix
    where = f"Pendulum, {setting}" if setting else "Pendulum"
    claim = f"{where}: AHHS2-15 is better than AHHS1-60"
    paper = "yes, Wilcoxon p < 0.05 (n = 10 AHHS2, 8 AHHS1)"
    if not c.missing(claim, paper, a, b):
        verdict, p = c.higher(a, b, "AHHS1-60")
        c.add(claim, paper, f"medians {c.median(a):.3f} (AHHS2-15) vs {c.median(b):.3f} "
              f"(AHHS1-60), p = {fmt(p)}", verdict, (a, b))
    claim = f"{where}: evolution speed (runs reaching 75 % of the maximum, and when)"
    paper = "no significant difference"
    if not c.not_fitness(claim, paper) and not c.missing(claim, paper, a, b):
        _, _, p = c.speed_logrank(a, b)
        ours = (c.speed_summary(a, "AHHS2-15") + "; " + c.speed_summary(b, "AHHS1-60") +
                f"; log-rank p = {fmt(p)}")
        verdict = ("not tested: no run reaches it" if p is None else
                   "reproduced" if p >= ALPHA else "differs: significant difference")
        c.add(claim, paper, ours, verdict, (a, b))


def damped(c):
    a, b = "gait-damped-ahhs2-30", "gait-damped-ahhs1-120"
    claim = "Damped gait: high fitness in every setting (each median over the wall, fitness > 1)"
    paper = "yes (best 1.88; above 1 once the wall is overcome)"
    if not c.missing(claim, paper, a, b):
        over = {n: float(np.mean(c.values(n) > OVER_THE_WALL)) for n in (a, b)}
        ours = "; ".join(f"{label(n)}: median {c.median(n):.3f}, {pct(over[n])} of runs over "
                         "the wall" for n in (a, b)) + c.success_note((a, b), label)
        low = [label(n) for n in (a, b) if c.median(n) <= OVER_THE_WALL]
        c.add(claim, paper, ours, "reproduced" if not low else
              "differs: " + " and ".join(low) + " at or before the wall (median <= 1)", (a, b))
    claim = "Damped gait: AHHS2-30 and AHHS1-120 do not differ significantly"
    paper = "yes (a trend: AHHS1 below AHHS2)"
    if not c.missing(claim, paper, a, b):
        verdict, p = c.no_difference(a, b, "AHHS2-30", "AHHS1-120")
        c.add(claim, paper, f"medians {c.median(a):.3f} (AHHS2-30) vs {c.median(b):.3f} "
              f"(AHHS1-120), p = {fmt(p)}" + c.success_note((a, b), label), verdict, (a, b))
    # "The behaviors evolved by AHHS1 show high variance depending on the deterministic chaos":
    # one controller's fitness from episode to episode, not the spread of the runs' bests.
    claim = ("Damped gait: an AHHS1 controller's fitness varies more from episode to episode "
             "(interquartile range of each run's best genome)")
    paper = "yes (AHHS1-120 vs AHHS2-30)"
    if not c.not_fitness(claim, paper) and not c.missing(claim, paper, b, a):
        spread = {n: getattr(c.get(n), "spread", None) for n in (a, b)}
        if any(s is None or len(s) < 2 for s in spread.values()):
            c.add(claim, paper, "no per-genome spread (a best genome's replays failed)", "open")
        else:
            verdict, p = c.higher(b, a, "AHHS2-30", values=spread)
            source = getattr(c.get(a), "spread_source", "episodes")
            c.add(claim, paper, f"median interquartile range {np.median(spread[b]):.3f} "
                  f"(AHHS1-120) vs {np.median(spread[a]):.3f} (AHHS2-30) over {source}, "
                  f"p = {fmt(p)}", verdict, (b, a))


def fixed(c, maxima):
    # Our maximum: the scenario's best fitness, or in the robust pass the highest robust fitness.
    top = maxima.get("gait-fixed")
    if c.stat != "best":
        robust = [c.values(n) for n, x in c.by.items()
                  if x.scenario_label == "gait-fixed" and x.runs and c.values(n) is not None]
        top = max(float(np.max(v)) for v in robust) if robust else None
    ours_max = "our maximum" if c.stat == "best" else "our highest robust fitness"
    for name, share in (("gait-fixed-ahhs2-50", 0.55), ("gait-fixed-ahhs1-80", 0.38)):
        claim = f"Fixed gait: share of {label(name)} runs within 80 % of the maximum"
        paper = f"{share:.0%} (maximum about 1.7)"
        if not c.missing(claim, paper, name):
            ours = c.within(name, 0.8 * PAPER_FIXED_MAXIMUM)
            own = c.within(name, 0.8 * top)
            c.add(claim, paper, f"{ours:.0%} of {len(c.get(name).runs)} runs >= 1.36 (80 % of "
                  f"1.7); {own:.0%} within 80 % of {ours_max} {top:.3f}",
                  "close" if abs(ours - share) <= CLOSE else "differs", (name,))
    low, high = "gait-fixed-ahhs1-20", ("gait-fixed-ahhs1-80", "gait-fixed-ahhs2-50")
    claim = "Fixed gait: AHHS1-20 is below AHHS1-80 and below AHHS2-50, significantly"
    paper = "yes (significant; the direction from the paper's figure)"
    if not c.missing(claim, paper, low, *high):
        parts, ours = [], []
        for h in high:
            verdict, p = c.higher(h, low, "AHHS1-20")
            ours.append(f"{label(h)} {c.median(h):.3f} vs AHHS1-20 {c.median(low):.3f}, "
                        f"p = {fmt(p)}")
            if verdict != "reproduced":
                parts.append(f"against {label(h)}: {verdict}")
        c.add(claim, paper, "medians " + "; ".join(ours) + c.success_note((low, *high), label),
              "reproduced" if not parts else "differs (" + "; ".join(parts) + ")",
              (low, *high))
    claim = "Fixed gait: no other pair of settings differs significantly"
    paper = "yes (significant only AHHS1-20 against AHHS1-80 and AHHS2-50)"
    present = [n for n in FIXED if c.get(n)]
    if not c.missing(claim, paper, *FIXED):
        others = [(x, y) for i, x in enumerate(FIXED) for y in FIXED[i + 1:]
                  if not (x == low and y in high)]
        found = [(x, y, c.test(x, y)) for x, y in others]
        sig = [f"{label(x)} vs {label(y)} (p = {fmt(p)})" for x, y, p in found if p < ALPHA]
        c.add(claim, paper, "; ".join(f"{label(x)} vs {label(y)}: p = {fmt(p)}"
                                      for x, y, p in found),
              "reproduced" if not sig else "differs: " + ", ".join(sig), FIXED)
    bad = "gait-fixed-ahhs2-20"
    claim = "Fixed gait: AHHS2-20 has the lowest best fitness"
    paper = "yes (not tested for significance)"
    if not c.missing(claim, paper, bad):
        medians = {n: c.median(n) for n in present}
        lowest = min(medians, key=medians.get)
        top_run = max(present, key=lambda n: float(np.max(c.values(n))))
        note = (f"; yet AHHS2-20 holds the highest run ({float(np.max(c.values(bad))):.3f})"
                if top_run == bad else "")
        c.add(claim, paper, "medians " + ", ".join(f"{label(n)} {m:.3f}"
                                                   for n, m in medians.items()) + note +
              c.success_note(tuple(present), label),
              "reproduced (in the median)" if lowest == bad else
              f"differs: {label(lowest)} is lowest", tuple(present))
    claim = "Fixed gait: AHHS2-20 evolves slowest (runs reaching 75 % of the maximum, and when)"
    paper = "yes (not tested for significance)"
    if not c.not_fitness(claim, paper) and not c.missing(claim, paper, bad):
        ours, slower = [], []
        for n in present:
            ours.append(c.speed_summary(n, label(n)))
            if n != bad:
                observed, expected, p = c.speed_logrank(bad, n)
                if p is not None and p < ALPHA:
                    slower.append((label(n), observed < expected))
        share = {n: float(np.mean(c.reached(n))) for n in present}
        slowest = min(present, key=lambda n: (share[n], -float(np.median(c.get(n).speed))))
        faster = [x for x, is_slower in slower if is_slower]
        note = ("; log-rank: AHHS2-20 significantly slower than " + ", ".join(faster)
                if faster else "; log-rank: no significant difference to AHHS2-20")
        c.add(claim, paper, "; ".join(ours) + note,
              "reproduced" if slowest == bad else f"differs: {label(slowest)} is slowest",
              tuple(present))


def neighbourhoods(c):
    # Mutation neighbourhood (post-evaluation, fixed docking), from several originals whose
    # robust fitness is nearest the paper's (study_report.neighbourhood_originals).
    for name, lbl, paper in (("gait-fixed-ahhs1-80", "AHHS1", "most below 0.2 (original 0.84)"),
                             ("gait-fixed-ahhs2-50", "AHHS2",
                              "most about as good as the original (0.81)")):
        claim = f"Mutation neighbourhood of a good {lbl} controller (35 single mutants each)"
        if c.get(name) and c.get(name).neighbourhood and c.not_fitness(claim, paper):
            continue
        if not c.missing(claim, paper, name, per_run=False) and c.get(name).neighbourhood:
            n = c.get(name).neighbourhood
            starts = ", ".join(f"{o['original']:.3f}" + (
                "" if o["robust"] is None else f" (robust {o['robust']:.3f})")
                for o in n["originals"])
            ours = (f"originals {starts}; mutants' median {n['median']:.3f}; "
                    f"{pct(n['below_0.2'])} below 0.2, {pct(n['keep_90'])} keep 90 % of "
                    "their original")
            if lbl == "AHHS1":
                verdict = "reproduced" if n["below_0.2"] > 0.5 else "differs"
            else:
                verdict = "reproduced" if (n["keep_90"] or 0) > 0.5 else "differs"
            c.add(claim, paper, ours, f"{verdict} (n = {len(n['originals'])} originals, "
                  f"{n['mutants']} mutants)")


def controllers(c, configs):
    gait = [x for x in configs if x.runs and x.scenario_label.startswith("gait")]
    uses = [u for x in gait for u in x.controllers]
    claim, paper = "Gait: rules that never or seldom trigger", "about one third"
    if c.not_fitness(claim, paper):
        pass
    elif not uses:
        c.add(claim, paper, "not run yet (gait)", "open")
    elif len(uses) < MIN_RUNS:
        c.add(claim, paper, f"too few best genomes so far ({len(uses)})", "open")
    else:
        share = [(u["never"] + u["seldom"]) / u["rules"] for u in uses]
        c.add(claim, paper, f"median {np.median(share):.0%} over {len(uses)} best genomes "
              f"(quartiles {np.percentile(share, 25):.0%} / {np.percentile(share, 75):.0%})",
              ("close" if abs(np.median(share) - 1 / 3) <= CLOSE else "differs") +
              f" (n = {len(uses)} genomes)")
    damped_uses = [u for x in gait if x.scenario_label == "gait-damped" for u in x.controllers]
    claim, paper = "Damped gait: hormones and rules a controller uses", "2-3 of 5 hormones, < 10 rules"
    if c.not_fitness(claim, paper):
        pass
    elif not damped_uses:
        c.add(claim, paper, "not run yet (gait-damped)", "open")
    elif len(damped_uses) < MIN_RUNS:
        c.add(claim, paper, f"too few best genomes so far ({len(damped_uses)})", "open")
    else:
        h = np.median([u["hormones_used"] for u in damped_uses])
        r = np.median([u["active"] for u in damped_uses])
        c.add(claim, paper, f"median {h:g} hormones touched by rules active in >= 1 % of ticks, "
              f"{r:g} such rules ({len(damped_uses)} best genomes)",
              ("reproduced" if h <= 3 and r < 10 else "differs") +
              f" (n = {len(damped_uses)} genomes)")
