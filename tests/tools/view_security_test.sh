#!/usr/bin/env bash
# ahhs-view as an attacker would probe it, over plain sockets (docs/viewer.md, "Security"): a
# foreign or null Origin and a foreign Host are refused, idle sockets do not keep a page from
# loading, an oversized message closes only its own connection, pages over --max-pages are
# refused with a reason, only the viewer's own files are served (no traversal, CGI, SSI,
# dotfiles or symlinks, also with a --web-root of the user's), and --run records into a fresh
# private temporary folder.
bin=${1:?usage: view_security_test.sh BIN_DIR}
source "${AHHS_SOURCE_DIR:?}/tests/lib.sh"
ahhs_netns "$0" "$@"
ahhs_scratch 'ahhs-view|ahhs-evolve|ahhs-worker'
cd "$tmp"

"$bin/ahhs-genome" random --variant ahhs2 --hormones 3 --rules 4 --sensors 10 --actuators 2 \
  --seed 5 > p.json || fail "ahhs-genome"
"$bin/ahhs-replay" --genome p.json --scenario pendulum --duration 2 --log p.lcm >/dev/null ||
  fail "replay"

source "$AHHS_SOURCE_DIR/tests/tools/view_lib.sh"
probe() { /usr/bin/python3 "$AHHS_SOURCE_DIR/tests/tools/view_probe.py" "$port" "$@"; }

echo "== 1. Origin and Host"
start_view p.lcm --max-pages 3
probe upgrade --expect 101 || fail "a WebSocket without Origin (not a browser) is accepted"
probe upgrade --origin "http://127.0.0.1:$port" --expect 101 || fail "the viewer's own Origin"
probe upgrade --origin "http://localhost:$port" --host "localhost:$port" --expect 101 ||
  fail "localhost"
probe upgrade --origin "http://evil.example" --expect refused || fail "a foreign Origin"
probe upgrade --origin "null" --expect refused || fail "a null Origin"
probe upgrade --origin "http://127.0.0.1:1" --expect refused || fail "another port's Origin"
probe upgrade --host "evil.example" --expect 421 || fail "a foreign Host on /ws"
probe get / --host "evil.example" --expect 421 || fail "a foreign Host on /"
probe get / --host "evil.example:$port" --expect 421 || fail "a foreign Host with the port"
probe get / --expect 200 || fail "the page"

echo "== 2. nine idle sockets, then a normal page loads"
probe idle-then-get --idle 9 --expect 200 || fail "idle sockets held the page down"

echo "== 3. an oversized message closes only its own connection"
probe oversize --size 65536 || fail "oversized message"

echo "== 4. pages over --max-pages are refused with a reason"
probe cap --pages 3 || fail "page cap"

echo "== 5. only the viewer's own files"
for path in /../../etc/passwd /%2e%2e/%2e%2e/etc/passwd /..%2f..%2fetc%2fpasswd /%252e%252e/etc/passwd \
  /view.js/../../../etc/passwd '/..\..\etc\passwd' /%c0%ae%c0%ae/etc/passwd /index.shtml \
  /cgi-bin/test.cgi /test.cgi /.hidden /link /web/index.html /view.js.bak /ws/x; do
  probe get "$path" --expect 404 || fail "$path is not 404"
done
kill "$view"; wait "$view" 2>/dev/null

# A web root of the user's own, holding what civetweb's document_root would serve or run.
mkdir web
cp "$AHHS_SOURCE_DIR"/tools/view/web/{index.html,*.js,view.css} web/
echo 'secret' > web/.hidden
printf '#!/bin/sh\necho Content-Type: text/plain; echo; echo ran\n' > web/test.cgi
chmod +x web/test.cgi
echo '<!--#exec cmd="echo ran" -->' > web/index.shtml
ln -s /etc/passwd web/link
start_view p.lcm --web-root web
probe get /view.css --expect 200 || fail "--web-root serves the page's files"
for path in /.hidden /test.cgi /index.shtml /link /cgi-bin/test.cgi; do
  probe get "$path" --expect 404 || fail "--web-root: $path is not 404"
done
kill "$view"; wait "$view" 2>/dev/null

echo "== 6. --run records into a fresh private folder (TMPDIR honoured)"
mkdir tmpdir
"$bin/ahhs-evolve" --scenario pendulum --hormones 3 --rules 4 --population 4 --generations 1 \
  --duration 2 --workers 1 --out run --lcm-url 'udpm://239.255.76.67:7693?ttl=0' >evolve.out 2>&1 ||
  fail "a run to follow: $(tail -3 evolve.out)"
TMPDIR=$tmp/tmpdir start_view --run run
for _ in $(seq 100); do grep -q 'showing' view.out && break; sleep 0.1; done
grep -q 'showing' view.out || fail "--run shows the run's best: $(cat view.out)"
mapfile -t made < <(find tmpdir -mindepth 1 -maxdepth 1)
[[ ${#made[@]} == 1 && "${made[0]}" =~ /ahhs-view-[A-Za-z0-9]{6}$ ]] ||
  fail "one ahhs-view-XXXXXX folder in TMPDIR: ${made[*]}"
[[ $(stat -c %a "${made[0]}") == 700 ]] || fail "the folder is private (mode 700)"
kill "$view"; wait "$view" 2>/dev/null
[[ -z "$(ls tmpdir)" ]] || fail "ahhs-view left its folder behind: $(ls tmpdir)"
echo "view security: all checks passed"
