// The editor page: loads the mesh and the current field from the server, draws them, turns
// mouse and keyboard input into constraint edits and shows the server's answers.

import { MeshData, vec } from './mesh.js';
import { OrbitCamera } from './camera.js';
import { Renderer, scalarColors } from './gl.js';
import { EditQueue, TOKEN, apiFetch, getBinary, parseFieldFrame } from './net.js';

const $ = (id) => document.getElementById(id);
const canvas = $('view');
const app = {
  mesh: null, camera: null, renderer: null, status: null, vectors: null,
  tool: 'vector', selected: null, drag: null, pending: null, furRequest: 0, errorTimer: 0,
};

function showError(message) {
  const box = $('error');
  box.textContent = message;
  box.hidden = false;
  document.body.dataset.error = message;
}
function clearError() { $('error').hidden = true; delete document.body.dataset.error; }

// Length in world units of a vector constraint of magnitude 1.
const valueUnit = () => 0.15 * app.mesh.radius;
const strength = () => { const s = parseFloat($('strength').value); return Number.isFinite(s) ? s : 1; };

function nextId(prefix) {
  const used = new Set((app.status ? app.status.constraints : []).map((c) => c.id));
  for (let i = 1; ; i++) if (!used.has(prefix + i)) return prefix + i;
}

// Where constraint c is drawn: {face, barycentric} (weights over the face's corners). A face
// constraint carries it; a vertex or edge constraint has the server's anchor.
function anchorOf(c) {
  if (c.face !== undefined) return { face: c.face, barycentric: c.barycentric || app.mesh.centroidWeights(c.face) };
  const i = app.status ? app.status.constraints.findIndex((x) => x.id === c.id) : -1;
  return i >= 0 ? app.status.anchors[i] : { face: 0, barycentric: null };
}

function constraintPoint(c) {
  const a = anchorOf(c);
  return app.mesh.pointAt(a.face, a.barycentric);
}

// The constraints to draw: the server's, with the one being dragged replaced by its local state.
function shownConstraints() {
  const list = app.status ? app.status.constraints.slice() : [];
  if (app.pending) {
    const i = list.findIndex((c) => c.id === app.pending.id);
    if (i >= 0) list[i] = app.pending; else list.push(app.pending);
  }
  return list;
}

function updateFieldLayers() {
  const { mesh, renderer, vectors } = app;
  if (!vectors) return;
  const mode = $('color-mode').value;
  let largestValue = 0;
  for (let k = 0; k < vectors.length; k++) largestValue = Math.max(largestValue, Math.abs(vectors[k]));
  if (mode === 'none' || largestValue === 0) {
    renderer.setTriangleColors(new Float32Array(3 * mesh.triangleCount).fill(0.82));
    $('color-range').textContent = '–';
  } else {
    const { colors, min, max } = scalarColors(mesh.triangleScalar(mode, vectors), mode !== 'magnitude');
    renderer.setTriangleColors(colors);
    $('color-range').textContent = `${min.toPrecision(3)} … ${max.toPrecision(3)}`;
  }
  // Arrows (one per face, at its corner average) at up to ~2500 faces (a fixed stride through
  // the faces), scaled so the longest arrow is about the sample spacing, lifted a little off
  // the surface.
  const stride = Math.max(1, Math.floor(mesh.faceCount / 2500));
  let largest = 0;
  for (let t = 0; t < mesh.faceCount; t++) largest = Math.max(largest, Math.hypot(vectors[3 * t], vectors[3 * t + 1], vectors[3 * t + 2]));
  const area = mesh.areas.reduce((a, b) => a + b, 0);
  const spacing = Math.sqrt(area * stride / mesh.faceCount);
  const scale = largest > 0 ? 0.9 * spacing / largest : 0;
  const lift = 0.002 * mesh.radius;
  const pos = [], col = [];
  for (let t = 0; t < mesh.faceCount; t += stride) {
    const n = mesh.normal(t);
    const v = [0, 1, 2].map((k) => vectors[3 * t + k] * scale);
    if (Math.hypot(v[0], v[1], v[2]) < 1e-3 * spacing) continue;
    const c = [0, 1, 2].map((k) => mesh.centroids[3 * t + k] + lift * n[k]);
    const a = c.map((x, k) => x - 0.5 * v[k]);
    const b = c.map((x, k) => x + 0.5 * v[k]);
    const side = vec.cross(n, v).map((x) => 0.25 * x);
    const h1 = b.map((x, k) => x - 0.35 * v[k] + side[k]);
    const h2 = b.map((x, k) => x - 0.35 * v[k] - side[k]);
    pos.push(...a, ...b, ...b, ...h1, ...b, ...h2);
    for (let i = 0; i < 6; i++) col.push(0.08, 0.08, 0.1);
  }
  renderer.setLayer('arrows', new Float32Array(pos), new Float32Array(col));
  renderer.setVisible('arrows', $('arrows').checked);
}

const KIND_COLORS = { source: [0.85, 0.1, 0.1], sink: [0.1, 0.3, 0.9], vortex: [0.1, 0.65, 0.2], vector: [0.95, 0.5, 0.05] };

function constraintLook(c) {
  if (c.kind === 'vector') return 'vector';
  if (c.kind === 'divergence') return c.value >= 0 ? 'source' : 'sink';
  return 'vortex';
}

function updateConstraintLayers() {
  const { mesh, renderer } = app;
  const points = [], pointColors = [], lines = [], lineColors = [];
  const lift = 0.004 * mesh.radius;
  for (const c of shownConstraints()) {
    const n = mesh.normal(anchorOf(c).face);
    const p = constraintPoint(c).map((x, k) => x + lift * n[k]);
    const color = c.id === app.selected ? [0.95, 0.1, 0.85] : KIND_COLORS[constraintLook(c)];
    points.push(...p);
    pointColors.push(...color);
    if (c.kind === 'vector') {
      const v = mesh.tangential(c.face, c.value).map((x) => x * valueUnit());
      const tip = p.map((x, k) => x + v[k]);
      const side = vec.cross(n, v).map((x) => 0.2 * x);
      // three parallel strokes for a thicker arrow, plus the head
      for (const o of [-0.004, 0, 0.004]) {
        const off = side.map((x) => x * o / 0.2 / Math.max(1e-12, vec.norm(v)) * mesh.radius);
        lines.push(...p.map((x, k) => x + off[k]), ...tip.map((x, k) => x + off[k]));
      }
      lines.push(...tip, ...tip.map((x, k) => x - 0.3 * v[k] + side[k]), ...tip, ...tip.map((x, k) => x - 0.3 * v[k] - side[k]));
      for (let i = 0; i < 10; i++) lineColors.push(...color);
    }
  }
  renderer.setLayer('markers', new Float32Array(points), new Float32Array(pointColors), 'points', 14);
  renderer.setLayer('constraint-arrows', new Float32Array(lines), new Float32Array(lineColors));
}

function updatePanel() {
  const s = app.status;
  if (!s) return;
  $('constraint-count').textContent = String(s.constraints.length);
  $('residual').textContent = s.constraints.length ? s.residual.toExponential(2) : '–';
  $('field-version').textContent = String(s.version);
  $('basis').max = String(s.max_basis_size);
  $('basis').value = String(s.basis_size);
  $('basis-value').textContent = String(s.basis_size);
  $('omega-value').textContent = s.omega.toPrecision(3);
  if (s.omega > 0) $('omega').value = String(Math.log10(s.omega));
  const c = s.constraints.find((x) => x.id === app.selected);
  if (!c) app.selected = null;
  const where = c && (c.face !== undefined ? `face ${c.face}` : c.vertex !== undefined ? `vertex ${c.vertex}` : `edge ${c.edge}`);
  $('selection').textContent = c ? `${c.id}: ${constraintLook(c)} at ${where}` : 'no constraint selected';
  $('value-row').hidden = !c || c.kind === 'vector';
  if (c && c.kind !== 'vector' && document.activeElement !== $('value')) $('value').value = String(c.value);
  document.body.dataset.version = String(s.version);
}

function redraw() {
  if (!app.renderer) return;
  app.renderer.draw(app.camera);
}
let frameRequested = false;
function requestRedraw() {
  if (frameRequested) return;
  frameRequested = true;
  requestAnimationFrame(() => { frameRequested = false; redraw(); });
}

function acceptField({ status, coords }, milliseconds) {
  if (coords.length !== 2 * app.mesh.faceCount) { showError(`field has ${coords.length} values, expected ${2 * app.mesh.faceCount}`); return; }
  app.status = status;
  app.vectors = app.mesh.vectorsFromFrames(coords);
  if (milliseconds !== undefined) $('latency').textContent = `${milliseconds.toFixed(1)} ms`;
  if (app.pending && !app.drag) app.pending = null;
  updatePanel();
  updateFieldLayers();
  updateConstraintLayers();
  if ($('fur').checked) requestFur();
  requestRedraw();
}

const edits = new EditQueue(
  (frame, ms) => { clearError(); acceptField(frame, ms); },
  (message, op) => {
    showError(message);
    if (op && op.op === 'add' && app.drag && app.drag.id === op.constraint.id) app.drag = { kind: 'none' };
    if (!app.drag || app.drag.kind === 'none') app.pending = null;
    updateConstraintLayers();
    requestRedraw();
  },
  () => {},
);

async function requestFur() {
  const ticket = ++app.furRequest;
  try {
    const buffer = await getBinary('/api/fur?strands=6000');
    if (ticket !== app.furRequest) return;
    const head = new Uint32Array(buffer, 0, 2);
    const [count, per] = [head[0], head[1]];
    const pts = new Float32Array(buffer, 8, 3 * count * per);
    const pos = [], col = [];
    for (let s = 0; s < count; s++) {
      for (let i = 0; i + 1 < per; i++) {
        const a = 3 * (s * per + i), b = a + 3;
        pos.push(pts[a], pts[a + 1], pts[a + 2], pts[b], pts[b + 1], pts[b + 2]);
        const shade = 0.25 + 0.6 * (i + 1) / per;
        col.push(0.35 * shade, 0.22 * shade, 0.1 * shade, 0.45 * shade, 0.3 * shade, 0.15 * shade);
      }
    }
    app.renderer.setLayer('fur', new Float32Array(pos), new Float32Array(col));
    window.__furStrands = count;
    app.renderer.setVisible('fur', $('fur').checked);
    requestRedraw();
  } catch (e) { showError(`fur: ${e.message}`); }
}

// ---- mouse interaction ----

function eventPixel(e) { const r = canvas.getBoundingClientRect(); return [e.clientX - r.left, e.clientY - r.top]; }
function ray(px) { return app.camera.ray(px[0], px[1], canvas.clientWidth, canvas.clientHeight); }

function screenOf(p) {
  const m = app.camera.viewProjection(canvas.clientWidth / canvas.clientHeight);
  const x = m[0] * p[0] + m[4] * p[1] + m[8] * p[2] + m[12];
  const y = m[1] * p[0] + m[5] * p[1] + m[9] * p[2] + m[13];
  const w = m[3] * p[0] + m[7] * p[1] + m[11] * p[2] + m[15];
  return [(x / w + 1) / 2 * canvas.clientWidth, (1 - y / w) / 2 * canvas.clientHeight];
}

// The constraint marker (anchor or vector tip) within 10 px of a pixel, if any.
function markerAt(px) {
  let best = null;
  for (const c of shownConstraints()) {
    const p = constraintPoint(c);
    const handles = [['move', p]];
    if (c.kind === 'vector') {
      const v = app.mesh.tangential(c.face, c.value).map((x) => x * valueUnit());
      handles.push(['turn', p.map((x, k) => x + v[k])]);
    }
    for (const [what, q] of handles) {
      const s = screenOf(q);
      const d = Math.hypot(s[0] - px[0], s[1] - px[1]);
      if (d < 10 && (!best || d < best.d)) best = { c, what, d };
    }
  }
  return best;
}

function toolFor(e) {
  if (e.shiftKey) return 'source';
  if (e.ctrlKey || e.metaKey) return 'sink';
  if (e.altKey) return 'vortex';
  return app.tool;
}

// A vector value from the anchor of c towards the point where the pixel's ray meets c's face plane.
function vectorTowards(c, px) {
  const { origin, dir } = ray(px);
  const hit = app.mesh.rayPlane(c.face, origin, dir);
  if (!hit) return null;
  const v = app.mesh.tangential(c.face, vec.sub(hit, constraintPoint(c)));
  return v.map((x) => x / valueUnit());
}

function newConstraint(tool, hit, px) {
  const base = { face: hit.face, barycentric: hit.barycentric };
  if (tool === 'vector') {
    const { right } = app.camera.axes();
    const v = app.mesh.tangential(hit.face, right);
    const l = vec.norm(v) || 1;
    return { id: nextId('v'), kind: 'vector', ...base, value: v.map((x) => x / l * strength()) };
  }
  if (tool === 'source') return { id: nextId('s'), kind: 'divergence', ...base, value: Math.abs(strength()) };
  if (tool === 'sink') return { id: nextId('k'), kind: 'divergence', ...base, value: -Math.abs(strength()) };
  return { id: nextId('r'), kind: 'curl', ...base, value: strength() };
}

canvas.addEventListener('contextmenu', (e) => e.preventDefault());
canvas.addEventListener('pointerdown', (e) => {
  if (!app.mesh) return;
  canvas.setPointerCapture(e.pointerId);
  const px = eventPixel(e);
  if (e.button !== 0) { app.drag = { kind: e.shiftKey ? 'pan' : 'orbit', last: px }; return; }
  const marker = markerAt(px);
  if (marker) {
    app.selected = marker.c.id;
    app.pending = { ...marker.c };
    app.drag = { kind: marker.what, id: marker.c.id, moved: false };
    updatePanel();
    updateConstraintLayers();
    requestRedraw();
    return;
  }
  const tool = toolFor(e);
  const hit = tool === 'select' ? null : app.mesh.pick(...Object.values(ray(px)));
  if (!hit) { app.drag = { kind: 'orbit', last: px }; return; }
  const c = newConstraint(tool, hit, px);
  app.selected = c.id;
  app.pending = c;
  edits.push({ op: 'add', constraint: c });
  app.drag = c.kind === 'vector' ? { kind: 'turn', id: c.id, moved: false } : { kind: 'none' };
  updateConstraintLayers();
  requestRedraw();
});

canvas.addEventListener('pointermove', (e) => {
  const d = app.drag;
  if (!d) return;
  const px = eventPixel(e);
  if (d.kind === 'orbit' || d.kind === 'pan') {
    if (d.kind === 'orbit') app.camera.orbit(px[0] - d.last[0], px[1] - d.last[1]);
    else app.camera.pan(px[0] - d.last[0], px[1] - d.last[1], canvas.clientHeight);
    d.last = px;
    requestRedraw();
    return;
  }
  if (!app.pending || d.kind === 'none') return;
  if (d.kind === 'turn') {
    const v = vectorTowards(app.pending, px);
    if (!v || vec.norm(v) === 0) return;
    app.pending = { ...app.pending, value: v };
  } else {
    const hit = app.mesh.pick(...Object.values(ray(px)));
    if (!hit) return;
    let value = app.pending.value;
    if (app.pending.kind === 'vector') {
      const t = app.mesh.tangential(hit.face, value);
      const l = vec.norm(value) / (vec.norm(t) || 1);
      value = t.map((x) => x * l);
    }
    app.pending = { ...app.pending, face: hit.face, barycentric: hit.barycentric, value };
  }
  d.moved = true;
  edits.push({ op: 'set', constraint: app.pending });
  updateConstraintLayers();
  requestRedraw();
});

function endDrag() { app.drag = null; if (!edits.busy) app.pending = null; }
canvas.addEventListener('pointerup', endDrag);
canvas.addEventListener('pointercancel', endDrag);
canvas.addEventListener('wheel', (e) => { e.preventDefault(); app.camera.zoom(Math.exp(e.deltaY * 0.001)); requestRedraw(); }, { passive: false });

// ---- toolbar ----

for (const b of document.querySelectorAll('#tools button')) {
  b.addEventListener('click', () => {
    app.tool = b.dataset.tool;
    for (const o of document.querySelectorAll('#tools button')) o.classList.toggle('active', o === b);
  });
}
function deleteSelected() { if (app.selected) { edits.push({ op: 'remove', id: app.selected }); app.selected = null; } }
$('undo').addEventListener('click', () => edits.push({ op: 'undo' }));
$('delete').addEventListener('click', deleteSelected);
document.addEventListener('keydown', (e) => {
  if (e.target instanceof HTMLInputElement) return;
  if (e.key === 'Delete' || e.key === 'Backspace') deleteSelected();
  if ((e.ctrlKey || e.metaKey) && e.key === 'z') { e.preventDefault(); edits.push({ op: 'undo' }); }
});
$('value').addEventListener('change', () => {
  const c = app.status && app.status.constraints.find((x) => x.id === app.selected);
  const v = parseFloat($('value').value);
  if (c && Number.isFinite(v)) edits.push({ op: 'set', constraint: { ...c, value: v } });
});
$('omega').addEventListener('input', () => {
  const omega = Math.pow(10, parseFloat($('omega').value));
  $('omega-value').textContent = omega.toPrecision(3);
  edits.push({ op: 'omega', value: omega });
});
$('basis').addEventListener('input', () => {
  $('basis-value').textContent = $('basis').value;
  edits.push({ op: 'basis_size', value: parseInt($('basis').value, 10) });
});
$('color-mode').addEventListener('change', () => { updateFieldLayers(); requestRedraw(); });
$('arrows').addEventListener('change', () => { app.renderer.setVisible('arrows', $('arrows').checked); requestRedraw(); });
$('outlines').addEventListener('change', () => { app.renderer.setVisible('outlines', $('outlines').checked); requestRedraw(); });
$('fur').addEventListener('change', () => {
  if ($('fur').checked) requestFur(); else app.renderer.setVisible('fur', false);
  requestRedraw();
});
$('save').addEventListener('click', async () => {
  try {
    const response = await apiFetch('/api/constraints');
    if (!response.ok) throw new Error(`${response.status} ${await response.text()}`);
    const url = URL.createObjectURL(await response.blob());
    const a = document.createElement('a');
    a.href = url; a.download = 'constraints.json';
    document.body.appendChild(a); a.click(); a.remove();
    setTimeout(() => URL.revokeObjectURL(url), 1000);
  } catch (e) { showError(`save failed: ${e.message}`); }
});
$('load').addEventListener('change', async () => {
  const file = $('load').files[0];
  if (!file) return;
  try { edits.push({ op: 'load', set: JSON.parse(await file.text()) }); } catch (e) { showError(`${file.name}: ${e.message}`); }
  $('load').value = '';
});

// A heartbeat, so that a server that went away is reported even while nobody edits.
setInterval(async () => {
  try {
    const r = await apiFetch('/api/ping');
    if (!r.ok) throw new Error(String(r.status));
    if (document.body.dataset.error && document.body.dataset.error.startsWith('lost connection')) clearError();
  } catch (e) { showError(`lost connection to the tvf server (${e.message})`); }
}, 3000);

window.addEventListener('resize', requestRedraw);

async function start() {
  // The download link is a plain navigation: it carries the token in its query.
  $('export-fur').href = `/api/fur.obj?token=${encodeURIComponent(TOKEN)}`;
  try {
    app.renderer = new Renderer(canvas);
    app.mesh = new MeshData(await getBinary('/api/mesh'));
    app.camera = new OrbitCamera(app.mesh.center, app.mesh.radius);
    app.renderer.setMesh(app.mesh);
    const { mesh } = app;
    $('mesh-info').textContent = mesh.isTriangleMesh
      ? `${mesh.vertexCount} V, ${mesh.faceCount} F`
      : `${mesh.faceCount} polygons (${mesh.triangleCount} triangles drawn)`;
    // A polygon mesh shows its polygons' sides (the display triangles' inner edges are not drawn).
    $('outlines-row').hidden = mesh.isTriangleMesh;
    if (!mesh.isTriangleMesh) {
      const segments = mesh.outlineSegments(0.001 * mesh.radius);
      app.renderer.setLayer('outlines', segments, new Float32Array(segments.length).fill(0.15));
      app.renderer.setVisible('outlines', $('outlines').checked);
    }
    acceptField(parseFieldFrame(await getBinary('/api/field')));
    redraw();
    // For scripting the page (the browser test uses it): the state and the projection.
    window.tvfEditor = { app, screenOf, requestRedraw };
    document.body.dataset.ready = 'true';
  } catch (e) {
    showError(`could not start the editor: ${e.message}`);
  }
}
start();
