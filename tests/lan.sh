# A LAN of network namespaces for tests (root only), sourced after tests/lib.sh:
#   ahhs_lan N     a switch namespace ($lan_switch) with a bridge (no multicast snooping) and N
#                  hosts (${lan_hosts[@]}) joined to it by veth pairs, host i at 10.213.0.(i+1)/24
#                  on v<i> (the bridge port is p<i>), multicast routed to the bridge. No namespace
#                  has any other interface, so ttl=1 multicast crosses the bridge and goes nowhere
#                  else. Exits 77 (skipped) when namespaces cannot be made here.
#   in_host H CMD  runs CMD on host H.
# The namespaces and their processes are removed when the test exits (via _ahhs_cleanup).
skip() {
  echo "SKIPPED: $*"
  exit 77
}

in_host() {
  local h=$1
  shift
  ip netns exec "$h" "$@"
}

ahhs_lan_down() {
  local h
  for h in "${lan_hosts[@]}"; do
    ip netns pids "$h" 2>/dev/null | xargs -r kill -KILL 2>/dev/null
    ip netns del "$h" 2>/dev/null
  done
  [[ -n "${lan_switch:-}" ]] && ip netns del "$lan_switch" 2>/dev/null
  return 0
}

ahhs_lan() {
  local n=$1 tag=ahhs$$ i h
  [[ $(id -u) == 0 ]] || skip "needs root to make network namespaces (ip netns)"
  command -v ip >/dev/null || skip "ip (iproute2) not found"
  lan_hosts=()
  lan_switch=$tag-sw
  ip netns add "$lan_switch" 2>/dev/null || { lan_switch=; skip "cannot create network namespaces here"; }
  ip -n "$lan_switch" link add br0 type bridge || fail "bridge"
  ip -n "$lan_switch" link set br0 type bridge mcast_snooping 0
  ip -n "$lan_switch" link set br0 up
  for ((i = 0; i < n; ++i)); do
    h=$tag-h$i
    ip netns add "$h" || fail "netns $h"
    lan_hosts+=("$h")
    ip link add v$i netns "$h" type veth peer name p$i netns "$lan_switch" || fail "veth $i"
    ip -n "$lan_switch" link set p$i master br0
    ip -n "$lan_switch" link set p$i up
    ip -n "$h" link set lo up
    ip -n "$h" addr add 10.213.0.$((i + 1))/24 dev v$i
    ip -n "$h" link set v$i up
    ip -n "$h" link set v$i multicast on
    ip -n "$h" route add 224.0.0.0/4 dev v$i
  done
}
