#!/usr/bin/python3
"""The paper-2010 study's claim verdicts (studies/paper-2010-claims.py, judged with
tools/report/claims_lib.py) on made-up studies whose answers are known: each claim row must say
reproduced, differs, open or close as the numbers demand, and never give a verdict on fewer than
MIN_RUNS runs. A study finds its claims by its plan's name."""
import os
import sys

sys.path.insert(0, os.path.join(os.environ["AHHS_SOURCE_DIR"], "tools", "report"))
import numpy as np  # noqa: E402
import study_report as sr  # noqa: E402

make_claims = sr.claims_of("paper-2010")
assert make_claims is not None and sr.claims_of("paper-2010-robust") is not None
assert sr.claims_of("no-such-study") is not None  # judged against the paper's claims


class FakeRun:
    def __init__(self, scenario_label, best):
        scenario, _, joints = scenario_label.partition("-")
        self.scenario_label = scenario_label
        self.setting_label = scenario_label
        self.config = {"scenario": scenario, "joints": joints or "damped"}
        self._best = best

    def best_overall(self):
        return self._best


def config(name, bests, speed=None, **extra):
    label = "pendulum" if name.startswith("pendulum") else "-".join(name.split("-")[:2])
    c = sr.Config(name, len(bests), [FakeRun(label, b) for b in bests])
    c.speed = speed or [10] * len(bests)
    for k, v in extra.items():
        setattr(c, k, v)
    return c


def rows(configs, stat="best"):
    maxima = {}
    for c in configs:
        if c.runs:
            maxima[c.scenario_label] = max(maxima.get(c.scenario_label, 0), float(np.max(c.best)))
    return {claim: (ours, verdict)
            for claim, _, ours, verdict in make_claims(configs, maxima, stat)}


rng = np.random.default_rng(1)
SPEED = "Pendulum: evolution speed (runs reaching 75 % of the maximum, and when)"
BETTER = "Pendulum: AHHS2-15 is better than AHHS1-60"
# The paper's pendulum: AHHS2-15 clearly better, same speed. Ten against eight runs without ties:
# the exact rank-sum p, 2 / C(18, 8).
r = rows([config("pendulum-ahhs2-15", list(0.6 + 0.01 * rng.random(10)), [5] * 10),
          config("pendulum-ahhs1-60", list(0.3 + 0.01 * rng.random(8)), [5] * 8)])
assert r[BETTER][1] == "reproduced (n = 10, 8)", r
assert r[BETTER][0].endswith(f"p = {2 / 43758:.3g}"), r[BETTER]
assert r[SPEED][1] == "reproduced (n = 10, 8)", r[SPEED]
assert r[SPEED][0].startswith("10 of 10 AHHS2-15 runs reach it, median generation of those 5"), r
# Ours so far: the opposite, significantly; then the paper's direction without significance.
r = rows([config("pendulum-ahhs2-15", list(0.3 + 0.01 * rng.random(10))),
          config("pendulum-ahhs1-60", list(0.6 + 0.01 * rng.random(10)))])
assert r[BETTER][1] == "differs, reversed: AHHS1-60 is higher (n = 10, 10)", r
r = rows([config("pendulum-ahhs2-15", [0.5, 0.52, 0.3, 0.61, 0.45]),
          config("pendulum-ahhs1-60", [0.49, 0.51, 0.31, 0.6, 0.44])])
assert r[BETTER][1] == "not significant (n = 5, 5)", r
# Speed is a time to an event: a run that never reaches 75 % is censored, not counted as fast
# or slow at its length. All AHHS2-15 runs reach it by generation 20, no AHHS1-60 run does.
a = config("pendulum-ahhs2-15", [0.6] * 6, [10, 12, 14, 16, 18, 20])
b = config("pendulum-ahhs1-60", [0.6] * 6, [200] * 6, reached=[False] * 6)
r = rows([a, b])
assert r[SPEED][1] == "differs: significant difference (n = 6, 6)", r[SPEED]
assert "0 of 6 AHHS1-60 runs reach it;" in r[SPEED][0], r[SPEED]
# Too few runs: no verdict. No runs: not run yet.
r = rows([config("pendulum-ahhs2-15", [0.5, 0.6]), config("pendulum-ahhs1-60", [0.1, 0.2])])
claim = r[BETTER]
assert claim[1] == "open" and "too few complete runs" in claim[0], claim
r = rows([config("pendulum-ahhs2-15", [])])
assert r[BETTER] == ("not run yet (pendulum-ahhs2-15, pendulum-ahhs1-60)", "open"), r
# Fixed docking: 11 of 20 AHHS2-50 runs at 1.4 or more (55 %) against a maximum of 1.75.
r = rows([config("gait-fixed-ahhs2-50", [1.4] * 10 + [1.75] + [0.5] * 9)])
ours, verdict = r["Fixed gait: share of AHHS2-50 runs within 80 % of the maximum"]
assert verdict == "close (n = 20)" and ours.startswith("55% of 20 runs >= 1.36"), ours
# AHHS1-20 significantly below the other two; no other pair differs: reproduced. AHHS2-20 has the
# lowest median but the highest run, and its runs never reach 75 % of the maximum.
LOW = "Fixed gait: AHHS1-20 is below AHHS1-80 and below AHHS2-50, significantly"
OTHERS = "Fixed gait: no other pair of settings differs significantly"
LOWEST = "Fixed gait: AHHS2-20 has the lowest best fitness"
SLOWEST = "Fixed gait: AHHS2-20 evolves slowest (runs reaching 75 % of the maximum, and when)"
high = lambda: list(1.0 + 0.5 * rng.random(10))
low = config("gait-fixed-ahhs1-20", list(0.9 + 0.2 * rng.random(10)), [30] * 10)
fixed = [low, config("gait-fixed-ahhs1-80", high(), [20] * 10),
         config("gait-fixed-ahhs2-50", high(), [25] * 10),
         config("gait-fixed-ahhs2-20", [0.5, 0.6, 0.7, 0.8, 1.6, 2.0], [200] * 6,
                reached=[False] * 5 + [True])]
r = rows(fixed)
assert r[LOW][1] == "reproduced (n = 10, 10, 10)", r[LOW]
assert r[OTHERS][1] == "reproduced (n = 10, 10, 10, 6)", r[OTHERS]
assert r[LOWEST][1] == "reproduced (in the median) (n = 10, 10, 10, 6)", r[LOWEST]
assert r[LOWEST][0].endswith("yet AHHS2-20 holds the highest run (2.000)"), r[LOWEST]
assert r[SLOWEST][1] == "reproduced (n = 10, 10, 10, 6)", r[SLOWEST]
assert "1 of 6 AHHS2-20 runs reach it, median generation of those 200" in r[SLOWEST][0], r
assert "significantly slower than AHHS1-20, AHHS1-80, AHHS2-50" in r[SLOWEST][0], r[SLOWEST]
# Ours: AHHS1-20 above AHHS1-80 (the reverse), level with AHHS2-50.
fixed[0] = config("gait-fixed-ahhs1-20", [2.0 + 0.02 * i for i in range(10)])
fixed[1] = config("gait-fixed-ahhs1-80", list(1.0 + 0.1 * rng.random(10)))
fixed[2] = config("gait-fixed-ahhs2-50", [2.01 + 0.02 * i for i in range(10)])
r = rows(fixed)
assert r[LOW][1].startswith("differs (against AHHS1-80: differs, reversed: AHHS1-20 is higher; "
                            "against AHHS2-50: not significant"), r[LOW]
assert r[OTHERS][1].startswith("differs: ") and "AHHS1-80 vs AHHS2-50 (p = " in r[OTHERS][1], r
assert "AHHS1-80 vs AHHS2-20" not in r[OTHERS][1], r[OTHERS]  # p = 0.31: not named
# Damped: the compound claim in two parts; "high" is over the wall (fitness > 1).
HIGH = "Damped gait: high fitness in every setting (each median over the wall, fitness > 1)"
SAME = "Damped gait: AHHS2-30 and AHHS1-120 do not differ significantly"
VARIES = ("Damped gait: an AHHS1 controller's fitness varies more from episode to episode "
          "(interquartile range of each run's best genome)")
damped = [config("gait-damped-ahhs2-30", list(1.0 + 0.1 * rng.random(10)), spread=[0.05] * 10,
                 spread_source="50 held-out episodes"),
          config("gait-damped-ahhs1-120", list(1.02 + 0.1 * rng.random(10)),
                 spread=list(0.3 + 0.1 * rng.random(10)))]
r = rows(damped)
assert r[HIGH][1] == "reproduced (n = 10, 10)", r[HIGH]
assert r[SAME][1] == "reproduced (n = 10, 10)", r[SAME]
assert r[VARIES][1] == "reproduced (n = 10, 10)", r[VARIES]
assert "over 50 held-out episodes" in r[VARIES][0], r[VARIES]
# Per-genome spreads alike: not significant, whatever the spread of the runs' bests.
damped[1].spread = [0.0455 + 0.001 * i for i in range(10)]
assert rows(damped)[VARIES][1].startswith("not significant"), rows(damped)[VARIES]
damped[1].spread = None
assert rows(damped)[VARIES][1] == "open", rows(damped)[VARIES]
# The robust pass judges the same claims on each run's robust fitness: here the AHHS1 bests are
# knife-edges (high bests, low robust fitness), so the robust verdicts turn round.
bests = lambda lo: list(lo + 0.1 * rng.random(6))
damped = [config("gait-damped-ahhs2-30", bests(0.6), robust=np.array(bests(0.55))),
          config("gait-damped-ahhs1-120", bests(2.5), robust=np.array(bests(0.3)))]
r, rr = rows(damped), rows(damped, "robust")
assert r[SAME][1] == "differs: AHHS1-120 is significantly higher (n = 6, 6)", r[SAME]
assert rr[SAME][1] == "differs: AHHS2-30 is significantly higher (n = 6, 6)", rr[SAME]
assert "medians 0.6" in r[SAME][0] and "vs 2.5" in r[SAME][0], r[SAME]
assert "medians 0.5" in rr[SAME][0] and "vs 0.3" in rr[SAME][0], rr[SAME]
assert r[HIGH][1] == "differs: AHHS2-30 at or before the wall (median <= 1) (n = 6, 6)", r[HIGH]
assert rr[HIGH][1].startswith("differs: AHHS2-30 and AHHS1-120 at or before the wall"), rr[HIGH]
# With post-evaluations (study_report.Config.success), the robust pass also says how many held-out
# episodes got over the wall: a median between two humps moves with sampling, this share does not.
assert "held-out" not in rr[SAME][0], rr[SAME]
damped[0].success = [0.5, 0.0, 0.25, 0.0, 0.0, 0.75]
damped[1].success = [0.0] * 6
rr = rows(damped, "robust")
assert rr[SAME][0].endswith("; held-out episodes over the wall: AHHS2-30 25 % (3 of 6 runs), "
                            "AHHS1-120 0 % (0 of 6 runs)"), rr[SAME]
assert rr[HIGH][0].endswith("AHHS1-120 0 % (0 of 6 runs)"), rr[HIGH]
assert "held-out" not in rows(damped)[SAME][0]  # the best pass has no held-out episodes
damped[1].success = None  # one configuration without post-evaluations: no share at all
assert "held-out" not in rows(damped, "robust")[SAME][0]
pend = [config("pendulum-ahhs2-15", bests(0.3), robust=np.array(bests(0.6))),
        config("pendulum-ahhs1-60", bests(0.6), robust=np.array(bests(0.3)))]
r, rr = rows(pend), rows(pend, "robust")
assert r[BETTER][1] == "differs, reversed: AHHS1-60 is higher (n = 6, 6)", r
assert rr[BETTER][1] == "reproduced (n = 6, 6)", rr
# Evolution speed is not about runs' fitness: judged once, an empty robust row.
assert rr[SPEED] == (None, None)
# A configuration without robust fitness (its replays failed) gives no robust verdict.
pend[0].robust = None
rr = rows(pend, "robust")
assert rr[BETTER][1] == "open", rr
# The robust pass measures "within 80 % of our maximum" against the highest robust fitness.
fixed = [config("gait-fixed-ahhs2-50", [3.0] * 5 + [1.0] * 5, robust=np.array([0.5] * 9 + [0.6])),
         config("gait-fixed-ahhs1-80", [1.0] * 10, robust=np.array([0.3] * 10))]
ours = rows(fixed, "robust")["Fixed gait: share of AHHS2-50 runs within 80 % of the maximum"][0]
assert ours == ("0% of 10 runs >= 1.36 (80 % of 1.7); "
                "100% within 80 % of our highest robust fitness 0.600"), ours
ours = rows(fixed)["Fixed gait: share of AHHS2-50 runs within 80 % of the maximum"][0]
assert ours.endswith("50% within 80 % of our maximum 3.000"), ours
# Every verdict that is not "open" names its n.
names = ("pendulum-ahhs2-15", "pendulum-ahhs1-60", "gait-damped-ahhs2-30", "gait-damped-ahhs1-120",
         "gait-fixed-ahhs1-20", "gait-fixed-ahhs1-80", "gait-fixed-ahhs2-50", "gait-fixed-ahhs2-20")
everything = [config(n, list(0.5 + rng.random(6)), spread=list(rng.random(6))) for n in names]
for claim, (ours, verdict) in rows(everything).items():
    assert verdict is None or verdict == "open" or "(n = " in verdict, (claim, verdict)
# Mutation neighbourhoods from several originals, their mutants pooled; judged once.
NB = "Mutation neighbourhood of a good AHHS1 controller (35 single mutants each)"
nb = {"originals": [{"run": "x/seed-3", "original": 0.84, "robust": 0.79},
                    {"run": "x/seed-1", "original": 0.9, "robust": 0.83}],
      "mutants": 70, "median": 0.15, "below_0.2": 0.6, "keep_90": 0.2}
c80 = config("gait-fixed-ahhs1-80", [1.0] * 6, neighbourhood=nb)
r, rr = rows([c80]), rows([c80], "robust")
assert r[NB] == ("originals 0.840 (robust 0.790), 0.900 (robust 0.830); mutants' median 0.150; "
                 "60 % below 0.2, 20 % keep 90 % of their original",
                 "reproduced (n = 2 originals, 70 mutants)"), r[NB]
assert rr[NB] == (None, None), rr[NB]
# Both passes have the same claims in the same order; merged, six columns.
maxima = {"pendulum": 0.7}
merged = sr.merge_claims(make_claims(pend, maxima), make_claims(pend, maxima, "robust"))
assert all(len(row) == 6 for row in merged), merged
# The claims about the best genomes themselves pool a task's configurations; fewer than MIN_RUNS
# genomes give no verdict, as fewer runs give none.
RULES = "Gait: rules that never or seldom trigger"
USES = "Damped gait: hormones and rules a controller uses"
use = {"never": 10, "seldom": 0, "rules": 30, "hormones_used": 2, "active": 8}
r = rows([config("gait-damped-ahhs2-30", [0.6, 0.6], controllers=[use] * 2)])
assert r[USES] == ("too few best genomes so far (2)", "open"), r[USES]
assert r[RULES] == ("too few best genomes so far (2)", "open"), r[RULES]
r = rows([config("gait-damped-ahhs2-30", [0.6] * 5, controllers=[use] * 5)])
assert r[USES][1] == "reproduced (n = 5 genomes)", r[USES]
assert r[RULES][1] == "close (n = 5 genomes)", r[RULES]

# Whether this build reproduces each run's best: "every" only when all do; a run whose replay
# differs is named; a run with no stored fitness is neither.
class Path:
    def __init__(self, path):
        self.path = path


def replayed(*verdicts):
    c = config("pendulum-ahhs1-60", [0.5] * len(verdicts))
    c.runs = [Path(f"seed-{k + 1}") for k in range(len(verdicts))]
    c.controllers = [{"reproduced": v} for v in verdicts]
    return sr.reproduction([c])


text, differ = replayed(True, True)
assert text.startswith("Every run's best genome replays") and text.endswith("(2 of 2).") and not differ
text, differ = replayed(True, None)
assert text.startswith("1 of 2 runs' best genomes replay") and not differ, text
text, differ = replayed(True, False, None)
assert text.startswith("**1 of 3 runs' best genomes do not replay") and differ == ["seed-2"], text

# The pendulum's choices (studies/pendulum-choices-claims.py): the paper's two pendulum claims per
# setting, then whether the verdict is the same in every setting.
choices = sr.claims_of("pendulum-choices")
assert choices is not make_claims


def choice_rows(configs, stat="best"):
    return {claim: (ours, verdict) for claim, _, ours, verdict in choices(configs, {}, stat)}


ALL_SAME = "Pendulum: the verdict on AHHS2-15 against AHHS1-60 is the same in every setting"
up = lambda: list(0.6 + 0.01 * rng.random(8))
down = lambda: list(0.3 + 0.01 * rng.random(8))
settings = {"": (up, down), "-gain10": (up, down), "-soft": (down, up)}
study = [config(f"pendulum-ahhs{v}{suffix}", make(), [5] * 8)
         for suffix, pair in settings.items() for v, make in zip(("2-15", "1-60"), pair)]
r = choice_rows(study)
assert r["Pendulum, task defaults: AHHS2-15 is better than AHHS1-60"][1] == "reproduced (n = 8, 8)"
assert r["Pendulum, actuator gain 10: AHHS2-15 is better than AHHS1-60"][1] == \
    "reproduced (n = 8, 8)", r
assert r["Pendulum, soft walls: AHHS2-15 is better than AHHS1-60"][1] == \
    "differs, reversed: AHHS1-60 is higher (n = 8, 8)", r
assert "Pendulum, soft walls: evolution speed (runs reaching 75 % of the maximum, and when)" in r
assert r[ALL_SAME] == ("task defaults: reproduced; actuator gain 10: reproduced; soft walls: "
                       "differs, reversed: AHHS1-60 is higher", "depends on the choice"), r[ALL_SAME]
study[5] = config("pendulum-ahhs1-60-soft", down(), [5] * 8)
study[4] = config("pendulum-ahhs2-15-soft", up(), [5] * 8)
assert choice_rows(study)[ALL_SAME][1] == "holds in every setting", choice_rows(study)[ALL_SAME]
assert choice_rows(study, "robust")[ALL_SAME][1] == "open"  # no robust fitness here
assert choice_rows(study[:4])[ALL_SAME] == ("not every setting has a verdict yet", "open")
# A run's setting: its scenario label with the task's choices that are not their defaults.
run = sr.Run.__new__(sr.Run)
run.config = {"scenario": "pendulum", "pendulum": {"actuator_gain": 10.0, "walls": "soft"}}
assert run.setting_label == "pendulum gain 10 soft walls", run.setting_label
run.config = {"scenario": "pendulum", "pendulum": {"actuator_gain": 1.0, "walls": "rigid"}}
assert run.setting_label == "pendulum", run.setting_label
run.config = {"scenario": "gait", "joints": "fixed"}
assert run.setting_label == "gait-fixed", run.setting_label

# A run's held-out successes from its summary.json: the share of its valid episodes that succeeded
# (a failed episode has no fitness and does not count), and the configuration's table cell.
import json  # noqa: E402
import tempfile  # noqa: E402
with tempfile.TemporaryDirectory() as d:
    episodes = [{"fitness": 0.8, "succeeded": False}, {"fitness": 1.4, "succeeded": True},
                {"fitness": None, "succeeded": False}, {"fitness": 0.7, "succeeded": False},
                {"fitness": 1.2, "succeeded": True}]
    with open(os.path.join(d, "summary.json"), "w") as f:
        json.dump({"post_eval": {"envelope": "paper", "per_episode": episodes}}, f)
    run = sr.Run.__new__(sr.Run)
    run.path = d
    post = sr.post_eval_of(run)
    assert post["episodes"] == 4 and post["success_share"] == 0.5 and post["median"] == 1.0, post
    c = config("gait-fixed-ahhs1-80", [1.0] * 3)
    c.runs = [run] * 3
    sr.robust_fitness(c)
    assert c.success == [0.5] * 3 and list(c.robust) == [1.0] * 3, (c.success, c.robust)
    assert sr.success_cell(c) == "50% (3 of 3)", sr.success_cell(c)
    c.success = [0.0, 0.1, 0.0]
    assert sr.success_cell(c) == "3% (1 of 3)", sr.success_cell(c)
    c.success = None
    assert sr.success_cell(c) == "-"

# A study has the claims of its tasks only: a gait-only plan (the robust study) says nothing of the
# pendulum, and its planned damped configurations are "not run yet" before they have runs (their
# task from the study's resolved configs); a configuration whose task is unknown could be any.
gait_only = [config("gait-fixed-ahhs1-80", [0.9]),
             sr.Config("gait-damped-ahhs2-30", 10, [], task="gait-damped"),
             sr.Config("gait-damped-ahhs1-120", 10, [], task="gait-damped")]
r = rows(gait_only)
assert not any(claim.startswith("Pendulum") for claim in r), r
assert r["Damped gait: AHHS2-30 and AHHS1-120 do not differ significantly"] == (
    "not run yet (gait-damped-ahhs2-30, gait-damped-ahhs1-120)", "open"), r
r = rows(gait_only + [sr.Config("pend2", 10, [])])
assert r[BETTER] == ("not run yet (pendulum-ahhs2-15, pendulum-ahhs1-60)", "open"), r
print("study claims: PASS")
