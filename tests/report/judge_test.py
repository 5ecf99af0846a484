#!/usr/bin/python3
"""ahhs-report judge on made-up judgments whose verdicts are known: a step agrees with half of it
by the rule of ahhs-report steps, a median more than 10 % from the one as evolved is bold, the
counts say so, a genome that differs and scores higher at the evolved step than at half of it is
counted, and so are the genomes that agree at one step and not at the other (McNemar's exact
test, by hand); with every genome in the cache
nothing is replayed (no ahhs-replay needed); a damaged cache entry, a run without a
post-evaluation and a missing directory are one line and exit 1, nothing half-written."""
import copy
import json
import os
import shutil
import subprocess
import sys
import tempfile

SOURCE = os.environ["AHHS_SOURCE_DIR"]
sys.path.insert(0, os.path.join(SOURCE, "tools", "report"))
import judge_report as jr  # noqa: E402

RUN = os.path.join(SOURCE, "studies", "paper-2010-robust", "gait-fixed-ahhs2-20", "seed-4")


def run(*args):
    env = dict(os.environ)
    env.pop("AHHS_BIN", None)
    r = subprocess.run([sys.executable, os.path.join(SOURCE, "tools", "report", "ahhs_report.py"),
                        "judge", *args], capture_output=True, text=True, env=env)
    return r.returncode, r.stdout + r.stderr


def dist(median, share=0.0):
    return {"step": 0.0125, "command_delay": 0.0, "start_hinge": 0.0, "failed": 0,
            "median": median, "lower_quartile": median - 0.01, "upper_quartile": median + 0.01,
            "min": median - 0.1, "success_share": share, "beyond_wall_share": 0.0,
            "fitness": [median]}


def judged(run_label, genome_hash, medians, shares=None):
    names = [c[0] for c in jr.CONDITIONS]
    shares = shares or {}
    return {"format": "ahhs-judged", "version": 1, "run": run_label, "genome_hash": genome_hash,
            "physics": "2026-12-05", "docking": "fixed", "episodes": 1,
            "conditions": {n: dist(m, shares.get(n, 0.0)) for n, m in zip(names, medians)}}


with tempfile.TemporaryDirectory() as tmp:
    # Two exported runs (copies of one, told apart by their genome hash).
    export = os.path.join(tmp, "E")
    hashes = {"seed-1": "aaaaaaaaaaaaaaaa", "seed-2": "bbbbbbbbbbbbbbbb"}
    for seed, h in hashes.items():
        d = os.path.join(export, "gait-fixed-ahhs2-20", seed)
        os.makedirs(d)
        for f in ("best.json", "generations.csv"):
            shutil.copy(os.path.join(RUN, f), d)
        with open(os.path.join(RUN, "summary.json")) as f:
            s = json.load(f)
        s["post_eval"]["genome_hash"] = h
        with open(os.path.join(d, "summary.json"), "w") as f:
            json.dump(s, f)
    with open(os.path.join(export, "study.toml"), "w") as f:
        f.write('name = "judge-fixture"\n')
    cache = os.path.join(tmp, "cache")
    os.makedirs(cache)
    # h/4, h/2, h, 2h, delay 0.25, delay 0.5, bent 0.1, bent 0.3 (one episode each, so each
    # bootstrap interval of a difference of medians is the difference itself)
    # seed-1: h is 9.9 % above h/2 (agrees), h/2 10.3 % above h/4 (differs), 2h agrees; the
    # delays move it by 8.3 % and 11.7 % (bold), the bent starts not at all.
    one = judged("E/gait-fixed-ahhs2-20/seed-1", hashes["seed-1"],
                 [0.495, 0.546, 0.6, 0.59, 0.55, 0.53, 0.6, 0.6])
    # seed-2: the medians agree everywhere, but h gets over the wall in 0.16 more of its
    # episodes than h/2: differs, and its median at h (0.70) is above the one at h/2 (0.69).
    two = judged("E/gait-fixed-ahhs2-20/seed-2", hashes["seed-2"],
                 [0.69, 0.69, 0.70, 0.69, 0.70, 0.70, 0.70, 0.50],
                 {"h": 0.2, "h/2": 0.04, "2h": 0.2})
    for seed, r in (("seed-1", one), ("seed-2", two)):
        with open(os.path.join(cache, f"{hashes[seed]}-2026-12-05-1.json"), "w") as f:
            json.dump(r, f)

    out = os.path.join(tmp, "out")
    code, text = run(export, "--cache", cache, "--episodes", "1", "-o", out)
    assert code == 0, text
    assert "judging" not in text, text  # all cached: nothing replayed, no ahhs-replay needed
    md = open(os.path.join(out, "judged.md")).read()
    assert "## Fixed docking (2 genomes; the scenario's step h = 12.5 ms)" in md, md
    assert ("| E/gait-fixed-ahhs2-20/seed-1 | 0.495 (0.485 / 0.505), 0% | 0.546 (0.536 / 0.556), "
            "0% | 0.600 (0.590 / 0.610), 0% | 0.590 (0.580 / 0.600), 0% | yes (+0.054 to +0.054) | "
            "**no** (+0.051 to +0.051) | yes (-0.010 to -0.010) |") \
        in md, md
    assert "| E/gait-fixed-ahhs2-20/seed-2 | 0.690 (0.680 / 0.700), 0% | 0.690 (0.680 / 0.700), " \
        "4% | 0.700 (0.690 / 0.710), 20% | 0.690 (0.680 / 0.700), 20% | **no** (+0.010 to " \
        "+0.010) | yes (+0.000 to +0.000) | yes (-0.010 to -0.010) |" \
        in md, md
    assert ("- 12.5 ms agrees with 6.25 ms for **1 of 2**, 6.25 ms with 3.125 ms for **1 of 2**, "
            "25 ms with 12.5 ms for 2 of 2.") in md, md
    assert ("- Of the 1 whose 12.5 ms differs from 6.25 ms, 1 score higher at 12.5 ms, the step "
            "they were evolved at.") in md, md
    # seed-1 agrees at h only, seed-2 at h/2 only: one discordant pair each way, p = 1.
    assert ("- Genome by genome: 1 agree at 12.5 ms (with 6.25 ms) and not at 6.25 ms (with "
            "3.125 ms), 1 the other way; McNemar's exact test of whether halving the step "
            "changes the share that agrees: p = 1.") in md, md
    # By hand: 0 against 6 discordant genomes, p = 2 / 2^6 = 0.03125; none discordant, p = 1.
    assert jr.halving_test([False] * 6 + [True] * 3, [True] * 9) == (0, 6, 0.03125)
    assert jr.halving_test([True, False], [True, False]) == (0, 0, 1.0)
    assert jr.halving_test([True] * 2 + [False], [False] * 2 + [True])[2] == 1.0
    # Delay: seed-1 at a quarter of a tick moved 8.3 % (kept), at half 11.7 % (bold).
    assert "| E/gait-fixed-ahhs2-20/seed-1 | 0.600 (0.590 / 0.610), 0% | 0.550 (0.540 / 0.560), " \
        "0% | **0.530** (0.520 / 0.540), 0% |" in md, md
    assert "- Keep their median within 10 %: **2 of 2** up to a quarter of a tick, **1 of 2** up " \
        "to half a tick." in md, md
    # Bent: seed-2 at 0.3 rad falls from 0.70 to 0.50.
    assert "| E/gait-fixed-ahhs2-20/seed-2 | 0.700 (0.690 / 0.710), 20% | 0.700 (0.690 / 0.710), " \
        "0% | **0.500** (0.490 / 0.510), 0% |" in md, md
    assert "- Keep their median within 10 %: **2 of 2** up to 0.1 rad, **1 of 2** up to 0.3 rad." \
        in md, md
    assert "Damped docking" not in md, md
    rows = open(os.path.join(out, "judged.csv")).read().splitlines()
    assert len(rows) == 1 + 2 * len(jr.CONDITIONS), rows
    assert rows[1].startswith(
        "E/gait-fixed-ahhs2-20/seed-1,aaaaaaaaaaaaaaaa,2026-12-05,fixed,h/4,"), rows[1]

    # Runs in the order of their seeds' values.
    assert sorted(["E/x/seed-10", "E/x/seed-2", "E/x/seed-1-median", "E/x/seed-1"],
                  key=jr.natural_key) == ["E/x/seed-1", "E/x/seed-1-median", "E/x/seed-2",
                                          "E/x/seed-10"]
    # higher_at_own_step: the median at h above the one at h/2; a tie or a failed step is not.
    assert jr.higher_at_own_step(two) and jr.higher_at_own_step(one)
    lower = copy.deepcopy(two)
    lower["conditions"]["h/2"]["median"] = 0.71
    assert not jr.higher_at_own_step(lower)
    tie = copy.deepcopy(two)
    tie["conditions"]["h/2"]["median"] = 0.70
    assert not jr.higher_at_own_step(tie)
    failed = copy.deepcopy(two)
    failed["conditions"]["h/2"]["median"] = None
    assert not jr.higher_at_own_step(failed)

    # Errors: one line, exit 1, no report written.
    def fails(args, message):
        target = os.path.join(tmp, "bad")
        code, text = run(*args, "-o", target)
        assert code == 1 and message in text and "Traceback" not in text \
            and len(text.strip().splitlines()) == 1, (code, text)
        assert not os.path.exists(os.path.join(target, "judged.md")), text

    fails([os.path.join(tmp, "nowhere"), "--cache", cache], "nowhere: no such directory")
    # A genome not in the cache needs ahhs-replay.
    fails([export, "--cache", cache, "--episodes", "2"], "cannot find ahhs-replay")
    bad = os.path.join(tmp, "badcache")
    shutil.copytree(cache, bad)
    with open(os.path.join(bad, f"{hashes['seed-1']}-2026-12-05-1.json"), "w") as f:
        json.dump({"format": "ahhs-judged", "version": 1, "conditions": {}}, f)
    fails([export, "--cache", bad, "--episodes", "1"], "not a judged genome of this version")
    with open(os.path.join(export, "gait-fixed-ahhs2-20", "seed-2", "summary.json")) as f:
        s = json.load(f)
    del s["post_eval"]
    with open(os.path.join(export, "gait-fixed-ahhs2-20", "seed-2", "summary.json"), "w") as f:
        json.dump(s, f)
    fails([export, "--cache", cache, "--episodes", "1"], "has no held-out post-evaluation")
print("PASS")
