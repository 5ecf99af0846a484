# The viewer tests' shared helper (sourced after tests/lib.sh; runs in the test's folder).
# start_view ARGS...: ahhs-view on a free port; sets $view (pid), $page (URL) and $port.
start_view() {
  # The previous viewer's output goes first, here: the redirection below empties the file only
  # when the child process runs, and a check before that read the last viewer's "open" line
  # (twice in CI beside a busy build: "ahhs-view did not start", with nothing printed).
  rm -f view.out
  "$bin/ahhs-view" --port 0 "$@" >view.out 2>&1 &
  view=$!
  # (Up to 30 s; on a quiet machine it starts in well under a second.)
  for _ in $(seq 600); do grep -qs '^open http' view.out && break; sleep 0.05; done
  page=$(sed -n 's/^open \(http[^ ]*\) .*/\1/p' view.out)
  [[ -n "$page" ]] || fail "ahhs-view did not start: $(cat view.out)"
  port=$(sed -n 's|^http://127.0.0.1:\([0-9]*\)/$|\1|p' <<<"$page")
}
