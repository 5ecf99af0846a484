#!/usr/bin/env bash
# ahhs-sim and one ahhs-module process per compartment, each its own process on udpm inside a
# private network namespace, run episodes in lockstep; the fitness equals the in-process
# reference to the bit (pendulum and gait, AHHS1 and AHHS2).
set -euo pipefail
bin=${1:?usage: multiprocess_arena.sh BUILD_DIR}
exec "${AHHS_SOURCE_DIR:?}/tools/ahhs-netns" bash -c '
  set -u
  bin=$1
  url="udpm://239.255.42.30:7721?ttl=0&recv_buf_size=4194304"
  tmp=$(mktemp -d)
  pids=()
  cleanup() { kill "${pids[@]}" 2>/dev/null || true; wait 2>/dev/null || true; rm -rf "$tmp"; }
  trap cleanup EXIT
  for case in "pendulum 2 15 1 ahhs2" "pendulum 2 15 2 ahhs1" "gait 5 5 3 ahhs2" "gait 4 5 4 ahhs1"; do
    set -- $case
    pids=()
    "$bin/bin/ahhs-sim" --lcm-url "$url" --episodes 1 2>"$tmp/sim.err" & sim=$!
    "$bin/bin/ahhs-fitness" --lcm-url "$url" --episodes 1 >/dev/null & pids+=($!)
    for ((m = 0; m < $2; m++)); do "$bin/bin/ahhs-module" --id $m --lcm-url "$url" 2>/dev/null & pids+=($!); done
    if ! timeout 120 "$bin/bin/arena_driver" --lcm-url "$url" --scenario $1 --modules $2 \
         --duration $3 --seed $4 --variant $5 >"$tmp/drv.out"; then
      echo "FAIL ($case): driver"; cat "$tmp/sim.err"; exit 1
    fi
    wait $sim
    kill "${pids[@]}"; wait "${pids[@]}" 2>/dev/null || true
    want=$(grep "^fitness " "$tmp/drv.out" | cut -d" " -f2)
    echo "$case: in-process $want"; tail -1 "$tmp/sim.err"
    grep -q "fitness $want; missed 0, late 0, dropped 0" "$tmp/sim.err" || { echo "FAIL ($case)"; exit 1; }
  done
  echo "multi-process arena equals in-process, bit for bit"
' _ "$bin"
