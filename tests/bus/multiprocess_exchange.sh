#!/usr/bin/env bash
# Two real processes exchange typed messages over udpm inside a private network namespace:
# 100 checked ping-pongs, then a burst of 2,000 messages with none lost.
set -euo pipefail
peer=${1:?usage: multiprocess_exchange.sh PATH/TO/bus_peer}
netns=${AHHS_SOURCE_DIR:?}/tools/ahhs-netns
# Raised receive buffer: default socket buffers drop bursts.
url='udpm://239.255.42.10:7701?ttl=0&recv_buf_size=4194304'
exec "$netns" bash -c '
  set -u
  "$1" --role responder --lcm-url "$2" & responder=$!
  "$1" --role initiator --lcm-url "$2" --pings 100 --burst 2000; rc=$?
  wait $responder; rr=$?
  [ $rc -eq 0 ] && [ $rr -eq 0 ]
' _ "$peer" "$url"
