#!/usr/bin/env bash
# ahhs-report's commands that only replay (no bus): mutation neighbourhoods of a run and of a
# genome file, the physics step judged by post-evaluated distributions, and the random pendulum
# genomes of docs/results.md, on the runs of the report:runs fixture. Python over ahhs-replay's
# files, so the Release pass only (the sanitizer pass runs ahhs-replay --mutants and
# --physics-step in report:replay-and-figures).
bin=${1:?usage: report_steps_test.sh BIN_DIR RUNS_DIR}
runs=${2:?usage: report_steps_test.sh BIN_DIR RUNS_DIR (report:runs makes it)}
source "${AHHS_SOURCE_DIR:?}/tests/lib.sh"
ci_tier_only "ahhs-report neighbourhood and steps" && exit 77
ahhs_netns "$0" "$@"
ahhs_scratch 'ahhs-replay'
cp -r "$runs"/. $tmp/ || fail "no runs in $runs (the report:runs fixture makes them)"

echo "== neighbourhood"
"$bin/ahhs-report" neighbourhood $tmp/a2-1 --mutants 6 -o $tmp/nb >$tmp/nb.out 2>&1 || { cat $tmp/nb.out; fail "neighbourhood"; }
[[ -s $tmp/nb/neighbourhood.png && -s $tmp/nb/neighbourhood.svg && -s $tmp/nb/controller.png ]] || fail "neighbourhood figures"
[[ $(wc -l <$tmp/nb/mutants.csv) == 8 ]] || fail "mutants.csv: $(cat $tmp/nb/mutants.csv)"
"$bin/ahhs-genome" random --variant ahhs1 --hormones 4 --rules 6 --sensors 10 --actuators 2 --seed 3 >$tmp/g.json
"$bin/ahhs-report" neighbourhood $tmp/g.json --scenario pendulum --duration 5 --mutants 3 -o $tmp/nb2 >/dev/null 2>&1 || fail "neighbourhood of a genome file"
[[ -s $tmp/nb2/neighbourhood.png ]] || fail "neighbourhood of a genome file: figure"
# With the physics a genome was evolved with (the first study's damped docking, dWorldStep): its
# original is its stored fitness to the last digit printed.
knife=$AHHS_SOURCE_DIR/tests/episode/data/knife-edge-damped-ahhs1-120.json
"$bin/ahhs-report" neighbourhood $knife --scenario gait --docking damped --seed 295761112068970292 \
  --physics 2026-12-01.2 --mutants 1 -o $tmp/nb3 >$tmp/nb3.out 2>&1 || { cat $tmp/nb3.out; fail "neighbourhood --physics"; }
grep -q "^original,2.7359187058763337," $tmp/nb3/mutants.csv || fail "neighbourhood --physics: $(cat $tmp/nb3/mutants.csv)"

echo "== steps: the physics step judged by post-evaluated distributions"
# A run directory (its best, with the run's own physics, duration and envelope), then a genome
# file with a named physics.
"$bin/ahhs-report" steps $tmp/gait --episodes 2 --jobs 2 -o $tmp/steps >$tmp/steps.out 2>&1 ||
  { cat $tmp/steps.out; fail "steps"; }
# One row per step, the damped docking's step (6.25 ms) and twice it judged against half of it.
[[ $(grep -c "/gait," $tmp/steps/steps.csv) == 3 ]] || fail "steps.csv: $(cat $tmp/steps/steps.csv)"
grep -q "^| genome | 3.125 ms: median (quartiles), over the wall | 6.25 ms: " $tmp/steps/summary.md &&
  grep -Eq "^- 6.25 ms: (passes|does not pass)$" $tmp/steps/summary.md &&
  grep -Eq "^- 12.5 ms: (passes|does not pass)$" $tmp/steps/summary.md || fail "steps summary: $(cat $tmp/steps/summary.md)"
# With a named physics; each verdict with the paired bootstrap interval of the difference.
"$bin/ahhs-report" steps $knife --episodes 3 --jobs 2 --physics 2026-12-04 -o $tmp/steps3 >$tmp/steps3.out 2>&1 ||
  { cat $tmp/steps3.out; fail "steps --physics"; }
grep -q "damped docking, physics 2026-12-04, at 3.125 ms" $tmp/steps3/summary.md &&
  grep -Eq "\((agrees|differs); [+-][0-9.]+ to [+-][0-9.]+\)" $tmp/steps3/summary.md ||
  fail "steps --physics: $(cat $tmp/steps3/summary.md)"
# (--joints, the old name of --docking, still works for one release and says so.)
"$bin/ahhs-report" steps $tmp/nothing.json --joints fixed -o $tmp/steps2 >$tmp/err 2>&1 && fail "steps of a missing genome"
grep -q "no such genome file or run directory" $tmp/err && ! grep -q Traceback $tmp/err ||
  fail "steps of a missing genome: $(cat $tmp/err)"
grep -qx "ahhs-report steps: --joints is deprecated and will go; use --docking" $tmp/err ||
  fail "steps --joints: $(cat $tmp/err)"

echo "== the random pendulum genomes of docs/results.md (1 per setting)"
"$AHHS_SOURCE_DIR/studies/paper-2010-random-genomes.py" "$bin" --count 1 >$tmp/random.md 2>&1 ||
  fail "random genomes: $(cat $tmp/random.md)"
# A header, a rule and seven settings, each with 1 genome scored.
[[ $(grep -c "^| .* | [01] of 1 | " $tmp/random.md) == 7 && $(wc -l <$tmp/random.md) == 9 ]] ||
  fail "random genomes table: $(cat $tmp/random.md)"

echo "== the pendulum behaviour table of docs/results.md (one exported run per configuration)"
for v in ahhs1-60 ahhs2-15; do
  mkdir -p $tmp/study/pendulum-$v/seed-1
  cp "$AHHS_SOURCE_DIR/tests/fixtures/genomes/pendulum-$v-seed1.json" $tmp/study/pendulum-$v/seed-1/best.json
  echo '{}' >$tmp/study/pendulum-$v/seed-1/summary.json
done
"$AHHS_SOURCE_DIR/studies/pendulum-behaviour.py" "$bin" $tmp/study >$tmp/behaviour.md 2>&1 ||
  fail "pendulum behaviour: $(cat $tmp/behaviour.md)"
# The AHHS1-60 best (0.666) keeps its cart at the left wall and spins the pendulum (docs/results.md).
grep -Eq '^\| pendulum-ahhs1-60 \| 1 \| 0\.666 \| [6-9][0-9] % \([0-9]+-[0-9]+ %\) \| 1 \| [67][0-9] % \| [1-9][0-9] \|$' $tmp/behaviour.md &&
  grep -q '^| pendulum-ahhs2-15 | 1 | ' $tmp/behaviour.md || fail "pendulum behaviour table: $(cat $tmp/behaviour.md)"

echo "== judge: a robust best under other steps, command delays and bent starts (2 held-out episodes)"
# The robust study's fixed AHHS2-20 seed-4 export: its stored episodes replay bit for bit at the
# scenario's step (or judge fails), and the genome's results go to the cache; a second report
# replays nothing.
robust=$AHHS_SOURCE_DIR/studies/paper-2010-robust/gait-fixed-ahhs2-20/seed-4
"$bin/ahhs-report" judge $robust --episodes 2 --jobs 2 --cache $tmp/jc -o $tmp/judge >$tmp/judge.out 2>&1 ||
  { cat $tmp/judge.out; fail "judge"; }
grep -q "^judging paper-2010-robust/gait-fixed-ahhs2-20/seed-4 (1 of 1)$" $tmp/judge.out || fail "judge: $(cat $tmp/judge.out)"
[[ -s $tmp/jc/6f5ce62da9d23dd2-2026-12-05-2.json ]] || fail "judge cache: $(ls $tmp/jc)"
grep -Eq '^\| paper-2010-robust/gait-fixed-ahhs2-20/seed-4 \| ([0-9.]+ \([0-9.]+ / [0-9.]+\), 0% \| ){4}(yes|\*\*no\*\*) \([+-][0-9.]+ to [+-][0-9.]+\) \|' $tmp/judge/judged.md ||
  fail "judge table: $(cat $tmp/judge/judged.md)"
[[ $(wc -l <$tmp/judge/judged.csv) == 9 ]] || fail "judged.csv: $(cat $tmp/judge/judged.csv)"
"$bin/ahhs-report" judge $robust --episodes 2 --cache $tmp/jc -o $tmp/judge --overwrite >$tmp/judge.out 2>&1 &&
  ! grep -q "^judging" $tmp/judge.out || fail "judge from its cache: $(cat $tmp/judge.out)"

echo "== bad input"
"$bin/ahhs-report" neighbourhood $tmp/nothing.json -o $tmp/x >$tmp/err 2>&1 && fail "missing genome accepted"
grep -q "no such genome file" $tmp/err || fail "missing genome message: $(cat $tmp/err)"
echo "PASS"
