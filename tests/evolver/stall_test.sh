#!/usr/bin/env bash
# Stalled processes change nothing (docs/evolution.md, "What we guarantee"): an evolution with
# process arenas while arena processes are stopped (SIGSTOP, then SIGCONT) for longer than the
# old 2 s lockstep timeout: a module, the sim, the fitness monitor, then a module for longer than
# the 10 s stall timeout (its episode fails and is run again). Exact lockstep waits instead of
# going on without a command or a hormone packet, so the run equals the undisturbed one to the
# bit. Before exact lockstep a module stopped for 2.5 s changed the fitness of its episode.
bin=${1:?usage: stall_test.sh BIN_DIR}
source "${AHHS_SOURCE_DIR:?}/tests/lib.sh"
ahhs_netns "$0" "$@"
ahhs_scratch 'ahhs-evolve|ahhs-worker|ahhs-sim|ahhs-module|ahhs-fitness'
E="$bin/ahhs-evolve"
# 24 generations take about 5 s undisturbed here, 4 times the 1.2 s of progress between
# the stalls: a machine twice as fast still has the run going at the fourth (12 took 3.6 s and
# ended before it).
gens=24
url="udpm://239.255.42.65:7766?ttl=0&recv_buf_size=4194304"
cfg=(--scenario gait --hormones 3 --rules 6 --population 8 --generations $gens --duration 3 --seed 34
     --lcm-url "$url" --arena-kind processes --workers 2)

"$E" "${cfg[@]}" --out $tmp/whole >$tmp/whole.out 2>&1 || { cat $tmp/whole.out; fail "the undisturbed run"; }
"$E" "${cfg[@]}" --out $tmp/stalled >$tmp/stalled.out 2>&1 &
evolver=$!
stalls=0
for plan in "ahhs-module 2.5" "ahhs-sim 2.5" "ahhs-fitness 2.5" "ahhs-module 11"; do
  read -r victim seconds <<<"$plan"
  sleep 0.3
  # The victim, once the workers have started their arenas (under load that can take longer
  # than the first 0.3 s: seen once in CI); none while the evolver runs no more: the run is over.
  pids=()
  for _ in $(seq 1 200); do
    mapfile -t pids < <(pgrep -g "$pg" -f "$bin/$victim( |$)")
    if [[ ${#pids[@]} -gt 0 ]] || ! kill -0 $evolver 2>/dev/null; then break; fi
    sleep 0.05
  done
  [[ ${#pids[@]} -gt 0 ]] || break
  pid=${pids[$((stalls % ${#pids[@]}))]}
  kill -STOP "$pid" && sleep "$seconds" && kill -CONT "$pid" && stalls=$((stalls + 1))
  echo "  stopped $victim ($pid) for $seconds s"
done
wait $evolver || { tail -5 $tmp/stalled.out; fail "the stalled run"; }
[[ $stalls == 4 ]] || fail "the run ended before the 4 stalls ($stalls): make it longer"
dump_run $tmp/whole >$tmp/whole.dump
dump_run $tmp/stalled >$tmp/stalled.dump
[[ $(wc -l <$tmp/whole.dump) == $((8 * gens)) ]] || fail "the undisturbed run is incomplete"
if ! cmp -s $tmp/whole.dump $tmp/stalled.dump; then
  diff $tmp/whole.dump $tmp/stalled.dump | head -8
  fail "the stalled run differs from the undisturbed one"
fi
echo "identical after $stalls stalls; $(grep -c 're-issued' $tmp/stalled.out) re-issues"
echo PASS
