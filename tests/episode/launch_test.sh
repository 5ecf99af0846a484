#!/usr/bin/env bash
# ahhs-launch end to end, inside a private network namespace:
#  1. fused (inproc:// and LCM's memq://) and process arenas give bit-identical fitness and
#     behaviour descriptor, also with the pendulum's choices, a command delay and a bent start
#     (carried in RESET) (pendulum, gait; AHHS1, AHHS2; seeds); --arena-kind fused refuses a URL that leaves the
#     process; the deprecated --fused still works and says so;
#  2. a genome of the wrong shape is refused;
#  3. --log records every tick of every module (ahhs-logger); replaying the log into a fresh
#     ahhs-fitness gives the live fitness; --logger lcm-logger also records;
#  4. a module killed mid-episode ends the episode with a clear error within seconds, no orphans;
#     Ctrl-C to the launcher stops the episode and every child (exit status 130);
#  5. 5 % of messages dropped: the episode completes and reports what was lost;
#  6. garbage on every channel: counted, ignored, fitness unchanged;
#  7. real time: a module started late joins the running episode.
bin=${1:?usage: launch_test.sh BIN_DIR}
# Re-run inside a private network namespace (ahhs-netns exits 77, "skipped", where it cannot).
source "${AHHS_SOURCE_DIR:?}/tests/lib.sh"
ahhs_netns "$0" "$@"
url="udpm://239.255.42.50:7741?ttl=0&recv_buf_size=4194304"
# Processes of this test only: its process group (never a run of the same build elsewhere).
ahhs_scratch 'ahhs-[a-z]+'
fit() { tail -1 "$1" | sed -n 's/^fitness: //p'; }
G="$bin/ahhs-genome"
$G random --variant ahhs2 --hormones 15 --rules 15 --sensors 10 --actuators 2 --seed 1 >$tmp/p2.json
$G random --variant ahhs1 --hormones 15 --rules 60 --sensors 10 --actuators 2 --seed 2 >$tmp/p1.json
$G random --variant ahhs2 --hormones 5 --rules 30 --sensors 4 --actuators 1 --seed 3 >$tmp/g2.json
$G random --variant ahhs1 --hormones 5 --rules 80 --sensors 4 --actuators 1 --seed 4 >$tmp/g1.json

echo "== 1. fused == processes"
for c in "pendulum p2 1 30" "pendulum p1 2 30" "gait g2 3 10" "gait g1 4 10" "gait g2 5 10 --docking fixed" \
  "pendulum p2 6 30 --pendulum.actuator-gain 10" "pendulum p1 7 30 --pendulum.walls soft" \
  "gait g1 8 10 --envelope.command-delay 0.5 --envelope.start-hinge 0.5"; do
  set -- $c
  "$bin/ahhs-launch" --scenario $1 --genome $tmp/$2.json --seed $3 --duration $4 ${@:5} --arena-kind fused >$tmp/f.out || fail "fused $c"
  "$bin/ahhs-launch" --scenario $1 --genome $tmp/$2.json --seed $3 --duration $4 ${@:5} --arena-kind fused --lcm-url memq:// >$tmp/m.out || fail "fused on memq $c"
  "$bin/ahhs-launch" --scenario $1 --genome $tmp/$2.json --seed $3 --duration $4 ${@:5} --lcm-url "$url" >$tmp/p.out 2>$tmp/p.err || { cat $tmp/p.err; fail "processes $c"; }
  echo "$c: fused $(fit $tmp/f.out) fused on memq $(fit $tmp/m.out) processes $(fit $tmp/p.out)"
  [[ -n "$(fit $tmp/f.out)" && "$(fit $tmp/f.out)" == "$(fit $tmp/p.out)" ]] || fail "fused and process fitness differ ($c)"
  [[ "$(fit $tmp/f.out)" == "$(fit $tmp/m.out)" ]] || fail "inproc:// and memq:// differ ($c)"
  # The behaviour descriptor too.
  d=$(grep "^descriptor: " $tmp/f.out)
  [[ -n $d && $d == "$(grep '^descriptor: ' $tmp/p.out)" ]] ||
    fail "fused and process descriptors differ ($c): $d; $(grep '^descriptor: ' $tmp/p.out)"
done
if "$bin/ahhs-launch" --scenario pendulum --genome $tmp/p2.json --arena-kind fused --lcm-url "$url" 2>$tmp/err; then fail "--arena-kind fused on udpm accepted"; fi
grep -q "must be inproc:// or memq://" $tmp/err || fail "--arena-kind fused URL message: $(cat $tmp/err)"
if "$bin/ahhs-launch" --scenario pendulum --genome $tmp/p2.json --lcm-url inproc:// 2>$tmp/err; then fail "process arena on inproc:// accepted"; fi
grep -q "use it with --arena-kind fused" $tmp/err || fail "inproc URL message: $(cat $tmp/err)"
# The old --fused, for one release: the same episode, and a line that says what replaced it.
"$bin/ahhs-launch" --scenario pendulum --genome $tmp/p2.json --seed 1 --duration 30 --fused >$tmp/old.out 2>$tmp/old.err ||
  fail "--fused: $(cat $tmp/old.err)"
grep -q "^ahhs-launch: --fused is deprecated and will go; use --arena-kind fused$" $tmp/old.err || fail "--fused: $(cat $tmp/old.err)"
"$bin/ahhs-launch" --scenario pendulum --genome $tmp/p2.json --seed 1 --duration 30 --arena-kind fused >$tmp/f.out
[[ "$(fit $tmp/old.out)" == "$(fit $tmp/f.out)" ]] || fail "--fused gives $(fit $tmp/old.out), --arena-kind fused $(fit $tmp/f.out)"
code=0
"$bin/ahhs-launch" --scenario pendulum --genome $tmp/p2.json --fused --arena-kind processes >/dev/null 2>$tmp/err || code=$?
[[ $code == 2 ]] && grep -q "excludes" $tmp/err || fail "--fused with --arena-kind: exit $code, $(cat $tmp/err)"
echo "--fused still works, says it is deprecated, and gives the fitness of --arena-kind fused"

echo "== 2. wrong genome shape"
if "$bin/ahhs-launch" --scenario gait --genome $tmp/p2.json --arena-kind fused 2>$tmp/err; then fail "shape accepted"; fi
grep -q "gives each module 4 sensors and 1 actuators" $tmp/err || fail "shape message: $(cat $tmp/err)"

echo "== 3. log and replay"
"$bin/ahhs-launch" --scenario pendulum --genome $tmp/p2.json --seed 7 --duration 10 --arena LOGGED --lcm-url "$url" --log $tmp/ep.log >$tmp/live.out 2>/dev/null || fail "logged run"
"$bin/log_check" $tmp/ep.log --arena LOGGED --modules 2 --ticks 200 || fail "log incomplete"
"$bin/ahhs-fitness" --lcm-url "$url" --arena LOGGED --episodes 1 --timeout 60 >$tmp/replay.out & fp=$!
sleep 0.3
lcm-logplayer --lcm-url="$url" $tmp/ep.log
wait $fp || fail "replay fitness monitor"
echo "live $(fit $tmp/live.out) replayed $(fit $tmp/replay.out)"
[[ "$(fit $tmp/live.out)" == "$(fit $tmp/replay.out)" ]] || fail "replayed fitness differs"
# Debian's lcm-logger as the recorder: the run works and writes a log (it may lose messages, so
# completeness is not checked; docs/protocol.md).
"$bin/ahhs-launch" --scenario pendulum --genome $tmp/p2.json --duration 2 --lcm-url "$url" --log $tmp/lcm-logger.log \
  --logger lcm-logger >/dev/null 2>&1 || fail "run with lcm-logger"
[[ -s $tmp/lcm-logger.log ]] || fail "lcm-logger wrote no log"
if "$bin/ahhs-launch" --scenario pendulum --genome $tmp/p2.json --log $tmp/x.log --logger tee 2>$tmp/err; then fail "unknown logger accepted"; fi
grep -q "logger" $tmp/err || fail "logger message: $(cat $tmp/err)"

echo "== 4. a module killed mid-episode"
start=$(date +%s)
"$bin/ahhs-launch" --scenario gait --genome $tmp/g2.json --duration 600 --arena KILL --lcm-url "$url" >/dev/null 2>$tmp/kill.err & lp=$!
for i in $(seq 50); do pgrep -g "$pg" -f "ahhs-module --id 2 .*KILL" >/dev/null && break; sleep 0.1; done
sleep 1
pkill -g "$pg" -9 -f "ahhs-module --id 2 .*KILL" || fail "no module to kill"
wait $lp && fail "launcher succeeded after a module was killed"
elapsed=$(( $(date +%s) - start ))
grep -q "ahhs-module 2 ended during the episode (killed by signal 9)" $tmp/kill.err || fail "kill message: $(cat $tmp/kill.err)"
(( elapsed < 15 )) || fail "took ${elapsed}s"
sleep 0.5
pgrep -g "$pg" -f "arena KILL" && fail "orphan processes left"
echo "ended with: $(grep "episode failed" $tmp/kill.err) after ${elapsed}s; no orphans"

echo "== 4b. Ctrl-C (SIGINT) to the launcher mid-episode"
"$bin/ahhs-launch" --scenario gait --genome $tmp/g2.json --duration 600 --arena INTR --lcm-url "$url" >/dev/null 2>$tmp/int.err & lp=$!
for i in $(seq 50); do pgrep -g "$pg" -f "ahhs-module --id 4 .*INTR" >/dev/null && break; sleep 0.1; done
sleep 1
kill -INT $lp
wait $lp; rc=$?
(( rc == 130 )) || fail "interrupted launcher exit status $rc: $(cat $tmp/int.err)"
grep -q "episode failed: interrupted" $tmp/int.err || fail "interrupt message: $(cat $tmp/int.err)"
sleep 0.5
pgrep -g "$pg" -f "arena INTR" && fail "orphan processes left after Ctrl-C"
echo "interrupted: exit status $rc, no orphans"

echo "== seeds are unsigned 64-bit numbers, never clamped"
big=17941434774548605579 int64_max=9223372036854775807
"$bin/ahhs-launch" --scenario pendulum --genome $tmp/p2.json --duration 2 --seed $big --arena-kind fused >$tmp/big.out || fail "seed above 2^63"
"$bin/ahhs-launch" --scenario pendulum --genome $tmp/p2.json --duration 2 --seed $int64_max --arena-kind fused >$tmp/max.out || fail "seed 2^63-1"
grep -q "seed $big," $tmp/big.out || fail "the seed printed is not the one given: $(cat $tmp/big.out)"
[[ "$(tail -1 $tmp/big.out)" != "$(tail -1 $tmp/max.out)" ]] || fail "seed $big gave the fitness of $int64_max (clamped?)"
"$bin/ahhs-launch" --scenario pendulum --genome $tmp/p2.json --duration 2 --seed $big --lcm-url "$url" >$tmp/bigp.out 2>/dev/null ||
  fail "seed above 2^63 in the process arena"
[[ "$(tail -1 $tmp/big.out)" == "$(tail -1 $tmp/bigp.out)" ]] || fail "seed above 2^63: fused and process arenas differ"
for bad in -1 18446744073709551616 x; do
  if "$bin/ahhs-launch" --scenario pendulum --genome $tmp/p2.json --seed $bad --arena-kind fused >/dev/null 2>$tmp/bad.err; then
    fail "--seed $bad accepted"
  fi
  grep -q -- "--seed" $tmp/bad.err || fail "--seed $bad: $(cat $tmp/bad.err)"
done
echo "seed $big: $(tail -1 $tmp/big.out) (seed $int64_max: $(tail -1 $tmp/max.out))"

echo "== 5. 5 % of messages dropped (fault injection of the bus, in every process)"
AHHS_FAULT_DROP=0.05 AHHS_FAULT_SEED=3 "$bin/ahhs-launch" --scenario pendulum --genome $tmp/p2.json --duration 10.5 \
  --lockstep-timeout-ms 20 --lcm-url "$url" >$tmp/drop.out 2>$tmp/drop.err || { cat $tmp/drop.err; fail "lossy run"; }
cat $tmp/drop.out; grep -E "^ahhs-(sim|module)" $tmp/drop.err
grep -q "finished after 600 ticks" $tmp/drop.err || fail "lossy episode did not run to the end"
grep "finished after" $tmp/drop.err | grep -vq "missed 0, late 0" || fail "losses not reported"
grep -q "^fitness: " $tmp/drop.out || fail "no fitness"

echo "== 6. garbage on every channel"
chans="GARB/SIM/CONTROL,GARB/SIM/STATE,GARB/SIM/CLOCK,GARB/TOPOLOGY,GARB/GENOME,GARB/FITNESS"
for m in 0 1 2 3 4; do chans="$chans,GARB/MODULE$m/SENSORS,GARB/MODULE$m/HINGE,GARB/MODULE$m/HORMONE,GARB/MODULE$m/STATUS"; done
"$bin/bus_peer" --role spam --lcm-url "$url" --channels "$chans" --seconds 8 >$tmp/spam.out & sp=$!
"$bin/ahhs-launch" --scenario gait --genome $tmp/g2.json --seed 3 --duration 10 --arena GARB --lcm-url "$url" >$tmp/garb.out 2>$tmp/garb.err || { cat $tmp/garb.err; fail "run under garbage"; }
wait $sp
"$bin/ahhs-launch" --scenario gait --genome $tmp/g2.json --seed 3 --duration 10 --arena-kind fused >$tmp/clean.out
echo "under garbage $(fit $tmp/garb.out), clean $(fit $tmp/clean.out); $(cat $tmp/spam.out)"
[[ "$(fit $tmp/garb.out)" == "$(fit $tmp/clean.out)" ]] || fail "garbage changed the fitness"
grep "ahhs-sim: episode" $tmp/garb.err | grep -q "dropped [1-9]" || fail "garbage not counted by the sim"
# Every role says what it dropped, per channel and reason, without -v.
grep -Eq "^dropped: module 0: .*[0-9]+ SENSORS \(undecodable\)" $tmp/garb.out ||
  fail "no per-channel drops of module 0: $(grep dropped $tmp/garb.out)"
grep -Eq "^dropped: fitness monitor: .*[0-9]+ SIM/STATE \(undecodable\)" $tmp/garb.out ||
  fail "no per-channel drops of the fitness monitor: $(grep dropped $tmp/garb.out)"
grep -Eq "^ahhs-sim: dropped so far: .*[0-9]+ HINGE \(undecodable\)" $tmp/garb.err ||
  fail "no per-channel drops of the sim: $(grep dropped $tmp/garb.err)"
grep "^dropped: module 2" $tmp/garb.out || true

echo "== 7. real time, a module joins late"
"$bin/ahhs-sim" --lcm-url "$url" --arena RT --episodes 1 2>$tmp/rt-sim.err & s=$!
"$bin/ahhs-fitness" --lcm-url "$url" --arena RT --episodes 1 >$tmp/rt-fit.out & f=$!
"$bin/ahhs-module" --id 0 --lcm-url "$url" --arena RT 2>$tmp/rt-m0.err & m0=$!
"$bin/arena_driver" --lcm-url "$url" --scenario pendulum --duration 5 --seed 1 --realtime --arena RT >$tmp/rt.out 2>&1 & d=$!
sleep 3
"$bin/ahhs-module" --id 1 --lcm-url "$url" --arena RT 2>$tmp/rt-m1.err & m1=$!
wait $d || { cat $tmp/rt.out; fail "real-time episode"; }
wait $s $f
kill $m0 $m1; wait $m0 $m1 2>/dev/null
cat $tmp/rt.out $tmp/rt-m0.err $tmp/rt-m1.err
ticks1=$(sed -n 's/^ahhs-module 1: \([0-9]*\) ticks.*/\1/p' $tmp/rt-m1.err)
ticks0=$(sed -n 's/^ahhs-module 0: \([0-9]*\) ticks.*/\1/p' $tmp/rt-m0.err)
(( ticks1 > 10 && ticks1 < ticks0 )) || fail "the late module did not join (module 0: $ticks0 ticks, module 1: $ticks1)"
echo "all ahhs-launch checks passed"
