// ahhs-view's page, part 2 of 4: the recordings and live frames, drawing a frame, the
// centroid track and the camera.
'use strict';

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
