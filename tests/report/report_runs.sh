#!/usr/bin/env bash
# The small real runs the report tests read (a CTest fixture: report:replay-and-figures and
# report:steps-and-neighbourhoods require it), made inside a private network namespace: six
# pendulum runs (AHHS2 and AHHS1, seeds 1-3) and a damped gait run, 4 generations of 8 each.
# They go to OUT_DIR whole or not at all.
bin=${1:?usage: report_runs.sh BIN_DIR OUT_DIR}
out=${2:?usage: report_runs.sh BIN_DIR OUT_DIR}
source "${AHHS_SOURCE_DIR:?}/tests/lib.sh"
ahhs_netns "$0" "$@"
url="udpm://239.255.42.80:7771?ttl=0&recv_buf_size=4194304"
# Processes of this test only: its process group (never a run of the same build elsewhere).
ahhs_scratch 'ahhs-evolve|ahhs-worker'
E="$bin/ahhs-evolve"
common="--population 8 --generations 4 --lcm-url $url --workers 2"
for seed in 1 2 3; do
  $E --scenario pendulum --variant ahhs2 --hormones 6 --rules 8 --duration 5.25 --seed $seed $common --out $tmp/a2-$seed >/dev/null 2>&1 || fail "run a2-$seed"
  $E --scenario pendulum --variant ahhs1 --hormones 6 --rules 12 --duration 5.25 --seed $seed $common --out $tmp/a1-$seed >/dev/null 2>&1 || fail "run a1-$seed"
done
$E --scenario gait --hormones 3 --rules 8 --duration 3 --seed 1 $common --out $tmp/gait >/dev/null 2>&1 || fail "gait run"
rm -rf "$out" && mkdir -p "$(dirname "$out")" && mkdir "$out.new.$$" &&
  mv $tmp/a1-* $tmp/a2-* $tmp/gait "$out.new.$$"/ && mv "$out.new.$$" "$out" || fail "could not move the runs to $out"
echo "PASS: 7 runs in $out"
