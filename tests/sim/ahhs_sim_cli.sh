#!/usr/bin/env bash
# ahhs-sim standalone mode: baseline runs end with "fitness: <value>"; bad input is refused.
set -uo pipefail
sim=${1:?usage: ahhs_sim_cli.sh PATH/TO/ahhs-sim}
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
expect_error() {
  local want=$1; shift
  if "$@" >"$tmp/out" 2>"$tmp/err"; then fail "expected failure: $*"; fi
  grep -qF -- "$want" "$tmp/err" || fail "stderr of '$*' lacks '$want': $(cat "$tmp/err")"
}
"$sim" --help >/dev/null || fail --help
out=$("$sim" --scenario pendulum --drive zero --seed 3) || fail "pendulum run"
last=$(tail -1 <<<"$out")
[[ $last =~ ^fitness:\ (-?[0-9.e+-]+)$ ]] || fail "last line is not 'fitness: <value>': $last"
awk -v f="${BASH_REMATCH[1]}" 'BEGIN { exit !(f > -1e-9 && f < 1e-9) }' || fail "hanging pendulum should score 0: $last"
out=$("$sim" --scenario gait --drive wave --modules 3 --duration 5 --docking fixed --seed 2) || fail "gait run"
[[ $(tail -1 <<<"$out") =~ ^fitness:\ [0-9.e+-]+$ ]] || fail "gait last line"
# --joints, the old name of --docking, works for one release and says so; not both at once.
old=$("$sim" --scenario gait --drive wave --modules 3 --duration 5 --joints fixed --seed 2 2>"$tmp/err") ||
  fail "--joints: $(cat "$tmp/err")"
[[ $(tail -1 <<<"$old") == $(tail -1 <<<"$out") ]] || fail "--joints fixed differs from --docking fixed"
grep -qx "ahhs-sim: --joints is deprecated and will go; use --docking" "$tmp/err" || fail "--joints: $(cat "$tmp/err")"
"$sim" --drive zero --joints fixed --docking fixed >/dev/null 2>&1
[[ $? == 2 ]] || fail "--joints with --docking is not a usage error"
a=$("$sim" --scenario gait --drive wave --duration 3 --seed 9 | tail -1)
b=$("$sim" --scenario gait --drive wave --duration 3 --seed 9 | tail -1)
[[ "$a" == "$b" ]] || fail "same seed, different fitness: $a vs $b"
expect_error "unknown scenario 'walker'" "$sim" --drive zero --scenario walker
expect_error "--duration must be a positive" "$sim" --drive zero --duration -5
expect_error "--duration must be a positive" "$sim" --drive zero --duration 0
expect_error "at least 2 modules" "$sim" --drive zero --modules 1
expect_error "unknown docking" "$sim" --drive zero --docking wobbly
expect_error "unknown drive" "$sim" --drive dance
expect_error "--drive swingup is not defined for the gait scenario" "$sim" --drive swingup
expect_error "--drive inchworm is not defined for the pendulum scenario" "$sim" --scenario pendulum --drive inchworm
# The designed swing-up turns the pendulum over the top; the behaviour line says so.
out=$("$sim" --scenario pendulum --drive swingup --seed 1) || fail "swing-up run"
[[ $out =~ behaviour:\ bob\ above\ the\ pivot\ in\ [0-9.]+\ %\ of\ ticks,\ ([0-9]+)\ passes\ over\ the\ top ]] ||
  fail "no pendulum behaviour line: $out"
(( BASH_REMATCH[1] >= 10 )) || fail "the swing-up passed the top only ${BASH_REMATCH[1]} times"
out=$("$sim" --scenario gait --drive zero) || fail "zero gait run"
grep -q "^behaviour: commands constant after 5 s; inside" <<<"$out" || fail "gait behaviour line: $out"
expect_error "--modules" "$sim" --drive zero --modules five
expect_error "--seed" "$sim" --drive zero --seed -x
expect_error "cannot open LCM bus" "$sim" --lcm-url "nosuch://x"
expect_error "--state-rate" "$sim" --state-rate -1
expect_error "--state-rate" "$sim" --state-rate fast
echo "ahhs-sim: all checks passed"
