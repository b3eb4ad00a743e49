// jellysim's animation viewer: plays jellyfish.glb (morph-target animation) with three.js.
// Bundled with esbuild into dist/jellyfish-viewer.js (an IIFE exposing JellyfishViewer.start), so
// viewer.html works offline and from file:// (no ES module or fetch restrictions).
import * as THREE from "three";
import { GLTFLoader } from "three/examples/jsm/loaders/GLTFLoader.js";
import { OrbitControls } from "three/examples/jsm/controls/OrbitControls.js";

function decodeBase64(text) {
  const bytes = atob(text);
  const out = new Uint8Array(bytes.length);
  for (let i = 0; i < bytes.length; ++i) out[i] = bytes.charCodeAt(i);
  return out.buffer;
}

async function loadGlb(options) {
  if (options.glbBase64) return decodeBase64(options.glbBase64);
  const response = await fetch(options.glbUrl);
  if (!response.ok) throw new Error(`cannot load ${options.glbUrl}: ${response.status}`);
  return response.arrayBuffer();
}

function waterBackground() {
  const canvas = document.createElement("canvas");
  canvas.width = 2;
  canvas.height = 256;
  const g = canvas.getContext("2d");
  const gradient = g.createLinearGradient(0, 0, 0, 256);
  gradient.addColorStop(0, "#5aa6c0");
  gradient.addColorStop(1, "#03223a");
  g.fillStyle = gradient;
  g.fillRect(0, 0, 2, 256);
  const texture = new THREE.CanvasTexture(canvas);
  texture.colorSpace = THREE.SRGBColorSpace;
  return texture;
}

export async function start(options) {
  const renderer = new THREE.WebGLRenderer({ antialias: true });
  renderer.setPixelRatio(window.devicePixelRatio);
  renderer.setSize(window.innerWidth, window.innerHeight);
  document.body.appendChild(renderer.domElement);

  const scene = new THREE.Scene();
  scene.background = waterBackground();
  scene.add(new THREE.AmbientLight(0x9fc7d8, 0.8));
  const sun = new THREE.DirectionalLight(0xf2f8ff, 2.2);
  sun.position.set(0.2, 1.0, 0.6);
  scene.add(sun);
  const fill = new THREE.DirectionalLight(0x4f6f8f, 0.8);
  fill.position.set(-0.6, -0.3, 0.4);
  scene.add(fill);

  const camera = new THREE.PerspectiveCamera(40, window.innerWidth / window.innerHeight, 1e-4, 100);
  const controls = new OrbitControls(camera, renderer.domElement);

  const gltf = await new GLTFLoader().parseAsync(await loadGlb(options), "");
  const model = gltf.scene;
  model.traverse((o) => {
    if (o.isMesh) {
      o.material.depthWrite = !o.material.transparent;
      o.renderOrder = o.material.transparent ? 1 : 0;
    }
  });
  scene.add(model);

  // Frame the jellyfish (not the marine snow around them) in the first frame.
  const box = new THREE.Box3();
  model.traverse((o) => {
    if (o.isMesh && o.name.startsWith("jellyfish")) box.expandByObject(o);
  });
  if (box.isEmpty()) box.setFromObject(model);
  const size = box.getSize(new THREE.Vector3()).length();
  const centre = box.getCenter(new THREE.Vector3());
  camera.position.copy(centre).add(new THREE.Vector3(0.4, 0.25, 1.0).normalize().multiplyScalar(1.6 * size));
  camera.near = size / 100;
  camera.far = size * 100;
  camera.updateProjectionMatrix();
  controls.target.copy(centre);
  controls.update();

  // The .glb's morph targets move positions only (normals would double its size): recompute each
  // mesh's normals from its morphed positions whenever the morph weights change.
  const morphed = [];
  model.traverse((o) => {
    if (o.isMesh && o.morphTargetInfluences && o.geometry.morphAttributes.position) morphed.push(o);
  });
  const updateNormals = (mesh) => {
    const g = mesh.geometry;
    const base = g.attributes.position;
    const targets = g.morphAttributes.position;
    const w = mesh.morphTargetInfluences;
    const key = w.join(",");
    if (mesh.userData.normalsFor === key) return;
    mesh.userData.normalsFor = key;
    const n = base.count;
    // Scratch arrays kept with the mesh: this runs every frame.
    if (!mesh.userData.morphScratch) mesh.userData.morphScratch = [new Float32Array(3 * n), new Float32Array(3 * n)];
    const [p, acc] = mesh.userData.morphScratch;
    acc.fill(0);
    for (let v = 0; v < n; ++v) {
      p[3 * v] = base.getX(v);
      p[3 * v + 1] = base.getY(v);
      p[3 * v + 2] = base.getZ(v);
    }
    for (let k = 0; k < targets.length; ++k) {
      if (w[k] === 0) continue;
      const t = targets[k];
      for (let v = 0; v < n; ++v) {
        p[3 * v] += w[k] * t.getX(v);
        p[3 * v + 1] += w[k] * t.getY(v);
        p[3 * v + 2] += w[k] * t.getZ(v);
      }
    }
    const normal = g.attributes.normal;
    const index = g.index.array;
    for (let i = 0; i < index.length; i += 3) {
      const a = 3 * index[i], b = 3 * index[i + 1], c = 3 * index[i + 2];
      const ux = p[b] - p[a], uy = p[b + 1] - p[a + 1], uz = p[b + 2] - p[a + 2];
      const vx = p[c] - p[a], vy = p[c + 1] - p[a + 1], vz = p[c + 2] - p[a + 2];
      const nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
      for (const j of [a, b, c]) {
        acc[j] += nx;
        acc[j + 1] += ny;
        acc[j + 2] += nz;
      }
    }
    for (let v = 0; v < n; ++v) {
      const len = Math.hypot(acc[3 * v], acc[3 * v + 1], acc[3 * v + 2]) || 1;
      normal.setXYZ(v, acc[3 * v] / len, acc[3 * v + 1] / len, acc[3 * v + 2] / len);
    }
    normal.needsUpdate = true;
  };

  const mixer = new THREE.AnimationMixer(model);
  for (const clip of gltf.animations) mixer.clipAction(clip).play();
  const clock = new THREE.Clock();
  let paused = false;
  window.addEventListener("keydown", (e) => {
    if (e.code === "Space") paused = !paused;
  });
  window.addEventListener("resize", () => {
    camera.aspect = window.innerWidth / window.innerHeight;
    camera.updateProjectionMatrix();
    renderer.setSize(window.innerWidth, window.innerHeight);
  });
  renderer.setAnimationLoop(() => {
    const dt = clock.getDelta();
    if (!paused) mixer.update(dt);
    for (const mesh of morphed) updateNormals(mesh);
    controls.update();
    renderer.render(scene, camera);
  });
  window.jellysimViewerReady = true;
}
