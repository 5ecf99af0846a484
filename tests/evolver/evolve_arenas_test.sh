#!/usr/bin/env bash
# ahhs-evolve with the processes arena (a simulator process and a controller process per module
# in lockstep over udpm, inside a private network namespace): the same config and seed give
# exactly the run of the direct arena, every genome, seed and fitness, for the pendulum and the
# gait. Its lockstep arenas hold the lock against the other tests of real processes;
# evolve_test.sh has the rest of ahhs-evolve, which talks only through the farm.
bin=${1:?usage: evolve_arenas_test.sh BIN_DIR}
source "${AHHS_SOURCE_DIR:?}/tests/lib.sh"
ahhs_netns "$0" "$@"
url="udpm://239.255.42.61:7752?ttl=0&recv_buf_size=4194304"
ahhs_scratch 'ahhs-evolve|ahhs-worker|ahhs-sim|ahhs-module'
E="$bin/ahhs-evolve"
same_run() {  # same_run DIR_A DIR_B WHAT
  dump_run "$1" >$tmp/a.dump; dump_run "$2" >$tmp/b.dump
  [[ -s $tmp/a.dump ]] || fail "$3: empty run"
  cmp -s $tmp/a.dump $tmp/b.dump || { diff $tmp/a.dump $tmp/b.dump | head -5; fail "$3: runs differ"; }
  echo "$3: identical ($(wc -l <$tmp/a.dump) individuals)"
}
pend="--scenario pendulum --hormones 6 --rules 8 --population 12 --generations 5 --duration 10 --seed 11 --lcm-url $url"
gait="--scenario gait --hormones 3 --rules 6 --population 6 --generations 3 --duration 2 --seed 12 --lcm-url $url"

$E $pend --out $tmp/p-direct --workers 2 >$tmp/out 2>&1 || { cat $tmp/out; fail "pendulum run"; }
$E $pend --out $tmp/p-processes --workers 1 --arena-kind processes >$tmp/out 2>&1 ||
  { cat $tmp/out; fail "pendulum, processes arena"; }
same_run $tmp/p-direct $tmp/p-processes "pendulum, 1 worker, processes arena"
$E $gait --out $tmp/g-direct --workers 2 >$tmp/out 2>&1 || { cat $tmp/out; fail "gait run"; }
$E $gait --out $tmp/g-processes --workers 1 --arena-kind processes >$tmp/out 2>&1 ||
  { cat $tmp/out; fail "gait, processes arena"; }
same_run $tmp/g-direct $tmp/g-processes "gait, processes arena"
echo "PASS"
