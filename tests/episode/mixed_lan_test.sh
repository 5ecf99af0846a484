#!/usr/bin/env bash
# A mixed organism over a LAN of network namespaces (root only; skipped otherwise): host 0 is the
# lab PC (ahhs-launch: the sim, the fitness monitor and the controllers of modules 0 and 2), host 1
# is module 1's board (the C reference firmware for its body and the Lua controller for its
# hormones). Multicast with ttl=1 crosses the bridge between them and nothing else. The sim
# publishes no readings for module 1 and its digital twin follows the firmware's hinge angle;
# every command of the real-time episode reaches the board, and module 1's controller steps on
# its own firmware's readings only.
bin=${1:?usage: mixed_lan_test.sh BIN_DIR}
source "${AHHS_SOURCE_DIR:?}/tests/lib.sh"
source "${AHHS_SOURCE_DIR:?}/tests/lan.sh"
ahhs_scratch
ahhs_lan 2
pc=${lan_hosts[0]} board=${lan_hosts[1]}
url="udpm://239.255.42.71:7763?ttl=1&recv_buf_size=4194304"
"$bin/ahhs-genome" random --variant ahhs2 --hormones 5 --rules 30 --sensors 4 --actuators 1 --seed 3 >$tmp/g.json

echo "== module 1 on its own board (host 1), everything else on the lab PC (host 0)"
in_host $board "$bin/ahhs-example-firmware" --arena LAB --id 1 --lcm-url "$url" --seconds 30 >$tmp/firmware.out 2>&1 &
fw=$!
in_host $board "$bin/ahhs-example-controller-lua" --arena LAB --id 1 --lcm-url "$url" --seconds 30 >$tmp/lua.out 2>&1 &
in_host $pc "$bin/ahhs-launch" --scenario gait --modules 3 --genome $tmp/g.json --seed 5 --duration 3 --realtime \
  --lcm-url "$url" --arena LAB --hardware-modules 1 --external module:1 --external-timeout 10 -v >$tmp/pc.out 2>&1 ||
  { cat $tmp/pc.out $tmp/lua.out; fail "the mixed organism's episode"; }
pkill -TERM -f "$bin/ahhs-example-firmware --arena LAB --id 1"  # ip netns exec forwards no signal
wait $fw
cat $tmp/firmware.out
realtime_firmware_ok $tmp/firmware.out 60  # floors: tests/lib.sh
followed=$(sed -n 's/.*hardware readings followed \([0-9]*\).*/\1/p' $tmp/pc.out)
(( ${followed:-0} >= 50 )) || fail "the sim followed ${followed:-no} hardware readings: $(grep ahhs-sim $tmp/pc.out)"
for m in 0 2; do realtime_controller_ok $tmp/pc.out $m 60; done
fitness=$(tail -1 $tmp/pc.out | sed -n 's/^fitness: //p')
[[ -n "$fitness" ]] || fail "no fitness: $(tail -3 $tmp/pc.out)"
echo "the sim's twin of module 1 followed $followed readings from the board, $fw_applied of 60 commands reached it; fitness $fitness"
echo "PASS"
