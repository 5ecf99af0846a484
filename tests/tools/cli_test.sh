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
usage_error "bad.toml:2: unknown key 'populaton' (did you mean population?)" \
  "$bin/ahhs-evolve" --config $tmp/bad.toml --show-config
# Config files are TOML, read strictly (a real parser): each error names the file and line.
config_error() {  # config_error EXPECTED_TEXT FILE_TEXT
  printf '%b' "$2" >$tmp/c.toml
  usage_error "c.toml:$1" "$bin/ahhs-evolve" --config $tmp/c.toml --show-config
}
config_error "2: .*cannot redefine existing integer 'rules'" 'rules = 30\nrules = 40\n'
config_error "3: 'foo' is a section" '# a comment\nrules = 3\n[foo]\nbar = 1\n'
config_error "1: 'rules' is a list" 'rules = [1, 2]\n'
config_error "1: Error while parsing value" 'rules = = 3\n'
config_error "1: .*unescaped control characters" 'scenario = "gait\n'
config_error "2: 'rules' must be a whole number" 'seed = 3\nrules = 3.5\n'
config_error "1: 'overwrite' must be true or false" 'overwrite = 1\n'
config_error "1: 'scenario' must be a string" 'scenario = 3\n'
config_error "1: a config file cannot name another" 'config = "x.toml"\n'
config_error "1: .*not representable in 64 bits .*as a string" 'seed = 18446744073709551615\n'
# What a valid file says holds, a seed above 2^63 as a string, and the command line wins.
printf 'scenario = "pendulum"\nseed = "18446744073709551615"\nmutation-rate = 1\n' >$tmp/ok.toml
"$bin/ahhs-evolve" --config $tmp/ok.toml --show-config >$tmp/out || fail "a valid config was refused"
grep -q '"seed": 18446744073709551615' $tmp/out && grep -q '"scenario": "pendulum"' $tmp/out &&
  grep -q '"mutation_rate": 1.0' $tmp/out || fail "config values: $(cat $tmp/out)"
"$bin/ahhs-evolve" --config $tmp/ok.toml --scenario gait --show-config | grep -q '"scenario": "gait"' ||
  fail "the command line does not override the config file"
# The scripts: ahhs-netns prints its own help (not bash's), ahhs-report exits 2 on a bad option.
"${AHHS_SOURCE_DIR:?}/tools/ahhs-netns" --help >$tmp/out 2>&1 || fail "ahhs-netns --help exits $?"
grep -q "^usage: ahhs-netns COMMAND" $tmp/out || fail "ahhs-netns --help: $(cat $tmp/out)"
"$bin/ahhs-report" --frobnicate >/dev/null 2>&1; [[ $? == 2 ]] || fail "ahhs-report --frobnicate"
"$bin/ahhs-report" --help | grep -q "ahhs-report neighbourhood" || fail "ahhs-report --help does not name neighbourhood"
echo PASS
