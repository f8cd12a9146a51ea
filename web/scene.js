// The three.js scene of `sylva view` (app.js) and of the Python package's notebook view
// (python/sylva/_view.py): renderer, camera and orbit controls, sky light, sun with shadows and a
// ground disc; framing, the ground and sun fitted to what is drawn, and the skeleton as lines.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

// opts.shadowsOnDemand: the shadow map is drawn when the caller sets
// renderer.shadowMap.needsUpdate (sylva view draws frames only when something changed).
// opts.antialias false: a canvas without multisampling (sylva view multisamples its full frames
// itself and draws a preview's straight onto it).
export function createScene(canvas, opts = {}) {
  const renderer = new THREE.WebGLRenderer({ canvas, antialias: opts.antialias ?? true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2));
  renderer.shadowMap.enabled = true;
  renderer.shadowMap.type = THREE.PCFSoftShadowMap;
  if (opts.shadowsOnDemand) renderer.shadowMap.autoUpdate = false;
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xdce6ef);
  const camera = new THREE.PerspectiveCamera(40, 1, 0.01, 5000);
  camera.position.set(6, 4, 8);
  const controls = new OrbitControls(camera, canvas);
  controls.enableDamping = false;
  const hemi = new THREE.HemisphereLight(0xeef4ff, 0x8a8070, 1.2);
  scene.add(hemi);
  const sun = new THREE.DirectionalLight(0xffffff, 2.2);
  sun.castShadow = true;
  sun.shadow.mapSize.set(1024, 1024);
  scene.add(sun, sun.target);
  // Lambert, not the physically based material: a matt ground looks the same, and its pixels —
  // a good part of the frame — cost 40 % less to shade in software WebGL (measured: 41 against
  // 66 ms a frame for the ground alone at 900 × 700 with shadows)
  const ground = new THREE.Mesh(new THREE.CircleGeometry(1, 64), new THREE.MeshLambertMaterial({ color: 0xa3a39a }));
  ground.rotation.x = -Math.PI / 2;
  ground.receiveShadow = true;
  scene.add(ground);

  const bounds = (obj) => new THREE.Box3().setFromObject(obj);

  // the camera looks at all of obj from the side and above
  function frame(obj) {
    const box = bounds(obj);
    const size = box.getSize(new THREE.Vector3()), centre = box.getCenter(new THREE.Vector3());
    const r = Math.max(size.length() / 2, 1e-3);
    const dist = r / Math.sin(THREE.MathUtils.degToRad(camera.fov / 2)) * 1.05;
    controls.target.copy(centre);
    camera.position.copy(centre).add(new THREE.Vector3(0.55, 0.35, 0.76).normalize().multiplyScalar(dist));
    camera.near = dist / 200; camera.far = dist * 50;
    camera.updateProjectionMatrix();
    controls.update();
  }

  function placeGroundAndSun(obj) {
    const box = bounds(obj);
    const size = box.getSize(new THREE.Vector3()), centre = box.getCenter(new THREE.Vector3());
    const r = Math.max(size.length() / 2, 1e-3);
    ground.position.set(centre.x, box.min.y - r * 0.002, centre.z);
    ground.scale.setScalar(r * 4);
    sun.position.set(centre.x + r * 1.5, centre.y + r * 3, centre.z + r * 1.0);
    sun.target.position.copy(centre);
    const cam = sun.shadow.camera;
    cam.left = cam.bottom = -r * 1.5; cam.right = cam.top = r * 1.5;
    cam.near = r * 0.1; cam.far = r * 8;
    cam.updateProjectionMatrix();
  }

  function resize() {
    const w = canvas.clientWidth, h = canvas.clientHeight;
    if (canvas.width !== Math.floor(w * renderer.getPixelRatio()) || canvas.height !== Math.floor(h * renderer.getPixelRatio())) {
      renderer.setSize(w, h, false);
      camera.aspect = w / Math.max(h, 1);
      camera.updateProjectionMatrix();
      return true;
    }
    return false;
  }

  return { renderer, scene, camera, controls, hemi, sun, ground, bounds, frame, placeGroundAndSun, resize };
}

// the skeleton's colours by branch order: trunk brown, then red, orange, green, blue, …
export const ORDER_COLOURS = [0x5a3a1a, 0xc0392b, 0xe67e22, 0x27ae60, 0x2980b9, 0x8e44ad, 0x16a085, 0x7f8c8d];

export function skeletonFrom(csv) {
  // id,parent,x,y,z,radius,order,kind (sylva skeleton's CSV): a segment from each node's parent
  const rows = csv.trim().split('\n').slice(1).map((l) => l.split(','));
  const pos = new Map();
  for (const r of rows) if (r[7] === 'internode' || r[7] === 'root') pos.set(r[0], [+r[2], +r[3], +r[4]]);
  const p = [], o = [];
  for (const r of rows) {
    if (r[7] !== 'internode' || !pos.has(r[1])) continue;
    p.push(...pos.get(r[1]), +r[2], +r[3], +r[4]);
    o.push(Math.min(+r[6], 255));
  }
  const j = joinStraight(new Float32Array(p), new Uint8Array(o)); // straight runs: one line each
  const c = new Float32Array(j.n * 6), col = new THREE.Color();
  for (let i = 0; i < j.n; i++) {
    col.setHex(ORDER_COLOURS[Math.min(j.order[i], ORDER_COLOURS.length - 1)]);
    c.set([col.r, col.g, col.b, col.r, col.g, col.b], i * 6);
  }
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(j.pos, 3));
  g.setAttribute('color', new THREE.BufferAttribute(c, 3));
  return new THREE.LineSegments(g, new THREE.LineBasicMaterial({ vertexColors: true }));
}

// Segments (6 floats each: from, to) with their branch orders, each segment that goes on
// straight from the one kept before it (it starts where that one ends, in the same direction,
// of the same order) joined to it: the same picture in fewer lines. An L-system's F → FF
// makes long straight runs (Fig. 1.24(e) at n = 9: 38,342 segments, 9,841 lines), and software
// WebGL spends a frame's time on each line. Returns {pos, order, n}.
export function joinStraight(pos, order) {
  const n = order.length, out = new Float32Array(n * 6), oo = new Uint8Array(n);
  let kept = 0;
  for (let i = 0, a = 0; i < n; i++, a += 6) {
    if (kept > 0 && oo[kept - 1] === order[i]) {
      const b = (kept - 1) * 6, ex = out[b + 3], ey = out[b + 4], ez = out[b + 5];
      if (pos[a] === ex && pos[a + 1] === ey && pos[a + 2] === ez) {
        const ux = ex - out[b], uy = ey - out[b + 1], uz = ez - out[b + 2];
        const vx = pos[a + 3] - ex, vy = pos[a + 4] - ey, vz = pos[a + 5] - ez;
        const cx = uy * vz - uz * vy, cy = uz * vx - ux * vz, cz = ux * vy - uy * vx;
        // parallel within float noise (sin² of the angle below 1e-8), and onward, not back
        if (ux * vx + uy * vy + uz * vz > 0 &&
            cx * cx + cy * cy + cz * cz <= 1e-8 * (ux * ux + uy * uy + uz * uz) * (vx * vx + vy * vy + vz * vz)) {
          out[b + 3] = pos[a + 3]; out[b + 4] = pos[a + 4]; out[b + 5] = pos[a + 5];
          continue;
        }
      }
    }
    const k = kept * 6;
    for (let j = 0; j < 6; j++) out[k + j] = pos[a + j];
    oo[kept++] = order[i];
  }
  return { pos: out.subarray(0, kept * 6), order: oo.subarray(0, kept), n: kept };
}
