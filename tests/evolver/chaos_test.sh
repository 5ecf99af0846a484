#!/usr/bin/env bash
# A chaos soak (docs/evolution.md, "What we guarantee"): an evolution with process arenas (every
# episode a sim, a fitness monitor and modules as processes) while 5 % of the farm's datagrams
# are lost (nftables in the private network namespace) and a schedule drawn from a seed kill -9's
# the evolver, workers, sims, fitness monitors and modules at random moments. The evolver is
# resumed after each kill of it; the final run must equal the uninterrupted, loss-free run to
# the bit. The schedule and the figures are printed. AHHS_CHAOS_SEED picks another schedule.
bin=${1:?usage: chaos_test.sh BIN_DIR}
source "${AHHS_SOURCE_DIR:?}/tests/lib.sh"
ahhs_netns "$0" "$@"
ahhs_scratch 'ahhs-evolve|ahhs-worker|ahhs-sim|ahhs-module|ahhs-fitness'
E="$bin/ahhs-evolve"
seed=${AHHS_CHAOS_SEED:-20101001}
port=7764
url="udpm://239.255.42.64:$port?ttl=0&recv_buf_size=4194304"
cfg=(--scenario gait --hormones 3 --rules 6 --population 8 --generations 14 --duration 3 --seed 33
     --lcm-url "$url" --arena-kind processes --workers 2)

start=$(date +%s.%N)
"$E" "${cfg[@]}" --out $tmp/whole >$tmp/whole.out 2>&1 || { cat $tmp/whole.out; fail "the uninterrupted run"; }
whole_s=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }')
echo "uninterrupted, loss-free: ${whole_s} s"

nft add table inet chaos &&
  nft add chain inet chaos in '{ type filter hook input priority 0; }' &&
  nft add rule inet chaos in udp dport $port numgen random mod 20 0 counter drop ||
  { echo "SKIPPED: nftables unavailable in the private namespace"; exit 77; }

# The schedule: (seconds to wait, what to kill), drawn from the seed.
/usr/bin/python3 - "$seed" >$tmp/schedule <<'PY'
import random, sys
rng = random.Random(int(sys.argv[1]))
victims = ["ahhs-evolve", "ahhs-worker", "ahhs-sim", "ahhs-module", "ahhs-fitness"]
for _ in range(12):
    print("%.2f %s %d" % (rng.uniform(0.5, 2.5), rng.choice(victims), rng.randrange(1000)))
PY
echo "schedule (seed $seed): $(awk '{ printf "%s %ss, ", $2, $1 }' $tmp/schedule)"

evolver=
run_evolver() {  # starts the run, or resumes it, in the background
  if [[ -e $tmp/chaos/run.sqlite ]]; then
    "$E" --resume $tmp/chaos --lcm-url "$url" --workers 2 --arena-kind processes >>$tmp/chaos.out 2>&1 &
  else
    "$E" "${cfg[@]}" --out $tmp/chaos >>$tmp/chaos.out 2>&1 &
  fi
  evolver=$!
}
start=$(date +%s.%N)
run_evolver
kills=0 resumes=0 misses=0
while read -r wait victim pick; do
  sleep "$wait"
  if ! kill -0 $evolver 2>/dev/null; then
    wait $evolver && break  # finished before the schedule did
    run_evolver; resumes=$((resumes + 1)); continue
  fi
  mapfile -t pids < <(pgrep -g "$pg" -f "$bin/$victim( |$)")
  if [[ ${#pids[@]} == 0 ]]; then misses=$((misses + 1)); continue; fi
  pid=${pids[$((pick % ${#pids[@]}))]}
  kill -9 "$pid" 2>/dev/null && kills=$((kills + 1)) && echo "  $(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%5.1f", b - a }') s: kill -9 $victim ($pid)"
  if [[ $victim == ahhs-evolve ]]; then
    wait $evolver 2>/dev/null
    sleep 0.3  # its workers end with it (PR_SET_PDEATHSIG)
    run_evolver; resumes=$((resumes + 1))
  fi
done <$tmp/schedule
# Then to the end, resuming as often as it takes (a job that failed too often stops a run).
for _ in 1 2 3 4 5; do
  wait $evolver && break
  run_evolver; resumes=$((resumes + 1))
done
kill -0 $evolver 2>/dev/null && { wait $evolver || fail "the chaos run did not finish: $(tail -5 $tmp/chaos.out)"; }
chaos_s=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }')
dropped=$(nft list chain inet chaos in | grep -o "packets [0-9]*" | grep -o "[0-9]*")
dump_run $tmp/whole >$tmp/whole.dump
dump_run $tmp/chaos >$tmp/chaos.dump
[[ $(wc -l <$tmp/whole.dump) == $((8 * 14)) ]] || fail "the uninterrupted run is incomplete"
if ! cmp -s $tmp/whole.dump $tmp/chaos.dump; then
  echo "generation|idx|genome|seed|elite|fitness|cost: < uninterrupted, > chaos (first differences)"
  diff $tmp/whole.dump $tmp/chaos.dump | head -12
  grep -E "error|failed|re-issued" $tmp/chaos.out | head -20
  fail "the chaos run differs from the uninterrupted run"
fi
echo "identical: $kills kill -9 ($misses scheduled victims not running), $resumes resumes, $dropped farm datagrams dropped, $(grep -c 're-issued' $tmp/chaos.out) re-issues; ${chaos_s} s"
echo PASS
