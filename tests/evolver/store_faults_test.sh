#!/usr/bin/env bash
# The run store as an adversary finds it (docs/evolution.md, "What we guarantee"): a store
# changed after it was written, a missing table, a read-only directory and a full disk each give
# one clear line and exit 1 from ahhs-evolve --resume (and ahhs-replay), never SIGABRT, never a
# silent resume; the store they refused is left as it was.
bin=${1:?usage: store_faults_test.sh BIN_DIR}
source "${AHHS_SOURCE_DIR:?}/tests/lib.sh"
ahhs_netns "$0" "$@"
ahhs_scratch 'ahhs-evolve|ahhs-worker'
E="$bin/ahhs-evolve"
url="udpm://239.255.42.61:7752?ttl=0"
# One error line on stderr, exit 1, nothing that looks like a crash.
refused() {  # refused EXPECTED_TEXT COMMAND...
  local want=$1; shift
  "$@" >$tmp/out 2>$tmp/err; local rc=$?
  [[ $rc == 1 ]] || fail "$*: exit $rc (want 1): $(cat $tmp/out $tmp/err)"
  grep -q -- "$want" $tmp/err || fail "$*: $(cat $tmp/err)"
  [[ $(wc -l <$tmp/err) == 1 ]] || fail "$*: more than one line: $(cat $tmp/err)"
  echo "  $(cat $tmp/err)"
}
run=(--scenario pendulum --population 6 --generations 6 --duration 2 --workers 1 --lcm-url "$url")
"$E" "${run[@]}" --out $tmp/run --seed 4 >/dev/null 2>&1 || fail "the run"
"$E" "${run[@]}" --out $tmp/half --seed 4 >/dev/null 2>&1 || fail "the run"
sqlite3 $tmp/half/run.sqlite "DELETE FROM individuals WHERE generation >= 3;
  DELETE FROM generations WHERE generation >= 3; DELETE FROM chain WHERE generation >= 3"
cp -r $tmp/half $tmp/half-copy

echo "== a store changed after it was written"
cp -r $tmp/run $tmp/t
sqlite3 $tmp/t/run.sqlite "UPDATE individuals SET fitness = fitness * (1 + 4.5e-16) WHERE generation = 4 AND idx = 1"
before=$(sha256sum <$tmp/t/run.sqlite)
refused "run.sqlite: generation 4 does not match its digest: .*(generations 0-3 are intact)" \
  "$E" --resume $tmp/t --lcm-url "$url"
refused "generation 4 does not match its digest" "$bin/ahhs-replay" $tmp/t
[[ $(sha256sum <$tmp/t/run.sqlite) == "$before" ]] || fail "the refused store was changed"

echo "== a missing table"
for table in sessions generations individuals chain run; do
  rm -rf $tmp/t && cp -r $tmp/half $tmp/t
  sqlite3 $tmp/t/run.sqlite "DROP TABLE $table"
  refused "no such table: $table\|not a readable run database" "$E" --resume $tmp/t --lcm-url "$url"
done

echo "== a read-only directory (a read-only bind mount: root ignores file modes)"
unshare -m bash -c "mount --bind -o ro $tmp/half $tmp/half && '$E' --resume $tmp/half --lcm-url '$url'" \
  >$tmp/out 2>$tmp/err
rc=$?
[[ $rc == 1 ]] || fail "read-only: exit $rc: $(cat $tmp/out $tmp/err)"
grep -qi "read-only file system" $tmp/err || fail "read-only message: $(cat $tmp/err)"
echo "  $(cat $tmp/err)"

echo "== a full disk"
mkdir $tmp/small
whole=$(sqlite3 $tmp/run/run.sqlite "SELECT group_concat(fitness) FROM individuals ORDER BY generation, idx")
# A 1 MiB tmpfs holding the half run, then filled to leave FILL kB: the session row, the WAL or
# a later generation cannot be written. Once space is freed the run resumes to the whole run.
for fill in 0 8 64; do
  unshare -m bash -c "
    mount -t tmpfs -o size=1m tmpfs $tmp/small && cp -r $tmp/half-copy $tmp/small/r &&
    head -c \$(( \$(stat -f -c '%a*%S' $tmp/small) - $fill * 1024 )) /dev/zero >$tmp/small/fill 2>/dev/null;
    '$E' --resume $tmp/small/r --lcm-url '$url' >$tmp/out 2>$tmp/err; echo \$? >$tmp/rc
    rm $tmp/small/fill
    '$E' --resume $tmp/small/r --lcm-url '$url' >$tmp/out2 2>&1; echo \$? >$tmp/rc2
    sqlite3 $tmp/small/r/run.sqlite 'SELECT group_concat(fitness) FROM individuals ORDER BY generation, idx' >$tmp/after" 2>/dev/null
  rc=$(cat $tmp/rc)
  [[ $rc == 1 ]] || fail "full disk ($fill kB free): exit $rc: $(cat $tmp/out $tmp/err)"
  grep -q "is full\|No space" $tmp/err || fail "full disk message: $(cat $tmp/err)"
  ! grep -q "terminate\|Aborted" $tmp/err || fail "full disk crashed: $(cat $tmp/err)"
  echo "  $fill kB free: $(grep -m1 "is full\|No space" $tmp/err | cut -c1-160)"
  [[ $(cat $tmp/rc2) == 0 && $(cat $tmp/after) == "$whole" ]] ||
    fail "resumed with space again ($fill kB): $(cat $tmp/out2)"
done
echo "  each resumed, with space again, to the whole run"
echo PASS
