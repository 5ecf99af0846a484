#!/usr/bin/env bash
# The .lcm files generate cleanly for C, Java, Python and Lua (hardware and foreign-language
# clients are part of the product), and the generated code compiles where a compiler exists.
set -euo pipefail
src=${AHHS_SOURCE_DIR:?}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
lcm=("$src"/lcmtypes/*.lcm)
count=${#lcm[@]}

mkdir -p "$out"/{c,java,python,lua,classes}
lcm-gen --c --c-cpath "$out/c" --c-hpath "$out/c" "${lcm[@]}"
lcm-gen --java --jpath "$out/java" "${lcm[@]}"
lcm-gen --python --ppath "$out/python" "${lcm[@]}"
lcm-gen --lua --lpath "$out/lua" "${lcm[@]}"

[[ $(ls "$out"/c/*.c | wc -l) -eq $count ]] || { echo "C: expected $count .c files"; exit 1; }
[[ $(ls "$out"/java/ahhs/*.java | wc -l) -eq $count ]] || { echo "Java: expected $count files"; exit 1; }
[[ $(ls "$out"/python/ahhs/*_t.py | wc -l) -eq $count ]] || { echo "Python: expected $count files"; exit 1; }
[[ $(ls "$out"/lua/ahhs/*_t.lua | wc -l) -eq $count ]] || { echo "Lua: expected $count files"; exit 1; }

for f in "$out"/c/*.c; do
  cc -std=c99 -Wall -Werror -c -I"$out/c" $(pkg-config --cflags lcm) "$f" -o "$out/c/$(basename "$f" .c).o"
done
echo "C: $count types compile"

if command -v javac >/dev/null && [[ -f /usr/share/java/lcm.jar ]]; then
  javac -Xlint:none -cp /usr/share/java/lcm.jar -d "$out/classes" "$out"/java/ahhs/*.java
  echo "Java: $count types compile"
else
  echo "Java: javac or lcm.jar missing, generated only"
fi

py=/usr/bin/python3
[[ -x $py ]] || py=python3
"$py" -m py_compile "$out"/python/ahhs/*.py
echo "Python: $count types byte-compile"

if command -v luac >/dev/null; then
  for f in "$out"/lua/ahhs/*.lua; do luac -p "$f"; done
  echo "Lua: $count types parse"
else
  echo "Lua: generated (no luac here to parse them)"
fi
