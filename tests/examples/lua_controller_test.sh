#!/usr/bin/env bash
# The Lua 5.2 module controller (examples/controller-lua), inside a private network namespace:
# as an external module of a lockstep gait arena it gives ahhs-module's fitness to the bit, for
# random AHHS2 and AHHS1 genomes, an evolved gait and an evolved pendulum (ownership masks) of the
# paper study; bad options exit 2.
# (Its protocol checklist is in tests/tools/conformance_test.sh.)
bin=${1:?usage: lua_controller_test.sh BIN_DIR}
source "${AHHS_SOURCE_DIR:?}/tests/lib.sh"
ahhs_netns "$0" "$@"
url="udpm://239.255.42.55:7753?ttl=0&recv_buf_size=4194304"
ahhs_scratch 'ahhs-[a-z-]+'
lua=()
trap 'kill "${lua[@]}" 2>/dev/null; _ahhs_cleanup' EXIT
fit() { tail -1 "$1" | sed -n 's/^fitness: //p'; }

same_fitness() {  # NAME LUA_ID GENOME LAUNCH_OPTIONS...: Lua as module LUA_ID = all ahhs-module
  local name=$1 id=$2 genome=$3
  shift 3
  local launch=("$bin/ahhs-launch" --genome "$genome" --lcm-url "$url" "$@")
  "${launch[@]}" --arena REF$name >$tmp/$name-ref.out 2>&1 || { cat $tmp/$name-ref.out; fail "$name: reference"; }
  "$bin/ahhs-example-controller-lua" --id $id --arena LUA$name --lcm-url "$url" --seconds 60 >$tmp/$name.lua 2>&1 &
  lua+=($!)
  "${launch[@]}" --arena LUA$name --external module:$id --external-timeout 20 >$tmp/$name.out 2>&1 ||
    { cat $tmp/$name.out $tmp/$name.lua; fail "$name: episode with the Lua module"; }
  kill "${lua[-1]}" 2>/dev/null
  local ref got
  ref=$(fit $tmp/$name-ref.out)
  got=$(fit $tmp/$name.out)
  [[ -n "$ref" && "$got" == "$ref" ]] || fail "$name: Lua module $id gives $got, ahhs-module $ref"
  echo "$name: Lua as module $id, fitness $got (ahhs-module: $ref)"
}

echo "== random genomes, 3-module gait"
"$bin/ahhs-genome" random --variant ahhs2 --hormones 5 --rules 30 --sensors 4 --actuators 1 --seed 3 >$tmp/a2.json
"$bin/ahhs-genome" random --variant ahhs1 --hormones 5 --rules 40 --sensors 4 --actuators 1 --seed 3 >$tmp/a1.json
same_fitness AHHS2 1 $tmp/a2.json --scenario gait --modules 3 --seed 5 --duration 4
same_fitness AHHS1 0 $tmp/a1.json --scenario gait --modules 3 --seed 5 --duration 4

# Evolved genomes: copies of the first study's bests (tests/fixtures/genomes), with the evaluation
# seed each stores.
genomes=$AHHS_SOURCE_DIR/tests/fixtures/genomes
stored_seed() { python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['meta']['eval_seed'])" "$1"; }
echo "== an evolved gait (the first study's gait-fixed-ahhs1-20 seed 2)"
same_fitness EVOLVED 2 "$genomes/gait-fixed-ahhs1-20-seed2.json" --scenario gait --modules 5 --docking fixed \
  --seed "$(stored_seed "$genomes/gait-fixed-ahhs1-20-seed2.json")"

echo "== an evolved pendulum (AHHS2-15 seed 1): compartments own some of the shared slots"
same_fitness PENDULUM 1 "$genomes/pendulum-ahhs2-15-seed1.json" --scenario pendulum \
  --seed "$(stored_seed "$genomes/pendulum-ahhs2-15-seed1.json")" --duration 20

echo "== bad options"
for args in "" "--id x" "--id 1 --seconds 0" "--id 1 --colour red"; do
  code=0
  # shellcheck disable=SC2086
  "$bin/ahhs-example-controller-lua" $args >$tmp/bad.out 2>&1 || code=$?
  [[ $code -eq 2 ]] && grep -q "^module.lua: " $tmp/bad.out || fail "'$args': exit $code, $(cat $tmp/bad.out)"
done
echo "PASS"
