#!/usr/bin/env bash
# ahhs-replay and ahhs-report on the small real runs of the report:runs fixture (in a private
# network namespace of its own): the replay reproduces the stored fitness and records every tick
# in an LCM log; every figure of the report exists and is not empty; bad input gives a clear
# message and a non-zero exit.
bin=${1:?usage: report_test.sh BIN_DIR RUNS_DIR}
source "${AHHS_SOURCE_DIR:?}/tests/lib.sh"
ahhs_netns "$0" "$@"
runs=${2:?usage: report_test.sh BIN_DIR RUNS_DIR (report:runs makes it)}
ahhs_scratch 'ahhs-replay|ahhs-logger'
cp -r "$runs"/. $tmp/ || fail "no runs in $runs (the report:runs fixture makes them)"

echo "== ahhs-replay reproduces stored fitness"
for r in a2-1 a1-2 gait; do
  "$bin/ahhs-replay" $tmp/$r --log $tmp/$r.lcm >$tmp/replay.out 2>&1 || { cat $tmp/replay.out; fail "replay $r"; }
  grep -q "reproduced exactly" $tmp/replay.out || fail "replay $r: $(cat $tmp/replay.out)"
done
"$bin/ahhs-replay" $tmp/a2-1 --generation 2 --individual 5 >$tmp/replay.out || fail "replay of one individual"
stored=$(sqlite3 $tmp/a2-1/run.sqlite "SELECT printf('%!.17g', fitness) FROM individuals WHERE generation = 2 AND idx = 5")
grep -q "reproduced exactly" $tmp/replay.out || fail "individual: $(cat $tmp/replay.out)"
[[ "$(tail -1 $tmp/replay.out)" == "fitness: $stored" ]] || fail "individual fitness $(tail -1 $tmp/replay.out) vs $stored"
# The log holds every tick of every module: 300 ticks x 2 modules of TRACE, SENSORS and HINGE.
"$bin/log_check" $tmp/a2-1.lcm --arena AHHS --modules 2 --ticks 300 --trace >$tmp/count.out 2>&1 ||
  { cat $tmp/count.out; fail "log_check"; }
grep -q "600 trace (module, tick) pairs; 0 incomplete" $tmp/count.out || fail "trace in the log: $(cat $tmp/count.out)"
"$bin/log_check" $tmp/gait.lcm --arena AHHS --modules 5 --ticks 60 --trace >/dev/null || fail "gait log"

# --physics-step: the docking's own step (damped docking: 6.25 ms) reproduces the stored fitness; another one is a check of
# how much a behaviour depends on the discretisation, and says so.
"$bin/ahhs-replay" $tmp/gait --physics-step 0.00625 >$tmp/out 2>&1 && grep -q "reproduced exactly" $tmp/out ||
  fail "--physics-step 0.00625 (the docking's): $(cat $tmp/out)"
"$bin/ahhs-replay" $tmp/gait --physics-step 0.0025 >$tmp/out 2>&1 || fail "--physics-step 0.0025: $(cat $tmp/out)"
grep -Eq "reproduced exactly|in the changed physics \(--physics-step, --friction-scale, --envelope, --physics\) the replay differs by" $tmp/out || fail "$(cat $tmp/out)"
"$bin/ahhs-replay" $tmp/gait --physics-step 1 >$tmp/out 2>&1; [[ $? == 2 ]] || fail "--physics-step 1 accepted"
# --mutants (what ahhs-report neighbourhood runs): the C++ part, in every tier.
"$bin/ahhs-replay" $tmp/a2-1 --mutants 3 --mutants-csv $tmp/mutants.csv >/dev/null 2>&1 || fail "replay --mutants"
[[ $(wc -l <$tmp/mutants.csv) == 5 ]] || fail "mutants.csv: $(cat $tmp/mutants.csv)"

if ! ci_tier_only "ahhs-report (figures)"; then
echo "== ahhs-report"
"$bin/ahhs-report" $tmp/a2-{1,2,3} $tmp/a1-{1,2,3} $tmp/gait -o $tmp/report >$tmp/report.out 2>&1 ||
  { cat $tmp/report.out; fail "ahhs-report"; }
for f in fitness box_best box_speed hormones trace sensors rules controller; do
  for ext in png svg; do
    [[ -s $tmp/report/$f.$ext ]] || fail "missing or empty: $f.$ext"
  done
done
# Every run is a point over its configuration's box: 3 + 3 pendulum runs and the gait's one.
python3 - $tmp/report/box_best.svg <<'PY' || fail "box_best.svg: not a point per run"
import sys, xml.etree.ElementTree as ET
svg = "{http://www.w3.org/2000/svg}"
runs = {g.get("id"): len(g.findall(".//" + svg + "use"))
        for g in ET.parse(sys.argv[1]).iter(svg + "g") if (g.get("id") or "").startswith("runs-")}
assert sorted(runs.values()) == [1, 3, 3], runs
PY
[[ -s $tmp/report/controller.dot && -s $tmp/report/replay.lcm && -s $tmp/report/replay-trace.csv ]] || fail "replay files"
grep -q "cart_x,pole_angle" $tmp/report/replay-body.csv || fail "the pendulum's body trace"
[[ ! -e $tmp/report/hinges.png ]] || fail "a hinge panel for the pendulum"
# A controller graph draws only rule parts that triggered, weighted by how often.
grep -q 'penwidth=' $tmp/report/controller.dot || fail "controller edges without activity weights"
"$bin/ahhs-report" $tmp/gait -o $tmp/report-gait >/dev/null 2>&1 || fail "gait report"
[[ -s $tmp/report-gait/hinges.png && ! -e $tmp/report-gait/trace.png ]] || fail "gait figures: $(ls $tmp/report-gait)"
grep -q "centroid_x,centroid_y" $tmp/report-gait/replay-body.csv || fail "the gait's body trace"
grep -q "^### How it moves" $tmp/report-gait/summary.md || fail "no motion table: $(cat $tmp/report-gait/summary.md)"
# A run with a held-out post-evaluation: the report replays the episode nearest its median, the
# stored fitness bit for bit, and says how the hinges move (a run directory's post-eval.json, and
# an exported best of the robust study).
cp -r $tmp/gait $tmp/gait-post
"$bin/ahhs-replay" $tmp/gait-post --post-eval 3 --post-eval-json $tmp/gait-post/post-eval.json >/dev/null 2>&1 ||
  fail "post-evaluation of the gait run"
robust=$AHHS_SOURCE_DIR/studies/paper-2010-robust/gait-fixed-ahhs2-20/seed-4
for r in $tmp/gait-post $robust; do
  post=$r/post-eval.json; [[ -e $post ]] || post=$r/summary.json
  seed=$(/usr/bin/python3 -c "import json,sys; p=json.load(open(sys.argv[1])); p=p.get('post_eval', p)
e=sorted((e for e in p['per_episode'] if e['fitness'] is not None), key=lambda e: e['fitness'])
print(e[len(e) // 2]['seed'])" $post)
  "$bin/ahhs-report" $r -o $tmp/report-post >$tmp/out 2>&1 || fail "report of $r: $(cat $tmp/out)"
  grep -q "held-out episode $seed, the one nearest the median .*, the stored one bit for bit" \
    $tmp/report-post/summary.md || fail "$r: not the median episode $seed: $(cat $tmp/report-post/summary.md)"
  grep -q "^- what \`ahhs-replay\` says the episode did: .*module halves beyond the wall.*; moved " \
    $tmp/report-post/summary.md || fail "$r: no behaviour line: $(cat $tmp/report-post/summary.md)"
  [[ $(grep -cE '^\| [0-4] \| -?[0-9]+\.[0-9] \|' $tmp/report-post/summary.md) == 5 ]] ||
    fail "$r: a hinge row per module: $(cat $tmp/report-post/summary.md)"
  rm -rf $tmp/report-post
done
# A replay that does not give the stored fitness is an error, not a report of another episode.
/usr/bin/python3 -c "import json,sys; p=json.load(open(sys.argv[1]))
for e in p['per_episode']: e['fitness'] = 0.123
json.dump(p, open(sys.argv[1], 'w'))" $tmp/gait-post/post-eval.json
"$bin/ahhs-report" $tmp/gait-post -o $tmp/report-post >$tmp/out 2>&1 && fail "a wrong stored fitness was reported"
grep -q "the run stored 0.123: another build or physics?" $tmp/out || fail "mismatch message: $(cat $tmp/out)"
grep -q "reproduced exactly" $tmp/report/summary.md || fail "summary lacks the replay check"
grep -q "| pendulum AHHS2-8 | pendulum AHHS1-12 | 3 | 3 |" $tmp/report/summary.md || fail "summary lacks the Wilcoxon table: $(cat $tmp/report/summary.md)"
[[ "$(head -c 4 $tmp/report/fitness.png | tail -c 3)" == PNG ]] || fail "fitness.png is not a PNG"
echo "summary: $(wc -l <$tmp/report/summary.md) lines"
# An old report is replaced only when asked, and then wholly (no stale figure stays).
"$bin/ahhs-report" $tmp/a2-1 -o $tmp/report --no-replay >$tmp/out 2>&1; rc=$?
[[ $rc == 2 ]] && grep -q "pass --overwrite" $tmp/out || fail "report into an old report: $rc $(cat $tmp/out)"
"$bin/ahhs-report" $tmp/a2-1 -o $tmp/report --no-replay --overwrite >$tmp/out 2>&1 || fail "--overwrite: $(cat $tmp/out)"
[[ ! -e $tmp/report/replay.lcm && -s $tmp/report/fitness.png ]] || fail "--overwrite left stale files"
mkdir $tmp/mine && echo x >$tmp/mine/notes.txt
"$bin/ahhs-report" $tmp/a2-1 -o $tmp/mine --no-replay --overwrite >$tmp/out 2>&1; rc=$?
[[ $rc == 2 && -s $tmp/mine/notes.txt ]] || fail "a foreign directory was emptied: $rc $(cat $tmp/out)"
"$bin/ahhs-replay" $tmp/a2-1 --log $tmp/a2-1.lcm >$tmp/out 2>&1; rc=$?
[[ $rc == 2 ]] && grep -q "a2-1.lcm exists; pass --overwrite" $tmp/out || fail "replay --log over a file: $rc $(cat $tmp/out)"
"$bin/ahhs-replay" $tmp/a2-1 --log $tmp/a2-1.lcm --overwrite >/dev/null 2>&1 || fail "replay --log --overwrite"

fi

echo "== bad input"
mkdir $tmp/notrun
"$bin/ahhs-report" $tmp/notrun -o $tmp/x >$tmp/err 2>&1 && fail "a non-run was accepted"
grep -q "is not a run directory" $tmp/err || fail "non-run message: $(cat $tmp/err)"
mkdir $tmp/corrupt && head -c 4096 /dev/urandom >$tmp/corrupt/run.sqlite
"$bin/ahhs-report" $tmp/corrupt -o $tmp/x >$tmp/err 2>&1 && fail "a corrupt database was accepted"
grep -q "not a readable run database" $tmp/err || fail "corrupt message: $(cat $tmp/err)"
grep -q Traceback $tmp/err && fail "a traceback instead of a message"
"$bin/ahhs-replay" $tmp/corrupt >$tmp/err 2>&1 && fail "replay of a corrupt run"
grep -q "not a readable run database" $tmp/err || fail "replay corrupt message: $(cat $tmp/err)"
"$bin/ahhs-replay" $tmp/a2-1 --generation 99 >$tmp/err 2>&1 && fail "replay of a missing generation"
grep -q "is not stored" $tmp/err || fail "missing generation message: $(cat $tmp/err)"
echo "PASS"
