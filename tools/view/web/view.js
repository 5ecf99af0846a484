// ahhs-view's page (docs/viewer.md): draws what ahhs-view sends over /ws with three.js.
// Two sources, one renderer: a recording (a log or a run's best: every frame known, played
// here with play, pause, seek, speed and step) and a live arena (frames appended as they come,
// the newest shown). World frame: x forward, z up, metres. window.ahhs is the page's API for
// tests and for ahhs-capture (headless Chromium): stats(), renderAt(t), seek(t), ...
// Part 4 of 4: playback, the live arena, the connection and the API (parts 1-3: view_scene.js,
// view_frames.js, view_panel.js).
'use strict';

// ---- playback --------------------------------------------------------------------------------
function redraw() {
  if (rec) showFrameIndex(frameAtTime(rec, playTime));
  else if (live.frames.length) drawLive();
  render();
}
function render() { renderer.render(scene, camera); }
let lastNow = null;
function loop(now) {
  requestAnimationFrame(loop);
  if (rec && playing && lastNow !== null) {
    playTime += ((now - lastNow) / 1000) * speed;
    if (playTime >= duration(rec)) {
      if (mode === 'run') playTime = rec.frames[0].time;  // a run's best loops
      else { playTime = duration(rec); playing = false; }
    }
    showFrameIndex(frameAtTime(rec, playTime));
  }
  lastNow = now;
  render();
}
function resize() {
  const w = window.innerWidth, h = window.innerHeight;
  renderer.setSize(w, h);
  camera.aspect = w / h;
  camera.updateProjectionMatrix();
  render();
}
window.addEventListener('resize', resize);
resize();
if (!capture) requestAnimationFrame(loop);

const playBtn = document.getElementById('play');
function setPlaying(p) { playing = p; playBtn.textContent = p ? 'pause' : 'play'; updateHud(); }
playBtn.onclick = () => {
  if (rec && !playing && playTime >= duration(rec)) playTime = rec.frames[0].time;
  setPlaying(!playing);
};
function step(n) {
  if (!rec) return;
  setPlaying(false);
  const i = Math.max(0, Math.min(rec.frames.length - 1, frameAtTime(rec, playTime) + n));
  playTime = rec.frames[i].time;
  redraw();
}
document.getElementById('back').onclick = () => step(-1);
document.getElementById('fwd').onclick = () => step(1);
document.getElementById('seek').oninput = (e) => { if (rec) { playTime = rec.frames[Number(e.target.value)].time; redraw(); } };
document.getElementById('speed').onchange = (e) => { speed = Number(e.target.value); updateHud(); };
document.getElementById('episode').onchange = (e) => { useRecording(recordings[Number(e.target.value)]); render(); };
for (const [id, k] of [['hr', 0], ['hg', 1], ['hb', 2]]) {
  document.getElementById(id).onchange = (e) => { hormonePick[k] = Math.max(0, Number(e.target.value) | 0); redraw(); };
}
window.addEventListener('keydown', (e) => {
  if (e.target.tagName === 'INPUT' && e.target.type === 'number') return;
  if (e.key === ' ') { playBtn.onclick(); e.preventDefault(); }
  if (e.key === 'ArrowLeft') step(-1);
  if (e.key === 'ArrowRight') step(1);
});

// ---- live ------------------------------------------------------------------------------------
const LIVE_KEEP = 2000;  // frames kept for the plots
function drawLive() {
  const f = live.frames[live.frames.length - 1];
  const fit = live.fitness && live.fitness.episode === live.episode ? live.fitness.fitness : null;
  const final = live.fitness && live.fitness.final && live.fitness.episode === live.episode ? live.fitness : null;
  drawFrame(f, f.mods, fit, final);
}
function onLive(e) {
  if (e.type === 'scene') {
    live.scene = e;
    buildStatic(e.bodies);
  } else if (e.type === 'state') {
    if (live.episode !== e.episode || !bodyMeta || bodyMeta.module.length !== e.bodies.module.length) {
      live.episode = e.episode;
      live.frames = [];
      live.mods = {};
      buildMoving(e.bodies);
      if (live.scene && live.scene.episode !== e.episode) buildStatic({module: [], shape: [], size: [], pose: []});
      frameCamera({pose: e.bodies.pose}, true);
    }
    const mods = [];
    for (const k in live.mods) mods[Number(k)] = live.mods[k];
    const f = {tick: e.tick, time: e.time, pose: e.bodies.pose, mods: mods};
    live.frames.push(f);
    if (live.frames.length > LIVE_KEEP) live.frames.shift();
    trackAppend(f);
    drawLive();
  } else if (e.type === 'module') {
    live.mods[e.module] = Object.assign({}, live.mods[e.module] || {}, e);
    const f = live.frames[live.frames.length - 1];
    if (f) f.mods[e.module] = live.mods[e.module];
  } else if (e.type === 'fitness') {
    live.fitness = e;
    if (live.frames.length) drawLive();
  } else if (e.type === 'clock') {
    live.clock = e;
  }
}

// ---- the connection --------------------------------------------------------------------------
let readyResolve;
const ready = new Promise((r) => { readyResolve = r; });
let connected = false;
function onMessage(e) {
  if (e.type === 'hello') {
    mode = e.mode;
    title = e.title || title;
    hormonePick = e.hormones || hormonePick;
    ['hr', 'hg', 'hb'].forEach((id, k) => { document.getElementById(id).value = hormonePick[k]; });
    const live_ = mode === 'live';
    for (const id of ['play', 'back', 'fwd', 'seek', 'speed']) document.getElementById(id).disabled = live_;
    document.getElementById('episode').hidden = mode !== 'log';
    if (e.waiting) document.getElementById('readout').textContent = e.waiting;
    else if (live_) document.getElementById('readout').textContent = 'waiting for SIM/STATE of ' + title;
    updateHud();
  } else if (e.type === 'recording') {
    if (mode === 'run') recordings = [e]; else recordings.push(e);
    const sel = document.getElementById('episode');
    sel.innerHTML = '';
    recordings.forEach((r, i) => { const o = document.createElement('option'); o.value = String(i); o.textContent = 'episode ' + r.episode; sel.appendChild(o); });
    if (mode === 'run' || recordings.length === 1) {
      useRecording(e);
      if (!capture) setPlaying(true);
    }
    render();
    readyResolve();
  } else {
    onLive(e);
    if (live.frames.length) { render(); readyResolve(); }
  }
}
let socket = null;
function connect() {
  const ws = socket = new WebSocket((location.protocol === 'https:' ? 'wss://' : 'ws://') + location.host + '/ws');
  ws.onopen = () => {
    connected = true;
    if (selected !== null && mode === 'live') ws.send(JSON.stringify({type: 'select', module: selected}));
  };
  ws.onmessage = (m) => onMessage(JSON.parse(m.data));
  ws.onclose = (e) => {
    connected = false;
    // A reason comes from the viewer when it refused this page (too many pages, a message too
    // large): say it, and try again less often.
    document.getElementById('message').textContent =
        e.reason ? e.reason + '; retrying in 10 s' : 'disconnected from ahhs-view; retrying';
    setTimeout(connect, e.reason ? 10000 : 1000);
  };
}
connect();
// The viewer closes a socket that says nothing for 30 s (an idle socket is not a page).
setInterval(() => {
  if (socket && socket.readyState === WebSocket.OPEN) socket.send('{"type":"alive"}');
}, 10000);

// ---- the page's API (tests, ahhs-capture) ----------------------------------------------------
function screenPosOf(module) {
  const ms = moving.filter((m) => m.userData.module === module);
  if (!ms.length) return null;
  const c = new THREE.Vector3();
  ms.forEach((m) => c.add(m.position));
  c.multiplyScalar(1 / ms.length).project(camera);
  const rect = renderer.domElement.getBoundingClientRect();
  return {x: Math.round((c.x + 1) / 2 * rect.width), y: Math.round((1 - c.y) / 2 * rect.height)};
}
window.ahhs = {
  ready: ready,
  isReady: () => shown !== null,
  stats: () => ({
    mode: mode,
    connected: connected,
    tick: shown ? shown.tick : -1,
    time: shown ? shown.time : -1,
    fitness: shown ? shown.fitness : null,
    bodies: moving.length + statics.length,  // meshes drawn (moving bodies and static scenery)
    moving: moving.length,
    static: statics.length,
    modules: bodyMeta ? new Set(bodyMeta.module.filter((m) => m >= 0)).size : 0,
    pendulum: isPendulum,
    frames: rec ? rec.frames.length : live.frames.length,
    duration: duration(rec),
    episode: rec ? rec.episode : live.episode,
    episodes: recordings.length,
    playing: playing,
    speed: speed,
    title: document.getElementById('title').textContent,
    selected: selected,
    panel: document.getElementById('panel').hidden ? null : plotted,
    run_generation: rec && rec.run_generation !== undefined ? rec.run_generation : null,
    colours: moving.map((m) => '#' + m.material.color.getHexString()),
  }),
  duration: () => duration(rec),
  renderAt: (t) => { playTime = t; setPlaying(false); redraw(); return window.ahhs.stats(); },
  seek: (t) => { playTime = t; redraw(); return window.ahhs.stats(); },
  play: () => setPlaying(true),
  pause: () => setPlaying(false),
  setSpeed: (s) => { speed = s; document.getElementById('speed').value = String(s); },
  step: (n) => { step(n); return window.ahhs.stats(); },
  select: select,
  screenPos: screenPosOf,
  // A click on the canvas at page pixel (x, y), as a user's (picking a module, or nothing).
  click: (x, y) => {
    const c = renderer.domElement;
    c.dispatchEvent(new PointerEvent('pointerdown', {clientX: x, clientY: y, bubbles: true}));
    window.dispatchEvent(new PointerEvent('pointerup', {clientX: x, clientY: y, bubbles: true}));
    return window.ahhs.stats();
  },
  setSize: (w, h) => { renderer.setSize(w, h); camera.aspect = w / h; camera.updateProjectionMatrix(); render(); },
};
