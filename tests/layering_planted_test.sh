#!/usr/bin/env bash
# tests/layering_test.py must fail on each kind of break: planted in a scratch tree, each one is
# named with its file and line, and the check exits 1.
bin=unused
source "${AHHS_SOURCE_DIR:?}/tests/lib.sh"
ahhs_scratch
check="${AHHS_SOURCE_DIR}/tests/layering_test.py"
plant() {  # plant FILE INCLUDE EXPECTED
  rm -rf "$tmp/tree"; mkdir -p "$tmp/tree/$(dirname "$1")"
  echo "#include $2" >"$tmp/tree/$1"
  python3 "$check" "$tmp/tree" >"$tmp/out"; local rc=$?
  [[ $rc == 1 ]] && grep -q "^$1:1: .*$3" "$tmp/out" || fail "$1 including $2: exit $rc: $(cat "$tmp/out")"
  echo "caught: $(head -1 "$tmp/out")"
}
plant evolver/farm/a.cc '"tools/launch/x.h"' "higher layer"
plant sim/core/b.cc '"bus/bus.h"' "the core sim/core includes"
plant modules/core/c.cc '<ahhs/genome_t.hpp>' "includes LCM"
plant sim/node/d.cc '"sim/app/main.h"' "includes the main"
plant bus/e.cc '"modules/core/genome.h"' "higher layer"
plant_files() {  # plant_files EXPECTED_FILE:LINE EXPECTED FILE CONTENT [FILE CONTENT...]
  local at=$1 expected=$2; shift 2
  rm -rf "$tmp/tree"
  while [[ $# -gt 0 ]]; do
    mkdir -p "$tmp/tree/$(dirname "$1")"; printf '%b\n' "$2" >"$tmp/tree/$1"; shift 2
  done
  python3 "$check" "$tmp/tree" >"$tmp/out"; local rc=$?
  [[ $rc == 1 ]] && grep -q "^$at: .*$expected" "$tmp/out" || fail "expected $at: $expected; exit $rc: $(cat "$tmp/out")"
  echo "caught: $(head -1 "$tmp/out")"
}
plant_files bus/CMakeLists.txt:2 "links ahhs_s of the higher layer sim/" \
  bus/CMakeLists.txt 'add_library(ahhs_b b.cc)\ntarget_link_libraries(ahhs_b PUBLIC ahhs_s)' \
  sim/CMakeLists.txt 'add_library(ahhs_s core/s.cc)'
plant_files sim/CMakeLists.txt:3 "the core sim/core target ahhs_c links ahhs_bus" \
  sim/CMakeLists.txt '# the core\nadd_library(ahhs_c core/c.cc)\ntarget_link_libraries(ahhs_c\n  PUBLIC ahhs_bus)'
plant_files tools/report/b.py:1 "import cycle a -> b -> a" \
  tools/report/a.py 'import os\n\ndef f():\n    import b' tools/report/b.py 'from a import f'
rm -rf "$tmp/tree"; mkdir -p "$tmp/tree/sim/core"; echo '#include "modules/core/genome.h"' >"$tmp/tree/sim/core/ok.cc"
python3 "$check" "$tmp/tree" >/dev/null || fail "a lawful include was refused"
echo PASS
