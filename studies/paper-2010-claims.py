"""The claims of Hamann, Stradner, Schmickl & Crailsheim (ALife 2010) about their runs, as
ahhs-report study judges them on a study of the plan studies/paper-2010.toml (and of
paper-2010-robust.toml): a row per claim, with the paper's figure, ours, and a verdict
("reproduced", "close", "differs", "open"). docs/results.md is the report of the first study."""
import numpy as np

from claims_lib import Claims, fmt, pct

PAPER_FIXED_MAXIMUM = 1.7  # "the theoretical maximum fitness of about 1.7" (fixed docking)


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
