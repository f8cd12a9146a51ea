// The page of `sylva view` (docs/view.md): draws the .glb the server builds with the library's
// own writers, follows the file's edits through the server's event stream, and gives every
// parameter a slider. The server is the only source: no request leaves this machine.
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { createScene, skeletonFrom } from './scene.js';
import { linesFrom } from './preview.js';

const $ = (id) => document.getElementById(id);

// ---- state ----
const state = {
  model: '',          // '' : the file's first model (or its scene)
  seed: '',
  step: '',           // '' : the model's `derive`
  leaves: '', lod: '', wind: false,
  sets: {},           // name -> value, the parameters moved away from the file's
  params: [],         // the chosen model's, from /api/describe
  mode: 'mesh',
  forceLod: 'auto',
  stats: null,
  build: null,        // the last build's answer (ok or not)
  loads: 0,           // models drawn, for the tests
  builtGen: -1,       // the files' generation of the last build shown (-1: none)
  error: '',          // the overlay's text ('' : none)
  gen: 0,
  placed: [],         // plants placed by clicks: {model, x, y, z, on}; the file is not rewritten
  impostor: false,    // the impostor's billboards as the far level
  caps: null,         // what the last build's kind can do, as the server names it (not_a_plant, ages, …)
  forest: null,       // an ecosystem's forest: its batches and what the last frame drew of them
  far: 1.5,           // the forest's far level beyond this many terrain diagonals from the camera
};
window.sylvaView = state;

// Whether a build's kind is not a plant (an ecosystem's run: its forest, panel and chart), asked
// of the capabilities the server sends from the library's table of kinds, never of a kind's name.
const notAPlant = (s) => !!(s && s.caps && s.caps.not_a_plant);

// ---- three.js (scene.js, shared with the Python package's notebook view) ----
const canvas = $('canvas');
const view = createScene(canvas, { shadowsOnDemand: true, antialias: false });
const { renderer, scene, camera, controls, sun, ground } = view;

let root = null;        // the drawn model (a group)
let lodObject = null;   // THREE.LOD when the file has levels
let skeletonLines = null, boxHelper = null;
let mixer = null;
let pickables = [];     // a scene's obstacles, for placing plants on them (not drawn: the .glb has them)
let forest = null;      // {batches: [{full: [InstancedMesh], coarse, centre, species, count}], diagonal}
const clock = new THREE.Clock();
const originals = new Map(); // mesh -> its own material (lighting and texture toggles swap them)

// where the camera is, for the tests (rounded: it must not move on a reload)
window.sylvaCamera = () => ({ position: camera.position.toArray().map((x) => +x.toFixed(4)),
  target: controls.target.toArray().map((x) => +x.toFixed(4)) });

// the triangles of level k of the levels of detail (the tests compare them with the build's)
window.sylvaLevelTriangles = (k) => {
  let n = 0;
  if (lodObject && lodObject.levels[k]) lodObject.levels[k].object.traverse((o) => {
    if (o.isMesh) n += (o.geometry.index ? o.geometry.index.count : o.geometry.attributes.position.count) / 3;
  });
  return n;
};
// the forest's far level, batch by batch (the tests): its triangles, whether it is textured, its look
window.sylvaForestFar = () => (forest ? forest.batches : []).map((b) => ({
  triangles: (b.coarse.geometry.index ? b.coarse.geometry.index.count : b.coarse.geometry.attributes.position.count) / 3,
  textured: !!(b.coarse.material && b.coarse.material.map), look: b.coarse.userData.impostor, count: b.coarse.count }));
// where a point of the world is on the canvas, in CSS pixels (for the tests' clicks)
window.sylvaProject = (x, y, z) => {
  const p = new THREE.Vector3(x, y, z).project(camera), r = canvas.getBoundingClientRect();
  return { x: r.left + (p.x + 1) / 2 * r.width, y: r.top + (1 - p.y) / 2 * r.height };
};

function resize() { if (view.resize()) redraw(); }

// The canvas is not multisampled: a full frame is drawn into a multisampled picture (the same
// four samples a pixel the canvas would have) and copied onto it, a preview's frame straight
// onto it. SwiftShader rasterizes each line and pixel four times over when multisampled: the
// 117 k-module plant's segments preview (9,841 lines and the ground) took 18 ms a frame on a
// multisampled canvas, 7 ms on this one. The picture is sRGB, as the canvas is: the same colours,
// kept in 8 bits without banding.
let fullTarget = null;
const copyScene = new THREE.Scene(), copyCamera = new THREE.OrthographicCamera(-1, 1, 1, -1, 0, 1);
const copyQuad = new THREE.Mesh(new THREE.PlaneGeometry(2, 2),
  new THREE.MeshBasicMaterial({ depthTest: false, depthWrite: false, toneMapped: false }));
copyScene.add(copyQuad);
const drawingSize = new THREE.Vector2();
// quick: straight onto the canvas (the first frame after a change, below); the same picture,
// shadows included, without the multisampling and its copy
function render(quick = false) {
  if (state.preview) { // nothing casts a shadow in a preview, nothing takes one: no shadow pass
    renderer.shadowMap.needsUpdate = false;
    renderer.render(scene, camera);
    return;
  }
  if (quick) { renderer.setRenderTarget(null); renderer.render(scene, camera); return; }
  renderer.getDrawingBufferSize(drawingSize);
  if (!fullTarget || fullTarget.width !== drawingSize.x || fullTarget.height !== drawingSize.y) {
    if (fullTarget) fullTarget.dispose();
    fullTarget = new THREE.WebGLRenderTarget(drawingSize.x, drawingSize.y, { samples: 4, colorSpace: THREE.SRGBColorSpace });
    copyQuad.material.map = fullTarget.texture;
    copyQuad.material.needsUpdate = true;
  }
  renderer.setRenderTarget(fullTarget);
  renderer.render(scene, camera);
  renderer.setRenderTarget(null);
  renderer.render(copyScene, copyCamera);
}

// The canvas's pixels as they are (RGBA rows, bottom first): the tests compare a quick frame
// with the full one that follows it.
window.sylvaCanvasPixels = () => {
  const gl = renderer.getContext(), px = new Uint8Array(gl.drawingBufferWidth * gl.drawingBufferHeight * 4);
  gl.readPixels(0, 0, gl.drawingBufferWidth, gl.drawingBufferHeight, gl.RGBA, gl.UNSIGNED_BYTE, px);
  return px;
};

// The time of one whole frame as it is now, in ms (the best of n): drawn, then a pixel read
// back, which waits for the pixels (make bench: frame time; the draw call alone returns early).
window.sylvaScene = view; // the renderer, scene, ground and sun (the tests and make bench)
// quick: the first frame after a change's (no multisampling), not the settled one's.
window.sylvaFrameMs = (n = 3, quick = false) => {
  const gl = renderer.getContext(), px = new Uint8Array(4);
  let best = Infinity;
  for (let k = 0; k < n; k++) {
    renderer.shadowMap.needsUpdate = true;
    const t = performance.now();
    if (forest) updateForest();
    render(quick);
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);
    best = Math.min(best, performance.now() - t);
  }
  return best;
};

// A frame is drawn when something changed (the camera, a control, a build) or while wind
// plays, not sixty times a second: an idle page costs nothing (laptops, software WebGL).
let dirty = true;
function redraw() { dirty = true; renderer.shadowMap.needsUpdate = true; }
controls.addEventListener('change', () => { dirty = true; if (forest) renderer.shadowMap.needsUpdate = true; });
// A parameter's slider or field, the seed and the step change the picture only when their build
// comes: redrawing the old model at each move of a drag would put a frame of it (in software
// WebGL, of a big plant, a second) before every new picture.
const builds = (e) => e.target && e.target.closest && e.target.closest('#params, #step, #seed');
for (const ev of ['input', 'change', 'click', 'keydown']) document.addEventListener(ev, (e) => { if (!builds(e)) redraw(); }, true);
window.addEventListener('resize', redraw);

// make bench (state.measurePixels): when the frame just drawn has its pixels (Date.now()). The
// draw call returns before software WebGL has filled them (a second later for a big mesh);
// reading a pixel back waits for them, and the page's thread with it: off for a user.
function pixelsDone() {
  const gl = renderer.getContext(), px = new Uint8Array(4);
  gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);
  return Date.now();
}

// A preview is drawn at half the resolution: software WebGL (and a slow GPU) spends a frame's
// time on its pixels, the ground's shadow lookups and multisampling above all.
const fullRatio = renderer.getPixelRatio();
let drawnRoot = null; // the model the last frame drew
// The first frame after a change (a build, the camera, a control) is drawn quick, straight onto
// the canvas; the full frame (multisampled, copied) follows in the next animation frame if
// nothing changed meanwhile, and stays. SwiftShader spends most of a full frame of a small
// plant on the multisampled picture and its copy (Fig. 2.6 at n = 10, 900 × 700: about 185 ms
// against 45 for the same frame drawn quick): a save's new plant is on screen that much sooner,
// and an orbit drag moves at the quick frame's rate. While wind plays every frame is a full one.
let settle = false;
state.settled = false; // the last frame drawn is the full one and none is due (the tests)
function animate() {
  const ratio = state.preview ? fullRatio / 2 : fullRatio;
  if (renderer.getPixelRatio() !== ratio) { renderer.setPixelRatio(ratio); redraw(); }
  resize();
  const dt = clock.getDelta();
  if (mixer) { mixer.update(dt); redraw(); }
  controls.update();
  if (dirty) {
    dirty = false;
    if (forest) updateForest();
    const tf = performance.now(), quick = !state.preview && !mixer;
    render(quick);
    settle = quick; state.settled = !quick;
    if (quick && state.keepQuick) state.quickPicture = window.sylvaCanvasPixels(); // the tests
    state.frameMs = performance.now() - tf; // the draw call's time (make bench: frame time)
    state.frames = (state.frames || 0) + 1;
    if (root !== drawnRoot) { drawnRoot = root; state.pictures = (state.pictures || 0) + 1; } // a new build on screen
    if (state.previewAt && !state.previewShownAt) { // a preview's first frame (make bench: save to preview)
      state.previewShownAt = performance.now(); state.previewShownWall = Date.now();
      state.previewMs = state.previewShownAt - state.previewAt; // its first frame's draw
      state.previewPixelsWall = state.measurePixels ? pixelsDone() : 0;
    }
    if (state.drawnAt && !state.shownAt) { // the first frame of the last build (make bench: save to frame)
      state.shownAt = performance.now(); state.shownWall = Date.now();
      if (state.timing) state.timing.frame = state.shownAt - state.drawnAt;
      state.pixelsWall = state.measurePixels ? pixelsDone() : 0;
      // the metrics once the page rests a second on this build (a save or a drag going on
      // asks for none: their light interception would share the processor with the builds)
      if (state.metricsPending) { const id = state.metricsPending; state.metricsPending = 0; setTimeout(() => { if (!loading) metricsOf(id); }, 1000); }
    }
  } else if (settle) { // nothing changed since the quick frame: the full one
    settle = false;
    render();
    state.settled = true; state.settledAt = performance.now(); state.settledWall = Date.now();
    state.settledFrames = (state.settledFrames || 0) + 1;
    state.settledPixelsWall = state.measurePixels ? pixelsDone() : 0;
  }
  requestAnimationFrame(animate);
}

// ---- the server ----
function query(extra = {}) {
  const q = new URLSearchParams();
  if (state.model) q.set('model', state.model);
  if (state.seed !== '') q.set('seed', state.seed);
  if (state.step !== '') q.set('n', state.step);
  if (state.leaves) q.set('leaves', state.leaves);
  if (state.lod !== '') q.set('lod', state.lod);
  if (state.wind) q.set('wind', '8');
  if (state.impostor) q.set('impostor', '1');
  for (const [k, v] of Object.entries(state.sets)) q.append('set', `${k}=${v}`);
  for (const [k, v] of Object.entries(extra)) q.set(k, v);
  return q.toString();
}

async function getJSON(url) {
  const r = await fetch(url, { credentials: 'same-origin' });
  return r.json();
}

// ---- drawing a build ----
const bounds = view.bounds;

function frame() {
  if (!root) return;
  view.frame(root);
  redraw();
}

function placeGroundAndSun() {
  view.placeGroundAndSun(root);
}

// MSFT_lod (what `sylva mesh --lod` writes): three.js's GLTFLoader draws the first level only;
// the others are nodes of the file, gathered into a THREE.LOD switched by distance, each level
// where its MSFT_screencoverage says.
async function gatherLods(gltf) {
  const json = gltf.parser.json;
  const nodes = json.nodes || [];
  const first = nodes.findIndex((n) => n.extensions && n.extensions.MSFT_lod);
  if (first < 0) return null;
  const ids = [first, ...nodes[first].extensions.MSFT_lod.ids];
  const coverage = (nodes[first].extras && nodes[first].extras.MSFT_screencoverage) || [];
  const lod = new THREE.LOD();
  const objects = await Promise.all(ids.map((i) => gltf.parser.getDependency('node', i)));
  const box = bounds(objects[0]);
  const r = Math.max(box.getSize(new THREE.Vector3()).length() / 2, 1e-3);
  const t = Math.tan(THREE.MathUtils.degToRad(camera.fov / 2));
  objects.forEach((o, k) => {
    const c = k === 0 ? 1 : (coverage[k - 1] || Math.pow(0.5, k));
    // a level is drawn while the sphere covers less than the previous level's share of the screen
    const d = k === 0 ? 0 : r / (Math.sqrt(c) * t);
    lod.addLevel(o.clone ? o : o, d);
  });
  return lod;
}


function meshes(fn) {
  if (root) root.traverse((o) => { if (o.isMesh) fn(o); });
}

function applyLook() {
  const lit = $('lighting').checked, tex = $('textures').checked, mode = state.mode;
  meshes((m) => {
    if (m.userData.pick) return; // an obstacle's target for clicks, never drawn
    if (!originals.has(m)) originals.set(m, m.material);
    const own = originals.get(m);
    const list = Array.isArray(own) ? own : [own];
    const made = list.map((o) => {
      const mat = lit ? o.clone() : new THREE.MeshBasicMaterial({ color: o.color, map: o.map, alphaTest: o.alphaTest,
        transparent: o.transparent, side: o.side });
      if (!tex) mat.map = null;
      mat.wireframe = mode === 'wireframe';
      mat.needsUpdate = true;
      return mat;
    });
    m.material = Array.isArray(own) ? made : made[0];
    m.castShadow = $('shadows').checked && !state.preview; // a preview's frame skips the shadow pass
    m.visible = mode === 'mesh' || mode === 'wireframe';
  });
  sun.visible = $('shadows').checked || lit;
  sun.castShadow = $('shadows').checked;
  ground.receiveShadow = $('shadows').checked && !state.preview; // nothing casts on it: no shadow lookups
  if (skeletonLines) skeletonLines.visible = mode === 'skeleton';
  if (boxHelper) boxHelper.visible = mode === 'box';
  if (lodObject) {
    lodObject.autoUpdate = state.forceLod === 'auto';
    if (state.forceLod !== 'auto') lodObject.levels.forEach((l, k) => { l.object.visible = k === +state.forceLod; });
  }
  redraw();
}

// The skeleton's lines of the build on show (sylva skeleton's CSV), asked for when first shown.
async function loadSkeleton() {
  const b = state.build, group = root;
  if (skeletonLines || !b || !b.ok || !group) return;
  const r = await fetch('/api/skeleton?id=' + b.id);
  if (!r.ok || root !== group || skeletonLines) return; // a newer build is on show
  skeletonLines = skeletonFrom(await r.text());
  group.add(skeletonLines);
}

async function setMode(mode) {
  if (mode === 'skeleton') await loadSkeleton();
  state.mode = mode;
  document.querySelectorAll('#modes button').forEach((b) => b.classList.toggle('on', b.dataset.mode === mode));
  applyLook();
}

function showError(text) {
  state.error = text;
  const el = $('error');
  el.hidden = !text;
  el.textContent = text;
}

function showStats(s) {
  const rows = notAPlant(s) ? [
    ['kind', s.kind], ['year', s.year], ['plants', s.plants], ...s.species.map((sp) => [sp.name, sp.plants]),
    ['simulate', (s.simulate_time * 1000).toFixed(1) + ' ms'],
  ] : s ? [
    ['kind', s.kind], ['modules', s.modules], ['nodes', s.nodes], ['organs', s.organs], ['polygons', s.polygons],
    ['vertices', s.vertices], ['triangles', s.triangles], ['leaf instances', s.leaf_instances],
    ['levels of detail', s.lod_levels ? s.lod_triangles.join(' / ') + ' triangles' : 'none'],
    ['compile', (s.compile_time * 1000).toFixed(1) + ' ms'], ['derive', (s.derive_time * 1000).toFixed(1) + ' ms'],
    ['turtle', (s.turtle_time * 1000).toFixed(1) + ' ms'], ['mesh', (s.mesh_time * 1000).toFixed(1) + ' ms'],
    ['write .glb', (s.write_time * 1000).toFixed(1) + ' ms'], ['memory', s.memory_mb + ' MB'],
  ] : [];
  const m = s && !notAPlant(s) && state.metrics;
  if (m) { // what `sylva compare` measures (syl_metrics_compute), once the server has them
    m.stems_by_order.forEach((n, k) => rows.push([`stems of order ${k}`, n]));
    rows.push(['leaves', m.leaves]);
    for (const r of m.metrics) rows.push([r.label, r.value === null ? '-' : +r.value.toPrecision(6) + (r.unit ? ' ' + r.unit : '')]);
  }
  $('stats').replaceChildren(...rows.map(([k, v]) => {
    const tr = document.createElement('tr');
    tr.innerHTML = '<td></td><td></td>';
    tr.children[0].textContent = k; tr.children[1].textContent = v;
    tr.children[1].id = 'stat-' + k.replace(/ /g, '-');
    return tr;
  }));
}

// The metrics of `sylva compare` for build id, asked for after its frame: their ray casting
// (light interception) never delays the picture. A newer build's answer wins.
async function metricsOf(id) {
  if (!state.build || state.build.id !== id) return; // a newer build is on show
  const r = await fetch('/api/metrics?id=' + id).catch(() => null);
  if (!r || !r.ok || !state.build || state.build.id !== id) return;
  state.metrics = await r.json();
  state.metricsId = id;
  showStats(state.stats);
}

// ---- an ecosystem: the forest, its chart and maps ----
// The forest .glb (syl_forest_write_glb) holds one node per species, age class, look and cell,
// its plants instanced with EXT_mesh_gpu_instancing (three.js draws them as InstancedMesh).
// Each batch is culled by three.js against the view frustum (its bounding sphere covers its
// instances); beyond `far` of the terrain's diagonal a batch is drawn by its far level: the
// look's impostor — three crossed billboards showing the look's pictures, baked by the library
// (syl_impostor_bake, as `sylva mesh --billboards 3`) and served as a .glb per look — one per
// plant, sharing the batch's instance matrices.
const palette = ['#2e7d32', '#e68c1e', '#1e5aa0', '#aa3c96', '#c0392b', '#16a085', '#7f8c8d', '#8e6e1e'];
const impostors = new Map(); // run (the query without the year) + look -> {geometry, material}

async function impostorOf(look) {
  const key = query({ n: '' }) + '#' + look;
  if (!impostors.has(key)) impostors.set(key, (async () => {
    const r = await fetch('/api/impostor?look=' + look);
    if (!r.ok) return null;
    const g = await loader.parseAsync(await r.arrayBuffer(), '');
    g.scene.updateMatrixWorld(true);
    let found = null;
    g.scene.traverse((o) => { if (o.isMesh && !found) found = o; });
    return found && { geometry: found.geometry.clone().applyMatrix4(found.matrixWorld), material: found.material };
  })());
  return impostors.get(key);
}

async function setupForest(sceneRoot, stats) {
  const byNode = new Map();
  sceneRoot.updateMatrixWorld(true);
  sceneRoot.traverse((o) => {
    if (!o.isInstancedMesh) return;
    let n = o;
    while (n && !(n.userData && n.userData.species)) n = n.parent;
    if (!n) return;
    if (!byNode.has(n)) byNode.set(n, []);
    byNode.get(n).push(o);
  });
  const batches = [];
  const looks = stats.looks || [];
  for (const [node, full] of byNode) {
    for (const m of full) m.computeBoundingSphere();
    const u = node.userData;
    const look = looks.findIndex((l) => l.species === u.species && l.class === u.class && l.variant === u.variant);
    const imp = look >= 0 ? await impostorOf(look) : null;
    // no picture of it (the bake failed): its far level is its looks
    const coarse = imp ? new THREE.InstancedMesh(imp.geometry, imp.material, full[0].count) : full[0].clone();
    coarse.userData.impostor = imp ? look : -1;
    coarse.instanceMatrix = full[0].instanceMatrix;
    coarse.matrixAutoUpdate = false;
    coarse.matrix.copy(full[0].matrixWorld);
    coarse.computeBoundingSphere();
    coarse.visible = false;
    coarse.castShadow = false;
    sceneRoot.add(coarse);
    const b = node.userData.bounds; // [x0, z0, x1, z1] of its cell
    const centre = new THREE.Vector3((b[0] + b[2]) / 2, full[0].boundingSphere.center.y, (b[1] + b[3]) / 2);
    batches.push({ full, coarse, centre, species: node.userData.species, count: full[0].count, look });
  }
  const t = stats.terrain;
  forest = { batches, diagonal: Math.hypot(t.width, t.depth) };
  const bySpecies = {};
  for (const b of batches) bySpecies[b.species] = (bySpecies[b.species] || 0) + b.count;
  state.forest = { batches: batches.length, instances: batches.reduce((a, b) => a + b.count, 0), bySpecies,
    full: 0, coarse: 0, culled: 0 };
}

const frustum = new THREE.Frustum(), projScreen = new THREE.Matrix4(), sphere = new THREE.Sphere();
function updateForest() {
  camera.updateMatrixWorld();
  projScreen.multiplyMatrices(camera.projectionMatrix, camera.matrixWorldInverse);
  frustum.setFromProjectionMatrix(projScreen);
  const far = state.far * forest.diagonal;
  let full = 0, coarse = 0, culled = 0;
  const force = state.forceLod;
  for (const b of forest.batches) {
    const level = force === 'auto' ? (camera.position.distanceTo(b.centre) > far ? 1 : 0) : +force;
    for (const m of b.full) m.visible = level === 0 && state.mode !== 'skeleton' && state.mode !== 'box';
    b.coarse.visible = level === 1 && state.mode !== 'skeleton' && state.mode !== 'box';
    sphere.copy(b.full[0].boundingSphere).applyMatrix4(b.full[0].matrixWorld);
    if (!frustum.intersectsSphere(sphere)) culled++; // three.js skips it too (frustumCulled)
    else if (level === 0) full++;
    else coarse++;
  }
  if (state.forest) Object.assign(state.forest, { full, coarse, culled });
  $('forest').textContent = `${state.forest.instances} plants in ${forest.batches.length} batches: ` +
    `${full} near, ${coarse} far, ${culled} culled`;
}

// The chart: each species' plants over the years (species.csv's count), the year shown marked.
function showChart(s) {
  const svg = $('chart'), W = 280, H = 150, L = 34, B = 16;
  const years = s.chart_years, maxYear = years[years.length - 1] || 1;
  const top = Math.max(1, ...s.species.map((sp) => Math.max(...sp.count)));
  const X = (y) => L + (W - L - 4) * y / maxYear, Y = (c) => H - B - (H - B - 6) * c / top;
  const ns = 'http://www.w3.org/2000/svg';
  const el = (name, attrs, text) => {
    const e = document.createElementNS(ns, name);
    for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
    if (text !== undefined) e.textContent = text;
    return e;
  };
  const kids = [el('line', { x1: L, y1: H - B, x2: W - 4, y2: H - B, stroke: '#888' }),
    el('line', { x1: L, y1: 6, x2: L, y2: H - B, stroke: '#888' }),
    el('text', { x: L - 3, y: 12, 'text-anchor': 'end', 'font-size': 9 }, String(top)),
    el('text', { x: L - 3, y: H - B, 'text-anchor': 'end', 'font-size': 9 }, '0'),
    el('text', { x: W - 4, y: H - 3, 'text-anchor': 'end', 'font-size': 9 }, `year ${maxYear}`)];
  s.species.forEach((sp, k) => {
    const pts = sp.count.map((c, i) => `${X(years[i]).toFixed(1)},${Y(c).toFixed(1)}`).join(' ');
    kids.push(el('polyline', { points: pts, fill: 'none', stroke: palette[k % palette.length], 'stroke-width': 1.5,
      'data-species': sp.name }));
  });
  kids.push(el('line', { id: 'chartyear', x1: X(s.year), x2: X(s.year), y1: 6, y2: H - B, stroke: '#000', 'stroke-dasharray': '3 2' }));
  svg.replaceChildren(...kids);
  const at = years.indexOf(s.year);
  $('legend').replaceChildren(...s.species.map((sp, k) => {
    const span = document.createElement('span');
    span.innerHTML = '<i></i><b></b> <em></em>';
    span.querySelector('i').style.background = palette[k % palette.length];
    span.querySelector('b').textContent = sp.name;
    span.querySelector('em').textContent = at >= 0 ? sp.count[at] : '';
    span.dataset.species = sp.name;
    return span;
  }));
  $('ecoyear').textContent = `year ${s.year} of ${s.years}: ${s.plants} plants` +
    (s.stride > 1 ? ` (every ${s.stride}th year kept)` : '');
}

function showMaps(s) {
  const sel = $('mapname'), keep = sel.value;
  sel.replaceChildren(...s.maps.map((m) => new Option(m, m)));
  sel.value = s.maps.includes(keep) ? keep : s.maps[0] || '';
  $('map').src = sel.value ? `/api/map?factor=${encodeURIComponent(sel.value)}&gen=${state.gen}` : '';
}

function showEco(s) {
  $('ecopanel').hidden = false;
  $('steplabel').textContent = 'Year';
  $('step').min = 1; $('step').max = s.years; $('step').value = s.year;
  $('stepval').textContent = s.year;
  showChart(s);
  showMaps(s);
}

const loader = new GLTFLoader();
let loading = null, again = false;

// The textures of the last builds by their PNG bytes: a save writes the same bark, leaf and
// card pictures again, and a texture already on the GPU (uploaded, mipmapped) is used again
// instead of the new copy. The .glb is not changed: only which THREE.Texture draws it.
const textures = new Map(); // key -> THREE.Texture
// the pictures kept, and those the drawn materials use (the tests)
window.sylvaTextures = () => {
  const drawn = new Set();
  if (root) root.traverse((o) => { if (o.isMesh) for (const m of [].concat(o.material)) if (m && m.map) drawn.add(m.map.source.uuid); });
  return { kept: [...textures.values()].map((t) => t.source.uuid), drawn: [...drawn] };
};
function pngKey(json, bin, i) {
  const img = json.images && json.images[i];
  const view = img && img.bufferView !== undefined ? json.bufferViews[img.bufferView] : null;
  if (!view) return null;
  const bytes = new Uint8Array(bin, (view.byteOffset || 0), view.byteLength);
  let h = 2166136261;
  for (let k = 0; k < bytes.length; k++) h = Math.imul(h ^ bytes[k], 16777619);
  return `${view.byteLength}:${h >>> 0}`;
}
// A GLTFLoader plugin for the builds' .glb: a texture whose PNG bytes (and sampler) are a kept
// one's is that texture — not decoded, not uploaded again; a new one is decoded and kept.
// used: the keys the last parse took (the others are let go after it).
let texturesUsed = new Set();
const usedBy = { full: new Set(), preview: new Set() }; // what the last full build's and preview's parses took
const reuse = (parser) => ({
  name: 'sylva_texture_reuse',
  loadTexture(t) {
    const json = parser.json, def = json.textures[t];
    if (def.source === undefined || (def.extensions && Object.keys(def.extensions).length)) return null;
    return parser.getDependency('buffer', 0).then((bin) => {
      const png = pngKey(json, bin, def.source);
      if (png === null) return parser.loadTextureImage(t, def.source, parser.textureLoader);
      const key = png + ':' + (def.sampler ?? '');
      texturesUsed.add(key);
      if (textures.has(key)) return textures.get(key);
      return parser.loadTextureImage(t, def.source, parser.textureLoader).then((tex) => { textures.set(key, tex); return tex; });
    });
  },
});
const buildLoader = new GLTFLoader().register(reuse);
function forgetTextures() { // the kept ones neither the last build nor the last preview used
  for (const [key, tex] of textures) if (!usedBy.full.has(key) && !usedBy.preview.has(key)) { tex.dispose(); textures.delete(key); }
  texturesUsed = new Set();
}

// What the previous build put on the GPU (its geometries; textures not kept above). Its
// materials are not disposed: three.js would then release their compiled shader programs, and
// the next build — the same kinds of material — would compile them again (in software WebGL a
// good part of a second). Programs are cached by what they do, so they stay a handful.
function disposeBuild(group) {
  const kept = new Set([...textures.values()].map((t) => t.source));
  group.traverse((o) => {
    if (o.geometry) o.geometry.dispose();
    for (const m of Array.isArray(o.material) ? o.material : o.material ? [o.material] : [])
      if (m.map && !kept.has(m.map.source)) m.map.dispose();
  });
}

// Build what the controls say and draw it; the camera stays unless frameIt. A model (not an
// ecosystem) is drawn twice when the "preview first" box is ticked: first a preview the server
// makes quickly (three-sided tubes and instanced leaf cards, or only the segments of a big
// plant), then the .glb of `sylva mesh` — the one exported, and the one left on screen. While a
// slider moves only previews are built; the full build waits until it rests, and a full build
// running when it moves again is stopped (the server sees the tab's newer request). The old model stays on screen until the
// new one is drawn.
// A preview is asked for only when the last full build had more than previewAbove triangles: a
// small plant's full mesh comes as soon as its preview would, and a preview first would only add
// a build and a frame (whose drawing the full mesh's frame then waits for). Triangles, not the
// milliseconds it took: those vary with the machine's load, and the choice would too.
state.previewAbove = 50000;
let lastInput = -1e9; // when a slider last moved (performance.now())
const REST_MS = 250;  // a slider still this long has come to rest
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

// This tab and its loads' numbers: the server stops a full build of an older load of this tab
// (a slider moved on) and builds what the newer one asks for.
const tab = 1 + Math.floor(Math.random() * 2 ** 52);
let seq = 0;

// The build's answer with its .glb (or a preview's segments) as .part, in one request (with=part:
// the JSON's length, the JSON, the bytes) — a round trip less than asking for them after.
async function requestBuild(q, text) {
  try {
    const url = '/api/build?' + q + '&with=part';
    const r = await (text === null ? fetch(url, { credentials: 'same-origin' }) : fetch(url, { method: 'POST', body: text }));
    const all = await r.arrayBuffer();
    if (!r.ok || all.byteLength < 4) return { ok: false, diag: new TextDecoder().decode(all) || 'the build failed' };
    const n = new DataView(all).getUint32(0, true);
    const b = JSON.parse(new TextDecoder().decode(new Uint8Array(all, 4, n)));
    b.part = all.byteLength > 4 + n ? all.slice(4 + n) : null;
    return b;
  } catch (e) { return { ok: false, diag: String(e) }; }
}

// A load waiting for a slider to come to rest, woken by the next move (no polling delay).
let wake = null;
const restOrMove = () => new Promise((r) => {
  wake = r;
  setTimeout(r, Math.max(5, REST_MS - (performance.now() - lastInput)));
});

async function load(frameIt = false) {
  if (loading) { again = true; if (wake) wake(); return loading; }
  state.idle = false;
  loading = (async () => {
    const t0 = performance.now();
    $('status').textContent = 'building…';
    const q = query();
    const text = await editedText();
    const mine = `&tab=${tab}&seq=${++seq}`;
    let full = null; // the full build's answer
    const resting = () => performance.now() - lastInput >= REST_MS;
    const small = state.stats && !notAPlant(state.stats) && state.stats.triangles <= state.previewAbove;
    if ($('preview').checked && !notAPlant(state) && !small) {
      const p = await requestBuild(q + '&preview=1' + mine, text);
      const buf = p.ok && p.stats && !notAPlant(p.stats) ? p.part : null;
      // a newer value's request goes out while this preview's frame is drawn (the server
      // builds it meanwhile); otherwise the full build waits for the frame, below
      // its frame drawn before anything else is asked for: on a machine of few cores a request
      // sent meanwhile (measured: the next value's preview) slows the frame more than it gains
      if (buf) await (await showPreview(p, buf, q, frameIt, t0));
      // the full build once the preview is on screen (not while a slider moves): asked for at
      // once, it would share the processor with the preview's frame on a machine of few cores
      if (!again && resting()) full = requestBuild(q + mine, text);
      frameIt = false;
      // while the slider moves, only previews; a newer value is built next (load coalesces)
      while (!full && !again && !resting()) await restOrMove();
      wake = null;
      if (!full && again) return;
    }
    const b = await (full || requestBuild(q + mine, text));
    if (b.superseded || (again && full)) { state.superseded = (state.superseded || 0) + 1; return; } // a newer value comes next
    await showBuild(b, q, frameIt, t0);
  })();
  try { await loading; } finally {
    loading = null;
    if (again) { again = false; load(); } else state.idle = true;
  }
}

// Put group on screen in place of what is there (freed), with the textures of kind ('full' or
// 'preview') as its parse used them.
function replaceRoot(group, kind) {
  if (root) { scene.remove(root); disposeBuild(root); }
  usedBy[kind] = texturesUsed;
  forgetTextures();
  originals.clear();
  root = group;
  scene.add(root);
}

// The preview p (its bytes in buf) put in place of the model on screen; resolves, once set up,
// to a promise of its first frame (the full .glb's fetch and parse wait for that frame: they
// would take the page's thread from it; a newer preview's request does not).
async function showPreview(p, buf, q, frameIt, t0) {
  const tFetched = performance.now();
  const group = new THREE.Group();
  if (p.lines) group.add(linesFrom(buf));
  else {
    texturesUsed = new Set();
    group.add((await buildLoader.parseAsync(buf, '')).scene);
  }
  replaceRoot(group, 'preview');
  lodObject = null; skeletonLines = null; mixer = null;
  boxHelper = new THREE.Box3Helper(bounds(group), 0x1a4fa0);
  group.add(boxHelper);
  placeGroundAndSun();
  if (frameIt || !state.framed) { frame(); state.framed = true; }
  state.preview = { kind: p.stats.preview, query: q, triangles: p.stats.triangles, leaf_instances: p.stats.leaf_instances,
    segments: p.lines ? buf.byteLength / 25 : 0 };
  applyLook();
  state.previews = (state.previews || 0) + 1;
  state.lastPreviewKind = p.stats.preview;
  state.previewAt = performance.now(); state.previewShownAt = 0; // the frame after this shows it
  // as state.timing: ms of the build request, the fetch, the parse and setup (frame: previewMs)
  state.previewTiming = { fetched: tFetched - t0, parse: state.previewAt - tFetched,
    server: ['compile', 'derive', 'turtle', 'mesh', 'lod', 'write'].reduce((t, k) => t + (p.stats[k + '_time'] || 0), 0) * 1000 };
  redraw();
  $('status').textContent = `preview (${p.stats.preview}) · ${p.stats.modules} modules · ${(performance.now() - t0).toFixed(0)} ms · building the mesh…`;
  return new Promise((r) => { const drawn = () => (state.previewShownAt ? r() : requestAnimationFrame(drawn)); requestAnimationFrame(drawn); });
}

async function showBuild(b, q, frameIt, t0) {
  const tBuilt = performance.now();
  state.build = b;
  state.builtGen = b.gen; // the files' generation on screen (or in the overlay): listen() compares
  const warnings = (b.diag || '').split('\n').filter((l) => / warning: /.test(l));
  $('warnings').textContent = b.ok ? (b.diag || '') : '';
  if (!b.ok) { // the last good model stays
    showError(b.diag || 'the build failed');
    $('status').textContent = 'error (the last good model is shown)';
    return;
  }
  const glb = b.part || await fetch('/api/glb?id=' + b.id).then((r) => r.arrayBuffer());
  b.part = null; // state.build keeps the answer, not its bytes
  const tFetched = performance.now();
  texturesUsed = new Set();
  const gltf = await buildLoader.parseAsync(glb, '');
  const tParsed = performance.now();
  const eco = notAPlant(b.stats);
  const lod = eco ? null : await gatherLods(gltf);
  const group = new THREE.Group();
  group.add(lod || gltf.scene);
  skeletonLines = null; // made when the skeleton mode shows it (loadSkeleton): not on every save
  pickables = [];
  if (b.obstacles) { // the obstacles' own meshes: what a click may place a plant on
    const ob = await loader.parseAsync(await fetch('/api/obstacles?id=' + b.id).then((r) => r.arrayBuffer()), '');
    ob.scene.traverse((o) => { if (o.isMesh) { o.material = new THREE.MeshBasicMaterial({ visible: false }); o.userData.pick = true; pickables.push(o); } });
    group.add(ob.scene);
  }
  replaceRoot(group, 'full');
  state.preview = null;
  lodObject = lod;
  boxHelper = new THREE.Box3Helper(bounds(lod || gltf.scene), 0x1a4fa0);
  root.add(boxHelper);
  mixer = null;
  state.animations = gltf.animations.length;
  state.levels = lod ? lod.levels.length : 1;
  if (gltf.animations.length) {
    mixer = new THREE.AnimationMixer(gltf.scene);
    gltf.animations.forEach((a) => mixer.clipAction(a).play());
  }
  const levels = eco ? 2 : lod ? lod.levels.length : 1;
  const sel = $('forcelod');
  const keep = state.forceLod;
  const name = (k) => eco ? ['near (the looks)', 'far (impostors)'][k]
    : state.impostor && k === levels - 1 ? `LOD${k} (impostor)` : 'LOD' + k;
  sel.replaceChildren(new Option('by distance', 'auto'), ...Array.from({ length: levels }, (_, k) => new Option(name(k), String(k))));
  state.forceLod = keep !== 'auto' && +keep < levels ? keep : 'auto';
  sel.value = state.forceLod;
  forest = null; state.forest = null;
  if (eco) await setupForest(gltf.scene, b.stats);
  $('ecopanel').hidden = !eco;
  if (!eco) $('steplabel').textContent = 'Step';
  ground.visible = !eco; // the terrain is in the forest's .glb
  placeGroundAndSun();
  if (frameIt || !state.framed || (eco !== notAPlant(state))) { frame(); state.framed = true; }
  state.caps = b.stats.caps;
  if (eco) showEco(b.stats);
  state.stats = b.stats;
  state.metrics = null;
  showStats(b.stats);
  state.metricsPending = eco ? 0 : b.id; // asked for once this build's frame is drawn
  showError('');
  if (state.mode === 'skeleton') await loadSkeleton();
  applyLook();
  state.loads++;
  state.drawnQuery = q; // what it was built from (the tests: a drag's last value is drawn)
  state.gen = b.gen;
  state.drawnAt = performance.now(); // the frame after this shows it (state.shownAt)
  // the page's side of save -> frame (make bench prints them): ms of the build request, the
  // .glb's fetch, its parse (GLTFLoader, textures decoded), the scene's setup; the first
  // frame's draw (upload, shaders, shadows) is shownAt - drawnAt
  state.timing = { build: tBuilt - t0, fetch: tFetched - tBuilt, parse: tParsed - tFetched, setup: state.drawnAt - tParsed };
  state.shownAt = 0;
  redraw();
  $('status').textContent = eco ? `year ${b.stats.year} · ${b.stats.plants} plants · ${(performance.now() - t0).toFixed(0)} ms`
    : `${b.stats.triangles} triangles · ${b.stats.modules} modules · ${(performance.now() - t0).toFixed(0)} ms` +
    (warnings.length ? ` · ${warnings.length} warning${warnings.length > 1 ? 's' : ''}` : '');
  updateExports();
}

// ---- parameters (syl_describe_json) ----
function paramRange(p) {
  const v = p.default;
  // the schema's ±1e9 stands for no bound: a slider over it would move in steps of 1e7
  const open = (x) => x === null || Math.abs(x) >= 1e8;
  let lo = open(p.min) ? null : p.min, hi = open(p.max) ? null : p.max;
  if (lo === null) lo = v < 0 ? v * 3 : 0;
  if (hi === null) hi = Math.max(Math.abs(v) * 3, lo + 1);
  if (p.name === 'derive' || p.name === 'years') hi = Math.min(hi, Math.max(12, v * 2));
  if (p.name === 'seed') hi = Math.min(hi, 1e6);
  return [lo, hi];
}

function paramChanged(name, value, def) {
  if ((name in state.sets ? state.sets[name] : def) === value) return; // the slider moved within a step
  if (value === def) delete state.sets[name]; else state.sets[name] = value;
  $('setline').value = setLine();
  load(); // at once; while a build runs, the latest value is built next (load coalesces)
}

function buildParams() {
  const box = $('params');
  box.replaceChildren();
  for (const p of state.params) {
    if (p.name === 'seed' || p.name === 'derive' || p.name === 'years') continue; // their own fields
    const div = document.createElement('div');
    div.className = 'param';
    if (!['number', 'integer', 'boolean'].includes(p.type)) { // --set takes numbers: shown, not moved
      div.innerHTML = '<div><span class="name"></span> <span class="dim"></span></div><div class="doc"></div>';
      div.querySelector('.name').textContent = p.name;
      div.querySelector('.dim').textContent = `${p.type}: ${JSON.stringify(p.value)}`;
      div.querySelector('.doc').textContent = p.doc || '';
      box.appendChild(div);
      continue;
    }
    if (p.type === 'boolean') {
      div.innerHTML = '<label><input type="checkbox"> <span class="name"></span></label><div class="doc"></div>';
      const cb = div.querySelector('input');
      cb.checked = !!(p.name in state.sets ? state.sets[p.name] : p.value);
      cb.dataset.param = p.name;
      div.querySelector('.name').textContent = p.name;
      div.querySelector('.doc').textContent = p.doc || '';
      cb.addEventListener('change', () => paramChanged(p.name, cb.checked ? 1 : 0, p.default ? 1 : 0));
      box.appendChild(div);
      continue;
    }
    const [lo, hi] = paramRange(p);
    const step = p.type === 'number' ? (hi - lo) / 200 : 1;
    const value = p.name in state.sets ? state.sets[p.name] : p.value;
    div.innerHTML = `<div><span class="name"></span> <span class="unit dim"></span></div>
      <input type="range"> <input type="number"><div class="doc"></div>`;
    div.querySelector('.name').textContent = p.name;
    div.querySelector('.unit').textContent = `${p.unit || ''} [${lo} … ${hi}] default ${p.default}`;
    div.querySelector('.doc').textContent = p.doc || '';
    const range = div.querySelector('input[type=range]'), num = div.querySelector('input[type=number]');
    for (const el of [range, num]) {
      el.min = lo; el.max = hi; el.step = step; el.value = value;
      el.dataset.param = p.name;
    }
    range.addEventListener('input', () => { lastInput = performance.now(); num.value = range.value; paramChanged(p.name, +range.value, p.default); });
    num.addEventListener('change', () => { range.value = num.value; paramChanged(p.name, +num.value, p.default); });
    box.appendChild(div);
  }
  // the step slider: an L-system's `derive`, a grow block's `years`
  const derive = state.params.find((p) => p.name === 'derive' || p.name === 'years');
  if (derive) { $('step').max = paramRange(derive)[1]; if (state.step === '') $('step').value = derive.value; }
}

async function loadParams() {
  const q = new URLSearchParams();
  if (state.model) q.set('model', state.model);
  const d = await getJSON('/api/describe?' + q);
  if (!d.models) return; // does not compile: the overlay says why
  const m = d.models.find((x) => x.name === state.model) || d.models[0];
  state.params = m ? m.params : [];
  buildParams();
}

function setLine() {
  return Object.entries(state.sets).map(([k, v]) => `--set ${k}=${v}`).join(' ') +
    (state.seed !== '' ? ` --seed ${state.seed}` : '') + (state.step !== '' ? ` -n ${state.step}` : '');
}

// The file's text with the moved parameters written into it: `param NAME = VALUE` and setting
// lines `NAME VALUE`. The user's file is not touched: this goes to a new file (save as…).
async function textWithSets() {
  let text = (await editedText()) ?? await fetch('/api/source').then((r) => r.text());
  for (const [k, v] of Object.entries(state.sets)) {
    const esc = k.replace(/[.*+?^${}()|[\]\\]/g, '\\$&');
    const asParam = new RegExp(`^(\\s*param\\s+${esc}\\s*=\\s*)([^#\\n]*?)(\\s*(#.*)?)$`, 'm');
    const asSetting = new RegExp(`^(\\s*${esc}\\s+)([^#\\n]*?)(\\s*(#.*)?)$`, 'm');
    if (asParam.test(text)) text = text.replace(asParam, `$1${v}$3`);
    else if (asSetting.test(text)) text = text.replace(asSetting, `$1${v}$3`);
  }
  return text;
}

async function saveAs() {
  const name = prompt('Save as a new file beside the model (a file name):', 'copy.syl');
  if (!name) return;
  const body = await textWithSets();
  let r = await fetch('/api/save?name=' + encodeURIComponent(name), { method: 'POST', body });
  if (r.status === 409 && confirm(`${name} exists. Overwrite it?`))
    r = await fetch('/api/save?overwrite=yes&name=' + encodeURIComponent(name), { method: 'POST', body });
  $('status').textContent = r.ok ? `saved ${name}` : `not saved: ${(await r.json()).error}`;
}

// ---- scenes: plants placed by clicks on the ground ----
// The file's text with a `plant MODEL at (x, y, z)` line for each placed plant: into its `scene`
// block, or a new one that also keeps the model at the origin. null: nothing placed.
async function editedText() {
  if (!state.placed.length) return null;
  const text = await fetch('/api/source').then((r) => r.text());
  const lines = state.placed.map((p) => `  plant ${p.model} at (${p.x}, ${p.y}, ${p.z})`).join('\n') + '\n';
  const m = /^scene\s*\{[^]*?\n\}/m.exec(text);
  if (m) {
    const end = m.index + m[0].length - 1; // the closing brace
    return text.slice(0, end) + lines + text.slice(end);
  }
  const first = state.placed[0].origin;
  return text + `\nscene {\n  plant ${first} at (0, 0, 0)\n${lines}}\n`;
}

function showPlaced() {
  $('placed').textContent = state.placed.map((p) => `plant ${p.model} at (${p.x}, ${p.y}, ${p.z})`).join('\n');
}

const pointer = { x: 0, y: 0 };
canvas.addEventListener('pointerdown', (e) => { pointer.x = e.clientX; pointer.y = e.clientY; });
canvas.addEventListener('pointerup', (e) => {
  if (!$('placing').checked || Math.hypot(e.clientX - pointer.x, e.clientY - pointer.y) > 4) return; // a drag orbits
  const r = canvas.getBoundingClientRect();
  const ndc = new THREE.Vector2((e.clientX - r.left) / r.width * 2 - 1, -((e.clientY - r.top) / r.height) * 2 + 1);
  const ray = new THREE.Raycaster();
  ray.setFromCamera(ndc, camera);
  // the nearest of the ground and the obstacles' surfaces under the pointer
  const hit = ray.intersectObjects([ground, ...pickables], false)[0];
  if (!hit) return;
  const round = (x) => +x.toFixed(2);
  const model = $('placemodel').value;
  const on = hit.object === ground ? 'ground' : hit.object.name || 'obstacle';
  state.placed.push({ model, origin: state.model || $('placemodel').options[0]?.value || model, on,
    x: round(hit.point.x), y: on === 'ground' ? 0 : round(hit.point.y), z: round(hit.point.z) });
  showPlaced();
  state.model = ''; $('model').value = ''; // the scene
  load();
});

function updateExports() {
  for (const f of ['glb', 'obj', 'csv']) $('exp-' + f).href = '/api/export?' + query({ format: f });
  $('exp-png').href = '/api/export?' + query({ format: 'png', size: $('pngsize').value });
}

// With placed plants the export is of the edited text: posted, and the answer saved as a file.
async function exportEdited(e) {
  const text = await editedText();
  if (text === null) return; // the link as it is
  e.preventDefault();
  const a = e.currentTarget;
  const r = await fetch(a.href, { method: 'POST', body: text });
  if (!r.ok) { showError((await r.json()).diag || 'the export failed'); return; }
  const url = URL.createObjectURL(await r.blob());
  const tmp = document.createElement('a');
  tmp.href = url; tmp.download = (r.headers.get('Content-Disposition') || '').replace(/.*filename="([^"]*)".*/, '$1') || 'export';
  tmp.click();
  setTimeout(() => URL.revokeObjectURL(url), 1000);
}

// ---- time ----
let playing = null;
function play() {
  if (playing) { clearInterval(playing); playing = null; $('play').textContent = 'play'; return; }
  $('play').textContent = 'stop';
  let k = 0;
  const max = +$('step').max;
  const next = async () => {
    state.step = String(k); $('step').value = k; $('stepval').textContent = k;
    await load();
    k = k >= max ? 0 : k + 1;
  };
  next();
  playing = setInterval(() => { if (!loading) next(); }, 400);
}

// ---- the file's models and its edits ----
async function loadModels() {
  const d = await getJSON('/api/models');
  $('file').textContent = d.file;
  const sel = $('model');
  sel.replaceChildren(new Option('(the file\'s first, or its scene)', ''), ...d.models.map((m) => new Option(m, m)));
  sel.value = state.model;
  const place = $('placemodel'), keep = place.value;
  place.replaceChildren(...d.models.map((m) => new Option(m, m)));
  if (keep) place.value = keep;
}

async function changed() {
  await load();           // the camera stays
  loadParams();
  loadModels();
}

// The stream's first event (hello, at each (re)connection) says the files' generation: a save
// that came before the stream was connected (or while it reconnected) has no change event of
// its own, so a build of an older generation than that is built again.
function listen() {
  const es = new EventSource('/api/events');
  es.addEventListener('hello', (e) => { if (+e.data !== state.builtGen) changed(); });
  es.addEventListener('change', () => {
    state.changeWall = Date.now(); // make bench: when the save's event came
    changed();
  });
}

// ---- controls ----
function wire() {
  document.querySelectorAll('#modes button').forEach((b) => b.addEventListener('click', () => setMode(b.dataset.mode)));
  for (const id of ['textures', 'lighting', 'shadows']) $(id).addEventListener('change', applyLook);
  $('wind').addEventListener('change', () => { state.wind = $('wind').checked; load(); });
  $('leaves').addEventListener('change', () => { state.leaves = $('leaves').value; load(); });
  $('lod').addEventListener('change', () => { state.lod = $('lod').value; load(); });
  $('forcelod').addEventListener('change', () => { state.forceLod = $('forcelod').value; applyLook(); });
  $('impostor').addEventListener('change', () => { state.impostor = $('impostor').checked; load(); });
  $('far').addEventListener('input', () => { state.far = +$('far').value; $('farval').textContent = `${state.far} diagonals`; });
  $('mapname').addEventListener('change', () => { $('map').src = `/api/map?factor=${encodeURIComponent($('mapname').value)}&gen=${state.gen}`; });
  $('chart').addEventListener('click', (e) => { // a click on the chart shows that year
    const r = $('chart').getBoundingClientRect(), s = state.stats;
    if (!notAPlant(s)) return;
    const maxYear = s.chart_years[s.chart_years.length - 1] || 1;
    const year = Math.round((e.clientX - r.left - 34) / (r.width - 38) * maxYear);
    state.step = String(Math.min(Math.max(year, 1), maxYear)); load();
  });
  $('frame').addEventListener('click', frame);
  $('reset').addEventListener('click', () => { camera.fov = 40; frame(); });
  $('model').addEventListener('change', async () => {
    state.model = $('model').value; state.sets = {}; state.step = '';
    await loadParams(); load(true);
  });
  $('seed').addEventListener('change', () => { state.seed = $('seed').value; load(); });
  $('newseed').addEventListener('click', () => {
    state.seed = String(Math.floor(Math.random() * 1e9)); $('seed').value = state.seed; load();
  });
  $('step').addEventListener('input', () => {
    lastInput = performance.now();
    if (state.step === $('step').value) return;
    state.step = $('step').value; $('stepval').textContent = state.step;
    load();
  });
  $('stepreset').addEventListener('click', () => { state.step = ''; $('stepval').textContent = 'the file\'s'; load(); });
  $('play').addEventListener('click', play);
  $('copyset').addEventListener('click', async () => {
    $('setline').value = setLine();
    try { await navigator.clipboard.writeText($('setline').value); } catch (e) { $('setline').select(); }
  });
  $('defaults').addEventListener('click', () => { state.sets = {}; buildParams(); $('setline').value = ''; load(); });
  $('saveas').addEventListener('click', saveAs);
  $('pngsize').addEventListener('change', updateExports);
  for (const f of ['glb', 'obj', 'csv', 'png']) $('exp-' + f).addEventListener('click', exportEdited);
  $('unplace').addEventListener('click', () => { state.placed = []; showPlaced(); load(); });
}

wire();
animate();
await loadModels();
await loadParams().catch(() => {});
await load(true);
listen();
