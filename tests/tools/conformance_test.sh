#!/usr/bin/env bash
# ahhs-conformance (docs/hardware.md, "Conformance kit"), inside a private network namespace:
# the reference firmware and tracker (examples/) pass every check; a firmware on its own timer
# that follows any episode's HINGE, and a tracker that does not copy the episode, fail the
# checks they break, with the evidence, and exit 1.
bin=${1:?usage: conformance_test.sh BIN_DIR}
source "${AHHS_SOURCE_DIR:?}/tests/lib.sh"
ahhs_netns "$0" "$@"
url="udpm://239.255.42.52:7747?ttl=0&recv_buf_size=4194304"
ahhs_scratch 'ahhs-[a-z-]+|role_peer'
kit() { "$bin/ahhs-conformance" "$@" --lcm-url "$url"; }

echo "== the reference firmware and tracker pass"
"$bin/ahhs-example-firmware" --arena OK --id 2 --lcm-url "$url" --seconds 20 >/dev/null &
"$bin/ahhs-example-tracker" --arena OK --modules 3 --lcm-url "$url" --seconds 20 >/dev/null &
sleep 0.3
kit firmware --arena OK --id 2 >$tmp/fw.out || { cat $tmp/fw.out; fail "the reference firmware"; }
[[ $(grep -c '^PASS' $tmp/fw.out) -eq 7 ]] || fail "firmware checklist: $(cat $tmp/fw.out)"
kit tracker --arena OK --modules 3 >$tmp/tr.out || { cat $tmp/tr.out; fail "the reference tracker"; }
[[ $(grep -c '^PASS' $tmp/tr.out) -eq 5 ]] || fail "tracker checklist: $(cat $tmp/tr.out)"
grep "budget" $tmp/fw.out $tmp/tr.out

echo "== planted faults fail"
"$bin/role_peer" --role drifting-firmware --arena BAD --id 1 --lcm-url "$url" --seconds 20 >/dev/null &
"$bin/role_peer" --role stale-tracker --arena BAD --modules 3 --lcm-url "$url" --seconds 20 >/dev/null &
sleep 0.3
code=0
kit firmware --arena BAD --id 1 >$tmp/bad-fw.out || code=$?
[[ $code -eq 1 ]] || { cat $tmp/bad-fw.out; fail "a drifting firmware: exit $code, not 1"; }
grep -q "^FAIL one reading per tick" $tmp/bad-fw.out || fail "drift not caught: $(cat $tmp/bad-fw.out)"
grep -q "^FAIL follows HINGE of its episode, ignores a foreign episode's: last hinge_angle -1" $tmp/bad-fw.out ||
  fail "foreign HINGE not caught: $(cat $tmp/bad-fw.out)"
grep -q "NOT conformant" $tmp/bad-fw.out || fail "no verdict"
code=0
kit tracker --arena BAD --modules 3 >$tmp/bad-tr.out || code=$?
[[ $code -eq 1 ]] || { cat $tmp/bad-tr.out; fail "a stale tracker: exit $code, not 1"; }
grep -q "^FAIL one state per tick, with the clock's episode and tick: 60 ticks played: 60 without" $tmp/bad-tr.out ||
  fail "episode not copied, not caught: $(cat $tmp/bad-tr.out)"
grep '^FAIL' $tmp/bad-fw.out $tmp/bad-tr.out

echo "== usage"
code=0
"$bin/ahhs-conformance" module --arena X >$tmp/usage.out 2>&1 || code=$?
[[ $code -eq 2 ]] || fail "an unknown role: exit $code"
code=0
"$bin/ahhs-conformance" firmware --arena X >$tmp/usage.out 2>&1 || code=$?
[[ $code -eq 2 ]] && grep -q "firmware needs --id N" $tmp/usage.out || fail "firmware without --id: exit $code, $(cat $tmp/usage.out)"
echo "PASS"
