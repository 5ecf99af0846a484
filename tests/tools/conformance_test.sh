#!/usr/bin/env bash
# ahhs-conformance (docs/hardware.md, "Conformance kit"), inside a private network namespace:
# the reference firmware and tracker (examples/) pass every check; a firmware on its own timer
# that follows any episode's HINGE, and a tracker that does not copy the episode, fail the
# checks they break, with the evidence, and exit 1. Module controllers: ahhs-module and the Lua
# controller (examples/controller-lua) equal modules/core bit for bit in every segment; modules
# that reset on a repeated GENOME, do not wait for their neighbours, or take any episode's
# messages fail exactly the segments they break. Episode servers: ahhs-sim and ahhs-sim --physics
# none pass; a server on its own timer that obeys any episode's STOP fails.
bin=${1:?usage: conformance_test.sh BIN_DIR}
source "${AHHS_SOURCE_DIR:?}/tests/lib.sh"
ahhs_netns "$0" "$@"
url="udpm://239.255.42.52:7747?ttl=0&recv_buf_size=4194304"
ahhs_scratch 'ahhs-[a-z-]+|role_peer'
lua_pids=()
trap 'kill "${lua_pids[@]}" 2>/dev/null; _ahhs_cleanup' EXIT
kit() { "$bin/ahhs-conformance" "$@" --lcm-url "$url"; }
# kit_pass OUT ARGS...: the kit on ARGS into OUT, for an implementation that must pass. Its
# timing (a reply within --budget-ms of its input; a server's clock on time) is what a shared
# machine decides, not the implementation: CI's machine, with only the next build beside at nice
# 19, once saw a reference firmware reply 101 ms and 88 ms after its clock in two tries (budget
# 25). So a reference implementation is held to 1 s (20 ticks), which still catches one that
# does not answer its own tick; the 25-ms verdict itself is checked in conformance_checks_test,
# and the faulty server below still fails the default budget.
kit_pass() {
  local out=$1
  shift
  kit "$@" --budget-ms 1000 >"$out"
}

echo "== the reference firmware and tracker pass"
"$bin/ahhs-example-firmware" --arena OKFW --id 2 --lcm-url "$url" --seconds 40 >/dev/null &
"$bin/ahhs-example-tracker" --arena OKTR --modules 3 --lcm-url "$url" --seconds 40 >/dev/null &
sleep 0.3
kit_pass $tmp/fw.out firmware --arena OKFW --id 2 &
fw_kit=$!
kit_pass $tmp/tr.out tracker --arena OKTR --modules 3 || { cat $tmp/tr.out; fail "the reference tracker"; }
wait $fw_kit || { cat $tmp/fw.out; fail "the reference firmware"; }
[[ $(grep -c '^PASS' $tmp/fw.out) -eq 7 ]] || fail "firmware checklist: $(cat $tmp/fw.out)"
[[ $(grep -c '^PASS' $tmp/tr.out) -eq 5 ]] || fail "tracker checklist: $(cat $tmp/tr.out)"
grep "budget" $tmp/fw.out $tmp/tr.out

echo "== planted faults fail"
"$bin/role_peer" --role drifting-firmware --arena BADFW --id 1 --lcm-url "$url" --seconds 20 >/dev/null &
"$bin/role_peer" --role stale-tracker --arena BADTR --modules 3 --lcm-url "$url" --seconds 20 >/dev/null &
sleep 0.3
(code=0; kit tracker --arena BADTR --modules 3 >$tmp/bad-tr.out || code=$?; echo $code >$tmp/bad-tr.code) &
bad_tr_kit=$!
code=0
kit firmware --arena BADFW --id 1 >$tmp/bad-fw.out || code=$?
[[ $code -eq 1 ]] || { cat $tmp/bad-fw.out; fail "a drifting firmware: exit $code, not 1"; }
grep -q "^FAIL one reading per tick" $tmp/bad-fw.out || fail "drift not caught: $(cat $tmp/bad-fw.out)"
grep -q "^FAIL follows HINGE of its episode, ignores a foreign episode's: last hinge_angle -1" $tmp/bad-fw.out ||
  fail "foreign HINGE not caught: $(cat $tmp/bad-fw.out)"
grep -q "NOT conformant" $tmp/bad-fw.out || fail "no verdict"
wait $bad_tr_kit
code=$(cat $tmp/bad-tr.code)
[[ $code -eq 1 ]] || { cat $tmp/bad-tr.out; fail "a stale tracker: exit $code, not 1"; }
grep -q "^FAIL one state per tick, with the clock's episode and tick: 60 ticks played: 60 without" $tmp/bad-tr.out ||
  fail "episode not copied, not caught: $(cat $tmp/bad-tr.out)"
grep '^FAIL' $tmp/bad-fw.out $tmp/bad-tr.out

echo "== module controllers: ahhs-module and the Lua controller pass"
"$bin/ahhs-module" --id 2 --arena MOD --lcm-url "$url" >/dev/null 2>&1 &
"$bin/ahhs-example-controller-lua" --id 4 --arena LUA --lcm-url "$url" --seconds 60 >$tmp/lua.err 2>&1 &
lua_pids+=($!)
sleep 0.3
kit_pass $tmp/mod.out module --arena MOD --id 2 &
kit_pass $tmp/lua.out module --arena LUA --id 4 || { cat $tmp/lua.out $tmp/lua.err; fail "the Lua controller"; }
wait $! || { cat $tmp/mod.out; fail "ahhs-module"; }
for who in mod lua; do
  [[ $(grep -c '^PASS' $tmp/$who.out) -eq 14 ]] || fail "$who checklist: $(cat $tmp/$who.out)"
  grep -q "^PASS equals the model bit for bit: real time, joined at tick 100: 30 ticks" $tmp/$who.out ||
    fail "$who: $(cat $tmp/$who.out)"
done
grep "bit for bit: lockstep\|budget" $tmp/mod.out $tmp/lua.out

echo "== module controllers: planted faults fail where they break the protocol"
faults=(reset-on-genome no-wait any-episode)
for f in "${faults[@]}"; do
  "$bin/role_peer" --role faulty-module --fault $f --arena F$f --id 1 --lcm-url "$url" --seconds 20 >/dev/null 2>&1 &
done
sleep 0.3
kits=()
for f in "${faults[@]}"; do
  (code=0; kit module --arena F$f --id 1 >$tmp/$f.out || code=$?; echo "exit $code" >>$tmp/$f.out) &
  kits+=($!)
done
wait "${kits[@]}"
for f in "${faults[@]}"; do grep -q "^exit 1" $tmp/$f.out || fail "$f: $(cat $tmp/$f.out)"; done
expect() {  # FAULT LINE...: each line is in the checklist
  local f=$1
  shift
  for line in "$@"; do grep -q "^$line" $tmp/$f.out || fail "$f: no '$line' in $(cat $tmp/$f.out)"; done
}
expect reset-on-genome "PASS equals the model bit for bit: lockstep, AHHS2" \
  "FAIL equals the model bit for bit: after a repeated GENOME and TOPOLOGY: tick 20: HINGE values\[0\] = "
expect no-wait "FAIL equals the model bit for bit: lockstep, AHHS2: tick 1: HINGE values\[0\] = " \
  "FAIL equals the model bit for bit: a new episode (RESET): AHHS1, from rest: tick 1"
expect any-episode "PASS equals the model bit for bit: after a repeated GENOME and TOPOLOGY" \
  "FAIL one HINGE and one HORMONE per tick.* [1-9][0-9]* of the foreign episode" \
  "FAIL equals the model bit for bit: a foreign episode's SENSORS and HORMONE ignored: tick 30"
grep -h 'bit for bit.*tick [0-9]*: HINGE' $tmp/reset-on-genome.out $tmp/no-wait.out $tmp/any-episode.out

echo "== episode servers: ahhs-sim and ahhs-sim --physics none pass, a faulty one fails"
"$bin/ahhs-sim" --arena SIM --lcm-url "$url" >/dev/null 2>&1 &
"$bin/ahhs-sim" --physics none --arena SRV --lcm-url "$url" </dev/null >$tmp/srv.err 2>&1 &
"$bin/role_peer" --role faulty-server --arena FSRV --lcm-url "$url" --seconds 20 >/dev/null 2>&1 &
sleep 0.3
kit_pass $tmp/sim.out sim --arena SIM &
sim_kit=$!
(code=0; kit sim --arena FSRV >$tmp/fsrv.out || code=$?; echo "exit $code" >>$tmp/fsrv.out) &
fsrv_kit=$!
kit_pass $tmp/srv.out sim --arena SRV || { cat $tmp/srv.out $tmp/srv.err; fail "ahhs-sim --physics none"; }
wait $sim_kit || { cat $tmp/sim.out; fail "ahhs-sim"; }
wait $fsrv_kit
for who in sim srv; do
  [[ $(grep -c '^PASS' $tmp/$who.out) -eq 9 ]] || fail "$who checklist: $(cat $tmp/$who.out)"
done
grep -q "^PASS SENSORS.*120 of 120" $tmp/sim.out || fail "sim SENSORS: $(cat $tmp/sim.out)"
grep -q "^PASS SENSORS.*none: an episode server" $tmp/srv.out || fail "server SENSORS: $(cat $tmp/srv.out)"
grep -q "^exit 1" $tmp/fsrv.out || fail "faulty server: $(cat $tmp/fsrv.out)"
for line in "FAIL keeps real time" "FAIL ignores another episode's PAUSE and STOP" \
  "FAIL ends after 40 ticks: SIM/CLOCK FINISHED three times.*: 1 FINISHED" \
  "FAIL refuses a bad RESET (unknown scenario): 5 clocks"; do
  grep -q "^$line" $tmp/fsrv.out || fail "faulty server: no '$line' in $(cat $tmp/fsrv.out)"
done
grep -h "keeps real time" $tmp/sim.out $tmp/srv.out $tmp/fsrv.out

echo "== usage"
code=0
"$bin/ahhs-conformance" planner --arena X >$tmp/usage.out 2>&1 || code=$?
[[ $code -eq 2 ]] || fail "an unknown role: exit $code"
code=0
"$bin/ahhs-conformance" firmware --arena X >$tmp/usage.out 2>&1 || code=$?
[[ $code -eq 2 ]] && grep -q "firmware needs --id N" $tmp/usage.out || fail "firmware without --id: exit $code, $(cat $tmp/usage.out)"
code=0
"$bin/ahhs-conformance" module --arena X >$tmp/usage.out 2>&1 || code=$?
[[ $code -eq 2 ]] && grep -q "module needs --id N" $tmp/usage.out || fail "module without --id: exit $code, $(cat $tmp/usage.out)"
echo "PASS"
