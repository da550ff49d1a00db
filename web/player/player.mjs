// meshvid's browser player: opens a .mvid (?src=URL, streamed by range requests so that it
// plays once its first group has arrived, or dropped on the page), plays it at the capture's
// frame rate with three.js, pauses, scrubs, steps, picks the level and orbits.
// The file is decoded in a worker (web/decoder/worker.mjs): while a frame is drawn, the next is
// decoded on another core. Within a key group the vertex buffer is updated in place; the index
// buffer is replaced only where a key group starts (one triangle array per key group and level).
// window.meshvidPlayer exposes the state and controls to tests.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { openMvidInWorker } from '/web/build/worker_client.mjs';

/** three.js's Draco decoder, which the decoder's worker loads. */
const DRACO_URL = new URL('/web/node_modules/three/examples/jsm/libs/draco/draco_decoder.js',
                          location.href).href;

const $ = (id) => document.getElementById(id);
const state = {
  ready: false,        // a frame is on screen
  error: null,         // the message shown when opening or decoding failed
  frame: 0, level: 0, keyGroup: -1, playing: false,
  framesShown: 0,      // frames decoded and shown since the file opened
  indexUploads: 0,     // index buffers made (one per key group and level visited)
  decodeMs: 0,         // total time in the decoder
  renders: 0,          // pictures drawn (one per display refresh)
  dropped: 0,          // frames skipped while playing, to keep up with the clock
  bytesFetched: 0,     // bytes of a streamed file received (as of the frame shown)
  firstFrameBytes: 0,  // bytes of a streamed file received when the first frame was shown
};

// --- the scene
const renderer = new THREE.WebGLRenderer({ antialias: false, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
$('view').appendChild(renderer.domElement);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0x20242a);
const camera = new THREE.PerspectiveCamera(35, 1, 0.001, 1000);
scene.add(camera);
scene.add(new THREE.HemisphereLight(0xffffff, 0x444450, 1.6));
const light = new THREE.DirectionalLight(0xffffff, 1.8);
light.position.set(0.5, 1, 1);
camera.add(light);  // lit from the viewer's side wherever the camera orbits
const controls = new OrbitControls(camera, renderer.domElement);
const geometry = new THREE.BufferGeometry();
const mesh = new THREE.Mesh(geometry, new THREE.MeshLambertMaterial({
  color: 0xc9ced6, side: THREE.DoubleSide }));
mesh.frustumCulled = false;
scene.add(mesh);

function resize() {
  const { clientWidth: width, clientHeight: height } = $('view');
  renderer.setSize(width, height);
  camera.aspect = width / Math.max(1, height);
  camera.updateProjectionMatrix();
}
window.addEventListener('resize', resize);
resize();

// --- the file
let file = null;
let triangles = null;  // the index array on the GPU (the decoder's, per key group and level)
let busy = null;       // the frame being decoded
let prefetch = null;   // { t, level, promise }: the next frame, asked for while playing
let clock = { start: 0, frame: 0 };

function showMessage(text, isError = false) {
  $('message').textContent = text;
  $('message').className = isError ? 'error' : '';
  $('message').style.display = text ? '' : 'none';
}

function fail(error) {
  state.error = `${error.message ?? error}`;
  state.playing = false;
  $('play').textContent = 'Play';
  showMessage(state.error, true);
}

function frameCamera() {
  geometry.computeBoundingSphere();
  const { center, radius } = geometry.boundingSphere;
  const distance = radius / Math.sin(THREE.MathUtils.degToRad(camera.fov / 2)) * 1.1;
  camera.position.copy(center).add(new THREE.Vector3(0, radius * 0.15, distance));
  camera.near = distance / 100;
  camera.far = distance * 10;
  camera.updateProjectionMatrix();
  controls.target.copy(center);
  controls.update();
}

/**
 * Aims the camera as `meshvid render --camera AZ,EL,ZOOM` does: from azimuth `azimuth` about +y
 * and elevation `elevation` (degrees), 40 degrees of view vertically, at the distance where the
 * frame's bounding sphere fits the picture (divided by `zoom`).
 */
function aimCamera(azimuth, elevation, zoom = 1) {
  geometry.computeBoundingBox();
  const box = geometry.boundingBox;
  const center = box.getCenter(new THREE.Vector3());
  const radius = Math.max(0.5 * box.getSize(new THREE.Vector3()).length(), 1e-6);
  const degrees = THREE.MathUtils.degToRad;
  const towardsEye = new THREE.Vector3(
    Math.cos(degrees(elevation)) * Math.sin(degrees(azimuth)), Math.sin(degrees(elevation)),
    Math.cos(degrees(elevation)) * Math.cos(degrees(azimuth)));
  camera.fov = 40;
  const tanHalf = Math.tan(degrees(camera.fov / 2)) * Math.min(1, camera.aspect);
  const distance = 1.02 * radius / Math.sin(Math.atan(tanHalf)) / zoom;
  camera.position.copy(center).addScaledVector(towardsEye, distance);
  camera.near = distance / 100;
  camera.far = distance * 10;
  camera.updateProjectionMatrix();
  controls.target.copy(center);
  controls.update();
}

/** Decodes frame t at the current level and puts it on screen. */
async function show(t) {
  const began = performance.now();
  const ready = prefetch?.t === t && prefetch.level === state.level ? prefetch.promise : null;
  prefetch = null;
  const decoded = await (ready ?? file.frame(t, state.level));
  state.decodeMs += performance.now() - began;
  if (state.playing) {
    // The next frame decodes in the worker while this one is drawn.
    const next = (t + 1) % file.frameCount;
    prefetch = { t: next, level: state.level, promise: file.frame(next, state.level) };
    prefetch.promise.catch(() => {});  // a failure surfaces when the frame is shown
  }
  if (decoded.triangles !== triangles) {
    // A new key group (or level): a new connectivity, so new buffers.
    triangles = decoded.triangles;
    geometry.setIndex(new THREE.BufferAttribute(triangles, 1));
    const positions = new THREE.BufferAttribute(new Float32Array(decoded.positions.length), 3);
    positions.setUsage(THREE.DynamicDrawUsage);
    geometry.setAttribute('position', positions);
    ++state.indexUploads;
  }
  const positions = geometry.getAttribute('position');
  positions.array.set(decoded.positions);
  positions.needsUpdate = true;
  geometry.computeVertexNormals();
  if (!state.ready) frameCamera();
  state.frame = t;
  state.keyGroup = decoded.keyGroup;
  state.bytesFetched = file.bytesFetched;
  if (!state.ready) state.firstFrameBytes = file.bytesFetched;
  state.ready = true;
  ++state.framesShown;
  $('seek').value = t;
  $('status').textContent = `frame ${t + 1} / ${file.frameCount} · key group ` +
    `${decoded.keyGroup + 1} / ${file.keyGroupCount} · ${decoded.positions.length / 3} vertices`;
}

/** Shows frame t once the frame being decoded is out (frames asked for meanwhile are
 * skipped, so playback keeps time when decoding is slower than the frame rate). */
function request(t) {
  if (busy) return busy;
  busy = show(t).catch(fail).finally(() => { busy = null; });
  return busy;
}

function setPlaying(playing) {
  state.playing = playing && file !== null && !state.error;
  $('play').textContent = state.playing ? 'Pause' : 'Play';
  clock = { start: performance.now(), frame: state.frame };
}

async function open(source, name) {
  try {
    showMessage(`Opening ${name}…`);
    file?.close();
    file = null;
    triangles = null;
    prefetch = null;
    Object.assign(state, { ready: false, error: null, frame: 0, keyGroup: -1, framesShown: 0,
                           indexUploads: 0, decodeMs: 0, dropped: 0, bytesFetched: 0,
                           firstFrameBytes: 0 });
    file = await openMvidInWorker(source, { dracoUrl: DRACO_URL });
    state.level = Math.min(1, file.levels);
    $('level').replaceChildren(...Array.from({ length: file.levels + 1 }, (_, level) => {
      const option = new Option(`${level}`, `${level}`);
      option.selected = level === state.level;
      return option;
    }));
    $('seek').max = file.frameCount - 1;
    document.title = `${name} · meshvid player`;
    showMessage('');
    await request(0);
    if (!state.error) setPlaying(true);
  } catch (error) {
    fail(error);
  }
}

/** Opens the file at `url`, streamed: it plays once its first group has arrived. */
function openUrl(url) {
  return open(url, url.split('/').pop());
}

// --- controls
$('play').onclick = () => setPlaying(!state.playing);
const step = (delta) => {
  if (!file) return;
  setPlaying(false);
  request((state.frame + delta + file.frameCount) % file.frameCount);
};
$('back').onclick = () => step(-1);
$('forward').onclick = () => step(1);
$('seek').oninput = () => {
  if (!file) return;
  setPlaying(false);
  request(Number($('seek').value));
};
$('level').onchange = () => {
  state.level = Number($('level').value);
  if (file) request(state.frame);
};
window.addEventListener('keydown', (event) => {
  if (event.target instanceof HTMLSelectElement) return;
  if (event.key === ' ') setPlaying(!state.playing);
  else if (event.key === 'ArrowLeft') step(-1);
  else if (event.key === 'ArrowRight') step(1);
  else return;
  event.preventDefault();
});
window.addEventListener('dragover', (event) => {
  event.preventDefault();
  document.body.classList.add('dragging');
});
window.addEventListener('dragleave', () => document.body.classList.remove('dragging'));
window.addEventListener('drop', async (event) => {
  event.preventDefault();
  document.body.classList.remove('dragging');
  const dropped = event.dataTransfer.files[0];
  if (dropped) await open(new Uint8Array(await dropped.arrayBuffer()), dropped.name);
});

function tick(now) {
  if (state.playing && file) {
    // rAF's time is its frame's start, which may precede the press of Play.
    const elapsed = Math.max(0, now - clock.start) / 1000;
    const target = (clock.frame + Math.floor(elapsed * file.frameRate)) % file.frameCount;
    if (target !== state.frame) {
      // A frame or two behind the clock, show the next frame (decoded ahead) rather than skip
      // to the clock's and wait for it; further behind, skip.
      const behind = (target - state.frame + file.frameCount) % file.frameCount;
      if (!busy) {
        const next = prefetch && behind <= 2 ? prefetch.t : target;
        state.dropped += (next - state.frame + file.frameCount) % file.frameCount - 1;
        request(next);
      }
    }
  }
  controls.update();
  renderer.render(scene, camera);
  ++state.renders;
  requestAnimationFrame(tick);
}
requestAnimationFrame(tick);

window.meshvidPlayer = {
  state,
  /** Shows frame t (paused); resolves when it is on screen. */
  seek: async (t) => {
    setPlaying(false);
    while (busy) await busy;
    await request(t);
  },
  setLevel: (level) => {
    state.level = level;
    $('level').value = `${level}`;
  },
  play: () => setPlaying(true),
  pause: () => setPlaying(false),
  /** Aims the camera as `meshvid render --camera AZ,EL,ZOOM` would at the frame shown. */
  aim: (azimuth, elevation, zoom = 1) => aimCamera(azimuth, elevation, zoom),
  /** The positions on screen (a copy). */
  positions: () => Array.from(geometry.getAttribute('position')?.array ?? []),
  frameCount: () => file?.frameCount ?? 0,
  frameRate: () => file?.frameRate ?? 0,
  levels: () => file?.levels ?? 0,
};

const src = new URLSearchParams(location.search).get('src');
if (src) openUrl(src);
