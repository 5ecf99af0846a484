#!/usr/bin/env bash
# ahhs-evaluate, the ask/tell evaluation service, end to end inside a private network namespace:
# its hello line; answers whose every trial ahhs-launch reproduces bit for bit (genome documents
# and vectors, trials under an envelope); one error line per bad request, the service going on;
# the same request, the same answer; external workers only; the end of input ends it cleanly; a
# recorded run is validated and post-evaluated when its input ends, as ahhs-evolve does.
bin=${1:?usage: evaluate_test.sh BIN_DIR}
source "${AHHS_SOURCE_DIR:?}/tests/lib.sh"
ahhs_netns "$0" "$@"
ahhs_scratch 'ahhs-evaluate|ahhs-worker'
url="udpm://239.255.42.61:7752?ttl=0&recv_buf_size=4194304"
S="$bin/ahhs-evaluate"
scenario="--scenario gait --docking fixed --duration 4"
"$bin/ahhs-genome" random --variant ahhs2 --hormones 5 --rules 30 --sensors 4 --actuators 1 --seed 3 >$tmp/g.json
python3 - $tmp/g.json >$tmp/requests <<'PY'
import json, sys
g = json.load(open(sys.argv[1]))
ask = lambda **k: print(json.dumps(dict(v=2, **k)))
ask(id="doc", seed=42, genomes=[g])
print("not json")
print(json.dumps({"v": 1, "id": 7, "genomes": [g]}))
ask(id="vec", seed="18446744073709551615", genomes=[{"vector": [0.5] * (15 + 13 * 30)}, g])
ask(id="short", genomes=[{"vector": [0.5] * 3}])
ask(id="neg", seed=-1, genomes=[g])
ask(id="key", genomes=[g], trails=3)
ask(id="doc", seed=42, genomes=[g])
ask(id="auto1", genomes=[g])
ask(id="auto2", genomes=[g])
PY
echo "== 1. answers, errors, determinism"
$S $scenario --trials 2 --envelope paper --workers 2 --lcm-url "$url" <$tmp/requests >$tmp/out 2>$tmp/err ||
  fail "service: $(cat $tmp/err)"
pgrep -g "$pg" -f "$bin/ahhs-worker" >/dev/null && fail "local workers outlived the service"
python3 - $tmp/out >$tmp/launches <<'PY' || fail "answers: $(cat $tmp/out)"
import json, sys
lines = [json.loads(l) for l in open(sys.argv[1])]
hello, answers = lines[0], lines[1:]
assert hello["v"] == 2 and hello["service"] == "ahhs-evaluate", hello
assert hello["descriptor"] == ["end_x", "end_y"], hello
assert hello["scenario"] == "gait" and hello["joints"] == "fixed" and hello["trials"] == 2, hello
assert hello["vector_size"] == 405 and hello["envelope"]["envelope.friction"] == 0.05, hello
assert len(answers) == 10, answers
by = {}
for a in answers:
    assert a["v"] == 2
    by.setdefault(a["id"], []).append(a)
doc = by["doc"][0]
assert doc["seed"] == 42 and len(doc["results"]) == 1
r = doc["results"][0]
assert len(r["trials"]) == 2 and r["fitness"] == (r["trials"][0]["fitness"] + r["trials"][1]["fitness"]) / 2, r
d = [t["descriptor"] for t in r["trials"]]
assert r["descriptor"] == [(d[0][0] + d[1][0]) / 2, (d[0][1] + d[1][1]) / 2], r
assert by["doc"][1] == doc, "the same request, another answer"
assert answers[1]["id"] is None and "not a JSON line" in answers[1]["error"], answers[1]
assert "protocol version" in by[7][0]["error"]
assert "genomes[0]: a vector of 3 values for a genome of 405" in by["short"][0]["error"], by["short"]
assert "seed" in by["neg"][0]["error"] and "unknown key 'trails'" in by["key"][0]["error"]
vec = by["vec"][0]
assert vec["seed"] == 18446744073709551615 and len(vec["results"]) == 2
assert vec["results"][1]["genome_hash"] == doc["results"][0]["genome_hash"]
a1, a2 = by["auto1"][0], by["auto2"][0]
assert a1["seed"] != a2["seed"], "requests without a seed got the same one"
# Every trial, for ahhs-launch to replay: genome, seed, fitness, descriptor.
for a, g in ((doc, 0), (vec, 0)):
    for t in a["results"][g]["trials"]:
        print(a["id"], t["seed"], repr(t["fitness"]), repr(t["descriptor"][0]), repr(t["descriptor"][1]))
PY
echo "== 2. every trial is what ahhs-launch gives"
"$bin/ahhs-genome" from-vector - >$tmp/vec.json <<<"{\"format\": \"ahhs-genome-vector\", \"version\": 1, \"shape\": {\"variant\": \"ahhs2\", \"hormones\": 5, \"rules\": 30, \"sensors\": 4, \"actuators\": 1}, \"x\": $(python3 -c 'print([0.5] * 405)')}"
while read -r id seed fitness x y; do
  genome=$tmp/g.json
  [[ $id == vec ]] && genome=$tmp/vec.json
  "$bin/ahhs-launch" $scenario --envelope paper --genome $genome --seed $seed --arena-kind fused >$tmp/launch.out
  got=$(sed -n 's/^fitness: //p' $tmp/launch.out)
  python3 -c "import sys; sys.exit(float('$got') != $fitness)" || fail "$id seed $seed: service $fitness, ahhs-launch $got"
  # The descriptor too (the service's from the farm's direct arenas, ahhs-launch's from its
  # fitness monitor's FITNESS): "descriptor: end_x X, end_y Y".
  got=$(sed -n 's/^descriptor: end_x \([^,]*\), end_y \(.*\)$/\1 \2/p' $tmp/launch.out)
  python3 -c "import sys; a = '$got'.split(); sys.exit(len(a) != 2 or float(a[0]) != $x or float(a[1]) != $y)" ||
    fail "$id seed $seed: service descriptor $x $y, ahhs-launch '$got'"
done <$tmp/launches
echo "  $(wc -l <$tmp/launches) trials reproduced exactly, fitness and descriptor"
echo "== 3. external workers only, the same answers"
"$bin/ahhs-worker" --lcm-url "$url" --any-run --id ext >/dev/null 2>&1 &
w=$!
head -1 $tmp/requests | $S $scenario --trials 2 --envelope paper --workers 0 --lcm-url "$url" \
  --wait-for-workers 1 --worker-wait 20 >$tmp/ext 2>$tmp/err || fail "external: $(cat $tmp/err)"
grep -qx "ahhs-evaluate: 1 worker ready" $tmp/err || fail "no ready line: $(cat $tmp/err)"
# Two asked for, one serving: exit 1 before the hello line, the worker heard named (a worker
# says it serves once a second, so the wait is 4 s).
$S $scenario --workers 0 --lcm-url "$url" --wait-for-workers 2 --worker-wait 4 </dev/null >$tmp/o 2>$tmp/err
[[ $? == 1 && ! -s $tmp/o ]] || fail "too few workers: $(cat $tmp/o $tmp/err)"
grep -q "only 1 of the 2 workers .*(heard: ext on " $tmp/err || fail "too-few message: $(cat $tmp/err)"
kill $w; wait $w 2>/dev/null
[[ "$(sed -n 2p $tmp/ext)" == "$(sed -n 2p $tmp/out)" ]] || fail "external workers answer otherwise: $(cat $tmp/ext)"
echo "== 4. a recorded run is validated and post-evaluated when its input ends"
python3 - >$tmp/run-requests <<'PY'
import json
for gen in range(2):
    print(json.dumps({"v": 2, "generation": gen,
                      "genomes": [{"vector": [0.1 * (gen + k + 1)] * (15 + 13 * 30)} for k in range(3)]}))
PY
$S $scenario --trials 2 --envelope paper --workers 2 --lcm-url "$url" --out $tmp/run --population 3 \
  --generations 2 --validation 3 --validation-candidates 2 --post-eval 4 <$tmp/run-requests \
  >$tmp/run.out 2>$tmp/run.err || fail "recorded run: $(cat $tmp/run.err)"
# stdout holds the protocol only: the hello (which says what the end brings) and two answers.
python3 - $tmp/run.out <<'PY' || fail "stdout of a recorded run: $(cat $tmp/run.out)"
import json, sys
lines = [json.loads(l) for l in open(sys.argv[1])]
assert len(lines) == 3, lines
assert lines[0]["run"]["validation"] == 3 and lines[0]["run"]["post_eval"] == 4, lines[0]
PY
grep -q "^validation: the best is generation" $tmp/run.err || fail "no validation: $(cat $tmp/run.err)"
said=$(grep "^post-evaluation on 4 held-out episodes" $tmp/run.err) || fail "no post-evaluation: $(cat $tmp/run.err)"
python3 - $tmp/run <<'PY' || fail "best.json and post-eval.json of a recorded run"
import json, sys
best = json.load(open(sys.argv[1] + "/best.json"))
post = json.load(open(sys.argv[1] + "/post-eval.json"))
assert best["meta"]["validation"]["episodes"] == 3, best["meta"]
assert post["episodes"] == 4 and post["generation"] == best["meta"]["generation"], post
PY
# ahhs-replay's post-evaluation of the chosen best says the same; a resume has nothing left to do.
"$bin/ahhs-replay" $tmp/run --post-eval 4 | grep -qxF "$said" || fail "ahhs-replay disagrees: $said"
$S --resume $tmp/run --workers 1 --lcm-url "$url" </dev/null >$tmp/r.out 2>$tmp/r.err || fail "resume: $(cat $tmp/r.err)"
[[ "$(cat $tmp/r.err)" == "$said" ]] || fail "a resumed finished run: $(cat $tmp/r.err)"
$S $scenario --validation 3 </dev/null >$tmp/o 2>&1; [[ $? == 2 ]] && grep -q "go with --out" $tmp/o ||
  fail "--validation without --out: $(cat $tmp/o)"
echo "== 5. bad options"
$S --trials 0 </dev/null >$tmp/o 2>&1; [[ $? == 2 ]] || fail "--trials 0: $(cat $tmp/o)"
$S --scenario walker </dev/null >$tmp/o 2>&1; [[ $? == 2 ]] && grep -q "unknown scenario" $tmp/o || fail "bad scenario: $(cat $tmp/o)"
echo PASS
