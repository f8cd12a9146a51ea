// The Python package's notebook view (docs/python.md, python/sylva/_view.py): a plant's .glb, a
// skeleton's lines or an ecosystem snapshot drawn in the scene of `sylva view` (scene.js),
// turned with the mouse. Everything it needs is inlined in the notebook's output.
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { createScene, skeletonFrom } from './scene.js';

const bytes = (b64) => Uint8Array.from(atob(b64), (c) => c.charCodeAt(0)).buffer;

// an ecosystem snapshot: the terrain as a height field, each plant a cone as tall as it is
function ecosystemFrom(d) {
  const group = new THREE.Group();
  const t = d.terrain;
  const geo = new THREE.PlaneGeometry((t.nx - 1) * t.cell, (t.nz - 1) * t.cell, t.nx - 1, t.nz - 1);
  geo.rotateX(-Math.PI / 2);
  const pos = geo.attributes.position;
  for (let k = 0; k < pos.count; k++) pos.setY(k, t.heights[k]);
  geo.translate(t.x0 + (t.nx - 1) * t.cell / 2, 0, t.z0 + (t.nz - 1) * t.cell / 2);
  geo.computeVertexNormals();
  const land = new THREE.Mesh(geo, new THREE.MeshStandardMaterial({ color: 0xa3a39a, roughness: 1 }));
  land.receiveShadow = true;
  group.add(land);
  const cone = new THREE.ConeGeometry(0.35, 1, 8).translate(0, 0.5, 0);
  const trees = new THREE.InstancedMesh(cone, new THREE.MeshStandardMaterial({ roughness: 0.8 }), Math.max(d.plants.length, 1));
  trees.castShadow = true;
  const m = new THREE.Matrix4(), col = new THREE.Color();
  d.plants.forEach(([x, y, z, h, s], i) => {
    m.makeScale(h, h, h).setPosition(x, y, z);
    trees.setMatrixAt(i, m);
    trees.setColorAt(i, col.setHex(d.colours[s % d.colours.length]));
  });
  trees.count = d.plants.length;
  group.add(trees);
  return group;
}

export async function show(el, d) {
  const canvas = el.querySelector('canvas');
  const view = createScene(canvas);
  let obj;
  if (d.glb) obj = (await new GLTFLoader().parseAsync(bytes(d.glb), '')).scene;
  else if (d.csv) obj = skeletonFrom(d.csv);
  else obj = ecosystemFrom(d);
  obj.traverse((o) => { if (o.isMesh) { o.castShadow = true; o.receiveShadow = true; } });
  view.scene.add(obj);
  if (d.terrain) view.ground.visible = false;
  view.placeGroundAndSun(obj);
  view.frame(obj);
  const draw = () => { view.resize(); view.renderer.render(view.scene, view.camera); };
  view.controls.addEventListener('change', draw);
  new ResizeObserver(draw).observe(canvas);
  draw();
  el.dataset.drawn = String((el.dataset.drawn | 0) + 1); // for the tests: it drew
}
