#!/usr/bin/env bash
# The gait's physics steps are fine enough for what evolution finds: an evolved gait's robust
# fitness (the median over replays with the friction scaled by 0.975..1.025, ahhs-replay
# --robustness) agrees at the docking's step and at half of it. A single replay cannot tell: evolved
# bests are knife-edges of deterministic chaos, and 1 % more friction changes them as much as a
# finer step (docs/findings.md, "Physics step and deterministic chaos"). The physics of 2026-12-05
# (the chain solver, warm-started), of 2026-12-04 (the chain solver) and of 2026-12-01
# (dWorldStep) agree the same way.
bin=${1:?usage: physics_step_test.sh BIN_DIR}
source "${AHHS_SOURCE_DIR:?}/tests/lib.sh"
ahhs_scratch
R="$bin/ahhs-replay"
fixed=$AHHS_SOURCE_DIR/tests/fixtures/genomes/gait-fixed-ahhs2-20-seed1.json  # evolved at 12.5 ms
damped=$AHHS_SOURCE_DIR/tests/sim/data/gait-damped-ahhs2-30-evolved.json        # evolved at 12.5 ms
die() { echo "FAIL: $*" >&2; exit 1; }  # inside $(...)
# median NAME JOINTS GENOME STEP [OPTION...]: the robust median of GENOME at physics step STEP (s).
median() {
  "$R" --genome "$3" --docking "$2" --physics-step "$4" "${@:5}" --robustness 8 --robustness-csv $tmp/$1.csv \
    >$tmp/$1.out 2>&1 || die "$1: $(cat $tmp/$1.out)"
  python3 -c "
import csv, statistics
rows = list(csv.DictReader(open('$tmp/$1.csv')))
assert len(rows) == 8 and all(r['fitness'] != 'failed' for r in rows), rows
assert 1.0 not in [float(r['friction_scale']) for r in rows]
print(statistics.median(float(r['fitness']) for r in rows))" || die "$1: $(cat $tmp/$1.csv)"
}
close() { python3 -c "import sys; sys.exit(0 if abs($1 - $2) <= $3 else 1)"; }

echo "== the best of an evolution is a knife-edge; its perturbed replays say so"
"$R" --genome $fixed --docking fixed --robustness 8 >$tmp/knife.out 2>&1 || fail "$(cat $tmp/knife.out)"
grep -q "reproduced exactly" $tmp/knife.out &&
  grep -q "this fitness 2.118 is above every perturbed replay: a knife-edge" $tmp/knife.out ||
  fail "$(cat $tmp/knife.out)"

echo "== a genome file that names its run's configuration replays in that run's docking"
"$R" --genome $fixed >$tmp/own.out 2>&1 || fail "$(cat $tmp/own.out)"
grep -q "reproduced exactly" $tmp/own.out || fail "without --docking: $(cat $tmp/own.out)"

# The rest repeats that replay path with other steps and physics, for its numbers.
if ! ci_tier_only "the step and physics comparisons (seven more robust medians)"; then
echo "== fixed docking: 12.5 ms (the docking's) agrees with 6.25 ms"
f1=$(median fixed-12 fixed $fixed 0.0125) || exit 1
f2=$(median fixed-6 fixed $fixed 0.00625) || exit 1
echo "robust medians: 12.5 ms $f1, 6.25 ms $f2"
close $f1 $f2 0.1 || fail "fixed docking: robust median $f1 at 12.5 ms, $f2 at 6.25 ms"

echo "== damped docking: 6.25 ms (the docking's) agrees with 3.125 ms; 12.5 ms did not"
d1=$(median damped-12 damped $damped 0.0125) || exit 1
d2=$(median damped-6 damped $damped 0.00625) || exit 1
d3=$(median damped-3 damped $damped 0.003125) || exit 1
echo "robust medians: 12.5 ms $d1, 6.25 ms $d2, 3.125 ms $d3"
close $d2 $d3 0.2 || fail "damped docking: robust median $d2 at 6.25 ms, $d3 at 3.125 ms"
# The check can tell: at 12.5 ms this gait reached the wall robustly, at finer steps it does not.
! close $d1 $d2 0.2 || fail "damped docking: 12.5 ms ($d1) should differ from 6.25 ms ($d2)"

echo "== the physics of 2026-12-05 and 2026-12-04 (the chain solver) agree with that of 2026-12-01 (dWorldStep)"
# The fixed genome names the physics it was evolved with (2026-12-01); the damped one does not,
# so its medians above are this build's (2026-12-05).
c1=$(median fixed-12-chain fixed $fixed 0.0125 --physics 2026-12-04) || exit 1
c2=$(median fixed-12-warm fixed $fixed 0.0125 --physics 2026-12-05) || exit 1
o2=$(median damped-6-ode damped $damped 0.00625 --physics 2026-12-01.2) || exit 1
echo "robust medians: fixed $f1 (2026-12-01), $c1 (2026-12-04) and $c2 (2026-12-05); damped $o2 (2026-12-01.2) and $d2 (2026-12-05)"
close $f1 $c1 0.1 || fail "fixed docking: robust median $c1 in the physics of 2026-12-04, $f1 in 2026-12-01"
close $f1 $c2 0.1 || fail "fixed docking: robust median $c2 in the physics of 2026-12-05, $f1 in 2026-12-01"
close $o2 $d2 0.2 || fail "damped docking: robust median $d2 in the physics of 2026-12-05, $o2 in 2026-12-01.2"
fi

echo "== bad options"
"$R" --genome $fixed --docking fixed --robustness-csv $tmp/x.csv >$tmp/out 2>&1
[[ $? == 1 ]] && grep -q "robustness-csv needs --robustness N" $tmp/out || fail "$(cat $tmp/out)"
"$R" --genome $fixed --docking fixed --friction-scale 0 >$tmp/out 2>&1
[[ $? == 2 ]] || fail "--friction-scale 0: $(cat $tmp/out)"
"$R" --genome $fixed --docking fixed --physics 2026-11-22 >$tmp/out 2>&1
[[ $? == 1 ]] && grep -q "physics: this build simulates the gait physics of 2026-12-05, 2026-12-04, 2026-12-01, not 2026-11-22" $tmp/out ||
  fail "--physics 2026-11-22: $(cat $tmp/out)"
echo PASS
