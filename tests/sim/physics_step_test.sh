#!/usr/bin/env bash
# The gait's physics steps are fine enough for what evolution finds: an evolved gait's robust
# fitness (the median over replays with the friction scaled by 0.975..1.025, ahhs-replay
# --robustness) agrees at the task's step and at half of it. A single replay cannot tell: evolved
# bests are knife-edges of deterministic chaos, and 1 % more friction changes them as much as a
# finer step (docs/findings.md, "Physics step and deterministic chaos"). The chain solver's robust
# medians agree with dWorldStep's the same way.
bin=${1:?usage: physics_step_test.sh BIN_DIR}
source "${AHHS_SOURCE_DIR:?}/tests/lib.sh"
ahhs_scratch
R="$bin/ahhs-replay"
fixed=$AHHS_SOURCE_DIR/tests/fixtures/genomes/gait-fixed-ahhs2-20-seed1.json  # evolved at 12.5 ms
damped=$AHHS_SOURCE_DIR/tests/sim/data/gait-damped-ahhs2-30-evolved.json        # evolved at 12.5 ms
die() { echo "FAIL: $*" >&2; exit 1; }  # inside $(...)
# median NAME JOINTS GENOME STEP [OPTION...]: the robust median of GENOME at physics step STEP (s).
median() {
  "$R" --genome "$3" --joints "$2" --physics-step "$4" "${@:5}" --robustness 8 --robustness-csv $tmp/$1.csv \
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
"$R" --genome $fixed --joints fixed --robustness 8 >$tmp/knife.out 2>&1 || fail "$(cat $tmp/knife.out)"
grep -q "reproduced exactly" $tmp/knife.out &&
  grep -q "this fitness 2.118 is above every perturbed replay: a knife-edge" $tmp/knife.out ||
  fail "$(cat $tmp/knife.out)"

echo "== fixed docking: 12.5 ms (the task's) agrees with 6.25 ms"
f1=$(median fixed-12 fixed $fixed 0.0125) || exit 1
f2=$(median fixed-6 fixed $fixed 0.00625) || exit 1
echo "robust medians: 12.5 ms $f1, 6.25 ms $f2"
close $f1 $f2 0.1 || fail "fixed docking: robust median $f1 at 12.5 ms, $f2 at 6.25 ms"

echo "== damped docking: 6.25 ms (the task's) agrees with 3.125 ms; 12.5 ms did not"
d1=$(median damped-12 damped $damped 0.0125) || exit 1
d2=$(median damped-6 damped $damped 0.00625) || exit 1
d3=$(median damped-3 damped $damped 0.003125) || exit 1
echo "robust medians: 12.5 ms $d1, 6.25 ms $d2, 3.125 ms $d3"
close $d2 $d3 0.2 || fail "damped docking: robust median $d2 at 6.25 ms, $d3 at 3.125 ms"
# The check can tell: at 12.5 ms this gait reached the wall robustly, at finer steps it does not.
! close $d1 $d2 0.2 || fail "damped docking: 12.5 ms ($d1) should differ from 6.25 ms ($d2)"

echo "== the chain solver (the same model, solved by the chain's structure) agrees with dWorldStep"
c2=$(median damped-6-chain damped $damped 0.00625 --solver chain) || exit 1
c1=$(median fixed-12-chain fixed $fixed 0.0125 --solver chain) || exit 1
echo "robust medians with the chain solver: damped $c2 (dWorldStep $d2), fixed $c1 (dWorldStep $f1)"
close $d2 $c2 0.2 || fail "damped docking: robust median $c2 with the chain solver, $d2 without"
close $f1 $c1 0.1 || fail "fixed docking: robust median $c1 with the chain solver, $f1 without"

echo "== bad options"
"$R" --genome $fixed --joints fixed --robustness-csv $tmp/x.csv >$tmp/out 2>&1
[[ $? == 1 ]] && grep -q "robustness-csv needs --robustness N" $tmp/out || fail "$(cat $tmp/out)"
"$R" --genome $fixed --joints fixed --friction-scale 0 >$tmp/out 2>&1
[[ $? == 2 ]] || fail "--friction-scale 0: $(cat $tmp/out)"
"$R" --genome $fixed --joints fixed --solver quick >$tmp/out 2>&1
[[ $? == 2 ]] && grep -q "solver" $tmp/out || fail "--solver quick: $(cat $tmp/out)"
echo PASS
