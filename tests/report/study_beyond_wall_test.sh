#!/usr/bin/env bash
# ahhs-study report counts the held-out episodes that end wholly beyond the wall, for exports made
# before post-evaluations counted them too: it post-evaluates the best again on the same held-out
# episodes and takes the count only when every stored fitness is reproduced bit for bit. The
# fixture is the robust study's fixed AHHS1-80 seed-2 export cut to its first two held-out
# episodes: short of the wall, then all ten module halves beyond it at fitness 0.838
# (tests/episode/post_eval_test.sh).
bin=${1:?usage: study_beyond_wall_test.sh BIN_DIR}
source "${AHHS_SOURCE_DIR:?}/tests/lib.sh"
ahhs_scratch  # every command runs in the foreground: nothing to kill
cd "$tmp"
run=$AHHS_SOURCE_DIR/studies/paper-2010-robust/gait-fixed-ahhs1-80/seed-2
mkdir -p E/configs
for c in a b; do cp "$AHHS_SOURCE_DIR/studies/paper-2010-robust/configs/gait-fixed-ahhs1-80.json" E/configs/$c.json; done
cat >E/study.toml <<'EOF'
name = "beyond-wall-fixture"
[[config]]
name = "a"
preset = "a.toml"
seeds = 1
[[config]]
name = "b"
preset = "b.toml"
seeds = 2
EOF
# a/seed-1: counted again; b/seed-1: counted by its post-evaluation; b/seed-2: a stored fitness one
# part in 1e12 off, so no count for b.
for d in a/seed-1 b/seed-1 b/seed-2; do mkdir -p E/$d && cp "$run"/{best.json,generations.csv} E/$d/; done
python3 - "$run/summary.json" E <<'PY' || fail "fixture"
import json, sys
s = json.load(open(sys.argv[1]))
p = s["post_eval"]
p["per_episode"] = p["per_episode"][:2]
p["episodes"] = 2
assert "beyond_wall_share" not in p, p.keys()
json.dump(s, open(sys.argv[2] + "/a/seed-1/summary.json", "w"))
p["beyond_wall_share"] = 0.25
json.dump(s, open(sys.argv[2] + "/b/seed-1/summary.json", "w"))
del p["beyond_wall_share"]
p["per_episode"][1]["fitness"] *= 1 + 1e-12
json.dump(s, open(sys.argv[2] + "/b/seed-2/summary.json", "w"))
PY
"$bin/ahhs-study" report E -o R --no-replay >out 2>&1 || fail "report: $(cat out)"
grep -q "warning: post-evaluations this build does not replay bit for bit: 1 (results.md)" out ||
  fail "no warning: $(cat out)"
grep -q "^Every run's best genome replays to its stored fitness bit for bit with this build (3 of 3). Post-evaluations made before episodes wholly beyond the wall were counted: 1. " R/results.md ||
  fail "results.md: $(head -8 R/results.md)"
grep -q "\*\*Post-evaluations this build does not replay bit for bit: 1\*\* (E/b/seed-2)" R/results.md ||
  fail "results.md names the run: $(head -8 R/results.md)"
grep -q "^| a | 1 of 1 | .* | 0% (0 of 1) | 50% (1 of 1) | " R/results.md || fail "row a: $(grep '^| a ' R/results.md)"
grep -q "^| b | 2 of 2 | .* | 0% (0 of 2) | - | " R/results.md || fail "row b: $(grep '^| b ' R/results.md)"
python3 - R/results.json <<'PY' || fail "results.json: $(cat R/results.json)"
import json, sys
d = json.load(open(sys.argv[1]))
a, b = d["configs"]["a"], d["configs"]["b"]
assert a["beyond_wall"] == [0.5] and a["beyond_wall_source"] == ["replayed"], a
assert b["beyond_wall"] is None, b
assert b["beyond_wall_source"][0] == "stored", b
assert "does not replay" in b["beyond_wall_source"][1], b
assert d["post_eval_differs"] == ["E/b/seed-2"], d["post_eval_differs"]
PY
echo "PASS"
