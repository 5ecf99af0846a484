#!/usr/bin/env python3
"""studies/search-comparison.py report counts a gait best's held-out episodes that end wholly
beyond the wall: from its post-evaluation when that counted them, else by post-evaluating the best
again on the same episodes, taken only when every seed and fitness is reproduced bit for bit. The
fixture is the robust study's fixed AHHS1-80 seed-2 export cut to its first two held-out episodes:
short of the wall, then all ten module halves beyond it (tests/report/study_beyond_wall_test.sh).
Usage: search_comparison_beyond_wall_test.py BIN_DIR"""
import argparse
import copy
import importlib.util
import json
import os
import sys
import tempfile

source = os.environ["AHHS_SOURCE_DIR"]
bin_dir = sys.argv[1]
spec = importlib.util.spec_from_file_location(
    "search_comparison", os.path.join(source, "studies", "search-comparison.py"))
sc = importlib.util.module_from_spec(spec)
spec.loader.exec_module(sc)
setting = sc.SETTINGS["gait-fixed"]
run = os.path.join(source, "studies", "paper-2010-robust", "gait-fixed-ahhs1-80", "seed-2")
genome = os.path.join(run, "best.json")
with open(os.path.join(run, "summary.json")) as f:
    evaluation = json.load(f)["post_eval"]
evaluation["per_episode"] = evaluation["per_episode"][:2]
assert "beyond_wall_share" not in evaluation, evaluation.keys()


def held_out(out, stored):
    args = argparse.Namespace(out=out, setting="gait-fixed", bin=bin_dir)
    return sc.held_out(args, setting, run, 2, "ga", stored)


with tempfile.TemporaryDirectory() as tmp:
    # Stored: taken as it is, nothing replayed.
    stored = dict(evaluation, beyond_wall_share=0.25)
    assert held_out(os.path.join(tmp, "stored"), stored)["beyond_wall_share"] == 0.25
    assert not os.path.exists(os.path.join(tmp, "stored")), "a stored count must not be replayed"

    # Not stored: replayed on the same two episodes, and kept (no .tmp left behind).
    out = os.path.join(tmp, "replayed")
    kept = os.path.join(out, "gait-fixed", "beyond-wall")
    assert held_out(out, evaluation)["beyond_wall_share"] == 0.5
    assert sorted(os.listdir(kept)) == ["ga-seed-2.json"], os.listdir(kept)
    assert held_out(out, evaluation)["beyond_wall_share"] == 0.5  # from what was kept

    # A stored fitness one part in 1e12 off: refused, naming the genome.
    off = copy.deepcopy(evaluation)
    off["per_episode"][1]["fitness"] *= 1 + 1e-12
    try:
        held_out(out, off)
        raise AssertionError("a post-evaluation that does not replay was counted")
    except SystemExit as e:
        assert "does not replay bit for bit" in str(e) and genome in str(e), e
print("PASS")
