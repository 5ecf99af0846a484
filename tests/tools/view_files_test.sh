#!/usr/bin/env bash
# ahhs-view in a real browser (headless Chromium, through ahhs-capture), on files: a log replay,
# damaged logs, videos and filmstrips. No arena runs here (view_test.sh has the live ones), so it
# needs no lock against the tests of real processes.
bin=${1:?usage: view_files_test.sh BIN_DIR}
source "${AHHS_SOURCE_DIR:?}/tests/lib.sh"
ahhs_netns "$0" "$@"
ahhs_scratch 'ahhs-view|ahhs-replay'
command -v chromium >/dev/null || { echo "chromium not installed (tools/install-deps)"; exit 77; }
cd "$tmp"
fixed=$AHHS_SOURCE_DIR/tests/fixtures/genomes/gait-fixed-ahhs2-20-seed1.json

# js EXPR: a JSON value from the page at $page (ahhs-capture probe).
js() { "$bin/ahhs-capture" probe "$page" --eval "$1" "${@:2}"; }
source "$AHHS_SOURCE_DIR/tests/tools/view_lib.sh"

echo "== 1. a replay log in the browser: bodies, ticks, seek, step, speed, module colours"
"$bin/ahhs-replay" --genome "$fixed" --scenario gait --docking fixed --log fixed.lcm >/dev/null ||
  fail "replay"
start_view fixed.lcm
# One page load, every check's value at once (a probe starts a Chromium: seconds each).
s=$(js '(async () => {
  const r = {start: ahhs.stats()};
  r.at30 = ahhs.renderAt(30);
  ahhs.step(3);
  r.stepped = ahhs.step(-1);
  r.end = ahhs.renderAt(1e9);
  ahhs.renderAt(0);
  ahhs.setSpeed(8);
  const t0 = performance.now();
  ahhs.play();
  // Until 6 s of the episode have played: playback moves only when a frame is drawn, and a
  // loaded machine draws few a second.
  while (ahhs.stats().time < 6 && performance.now() - t0 < 30000)
    await new Promise(done => setTimeout(done, 50));
  r.played = ahhs.stats();
  r.wall = (performance.now() - t0) / 1000;
  ahhs.pause();
  // The click is on a fixed frame: where playback stopped depends on how fast the machine is,
  // and in some poses another module hides the centre of module 3.
  ahhs.renderAt(10);
  const p = ahhs.screenPos(3);
  r.clicked = ahhs.click(p.x, p.y);
  r.unclicked = ahhs.click(5, 300);  // the sky: nothing picked, the panel closes
  return r; })()')
check() { python3 -c "import json,sys; s=json.loads(sys.argv[1]); assert $1, s" "$s" || fail "$2"; }
check "s['start']['mode'] == 'log'" "log mode"
check "s['start']['moving'] == 10" "5 modules are 10 moving bodies"
check "s['start']['static'] > 0" "the wall and cubes are drawn"
check "s['start']['frames'] == 1200" "60 s are 1200 states"
check "s['at30']['tick'] == 600" "t = 30 s is tick 600"
check "s['stepped']['tick'] == 602" "3 ticks on and 1 back"
# The last frame carries the replay's fitness (the stored one, 6 digits as the page gets it).
check "abs(s['end']['fitness'] - 2.117765) < 1e-5" "final fitness"
# At 8x, 6 s of the episode play in well under 2 s of wall time (at 1x they would take 6 s),
# and never in less than an eighth of it (one frame's interval of slack).
check "s['played']['time'] >= 6 and 3 * s['wall'] < s['played']['time'] < 8 * s['wall'] + 4" "8x speed"
# A click on module 3 opens its panel: 4 sensors, 5 hormones and 1 actuator over the last 10 s.
check "s['clicked']['selected'] == 3" "a click picks module 3"
check "s['clicked']['panel']['sensors'] == 4 and s['clicked']['panel']['hormones'] == 5" "panel plots"
check "s['clicked']['panel']['actuators'] == 1 and s['clicked']['panel']['points'] > 100" "panel"
check "s['unclicked']['selected'] is None and s['unclicked']['panel'] is None" "click beside"
# A screenshot has module 2's colour where module 2 is drawn.
js '(ahhs.renderAt(20), {pos: ahhs.screenPos(2), colours: ahhs.stats().colours})' \
  --screenshot log.png >probe.json || fail "screenshot"
/usr/bin/python3 - log.png probe.json <<'EOF' || fail "module colours in the screenshot"
import json, sys
from PIL import Image
img = Image.open(sys.argv[1]).convert("RGB")
p = json.load(open(sys.argv[2]))
want = [tuple(int(c[i:i + 2], 16) for i in (1, 3, 5)) for c in p["colours"][4:6]]  # module 2
x, y = p["pos"]["x"], p["pos"]["y"]
near = [img.getpixel((i, j)) for i in range(x - 40, x + 41, 2) for j in range(y - 40, y + 41, 2)
        if 0 <= i < img.width and 0 <= j < img.height]
hue = lambda c: tuple(v / max(1, max(c)) for v in c)  # shading scales a colour, keeps its hue
close = [c for c in near if any(sum(abs(a - b) for a, b in zip(hue(c), hue(w))) < 0.12 and max(c) > 40 for w in want)]
print("pixels of module 2's colour near it: %d of %d" % (len(close), len(near)))
assert len(close) > 0.1 * len(near)
EOF
kill $view; wait $view

echo "== 2. damaged logs and other files: one line, exit 1"
head -c 100000 fixed.lcm >truncated.lcm
{ head -c 5000 fixed.lcm; echo garbage-garbage; tail -c +5001 fixed.lcm; } >garbage.lcm
echo "not a log at all" >text.lcm
: >empty.lcm
for f in truncated garbage text empty missing; do
  "$bin/ahhs-view" $f.lcm --port 0 >out.txt 2>err.txt
  code=$?
  [[ $code == 1 ]] || fail "$f: exit $code"
  [[ $(wc -l <err.txt) == 1 ]] || fail "$f: not one line: $(cat err.txt)"
  echo "  $f: $(cat err.txt)"
done
grep -q "truncated at byte" <("$bin/ahhs-view" truncated.lcm 2>&1) || fail "truncated"
grep -Eq "garbage at byte|corrupt event header at byte" <("$bin/ahhs-view" garbage.lcm 2>&1) || fail "garbage"
grep -q "not an LCM log" <("$bin/ahhs-view" text.lcm 2>&1) || fail "text"

echo "== 3. a video of a replay: 1280x720 H.264, its duration and frame count, frames that differ"
"$bin/ahhs-replay" --genome "$fixed" --scenario gait --docking fixed --video fixed.mp4 --from 8 \
  --to 12 | tail -2 || fail "ahhs-replay --video"
probe=$(ffprobe -v error -select_streams v:0 -count_frames -show_entries \
  stream=codec_name,width,height,nb_read_frames,r_frame_rate:format=duration -of json fixed.mp4)
python3 - "$probe" <<'EOF' || fail "video: $probe"
import json, sys
p = json.loads(sys.argv[1])
s, f = p["streams"][0], p["format"]
assert s["codec_name"] == "h264" and (s["width"], s["height"]) == (1280, 720), s
assert s["r_frame_rate"] == "25/1", s
assert int(s["nb_read_frames"]) == 4 * 25, s
assert abs(float(f["duration"]) - 4) < 0.05, f
EOF
# Episode times 8.5 s and 11.5 s are video times 0.5 s and 3.5 s.
ffmpeg -v error -ss 0.5 -i fixed.mp4 -frames:v 1 a.png && ffmpeg -v error -ss 3.5 -i fixed.mp4 \
  -frames:v 1 b.png || fail "frames"
/usr/bin/python3 - <<'EOF' || fail "frames at 8.5 s and 11.5 s do not differ"
from PIL import Image, ImageChops
a, b = Image.open("a.png").convert("RGB"), Image.open("b.png").convert("RGB")
diff = ImageChops.difference(a, b).convert("L").point(lambda v: 255 if v > 40 else 0)
share = sum(diff.histogram()[255:]) / (a.width * a.height)
print("  frames at 8.5 s and 11.5 s: %.1f %% of pixels differ" % (100 * share))
assert share > 0.02
EOF
"$bin/ahhs-replay" --genome "$fixed" --scenario gait --docking fixed --video fixed.mp4 >/dev/null 2>err.txt
[[ $? == 2 ]] && grep -q "exists" err.txt || fail "an existing video is refused: $(cat err.txt)"

echo "== 4. a filmstrip: 8 frames in one PNG"
"$bin/ahhs-view" fixed.lcm --filmstrip strip.png --size 640x360 || fail "filmstrip"
/usr/bin/python3 -c "from PIL import Image; im = Image.open('strip.png'); assert im.size == (4 * 320, 2 * 180), im.size" ||
  fail "filmstrip size"

echo "PASS"
