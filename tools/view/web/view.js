// ahhs-view's page (docs/viewer.md): draws what ahhs-view sends over /ws with three.js.
// Two sources, one renderer: a recording (a log or a run's best: every frame known, played
// here with play, pause, seek, speed and step) and a live arena (frames appended as they come,
// the newest shown). World frame: x forward, z up, metres. window.ahhs is the page's API for
// tests and for ahhs-capture (headless Chromium): stats(), renderAt(t), seek(t), ...
'use strict';

const params = new URLSearchParams(location.search);
const capture = params.get('capture') === '1';
if (capture) document.body.classList.add('capture');

const PALETTE = [0xe6194b, 0x3cb44b, 0x4363d8, 0xf58231, 0x911eb4, 0x42d4f4, 0xf032e6, 0xbfef45,
                 0x469990, 0x9a6324];
const SHAPE_BOX = 0, SHAPE_SPHERE = 1, SHAPE_CYLINDER = 2;

// ---- three.js scene -------------------------------------------------------------------------
const container = document.getElementById('view');
const renderer = new THREE.WebGLRenderer({antialias: true, preserveDrawingBuffer: capture});
renderer.setPixelRatio(capture ? 1 : window.devicePixelRatio);
container.appendChild(renderer.domElement);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0xdfe4ea);
const camera = new THREE.PerspectiveCamera(40, 16 / 9, 0.01, 100);
camera.up.set(0, 0, 1);
scene.add(new THREE.HemisphereLight(0xffffff, 0x8a8f96, 0.75));
const sun = new THREE.DirectionalLight(0xffffff, 0.6);
sun.position.set(2, -3, 5);
scene.add(sun);

const ground = new THREE.Mesh(new THREE.PlaneGeometry(40, 40),
                              new THREE.MeshLambertMaterial({color: 0xc9cdb8}));
scene.add(ground);
const grid = new THREE.GridHelper(40, 200, 0x9a9f8a, 0xb2b6a2);
grid.rotation.x = Math.PI / 2;
grid.position.z = 0.0005;
scene.add(grid);

const movingGroup = new THREE.Group(), staticGroup = new THREE.Group();
scene.add(movingGroup, staticGroup);
let moving = [];      // meshes of the moving bodies, in state order
let statics = [];     // meshes of the scene's static bodies
let bodyMeta = null;  // {module[], shape[], size[]} of the moving bodies
let isPendulum = false;

const rod = new THREE.Line(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({color: 0x333333}));
rod.geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(6), 3));
rod.visible = false;
scene.add(rod);
const rail = new THREE.Mesh(new THREE.BoxGeometry(1, 0.02, 0.01), new THREE.MeshLambertMaterial({color: 0x666666}));
rail.position.z = -0.03;
rail.visible = false;
scene.add(rail);

const TRACK_MAX = 20000;
const track = new THREE.Line(new THREE.BufferGeometry(),
                             new THREE.LineBasicMaterial({color: 0x202a80}));
track.geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(TRACK_MAX * 3), 3));
track.geometry.setDrawRange(0, 0);
track.frustumCulled = false;
scene.add(track);

function geometryFor(shape, size) {
  if (shape === SHAPE_SPHERE) return new THREE.SphereGeometry(size[0], 24, 16);
  if (shape === SHAPE_CYLINDER) {
    const g = new THREE.CylinderGeometry(size[0], size[0], size[2], 24);
    g.rotateX(Math.PI / 2);  // three's cylinders run along y; ours along the body's z
    return g;
  }
  return new THREE.BoxGeometry(size[0], size[1], size[2]);
}

function buildMoving(meta) {
  for (const m of moving) { movingGroup.remove(m); m.geometry.dispose(); }
  moving = [];
  const n = meta.module.length;
  isPendulum = meta.shape.includes(SHAPE_SPHERE) && n <= 3;
  for (let i = 0; i < n; ++i) {
    const size = meta.size.slice(3 * i, 3 * i + 3);
    const mesh = new THREE.Mesh(geometryFor(meta.shape[i], size),
                                new THREE.MeshLambertMaterial({color: 0x888888}));
    mesh.userData = {module: meta.module[i], half: countBefore(meta.module, i)};
    movingGroup.add(mesh);
    moving.push(mesh);
    if (meta.shape[i] === SHAPE_BOX && !isPendulum) {
      const edges = new THREE.LineSegments(new THREE.EdgesGeometry(mesh.geometry),
                                           new THREE.LineBasicMaterial({color: 0x222222}));
      mesh.add(edges);
    }
  }
  bodyMeta = meta;
  rod.visible = rail.visible = isPendulum;
  ground.visible = grid.visible = !isPendulum;
  clearTrack();
}

function countBefore(modules, i) {
  let k = 0;
  for (let j = 0; j < i; ++j) if (modules[j] === modules[i]) ++k;
  return k;
}

function buildStatic(bodies) {
  for (const m of statics) { staticGroup.remove(m); m.geometry.dispose(); }
  statics = [];
  const n = bodies.module.length;
  for (let i = 0; i < n; ++i) {
    const mesh = new THREE.Mesh(geometryFor(bodies.shape[i], bodies.size.slice(3 * i, 3 * i + 3)),
                                new THREE.MeshLambertMaterial({color: 0x8d6e4a}));
    placeMesh(mesh, bodies.pose, i);
    staticGroup.add(mesh);
    statics.push(mesh);
  }
}

function placeMesh(mesh, pose, i) {
  const o = 7 * i;
  mesh.position.set(pose[o], pose[o + 1], pose[o + 2]);
  mesh.quaternion.set(pose[o + 4], pose[o + 5], pose[o + 6], pose[o + 3]);  // x y z w
}

// ---- colours ---------------------------------------------------------------------------------
let hormonePick = [0, 1, 2];
function moduleColour(module, mods, half) {
  const m = mods && mods[module];
  const c = new THREE.Color();
  if (m && m.h && m.h.length) {
    const v = hormonePick.map((k) => (k < m.h.length ? m.h[k] : 0));
    c.setRGB(0.15 + 0.85 * v[0], 0.15 + 0.85 * v[1], 0.15 + 0.85 * v[2]);
  } else {
    c.setHex(PALETTE[module % PALETTE.length]);
  }
  if (half === 1) c.multiplyScalar(0.8);
  return c;
}

// ---- the data --------------------------------------------------------------------------------
let mode = 'none';      // log | run | live
let recordings = [];    // log: every episode; run: the newest best
let rec = null;         // the recording shown
let playTime = 0, playing = !capture, speed = 1;
let live = {frames: [], scene: null, fitness: null, clock: null, mods: {}, episode: null};
let shown = null;       // the frame on screen
let selected = null;    // module of the side panel

function frameAtTime(r, t) {
  // The last frame whose time <= t (frames are in time order).
  const f = r.frames;
  let lo = 0, hi = f.length - 1;
  if (hi < 0) return -1;
  if (t <= f[0].time) return 0;
  while (lo < hi) {
    const mid = (lo + hi + 1) >> 1;
    if (f[mid].time <= t + 1e-9) lo = mid; else hi = mid - 1;
  }
  return lo;
}

function duration(r) { return r && r.frames.length ? r.frames[r.frames.length - 1].time : 0; }

function useRecording(r) {
  rec = r;
  buildMoving(r.bodies);
  if (r.scene && r.scene.bodies) buildStatic(r.scene.bodies); else buildStatic({module: [], shape: [], size: [], pose: []});
  playTime = r.frames.length ? r.frames[0].time : 0;
  document.getElementById('seek').max = String(r.frames.length - 1);
  frameCamera(r.frames[0], true);
  showFrameIndex(0);
}

// Mods carried forward: a frame without data of a module shows that module's last data.
function modsUpTo(r, index) {
  const out = [];
  for (let i = index; i >= 0 && i > index - 50; --i) {
    const ms = r.frames[i].mods || [];
    for (let k = 0; k < ms.length; ++k) if (ms[k] && !out[k]) out[k] = ms[k];
  }
  return out;
}

function showFrameIndex(index) {
  if (!rec || index < 0) return;
  const f = rec.frames[index];
  let fit = null;
  for (let i = index; i >= 0; --i) if (rec.frames[i].fitness !== null && rec.frames[i].fitness !== undefined) { fit = rec.frames[i].fitness; break; }
  const final = index === rec.frames.length - 1 ? rec.final : null;
  drawFrame(f, modsUpTo(rec, index), fit, final);
  document.getElementById('seek').value = String(index);
  trackTo(rec, index);
}

function drawFrame(f, mods, fitness, final) {
  if (!bodyMeta) return;
  const n = Math.min(moving.length, f.pose.length / 7);
  for (let i = 0; i < n; ++i) {
    placeMesh(moving[i], f.pose, i);
    const u = moving[i].userData;
    moving[i].material.color.copy(moduleColour(u.module, mods, isPendulum ? 0 : u.half));
    if (selected !== null && u.module === selected) moving[i].material.emissive.setHex(0x333333);
    else moving[i].material.emissive.setHex(0x000000);
  }
  if (isPendulum && n >= 2) {
    const p = rod.geometry.attributes.position.array;
    p.set([f.pose[0], f.pose[1], f.pose[2], f.pose[7], f.pose[8], f.pose[9]]);
    rod.geometry.attributes.position.needsUpdate = true;
  }
  shown = {tick: f.tick, time: f.time, fitness: fitness, mods: mods, final: final, pose: f.pose};
  followCamera(f);
  updateHud();
  updatePanel();
}

// ---- centroid track --------------------------------------------------------------------------
let trackLen = 0;
function clearTrack() { trackLen = 0; track.geometry.setDrawRange(0, 0); }
function trackPoint(f) {
  // Gait: the centroid of the module bodies on the ground; pendulum: the bob.
  if (isPendulum) { const i = bodyMeta.shape.indexOf(SHAPE_SPHERE); return [f.pose[7 * i], f.pose[7 * i + 1], f.pose[7 * i + 2]]; }
  let x = 0, y = 0, k = 0;
  for (let i = 0; i < bodyMeta.module.length; ++i) if (bodyMeta.module[i] >= 0) { x += f.pose[7 * i]; y += f.pose[7 * i + 1]; ++k; }
  return [x / k, y / k, 0.002];
}
function trackTo(r, index) {
  // Recording: the track from the start to the frame shown (the bob's: the last 2 s).
  const start = isPendulum ? Math.max(0, index - Math.round(2 / (r.period || 0.05))) : 0;
  const step = Math.max(1, Math.ceil((index - start + 1) / TRACK_MAX));
  const a = track.geometry.attributes.position.array;
  let k = 0;
  for (let i = start; i <= index; i += step) { a.set(trackPoint(r.frames[i]), 3 * k); ++k; }
  trackLen = k;
  track.geometry.setDrawRange(0, k);
  track.geometry.attributes.position.needsUpdate = true;
}
function trackAppend(f) {
  if (trackLen >= TRACK_MAX) clearTrack();
  track.geometry.attributes.position.array.set(trackPoint(f), 3 * trackLen);
  ++trackLen;
  track.geometry.setDrawRange(0, trackLen);
  track.geometry.attributes.position.needsUpdate = true;
}

// ---- camera ----------------------------------------------------------------------------------
const camTarget = new THREE.Vector3();
let camOffset = new THREE.Vector3(-0.5, -1.1, 0.55);
function organismCentre(f) {
  const c = new THREE.Vector3();
  let k = 0;
  for (let i = 0; i < bodyMeta.module.length; ++i) {
    if (bodyMeta.module[i] < 0) continue;
    c.x += f.pose[7 * i]; c.y += f.pose[7 * i + 1]; c.z += f.pose[7 * i + 2]; ++k;
  }
  return k ? c.multiplyScalar(1 / k) : c;
}
function frameCamera(f, jump) {
  if (!f || !bodyMeta) return;
  if (isPendulum) {
    // Side-on, framing the walls and the whole circle of the bob around the pivot.
    // The cart can reach a wall, and the bob swings a rod's length beyond it.
    const i = bodyMeta.shape.indexOf(SHAPE_SPHERE);
    const length = Math.hypot(f.pose[7 * i] - f.pose[0], f.pose[7 * i + 2] - f.pose[2]);
    let walls = 1;
    for (const m of statics) walls = Math.max(walls, Math.abs(m.position.x));
    const halfWidth = walls + length + 0.05;
    const t = Math.tan((camera.fov / 2) * Math.PI / 180);
    const d = 1.1 * Math.max((length + 0.08) / t, halfWidth / (t * camera.aspect));
    camTarget.set(0, 0, 0);
    camOffset = new THREE.Vector3(0, -d, 0.0001);
    rail.scale.set(2 * walls, 1, 1);
  } else {
    let extent = 0;
    const c = organismCentre(f);
    for (let i = 0; i < bodyMeta.module.length; ++i) if (bodyMeta.module[i] >= 0) extent = Math.max(extent, Math.hypot(f.pose[7 * i] - c.x, f.pose[7 * i + 1] - c.y));
    const d = Math.max(1.0, 4.5 * extent);
    camOffset = new THREE.Vector3(-0.45 * d, -1.0 * d, 0.55 * d);
    if (jump) camTarget.set(c.x, c.y, 0.03);
  }
  placeCamera();
}
function followCamera(f) {
  if (!bodyMeta || isPendulum) { placeCamera(); return; }
  const c = organismCentre(f);
  // A camera that follows the organism: the target eases towards the centroid (a capture renders
  // frames in any order, so there it is the centroid).
  if (capture) { camTarget.set(c.x, c.y, 0.03); placeCamera(); return; }
  camTarget.x += 0.15 * (c.x - camTarget.x);
  camTarget.y += 0.15 * (c.y - camTarget.y);
  if (Math.hypot(c.x - camTarget.x, c.y - camTarget.y) > 1) camTarget.set(c.x, c.y, 0.03);
  placeCamera();
}
function placeCamera() {
  camera.position.copy(camTarget).add(camOffset);
  camera.lookAt(camTarget);
}
// Orbit by dragging, zoom with the wheel (the camera keeps following).
(function mouseCamera() {
  let drag = null;
  renderer.domElement.addEventListener('pointerdown', (e) => { drag = {x: e.clientX, y: e.clientY, moved: false}; });
  window.addEventListener('pointerup', (e) => { if (drag && !drag.moved) pick(e); drag = null; });
  window.addEventListener('pointermove', (e) => {
    if (!drag) return;
    const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
    if (Math.abs(dx) + Math.abs(dy) > 3) drag.moved = true;
    drag.x = e.clientX; drag.y = e.clientY;
    const r = camOffset.length();
    let az = Math.atan2(camOffset.y, camOffset.x) - dx * 0.008;
    let el = Math.asin(Math.max(-1, Math.min(1, camOffset.z / r))) + dy * 0.008;
    el = Math.max(0.05, Math.min(1.5, el));
    camOffset.set(r * Math.cos(el) * Math.cos(az), r * Math.cos(el) * Math.sin(az), r * Math.sin(el));
    placeCamera();
  });
  renderer.domElement.addEventListener('wheel', (e) => {
    camOffset.multiplyScalar(e.deltaY > 0 ? 1.1 : 1 / 1.1);
    placeCamera();
    e.preventDefault();
  }, {passive: false});
})();

// ---- picking and the module panel ------------------------------------------------------------
const raycaster = new THREE.Raycaster();
function pick(e) {
  const rect = renderer.domElement.getBoundingClientRect();
  const p = new THREE.Vector2(((e.clientX - rect.left) / rect.width) * 2 - 1, -((e.clientY - rect.top) / rect.height) * 2 + 1);
  raycaster.setFromCamera(p, camera);
  const hit = raycaster.intersectObjects(moving, false)[0];
  select(hit ? hit.object.userData.module : null);
}
function select(module) {
  selected = module;
  // A live viewer sends a module's sensors and commands only to those who ask (it listens to
  // them only then: watching must not cost the arena).
  if (module !== null && mode === 'live' && socket && socket.readyState === 1) socket.send(JSON.stringify({type: 'select', module: module}));
  document.getElementById('panel').hidden = module === null;
  if (shown) redraw();
}
document.getElementById('panel-close').onclick = () => select(null);

// History of a module for the plots: the last 10 s up to the frame shown.
function moduleHistory(module) {
  const out = [];
  if (rec) {
    const end = shown ? frameAtTime(rec, shown.time) : 0;
    const span = Math.round(10 / (rec.period || 0.05));
    for (let i = Math.max(0, end - span); i <= end; ++i) {
      const m = (rec.frames[i].mods || [])[module];
      if (m) out.push({t: rec.frames[i].time, m: m});
    }
  } else {
    for (const f of live.frames) if (f.mods && f.mods[module]) out.push({t: f.time, m: f.mods[module]});
  }
  return out;
}
function plot(canvasId, label, series, lo, hi) {
  const cv = document.getElementById(canvasId), g = cv.getContext('2d');
  g.clearRect(0, 0, cv.width, cv.height);
  g.fillStyle = '#333'; g.font = '11px DejaVu Sans'; g.fillText(label, 4, 11);
  if (!series.length || !series[0].values.length) return;
  const t0 = series[0].t[0], t1 = series[0].t[series[0].t.length - 1] || t0 + 1;
  const y = (v) => cv.height - 4 - ((v - lo) / (hi - lo)) * (cv.height - 18);
  series.forEach((s, k) => {
    g.strokeStyle = '#' + PALETTE[k % PALETTE.length].toString(16).padStart(6, '0');
    g.beginPath();
    s.values.forEach((v, i) => {
      const x = 2 + ((s.t[i] - t0) / Math.max(1e-9, t1 - t0)) * (cv.width - 4);
      if (i) g.lineTo(x, y(v)); else g.moveTo(x, y(v));
    });
    g.stroke();
  });
}
function seriesOf(hist, key) {
  const n = hist.reduce((a, h) => Math.max(a, h.m[key] ? h.m[key].length : 0), 0);
  const out = [];
  for (let k = 0; k < n; ++k) {
    const s = {t: [], values: []};
    for (const h of hist) if (h.m[key] && k < h.m[key].length && (key !== 's' || !h.m.sp || h.m.sp[k])) { s.t.push(h.t); s.values.push(h.m[key][k]); }
    if (s.values.length) out.push(s);
  }
  return out;
}
function updatePanel() {
  if (selected === null || capture) return;
  const m = shown && shown.mods ? shown.mods[selected] : null;
  const hinge = m && m.g !== undefined && !isPendulum ? ', hinge ' + (m.g * 180 / Math.PI).toFixed(1) + '\u00b0' : '';
  document.getElementById('panel-title').textContent = (isPendulum ? 'compartment ' : 'module ') + selected + hinge;
  const hist = moduleHistory(selected);
  const series = {s: seriesOf(hist, 's'), h: seriesOf(hist, 'h'), a: seriesOf(hist, 'a')};
  plot('plot-sensors', 'sensors', series.s, 0, 1);
  plot('plot-hormones', hist.some((h) => h.m.h) ? 'hormones' : 'hormones (only in ahhs-replay logs)', series.h, 0, 1);
  plot('plot-actuators', 'actuators', series.a, -1, 1);
  plotted = {sensors: series.s.length, hormones: series.h.length, actuators: series.a.length, points: hist.length};
}
let plotted = null;  // what the module panel drew (tests)

// ---- HUD -------------------------------------------------------------------------------------
let title = 'ahhs-view';
function updateHud() {
  document.getElementById('title').textContent = title + (rec && rec.title ? ': ' + rec.title : '');
  if (!shown) return;
  const fit = shown.fitness === null || shown.fitness === undefined ? '-' : shown.fitness.toFixed(4);
  let hinges = '';
  if (shown.mods && !isPendulum) {
    hinges = '\nhinges ' + shown.mods.map((m) => (m && m.g !== undefined ? (m.g * 180 / Math.PI).toFixed(0) + '\u00b0' : '-')).join(' ');
  }
  let text = 't ' + shown.time.toFixed(2) + ' s   tick ' + shown.tick + '   fitness ' + fit + hinges;
  if (mode !== 'live' && !capture) text += '\n' + speed + 'x' + (playing ? '' : ' (paused)');
  document.getElementById('readout').textContent = text;
  const msg = shown.final && !shown.final.ok ? 'episode failed: ' + shown.final.message : '';
  document.getElementById('message').textContent = msg;
}

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
