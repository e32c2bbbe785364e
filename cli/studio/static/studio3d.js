/* text2anim studio: the user's character drawn skinned (three.js, vendored in /static/vendor/three/),
 * playing the GLB the studio exports for it, on a floor with a grid and shadows; orbit and zoom with the
 * mouse. The things of the scene are in the same file (nodes whose extras name a prop shape: meshes moved by
 * the same animation), each labelled with its name. State for tests: window.__studio3d (ready, time, duration,
 * playing, props: the things' names). */
import * as THREE from "three";
import { GLTFLoader } from "/static/vendor/three/examples/jsm/loaders/GLTFLoader.js";
import { OrbitControls } from "/static/vendor/three/examples/jsm/controls/OrbitControls.js";

const box = document.getElementById("view3d");
const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
renderer.shadowMap.enabled = true;
renderer.setPixelRatio(window.devicePixelRatio || 1);
box.appendChild(renderer.domElement);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0x14161b);
const camera = new THREE.PerspectiveCamera(40, 1, 0.01, 1000);
const controls = new OrbitControls(camera, renderer.domElement);
scene.add(new THREE.HemisphereLight(0xdde6ff, 0x30343c, 1.4));
const sun = new THREE.DirectionalLight(0xffffff, 2.2);
sun.castShadow = true;
sun.shadow.mapSize.set(2048, 2048);
scene.add(sun, sun.target);
const floor = new THREE.Mesh(new THREE.PlaneGeometry(1, 1), new THREE.MeshStandardMaterial({ color: 0x22262e }));
floor.rotation.x = -Math.PI / 2;
floor.receiveShadow = true;
scene.add(floor);
let grid = null, model = null, mixer = null, action = null, things = [];
const timer = new THREE.Timer();
const S = { ready: false, time: 0, duration: 0, playing: true, loads: 0, props: [] };
window.__studio3d = S;

function resize() {
  const w = box.clientWidth || 800, h = box.clientHeight || 480;
  renderer.setSize(w, h, false);
  camera.aspect = w / h;
  camera.updateProjectionMatrix();
}

let bones = [], hips = null;

function boneBounds() {
  // the skeleton as it stands now (a skinned mesh's own box is its bind pose, wherever the bones went)
  const bounds = new THREE.Box3(), p = new THREE.Vector3();
  model.updateMatrixWorld(true);
  bones.forEach((b) => bounds.expandByPoint(b.getWorldPosition(p)));
  return bounds;
}

function frame(object) {
  // floor, grid, light and camera sized to the character (0.2 m or 20 m tall alike)
  const bounds = boneBounds(), size = new THREE.Vector3(), mid = new THREE.Vector3();
  bounds.getSize(size); bounds.getCenter(mid);
  const h = Math.max(size.y, 1e-3), span = h * 8;
  floor.scale.set(span, span, 1);
  if (grid) scene.remove(grid);
  grid = new THREE.GridHelper(span, 16, 0x4a5060, 0x30343c);
  grid.position.y = 1e-4 * h;
  scene.add(grid);
  sun.position.set(mid.x + h * 2, h * 4, mid.z + h * 3);
  sun.target.position.copy(mid);
  const cam = sun.shadow.camera;
  cam.left = cam.bottom = -span / 2; cam.right = cam.top = span / 2; cam.near = h * 0.1; cam.far = h * 20;
  cam.updateProjectionMatrix();
  camera.near = h * 0.01; camera.far = h * 200;
  camera.position.set(mid.x + h * 1.2, mid.y + h * 0.4, mid.z + h * 3.2);
  controls.target.copy(mid);
  controls.update();
}

export function show(buffer, at) {
  return new Promise((resolve, reject) => {
    new GLTFLoader().parse(buffer, "", (gltf) => {
      if (model) scene.remove(model);
      model = gltf.scene;
      bones = [];
      things.forEach((t) => t.label.remove());
      things = [];
      model.traverse((o) => {
        if (o.isMesh) { o.castShadow = true; o.frustumCulled = false; }
        if (o.isBone) bones.push(o);
        if (o.userData && o.userData.prop) {
          const g = o.geometry;
          if (g) g.computeBoundingSphere();
          things.push({ node: o, label: label(o.name), up: (g ? g.boundingSphere.radius : 0.2) + 0.05 });
        }
      });
      S.props = things.map((t) => t.node.name);
      hips = bones[0] || null;
      scene.add(model);
      mixer = new THREE.AnimationMixer(model);
      const clip = gltf.animations[0];
      S.duration = clip ? clip.duration : 0;
      action = clip ? mixer.clipAction(clip) : null;
      if (action) action.play();
      mixer.setTime(Math.min(at || 0, S.duration));
      resize();
      frame(model);
      S.ready = true; S.loads += 1;
      resolve(S);
    }, reject);
  });
}

function label(text) {
  const div = document.createElement("div");
  div.className = "label3d";
  div.textContent = text;
  box.appendChild(div);
  return div;
}

function placeLabels() {
  // each thing's name just above it, where the camera sees it
  const w = box.clientWidth, h = box.clientHeight, p = new THREE.Vector3();
  things.forEach((t) => {
    t.node.getWorldPosition(p);
    p.y += t.up;
    p.project(camera);
    const seen = p.z < 1 && Math.abs(p.x) <= 1 && Math.abs(p.y) <= 1;
    t.label.style.display = seen ? "block" : "none";
    t.label.style.left = ((p.x + 1) / 2 * w) + "px";
    t.label.style.top = ((1 - p.y) / 2 * h) + "px";
  });
}

export function seek(t) { if (mixer) mixer.setTime(t); }

function tick() {
  timer.update();
  if (box.hidden) { requestAnimationFrame(tick); return; }  // the viewer page is shown: nothing to draw here
  const dt = timer.getDelta();
  if (mixer && S.playing) { mixer.update(dt); }
  if (mixer) S.time = action ? action.time : 0;
  if (hips) {  // follow the character as it travels, as the viewer does
    const p = hips.getWorldPosition(new THREE.Vector3()), d = p.clone().sub(controls.target);
    d.y = 0;
    controls.target.add(d); camera.position.add(d);
  }
  controls.update();
  renderer.render(scene, camera);
  placeLabels();
  requestAnimationFrame(tick);
}
window.addEventListener("resize", resize);
resize();
tick();
window.__studio3dApi = { show, seek };
