#!/usr/bin/env bash
# Every preset in configs/ loads through ahhs-evolve --config and gives the paper's setting
# (docs/evolution.md, "Presets"); command-line options override a preset.
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
trap 'rm -f /tmp/preset.$$.json /tmp/preset.$$.err' EXIT
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
# The robust presets (not the paper's): trials, an envelope and a post-evaluation.
check gait-damped-ahhs2-30-robust scenario=gait joints=damped variant=ahhs2 rules=30 population=20 trials=3 aggregate=mean
check gait-fixed-ahhs1-80-robust scenario=gait joints=fixed variant=ahhs1 rules=80 population=20 trials=5 aggregate=median
n=$((n + 2))
for p in gait-damped-ahhs2-30-robust gait-fixed-ahhs1-80-robust; do
  "$E" --config "$src/configs/$p.toml" --show-config >/tmp/preset.$$.json
  /usr/bin/python3 - /tmp/preset.$$.json <<'PY' || fail "$p: envelope or post-evaluation"
import json, sys
c = json.load(open(sys.argv[1]))
assert c["envelope"]["friction"] == 0.05 and c["envelope"]["sensor-noise"] == 0.023, c["envelope"]
assert c["post_eval"]["episodes"] == 50 and c["post_eval"]["envelope"] == c["envelope"], c["post_eval"]
assert c["validation"] == {"episodes": 20, "candidates": 10}, c.get("validation")
PY
done
# A paper preset's configuration has none of the robust keys.
"$E" --config "$src/configs/gait-damped-ahhs2-30.toml" --show-config | grep -Eq '"(trials|envelope|post_eval|validation)"' &&
  fail "a paper preset has robust keys"
# Single envelope keys are quoted TOML keys ("envelope.friction" = 0.1), on top of the preset.
printf 'envelope = "paper"\n"envelope.friction" = 0.1\ntrials = 2\n' >/tmp/preset.$$.json
"$E" --config /tmp/preset.$$.json --show-config | grep -q '"friction": 0.1' || fail "envelope key in a config"
# A config file's key 'joints', the old name of 'docking', works for one release and says so.
printf 'scenario = "gait"\njoints = "fixed"\n' >/tmp/preset.$$.json
"$E" --config /tmp/preset.$$.json --show-config 2>/tmp/preset.$$.err | grep -q '"joints": "fixed"' ||
  fail "joints in a config file: $(cat /tmp/preset.$$.err)"
grep -qx "ahhs-evolve: --joints is deprecated and will go; use --docking" /tmp/preset.$$.err ||
  fail "joints in a config file: $(cat /tmp/preset.$$.err)"
[[ $(ls "$src"/configs/*.toml | wc -l) == $n ]] || fail "configs/ holds presets this test does not know"
# Options given on the command line override the preset.
"$E" --config "$src/configs/gait-damped-ahhs2-30.toml" --generations 7 --seed 5 --show-config | grep -q '"generations": 7' ||
  fail "override"
# The README's main job: without --config or --scenario, ahhs-evolve is the robust damped preset;
# with --scenario it starts from the paper's defaults; options still override.
"$E" --show-config >/tmp/preset.$$.json || fail "no --config"
"$E" --config "$src/configs/gait-damped-ahhs2-30-robust.toml" --show-config |
  cmp -s - /tmp/preset.$$.json || fail "the main job is not configs/gait-damped-ahhs2-30-robust.toml"
"$E" --scenario gait --show-config | grep -Eq '"(trials|envelope|post_eval|validation)"' &&
  fail "--scenario without --config is not the paper's defaults"
"$E" --trials 2 --envelope none --post-eval 0 --show-config | grep -Eq '"(envelope|post_eval)"|"trials": 3' &&
  fail "options do not override the main job"
# The held-out envelope: a preset with single keys on top; a bad key is one line, exit 2.
"$E" --post-eval-envelope paper,command-delay=0.5,start-hinge=0.25 --show-config |
  tr -d ' \n' | grep -q '"post_eval":{"envelope":{"cart-speed":0.05,"command-delay":0.5,.*"start-hinge":0.25,' ||
  fail "--post-eval-envelope with single keys"
"$E" --post-eval-envelope paper,delay=0.5 --show-config >/dev/null 2>/tmp/preset.$$.err
[[ $? == 2 && $(wc -l </tmp/preset.$$.err) == 1 ]] && grep -q "'delay=0.5' is not KEY=W" /tmp/preset.$$.err ||
  fail "a bad --post-eval-envelope key: $(cat /tmp/preset.$$.err)"
echo 'rules = "many"' >/tmp/preset.$$.json
"$E" --config /tmp/preset.$$.json --show-config >/dev/null 2>&1 && fail "a bad preset value was accepted"
echo "PASS ($n presets)"
