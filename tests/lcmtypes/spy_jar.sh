#!/usr/bin/env bash
# ahhs-lcmtypes.jar holds one class per .lcm file, each an LCMEncodable lcm-spy can decode with.
set -euo pipefail
jar=${1:?usage: spy_jar.sh ahhs-lcmtypes.jar}
src=${AHHS_SOURCE_DIR:?}
expected=$(ls "$src"/lcmtypes/*.lcm | wc -l)
classes=$(unzip -l "$jar" 2>/dev/null | grep -c 'ahhs/[a-z_]*_t\.class' || true)
if [[ -z "$classes" || "$classes" -eq 0 ]]; then
  classes=$(jar tf "$jar" | grep -c 'ahhs/[a-z_]*_t\.class')
fi
[[ "$classes" -eq "$expected" ]] || { echo "jar has $classes type classes, expected $expected"; exit 1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cat > "$tmp/Check.java" <<'JAVA'
public class Check {
  public static void main(String[] a) throws Exception {
    lcm.lcm.LCMEncodable m = (lcm.lcm.LCMEncodable) Class.forName("ahhs.hormone_packet_t")
        .getDeclaredConstructor().newInstance();
    java.io.ByteArrayOutputStream bytes = new java.io.ByteArrayOutputStream();
    m.encode(new java.io.DataOutputStream(bytes));
    Class.forName("lcm.spy.Spy");
    System.out.println("jar ok: " + bytes.size() + " bytes for an empty hormone_packet_t");
  }
}
JAVA
javac -cp "/usr/share/java/lcm.jar:$jar" -d "$tmp" "$tmp/Check.java"
java -Djava.awt.headless=true -cp "/usr/share/java/lcm.jar:/usr/share/java/jchart2d.jar:$jar:$tmp" Check
