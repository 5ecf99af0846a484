#!/usr/bin/env bash
# ahhs-evolve and ahhs-worker end to end, inside a private network namespace:
#  1. the same config and seed give identical runs (every genome, seed and fitness) with 1 or 2
#     local workers and with direct and fused arenas, for the pendulum and the gait (the
#     processes arena: evolve_arenas_test.sh, which holds the lock against lockstep tests);
#  2. kill -9 mid-run, then --resume: the run ends exactly as the uninterrupted one; Ctrl-C stops
#     cleanly with exit 130 and the resume command;
#  3. external workers: one killed mid-run, one returning NaN, a worker of another protocol
#     version, garbage on every farm channel: the run completes with identical results and
#     reports what happened; a worker refuses a request of another protocol version;
#  4. bad input: an existing run directory, bad options, a directory that is not a run, no
#     worker at all: clear messages, non-zero exits, nothing overwritten; local workers that are
#     silent because they wait for a CPU are waited for;
#  5. runs are isolated: two runs on one bus never use each other's local workers, a worker
#     told to serve another run is passed over, and a worker must be told what to serve.
bin=${1:?usage: evolve_test.sh BIN_DIR}
source "${AHHS_SOURCE_DIR:?}/tests/lib.sh"
ahhs_netns "$0" "$@"
url="udpm://239.255.42.60:7751?ttl=0&recv_buf_size=4194304"
ahhs_scratch 'ahhs-evolve|ahhs-worker|bus_peer|farm_peer'
E="$bin/ahhs-evolve"
same_run() {  # same_run DIR_A DIR_B WHAT
  dump_run "$1" >$tmp/a.dump; dump_run "$2" >$tmp/b.dump
  [[ -s $tmp/a.dump ]] || fail "$3: empty run"
  cmp -s $tmp/a.dump $tmp/b.dump || { diff $tmp/a.dump $tmp/b.dump | head -5; fail "$3: runs differ"; }
  echo "$3: identical ($(wc -l <$tmp/a.dump) individuals)"
}
pend="--scenario pendulum --hormones 6 --rules 8 --population 12 --generations 5 --duration 10 --seed 11 --lcm-url $url"
gait="--scenario gait --hormones 3 --rules 6 --population 6 --generations 3 --duration 2 --seed 12 --lcm-url $url"

echo "== 1. determinism across workers and arenas"
$E $pend --out $tmp/p-direct-1 --workers 1 >$tmp/out 2>&1 || { cat $tmp/out; fail "pendulum run"; }
grep -q "^best fitness: " $tmp/out || fail "no summary: $(cat $tmp/out)"
grep -q "^replay the best genome: $bin/ahhs-launch --scenario pendulum --duration 10 --genome $tmp/p-direct-1/best.json --seed " $tmp/out ||
  fail "no replay command: $(cat $tmp/out)"
[[ $(wc -l <$tmp/p-direct-1/generations.csv) == 6 ]] || fail "generations.csv: $(cat $tmp/p-direct-1/generations.csv)"
ls $tmp/p-direct-1/best/gen-000{0,1,2,3,4}.json >/dev/null || fail "best genome files"
# The replay command reproduces the stored best fitness.
replay=$(sed -n "s|^replay the best genome: $bin/ahhs-launch ||p" $tmp/out)
best=$(sed -n 's/^best fitness: \([^ ]*\) .*/\1/p' $tmp/out)
"$bin/ahhs-launch" $replay --arena-kind fused >$tmp/replay.out || fail "replay"
[[ "$(tail -1 $tmp/replay.out)" == "fitness: $best" ]] || fail "replay gives $(tail -1 $tmp/replay.out), stored $best"
echo "replayed best: $best"
# Without --seed, ahhs-launch and ahhs-replay --genome use the evaluation seed best.json stores,
# say so, and reproduce the stored fitness.
"$bin/ahhs-launch" --scenario pendulum --duration 10 --genome $tmp/p-direct-1/best.json --arena-kind fused >$tmp/noseed.out ||
  fail "launch without --seed"
grep -q "^seed [0-9]*: the evaluation seed stored in $tmp/p-direct-1/best.json" $tmp/noseed.out ||
  fail "launch does not say which seed: $(cat $tmp/noseed.out)"
[[ "$(tail -1 $tmp/noseed.out)" == "fitness: $best" ]] || fail "launch without --seed: $(tail -1 $tmp/noseed.out), stored $best"
"$bin/ahhs-replay" --genome $tmp/p-direct-1/best.json --scenario pendulum --duration 10 >$tmp/noseed.out ||
  fail "replay --genome without --seed"
grep -q "with the evaluation seed it stores" $tmp/noseed.out && grep -q "reproduced exactly" $tmp/noseed.out ||
  fail "replay --genome without --seed: $(cat $tmp/noseed.out)"
[[ "$(tail -1 $tmp/noseed.out)" == "fitness: $best" ]] || fail "replay --genome without --seed: $(tail -1 $tmp/noseed.out)"
for v in "2 direct" "2 fused"; do
  set -- $v
  $E $pend --out $tmp/p-$2-$1 --workers $1 --arena-kind $2 >$tmp/out 2>&1 || { cat $tmp/out; fail "pendulum $v"; }
  same_run $tmp/p-direct-1 $tmp/p-$2-$1 "pendulum, $1 workers, $2 arena"
done
$E $gait --out $tmp/g-direct --workers 2 >$tmp/out 2>&1 || { cat $tmp/out; fail "gait run"; }
$E $gait --out $tmp/g-fused --workers 1 --arena-kind fused >$tmp/out 2>&1 || { cat $tmp/out; fail "gait fused"; }
same_run $tmp/g-direct $tmp/g-fused "gait, fused arena"
$E $gait --docking fixed --variant ahhs1 --out $tmp/gf-direct --workers 2 >/dev/null 2>&1 || fail "gait fixed"
$E $gait --docking fixed --variant ahhs1 --out $tmp/gf-fused --workers 1 --arena-kind fused >/dev/null 2>&1 || fail "gait fixed fused"
same_run $tmp/gf-direct $tmp/gf-fused "gait fixed ahhs1, fused arena"

echo "== 2. kill -9 and resume; Ctrl-C"
# The sanitizer tier runs the long run with half its generations and one kill point.
long_gens=16 kill_points="2 9" external_at=5
ci_tier_only "a 16-generation long run (8 here) and a second kill point" &&
  long_gens=8 kill_points=5 external_at=3
long="--scenario gait --hormones 3 --rules 6 --population 8 --generations $long_gens --duration 3 --seed 13 --lcm-url $url"
$E $long --out $tmp/whole --workers 2 >/dev/null 2>&1 || fail "uninterrupted run"
for at in $kill_points; do
  $E $long --out $tmp/killed$at --workers 2 >$tmp/killed.out 2>&1 &
  pid=$!
  for _ in $(seq 1 600); do
    [[ $(wc -l 2>/dev/null <$tmp/killed$at/generations.csv || echo 0) -gt $at ]] && break
    sleep 0.01
  done
  kill -9 $pid; wait $pid 2>/dev/null
  stored=$(($(wc -l <$tmp/killed$at/generations.csv) - 1))
  [[ $stored -lt $long_gens ]] || fail "the run ended before the kill"
  sleep 0.3
  pgrep -g "$pg" -f "$bin/ahhs-worker" >/dev/null && fail "local workers outlived a killed evolver"
  $E --resume $tmp/killed$at --workers 2 >$tmp/resume.out 2>&1 || { cat $tmp/resume.out; fail "resume"; }
  grep -q "resuming at generation $stored" $tmp/resume.out || fail "resume message: $(head -3 $tmp/resume.out)"
  same_run $tmp/whole $tmp/killed$at "killed after $stored generations, resumed"
  cmp -s $tmp/whole/generations.csv $tmp/killed$at/generations.csv && fail "wall times cannot all match"
  diff <(cut -d, -f1-6 $tmp/whole/generations.csv) <(cut -d, -f1-6 $tmp/killed$at/generations.csv) ||
    fail "generations.csv statistics differ after resume"
done
$E $long --out $tmp/ctrlc --workers 2 >$tmp/ctrlc.out 2>&1 &
pid=$!
for _ in $(seq 1 600); do [[ $(wc -l 2>/dev/null <$tmp/ctrlc/generations.csv || echo 0) -gt 3 ]] && break; sleep 0.01; done
kill -INT $pid; wait $pid; rc=$?
[[ $rc == 130 ]] || fail "Ctrl-C exit status $rc: $(cat $tmp/ctrlc.out)"
grep -q "continue with: $E --resume $tmp/ctrlc" $tmp/ctrlc.out || fail "Ctrl-C message: $(cat $tmp/ctrlc.out)"
sleep 0.3
pgrep -g "$pg" -f "$bin/ahhs-worker" >/dev/null && fail "workers left after Ctrl-C"
# The printed command runs as printed, with this session's farm (its workers and bus).
hint=$(sed -n 's/^continue with: //p' $tmp/ctrlc.out)
[[ "$hint" == "$E --resume $tmp/ctrlc --workers 2 --lcm-url '$url'" ]] || fail "resume hint: $hint"
eval "$hint" >/dev/null 2>&1 || fail "resume after Ctrl-C"
same_run $tmp/whole $tmp/ctrlc "Ctrl-C, resumed"
$E --resume $tmp/ctrlc >$tmp/again.out 2>&1 || fail "resume of a finished run"
grep -q "already complete" $tmp/again.out || fail "finished run: $(cat $tmp/again.out)"
if ! ci_tier_only "a 12 s pause (SIGSTOP) of the evolver and its workers"; then
# A pause longer than --worker-wait and than the workers' silence limit (10 s): SIGSTOP of the
# evolver and its workers, as on a suspended machine, is not a missing worker; the run goes on
# and ends as the uninterrupted one (before, the study's runs failed after such a pause).
$E $long --out $tmp/paused --workers 2 --worker-wait 2 >$tmp/paused.out 2>&1 &
pid=$!
for _ in $(seq 1 600); do [[ $(wc -l 2>/dev/null <$tmp/paused/generations.csv || echo 0) -gt 3 ]] && break; sleep 0.01; done
kids=$(pgrep -P $pid | tr '\n' ' ')
kill -STOP $pid $kids; sleep 12; kill -CONT $pid $kids
wait $pid || fail "paused run: $(tail -3 $tmp/paused.out)"
same_run $tmp/whole $tmp/paused "paused 12 s with --worker-wait 2"
fi
if ! ci_tier_only "local workers starved of CPU by busy loops"; then
# Local workers that a busy machine runs at idle priority (a study under `chrt -i 0` beside a
# report) are silent for longer than the workers' silence limit (10 s) and --worker-wait: they
# are alive and waiting for a CPU, not missing. The run waits for them, says so, and ends as the
# uninterrupted one (before, it ended with "no evaluation worker has answered"). The busy loops
# run until the evolver has said it waits (at most 60 s each).
starve="--scenario gait --hormones 3 --rules 6 --population 8 --generations 4 --duration 200 --seed 13 --lcm-url $url"
$E $starve --out $tmp/fed --workers 2 >/dev/null 2>&1 || fail "uninterrupted 200-s run"
hogs=()
for _ in 1 2 3 4 5 6; do
  bash -c 'end=$((SECONDS + 60)); while ((SECONDS < end)); do :; done' & hogs+=($!)
done
$E $starve --out $tmp/starved --workers 2 --worker-wait 2 >$tmp/starved.out 2>&1 &
pid=$!
# Its workers idle-class as soon as they exist (an episode takes them about 0.5 s beside the
# busy loops at normal priority, so none ends before).
workers=""
for _ in $(seq 1 500); do
  workers=$(pgrep -P $pid -f ahhs-worker | tr '\n' ' ')
  [[ $(wc -w <<<"$workers") == 2 ]] && break
  sleep 0.01
done
[[ $(wc -w <<<"$workers") == 2 ]] || fail "the starved run's two workers: '$workers'"
for k in $workers; do chrt --idle -p 0 $k >/dev/null || fail "chrt --idle"; done
for _ in $(seq 1 600); do
  grep -q "waiting for a CPU" $tmp/starved.out && break
  kill -0 $pid 2>/dev/null || break
  sleep 0.1
done
kill "${hogs[@]}" 2>/dev/null; wait "${hogs[@]}" 2>/dev/null
wait $pid || fail "starved run: $(tail -3 $tmp/starved.out)"
grep -q "but the local workers are waiting for a CPU (a busy machine): waiting on" $tmp/starved.out ||
  fail "the workers were never starved long enough: $(tail -3 $tmp/starved.out)"
same_run $tmp/fed $tmp/starved "workers starved of CPU, with --worker-wait 2"
fi

echo "== 2b. robust evolution: 3 trials under the envelope, killed and resumed, external workers"
robust="--scenario gait --hormones 3 --rules 6 --population 6 --generations 6 --duration 2 --seed 12
  --lcm-url $url --trials 3 --aggregate median --envelope paper --validation 4 --validation-candidates 2"
# The validation that chose the best: every candidate's episodes, as stored.
validation() { sqlite3 $1/run.sqlite "SELECT * FROM validation ORDER BY candidate, episode"; }
$E $robust --out $tmp/r-whole --workers 2 --post-eval 3 >$tmp/out 2>&1 || { cat $tmp/out; fail "robust run"; }
grep -q "3 trials (median), envelope paper" $tmp/out || fail "robust run header: $(head -3 $tmp/out)"
# Its best is chosen among 2 + up to 2 candidates on 4 validation episodes, through the workers.
grep -q "^chosen by validation among [2-4] candidates: median .* on 4 episodes" $tmp/out ||
  fail "no validation: $(tail -4 $tmp/out)"
[[ $(validation $tmp/r-whole | wc -l) -ge 8 ]] || fail "validation rows: $(validation $tmp/r-whole)"
# The run ends with its best post-evaluated on held-out episodes, also in post-eval.json.
grep -q "^post-evaluation on 3 held-out episodes (envelope paper): median " $tmp/out ||
  fail "no post-evaluation: $(tail -3 $tmp/out)"
python3 - $tmp/r-whole/post-eval.json <<'PY' || fail "post-eval.json"
import json, sys
d = json.load(open(sys.argv[1]))
assert d["episodes"] == 3 and len(d["per_episode"]) == 3 and d["envelope"] == "paper", d
assert d["per_episode"][0]["seed"] not in (None, 0)
PY
# The printed replay command replays the best's first trial, envelope included, exactly.
replay=$(sed -n "s|^replay the best genome's first trial (fitness \([^)]*\)): $bin/ahhs-launch ||p" $tmp/out)
first=$(sed -n "s|^replay the best genome's first trial (fitness \([^)]*\)).*|\1|p" $tmp/out)
[[ $replay == *"--envelope paper"* ]] || fail "robust replay command: $(grep replay $tmp/out)"
"$bin/ahhs-launch" $replay --arena-kind fused >$tmp/replay.out || fail "robust replay"
[[ "$(tail -1 $tmp/replay.out)" == "fitness: $first" ]] || fail "robust replay gives $(tail -1 $tmp/replay.out), trial 0 stored $first"
"$bin/ahhs-replay" $tmp/r-whole >$tmp/replay.out || fail "ahhs-replay of a robust run"
grep -q "trial 0 of 3 (the median of all 3 is" $tmp/replay.out && grep -q "reproduced exactly" $tmp/replay.out ||
  fail "ahhs-replay of a robust run: $(cat $tmp/replay.out)"
# Its best.json alone replays under the run's envelope (meta.config) without --envelope.
"$bin/ahhs-replay" --genome $tmp/r-whole/best.json --scenario gait --duration 2 >$tmp/replay.out ||
  fail "ahhs-replay of a robust best.json"
grep -q "under the envelope of its run, paper" $tmp/replay.out && grep -q "reproduced exactly" $tmp/replay.out ||
  fail "a robust best.json replays without its envelope: $(cat $tmp/replay.out)"
$E --resume $tmp/r-whole >$tmp/out 2>&1 && grep -q "^post-evaluation on 3 held-out" $tmp/out &&
  ! grep -q "post-evaluating" $tmp/out || fail "a finished run's post-evaluation was not kept: $(cat $tmp/out)"
[[ $(sqlite3 $tmp/r-whole/run.sqlite "SELECT COUNT(*) FROM trials") == $((6 * 6 * 3)) ]] ||
  fail "trials stored: $(sqlite3 $tmp/r-whole/run.sqlite 'SELECT COUNT(*) FROM trials')"
# The elite is evaluated again on fresh seeds: its stored fitness changes from one generation to
# the next (in a paper run it never does).
elite_changes=$(sqlite3 $tmp/r-whole/run.sqlite "SELECT COUNT(*) FROM individuals i JOIN generations p
  ON p.generation = i.generation - 1 JOIN individuals b ON b.generation = p.generation AND
  b.idx = p.best_index WHERE i.elite = 1 AND i.fitness != b.fitness")
[[ $elite_changes -ge 4 ]] || fail "the elite kept its fitness under the envelope ($elite_changes of 5 changed)"
paper_changes=$(sqlite3 $tmp/g-direct/run.sqlite "SELECT COUNT(*) FROM individuals i JOIN generations p
  ON p.generation = i.generation - 1 JOIN individuals b ON b.generation = p.generation AND
  b.idx = p.best_index WHERE i.elite = 1 AND i.fitness != b.fitness")
[[ $paper_changes == 0 ]] || fail "a paper run's elite changed its fitness ($paper_changes times)"
$E $robust --out $tmp/r-killed --workers 2 >$tmp/killed.out 2>&1 &
pid=$!
for _ in $(seq 1 600); do
  [[ $(wc -l 2>/dev/null <$tmp/r-killed/generations.csv || echo 0) -gt 2 ]] && break
  sleep 0.01
done
kill -9 $pid; wait $pid 2>/dev/null
$E --resume $tmp/r-killed --workers 1 >$tmp/resume.out 2>&1 || { cat $tmp/resume.out; fail "robust resume"; }
same_run $tmp/r-whole $tmp/r-killed "robust run killed and resumed"
[[ "$(validation $tmp/r-killed)" == "$(validation $tmp/r-whole)" ]] || fail "the resumed run's validation differs"
$E --resume $tmp/r-killed --envelope none >$tmp/out 2>&1 && fail "--envelope accepted with --resume"
grep -q "cannot be given with --resume" $tmp/out || fail "robust resume option message: $(cat $tmp/out)"
"$bin/ahhs-worker" --lcm-url "$url" --any-run --id lan-a >/dev/null 2>&1 &
wa=$!
"$bin/ahhs-worker" --lcm-url "$url" --any-run --id lan-b >/dev/null 2>&1 &
wb=$!
# Both workers serve before generation 0 (a worker still starting on a loaded machine would
# leave every trial to the other).
$E $robust --out $tmp/r-external --workers 0 --wait-for-workers 2 --worker-wait 20 >$tmp/out 2>&1 ||
  { cat $tmp/out; fail "robust run, external workers"; }
kill $wa $wb; wait $wa $wb 2>/dev/null
same_run $tmp/r-whole $tmp/r-external "robust run on external workers only"
[[ "$(validation $tmp/r-external)" == "$(validation $tmp/r-whole)" ]] || fail "the validation on external workers differs"
[[ $(sqlite3 $tmp/r-external/run.sqlite "SELECT COUNT(DISTINCT worker) FROM trials") == 2 ]] ||
  fail "the trials did not spread over both workers"

echo "== 3. external workers and faults"
"$bin/ahhs-worker" --lcm-url "$url" --any-run --id steady >$tmp/w1.out 2>&1 &
w1=$!
"$bin/ahhs-worker" --lcm-url "$url" --any-run --id doomed >$tmp/w2.out 2>&1 &
w2=$!
AHHS_WORKER_FAULT=nan "$bin/ahhs-worker" --lcm-url "$url" --any-run --id liar >$tmp/w3.out 2>&1 &
w3=$!
"$bin/farm_peer" --role foreign-worker --lcm-url "$url" --seconds 60 >/dev/null 2>&1 &
"$bin/bus_peer" --role spam --lcm-url "$url" --channels "EVAL/REQUEST,EVAL/RESULT,WORKER/STATUS" --seconds 60 >$tmp/spam.out 2>&1 &
spam=$!
sleep 0.5
"$bin/farm_peer" --role foreign-evolver --lcm-url "$url" --worker steady --seconds 5 >$tmp/refusal.out ||
  fail "the worker did not refuse a foreign request: $(cat $tmp/refusal.out)"
grep -q "version" $tmp/refusal.out || fail "refusal message: $(cat $tmp/refusal.out)"
$E $long --out $tmp/external --workers 0 --job-deadline 20 >$tmp/external.out 2>&1 &
pid=$!
for _ in $(seq 1 600); do [[ $(wc -l 2>/dev/null <$tmp/external/generations.csv || echo 0) -gt $external_at ]] && break; sleep 0.01; done
kill -9 $w2
wait $pid || { cat $tmp/external.out; fail "run with external workers"; }
kill $spam 2>/dev/null
same_run $tmp/whole $tmp/external "external workers (one killed, one returning NaN, garbage)"
grep -q "refused worker future-worker.*version 99" $tmp/external.out || fail "no refusal reported: $(head $tmp/external.out)"
grep -q "worker liar returned a non-finite fitness" $tmp/external.out || fail "NaN not reported"
grep -q "worker liar returned 3 invalid results; it gets no more jobs" $tmp/external.out || fail "liar not quarantined"
grep -Eq "re-issued \((worker silent|lease expired)" $tmp/external.out || fail "no re-issue reported"
grep -Eq "farm: [0-9]+ jobs re-issued, [1-9][0-9]* invalid results, [1-9][0-9]* undecodable" $tmp/external.out ||
  fail "farm summary: $(tail -5 $tmp/external.out)"
[[ $(sqlite3 $tmp/external/run.sqlite "SELECT COUNT(*) FROM individuals WHERE worker = 'liar'") == 0 ]] ||
  fail "a NaN result was stored"
kill $w1 $w3; wait $w1 $w3 2>/dev/null
grep -q "undecodable messages dropped" $tmp/w1.out || fail "worker summary: $(cat $tmp/w1.out)"
echo "$(grep -c . $tmp/external.out) lines of output; $(grep -c 're-issued' $tmp/external.out) re-issues reported"

echo "== 4. bad input"
$E $pend --out $tmp/p-direct-1 --workers 1 >$tmp/out 2>&1 && fail "overwrote a run"
grep -q "already holds files; continue that run with --resume" $tmp/out || fail "overwrite message: $(cat $tmp/out)"
same_run $tmp/p-direct-1 $tmp/p-direct-2 "the refused run left the old one intact"
$E $pend --out $tmp/p-direct-1 --workers 1 --overwrite >/dev/null 2>&1 || fail "--overwrite"
$E --scenario pendulum --population 1 --out $tmp/bad1 >$tmp/out 2>&1 && fail "population 1 accepted"
grep -q "population must be at least 2" $tmp/out || fail "population message: $(cat $tmp/out)"
[[ -e $tmp/bad1 ]] && fail "a refused config left a directory"
$E --resume $tmp/nothing >$tmp/out 2>&1 && fail "resume of nothing"
grep -q "is not a directory" $tmp/out || fail "resume message: $(cat $tmp/out)"
mkdir $tmp/notrun
$E --resume $tmp/notrun >$tmp/out 2>&1 && fail "resume of a non-run"
grep -q "not a run directory" $tmp/out || fail "non-run message: $(cat $tmp/out)"
$E --resume $tmp/whole --population 30 >$tmp/out 2>&1 && fail "resume with a new population"
grep -q "cannot be given with --resume" $tmp/out || fail "resume option message: $(cat $tmp/out)"
$E --config /nonexistent.toml >$tmp/out 2>&1 && fail "missing config accepted"
$E $pend --out $tmp/noworker --workers 0 --worker-wait 1 >$tmp/out 2>&1
rc=$?
[[ $rc == 1 ]] || fail "no worker: exit $rc"
grep -q "no evaluation worker has answered" $tmp/out || fail "no-worker message: $(cat $tmp/out)"
grep -q "continue with: $E --resume $tmp/noworker" $tmp/out || fail "no resume hint"
# --wait-for-workers N: generation 0 starts once N workers serve; too few is exit 1, resumable,
# with the workers heard named (a worker says it serves once a second, so the wait is 4 s).
$E $pend --out $tmp/toofew --workers 1 --wait-for-workers 2 --worker-wait 4 >$tmp/out 2>&1
rc=$?
[[ $rc == 1 ]] || fail "too few workers: exit $rc"
grep -q "only 1 of the 2 workers asked for (--wait-for-workers) were ready to serve after 4 s (heard: .* on " $tmp/out ||
  fail "too-few-workers message: $(cat $tmp/out)"
grep -q "continue with: $E --resume $tmp/toofew" $tmp/out || fail "no resume hint after too few workers"
$E --resume $tmp/toofew --workers 2 --wait-for-workers 2 >$tmp/out 2>&1 || fail "resume with 2 workers: $(cat $tmp/out)"
grep -q "2 workers ready" $tmp/out || fail "no ready line: $(cat $tmp/out)"

# Files derived from the database are rebuilt by --resume when a kill left them short or missing.
cp $tmp/p-direct-1/generations.csv $tmp/gen.csv
sed -i '$d' $tmp/p-direct-1/generations.csv
rm $tmp/p-direct-1/best/gen-0004.json $tmp/p-direct-1/best.json
$E --resume $tmp/p-direct-1 >$tmp/out 2>&1 || fail "resume of a complete run: $(cat $tmp/out)"
grep -q "already complete" $tmp/out || fail "complete run: $(cat $tmp/out)"
cmp -s $tmp/gen.csv $tmp/p-direct-1/generations.csv || fail "generations.csv not rebuilt"
[[ -s $tmp/p-direct-1/best/gen-0004.json && -s $tmp/p-direct-1/best.json ]] || fail "best files not rebuilt"
echo "a complete run's missing exports are rebuilt by --resume"
# A run records the physics its fitnesses were measured with; a resume in other physics is refused,
# a run made before the physics was recorded resumes with a note.
[[ $(sqlite3 $tmp/p-direct-1/run.sqlite "SELECT value FROM run WHERE key = 'physics'") == 2026-* ]] ||
  fail "no physics recorded"
cp -r $tmp/p-direct-1 $tmp/older
# (as a build before the digest chain left it: the chain would refuse a changed run table)
unchain="DROP TABLE chain; UPDATE run SET value = '2' WHERE key = 'format_version'"
sqlite3 $tmp/older/run.sqlite "UPDATE run SET value = '1999-01-01' WHERE key = 'physics'; $unchain"
$E --resume $tmp/older >$tmp/out 2>&1
[[ $? == 1 ]] && grep -q "was made with the pendulum physics of 1999-01-01, this build has" $tmp/out ||
  fail "other physics resumed: $(cat $tmp/out)"
sqlite3 $tmp/older/run.sqlite "DELETE FROM run WHERE key = 'physics'; $unchain"
$E --resume $tmp/older >$tmp/out 2>&1 && grep -q "does not record its physics" $tmp/out ||
  fail "run without physics: $(cat $tmp/out)"
# --physics keeps an earlier physics this build simulates: the run records it, its workers evaluate
# in it (EVAL/REQUEST names it), a resume keeps it, and its best replays in it bit for bit, by
# ahhs-replay and by the ahhs-launch line the run prints; one it does not simulate is refused.
gait_pin="--scenario gait --docking fixed --hormones 3 --rules 6 --population 4 --generations 2 --duration 10 --seed 3 --lcm-url $url --workers 1"
$E $gait_pin --physics 2026-12-04 --out $tmp/pinned >$tmp/out 2>&1 || fail "--physics 2026-12-04: $(cat $tmp/out)"
[[ $(sqlite3 $tmp/pinned/run.sqlite "SELECT value FROM run WHERE key = 'physics'") == 2026-12-04 ]] ||
  fail "pinned physics not recorded"
launch=$(sed -n 's/^replay the best genome: //p' $tmp/out)
[[ $launch == *" --physics 2026-12-04 "* ]] || fail "launch line without the physics: $launch"
best=$(sed -n 's/^best fitness: \([^ ]*\).*/\1/p' $tmp/out)
$launch --arena-kind fused 2>&1 | grep -q "^fitness: $best\$" || fail "the launch line does not reproduce $best"
"$bin/ahhs-replay" $tmp/pinned >$tmp/rep 2>&1 && grep -q "^physics: 2026-12-04 (this build's is" $tmp/rep &&
  grep -q "reproduced exactly" $tmp/rep || fail "replay of a pinned run: $(cat $tmp/rep)"
$E --resume $tmp/pinned >$tmp/out 2>&1 || fail "resume of a pinned run: $(cat $tmp/out)"
$E $gait_pin --out $tmp/own >/dev/null 2>&1 || fail "the same run in this build's physics"
[[ $(cut -d, -f2-5 $tmp/pinned/generations.csv) != $(cut -d, -f2-5 $tmp/own/generations.csv) ]] ||
  fail "the pinned run's fitnesses are this build's physics'"
$E $gait_pin --physics 1999-01-01 --out $tmp/never >$tmp/out 2>&1
[[ $? == 1 && ! -e $tmp/never ]] && grep -q "this build simulates the gait physics of .*, not 1999-01-01" $tmp/out ||
  fail "--physics 1999-01-01: $(cat $tmp/out)"

echo "== 5. runs are isolated"
"$bin/ahhs-worker" --lcm-url "$url" --id stranger --run someone-else >$tmp/stranger.out 2>&1 &
$E $pend --out $tmp/iso-a --workers 1 >$tmp/iso-a.out 2>&1 &
a=$!
$E $pend --out $tmp/iso-b --workers 1 >$tmp/iso-b.out 2>&1 || fail "run b: $(cat $tmp/iso-b.out)"
wait $a || fail "run a: $(cat $tmp/iso-a.out)"
wa=$(sqlite3 $tmp/iso-a/run.sqlite "SELECT DISTINCT worker FROM individuals")
wb=$(sqlite3 $tmp/iso-b/run.sqlite "SELECT DISTINCT worker FROM individuals")
[[ $(echo "$wa" | wc -l) == 1 && $(echo "$wb" | wc -l) == 1 && "$wa" != "$wb" ]] ||
  fail "runs shared workers: a: $wa; b: $wb"
same_run $tmp/p-direct-1 $tmp/iso-a "isolated run a"
grep -q -- "--run $(sqlite3 $tmp/iso-a/run.sqlite "SELECT value FROM run WHERE key = 'run_id'")" $tmp/iso-a.out ||
  fail "no command for more workers: $(cat $tmp/iso-a.out)"
"$bin/ahhs-worker" --lcm-url "$url" >$tmp/out 2>&1; rc=$?
[[ $rc == 2 ]] && grep -q "say which run to serve" $tmp/out || fail "worker without --run: $rc $(cat $tmp/out)"
echo "each run used its own worker only ($wa; $wb), the stranger none"
echo "PASS"
