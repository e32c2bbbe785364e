// Plays a VRM Animation (.vrma) on a VRM avatar with @pixiv/three-vrm and @pixiv/three-vrm-animation.
//
//   node vrma_check.mjs NODE_MODULES_DIR AVATAR.vrm ANIMATION.vrma '[t0, t1, ...]'
//
// NODE_MODULES_DIR holds three, @pixiv/three-vrm and @pixiv/three-vrm-animation
// (tests/browser/node_modules after `npm ci --prefix tests/browser`).
// Prints JSON: {metaVersion, duration, animations, warnings: [console.warn lines],
//               bones: {humanoid bone name: [per time: world position [x, y, z] of the avatar's raw bone]}}
import fs from "node:fs";
import path from "node:path";
import { pathToFileURL } from "node:url";

const [dir, avatarFile, vrmaFile, timesJson] = process.argv.slice(2);
const times = JSON.parse(timesJson || "[0]");
const warnings = [];
console.warn = (...args) => warnings.push(args.map(String).join(" "));

const load = (p) => import(pathToFileURL(path.join(dir, p)).href);
const THREE = await load("three/build/three.module.js");
const { GLTFLoader } = await load("three/examples/jsm/loaders/GLTFLoader.js");
const { VRMLoaderPlugin } = await load("@pixiv/three-vrm/lib/three-vrm.module.js");
const { VRMAnimationLoaderPlugin, createVRMAnimationClip } = await load(
  "@pixiv/three-vrm-animation/lib/three-vrm-animation.module.js");

function parse(file) {
  const bytes = fs.readFileSync(file);
  const ab = bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength);
  const loader = new GLTFLoader();
  loader.register((parser) => new VRMLoaderPlugin(parser));
  loader.register((parser) => new VRMAnimationLoaderPlugin(parser));
  return new Promise((resolve, reject) => loader.parse(ab, "", resolve, reject));
}

const avatar = await parse(avatarFile);
const vrm = avatar.userData.vrm;
if (!vrm) throw new Error(`${avatarFile}: three-vrm found no VRM in it`);
const anim = await parse(vrmaFile);
const vrmAnimations = anim.userData.vrmAnimations || [];
if (!vrmAnimations.length) throw new Error(`${vrmaFile}: three-vrm-animation found no VRM animation in it`);

const clip = createVRMAnimationClip(vrmAnimations[0], vrm);
const mixer = new THREE.AnimationMixer(vrm.scene);
const action = mixer.clipAction(clip);
action.setLoop(THREE.LoopOnce);
action.clampWhenFinished = true;
action.play();

const names = Object.keys(vrm.humanoid.humanBones);
const bones = Object.fromEntries(names.map((n) => [n, []]));
let last = 0;
for (const t of times) {
  mixer.update(t - last); // advances the clip's time as a player's frame loop does
  last = t;
  vrm.update(0); // normalized bones -> raw bones
  vrm.scene.updateMatrixWorld(true);
  for (const n of names) {
    const node = vrm.humanoid.getRawBoneNode(n);
    bones[n].push(node.getWorldPosition(new THREE.Vector3()).toArray());
  }
}
process.stdout.write(JSON.stringify({
  metaVersion: vrm.meta.metaVersion, duration: clip.duration, animations: vrmAnimations.length, warnings, bones,
}));
