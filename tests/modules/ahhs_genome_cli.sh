#!/usr/bin/env bash
# ahhs-genome end to end: every subcommand works, is deterministic, and refuses bad input with a
# message and a non-zero exit.
set -uo pipefail
tool=${1:?usage: ahhs_genome_cli.sh PATH/TO/ahhs-genome}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
expect_error() {  # expect_error "text in stderr" command...
  local want=$1; shift
  if "$@" >"$tmp/out" 2>"$tmp/err"; then fail "expected failure: $*"; fi
  grep -qF -- "$want" "$tmp/err" || fail "stderr of '$*' lacks '$want': $(cat "$tmp/err")"
  [[ ! -s "$tmp/out" ]] || fail "'$*' failed but still printed to stdout"
}

for sub in random mutate crossover validate show run to-vector from-vector; do
  "$tool" "$sub" --help >/dev/null || fail "$sub --help"
done

"$tool" random --variant ahhs2 --hormones 5 --rules 30 --sensors 4 --actuators 1 --seed 7 >"$tmp/a.json" || fail random
"$tool" random --variant ahhs2 --hormones 5 --rules 30 --sensors 4 --actuators 1 --seed 7 >"$tmp/a2.json"
cmp -s "$tmp/a.json" "$tmp/a2.json" || fail "same seed, different genome"
"$tool" random --variant ahhs2 --hormones 5 --rules 30 --sensors 4 --actuators 1 --seed 8 >"$tmp/b.json"
cmp -s "$tmp/a.json" "$tmp/b.json" && fail "different seeds, same genome"
"$tool" validate "$tmp/a.json" | grep -q "valid ahhs2 genome, 5 hormones, 30 rules" || fail validate
"$tool" show "$tmp/a.json" | grep -q "^29 " || fail "show lists rule 29"
"$tool" random --variant ahhs1 --rules 60 --hormones 15 --sensors 10 --actuators 2 --seed 1 >"$tmp/c.json"
"$tool" show "$tmp/c.json" | grep -qE "^59 +(idle|sensor|hormone|actuator)" || fail "show ahhs1"

"$tool" mutate "$tmp/a.json" --seed 3 >"$tmp/m.json" || fail mutate
"$tool" validate "$tmp/m.json" >/dev/null || fail "mutant invalid"
cmp -s "$tmp/a.json" "$tmp/m.json" && fail "mutant equals parent"
"$tool" mutate "$tmp/a.json" --seed 3 --count 5 | grep -c '"format": "ahhs-genome"' | grep -qx 5 || fail "mutate --count 5"
"$tool" crossover "$tmp/a.json" "$tmp/b.json" --seed 4 | grep -c '"format": "ahhs-genome"' | grep -qx 2 || fail crossover
expect_error "differ in variant or size" "$tool" crossover "$tmp/a.json" "$tmp/c.json" --seed 1

# Genome vectors: the round trip gives the same genome (hash); a vector from stdin; bad vectors.
for g in a c; do
  "$tool" to-vector "$tmp/$g.json" >"$tmp/$g.vec" || fail "to-vector $g"
  "$tool" from-vector "$tmp/$g.vec" >"$tmp/$g.back" || fail "from-vector $g"
  [[ "$("$tool" validate "$tmp/$g.back" | sed 's/.*hash //')" == "$("$tool" validate "$tmp/$g.json" | sed 's/.*hash //')" ]] ||
    fail "vector round trip of $g changed the genome"
done
grep -q '"rules\[29\].actuator"' "$tmp/a.vec" || fail "to-vector names"
"$tool" from-vector - <"$tmp/c.vec" | cmp -s - "$tmp/c.back" || fail "from-vector from stdin"
printf "tick,x\n" >"$tmp/text.vec"
expect_error "not JSON" "$tool" from-vector "$tmp/text.vec"
echo '{"format": "ahhs-genome-vector", "version": 1, "shape": {"variant": "ahhs2", "hormones": 1, "rules": 0, "sensors": 1, "actuators": 1}, "x": [0, null, 0]}' >"$tmp/n.vec"
expect_error "genome vector" "$tool" from-vector "$tmp/n.vec"
expect_error "cannot open" "$tool" from-vector "$tmp/none.vec"

# Open-loop run: 2 compartments, sample-and-hold, an empty cell is an absent slot.
printf 'tick,compartment,s0,s1,s2,s3\n0,0,0.1,0.2,,0.4\n0,1,0.5,,0.7,0.8\n5,0,1,1,1,1\n' >"$tmp/s.csv"
"$tool" run "$tmp/a.json" --compartments 2 --sensors "$tmp/s.csv" >"$tmp/run.csv" || fail run
[[ $(head -1 "$tmp/run.csv") == "tick,compartment,h0,h1,h2,h3,h4,a0" ]] || fail "run header"
[[ $(wc -l <"$tmp/run.csv") -eq $((1 + 6 * 2)) ]] || fail "run: ticks 0..5 for 2 compartments"
"$tool" run "$tmp/a.json" --compartments 2 --sensors "$tmp/s.csv" --ticks 20 | tail -n +2 | wc -l | grep -qx 40 || fail "--ticks"
"$tool" run "$tmp/a.json" --compartments 2 --sensors "$tmp/s.csv" | cmp -s - "$tmp/run.csv" || fail "run not deterministic"
awk -F, 'NR > 1 { for (i = 3; i <= 7; i++) if ($i < 0 || $i > 1) exit 1; if ($8 < -1 || $8 > 1) exit 1 }' "$tmp/run.csv" || fail "values out of range"

# Bad input: clear message, non-zero exit, nothing on stdout.
expect_error "cannot open" "$tool" validate "$tmp/none.json"
echo '{"format": "ahhs-genome"' >"$tmp/bad.json"
expect_error "not valid JSON" "$tool" validate "$tmp/bad.json"
sed 's/"version": 1/"version": 9/' "$tmp/a.json" >"$tmp/v9.json"
expect_error "version: unsupported" "$tool" validate "$tmp/v9.json"
sed '0,/"mu": [0-9.e-]*/s//"mu": 7/' "$tmp/a.json" >"$tmp/mu.json"
expect_error "hormones[0].mu: value 7 outside [0, 1]" "$tool" show "$tmp/mu.json"
expect_error "--variant" "$tool" random --variant ahhs3 --seed 1
expect_error "--hormones" "$tool" random --hormones 0 --seed 1
expect_error "--seed" "$tool" random --hormones 2
expect_error "--count" "$tool" mutate "$tmp/a.json" --seed 1 --count 0
printf '0,0,0.1,0.2,0.3\n' >"$tmp/short.csv"
expect_error "short.csv:1: expected 6 cells" "$tool" run "$tmp/a.json" --compartments 1 --sensors "$tmp/short.csv"
printf '0,0,0.1,0.2,1.5,0\n' >"$tmp/range.csv"
expect_error "s2 = 1.5 outside [0, 1]" "$tool" run "$tmp/a.json" --compartments 1 --sensors "$tmp/range.csv"
printf '0,3,0.1,0.2,0.5,0\n' >"$tmp/comp.csv"
expect_error "compartment '3' is not in [0, 2)" "$tool" run "$tmp/a.json" --compartments 2 --sensors "$tmp/comp.csv"
printf '0,0,0.1,0.2,x,0\n' >"$tmp/nan.csv"
expect_error "s2 'x' is not a finite number" "$tool" run "$tmp/a.json" --compartments 1 --sensors "$tmp/nan.csv"
echo "ahhs-genome: all checks passed"
