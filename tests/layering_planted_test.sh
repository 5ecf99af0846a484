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
rm -rf "$tmp/tree"; mkdir -p "$tmp/tree/sim/core"; echo '#include "modules/core/genome.h"' >"$tmp/tree/sim/core/ok.cc"
python3 "$check" "$tmp/tree" >/dev/null || fail "a lawful include was refused"
echo PASS
