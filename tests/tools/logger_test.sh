#!/usr/bin/env bash
# ahhs-logger, inside a private network namespace:
#  1. bad input: an existing file without --force, an unusable URL, no file: clear message, exit 1;
#  2. a burst of 3,000 messages published back to back is recorded whole (stopped by SIGINT),
#     and a smaller one when stopped by SIGTERM; the log is read back with lcm::LogFile;
#  3. Debian's lcm-logger on the same burst writes a readable log without duplicates; how much
#     of the burst it kept is printed (its 30-message queue loses part of a burst).
bin=${1:?usage: logger_test.sh BIN_DIR}
source "${AHHS_SOURCE_DIR:?}/tests/lib.sh"
ahhs_netns "$0" "$@"
ahhs_scratch 'ahhs-logger'
url="udpm://239.255.42.90:7781?ttl=0&recv_buf_size=4194304"

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

echo "== 3. lcm-logger on the same burst"
[[ -x /usr/bin/lcm-logger ]] || fail "no /usr/bin/lcm-logger (liblcm-bin)"
n=3000 signal=INT record /usr/bin/lcm-logger --lcm-url="$url" --quiet --force
"$bin/log_check" $tmp/burst.log --burst-channel TEST/BURST --ticks 3000 >$tmp/check.out 2>&1
line=$(grep -o "[0-9]* of 3000 burst ticks missing, [0-9]* duplicates" $tmp/check.out) ||
  fail "lcm-logger's log is not readable: $(cat $tmp/check.out)"
missing=${line%% of *}
[[ $missing -lt 3000 && "$line" == *", 0 duplicates" ]] || fail "lcm-logger: $line"
echo "lcm-logger kept $((3000 - missing)) of the 3000 messages (ahhs-logger: all)"
echo "all ahhs-logger checks passed"
