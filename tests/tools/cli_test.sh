#!/usr/bin/env bash
# The command-line conventions every program shares (docs/development.md, "Exit codes and
# errors"): --help exits 0; an unknown option, a bad value or an unknown config key exits 2 with
# one line naming the program, and a mistyped name gets the nearest known one.
bin=${1:?usage: cli_test.sh BIN_DIR}
source "${AHHS_SOURCE_DIR:?}/tests/lib.sh"
ahhs_scratch
usage_error() {  # usage_error EXPECTED_TEXT PROGRAM ARGS...
  local want=$1; shift
  "$@" >$tmp/out 2>$tmp/err; local rc=$?
  [[ $rc == 2 ]] || fail "$*: exit $rc (want 2): $(cat $tmp/err)"
  [[ $(wc -l <$tmp/err) == 1 && ! -s $tmp/out ]] || fail "$*: not one line on stderr: $(cat $tmp/out $tmp/err)"
  grep -q -- "^$(basename $1): .*$want" $tmp/err || fail "$*: $(cat $tmp/err)"
  echo "$(basename $1): $(cat $tmp/err)"
}
for p in ahhs-evolve ahhs-worker ahhs-fitness ahhs-launch ahhs-replay ahhs-sim ahhs-module ahhs-genome \
         ahhs-logger ahhs-bench ahhs-study; do
  "$bin/$p" --help >$tmp/out 2>&1 || fail "$p --help exits $?"
  grep -q "^Usage:" $tmp/out || grep -q "Usage:" $tmp/out || fail "$p --help: $(head -3 $tmp/out)"
  usage_error "frobnicate" "$bin/$p" --frobnicate
done
usage_error "did you mean --population?" "$bin/ahhs-evolve" --populaton 4
usage_error "Could not convert" "$bin/ahhs-evolve" --population many
usage_error "did you mean --scenario?" "$bin/ahhs-sim" --scenaro gait
usage_error "did you mean --parallel?" "$bin/ahhs-study" run --paralel 2
printf 'scenario = "pendulum"\npopulaton = 5\n' >$tmp/bad.toml
usage_error "unknown key 'populaton' in the config file (did you mean population?)" \
  "$bin/ahhs-evolve" --config $tmp/bad.toml --show-config
# The scripts: ahhs-netns prints its own help (not bash's), ahhs-report exits 2 on a bad option.
"${AHHS_SOURCE_DIR:?}/tools/ahhs-netns" --help >$tmp/out 2>&1 || fail "ahhs-netns --help exits $?"
grep -q "^usage: ahhs-netns COMMAND" $tmp/out || fail "ahhs-netns --help: $(cat $tmp/out)"
"$bin/ahhs-report" --frobnicate >/dev/null 2>&1; [[ $? == 2 ]] || fail "ahhs-report --frobnicate"
"$bin/ahhs-report" --help | grep -q "ahhs-report neighbourhood" || fail "ahhs-report --help does not name neighbourhood"
echo PASS
