# The viewer tests' shared helper (sourced after tests/lib.sh; runs in the test's folder).
# start_view ARGS...: ahhs-view on a free port; sets $view (pid), $page (URL) and $port.
start_view() {
  "$bin/ahhs-view" --port 0 "$@" >view.out 2>&1 &
  view=$!
  # (Up to 30 s: in CI's first pass a viewer once printed nothing in 5 s beside the sanitizer
  # build's linking; on a quiet machine it starts in well under a second.)
  for _ in $(seq 600); do grep -q '^open http' view.out && break; sleep 0.05; done
  page=$(sed -n 's/^open \(http[^ ]*\) .*/\1/p' view.out)
  [[ -n "$page" ]] || fail "ahhs-view did not start: $(cat view.out)"
  port=$(sed -n 's|^http://127.0.0.1:\([0-9]*\)/$|\1|p' <<<"$page")
}
