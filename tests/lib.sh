# The prologue the shell tests share. A test starts with
#   bin=${1:?usage: NAME.sh BIN_DIR}
#   source "${AHHS_SOURCE_DIR:?}/tests/lib.sh"
#   ahhs_netns "$0" "$@"          # multi-process tests: re-run inside a private network namespace
#   ahhs_scratch 'ahhs-evolve|ahhs-worker'
# ahhs_scratch makes $tmp and $pg (the process group) and, on exit, kills this test's own processes (its process group, never
# a run of the same build elsewhere) whose command matches $bin/(PATTERN), then removes $tmp.
set -uo pipefail

fail() {
  echo "FAIL: $*"
  exit 1
}

# Also gives the test a process group of its own: CTest runs every test in CTest's own group, so
# without this `pgrep -g "$pg"` and the cleanup would reach the processes of any test running
# beside it (unit tests do; multiprocess ones hold a lock against each other only). setsid does not fork here (under
# CTest the test is not a group leader); run by hand from a shell, the test already leads its own
# group and keeps it, so Ctrl-C still reaches it.
ahhs_netns() {
  [[ "${AHHS_IN_NETNS:-}" == 1 ]] && return
  local own=()
  [[ $(ps -o pgid= -p $$ | tr -d ' ') == "$$" ]] || own=(setsid)
  exec "${own[@]}" "${AHHS_SOURCE_DIR:?}/tools/ahhs-netns" bash "$@"
}

# ahhs_own_group "$0" "$@": only the process group of its own, for a test that cannot run in a
# network namespace but kills by pattern (ahhs_scratch PATTERN).
ahhs_own_group() {
  [[ $(ps -o pgid= -p $$ | tr -d ' ') == "$$" ]] && return
  exec setsid bash "$@"
}

ahhs_scratch() {
  tmp=$(mktemp -d)
  pg=$(ps -o pgid= -p $$ | tr -d ' ')
  _ahhs_kill=${1:-}
  # Killing by pattern in CTest's own group would reach the tests running beside this one.
  if [[ -n "$_ahhs_kill" && "$pg" != "$$" && -z "${AHHS_IN_NETNS:-}" ]]; then
    rm -rf "$tmp"
    fail "ahhs_scratch PATTERN needs a process group of its own: call ahhs_netns or ahhs_own_group first"
  fi
  trap _ahhs_cleanup EXIT
}

_ahhs_cleanup() {
  if [[ -n "$_ahhs_kill" ]]; then pkill -g "$pg" -KILL -f "$bin/($_ahhs_kill)" 2>/dev/null; fi
  if declare -F ahhs_lan_down >/dev/null; then ahhs_lan_down; fi  # tests/lan.sh
  rm -rf "$tmp"
}

# ci_tier_only WHAT: true in the sanitizer tier (the asan test preset sets AHHS_TEST_TIER), where a
# test skips a part that the sanitizers cannot add to: Python figures and tables over files its
# C++ part made, or more of the same C++ path with other numbers (a physics check that repeats
# the replay that the sanitizer tier already ran once). Such a part is checked in the ci tier,
# which runs every test whole; the sanitizers look for memory errors in the C++
# (docs/development.md, "Tests").
ci_tier_only() {
  [[ "${AHHS_TEST_TIER:-}" == asan ]] || return 1
  echo "  (sanitizer tier: $1 is checked in the ci tier)"
}

# dump_run RUN_DIR: every individual of a run, a line each: genome, seeds, elite, fitness and cost
# to the last bit; what must not depend on how the run was run (layout, faults, resumes).
dump_run() {
  sqlite3 "$1/run.sqlite" "SELECT generation, idx, genome_hash, eval_seed, elite,
    printf('%!.17g', fitness), printf('%!.17g', cost) FROM individuals ORDER BY generation, idx"
  # Every trial of a run that evaluates each individual several times (store format 4).
  if [[ $(sqlite3 "$1/run.sqlite" "SELECT COUNT(*) FROM sqlite_master WHERE name = 'trials'") == 1 ]]; then
    sqlite3 "$1/run.sqlite" "SELECT 'trial', generation, idx, trial, seed,
      printf('%!.17g', fitness), printf('%!.17g', cost) FROM trials ORDER BY generation, idx, trial"
  fi
}

# wait_for_file PATH: up to 4 s for PATH to appear.
wait_for_file() {
  for _ in $(seq 200); do [[ -e "$1" ]] && return 0; sleep 0.02; done
  fail "no $1"
}

# Real-time episodes wait for no one: under load (clean-clone CI, tests beside) a controller can
# miss a tick (the sim's readings of the next tick come first) and the last ticks' commands can
# reach a board after the episode (58 and 59 of 60 seen). These checks put a floor (TICKS - 5) on
# those counts and keep the rest exact.
# realtime_controller_ok OUT MODULE TICKS: "ahhs-module MODULE" in OUT stepped at least TICKS-5
# ticks, counted every other one as late, and dropped nothing.
realtime_controller_ok() {
  local line ticks late
  line=$(grep "ahhs-module $2:" "$1")
  read -r ticks late < <(sed -n 's/.*: \([0-9]*\) ticks, [0-9]* missing packets, \([0-9]*\) late, 0 dropped.*/\1 \2/p' <<<"$line")
  (( ${ticks:-0} >= $3 - 5 && ticks + late == $3 )) || fail "module $2's controller: ${line:-no summary in $1}"
}
# realtime_firmware_ok OUT TICKS: the example firmware sent TICKS readings, applied at least
# TICKS-5 commands, dropped none and heard no other module's readings. Sets fw_applied (the count).
realtime_firmware_ok() {
  local line
  line=$(grep -E "^firmware of module [0-9]+: $2 readings sent, [0-9]+ commands applied, 0 dropped, 0 readings of others" "$1")
  fw_applied=$(sed -E 's/.* ([0-9]+) commands applied.*/\1/' <<<"$line")
  (( ${fw_applied:-0} >= $2 - 5 && fw_applied <= $2 )) || fail "firmware: $(cat "$1")"
}
