#!/usr/bin/env bash
# The module board's package built for arm64 (tools/cross-arm64) and run here under qemu-user:
#  1. its ahhs-module speaks the native wire format (--version's wire line);
#  2. the arm64 controller (ahhs-genome run: AHHS2 and AHHS1 genomes, three compartments, on
#     recorded sensors) prints the native numbers to the last bit;
#  3. as external modules of an x86-64 arena (ahhs-launch --external), one module and then the
#     whole organism give the fitness of the native process arena, to the bit.
# Needs the cross toolchain, qemu-user and the arm64 architecture (tools/cross-arm64
# --install-deps); skipped without them. Part 3 needs threads (LCM's receiver), and is skipped,
# saying so, where qemu-user cannot start one (qemu 7.2 under a 6.18 kernel: pthread_create
# never returns).
bin=${1:?usage: arm64_module_test.sh BIN_DIR}
source "${AHHS_SOURCE_DIR:?}/tests/lib.sh"
for tool in aarch64-linux-gnu-g++ qemu-aarch64; do
  command -v $tool >/dev/null ||
    { echo "SKIPPED: $tool missing (tools/cross-arm64 --install-deps installs the cross toolchain)"; exit 77; }
done
dpkg --print-foreign-architectures | grep -qx arm64 ||
  { echo "SKIPPED: the arm64 architecture is not added (tools/cross-arm64 --install-deps)"; exit 77; }
arm=${AHHS_BINARY_DIR:?}/arm64
# Outside the namespace (LCM's arm64 packages are downloaded the first time); inside it again,
# where it is up to date.
if [[ -z ${AHHS_IN_NETNS:-} ]]; then
  "$AHHS_SOURCE_DIR/tools/cross-arm64" "$arm" >"$AHHS_BINARY_DIR/arm64.log" 2>&1 ||
    { tail -20 "$AHHS_BINARY_DIR/arm64.log"; fail "tools/cross-arm64"; }
fi
ahhs_netns "$0" "$@"
url="udpm://239.255.42.82:7775?ttl=0&recv_buf_size=4194304"
ahhs_scratch 'ahhs-[a-z-]+'
trap 'pkill -g "$pg" -KILL -f "qemu-aarch64 $tmp/board" 2>/dev/null; _ahhs_cleanup' EXIT
deb=$(ls "$arm"/packages/ahhs-module_*_arm64.deb)
dpkg-deb -x "$deb" "$tmp/board" || fail "dpkg-deb -x $deb"
file -b "$tmp/board/usr/bin/ahhs-module" | grep -q "ARM aarch64" || fail "ahhs-module is not an arm64 program"
# The board's libraries: Debian's arm64 C runtime of the cross toolchain, GLib (multiarch), LCM
# (unpacked by tools/cross-arm64).
board_module() {
  QEMU_LD_PREFIX=/usr/aarch64-linux-gnu \
    LD_LIBRARY_PATH="$arm/lcm-arm64/usr/lib/aarch64-linux-gnu:/usr/lib/aarch64-linux-gnu" \
    qemu-aarch64 "$tmp/board/usr/bin/ahhs-module" "$@"
}
echo "== 1. the wire format"
[[ $(board_module --version | grep wire) == "$("$bin/ahhs-module" --version | grep wire)" ]] ||
  fail "the arm64 module's wire line differs from the native one"

echo "== 2. the controller's arithmetic, arm64 against native"
board_genome() {
  QEMU_LD_PREFIX=/usr/aarch64-linux-gnu LD_LIBRARY_PATH=/usr/lib/aarch64-linux-gnu \
    qemu-aarch64 "$arm/bin/ahhs-genome" "$@"
}
/usr/bin/python3 -c '
import random
r = random.Random(5)
print("tick,compartment,s0,s1,s2,s3")
for t in range(300):
    for c in range(3):
        print(f"{t},{c}," + ",".join(repr(r.random()) for _ in range(4)))' >"$tmp/sensors.csv"
for variant in ahhs2 ahhs1; do
  "$bin/ahhs-genome" random --variant $variant --hormones 5 --rules 20 --sensors 4 --actuators 1 \
    --seed 3 >"$tmp/g-$variant.json"
  "$bin/ahhs-genome" run "$tmp/g-$variant.json" --compartments 3 --sensors "$tmp/sensors.csv" \
    >"$tmp/native-$variant.csv" || fail "native ahhs-genome run"
  board_genome run "$tmp/g-$variant.json" --compartments 3 --sensors "$tmp/sensors.csv" \
    >"$tmp/board-$variant.csv" || fail "arm64 ahhs-genome run"
  cmp -s "$tmp/native-$variant.csv" "$tmp/board-$variant.csv" ||
    fail "$variant: the arm64 controller's numbers differ from the native ones"
  echo "$variant: 900 compartment-ticks, arm64 equal to native"
done

echo "== 3. arm64 modules in an x86-64 arena"
cat >"$tmp/thread.c" <<'C'
#include <pthread.h>
static void* run(void* arg) { return arg; }
int main(void) {
  pthread_t t;
  if (pthread_create(&t, 0, run, 0) != 0) return 1;
  return pthread_join(t, 0);
}
C
aarch64-linux-gnu-gcc -pthread "$tmp/thread.c" -o "$tmp/thread" || fail "the thread probe does not build"
if ! QEMU_LD_PREFIX=/usr/aarch64-linux-gnu timeout 10 qemu-aarch64 "$tmp/thread"; then
  echo "SKIPPED (parts 1 and 2 passed): qemu-aarch64 $(qemu-aarch64 --version | head -1 |
    sed 's/.*version //') cannot start a thread under kernel $(uname -r) (pthread_create never" \
    "returns), and ahhs-module's LCM receiver is a thread"
  exit 77
fi
fit() { tail -1 "$1" | sed -n 's/^fitness: //p'; }
for variant in ahhs2 ahhs1; do
  launch=("$bin/ahhs-launch" --scenario gait --modules 3 --genome "$tmp/g-$variant.json" --seed 5
          --duration 4 --lcm-url "$url")
  "${launch[@]}" --arena REF-$variant >"$tmp/ref.out" 2>&1 || { cat "$tmp/ref.out"; fail "native episode"; }
  ref=$(fit "$tmp/ref.out")
  [[ -n $ref ]] || fail "no native fitness"
  for external in module:1 modules; do
    arena=A64-$variant-${external%%:*}
    ids=(1)
    [[ $external == modules ]] && ids=(0 1 2)
    pids=()
    for id in "${ids[@]}"; do
      board_module --id "$id" --arena "$arena" --lcm-url "$url" --hormone-timeout-ms 2000 \
        >>"$tmp/board.log" 2>&1 &
      pids+=($!)
    done
    "${launch[@]}" --arena "$arena" --external "$external" --external-timeout 60 >"$tmp/a64.out" 2>&1 ||
      { cat "$tmp/a64.out" "$tmp/board.log"; fail "$variant with arm64 $external"; }
    kill "${pids[@]}" 2>/dev/null
    wait "${pids[@]}" 2>/dev/null
    [[ $(fit "$tmp/a64.out") == "$ref" ]] ||
      fail "$variant with arm64 $external: fitness $(fit "$tmp/a64.out"), native $ref"
    echo "$variant, arm64 $external: fitness $ref, as native"
  done
done
echo "arm64 module: all checks passed"
