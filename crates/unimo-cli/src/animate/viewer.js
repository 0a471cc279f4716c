// unimo animate: the viewer. Reads the scene (#unimo-data), builds one three.js mesh
// per body from its shape and dimensions, and plays the frames: play/pause, scrub,
// speed, the current time. `#t=1.5` in the address opens paused at that time.
// window.unimoScene exposes the state (also written to #unimo-state as JSON), so a
// test can read what is drawn.
const data = JSON.parse(document.getElementById("unimo-data").textContent);
const canvas = document.getElementById("view");
const times = data.times;
const last = times.length - 1;
const palette = [0x3f7fbf, 0xd9822b, 0x4c9f50, 0xc2413b, 0x8a63b8, 0x8c6d46, 0xd474b6, 0x7f7f7f];

const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(1);
const background = new THREE.Color(0xf4f5f7);
renderer.setClearColor(background);
const scene = new THREE.Scene();
const up = new THREE.Vector3(0, 0, 0).setComponent(data.up, 1);
scene.add(new THREE.HemisphereLight(0xffffff, 0x666677, 1.6));
const sun = new THREE.DirectionalLight(0xffffff, 1.8);
scene.add(sun);

// The largest distance of a body's points from its origin.
function extent(b) {
  const [a, c, d] = b.size;
  switch (b.shape) {
    case "sphere": return a;
    case "ellipsoid": return Math.max(a, c, d);
    case "box": return Math.hypot(a, c, d) / 2;
    case "capsule": return a + c / 2;
    default: return Math.hypot(a, c / 2); // cylinder, cone
  }
}

// The region the bodies sweep (planes excluded): centre and radius for the camera.
const box = new THREE.Box3();
for (const b of data.bodies) {
  if (b.shape === "plane") continue;
  const reach = extent(b);
  for (let k = 0; k + 2 < b.p.length; k += 3) {
    const p = new THREE.Vector3(b.p[k], b.p[k + 1], b.p[k + 2]);
    box.expandByPoint(p.clone().addScalar(reach));
    box.expandByPoint(p.clone().addScalar(-reach));
  }
}
if (box.isEmpty()) box.set(new THREE.Vector3(-1, -1, -1), new THREE.Vector3(1, 1, 1));
const centre = box.getCenter(new THREE.Vector3());
const radius = Math.max(box.getSize(new THREE.Vector3()).length() / 2, 1e-3);

function geometry(b) {
  const [a, c, d] = b.size;
  switch (b.shape) {
    case "sphere": return new THREE.SphereGeometry(a, 48, 24);
    case "ellipsoid": return new THREE.SphereGeometry(1, 48, 24).scale(a, c, d);
    case "box": return new THREE.BoxGeometry(a, c, d);
    case "capsule": return new THREE.CapsuleGeometry(a, c, 12, 32);
    case "cylinder": return new THREE.CylinderGeometry(a, a, c, 48);
    case "cone": return new THREE.ConeGeometry(a, c, 48);
    default: throw new Error("unknown shape " + b.shape);
  }
}

// A plane: a square in the body frame with the given normal, around the scene's
// centre projected onto it, with a grid.
function plane(b) {
  const group = new THREE.Group();
  const size = 4 * radius;
  const surface = new THREE.Mesh(
    new THREE.PlaneGeometry(size, size),
    new THREE.MeshStandardMaterial({ color: b.color || 0xd8dce3, side: THREE.DoubleSide, roughness: 0.9 })
  );
  const grid = new THREE.GridHelper(size, 20, 0x99a0ad, 0xb8bec9);
  grid.rotation.x = Math.PI / 2; // GridHelper lies in x-z; the square lies in x-y
  grid.position.z = 1e-4 * size;
  const inner = new THREE.Group();
  inner.add(surface, grid);
  inner.quaternion.setFromUnitVectors(new THREE.Vector3(0, 0, 1), new THREE.Vector3(...b.normal));
  group.add(inner);
  group.userData.inner = inner;
  return group;
}

const objects = data.bodies.map((b, k) => {
  let object;
  if (b.shape === "plane") {
    object = plane(b);
  } else {
    const color = b.color ? new THREE.Color(b.color) : new THREE.Color(palette[k % palette.length]);
    object = new THREE.Mesh(geometry(b), new THREE.MeshStandardMaterial({ color, roughness: 0.55, metalness: 0.05 }));
    // A moving body's axes, so that a spinning symmetric body shows its rotation.
    if (b.p.length > 3) object.add(new THREE.AxesHelper(1.3 * extent(b)));
  }
  object.name = b.name;
  scene.add(object);
  return object;
});

// The camera looks at the centre from a direction tilted off the up axis; drag turns
// it, the wheel zooms.
const camera = new THREE.PerspectiveCamera(40, 1, radius / 100, radius * 100);
camera.up.copy(up);
let azimuth = 0.8, elevation = 0.45, distance = 2.6 * radius;
function placeCamera() {
  const side = new THREE.Vector3(1, 0, 0);
  if (Math.abs(side.dot(up)) > 0.9) side.set(0, 1, 0);
  const other = new THREE.Vector3().crossVectors(up, side);
  const dir = side.clone().multiplyScalar(Math.cos(elevation) * Math.cos(azimuth))
    .addScaledVector(other, Math.cos(elevation) * Math.sin(azimuth))
    .addScaledVector(up, Math.sin(elevation));
  camera.position.copy(centre).addScaledVector(dir, distance);
  camera.lookAt(centre);
  sun.position.copy(camera.position).addScaledVector(up, distance);
}
let dragging = null;
canvas.addEventListener("pointerdown", (e) => { dragging = [e.clientX, e.clientY]; });
window.addEventListener("pointerup", () => { dragging = null; });
window.addEventListener("pointermove", (e) => {
  if (!dragging) return;
  azimuth -= (e.clientX - dragging[0]) * 0.01;
  elevation = Math.min(1.5, Math.max(-1.5, elevation + (e.clientY - dragging[1]) * 0.01));
  dragging = [e.clientX, e.clientY];
  draw();
});
canvas.addEventListener("wheel", (e) => {
  e.preventDefault();
  distance *= Math.exp(e.deltaY * 0.001);
  draw();
}, { passive: false });

// Playback: `now` is the clock value shown; the frame drawn is the last at or before it.
const play = document.getElementById("play");
const scrub = document.getElementById("scrub");
const speed = document.getElementById("speed");
const clock = document.getElementById("clock");
const t0 = times[0], t1 = times[last];
let now = t0, playing = false, lastTick = null;
function frameAt(t) {
  let lo = 0, hi = last;
  while (lo < hi) {
    const mid = (lo + hi + 1) >> 1;
    if (times[mid] <= t) lo = mid; else hi = mid - 1;
  }
  return lo;
}
function place(frame) {
  data.bodies.forEach((b, k) => {
    const f = Math.min(frame, b.p.length / 3 - 1);
    objects[k].position.set(b.p[3 * f], b.p[3 * f + 1], b.p[3 * f + 2]);
    objects[k].quaternion.set(b.q[4 * f], b.q[4 * f + 1], b.q[4 * f + 2], b.q[4 * f + 3]);
  });
  if (data.bodies.some((b) => b.shape === "plane")) {
    // keep each plane's square under the scene: shift it within its own plane
    data.bodies.forEach((b, k) => {
      if (b.shape !== "plane") return;
      const o = objects[k];
      o.updateMatrixWorld();
      const n = new THREE.Vector3(...b.normal).applyQuaternion(o.quaternion);
      const offset = centre.clone().sub(o.position);
      offset.addScaledVector(n, -offset.dot(n));
      o.userData.inner.position.copy(offset.applyQuaternion(o.quaternion.clone().invert()));
    });
  }
}
function resize() {
  const w = canvas.clientWidth, h = canvas.clientHeight;
  if (canvas.width !== w || canvas.height !== h) renderer.setSize(w, h, false);
  camera.aspect = w / Math.max(h, 1);
  camera.updateProjectionMatrix();
}
function draw() {
  const frame = frameAt(now);
  place(frame);
  resize();
  placeCamera();
  renderer.render(scene, camera);
  clock.textContent = data.clock + " = " + now.toFixed(3) + " / " + t1.toFixed(3);
  scrub.value = String(Math.round(1000 * (t1 > t0 ? (now - t0) / (t1 - t0) : 0)));
  expose(frame);
}
function tick(stamp) {
  if (playing) {
    if (lastTick !== null) now += ((stamp - lastTick) / 1000) * Number(speed.value);
    lastTick = stamp;
    if (now >= t1) { now = t1; setPlaying(false); }
    draw();
  }
  requestAnimationFrame(tick);
}
function setPlaying(on) {
  playing = on;
  lastTick = null;
  play.textContent = on ? "Pause" : "Play";
  if (on && now >= t1) now = t0;
}
play.addEventListener("click", () => setPlaying(!playing));
scrub.addEventListener("input", () => { now = t0 + (t1 - t0) * Number(scrub.value) / 1000; draw(); });
window.addEventListener("keydown", (e) => { if (e.code === "Space") { e.preventDefault(); setPlaying(!playing); } });
window.addEventListener("resize", draw);

// What a test reads: the time and frame drawn, each body's placement, and a summary of
// the pixels drawn (how many differ from the background, and a checksum).
function pixels() {
  const gl = renderer.getContext();
  const w = gl.drawingBufferWidth, h = gl.drawingBufferHeight;
  const buffer = new Uint8Array(w * h * 4);
  gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, buffer);
  const bg = [background.r, background.g, background.b].map((c) => Math.round(255 * c));
  let drawn = 0, sum = 0;
  for (let i = 0; i < buffer.length; i += 4) {
    if (Math.abs(buffer[i] - bg[0]) + Math.abs(buffer[i + 1] - bg[1]) + Math.abs(buffer[i + 2] - bg[2]) > 6) drawn++;
    sum = (sum * 31 + buffer[i] + 7 * buffer[i + 1] + 13 * buffer[i + 2]) % 1000000007;
  }
  return { width: w, height: h, drawn, checksum: sum };
}
function expose(frame) {
  const state = {
    ready: true,
    time: now,
    frame,
    frames: times.length,
    errors: window.unimoErrors,
    bodies: data.bodies.map((b, k) => ({
      name: b.name,
      shape: b.shape,
      position: objects[k].position.toArray(),
      quaternion: objects[k].quaternion.toArray(),
    })),
    pixels: playing ? null : pixels(),
  };
  window.unimoScene = state;
  document.getElementById("unimo-state").textContent = JSON.stringify(state);
}

const hash = new URLSearchParams(location.hash.slice(1));
if (hash.has("t")) now = Math.min(t1, Math.max(t0, Number(hash.get("t"))));
if (hash.has("play")) setPlaying(true);
draw();
requestAnimationFrame(tick);
