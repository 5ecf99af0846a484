#!/usr/bin/env bash
# Every preset in configs/ loads through ahhs-evolve --config and gives the paper's setting
# (ahhs-model.md, "Configurations used in the paper"); command-line options override a preset.
set -uo pipefail
E=${1:?usage: presets_test.sh AHHS_EVOLVE}
src=${AHHS_SOURCE_DIR:?}
fail() { echo "FAIL: $*"; exit 1; }
check() {  # check PRESET FIELD=VALUE...
  local preset=$1; shift
  "$E" --config "$src/configs/$preset.toml" --show-config >/tmp/preset.$$.json 2>&1 ||
    fail "$preset: $(cat /tmp/preset.$$.json)"
  for kv in "$@"; do
    got=$(/usr/bin/python3 -c "import json,sys; print(json.load(open(sys.argv[1]))[sys.argv[2]])" \
      /tmp/preset.$$.json "${kv%%=*}")
    [[ "$got" == "${kv#*=}" ]] || fail "$preset: ${kv%%=*} is $got, expected ${kv#*=}"
  done
  echo "$preset: ok"
}
trap 'rm -f /tmp/preset.$$.json' EXIT
n=0
for v in "ahhs1 60" "ahhs2 15"; do
  set -- $v
  check pendulum-$1-$2 scenario=pendulum variant=$1 hormones=15 rules=$2 population=200 generations=200 elitism=1 mutation_rate=0.15 mutation_max_change=0.1 crossover_rate=0.05
  n=$((n + 1))
done
for j in damped fixed; do
  for v in "ahhs1 20" "ahhs1 80" "ahhs1 120" "ahhs1 300" "ahhs2 20" "ahhs2 30" "ahhs2 50"; do
    set -- $v
    check gait-$j-$1-$2 scenario=gait joints=$j modules=5 variant=$1 hormones=5 rules=$2 population=20 generations=200 duration=0.0
    n=$((n + 1))
  done
done
[[ $(ls "$src"/configs/*.toml | wc -l) == $n ]] || fail "configs/ holds presets this test does not know"
# Options given on the command line override the preset.
"$E" --config "$src/configs/gait-damped-ahhs2-30.toml" --generations 7 --seed 5 --show-config | grep -q '"generations": 7' ||
  fail "override"
echo 'rules = "many"' >/tmp/preset.$$.json
"$E" --config /tmp/preset.$$.json --show-config >/dev/null 2>&1 && fail "a bad preset value was accepted"
echo "PASS ($n presets)"
