#!/usr/bin/env bash
# ahhs-study on a real Slurm (Debian's slurm-wlm and munge, a private single node started by
# tools/slurm-local; its daemons talk TCP over 127.0.0.1, and every array task and every local
# study runs in a private network namespace of its own, tools/ahhs-netns, so no run's multicast
# reaches a real interface):
#  1. submit a tiny plan as a job array; every run completes, and equals `ahhs-study run` of the
#     same plan bit for bit;
#  2. a task cancelled mid-run and submitted again (submit --resume) resumes its run, with the
#     same result; status, report and export work on the directory;
#  3. errors: no sbatch, submit without --slurm, a bad array index.
bin=${1:?usage: study_slurm_test.sh BIN_DIR}
source "${AHHS_SOURCE_DIR:?}/tests/lib.sh"
src=$AHHS_SOURCE_DIR
# Not in ahhs_netns: slurmd drops supplementary groups, which a user namespace forbids, and Slurm
# resolves 127.0.0.1 with AI_ADDRCONFIG, which fails where loopback is the only interface.
[[ $(id -u) == 0 ]] || { echo "SKIPPED: a private Slurm needs root (slurmd)"; exit 77; }
netns="$src/tools/ahhs-netns"
wrap="--task-wrapper $netns"
ahhs_own_group "$0" "$@"
ahhs_scratch 'ahhs-study|ahhs-evolve|ahhs-worker'
trap '[[ -n "${SLURM_CONF:-}" ]] && scancel -u "$(id -un)" 2>/dev/null; "$src/tools/slurm-local" stop $tmp/slurm; _ahhs_cleanup' EXIT
S="$bin/ahhs-study"
source "$src/tests/tools/study_lib.sh"
# wait_array DIR SECONDS: until Slurm has no job left and every run of DIR is complete.
wait_array() {
  for _ in $(seq $(($2 * 5))); do
    [[ -z "$(squeue -h 2>/dev/null)" ]] && break
    sleep 0.2
  done
  [[ -z "$(squeue -h)" ]] || fail "jobs still queued after $2 s: $(squeue)"
}
tiny_plan $tmp/plan.toml 12

echo "== 0. a private Slurm"
"$src/tools/slurm-local" start $tmp/slurm --port $((20000 + $$ % 20000)) >$tmp/slurm.out 2>&1 ||
  fail "slurm-local: $(cat $tmp/slurm.out)"
eval "$(cat $tmp/slurm.out)"
sinfo -h -N -o "%N %t %c" | grep -q " idle " || fail "node not idle: $(sinfo)"

echo "== 1. submit; equal to a local study"
"$S" submit $tmp/plan.toml --out $tmp/A --slurm --cpus-per-run 1 $wrap >$tmp/submit.out 2>&1 || fail "submit: $(cat $tmp/submit.out)"
grep -q "4 runs submitted as Slurm job array [0-9]" $tmp/submit.out || fail "$(cat $tmp/submit.out)"
[[ $(wc -l <$tmp/A/slurm/submit-1/runs.txt) == 4 ]] || fail "runs.txt: $(cat $tmp/A/slurm/submit-1/runs.txt)"
$netns "$S" run $tmp/plan.toml --out $tmp/L --parallel 1 --workers-per-run 1 --port-base 7600 >$tmp/L.out 2>&1 || fail "local study: $(cat $tmp/L.out)"
wait_array $tmp/A 300
"$S" status $tmp/A >$tmp/status || fail "status: $(cat $tmp/status)"
grep -q "4 of 4 runs complete, 0 running, 0 failed" $tmp/status || { cat $tmp/A/slurm/submit-1/task-*.out; fail "$(cat $tmp/status)"; }
same_study $tmp/A $tmp/L "Slurm array against ahhs-study run"
"$S" submit --resume $tmp/A --slurm >$tmp/out 2>&1 && grep -q "nothing to submit" $tmp/out || fail "resubmit of a complete study: $(cat $tmp/out)"

echo "== 2. a task cancelled mid-run, submitted again, resumes its run"
long=40
ci_tier_only "a 40-generation run to cancel (20 here)" && long=20
sed "s/^generations = 12/generations = $long/" $tmp/plan.toml >$tmp/plan40.toml
$netns "$S" run $tmp/plan40.toml --out $tmp/L40 --only pend1 --parallel 2 --workers-per-run 1 --port-base 7650 >$tmp/L40.out 2>&1 || fail "local: $(cat $tmp/L40.out)"
"$S" submit $tmp/plan40.toml --out $tmp/B --slurm --only pend1 $wrap >$tmp/out 2>&1 || fail "submit B: $(cat $tmp/out)"
job=$(cat $tmp/B/slurm/submit-1/job)
for _ in $(seq 600); do  # until the first run has committed a few generations
  [[ -f $tmp/B/pend1/seed-1/generations.csv && $(wc -l <$tmp/B/pend1/seed-1/generations.csv) -ge 4 ]] && break
  sleep 0.1
done
scancel $job
for _ in $(seq 300); do [[ -z "$(squeue -h)" ]] && break; sleep 0.1; done
gens=$(($(wc -l <$tmp/B/pend1/seed-1/generations.csv) - 1))
(( gens >= 3 && gens < long )) || fail "cancelled after $gens generations"
"$S" status $tmp/B | grep -q "pend1/seed-1 .*stopped" || fail "status after cancel: $($S status $tmp/B)"
"$S" submit --resume $tmp/B --slurm --only pend1 $wrap >$tmp/out 2>&1 || fail "resubmit: $(cat $tmp/out)"
[[ -s $tmp/B/slurm/submit-2/job ]] || fail "no second submission: $(cat $tmp/out)"
wait_array $tmp/B 300
grep -q "resuming at generation" $tmp/B/pend1/seed-1.log || fail "not resumed: $(tail $tmp/B/pend1/seed-1.log)"
runs="pend1/seed-1 pend1/seed-2" same_study $tmp/B $tmp/L40 "cancelled and resubmitted"
"$S" export $tmp/B $tmp/E >/dev/null && [[ -s $tmp/E/pend1/seed-1/summary.json ]] || fail "export"
"$S" report $tmp/A -o $tmp/R --no-replay >/dev/null 2>&1 && [[ -s $tmp/R/results.md ]] || fail "report"

echo "== 3. errors"
"$S" submit $tmp/plan.toml --out $tmp/C >$tmp/out 2>&1; [[ $? == 2 ]] && grep -q "slurm is required" $tmp/out || fail "without --slurm: $(cat $tmp/out)"
env PATH=/nonexistent "$S" submit $tmp/plan.toml --out $tmp/D --slurm >$tmp/out 2>&1; rc=$?
[[ $rc == 1 ]] && grep -q "sbatch refused the job array" $tmp/out && [[ ! -e $tmp/D/slurm/submit-1 ]] || fail "no sbatch: $rc $(cat $tmp/out)"
"$S" task $tmp/A --submission $tmp/A/slurm/submit-1 --index 9 >$tmp/out 2>&1; [[ $? == 1 ]] && grep -q "has only 4 runs" $tmp/out || fail "bad index: $(cat $tmp/out)"
echo "PASS"
