#!/usr/bin/env bash
# ahhs-study end to end, inside a private network namespace:
#  1. bad plans give one line naming the file and line, exit 2, and leave no study directory;
#  2. a study (2 configurations x 2 seeds, 2 runs at a time) ends with every run complete;
#  3. kill -9 of ahhs-study at a random moment, or Ctrl-C, then run --resume: every run equals the
#     uninterrupted study's bit for bit; a second ahhs-study on the same directory is refused;
#  4. export keeps best genome, generations and summary per run; a new study given the export
#     runs only what the export lacks, and its runs equal the others bit for bit;
#     --finish-by starts no run that would end too late;
#  5. status reports every run;
#  6. report (ahhs-report study) of the study directory and of its export give the same numbers.
bin=${1:?usage: study_test.sh BIN_DIR}
source "${AHHS_SOURCE_DIR:?}/tests/lib.sh"
ahhs_netns "$0" "$@"
ahhs_scratch 'ahhs-study|ahhs-evolve|ahhs-worker'
src=$AHHS_SOURCE_DIR
S="$bin/ahhs-study"
source "$src/tests/tools/study_lib.sh"
gens=20
ci_tier_only "the plan's 20 generations (10 here)" && gens=10
tiny_plan $tmp/plan.toml $gens
opts="--parallel 2 --workers-per-run 1 --port-base 7811"

echo "== 1. bad plans"
bad() {  # bad WHAT EXPECTED_TEXT: the plan in $tmp/bad.toml
  "$S" run $tmp/bad.toml --out $tmp/bad >$tmp/out 2>&1; rc=$?
  [[ $rc == 2 ]] || fail "$1: exit $rc: $(cat $tmp/out)"
  [[ $(wc -l <$tmp/out) == 1 ]] || fail "$1: not one line: $(cat $tmp/out)"
  grep -q -- "$2" $tmp/out || fail "$1: $(cat $tmp/out)"
  [[ ! -e $tmp/bad ]] || fail "$1: left a study directory"
  echo "$1: $(cat $tmp/out)"
}
sed 's/^seeds = 2$/seeds = 0/' $tmp/plan.toml >$tmp/bad.toml; bad "no seeds" "bad.toml:9: seeds must be"
sed "s/^generations = $gens\$/generatons = $gens/" $tmp/plan.toml >$tmp/bad.toml; bad "unknown setting" "bad.toml:3: 'generatons' is not an ahhs-evolve setting"
sed 's/^name = "pend1"$/name = "pend2"/' $tmp/plan.toml >$tmp/bad.toml; bad "repeated name" "pend2 is named twice"
sed 's/pendulum-ahhs1-60/nothing-here/' $tmp/plan.toml >$tmp/bad.toml; bad "missing preset" "nothing-here.toml does not exist"
sed 's/^seeds = 2$/seeds = 2\nseeds = 3/' $tmp/plan.toml >$tmp/bad.toml; bad "repeated key" "bad.toml:10:"
sed 's/^name = "tiny"$/name = "tiny"\nparallel = 3/' $tmp/plan.toml >$tmp/bad.toml; bad "unknown key" "unknown key 'parallel'"
sed 's/^duration = 20.0$/duration = "long"/' $tmp/plan.toml >$tmp/bad.toml; bad "refused by ahhs-evolve" "ahhs-evolve refuses it"
"$S" run --resume $tmp/nothing >$tmp/out 2>&1; [[ $? == 2 ]] || fail "resume of nothing: $(cat $tmp/out)"
grep -q "is not a study directory" $tmp/out || fail "resume of nothing: $(cat $tmp/out)"
"$S" run $tmp/plan.toml >$tmp/out 2>&1; [[ $? == 2 ]] || fail "no --out: $(cat $tmp/out)"
# A study whose creation was killed (configs/ but no plan yet): --resume says to start it again,
# and starting it again works.
mkdir -p $tmp/U/configs && echo x >$tmp/U/configs/pend2.toml
"$S" run --resume $tmp/U >$tmp/out 2>&1; [[ $? == 2 ]] && grep -q "creation was interrupted" $tmp/out || fail "unfinished: $(cat $tmp/out)"
"$S" run $tmp/plan.toml --out $tmp/U --only pend1 $opts >$tmp/out 2>&1 || fail "restart of an unfinished study: $(cat $tmp/out)"

echo "== 2. a whole study"
"$S" run $tmp/plan.toml --out $tmp/A $opts >$tmp/A.out 2>&1 || { cat $tmp/A.out; fail "study A"; }
grep -q "^study complete: 4 runs" $tmp/A.out || fail "study A: $(cat $tmp/A.out)"
for r in $runs; do
  [[ $(wc -l <$tmp/A/$r/generations.csv) == $((gens + 1)) ]] || fail "$r: generations.csv"
  [[ -s $tmp/A/$r/summary.json && -s $tmp/A/$r.log ]] || fail "$r: summary or log missing"
done
"$S" run $tmp/plan.toml --out $tmp/A $opts >$tmp/out 2>&1; [[ $? == 2 ]] || fail "a second study into A"
grep -q "already holds files; continue that study with ahhs-study run --resume $tmp/A" $tmp/out || fail "$(cat $tmp/out)"
"$S" run --resume $tmp/A $opts >$tmp/out 2>&1 || fail "resume of a complete study: $(cat $tmp/out)"
grep -q "4 of 4 runs complete, 0 to run" $tmp/out || fail "resume of a complete study: $(cat $tmp/out)"

echo "== 3. kill -9, Ctrl-C, resume"
kills="1 2 3"
ci_tier_only "two more kill -9 at random moments" && kills=1
for k in $kills; do
  rm -rf $tmp/B
  "$S" run $tmp/plan.toml --out $tmp/B $opts >$tmp/B.out 2>&1 &
  pid=$!
  sleep "$((RANDOM % 3)).$((RANDOM % 10))"
  kill -9 $pid; wait $pid 2>/dev/null
  # The runs it started end themselves (their owner is gone); the resume waits for them. Killed
  # while it was still making the study, there is nothing to resume: it is started again.
  if [[ -e $tmp/B/study.toml ]]; then
    "$S" run --resume $tmp/B $opts >$tmp/B2.out 2>&1 || { cat $tmp/B2.out; fail "resume after kill -9 #$k"; }
  else
    "$S" run --resume $tmp/B $opts >$tmp/B2.out 2>&1; [[ $? == 2 ]] && grep -q "creation was interrupted" $tmp/B2.out ||
      [[ ! -e $tmp/B ]] || fail "resume of an interrupted creation: $(cat $tmp/B2.out)"
    "$S" run $tmp/plan.toml --out $tmp/B $opts >$tmp/B2.out 2>&1 || { cat $tmp/B2.out; fail "restart after kill -9 #$k"; }
  fi
  same_study $tmp/A $tmp/B "kill -9 #$k ($(grep -c '^\[.*complete' $tmp/B.out) runs had completed)"
done
# B.out is emptied first: the background shell may truncate it only after the wait below has
# read the last study's "started".
rm -rf $tmp/B; : >$tmp/B.out
"$S" run $tmp/plan.toml --out $tmp/B $opts >$tmp/B.out 2>&1 &
pid=$!
# (Up to 60 s: on a loaded machine making the study can take more than a few seconds.)
for _ in $(seq 1200); do grep -q started $tmp/B.out 2>/dev/null && break; sleep 0.05; done
grep -q started $tmp/B.out || fail "the first ahhs-study started no run in 60 s: $(cat $tmp/B.out)"
"$S" run --resume $tmp/B $opts >$tmp/out 2>&1; rc=$?
[[ $rc == 1 ]] && grep -q "is in use by another ahhs-study run" $tmp/out || fail "second ahhs-study: $rc $(cat $tmp/out)"
kill -INT $pid; wait $pid; rc=$?
[[ $rc == 130 ]] || fail "Ctrl-C: exit $rc: $(cat $tmp/B.out)"
grep -q "continue with: $S run --resume $tmp/B" $tmp/B.out || fail "Ctrl-C: $(cat $tmp/B.out)"
"$S" status $tmp/B >$tmp/status || fail "status"
grep -Eq "pend2/seed-1 +(stopped|complete)" $tmp/status || fail "status after Ctrl-C: $(cat $tmp/status)"
grep -Eq "^time left here, one run at a time: [0-9.]+ (s|min|h) \(0 running, [0-9]+ waiting runs" $tmp/status ||
  fail "status after Ctrl-C: no time left: $(cat $tmp/status)"
# The printed command runs as printed.
$(sed -n 's/^stopped; continue with: //p' $tmp/B.out) $opts >$tmp/B2.out 2>&1 || { cat $tmp/B2.out; fail "resume after Ctrl-C"; }
same_study $tmp/A $tmp/B "Ctrl-C"

echo "== 4. export, and a study that starts from it"
"$S" export $tmp/A $tmp/E >$tmp/out || fail "export: $(cat $tmp/out)"
grep -q "exported 4 complete runs" $tmp/out || fail "export: $(cat $tmp/out)"
[[ "$(cd $tmp/E/pend1/seed-2 && ls | tr '\n' ' ')" == "best.json generations.csv summary.json " ]] ||
  fail "export holds: $(ls $tmp/E/pend1/seed-2)"
[[ -z "$(find $tmp/E -name '*.sqlite' -o -name '*.log')" ]] || fail "export holds databases or logs"
"$S" export $tmp/A $tmp/E >/dev/null || fail "export into the same export again"
mkdir $tmp/other; echo x >$tmp/other/file
"$S" export $tmp/A $tmp/other >$tmp/out 2>&1; [[ $? == 2 ]] && grep -q "is not a study export" $tmp/out || fail "export into a foreign directory: $(cat $tmp/out)"
"$S" status $tmp/E | grep -Eq "pend1/seed-2 +exported +$gens/$gens" || fail "status of an export: $($S status $tmp/E)"
rm -r $tmp/E/pend2/seed-2
"$S" status $tmp/E >$tmp/status || fail "status of an export with a run missing"
grep -Eq "^time left here, one run at a time: .*1 at the run time of their configuration's exported runs \(made elsewhere\)" $tmp/status ||
  fail "time left from exported runs: $(cat $tmp/status)"
"$S" run $tmp/plan.toml --out $tmp/C $opts --from-export $tmp/E >$tmp/C.out 2>&1 || { cat $tmp/C.out; fail "study from an export"; }
grep -q "3 complete runs taken" $tmp/C.out && grep -q "3 of 4 runs complete, 1 to run" $tmp/C.out ||
  fail "from export: $(cat $tmp/C.out)"
[[ $(grep -c started $tmp/C.out) == 1 ]] && grep -q "started pend2/seed-2" $tmp/C.out || fail "from export ran: $(cat $tmp/C.out)"
dump_run $tmp/A/pend2/seed-2 >$tmp/a.dump; dump_run $tmp/C/pend2/seed-2 >$tmp/c.dump
cmp -s $tmp/a.dump $tmp/c.dump || fail "the run made beside an export differs"
cmp -s $tmp/A/pend1/seed-1/best.json $tmp/C/pend1/seed-1/best.json || fail "taken run's best.json is not the export's"
# --finish-by: a run that its configuration's run time (here: an exported run's, made to take 2 h)
# would end too late is not started, and the study says how to go on; a later time starts it.
cp -r $tmp/E $tmp/E5
python3 -c "
f = '$tmp/E5/pend2/seed-1/generations.csv'
head, *rows = open(f).read().splitlines()
rows = [r.split(',') for r in rows]
for r in rows: r[6] = repr(7200 / len(rows))  # wall_time_s of each generation
open(f, 'w').write('\\n'.join([head] + [','.join(r) for r in rows]) + '\\n')"
"$S" run $tmp/plan.toml --out $tmp/H $opts --from-export $tmp/E5 --finish-by 1h >$tmp/H.out 2>&1 || fail "--finish-by: $(cat $tmp/H.out)"
grep -q "not starting pend2/seed-2: about 2.0 h, it would end after [0-9:]* (--finish-by)" $tmp/H.out &&
  grep -q "^1 run not started, it would end after [0-9:]* (--finish-by); continue with: .*ahhs-study run --resume $tmp/H" $tmp/H.out &&
  ! grep -q "\] started" $tmp/H.out || fail "--finish-by 1h: $(cat $tmp/H.out)"
"$S" run --resume $tmp/H $opts --finish-by 2.5h >$tmp/H.out 2>&1 && grep -q "started pend2/seed-2" $tmp/H.out &&
  grep -q "^study complete: 4 runs" $tmp/H.out || fail "--finish-by 2.5h: $(cat $tmp/H.out)"
"$S" run --resume $tmp/H $opts --finish-by soon >$tmp/out 2>&1; [[ $? == 2 && $(wc -l <$tmp/out) == 1 ]] &&
  grep -q "finish-by soon: give a time of day HH:MM" $tmp/out || fail "--finish-by soon: $(cat $tmp/out)"
# The exported best genome replays to its stored fitness without the run directory.
best=$(python3 -c "import json;print(repr(json.load(open('$tmp/E/pend1/seed-1/summary.json'))['best_fitness']))")
"$bin/ahhs-replay" --genome $tmp/E/pend1/seed-1/best.json --scenario pendulum --duration 20 >$tmp/out 2>&1 ||
  fail "replay of an exported best: $(cat $tmp/out)"
grep -q "reproduced exactly" $tmp/out || fail "exported best does not reproduce ($best): $(cat $tmp/out)"
# ahhs-report reads exported runs (no database), and their best genomes replay exactly.
if ! ci_tier_only "ahhs-report of an export"; then
"$bin/ahhs-report" $tmp/E/pend1/seed-1 $tmp/E/pend1/seed-2 $tmp/E/pend2/seed-1 -o $tmp/R >$tmp/out 2>&1 ||
  fail "report of an export: $(cat $tmp/out)"
grep -q "reproduced exactly" $tmp/R/summary.md && [[ -s $tmp/R/box_best.png ]] || fail "report of an export: $(cat $tmp/R/summary.md)"
fi
# A plan that changed a configuration: its exported runs are not taken.
sed 's/^rules = 20$/rules = 21/' $tmp/plan.toml >$tmp/plan2.toml
"$S" run $tmp/plan2.toml --out $tmp/D $opts --from-export $tmp/E >$tmp/D.out 2>&1 || fail "study D: $(cat $tmp/D.out)"
grep -q "pend1/seed-1: not taken, its configuration or physics differs" $tmp/D.out || fail "changed config taken: $(cat $tmp/D.out)"

# --only runs the named configurations now; the others wait. An exported run of other physics
# (sim::PhysicsVersion) is not taken.
"$S" run $tmp/plan.toml --out $tmp/F $opts --only pend1 >$tmp/F.out 2>&1 || fail "--only: $(cat $tmp/F.out)"
[[ $(grep -c started $tmp/F.out) == 2 ]] && ! grep -q "started pend2" $tmp/F.out && grep -q "2 runs of the others wait" $tmp/F.out ||
  fail "--only: $(cat $tmp/F.out)"
"$S" run --resume $tmp/F $opts --only nothing >$tmp/out 2>&1; [[ $? == 2 ]] && grep -q "no such configuration" $tmp/out || fail "--only nothing"
sed -i 's/"physics": "[^"]*"/"physics": "older"/' $tmp/E/pend1/seed-2/summary.json
"$S" run $tmp/plan.toml --out $tmp/G $opts --from-export $tmp/E --only pend1 >$tmp/G.out 2>&1 || fail "G: $(cat $tmp/G.out)"
grep -q "pend1/seed-2: not taken, its configuration or physics differs" $tmp/G.out || fail "other physics taken: $(cat $tmp/G.out)"

echo "== 5. status"
"$S" status $tmp/A >$tmp/status || fail "status"
grep -q "study tiny in $tmp/A: 4 of 4 runs complete, 0 running, 0 failed" $tmp/status || fail "$(cat $tmp/status)"
grep -Eq "^pend1 +2/2" $tmp/status || fail "$(cat $tmp/status)"
! grep -q "^time left" $tmp/status || fail "a complete study has time left: $(cat $tmp/status)"

echo "== 6. report"
if ! ci_tier_only "ahhs-study report"; then
# Of the study directory (its runs read from their summaries, not their databases) and of an
# export: the same numbers.
"$S" report $tmp/A -o $tmp/RA >$tmp/out 2>&1 || fail "report: $(cat $tmp/out)"
grep -q "results.md, results.json and one directory per scenario (4 of 4 runs complete)" $tmp/out || fail "$(cat $tmp/out)"
[[ -s $tmp/RA/results.md && -s $tmp/RA/pendulum/box_best.png && -s $tmp/RA/pendulum/box_robust.png &&
   -s $tmp/RA/pendulum/neighbourhood-pend1/seed-1/neighbourhood.png &&
   -s $tmp/RA/pendulum/neighbourhood-pend1/seed-2/neighbourhood.png &&
   -s $tmp/RA/pendulum/neighbourhood-pend2/seed-2/neighbourhood.png ]] ||
  fail "report files: $(find $tmp/RA | head -30)"
# The paper's claims name the paper's configurations; this plan has none of them.
grep -q "| Pendulum: AHHS2-15 is better than AHHS1-60 | yes, Wilcoxon p < 0.05 (n = 10 AHHS2, 8 AHHS1) | not run yet" $tmp/RA/results.md ||
  fail "claims: $(cat $tmp/RA/results.md)"
grep -q "^Every run's best genome replays to its stored fitness bit for bit with this build (4 of 4)." $tmp/RA/results.md ||
  fail "reproduction: $(cat $tmp/RA/results.md)"
"$S" export $tmp/A $tmp/E2 >/dev/null && "$S" report $tmp/E2 -o $tmp/RE --no-replay >/dev/null 2>&1 || fail "report of an export"
python3 -c "
import json
a, e = (json.load(open(f'$tmp/{d}/results.json'))['configs'] for d in ('RA', 'RE'))
# Mutation neighbourhoods of up to three runs' bests per configuration, the most robust first
# (none with --no-replay); their mutants pooled.
for k, v in a.items():
    starts = [o['run'] for o in v['neighbourhood']['originals']]
    order = sorted(range(v['runs']), key=lambda i: (-v['robust'][i], i))
    assert starts == [s.rsplit('/', 1)[0] + f'/seed-{i + 1}' for s, i in zip(starts, order)], (k, v)
    assert v['neighbourhood']['mutants'] == 35 * v['runs'], v['neighbourhood']
assert all(v['neighbourhood'] is None for v in e.values()), e
assert {k: v['best'] for k, v in a.items()} == {k: v['best'] for k, v in e.items()}, (a, e)
assert a['pend1']['runs'] == 2 and a['pend1']['robustness']['replays'] == 8, a['pend1']
# Every run's best has its robust fitness: the median of its 8 perturbed replays.
assert {k: v['robust'] for k, v in a.items()} == {k: v['robust'] for k, v in e.items()}, (a, e)
for v in a.values():
    runs = v['robustness_runs']
    assert len(v['robust']) == v['runs'] == len(runs) and all(r['replays'] == 8 for r in runs), v
    assert v['robustness'] == runs[v['best'].index(max(v['best']))], v
" || fail "study and export reports differ"
# A best genome this build does not reproduce (here: its stored fitness one part in 1e9 off) is
# named, in results.md, results.json and on stderr.
cp -r $tmp/E2 $tmp/E3
python3 -c "
import json
f = '$tmp/E3/pend2/seed-1/best.json'
g = json.load(open(f)); g['meta']['fitness'] *= 1 + 1e-9; json.dump(g, open(f, 'w'))"
"$S" report $tmp/E3 -o $tmp/R3 --no-replay >$tmp/out 2>&1 || fail "report E3: $(cat $tmp/out)"
grep -q "warning: 1 of 4 runs' best genomes do not replay to their stored fitness" $tmp/out &&
  grep -q "^\*\*1 of 4 runs' best genomes do not replay to their stored fitness with this build\*\* ($tmp/E3/pend2/seed-1)" $tmp/R3/results.md &&
  python3 -c "import json; assert json.load(open('$tmp/R3/results.json'))['replay_differs'] == ['$tmp/E3/pend2/seed-1']" ||
  fail "a best genome not reproduced: $(cat $tmp/out; head -5 $tmp/R3/results.md)"
"$S" report $tmp/A -o $tmp/RA >$tmp/out 2>&1; [[ $? == 2 ]] && grep -q "pass --overwrite" $tmp/out || fail "report over a report: $(cat $tmp/out)"
"$S" report $tmp/A -o $tmp/RA --overwrite --no-replay >/dev/null 2>&1 && [[ ! -e $tmp/RA/pendulum/neighbourhood-pend1 ]] ||
  fail "--overwrite left the old report's files"
"$S" report $tmp -o $tmp/RX >$tmp/out 2>&1; [[ $? == 1 ]] && grep -q "is not a study directory or export" $tmp/out || fail "$(cat $tmp/out)"
fi
echo "PASS"
