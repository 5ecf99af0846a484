#!/usr/bin/env bash
# The Debian packages (docs/install.md), made from this build by CPack and used from a fresh
# prefix with no build tree in sight: lintian finds no error; ahhs-module holds what a module
# board needs and nothing else; nothing installed names the build or source tree; every tool
# answers --version with this build's version; and from the unpacked tree a short pendulum
# evolution runs, ahhs-replay reproduces it and films it through ahhs-view --video, ahhs-report
# reports it, the Python package imports, and a project of one's own (examples/downstream) builds
# against the CMake package and runs a controller bit for bit as ahhs-genome does.
build=${1:?usage: packages_test.sh BUILD_DIR}
source "${AHHS_SOURCE_DIR:?}/tests/lib.sh"
ahhs_netns "$0" "$@"
bin=$build/bin  # ahhs_scratch's cleanup kills this test's processes of $bin; the installed ones below
url="udpm://239.255.42.81:7773?ttl=0&recv_buf_size=4194304"
ahhs_scratch 'ahhs-evolve|ahhs-worker|ahhs-view|ahhs-capture'
version=$(sed -n 's/^CMAKE_PROJECT_VERSION:STATIC=//p' "$build/CMakeCache.txt")
[[ -n $version ]] || fail "no project version in $build/CMakeCache.txt"

echo "== cpack: ahhs and ahhs-module"
(cd "$tmp" && cpack --config "$build/CPackConfig.cmake" -B "$tmp/pkg" >"$tmp/cpack.log" 2>&1) ||
  { tail -20 "$tmp/cpack.log"; fail "cpack"; }
arch=$(dpkg --print-architecture)
lab=$tmp/pkg/ahhs_${version}_$arch.deb
module=$tmp/pkg/ahhs-module_${version}_$arch.deb
[[ -f $lab && -f $module ]] || fail "packages missing: $(ls "$tmp/pkg")"
dpkg-deb -f "$lab" Depends | grep -q "ahhs-module (= $version)" || fail "ahhs does not depend on ahhs-module"
for dep in liblcm1 libode8 lua5.2; do
  dpkg-deb -f "$lab" Depends | grep -q "$dep" || dpkg-deb -f "$module" Depends | grep -q "$dep" ||
    fail "no package depends on $dep"
done

echo "== lintian: no errors"
command -v lintian >/dev/null || fail "lintian is missing (tools/install-deps installs it)"
lintian --fail-on error "$lab" "$module" >"$tmp/lintian.txt" 2>&1 ||
  { grep -v '^W:' "$tmp/lintian.txt"; fail "lintian found errors (or did not run)"; }

echo "== ahhs-module holds what a module board needs, and nothing else"
dpkg-deb -c "$module" | awk '{print $6}' | grep -v '/$' | sed 's|^\./||' | sort >"$tmp/module.files"
{
  echo usr/bin/ahhs-example-controller-lua
  echo usr/bin/ahhs-module
  echo usr/share/ahhs/controller-lua/ahhs_model.lua
  echo usr/share/ahhs/controller-lua/module.lua
  echo usr/share/ahhs/lua/ahhs/init.lua
  for f in "$AHHS_SOURCE_DIR"/lcmtypes/*.lcm; do echo "usr/share/ahhs/lua/ahhs/$(basename "${f%.lcm}").lua"; done
  echo usr/share/doc/ahhs-module/changelog.gz
  echo usr/share/doc/ahhs-module/copyright
  echo usr/share/man/man1/ahhs-module.1.gz
} | sort >"$tmp/module.expected"
diff "$tmp/module.expected" "$tmp/module.files" || fail "ahhs-module's files differ from the list above"
! dpkg-deb -c "$lab" | grep -q 'usr/bin/ahhs-module$' || fail "ahhs ships ahhs-module too"

echo "== unpacked into a fresh prefix: nothing names the build or the source tree"
root=$tmp/root
dpkg-deb -x "$lab" "$root" && dpkg-deb -x "$module" "$root" || fail "dpkg-deb -x"
P=$root/usr
bin=$P/bin
src=$(cd "$AHHS_SOURCE_DIR" && pwd -P)
bld=$(cd "$build" && pwd -P)
for baked in "$src" "$bld"; do
  hits=$(grep -rlF "$baked" "$root" | grep -v '/share/doc/' || true)
  [[ -z $hits ]] || fail "installed files name $baked: $hits"
done

echo "== every tool answers --version with version $version"
for tool in "$P"/bin/*; do
  # (All of it, then its first line: `| head -1` would close the pipe after one line, and a
  # tool still writing its second one would die of SIGPIPE, a failure under pipefail.)
  out=$("$tool" --version 2>&1) || fail "$(basename "$tool") --version failed: $out"
  first=${out%%$'\n'*}
  [[ $first == "$(basename "$tool") $version" ]] || fail "$(basename "$tool") --version: '$first'"
done
"$P/bin/ahhs-evolve" --version | grep -q "farm protocol" || fail "ahhs-evolve --version names no farm protocol"
types=$(ls "$AHHS_SOURCE_DIR"/lcmtypes/*.lcm | wc -l)
"$P/bin/ahhs-sim" --version | grep -q "package ahhs, $types types," ||
  fail "the wire fingerprint does not cover the $types types of lcmtypes/"
wire_lab=$("$P/bin/ahhs-sim" --version | grep wire)
wire_module=$("$P/bin/ahhs-module" --version | grep wire)
[[ -n $wire_lab && $wire_lab == "$wire_module" ]] || fail "wire lines differ: '$wire_lab' / '$wire_module'"

echo "== from the installed tree: evolve, replay, film, report"
PATH=$P/bin:/usr/bin:/bin
cd "$tmp"
ahhs-evolve --scenario pendulum --variant ahhs2 --hormones 4 --rules 6 --duration 3.5 --seed 3 \
  --population 6 --generations 2 --workers 2 --lcm-url "$url" --out run >evolve.log 2>&1 ||
  { tail -5 evolve.log; fail "installed ahhs-evolve"; }
ahhs-replay run --log best.lcm >replay.log 2>&1 && grep -q "reproduced exactly" replay.log ||
  { cat replay.log; fail "installed ahhs-replay"; }
ahhs-view best.lcm --video best.mp4 --size 320x240 --fps 10 --to 2 >view.log 2>&1 ||
  { tail -5 view.log; fail "installed ahhs-view --video"; }
[[ -s best.mp4 ]] && [[ $(head -c 8 best.mp4 | tail -c 4) == ftyp ]] || fail "best.mp4 is no MP4"
ahhs-report run -o report >report.log 2>&1 || { tail -5 report.log; fail "installed ahhs-report"; }
ls report/*.png >/dev/null 2>&1 || fail "ahhs-report made no figures: $(ls report)"
PYTHONPATH=$P/lib/python3/dist-packages /usr/bin/python3 -c '
import ahhs, ahhs.genome_t, json, sys
g = json.load(open("run/best.json"))
x = ahhs.to_vector(g)
assert ahhs.from_vector(ahhs.Shape.of(g), x)["hormones"] == g["hormones"]
assert ahhs.genome_t.genome_t()._get_packed_fingerprint()
' || fail "the installed Python package"

echo "== a project of one's own against the CMake package and pkg-config"
cmake -S "$P/share/doc/ahhs/examples/downstream" -B downstream -DCMAKE_PREFIX_PATH="$P" \
  >downstream.log 2>&1 && cmake --build downstream >>downstream.log 2>&1 ||
  { tail -20 downstream.log; fail "examples/downstream against the installed tree"; }
ahhs-genome random --seed 7 >g.json
/usr/bin/python3 -c '
import random
r = random.Random(5)
print("tick,compartment,s0,s1,s2,s3")
for t in range(200):
    for c in range(3):
        print(f"{t},{c}," + ",".join(repr(r.random()) for _ in range(4)))' >sensors.csv
ahhs-genome run g.json --compartments 3 --sensors sensors.csv >expected.csv || fail "ahhs-genome run"
downstream/run-controller g.json sensors.csv 3 >got.csv || fail "run-controller"
cmp -s expected.csv got.csv || fail "run-controller differs from ahhs-genome run"
PKG_CONFIG_PATH=$P/lib/pkgconfig pkg-config --libs ahhs | grep -q -- "-lahhs_modules_core" ||
  fail "pkg-config ahhs"
echo "packages: all checks passed"
