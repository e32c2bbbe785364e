// Loads a .glb with three.js' GLTFLoader and runs the Khronos glTF validator on it.
//
//   node gltf_check.mjs NODE_MODULES_DIR FILE.glb '[t0, t1, ...]'
//
// NODE_MODULES_DIR holds the npm packages `three` and `gltf-validator`
// (tests/browser/node_modules after `npm ci --prefix tests/browser`; either may be missing).
// Prints JSON: {validator: {errors, warnings, infos, hints, messages} | null,
//               three: {actors: [{name, bones: [names], frames: [per time: [[x,y,z] per bone]],
//                        vertex: [per time: world position of vertex 0]}],
//                       props: [{name, shape, mesh, frames: [per time: [x,y,z]]}], animations, duration} | null}
import fs from "node:fs";
import path from "node:path";
import { createRequire } from "node:module";
import { pathToFileURL } from "node:url";

const [dir, file, timesJson] = process.argv.slice(2);
const times = JSON.parse(timesJson || "[0]");
const bytes = fs.readFileSync(file);
const out = { validator: null, three: null };

const require = createRequire(path.join(dir, "noop.js"));

if (fs.existsSync(path.join(dir, "gltf-validator"))) {
  const validator = require("gltf-validator");
  const report = await validator.validateBytes(new Uint8Array(bytes), { maxIssues: 100 });
  out.validator = { ...report.issues, messages: report.issues.messages.map((m) => `${m.code}: ${m.message} (${m.pointer || ""})`) };
}

const threeDir = path.join(dir, "three");
if (fs.existsSync(threeDir)) {
  const THREE = await import(pathToFileURL(path.join(threeDir, "build", "three.module.js")).href);
  const { GLTFLoader } = await import(pathToFileURL(path.join(threeDir, "examples", "jsm", "loaders", "GLTFLoader.js")).href);
  const ab = bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength);
  const gltf = await new Promise((resolve, reject) => new GLTFLoader().parse(ab, "", resolve, reject));
  const scene = gltf.scene;
  const meshes = [];
  scene.traverse((o) => { if (o.isSkinnedMesh) meshes.push(o); });
  const mixer = new THREE.AnimationMixer(scene);
  // played once and held at its end, so t = duration is the last key frame (a looping action wraps to 0)
  const action = mixer.clipAction(gltf.animations[0]);
  action.setLoop(THREE.LoopOnce);
  action.clampWhenFinished = true;
  action.play();
  const actors = meshes.map((m) => ({ name: m.name, bones: m.skeleton.bones.map((b) => b.name), frames: [], vertex: [] }));
  // the things of the scene: nodes whose extras name a prop shape
  const things = [];
  scene.traverse((o) => { if (o.userData && o.userData.prop) things.push(o); });
  const props = things.map((o) => ({ name: o.name, shape: o.userData.prop, mesh: !!o.isMesh, frames: [] }));
  for (const t of times) {
    mixer.setTime(t);
    scene.updateMatrixWorld(true);
    things.forEach((o, i) => props[i].frames.push(o.getWorldPosition(new THREE.Vector3()).toArray()));
    meshes.forEach((m, i) => {
      m.skeleton.update();
      actors[i].frames.push(m.skeleton.bones.map((b) => b.getWorldPosition(new THREE.Vector3()).toArray()));
      const v = new THREE.Vector3().fromBufferAttribute(m.geometry.attributes.position, 0);
      m.applyBoneTransform(0, v);
      actors[i].vertex.push(v.toArray());
    });
  }
  out.three = { actors, props, animations: gltf.animations.length, duration: gltf.animations[0].duration };
}
process.stdout.write(JSON.stringify(out));
