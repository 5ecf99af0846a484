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
    def __init__(self, task, best):
        scenario, _, joints = task.partition("-")
        self.task, self.config = task, {"scenario": scenario, "joints": joints or "damped"}
        self._best = best

    def best_overall(self):
        return self._best


def config(name, bests, speed=None, **extra):
    task = "pendulum" if name.startswith("pendulum") else "-".join(name.split("-")[:2])
    c = sr.Config(name, len(bests), [FakeRun(task, b) for b in bests])
    c.speed = speed or [10] * len(bests)
    for k, v in extra.items():
        setattr(c, k, v)
    return c


def rows(configs, stat="best"):
    maxima = {}
    for c in configs:
        if c.runs:
            maxima[c.task] = max(maxima.get(c.task, 0), float(np.max(c.best)))
    return {claim: (ours, verdict)
            for claim, _, ours, verdict in make_claims(configs, maxima, stat)}


rng = np.random.default_rng(1)
# The paper's pendulum: AHHS2-15 clearly better, same speed.
r = rows([config("pendulum-ahhs2-15", list(0.6 + 0.01 * rng.random(10)), [5] * 10),
          config("pendulum-ahhs1-60", list(0.3 + 0.01 * rng.random(8)), [5] * 8)])
assert r["Pendulum: AHHS2-15 is better than AHHS1-60"][1] == "reproduced", r
assert r["Pendulum: evolution speed (generation reaching 75 % of the maximum)"][1] == "reproduced"
# Ours so far: the opposite.
r = rows([config("pendulum-ahhs2-15", list(0.3 + 0.01 * rng.random(10))),
          config("pendulum-ahhs1-60", list(0.6 + 0.01 * rng.random(10)))])
assert r["Pendulum: AHHS2-15 is better than AHHS1-60"][1] == "opposite: AHHS1-60 is better", r
# Too few runs: no verdict. No runs: not run yet.
r = rows([config("pendulum-ahhs2-15", [0.5, 0.6]), config("pendulum-ahhs1-60", [0.1, 0.2])])
claim = r["Pendulum: AHHS2-15 is better than AHHS1-60"]
assert claim[1] == "open" and "too few complete runs" in claim[0], claim
r = rows([config("pendulum-ahhs2-15", [])])
assert r["Pendulum: AHHS2-15 is better than AHHS1-60"] == (
    "not run yet (pendulum-ahhs2-15, pendulum-ahhs1-60)", "open"), r
# Fixed docking: 11 of 20 AHHS2-50 runs at 1.4 or more (55 %) against a maximum of 1.75.
r = rows([config("gait-fixed-ahhs2-50", [1.4] * 10 + [1.75] + [0.5] * 9)])
ours, verdict = r["Fixed gait: share of AHHS2-50 runs within 80 % of the maximum"]
assert verdict == "close" and ours.startswith("55% of 20 runs >= 1.36"), ours
# AHHS1-20 significantly below the other two, which do not differ: reproduced.
low, high = list(0.2 + 0.01 * rng.random(10)), lambda: list(1.0 + 0.5 * rng.random(10))
r = rows([config("gait-fixed-ahhs1-20", low), config("gait-fixed-ahhs1-80", high()),
          config("gait-fixed-ahhs2-50", high()), config("gait-fixed-ahhs2-20", [0.1] * 6)])
assert r["Fixed gait: AHHS1-20 differs significantly from AHHS1-80 and from AHHS2-50"][1] == \
    "reproduced", r
assert r["Fixed gait: AHHS2-20 performs badly"][1] == "reproduced", r
# Damped: AHHS1 varies more; no significant difference.
r = rows([config("gait-damped-ahhs2-30", list(1.0 + 0.1 * rng.random(10))),
          config("gait-damped-ahhs1-120", list(0.6 + 0.9 * rng.random(10)))])
assert r["Damped gait: AHHS1 runs vary more"][1] == "reproduced", r
# The robust pass judges the same claims on each run's robust fitness: here the AHHS1 bests are
# knife-edges (high bests, low robust fitness), so the robust verdicts turn round.
bests = lambda lo: list(lo + 0.1 * rng.random(6))
damped = [config("gait-damped-ahhs2-30", bests(0.6), robust=np.array(bests(0.55))),
          config("gait-damped-ahhs1-120", bests(2.5), robust=np.array(bests(0.3)))]
r, rr = rows(damped), rows(damped, "robust")
claim = "Damped gait: high fitness in every setting, no significant difference"
assert r[claim][1] == rr[claim][1] == "differs: significant difference", (r, rr)
assert "medians 0.6" in r[claim][0] and "vs 2.5" in r[claim][0], r[claim]
assert "medians 0.5" in rr[claim][0] and "vs 0.3" in rr[claim][0], rr[claim]
pend = [config("pendulum-ahhs2-15", bests(0.3), robust=np.array(bests(0.6))),
        config("pendulum-ahhs1-60", bests(0.6), robust=np.array(bests(0.3)))]
r, rr = rows(pend), rows(pend, "robust")
assert r["Pendulum: AHHS2-15 is better than AHHS1-60"][1] == "opposite: AHHS1-60 is better", r
assert rr["Pendulum: AHHS2-15 is better than AHHS1-60"][1] == "reproduced", rr
# Evolution speed is not about runs' fitness: judged once, an empty robust row.
assert rr["Pendulum: evolution speed (generation reaching 75 % of the maximum)"] == (None, None)
# A configuration without robust fitness (its replays failed) gives no robust verdict.
pend[0].robust = None
rr = rows(pend, "robust")
assert rr["Pendulum: AHHS2-15 is better than AHHS1-60"][1] == "open", rr
# The robust pass measures "within 80 % of our maximum" against the highest robust fitness.
fixed = [config("gait-fixed-ahhs2-50", [3.0] * 5 + [1.0] * 5, robust=np.array([0.5] * 9 + [0.6])),
         config("gait-fixed-ahhs1-80", [1.0] * 10, robust=np.array([0.3] * 10))]
ours = rows(fixed, "robust")["Fixed gait: share of AHHS2-50 runs within 80 % of the maximum"][0]
assert ours == ("0% of 10 runs >= 1.36 (80 % of 1.7); "
                "100% within 80 % of our highest robust fitness 0.600"), ours
ours = rows(fixed)["Fixed gait: share of AHHS2-50 runs within 80 % of the maximum"][0]
assert ours.endswith("50% within 80 % of our maximum 3.000"), ours
# Both passes have the same claims in the same order; merged, six columns.
maxima = {"pendulum": 0.7}
merged = sr.merge_claims(make_claims(pend, maxima), make_claims(pend, maxima, "robust"))
assert all(len(row) == 6 for row in merged), merged
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
print("study claims: PASS")
