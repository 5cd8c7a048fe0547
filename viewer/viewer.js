// dla3d's web viewer: the script every PREFIX.html inlines (bundled with three.js by esbuild
// at build time). It reads the structure the page embeds (libdla/io/html_writer.cpp writes it) and
// shows it with orbit controls, a growth slider that replays the attach order, a colour
// attribute, lines or tubes, and the constraint mesh as glass. docs/animation.md has the user's
// side.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

// The bytes of a <script type="application/octet-stream"> block, held as base64.
function embedded(id) {
  const element = document.getElementById(id);
  if (!element) return null;
  const text = element.textContent.trim();
  if (Uint8Array.fromBase64) return Uint8Array.fromBase64(text).buffer;
  const binary = atob(text);
  const bytes = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; ++i) bytes[i] = binary.charCodeAt(i);
  return bytes.buffer;
}

const meta = JSON.parse(document.getElementById('dla-meta').textContent);
const count = meta.particles;
const seeds = meta.seeds;
const positions = new Float32Array(embedded('dla-positions'));
const parents = new Int32Array(embedded('dla-parents'));
// Links beside the tree: (earlier, later) pairs in order of the later particle.
const links = meta.links ? new Int32Array(embedded('dla-links')) : new Int32Array(0);
const linkCount = links.length / 2;
const radii = new Float32Array(embedded('dla-radii'));
// One byte a particle for each colour attribute, in meta.colorings' order: value / 255.
const colorings = new Uint8Array(embedded('dla-colors'));
const meshVertices = meta.mesh ? new Float32Array(embedded('dla-mesh-vertices')) : null;

// The colour map of every dla3d file (viridis, linear RGB), from the writer.
function colorAt(value, target) {
  const stops = meta.color_stops;
  const x = Math.min(Math.max(value, 0), 1) * (stops.length - 1);
  const k = Math.min(Math.floor(x), stops.length - 2);
  const f = x - k;
  target.setRGB(stops[k][0] + (stops[k + 1][0] - stops[k][0]) * f, stops[k][1] + (stops[k + 1][1] - stops[k][1]) * f,
                stops[k][2] + (stops[k + 1][2] - stops[k][2]) * f);
  return target;
}
const plain = new THREE.Color(0.9, 0.8, 0.62);

// --- The scene --------------------------------------------------------------------------------
const renderer = new THREE.WebGLRenderer({ antialias: true });
renderer.setPixelRatio(window.devicePixelRatio);
renderer.setSize(window.innerWidth, window.innerHeight);
document.body.appendChild(renderer.domElement);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0x0a0d12);
scene.add(new THREE.HemisphereLight(0xffffff, 0x303040, 1.6));
const sun = new THREE.DirectionalLight(0xffffff, 2.0);
sun.position.set(-0.6, 1.0, 0.8);
scene.add(sun);

// The frame: a sphere around every particle and mesh vertex, seen as the POV-Ray scene sees it.
const box = new THREE.Box3().setFromArray(positions);
if (meshVertices) box.union(new THREE.Box3().setFromArray(meshVertices));
const center = box.getCenter(new THREE.Vector3());
let reach = 1;
{
  const p = new THREE.Vector3();
  for (let i = 0; i < positions.length; i += 3) reach = Math.max(reach, p.fromArray(positions, i).distanceTo(center));
  if (meshVertices) reach = Math.max(reach, box.getSize(p).length() / 2);
}
const camera = new THREE.PerspectiveCamera(40, window.innerWidth / window.innerHeight, reach / 1000, reach * 100);
camera.up.set(meta.up === 'z' ? 0 : meta.up === 'x' ? 1 : 0, meta.up === 'y' ? 1 : 0, meta.up === 'z' ? 1 : 0);
const view = new THREE.Vector3(...meta.view).normalize();
// Far enough that the sphere around it all fits the narrower of the two fields of view.
const halfAngle = Math.min(20, THREE.MathUtils.radToDeg(Math.atan(Math.tan(THREE.MathUtils.degToRad(20)) * camera.aspect)));
camera.position.copy(center).addScaledVector(view, 1.05 * reach / Math.sin(THREE.MathUtils.degToRad(halfAngle)));
const controls = new OrbitControls(camera, renderer.domElement);
controls.target.copy(center);
controls.update();

// Lines: a segment from each particle to its parent, in attach order, so the first k
// particles are a draw range.
const lineGeometry = new THREE.BufferGeometry();
{
  const ends = new Float32Array(6 * count);
  for (let i = 0; i < count; ++i) {
    const p = parents[i] >= 0 ? parents[i] : i;
    ends.set(positions.subarray(3 * p, 3 * p + 3), 6 * i);
    ends.set(positions.subarray(3 * i, 3 * i + 3), 6 * i + 3);
  }
  lineGeometry.setAttribute('position', new THREE.BufferAttribute(ends, 3));
  lineGeometry.setAttribute('color', new THREE.BufferAttribute(new Float32Array(6 * count), 3));
}
const lines = new THREE.LineSegments(lineGeometry, new THREE.LineBasicMaterial({ vertexColors: true }));
scene.add(lines);
// The links as lines too, a segment each, so the links of the first k particles are a draw range.
const linkGeometry = new THREE.BufferGeometry();
{
  const ends = new Float32Array(6 * linkCount);
  for (let k = 0; k < linkCount; ++k) {
    ends.set(positions.subarray(3 * links[2 * k], 3 * links[2 * k] + 3), 6 * k);
    ends.set(positions.subarray(3 * links[2 * k + 1], 3 * links[2 * k + 1] + 3), 6 * k + 3);
  }
  linkGeometry.setAttribute('position', new THREE.BufferAttribute(ends, 3));
  linkGeometry.setAttribute('color', new THREE.BufferAttribute(new Float32Array(6 * linkCount), 3));
}
const linkLines = new THREE.LineSegments(linkGeometry, lines.material);
scene.add(linkLines);
// How many links the first `shown` particles hold: those whose later particle is among them.
function linksShown(shown) {
  let lo = 0, hi = linkCount;
  while (lo < hi) {
    const mid = (lo + hi) >> 1;
    if (links[2 * mid + 1] < shown) lo = mid + 1; else hi = mid;
  }
  return lo;
}

// Tubes, at modest sizes: a cylinder from each particle to its parent, as wide as the
// particle's branch radius, and a sphere at each particle to round the joints. Instances in
// attach order, so the first k particles are the first k instances.
let tubes = null;
if (count <= meta.tube_limit) {
  const cylinder = new THREE.CylinderGeometry(1, 1, 1, 8, 1, true).translate(0, 0.5, 0);
  const ball = new THREE.SphereGeometry(1, 10, 6);
  const material = new THREE.MeshStandardMaterial({ roughness: 0.45, metalness: 0.0 });
  tubes = { sticks: new THREE.InstancedMesh(cylinder, material, count), joints: new THREE.InstancedMesh(ball, material, count),
            links: new THREE.InstancedMesh(cylinder, material, Math.max(linkCount, 1)), placed: -1 };
  scene.add(tubes.sticks, tubes.joints, tubes.links);
}

// The branch radii of the first `shown` particles, in spacings, as the POV-Ray scene's frames
// have them (docs/animation.md): the strands are the finished structure's, cut at the last
// particle grown, the taper runs along the part grown, and the pipe model counts the subtrees so
// far, so a branch only thickens as it grows. The other models' radii do not change as it grows,
// and come from the page.
const descendants = new Int32Array(count), last = new Int32Array(count), grownRadii = new Float32Array(count);
// Each particle's place on its strand from the strand's start: at a branch point the strand goes
// on into the child with the largest finished subtree (ties: the earliest), as dla3d's rule.
const next = new Int32Array(count).fill(-1), step = new Int32Array(count);
{
  for (let i = count - 1; i >= 0; --i) if (parents[i] >= 0) descendants[parents[i]] += descendants[i] + 1;
  for (let i = 0; i < count; ++i) {
    const p = parents[i];
    if (p >= 0 && (next[p] < 0 || descendants[i] > descendants[next[p]])) next[p] = i;
  }
  for (let i = 0; i < count; ++i) step[i] = parents[i] < 0 ? 0 : next[parents[i]] === i ? step[parents[i]] + 1 : 1;
}
function radiiAt(shown) {
  const { model, tip, base, exponent } = meta.radius;
  if (model !== 'taper' && model !== 'pipe') return radii;
  if (model === 'pipe') {
    descendants.fill(0, 0, shown);
    for (let i = shown - 1; i >= 0; --i) if (parents[i] >= 0) descendants[parents[i]] += descendants[i] + 1;
    for (let i = 0; i < shown; ++i) grownRadii[i] = Math.min(tip * Math.pow(descendants[i] + 1, 1 / exponent), Math.max(base, tip));
    return grownRadii;
  }
  last.set(step.subarray(0, shown));
  for (let i = shown - 1; i >= 0; --i) {
    const p = parents[i];
    if (p >= 0 && next[p] === i) last[p] = last[i];
    grownRadii[i] = tip + (base - tip) * (last[i] > 0 ? 1 - step[i] / last[i] : 1);
  }
  return grownRadii;
}

function placeTubes(shown) {
  if (tubes.placed === shown) return;
  const r = radiiAt(shown);
  const matrix = new THREE.Matrix4(), from = new THREE.Vector3(), to = new THREE.Vector3(), axis = new THREE.Vector3();
  const turn = new THREE.Quaternion(), up = new THREE.Vector3(0, 1, 0), scale = new THREE.Vector3();
  for (let i = 0; i < shown; ++i) {
    from.fromArray(positions, 3 * i);
    to.fromArray(positions, 3 * (parents[i] >= 0 ? parents[i] : i));
    axis.subVectors(to, from);
    const length = axis.length();
    turn.setFromUnitVectors(up, length > 0 ? axis.divideScalar(length) : up);
    tubes.sticks.setMatrixAt(i, matrix.compose(from, turn, scale.set(r[i], length, r[i])));
    tubes.joints.setMatrixAt(i, matrix.compose(from, turn.identity(), scale.set(r[i], r[i], r[i])));
  }
  // A link as wide as its thinner end.
  for (let k = 0, shownLinks = linksShown(shown); k < shownLinks; ++k) {
    const a = links[2 * k], b = links[2 * k + 1];
    from.fromArray(positions, 3 * b);
    to.fromArray(positions, 3 * a);
    axis.subVectors(to, from);
    const length = axis.length();
    const width = Math.min(r[a], r[b]);
    turn.setFromUnitVectors(up, length > 0 ? axis.divideScalar(length) : up);
    tubes.links.setMatrixAt(k, matrix.compose(from, turn, scale.set(width, length, width)));
  }
  tubes.sticks.instanceMatrix.needsUpdate = tubes.joints.instanceMatrix.needsUpdate = true;
  tubes.links.instanceMatrix.needsUpdate = true;
  tubes.placed = shown;
}

let meshObject = null;
if (meshVertices) {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(meshVertices, 3));
  geometry.setIndex(new THREE.BufferAttribute(new Uint32Array(embedded('dla-mesh-triangles')), 1));
  geometry.computeVertexNormals();
  meshObject = new THREE.Mesh(geometry, new THREE.MeshStandardMaterial({
    color: 0xcce6ff, transparent: true, opacity: 0.18, roughness: 0.1, side: THREE.DoubleSide, depthWrite: false }));
  meshObject.renderOrder = 1;
  scene.add(meshObject);
}

// --- The controls -----------------------------------------------------------------------------
const panel = document.getElementById('dla-panel');
const slider = panel.querySelector('#dla-show');
const label = panel.querySelector('#dla-count');
const play = panel.querySelector('#dla-play');
const coloring = panel.querySelector('#dla-color');
const tubeBox = panel.querySelector('#dla-tubes');
const meshBox = panel.querySelector('#dla-mesh');
for (const name of ['none', ...meta.colorings]) coloring.add(new Option(name, name));
coloring.value = meta.color_by;
tubeBox.disabled = !tubes;
tubeBox.checked = !!tubes && count <= meta.tube_default_limit;
meshBox.disabled = !meshObject;
meshBox.checked = !!meshObject;

function paint() {
  const which = meta.colorings.indexOf(coloring.value);
  const colors = lineGeometry.getAttribute('color');
  const color = new THREE.Color();
  for (let i = 0; i < count; ++i) {
    if (which < 0) color.copy(plain);
    else colorAt(colorings[meta.colorings.length * i + which] / 255, color);
    colors.setXYZ(2 * i, color.r, color.g, color.b);
    colors.setXYZ(2 * i + 1, color.r, color.g, color.b);
    if (tubes) {
      tubes.sticks.setColorAt(i, color);
      tubes.joints.setColorAt(i, color);
    }
  }
  colors.needsUpdate = true;
  // A link takes its later particle's colour.
  const linkColors = linkGeometry.getAttribute('color');
  for (let k = 0; k < linkCount; ++k) {
    const b = links[2 * k + 1];
    color.setRGB(colors.getX(2 * b), colors.getY(2 * b), colors.getZ(2 * b));
    linkColors.setXYZ(2 * k, color.r, color.g, color.b);
    linkColors.setXYZ(2 * k + 1, color.r, color.g, color.b);
    if (tubes) tubes.links.setColorAt(k, color);
  }
  linkColors.needsUpdate = true;
  if (tubes) tubes.sticks.instanceColor.needsUpdate = tubes.joints.instanceColor.needsUpdate = true;
  if (tubes && tubes.links.instanceColor) tubes.links.instanceColor.needsUpdate = true;
}

// The first `shown` particles: the seeds and a fraction of the rest, as DLA_Show in POV-Ray.
function show() {
  const fraction = Number(slider.value) / Number(slider.max);
  const shown = seeds + Math.round(fraction * (count - seeds));
  lineGeometry.setDrawRange(0, 2 * shown);
  const shownLinks = linksShown(shown);
  linkGeometry.setDrawRange(0, 2 * shownLinks);
  const asTubes = !!tubes && tubeBox.checked;
  lines.visible = linkLines.visible = !asTubes;
  if (tubes) {
    tubes.sticks.visible = tubes.joints.visible = tubes.links.visible = asTubes;
    tubes.sticks.count = tubes.joints.count = shown;
    tubes.links.count = shownLinks;
    if (asTubes) placeTubes(shown);
  }
  if (meshObject) meshObject.visible = meshBox.checked;
  label.textContent = `${shown.toLocaleString('en')} of ${count.toLocaleString('en')} particles` +
    (linkCount ? `, ${shownLinks.toLocaleString('en')} links` : '');
}

let playing = false, lastFrame = 0;
play.addEventListener('click', () => {
  playing = !playing;
  if (playing && Number(slider.value) >= Number(slider.max)) slider.value = 0;
  play.textContent = playing ? 'Pause' : 'Play';
  lastFrame = performance.now();
});
slider.addEventListener('input', () => { playing = false; play.textContent = 'Play'; show(); });
coloring.addEventListener('change', paint);
tubeBox.addEventListener('change', show);
meshBox.addEventListener('change', show);
window.addEventListener('resize', () => {
  camera.aspect = window.innerWidth / window.innerHeight;
  camera.updateProjectionMatrix();
  renderer.setSize(window.innerWidth, window.innerHeight);
});

// #show=0.25 in the address opens the page part grown.
const start = new URLSearchParams(location.hash.slice(1)).get('show');
if (start !== null && Number.isFinite(Number(start))) slider.value = Math.round(Math.min(Math.max(Number(start), 0), 1) * Number(slider.max));

paint();
show();
renderer.setAnimationLoop((now) => {
  if (playing) {
    // The whole growth in ten seconds.
    const advance = (now - lastFrame) / 10000 * Number(slider.max);
    lastFrame = now;
    slider.value = Math.min(Number(slider.max), Number(slider.value) + Math.max(1, Math.round(advance)));
    if (Number(slider.value) >= Number(slider.max)) { playing = false; play.textContent = 'Play'; }
    show();
  }
  controls.update();
  renderer.render(scene, camera);
  document.body.dataset.ready = 'true';
});
