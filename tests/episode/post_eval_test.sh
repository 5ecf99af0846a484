#!/usr/bin/env bash
# Held-out post-evaluation (ahhs-replay --post-eval, docs/evolution.md): a knife-edge, the first
# study's damped AHHS1-120 seed-1 best (2.736 on its own episode; the fixture is a copy), scores
# far lower on held-out episodes under the paper's envelope; a gait that crosses the wall is
# counted as wholly beyond it whatever its fitness; bad envelope options are usage errors. (The draws' determinism: tests/sim/envelope_test.cc.)
bin=${1:?usage: post_eval_test.sh BIN_DIR}
source "${AHHS_SOURCE_DIR:?}/tests/lib.sh"
ahhs_scratch  # every command runs in the foreground: nothing to kill
cd "$tmp"
knife=$AHHS_SOURCE_DIR/tests/episode/data/knife-edge-damped-ahhs1-120.json
replay=("$bin/ahhs-replay" --genome "$knife" --scenario gait --docking damped)
"${replay[@]}" --post-eval 3 >a.out 2>&1 || fail "post-evaluation: $(cat a.out)"
grep -q "stored fitness 2.7359187058763337: reproduced exactly" a.out || fail "own episode: $(cat a.out)"
line=$(grep "^post-evaluation on 3 held-out episodes (envelope paper): median" a.out) ||
  fail "no post-evaluation line: $(cat a.out)"
median=$(sed -n 's/.*median \([0-9.e+-]*\),.*/\1/p' <<<"$line")
awk -v m="$median" 'BEGIN { exit !(m < 0.5 * 2.7359187058763337) }' ||
  fail "a knife-edge keeps its fitness held out? $line"
grep -q "over the wall (fitness > 1) in 0 %" <<<"$line" || fail "share over the wall: $line"
echo "$line"
# Crossing the wall is not scoring over 1: the robust study's fixed AHHS1-80 seed-2 best ends its
# second held-out episode with all ten module halves beyond the wall at fitness 0.838, its first
# short of the wall; both are in post-eval.json.
crosser=$AHHS_SOURCE_DIR/studies/paper-2010-robust/gait-fixed-ahhs1-80/seed-2/best.json
"$bin/ahhs-replay" --genome "$crosser" --post-eval 2 --post-eval-json pe.json >b.out 2>&1 ||
  fail "post-evaluation of the crosser: $(cat b.out)"
grep -q "over the wall (fitness > 1) in 0 %, wholly beyond it at the end in 50 %" b.out ||
  fail "wholly beyond the wall: $(cat b.out)"
python3 - pe.json <<'PY' || fail "post-eval.json of the crosser: $(cat pe.json)"
import json, sys
d = json.load(open(sys.argv[1]))
assert d["beyond_wall_share"] == 0.5 and d["success_share"] == 0, d
e = d["per_episode"]
assert [x["halves_over_wall"] for x in e] == [0, 10] and e[1]["fitness"] == 0.8384751620859672, e
PY
# Under an envelope the episode itself changes, and says so.
"${replay[@]}" --envelope paper --duration 5 >c.out 2>&1 || fail "--envelope paper: $(cat c.out)"
grep -q "in the changed physics" c.out || fail "an enveloped replay compared as if unchanged: $(cat c.out)"
# Usage errors: exit 2, one line.
for bad in "--envelope loud" "--envelope.friction 0.7" "--post-eval 0" "--envelope.start-offset 0.2"; do
  "${replay[@]}" $bad >bad.out 2>&1
  code=$?
  [[ $code == 2 && $(wc -l <bad.out) == 1 ]] || fail "$bad: exit $code ($(cat bad.out))"
done
grep -q "envelope.start-offset: at most 0.1 m" bad.out || fail "the bad key named: $(cat bad.out)"
echo "post-evaluation: ok"
