#!/usr/bin/env bash
# ahhs-sim as its own process over udpm (private network namespace), driven in lockstep by a
# second process: its fitness equals the same closed-loop policy run in-process, to the bit.
set -euo pipefail
sim=${1:?usage: multiprocess_sim.sh ahhs-sim sim_driver}
driver=${2:?}
netns=${AHHS_SOURCE_DIR:?}/tools/ahhs-netns
exec "$netns" bash -c '
  set -u
  sim=$1; driver=$2
  url="udpm://239.255.42.20:7711?ttl=0&recv_buf_size=4194304"
  tmp=$(mktemp -d); trap "rm -rf $tmp" EXIT
  for case in "pendulum 20 3" "gait 10 5"; do
    set -- $case
    "$sim" --lcm-url "$url" --episodes 1 2>"$tmp/sim.err" & pid=$!
    if ! timeout 120 "$driver" --lcm-url "$url" --scenario $1 --duration $2 --seed $3 >"$tmp/drv.out"; then
      echo "driver failed ($1)"; kill $pid 2>/dev/null; cat "$tmp/sim.err"; exit 1
    fi
    wait $pid || { echo "ahhs-sim exited with an error"; cat "$tmp/sim.err"; exit 1; }
    cat "$tmp/drv.out" "$tmp/sim.err"
    want=$(grep "^fitness " "$tmp/drv.out" | cut -d" " -f2)
    grep -q "finished after .* ticks, fitness $want; missed 0, late 0, dropped 0" "$tmp/sim.err" || {
      echo "FAIL ($1): the sim process did not report fitness $want with nothing missed"; exit 1; }
  done
  echo "multi-process lockstep equals in-process, bit for bit"
' _ "$sim" "$driver"
