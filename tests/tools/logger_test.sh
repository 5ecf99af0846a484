#!/usr/bin/env bash
# ahhs-logger, inside a private network namespace:
#  1. bad input: an existing file without --force, an unusable URL, no file: clear message, exit 1;
#  2. a burst of 3,000 messages published back to back is recorded whole (stopped by SIGINT),
#     and a smaller one when stopped by SIGTERM; the log is read back with lcm::LogFile;
#  3. for comparison (not asserted): what Debian's lcm-logger keeps of the same burst.
set -uo pipefail
bin=${1:?usage: logger_test.sh BIN_DIR}
[[ "${AHHS_IN_NETNS:-}" == 1 ]] || exec "${AHHS_SOURCE_DIR:?}/tools/ahhs-netns" bash "$0" "$@"
url="udpm://239.255.42.90:7781?ttl=0&recv_buf_size=4194304"
tmp=$(mktemp -d)
# Processes of this test only: its process group (never a run of the same build elsewhere).
pg=$(ps -o pgid= -p $$ | tr -d ' ')
trap 'pkill -g "$pg" -f "$bin/ahhs-logger" 2>/dev/null; rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
wait_for_file() { for _ in $(seq 200); do [[ -e "$1" ]] && return 0; sleep 0.02; done; fail "no $1"; }

echo "== 1. bad input"
touch $tmp/exists.log
"$bin/ahhs-logger" --lcm-url "$url" $tmp/exists.log 2>$tmp/err && fail "overwrote a file"
grep -q "exists (use --force" $tmp/err || fail "message: $(cat $tmp/err)"
[[ ! -s $tmp/exists.log ]] || fail "existing file touched"
"$bin/ahhs-logger" --lcm-url "nosuch://x" $tmp/bad.log 2>$tmp/err && fail "bad URL accepted"
grep -q "cannot open LCM URL" $tmp/err || fail "message: $(cat $tmp/err)"
[[ ! -e $tmp/bad.log ]] || fail "a file was left for a bad URL"
"$bin/ahhs-logger" --lcm-url "$url" 2>$tmp/err && fail "no FILE accepted"
grep -q "FILE is required" $tmp/err || fail "message: $(cat $tmp/err)"

record() {  # record LOGGER_COMMAND... : records one burst of $n messages into $tmp/burst.log
  rm -f $tmp/burst.log
  "$@" $tmp/burst.log 2>$tmp/logger.err & lp=$!
  wait_for_file $tmp/burst.log
  "$bin/bus_peer" --role burst --lcm-url "$url" --burst $n >/dev/null || fail "burst"
  sleep 0.5
  kill -$signal $lp
  wait $lp || fail "logger exit status after SIG$signal: $(cat $tmp/logger.err)"
}

echo "== 2. bursts are recorded whole"
n=3000 signal=INT record "$bin/ahhs-logger" --lcm-url "$url"
cat $tmp/logger.err
"$bin/log_check" $tmp/burst.log --burst-channel TEST/BURST --ticks 3000 || fail "burst not recorded whole"
n=500 signal=TERM record "$bin/ahhs-logger" --lcm-url "$url"
"$bin/log_check" $tmp/burst.log --burst-channel TEST/BURST --ticks 500 || fail "SIGTERM: log incomplete"

echo "== 3. lcm-logger on the same burst (for comparison, not checked)"
if [[ -x /usr/bin/lcm-logger ]]; then
  n=3000 signal=INT record /usr/bin/lcm-logger --lcm-url="$url" --quiet --force
  "$bin/log_check" $tmp/burst.log --burst-channel TEST/BURST --ticks 3000 || true
fi
echo "all ahhs-logger checks passed"
