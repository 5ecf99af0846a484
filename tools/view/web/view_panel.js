// ahhs-view's page, part 3 of 4: picking a module, its side panel with plots, and the HUD.
'use strict';

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
