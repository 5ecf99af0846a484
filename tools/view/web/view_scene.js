// ahhs-view's page, part 1 of 4 (docs/viewer.md): the three.js scene, the bodies' meshes and
// their colours. The page's scripts are classic scripts loaded in order (index.html): view_scene.js,
// view_frames.js, view_panel.js, view.js; each uses what the ones before it declare.
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
