#!/usr/bin/env bash
# ahhs-view in a real browser (headless Chromium, through ahhs-capture), live: a multi-process
# arena, a viewer that goes away during a lockstep episode without stalling or changing it,
# a run being evolved, and a run another optimizer made through ahhs-evaluate --out
# (view_files_test.sh has logs, videos and filmstrips).
bin=${1:?usage: view_test.sh BIN_DIR}
source "${AHHS_SOURCE_DIR:?}/tests/lib.sh"
ahhs_netns "$0" "$@"
ahhs_scratch 'ahhs-view|ahhs-launch|ahhs-sim|ahhs-module|ahhs-fitness|ahhs-logger|ahhs-evolve|ahhs-evaluate|ahhs-worker'
command -v chromium >/dev/null || { echo "chromium not installed (tools/install-deps)"; exit 77; }
cd "$tmp"
fixed=$AHHS_SOURCE_DIR/tests/fixtures/genomes/gait-fixed-ahhs2-20-seed1.json
pend=$AHHS_SOURCE_DIR/tests/fixtures/genomes/pendulum-ahhs1-60-seed1.json
url='udpm://239.255.76.67:7681?ttl=0&recv_buf_size=4194304'

# js EXPR: a JSON value from the page at $page (ahhs-capture probe).
js() { "$bin/ahhs-capture" probe "$page" --eval "$1" "${@:2}"; }
field() { python3 -c "import json,sys; print(json.load(sys.stdin)$1)"; }
source "$AHHS_SOURCE_DIR/tests/tools/view_lib.sh"

echo "== 1. a live multi-process arena (real time), a page that joins while it runs"
start_view --lcm-url "$url" --arena VIEW3
"$bin/ahhs-launch" --scenario pendulum --genome "$pend" --realtime --duration 20 --arena VIEW3 \
  --lcm-url "$url" >launch3.out 2>&1 &
launch=$!
# Its panel: a live viewer listens to a module's sensors and commands once a page asks. The
# episode is long enough for a page whose Chromium takes 15 s to start on a loaded machine.
s=$(js '(async () => { ahhs.select(1); await new Promise(r => setTimeout(r, 1500));
          const s = ahhs.stats(); s.bob = ahhs.screenPos(1); return s; })()' \
  --wait 'window.ahhs && ahhs.stats().tick > 100' --screenshot live.png)
python3 -c "import json,sys; s=json.loads(sys.argv[1]); assert s['panel']['sensors'] > 0 and s['panel']['actuators'] == 2, s" "$s" ||
  fail "the live panel of compartment 1: $s"
[[ $(field "['mode']" <<<"$s") == live ]] || fail "live mode: $s"
[[ $(field "['pendulum']" <<<"$s") == True ]] || fail "a pendulum: $s"
[[ $(field "['moving']" <<<"$s") == 2 && $(field "['static']" <<<"$s") == 2 ]] ||
  fail "cart, bob and two walls: $s"
wait $launch || fail "the episode with a viewer: $(cat launch3.out)"
kill $view; wait $view

echo "== 2. a viewer takes no part in the lockstep: one that vanishes stalls and changes nothing"
run_lockstep() {
  "$bin/ahhs-launch" --scenario gait --docking fixed --genome "$fixed" --duration 60 --arena VIEW4 \
    --lcm-url "$url" --timeout 120 "$@" 2>&1 | sed -n 's/^fitness: //p'
}
alone=$(run_lockstep --log launched.lcm)
[[ -n "$alone" ]] || fail "lockstep episode alone"
start_view --lcm-url "$url" --arena VIEW4 --rate 200
mkdir probe-tmp  # the probe's own TMPDIR: killed, it must leave nothing in it
TMPDIR=$tmp/probe-tmp "$bin/ahhs-capture" probe "$page" --hold 60 --timeout 90 >/dev/null 2>&1 &
probe=$!
for _ in $(seq 300); do grep -q "a page connected" view.out && break; sleep 0.1; done
grep -q "a page connected" view.out || fail "no page connected: $(cat view.out)"
kill -STOP $view  # a viewer that stops reading, with a page attached
stalled=$(run_lockstep)
kill -KILL $view  # and one that vanishes: the page is disconnected
wait $view 2>/dev/null
vanished=$(run_lockstep)
kill $probe 2>/dev/null
wait $probe 2>/dev/null
probe_rc=$?
[[ $probe_rc == 143 ]] || fail "ahhs-capture on SIGTERM: exit $probe_rc, not 143"
left=$(ls -A probe-tmp)
[[ -z "$left" ]] || fail "ahhs-capture killed by SIGTERM left its temporary files: $left"
[[ "$stalled" == "$alone" ]] || fail "fitness alone $alone, with a stalled viewer $stalled"
watched=$vanished
[[ "$watched" == "$alone" ]] || fail "fitness alone $alone, with a vanishing viewer $watched"
echo "  fitness $alone alone, with a stalled viewer and after it vanished"
# The log ahhs-launch recorded plays too: the reset state, 1200 ticks and the end, its fitness.
start_view launched.lcm
s=$(js '(ahhs.renderAt(1e9), ahhs.stats())')
python3 -c "import json,sys; s=json.loads(sys.argv[1]); assert s['frames'] >= 1201 and s['tick'] == 1200 and abs(s['fitness'] - float(sys.argv[2])) < 1e-9, s" "$s" "$alone" ||
  fail "an ahhs-launch log: $s"
kill $view; wait $view

echo "== 3. watching an evolution: the newest generation's best, switching as new ones arrive"
# The viewer and its page come first (the viewer waits for the run's first generation), the run
# only once the page is connected: a Chromium slow to start cannot miss every switch.
start_view --run run --poll 0.2
js 'new Promise(r => { const g0 = ahhs.stats().run_generation; const i = setInterval(() => {
      const s = ahhs.stats(); if (s.run_generation !== g0) { clearInterval(i); s.first = g0; r(s); } }, 100); })' \
  --wait 'window.ahhs && ahhs.isReady()' --timeout 120 >probe7.out 2>&1 &
probe=$!
for _ in $(seq 1200); do grep -q "a page connected" view.out && break; sleep 0.1; done
grep -q "a page connected" view.out || fail "no page connected to the run's viewer: $(cat view.out)"
"$bin/ahhs-evolve" --config "$AHHS_SOURCE_DIR/configs/gait-fixed-ahhs2-20.toml" --population 8 \
  --generations 10 --duration 15 --workers 1 --lcm-url "$url" --out run >evolve.out 2>&1 &
evolve=$!
wait $probe
s=$(cat probe7.out)
[[ $(field "['mode']" <<<"$s") == run ]] || fail "run mode: $s"
python3 -c "import json,sys; s=json.loads(sys.argv[1]); assert s['run_generation'] > s['first'], s" "$s" ||
  fail "no switch to a newer best: $s"
echo "  $(field "['title']" <<<"$s")"
wait $evolve || fail "evolve: $(tail -3 evolve.out)"
kill $view; wait $view

echo "== 4. a run of another optimizer (ahhs-evaluate --out) is watched the same way"
python3 - >requests <<'PY'
import json
for g in range(2):
    print(json.dumps({"v": 2, "generation": g,
                      "genomes": [{"vector": [0.3 + 0.2 * g + 0.1 * i] * 61} for i in range(2)]}))
PY
"$bin/ahhs-evaluate" --scenario gait --docking fixed --duration 5 --variant ahhs2 --hormones 3 \
  --rules 4 --workers 1 --lcm-url "$url" --out orun --population 2 --generations 2 \
  --optimizer test <requests >evaluate.out 2>&1 || fail "ahhs-evaluate --out: $(cat evaluate.out)"
start_view --run orun --poll 0.2
s=$(js 'new Promise(r => { const i = setInterval(() => { const s = ahhs.stats();
      if (s.run_generation === 1) { clearInterval(i); r(s); } }, 100); })' \
  --wait 'window.ahhs && ahhs.isReady()' --timeout 60)
[[ $(field "['mode']" <<<"$s") == run ]] || fail "an optimizer's run: $s"
echo "  $(field "['title']" <<<"$s")"
kill $view; wait $view
echo "PASS"
