// The growth studio's page (docs/studio.md): the option panel from `dla3d options`, a mesh to
// paint seeds on, and the particles of a run drawn as its frames arrive on the session's
// WebSocket (the `--stream` format: "DLAs", u32 count, u64 first, done, total, then float32
// positions and int32 parents). Bundled with three.js by esbuild at build time: no CDN.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { STLLoader } from 'three/addons/loaders/STLLoader.js';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { mergeVertices } from 'three/addons/utils/BufferGeometryUtils.js';

const token = window.STUDIO_TOKEN;
const $ = (id) => document.getElementById(id);
const api = (path, query = {}) => {
  const q = new URLSearchParams({ token, ...query });
  return `${path}?${q}`;
};
const PAINT = { seeds: [255, 0, 0], attractors: [0, 255, 0], bare: [0, 0, 255], erase: [255, 255, 255] };

// -- the view ----------------------------------------------------------------------------------
const view = $('view');
const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
view.appendChild(renderer.domElement);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0x111111);
scene.add(new THREE.HemisphereLight(0xffffff, 0x444444, 2.0));
const sun = new THREE.DirectionalLight(0xffffff, 1.5);
sun.position.set(1, 2, 3);
scene.add(sun);
const camera = new THREE.PerspectiveCamera(40, 1, 0.01, 1000);
const controls = new OrbitControls(camera, renderer.domElement);

function resize() {
  const w = view.clientWidth, h = view.clientHeight;
  renderer.setSize(w, h);
  camera.aspect = w / Math.max(1, h);
  camera.updateProjectionMatrix();
}
window.addEventListener('resize', resize);

//! Looks at `center` from 2.8 radii away; `up`, a unit axis, is up in the view (a mesh's longest
//! side, as the POV-Ray scene's --up), and the view is from the front, along the next axis.
function frame(center, radius, up = new THREE.Vector3(0, 1, 0)) {
  const r = Math.max(radius, 1e-6);
  camera.near = r / 100;
  camera.far = r * 100;
  camera.up.copy(up);
  const front = up.z !== 0 ? new THREE.Vector3(0, -1, 0) : new THREE.Vector3(0, 0, 1);
  camera.position.copy(center).addScaledVector(front, r * 2.8);
  controls.target.copy(center);
  camera.updateProjectionMatrix();
  controls.update();
}

// The particles: one buffer, grown by doubling, drawn up to the count that has arrived.
const pointMaterial = new THREE.PointsMaterial({ size: 2, sizeAttenuation: false, vertexColors: true });
let points = null, capacity = 0, have = 0, total = 0, done = 0, framed = 0;
const structure = { min: new THREE.Vector3(), max: new THREE.Vector3() };

function resetPoints() {
  if (points) scene.remove(points);
  capacity = 1 << 16;
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(capacity * 3), 3));
  geometry.setAttribute('color', new THREE.BufferAttribute(new Float32Array(capacity * 3), 3));
  geometry.setDrawRange(0, 0);
  points = new THREE.Points(geometry, pointMaterial);
  points.frustumCulled = false;
  scene.add(points);
  have = total = done = framed = 0;
  structure.min.set(Infinity, Infinity, Infinity);
  structure.max.set(-Infinity, -Infinity, -Infinity);
  showCount();
}

function reserve(count) {
  if (count <= capacity) return;
  while (capacity < count) capacity *= 2;
  for (const name of ['position', 'color']) {
    const old = points.geometry.getAttribute(name).array;
    const grown = new Float32Array(capacity * 3);
    grown.set(old);
    points.geometry.setAttribute(name, new THREE.BufferAttribute(grown, 3));
  }
}

const colour = new THREE.Color(), at = new THREE.Vector3();
function receive(buffer) {
  const head = new DataView(buffer, 0, 32);
  if (head.getUint32(0, true) !== 0x73414c44) return;  // "DLAs"
  const count = head.getUint32(4, true);
  const first = Number(head.getBigUint64(8, true));
  done = Number(head.getBigUint64(16, true));
  total = Number(head.getBigUint64(24, true));
  const xyz = new Float32Array(buffer, 32, count * 3);
  reserve(first + count);
  const position = points.geometry.getAttribute('position'), colours = points.geometry.getAttribute('color');
  position.array.set(xyz, first * 3);
  for (let i = 0; i < count; ++i) {
    const k = first + i;
    colour.setHSL(0.62 - 0.62 * Math.min(1, k / Math.max(1, total)), 0.85, 0.6);
    colours.array[3 * k] = colour.r; colours.array[3 * k + 1] = colour.g; colours.array[3 * k + 2] = colour.b;
    at.set(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
    structure.min.min(at);
    structure.max.max(at);
  }
  position.needsUpdate = true;
  colours.needsUpdate = true;
  have = Math.max(have, first + count);
  points.geometry.setDrawRange(0, have);
  // Without a mesh the view follows the structure while it doubles in size.
  if (!mesh && have > 0) {
    const size = structure.max.distanceTo(structure.min) / 2;
    if (size > 1.5 * framed || framed === 0) {
      framed = Math.max(size, 1);
      frame(structure.min.clone().add(structure.max).multiplyScalar(0.5), framed);
    }
  }
  showProgress();
}

// -- progress ----------------------------------------------------------------------------------
let samples = [];
function showCount() {
  $('count').textContent = `${have.toLocaleString('en')} particles`;
  document.body.dataset.count = String(have);
}
function showProgress() {
  showCount();
  const now = performance.now() / 1000;
  samples.push([now, done]);
  while (samples.length > 2 && now - samples[0][0] > 3) samples.shift();
  const [t0, d0] = samples[0];
  const rate = now > t0 ? (done - d0) / (now - t0) : 0;
  $('progress').max = Math.max(1, total);
  $('progress').value = done;
  const eta = rate > 0 ? (total - done) / rate : Infinity;
  $('status').textContent = `${done.toLocaleString('en')} of ${total.toLocaleString('en')}` +
    (rate > 0 ? `, ${Math.round(rate).toLocaleString('en')}/s, ${isFinite(eta) ? Math.ceil(eta) + ' s left' : ''}` : '');
}

// -- the mesh and its paint --------------------------------------------------------------------
let mesh = null, painted = false;
const glass = () => $('glass').checked;
function meshMaterial() {
  return new THREE.MeshStandardMaterial({ vertexColors: true, roughness: 0.6, metalness: 0.0,
    transparent: glass(), opacity: glass() ? 0.3 : 1.0, depthWrite: !glass(), side: THREE.DoubleSide });
}
$('glass').addEventListener('change', () => { if (mesh) mesh.material = meshMaterial(); });

function showMesh(buffer) {
  if (mesh) scene.remove(mesh);
  let geometry = new STLLoader().parse(buffer);
  geometry.deleteAttribute('normal');
  geometry = mergeVertices(geometry, 1e-9);  // the STL's shared corners, bit for bit
  geometry.computeVertexNormals();
  const n = geometry.getAttribute('position').count;
  geometry.setAttribute('color', new THREE.BufferAttribute(new Float32Array(n * 3).fill(1), 3));
  mesh = new THREE.Mesh(geometry, meshMaterial());
  mesh.renderOrder = 1;
  scene.add(mesh);
  geometry.computeBoundingSphere();
  geometry.computeBoundingBox();
  const size = geometry.boundingBox.getSize(new THREE.Vector3());
  const longest = size.x >= size.y && size.x >= size.z ? 'x' : size.y >= size.z ? 'y' : 'z';
  const up = new THREE.Vector3(longest === 'x' ? 1 : 0, longest === 'y' ? 1 : 0, longest === 'z' ? 1 : 0);
  frame(geometry.boundingSphere.center, geometry.boundingSphere.radius, up);
  painted = false;
  $('mesh-status').textContent = `${n.toLocaleString('en')} vertices, ${(geometry.index.count / 3).toLocaleString('en')} triangles`;
}

async function loadMesh(path, query, body) {
  $('error').textContent = '';
  const response = await fetch(api(path, { session, ...query }), { method: 'POST', body });
  if (!response.ok) {
    $('error').textContent = (await response.text()).trim();
    return;
  }
  showMesh(await response.arrayBuffer());
  document.body.dataset.mesh = 'true';
}
$('bust').addEventListener('click', () => loadMesh('/api/bust', {}, ''));
$('upload').addEventListener('change', () => {
  const file = $('upload').files[0];
  if (file) loadMesh('/api/mesh', { type: file.name.split('.').pop().toLowerCase() }, file);
});
$('no-mesh').addEventListener('click', () => {
  if (mesh) scene.remove(mesh);
  mesh = null;
  painted = false;
  document.body.dataset.mesh = 'false';
});

const raycaster = new THREE.Raycaster();
function paintAt(event) {
  const brush = $('brush').value;
  if (!mesh || brush === 'none') return;
  const box = renderer.domElement.getBoundingClientRect();
  const pointer = new THREE.Vector2(((event.clientX - box.left) / box.width) * 2 - 1,
    -((event.clientY - box.top) / box.height) * 2 + 1);
  raycaster.setFromCamera(pointer, camera);
  const hit = raycaster.intersectObject(mesh)[0];
  if (!hit) return;
  const radius = mesh.geometry.boundingSphere.radius * Number($('brush-size').value) / 100;
  const position = mesh.geometry.getAttribute('position'), colours = mesh.geometry.getAttribute('color');
  const [r, g, b] = PAINT[brush];
  const v = new THREE.Vector3();
  for (let i = 0; i < position.count; ++i) {
    v.fromBufferAttribute(position, i);
    if (v.distanceToSquared(hit.point) <= radius * radius) colours.setXYZ(i, r / 255, g / 255, b / 255);
  }
  colours.needsUpdate = true;
  painted = true;
  document.body.dataset.painted = 'true';
}
let painting = false;
$('brush').addEventListener('change', () => { controls.enabled = $('brush').value === 'none'; });
renderer.domElement.addEventListener('pointerdown', (e) => { painting = true; paintAt(e); });
renderer.domElement.addEventListener('pointermove', (e) => { if (painting) paintAt(e); });
window.addEventListener('pointerup', () => { painting = false; });
$('clear-paint').addEventListener('click', () => {
  if (!mesh) return;
  mesh.geometry.getAttribute('color').array.fill(1);
  mesh.geometry.getAttribute('color').needsUpdate = true;
  painted = false;
});

//! The mesh with its paint, as a binary PLY with vertex colours: the run's --stl.
function paintedPly() {
  const position = mesh.geometry.getAttribute('position'), colours = mesh.geometry.getAttribute('color');
  const index = mesh.geometry.index.array, n = position.count, faces = index.length / 3;
  const header = 'ply\nformat binary_little_endian 1.0\ncomment dla3d studio: seeds red, attractors green, bare tips blue\n' +
    `element vertex ${n}\nproperty float x\nproperty float y\nproperty float z\n` +
    'property uchar red\nproperty uchar green\nproperty uchar blue\n' +
    `element face ${faces}\nproperty list uchar int vertex_indices\nend_header\n`;
  const head = new TextEncoder().encode(header);
  const bytes = new ArrayBuffer(head.length + n * 15 + faces * 13);
  new Uint8Array(bytes).set(head);
  const out = new DataView(bytes);
  let at = head.length;
  for (let i = 0; i < n; ++i, at += 15) {
    out.setFloat32(at, position.getX(i), true);
    out.setFloat32(at + 4, position.getY(i), true);
    out.setFloat32(at + 8, position.getZ(i), true);
    out.setUint8(at + 12, Math.round(colours.getX(i) * 255));
    out.setUint8(at + 13, Math.round(colours.getY(i) * 255));
    out.setUint8(at + 14, Math.round(colours.getZ(i) * 255));
  }
  for (let f = 0; f < faces; ++f, at += 13) {
    out.setUint8(at, 3);
    for (let c = 0; c < 3; ++c) out.setInt32(at + 1 + 4 * c, index[3 * f + c], true);
  }
  return bytes;
}
function paintedColours() {
  const colours = mesh.geometry.getAttribute('color').array, seen = new Set();
  for (let i = 0; i < colours.length; i += 3)
    for (const [name, [r, g, b]] of Object.entries(PAINT))
      if (name !== 'erase' && colours[i] === r / 255 && colours[i + 1] === g / 255 && colours[i + 2] === b / 255) seen.add(name);
  return seen;
}

// -- the option panel, from `dla3d options` ----------------------------------------------------
let models = [], serverOptions = new Set();
const model = () => models.find((m) => m.name === $('model').value);
//! The model's option that a painting gives (its `paints`: seeds, attractors, bare, mask), if any.
const optionPainted = (role) => model().options.find((o) => o.paints === role);
//! Whether the model reads a mesh: the server hands the uploaded one to its main mesh option.
const readsMesh = () => model().options.some((o) => o.kind === 'file' && o.type === 'MESH_FILE');

function buildPanel() {
  const m = model();
  $('summary').textContent = m.summary;
  const mask = optionPainted('mask');
  $('mask-painter').hidden = !mask;
  $('mask-option').textContent = mask ? `(${mask.name} mask.txt)` : '';
  // Each brush names the option its paint goes to, as this model spells it.
  for (const brush of $('brush').querySelectorAll('option[data-label]')) {
    const option = optionPainted(brush.value);
    brush.textContent = `${brush.dataset.label}: ${option ? option.name : 'not read by ' + m.name})`;
  }
  const groups = new Map();
  for (const option of m.options) {
    // --preset is the Preset menu above the groups.
    if (serverOptions.has(option.name) || option.kind === 'file' || option.name === '--preset') continue;
    if (!groups.has(option.group)) groups.set(option.group, []);
    groups.get(option.group).push(option);
  }
  const panel = $('options');
  panel.replaceChildren();
  if (m.presets && m.presets.length) panel.appendChild(presetRow(m.presets));
  for (const [group, options] of groups) {
    const details = document.createElement('details');
    details.open = group === 'Growth' || group === 'Growth and look';
    const summary = document.createElement('summary');
    summary.textContent = group;
    details.appendChild(summary);
    for (const option of options) details.appendChild(optionRow(option));
    panel.appendChild(details);
  }
}

//! The model's presets, from `dla3d options`: picking one sets the panel's controls to its
//! options (and clears the others), so that the user sees, and can change, what it sets.
function presetRow(presets) {
  const row = document.createElement('div');
  row.className = 'option';
  const label = document.createElement('label');
  const flagName = document.createElement('code');
  flagName.textContent = '--preset';
  label.append('preset ', flagName);
  const menu = document.createElement('select');
  menu.id = 'preset';
  menu.append(new Option('(none)', ''), ...presets.map((p) => new Option(p.name, p.name)));
  const help = document.createElement('small');
  menu.addEventListener('change', () => {
    const preset = presets.find((p) => p.name === menu.value);
    help.textContent = preset ? preset.summary : '';
    applyPreset(preset ? preset.options : []);
  });
  row.append(label, menu, help);
  return row;
}

function applyPreset(options) {
  const panel = $('options');
  for (const input of panel.querySelectorAll('[data-option]')) {
    if (input.type === 'checkbox') input.checked = Boolean(input.dataset.negation);
    else input.value = '';
    input.dispatchEvent(new Event('change'));
  }
  for (const [name, value] of options) {
    const negated = panel.querySelector(`input[data-negation="${name}"]`);
    const input = negated || panel.querySelector(`[data-option="${name}"]`);
    if (!input) continue;  // a file, which the studio chooses
    if (input.type === 'checkbox') input.checked = !negated;
    else input.value = value;
    input.dispatchEvent(new Event('change'));
  }
}

//! An option's control, as its description says: a choice a drop-down, a flag a check box, a
//! number with a range a slider beside its field; labelled in words, with the flag small beside.
function optionRow(option) {
  const row = document.createElement('div');
  row.className = 'option';
  const label = document.createElement('label');
  const flagName = document.createElement('code');
  flagName.textContent = option.name;
  const words = option.name.replace(/^-+/, '').replace(/-/g, ' ') + (option.unit ? ` (${option.unit})` : '');
  let input;
  if (option.flag) {
    input = document.createElement('input');
    input.type = 'checkbox';
    // A flag that is on by default can be turned off only by its negation (--no-stop-at-strike).
    input.checked = option.default === 'true' && option.negation.length > 0;
    input.dataset.negation = input.checked ? option.negation[0] : '';
    label.append(input, ' ' + words + ' ', flagName);
    row.append(label);
  } else if (option.choices) {
    input = document.createElement('select');
    const unset = new Option(`(default: ${option.default})`, '');
    input.append(unset, ...option.choices.map((choice) => new Option(choice, choice)));
    label.append(words + ' ', flagName);
    row.append(label, input);
  } else {
    input = document.createElement('input');
    input.type = 'text';
    input.placeholder = option.default || option.type;
    label.append(words + ' ', flagName);
    row.append(label, input);
    if (option.min !== undefined && option.max !== undefined) {
      const slider = document.createElement('input');
      slider.type = 'range';
      slider.min = option.min;
      slider.max = option.max;
      slider.step = option.kind === 'integer' ? 1 : (option.max - option.min) / 100;
      slider.value = option.default !== '' ? option.default : option.min;
      slider.dataset.sliderOf = option.name;
      slider.addEventListener('input', () => { input.value = slider.value; });
      input.addEventListener('change', () => {
        slider.value = input.value.trim() !== '' ? input.value : option.default !== '' ? option.default : option.min;
      });
      row.append(slider);
    }
  }
  input.dataset.option = option.name;
  input.dataset.repeats = option.repeats;
  input.title = option.help;
  const help = document.createElement('small');
  help.textContent = option.help + (option.default ? ` (default ${option.default})` : '');
  row.append(help);
  return row;
}

// -- Eden's mask, painted on a grid: the sites it counts around the dropped one -------------
const MASK_SIDE = 9;
for (let k = 0; k < MASK_SIDE * MASK_SIDE; ++k) {
  const cell = document.createElement('span');
  cell.dataset.cell = String(k);
  if (k === (MASK_SIDE * MASK_SIDE - 1) / 2) cell.className = 'drop';
  else cell.addEventListener('click', () => cell.classList.toggle('on'));
  $('mask').appendChild(cell);
}
//! The grid as a mask file's rows, top row first: 'o' the dropped site, 'x' a counted one.
function maskRows() {
  const cells = [...$('mask').children], rows = [];
  for (let y = 0; y < MASK_SIDE; ++y)
    rows.push(cells.slice(y * MASK_SIDE, (y + 1) * MASK_SIDE)
      .map((c) => (c.className === 'drop' ? 'o' : c.classList.contains('on') ? 'x' : '.')).join(''));
  return rows;
}

//! The options the panel gives, as [name, value] pairs; a repeated option's values split at ';'.
function chosenOptions() {
  const chosen = [];
  for (const input of $('options').querySelectorAll('[data-option]')) {
    const name = input.dataset.option;
    if (input.type === 'checkbox') {
      if (input.dataset.negation) {
        if (!input.checked) chosen.push([input.dataset.negation, '']);
      } else if (input.checked) chosen.push([name, '']);
    } else if (input.value.trim() !== '') {
      const values = input.dataset.repeats === 'true' ? input.value.split(';') : [input.value];
      for (const value of values) chosen.push([name, value.trim()]);
    }
  }
  return chosen;
}

// -- growing -----------------------------------------------------------------------------------
let socket = null, session = null, running = false, files = [], meshUsed = null, maskUsed = false;
function setRunning(on) {
  running = on;
  $('grow').disabled = on;
  $('stop').disabled = !on;
  $('goon').disabled = on || files.length === 0;
  document.body.dataset.running = String(on);
}

async function grow() {
  $('error').textContent = '';
  resetPoints();
  samples = [];
  if (tubes) scene.remove(tubes), tubes = null;
  const options = chosenOptions();
  const given = new Set(options.map(([name]) => name));
  meshUsed = null;
  if (mesh && readsMesh()) {
    meshUsed = 'mesh';
    if (painted) {
      const response = await fetch(api('/api/paint', { session }), { method: 'POST', body: paintedPly() });
      if (!response.ok) return void ($('error').textContent = (await response.text()).trim());
      meshUsed = 'painted';
      // Each colour painted to the option that reads it, unless the page gave that option, one
      // it cannot go with, or another value of the one it needs (colonize's attractors need
      // --attractors-in surface).
      for (const role of paintedColours()) {
        const option = optionPainted(role);
        if (!option || given.has(option.name) || (option.excludes || []).some((n) => given.has(n))) continue;
        const [needed, value] = option.needs || [];
        if (needed && given.has(needed) && !options.some(([n, v]) => n === needed && v === value)) continue;
        if (needed && !given.has(needed)) options.push([needed, value]);
        options.push([option.name, PAINT[role].map((c) => c.toString(16).padStart(2, '0')).join('')]);
      }
    }
  }
  maskUsed = Boolean(optionPainted('mask')) && $('mask-use').checked;
  setRunning(true);
  socket.send(JSON.stringify({ type: 'grow', model: model().name, options, mesh: meshUsed,
                               ...(maskUsed ? { mask: maskRows() } : {}) }));
}
$('grow').addEventListener('click', grow);
$('stop').addEventListener('click', () => socket.send(JSON.stringify({ type: 'stop' })));
$('goon').addEventListener('click', () => {
  $('error').textContent = '';
  samples = [];
  setRunning(true);
  socket.send(JSON.stringify({ type: 'goon' }));
});

const quote = (word) => (/^[\w@%+=:,./-]+$/.test(word) ? word : `'${word.replace(/'/g, `'\\''`)}'`);
function showFiles(names) {
  files = names;
  const links = $('files');
  links.replaceChildren();
  const all = [...names];
  if (meshUsed === 'painted') all.push('painted.ply');
  else if (meshUsed === 'mesh') all.push('mesh.stl');
  if (maskUsed) all.push('mask.txt');
  for (const name of all) {
    const a = document.createElement('a');
    a.href = api('/api/file', { session, name });
    a.download = name;
    a.textContent = name;
    a.dataset.file = name;
    links.appendChild(a);
  }
}

let tubes = null;
async function showTubes() {
  if (tubes) scene.remove(tubes), tubes = null;
  const wantTubes = $('show').value === 'tubes' && files.includes('run.glb');
  if (points) points.visible = !wantTubes;
  if (!wantTubes) return;
  const response = await fetch(api('/api/file', { session, name: 'run.glb' }));
  const gltf = await new GLTFLoader().parseAsync(await response.arrayBuffer(), '');
  tubes = gltf.scene;
  scene.add(tubes);
}
$('show').addEventListener('change', showTubes);

function connect() {
  socket = new WebSocket(`${location.protocol === 'https:' ? 'wss' : 'ws'}://${location.host}${api('/api/session')}`);
  socket.binaryType = 'arraybuffer';
  socket.onmessage = (event) => {
    if (typeof event.data !== 'string') return receive(event.data);
    const message = JSON.parse(event.data);
    if (message.type === 'hello') {
      session = message.session;
      document.body.dataset.ready = 'true';
    } else if (message.type === 'started') {
      $('command').textContent = message.command.map(quote).join(' ');
      document.body.dataset.state = 'running';
    } else if (message.type === 'done') {
      showProgress();
      showFiles(message.files);
      $('status').textContent += message.stopped ? ' (stopped: Go on grows on)' : ' (done)';
      setRunning(false);
      document.body.dataset.state = message.stopped ? 'stopped' : 'done';
      showTubes();
    } else if (message.type === 'error' || message.type === 'busy') {
      $('error').textContent = message.line;
      if (message.files) showFiles(message.files);
      setRunning(false);
      document.body.dataset.state = message.type;
    }
  };
  socket.onclose = () => {
    $('error').textContent = 'the studio closed the connection: reload the page';
    document.body.dataset.ready = 'false';
  };
}

async function start() {
  resize();
  frame(new THREE.Vector3(), 50);
  resetPoints();
  const response = await fetch(api('/api/models'));
  const description = await response.json();
  models = description.models;
  serverOptions = new Set(description.server_options);
  for (const m of models) $('model').add(new Option(m.name, m.name));
  $('model').addEventListener('change', buildPanel);
  buildPanel();
  $('bust').disabled = !description.bust;
  connect();
  renderer.setAnimationLoop(() => { controls.update(); renderer.render(scene, camera); });
}
start();
