// The editor page of `bspcsg edit`: a scene document edited as JSON, every edit an entry of an
// undoable action log, validated by the server (the library's JSON-path messages), previewed
// by the WebGL2 ray marcher the server generates from the scene.
'use strict';

const $ = (id) => document.getElementById(id);

// ---- State ----------------------------------------------------------------------------------
// `history[i].json` is the document after action i; `at` is the current entry.
const state = {
  doc: null,
  history: [],
  at: -1,
  selected: null, // path (array) of the selected node
  marked: [], // paths of Ctrl-clicked siblings
  notes: [], // saves and exports, each after history entry `after`
  valid: false,
  leafPaths: [],
  serverCamera: null,
  camera: null, // {target, dist, yaw, pitch, up, fov, ortho}
  autoFrame: true, // follow the server's framing until the user moves the view
  viewMode: 'preview',
};

const clone = (v) => JSON.parse(JSON.stringify(v));

// A JSON path string of the library's form: $.tree.children[1].data.radius
function pathString(path) {
  let s = '$';
  for (const k of path) s += typeof k === 'number' ? `[${k}]` : `.${k}`;
  return s;
}
function getAt(doc, path) {
  let v = doc;
  for (const k of path) {
    if (v == null) return undefined;
    v = v[k];
  }
  return v;
}
function setAt(doc, path, value) {
  const parent = getAt(doc, path.slice(0, -1));
  parent[path[path.length - 1]] = value;
}
const samePath = (a, b) => a && b && a.length === b.length && a.every((k, i) => k === b[i]);

// ---- Server ---------------------------------------------------------------------------------
async function post(url, body) {
  const r = await fetch(url, {
    method: 'POST',
    headers: { 'Content-Type': 'application/json' },
    body: JSON.stringify(body),
  });
  return r;
}

// ---- Actions and undo -----------------------------------------------------------------------
function record(label) {
  state.history.length = state.at + 1;
  state.notes = state.notes.filter((n) => n.after <= state.at);
  state.history.push({ label, json: JSON.stringify(state.doc), time: new Date() });
  state.at = state.history.length - 1;
  changed();
}
// Applies `fn` to a copy of the document; on success it becomes an action.
function act(label, fn) {
  const doc = clone(state.doc);
  const result = fn(doc);
  if (result === false) return false;
  // A change to the value a field already has is no action.
  if (JSON.stringify(doc) === JSON.stringify(state.doc)) return false;
  state.doc = doc;
  record(label);
  return true;
}
function undo() {
  if (state.at <= 0) return;
  state.at -= 1;
  state.doc = JSON.parse(state.history[state.at].json);
  fixSelection();
  changed();
}
function redo() {
  if (state.at >= state.history.length - 1) return;
  state.at += 1;
  state.doc = JSON.parse(state.history[state.at].json);
  fixSelection();
  changed();
}
function fixSelection() {
  if (state.selected && getAt(state.doc, state.selected) === undefined) state.selected = null;
  state.marked = state.marked.filter((p) => getAt(state.doc, p) !== undefined);
}

// ---- Tree model -----------------------------------------------------------------------------
// The roots the page edits: the envelope's `tree` and each placed tree of `nodes`.
function roots(doc) {
  const out = [];
  if (doc.tree) out.push(['tree']);
  (doc.nodes || []).forEach((n, i) => out.push(['nodes', i, 'tree']));
  return out;
}
function childList(node) {
  if (node && node.op && Array.isArray(node.children)) return 'children';
  if (node && node.kind === 'sdf_csg_tree') return 'root';
  return null;
}
function label(node) {
  if (node.op === 'extrude' || node.op === 'revolve') return node.op;
  if (node.op) return node.op + (node.smooth_k !== undefined ? ` k=${node.smooth_k}` : '');
  if (node.kind === 'sdf_primitive') return (node.data && node.data.primitive_type) || 'primitive';
  if (node.kind === 'sdf_csg_tree') return 'tree';
  return '?';
}
function isOp(node) {
  return node && node.op && Array.isArray(node.children);
}

// Where a new node goes: into the selected operation, after the selected node, or into the
// first root (made a union when it is not one).
function insertNode(doc, node) {
  let sel = state.selected && getAt(doc, state.selected);
  if (sel && isOp(sel)) {
    sel.children.push(node);
    return [...state.selected, 'children', sel.children.length - 1];
  }
  if (sel && state.selected.length >= 2 && state.selected[state.selected.length - 2] === 'children') {
    const parentPath = state.selected.slice(0, -2);
    const parent = getAt(doc, parentPath);
    const i = state.selected[state.selected.length - 1] + 1;
    parent.children.splice(i, 0, node);
    return [...parentPath, 'children', i];
  }
  if (!doc.tree && !(doc.nodes && doc.nodes.length)) doc.tree = { op: 'union', children: [] };
  const rootPath = doc.tree ? ['tree'] : ['nodes', 0, 'tree'];
  let root = getAt(doc, rootPath);
  if (!isOp(root)) {
    root = { op: 'union', children: [root] };
    setAt(doc, rootPath, root);
  }
  root.children.push(node);
  return [...rootPath, 'children', root.children.length - 1];
}

const NEW = {
  box: () => ({ kind: 'sdf_primitive', name: 'box', data: { primitive_type: 'box', size: [1, 1, 1] } }),
  sphere: () => ({ kind: 'sdf_primitive', name: 'sphere', data: { primitive_type: 'sphere', radius: 0.6 } }),
  cylinder: () => ({ kind: 'sdf_primitive', name: 'cylinder', data: { primitive_type: 'cylinder', radius: 0.4, height: 1.2 } }),
  torus: () => ({ kind: 'sdf_primitive', name: 'torus', data: { primitive_type: 'torus', radius: 0.6, tube_radius: 0.2 } }),
  cone: () => ({ kind: 'sdf_primitive', name: 'cone', data: { primitive_type: 'cone', radius: 0.5, height: 1 } }),
  extrude: () => ({ op: 'extrude', name: 'extrusion', extrude_depth: 0.5,
    source_2d_sdf: { type: 'regular_polygon', sides: 6, radius: 0.5 } }),
  revolve: () => ({ op: 'revolve', name: 'revolution',
    source_2d_sdf: { type: 'rounded_rectangle', size: [0.3, 0.8], radius: 0.05, pos: [0.5, 0] } }),
};

function addNode(kind) {
  let path = null;
  act(`add ${kind}`, (doc) => { path = insertNode(doc, NEW[kind]()); });
  state.selected = path;
  state.marked = [];
  renderAll();
}

// The selected node and its Ctrl-clicked siblings go under a new operation, in tree order.
function group(op) {
  if (!state.selected) return say('Select a node first (Ctrl-click siblings to group several).');
  const sel = state.selected;
  const parentPath = sel.slice(0, -2);
  const siblings = [sel, ...state.marked.filter((p) => samePath(p.slice(0, -2), parentPath) && p[p.length - 2] === 'children')];
  const idx = [...new Set(siblings.map((p) => p[p.length - 1]))].sort((a, b) => a - b);
  const inOp = sel.length >= 2 && sel[sel.length - 2] === 'children';
  let newPath = null;
  act(`group ${idx.length} under ${op}`, (doc) => {
    const node = { op, children: [] };
    if (op.startsWith('smooth_')) node.smooth_k = 0.2, node.smooth = 'polynomial';
    if (!inOp) {
      node.children.push(getAt(doc, sel));
      setAt(doc, sel, node);
      newPath = sel;
      return;
    }
    const parent = getAt(doc, parentPath);
    node.children = idx.map((i) => parent.children[i]);
    for (const i of [...idx].reverse()) parent.children.splice(i, 1);
    parent.children.splice(idx[0], 0, node);
    newPath = [...parentPath, 'children', idx[0]];
  });
  state.selected = newPath;
  state.marked = [];
  renderAll();
}

function move(delta) {
  const sel = state.selected;
  if (!sel || sel[sel.length - 2] !== 'children') return;
  const parentPath = sel.slice(0, -2);
  const i = sel[sel.length - 1];
  const j = i + delta;
  const parent = getAt(state.doc, parentPath);
  if (j < 0 || j >= parent.children.length) return;
  act(`move ${label(parent.children[i])} ${delta < 0 ? 'up' : 'down'}`, (doc) => {
    const c = getAt(doc, parentPath).children;
    [c[i], c[j]] = [c[j], c[i]];
  });
  state.selected = [...parentPath, 'children', j];
  renderAll();
}

function remove() {
  const sel = state.selected;
  if (!sel) return;
  const node = getAt(state.doc, sel);
  act(`delete ${label(node)}`, (doc) => {
    if (sel[sel.length - 2] === 'children') {
      getAt(doc, sel.slice(0, -2)).children.splice(sel[sel.length - 1], 1);
    } else if (sel.length === 1) {
      doc.tree = { op: 'union', children: [] };
    } else if (sel[0] === 'nodes') {
      doc.nodes.splice(sel[1], 1);
      if (!doc.nodes.length) delete doc.nodes;
      if (!doc.tree && !doc.nodes) doc.tree = { op: 'union', children: [] };
    } else {
      return false;
    }
  });
  state.selected = null;
  state.marked = [];
  renderAll();
}

// ---- Tree panel -----------------------------------------------------------------------------
function renderTree() {
  const el = $('tree');
  el.textContent = '';
  // Explicit stack: documents may nest deeply.
  const stack = roots(state.doc).reverse().map((p) => ({ path: p, depth: 0 }));
  while (stack.length) {
    const { path, depth } = stack.pop();
    const node = getAt(state.doc, path);
    if (node === undefined) continue;
    const row = document.createElement('div');
    row.className = 'node';
    row.dataset.path = pathString(path);
    row.style.paddingLeft = `${4 + depth * 14}px`;
    const kind = document.createElement('span');
    kind.className = 'kind';
    kind.textContent = typeof node === 'object' ? label(node) : String(node);
    row.appendChild(kind);
    if (node && node.name) {
      const n = document.createElement('span');
      n.className = 'name';
      n.textContent = ` ${node.name}`;
      row.appendChild(n);
    }
    if (samePath(path, state.selected)) row.classList.add('selected');
    if (state.marked.some((p) => samePath(p, path))) row.classList.add('marked');
    row.addEventListener('click', (e) => {
      if ((e.ctrlKey || e.metaKey) && state.selected) {
        const k = state.marked.findIndex((p) => samePath(p, path));
        if (k >= 0) state.marked.splice(k, 1); else state.marked.push(path);
      } else {
        state.selected = path;
        state.marked = [];
      }
      renderTree();
      renderProps();
      updateSelection();
    });
    el.appendChild(row);
    const key = childList(node);
    if (key === 'children') {
      for (let i = node.children.length - 1; i >= 0; i--) stack.push({ path: [...path, 'children', i], depth: depth + 1 });
    } else if (key === 'root') {
      stack.push({ path: [...path, 'root'], depth: depth + 1 });
    }
  }
  if (!el.children.length) el.textContent = '(empty)';
}

// ---- Properties panel -----------------------------------------------------------------------
const FIELDS = {
  box: [['size', 'vec3']],
  sphere: [['radius', 'num']],
  cylinder: [['radius', 'num'], ['height', 'num']],
  cone: [['radius', 'num'], ['radius_top', 'num'], ['height', 'num']],
  pyramid: [['base', 'num'], ['height', 'num']],
  torus: [['radius', 'num'], ['tube_radius', 'num']],
  plane: [['normal', 'vec3'], ['offset', 'num']],
};
const OPS = ['union', 'intersect', 'subtract', 'smooth_union', 'smooth_intersect', 'smooth_subtract'];

function row(labelText, control) {
  const l = document.createElement('label');
  const s = document.createElement('span');
  s.textContent = labelText;
  l.append(s, control);
  return l;
}
function numberInput(value, path, onValue) {
  const i = document.createElement('input');
  i.type = 'number';
  i.step = 'any';
  i.value = value === undefined ? '' : value;
  i.dataset.path = pathString(path);
  i.addEventListener('change', () => {
    if (i.value === '') return onValue(undefined, i);
    const x = Number(i.value);
    if (!Number.isFinite(x)) {
      i.classList.add('invalid');
      return say(`${pathString(path)}: expected a number`);
    }
    i.classList.remove('invalid');
    onValue(x, i);
  });
  return i;
}
function vecInput(value, n, path, onValue) {
  const box = document.createElement('span');
  box.className = 'vec';
  const v = Array.isArray(value) ? [...value] : Array(n).fill(value === undefined ? '' : value);
  const inputs = [];
  for (let k = 0; k < n; k++) {
    const i = numberInput(v[k], [...path, k], () => {
      const vals = inputs.map((x) => Number(x.value));
      if (vals.some((x) => !Number.isFinite(x) || inputs.some((y) => y.value === ''))) return;
      onValue(vals);
    });
    i.dataset.path = pathString([...path, k]);
    inputs.push(i);
    box.appendChild(i);
  }
  box.dataset.path = pathString(path);
  return box;
}
function setField(nodePath, key, value, what) {
  act(`set ${what || key} = ${JSON.stringify(value)}`, (doc) => {
    const node = getAt(doc, nodePath);
    const keys = key.split('.');
    let o = node;
    for (const k of keys.slice(0, -1)) o = o[k] = o[k] || {};
    const last = keys[keys.length - 1];
    if (value === undefined) delete o[last]; else o[last] = value;
  });
  renderTree();
}

function renderProps() {
  const el = $('props');
  el.textContent = '';
  const path = state.selected;
  const node = path && getAt(state.doc, path);
  if (!node || typeof node !== 'object') {
    el.textContent = 'Select a node in the tree.';
    return;
  }
  const name = document.createElement('input');
  name.value = node.name || '';
  name.addEventListener('change', () => setField(path, 'name', name.value || undefined, 'name'));
  el.appendChild(row('name', name));
  const isPrim = node.kind === 'sdf_primitive';
  if (node.op && OPS.includes(node.op)) {
    const sel = document.createElement('select');
    for (const o of OPS) sel.add(new Option(o, o, false, o === node.op));
    sel.id = 'prop-op';
    sel.addEventListener('change', () => {
      act(`set op = ${sel.value}`, (doc) => {
        const n = getAt(doc, path);
        n.op = sel.value;
        if (sel.value.startsWith('smooth_')) {
          if (n.smooth_k === undefined) n.smooth_k = 0.2;
          if (n.smooth === undefined) n.smooth = 'polynomial';
        } else {
          delete n.smooth_k;
          delete n.smooth;
        }
      });
      renderTree();
      renderProps();
    });
    el.appendChild(row('op', sel));
    if (node.op.startsWith('smooth_')) {
      el.appendChild(row('smooth k', numberInput(node.smooth_k, [...path, 'smooth_k'], (x) => setField(path, 'smooth_k', x, 'smooth k'))));
      const kind = document.createElement('select');
      for (const o of ['exponential', 'polynomial']) kind.add(new Option(o, o, false, o === (node.smooth || 'exponential')));
      kind.addEventListener('change', () => setField(path, 'smooth', kind.value, 'smooth'));
      el.appendChild(row('smooth', kind));
    }
  }
  if (isPrim && node.data) {
    const t = node.data.primitive_type;
    const pt = document.createElement('input');
    pt.value = t;
    pt.disabled = true;
    el.appendChild(row('type', pt));
    for (const [key, kind] of FIELDS[t] || []) {
      const p = [...path, 'data', key];
      const c = kind === 'vec3'
        ? vecInput(node.data[key], 3, p, (v) => setField(path, `data.${key}`, v, key))
        : numberInput(node.data[key], p, (x) => setField(path, `data.${key}`, x, key));
      c.id = `prop-${key}`;
      el.appendChild(row(key, c));
    }
  }
  if (node.op === 'extrude') {
    el.appendChild(row('depth', numberInput(node.extrude_depth, [...path, 'extrude_depth'], (x) => setField(path, 'extrude_depth', x, 'extrude depth'))));
    el.appendChild(row('twist°', numberInput(node.twist, [...path, 'twist'], (x) => setField(path, 'twist', x, 'twist'))));
    el.appendChild(row('scale top', numberInput(typeof node.scale_top === 'number' ? node.scale_top : undefined, [...path, 'scale_top'], (x) => setField(path, 'scale_top', x, 'scale top'))));
  }
  if (node.op === 'revolve') {
    el.appendChild(row('angle°', numberInput(node.angle, [...path, 'angle'], (x) => setField(path, 'angle', x, 'angle'))));
  }
  if (node.op === 'extrude' || node.op === 'revolve') {
    el.appendChild(row('2D shape', jsonArea(node.source_2d_sdf, [...path, 'source_2d_sdf'], (v) => setField(path, 'source_2d_sdf', v, '2D shape'))));
  }
  if (isPrim || node.op === 'extrude' || node.op === 'revolve') {
    const mat = document.createElement('select');
    mat.id = 'prop-material';
    const current = isPrim ? node.data && node.data.material : node.material;
    mat.add(new Option('(default)', '', false, current === undefined));
    for (const m of Object.keys(state.doc.materials || {})) mat.add(new Option(m, m, false, m === current));
    mat.addEventListener('change', () => setField(path, isPrim ? 'data.material' : 'material', mat.value || undefined, 'material'));
    el.appendChild(row('material', mat));
  }
  const pos = vecInput(node.pos || [0, 0, 0], 3, [...path, 'pos'], (v) => setField(path, 'pos', v, 'pos'));
  pos.id = 'prop-pos';
  el.appendChild(row('pos', pos));
  const rot = vecInput(node.rot || [0, 0, 0], 3, [...path, 'rot'], (v) => setField(path, 'rot', v, 'rot°'));
  rot.id = 'prop-rot';
  el.appendChild(row('rot°', rot));
  const s = node.scale === undefined ? 1 : node.scale;
  const scale = vecInput(s, 3, [...path, 'scale'], (v) => setField(path, 'scale', v.every((x) => x === v[0]) ? v[0] : v, 'scale'));
  scale.id = 'prop-scale';
  el.appendChild(row('scale', scale));
  el.appendChild(row('JSON', jsonArea(node, path, (v) => {
    act(`edit ${label(node)} as JSON`, (doc) => setAt(doc, path, v));
    renderAll();
  })));
  markFault();
}

function jsonArea(value, path, onValue) {
  const t = document.createElement('textarea');
  t.value = JSON.stringify(value, null, 1);
  t.dataset.path = pathString(path);
  t.addEventListener('change', () => {
    let v;
    try {
      v = JSON.parse(t.value);
    } catch (e) {
      t.classList.add('invalid');
      return say(`${pathString(path)}: not valid JSON: ${e.message}`);
    }
    t.classList.remove('invalid');
    onValue(v);
  });
  return t;
}

// ---- Document panel -------------------------------------------------------------------------
function renderDocFields() {
  const el = $('doc-fields');
  el.textContent = '';
  for (const key of ['materials', 'lights', 'camera', 'render_profile']) {
    const v = state.doc[key];
    const t = jsonArea(v === undefined ? null : v, [key], (x) => {
      act(`set ${key}`, (doc) => { if (x === null) delete doc[key]; else doc[key] = x; });
      renderAll();
    });
    t.id = `doc-${key}`;
    el.appendChild(row(key, t));
  }
}

// ---- Messages, log --------------------------------------------------------------------------
let lastFault = null;
function say(text, ok) {
  const m = $('message');
  m.textContent = text || '';
  m.className = ok ? 'message ok' : 'message';
}
// Marks the input whose JSON path the server's message names (or its nearest ancestor).
function markFault() {
  document.querySelectorAll('.invalid').forEach((e) => e.classList.remove('invalid'));
  if (!lastFault) return;
  let p = lastFault;
  while (p.length > 1) {
    const e = document.querySelector(`[data-path="${CSS.escape(p)}"]`);
    if (e) {
      e.classList.add('invalid');
      return;
    }
    p = p.replace(/(\.[^.[\]]*|\[\d+\])$/, '');
  }
}
function renderLog() {
  const el = $('log');
  el.textContent = '';
  state.history.forEach((h, i) => {
    const li = document.createElement('li');
    li.textContent = `${h.time.toLocaleTimeString()} ${h.label}`;
    if (i > state.at) li.className = 'undone';
    if (i === state.at) li.className = 'current';
    el.appendChild(li);
    for (const n of state.notes.filter((n) => n.after === i)) {
      const note = document.createElement('li');
      note.textContent = `${n.time.toLocaleTimeString()} ${n.text}`;
      note.className = 'note';
      el.appendChild(note);
    }
  });
  el.scrollTop = el.scrollHeight;
  $('undo').disabled = state.at <= 0;
  $('redo').disabled = state.at >= state.history.length - 1;
}
function renderAll() {
  fixSelection();
  renderTree();
  renderProps();
  renderDocFields();
  renderLog();
}

// ---- Validation and preview -----------------------------------------------------------------
function isEmpty(doc) {
  return roots(doc).every((p) => {
    const n = getAt(doc, p);
    return isOp(n) && n.children.length === 0;
  });
}
let generation = 0;
function changed() {
  renderLog();
  const gen = ++generation;
  clearTimeout(changed.timer);
  changed.timer = setTimeout(() => refresh(gen), 60);
}
async function refresh(gen) {
  if (isEmpty(state.doc)) {
    state.valid = false;
    lastFault = null;
    say('The scene is empty: add a primitive.', true);
    preview.clear();
    return;
  }
  const [w, h] = preview.size();
  const r = await post(`/api/shader?w=${w}&h=${h}`, state.doc);
  if (gen !== generation) return;
  const body = await r.json();
  if (!r.ok) {
    state.valid = false;
    lastFault = body.json_path || null;
    say(body.error);
    markFault();
    $('status').textContent = 'invalid scene: preview shows the last valid one';
    return;
  }
  state.valid = true;
  lastFault = null;
  say('valid', true);
  $('status').textContent = '';
  markFault();
  state.leafPaths = body.leaf_paths;
  state.serverCamera = body.camera;
  if (state.autoFrame || !state.camera) setCamera(body.camera);
  preview.setShader(body.glsl);
  updateSelection();
  if (state.viewMode === 'mesh') meshView.load();
  state.previews = (state.previews || 0) + 1;
  window.dispatchEvent(new Event('bspcsg-preview'));
}

// The selected node's leaves: a contiguous run of the shader's leaf list.
function updateSelection() {
  let lo = -1, hi = -1;
  if (state.selected) {
    const s = pathString(state.selected);
    state.leafPaths.forEach((p, i) => {
      if (p === s || p.startsWith(`${s}.`) || p.startsWith(`${s}[`)) {
        if (lo < 0) lo = i;
        hi = i + 1;
      }
    });
  }
  preview.selection = [lo, hi];
  preview.draw();
}

// ---- Camera: orbit, pan, zoom ---------------------------------------------------------------
function setCamera(c) {
  const eye = c.eye, target = c.target;
  const d = [eye[0] - target[0], eye[1] - target[1], eye[2] - target[2]];
  const dist = Math.hypot(...d);
  state.camera = {
    target: [...target],
    dist,
    yaw: Math.atan2(d[0], d[2]),
    pitch: Math.asin(Math.max(-1, Math.min(1, d[1] / dist))),
    up: c.up,
    fov: c.fov_deg,
    ortho: c.ortho_height,
    // Kept exactly while the view is the server's, so the preview matches `bspcsg render`.
    exactEye: [...eye],
  };
}
function cameraEye() {
  const c = state.camera;
  if (c.exactEye) return c.exactEye;
  const cp = Math.cos(c.pitch);
  return [c.target[0] + c.dist * cp * Math.sin(c.yaw), c.target[1] + c.dist * Math.sin(c.pitch), c.target[2] + c.dist * cp * Math.cos(c.yaw)];
}
function viewMoved() {
  state.autoFrame = false;
  state.camera.exactEye = null;
  // Up stays Y while orbiting (a top view's -Z up would flip).
  state.camera.up = [0, 1, 0];
  if (state.viewMode === 'mesh') meshView.draw(); else preview.drawMoving();
}
function attachControls(canvas) {
  let drag = null;
  canvas.addEventListener('contextmenu', (e) => e.preventDefault());
  canvas.addEventListener('pointerdown', (e) => {
    drag = { x: e.clientX, y: e.clientY, pan: e.button === 2 || e.shiftKey };
    canvas.setPointerCapture(e.pointerId);
  });
  canvas.addEventListener('pointerup', () => { drag = null; });
  canvas.addEventListener('pointermove', (e) => {
    if (!drag || !state.camera) return;
    const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
    drag.x = e.clientX;
    drag.y = e.clientY;
    const c = state.camera;
    if (drag.pan) {
      const eye = cameraEye();
      const f = norm(sub(c.target, eye));
      const r = norm(cross(f, [0, 1, 0]));
      const u = cross(r, f);
      const k = (c.ortho > 0 ? c.ortho : 2 * c.dist * Math.tan((c.fov * Math.PI) / 360)) / canvas.height;
      for (let i = 0; i < 3; i++) c.target[i] += (-dx * r[i] + dy * u[i]) * k;
    } else {
      c.yaw -= dx * 0.008;
      c.pitch = Math.max(-1.55, Math.min(1.55, c.pitch + dy * 0.008));
    }
    viewMoved();
  });
  canvas.addEventListener('wheel', (e) => {
    e.preventDefault();
    if (!state.camera) return;
    const f = Math.exp(e.deltaY * 0.001);
    state.camera.dist *= f;
    if (state.camera.ortho > 0) state.camera.ortho *= f;
    viewMoved();
  }, { passive: false });
}
const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const norm = (a) => { const l = Math.hypot(...a) || 1; return [a[0] / l, a[1] / l, a[2] / l]; };

// ---- WebGL2 preview -------------------------------------------------------------------------
const VERTEX = `#version 300 es
void main() {
  // One triangle covering the viewport.
  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}`;

const preview = {
  canvas: null,
  gl: null,
  program: null,
  uniforms: {},
  selection: [-1, -1],
  init() {
    this.canvas = $('preview');
    this.gl = this.canvas.getContext('webgl2', { preserveDrawingBuffer: true, antialias: false });
    if (!this.gl) say('This browser has no WebGL2: the preview is off (save, export and check still work).');
    attachControls(this.canvas);
    this.resize();
    window.addEventListener('resize', () => this.resize());
  },
  size() {
    return [this.canvas.width, this.canvas.height];
  },
  resize() {
    const mode = $('preview-size').value;
    let w, h;
    if (mode === 'fit') {
      const vp = $('viewport');
      w = Math.max(64, Math.floor(vp.clientWidth));
      h = Math.max(48, Math.floor(vp.clientHeight));
    } else {
      [w, h] = mode.split('x').map(Number);
    }
    if (w !== this.canvas.width || h !== this.canvas.height) {
      this.canvas.width = w;
      this.canvas.height = h;
      meshView.canvasChanged();
      changed();
    }
  },
  setShader(source) {
    const gl = this.gl;
    if (!gl) return;
    const compile = (type, src) => {
      const s = gl.createShader(type);
      gl.shaderSource(s, src);
      gl.compileShader(s);
      if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(s));
      return s;
    };
    const t0 = performance.now();
    try {
      const p = gl.createProgram();
      gl.attachShader(p, compile(gl.VERTEX_SHADER, VERTEX));
      gl.attachShader(p, compile(gl.FRAGMENT_SHADER, source));
      gl.linkProgram(p);
      if (!gl.getProgramParameter(p, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(p));
      if (this.program) gl.deleteProgram(this.program);
      this.program = p;
      this.uniforms = {};
      for (const u of ['uResolution', 'uEye', 'uTarget', 'uUp', 'uFov', 'uOrthoHeight', 'uSelLo', 'uSelHi']) {
        this.uniforms[u] = gl.getUniformLocation(p, u);
      }
      this.compileMs = performance.now() - t0;
    } catch (e) {
      say(`the generated shader did not compile: ${e.message}`);
    }
    this.draw();
  },
  clear() {
    const gl = this.gl;
    if (!gl) return;
    this.program = null;
    gl.viewport(0, 0, this.canvas.width, this.canvas.height);
    gl.clearColor(0.07, 0.07, 0.08, 1);
    gl.clear(gl.COLOR_BUFFER_BIT);
  },
  // One frame (also what measureFps times). With `scale` < 1 it is marched at that fraction
  // of the resolution into a texture and scaled up: what dragging the view shows.
  frame(scale = 1) {
    const gl = this.gl;
    if (!gl || !this.program || !state.camera) return;
    const c = state.camera, u = this.uniforms;
    const W = this.canvas.width, H = this.canvas.height;
    const w = Math.max(1, Math.round(W * scale)), h = Math.max(1, Math.round(H * scale));
    if (scale < 1) {
      if (!this.fbo || this.fboSize !== `${w}x${h}`) {
        if (this.fbo) { gl.deleteFramebuffer(this.fbo); gl.deleteRenderbuffer(this.rbo); }
        this.fbo = gl.createFramebuffer();
        this.rbo = gl.createRenderbuffer();
        gl.bindRenderbuffer(gl.RENDERBUFFER, this.rbo);
        gl.renderbufferStorage(gl.RENDERBUFFER, gl.RGBA8, w, h);
        gl.bindFramebuffer(gl.FRAMEBUFFER, this.fbo);
        gl.framebufferRenderbuffer(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.RENDERBUFFER, this.rbo);
        this.fboSize = `${w}x${h}`;
      }
      gl.bindFramebuffer(gl.FRAMEBUFFER, this.fbo);
    }
    gl.viewport(0, 0, w, h);
    gl.useProgram(this.program);
    gl.uniform2f(u.uResolution, w, h);
    gl.uniform3fv(u.uEye, cameraEye());
    gl.uniform3fv(u.uTarget, c.target);
    gl.uniform3fv(u.uUp, c.up);
    gl.uniform1f(u.uFov, c.fov || 40);
    gl.uniform1f(u.uOrthoHeight, c.ortho || 0);
    gl.uniform1i(u.uSelLo, this.selection[0]);
    gl.uniform1i(u.uSelHi, this.selection[1]);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
    if (scale < 1) {
      gl.bindFramebuffer(gl.READ_FRAMEBUFFER, this.fbo);
      gl.bindFramebuffer(gl.DRAW_FRAMEBUFFER, null);
      gl.blitFramebuffer(0, 0, w, h, 0, 0, W, H, gl.COLOR_BUFFER_BIT, gl.LINEAR);
      gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    }
  },
  // While the view moves: half resolution now, full resolution once it rests for 200 ms.
  drawMoving() {
    if (state.viewMode !== 'preview') return;
    if (!this.movePending) {
      this.movePending = true;
      requestAnimationFrame(() => {
        this.movePending = false;
        this.frame(0.5);
      });
    }
    clearTimeout(this.rest);
    this.rest = setTimeout(() => this.draw(), 200);
  },
  draw() {
    if (state.viewMode !== 'preview') return;
    if (this.pending) return;
    this.pending = true;
    requestAnimationFrame(() => {
      this.pending = false;
      this.frame();
    });
  },
};

// Frames per second over `frames` frames at `scale` of the canvas, each waited for (readPixels
// blocks until the frame is done).
function measureFps(frames, scale = 1) {
  const gl = preview.gl;
  const px = new Uint8Array(4);
  preview.frame(scale);
  gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);
  const t0 = performance.now();
  for (let i = 0; i < frames; i++) {
    preview.frame(scale);
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);
  }
  const ms = performance.now() - t0;
  return { fps: (1000 * frames) / ms, ms_per_frame: ms / frames, width: preview.canvas.width, height: preview.canvas.height };
}

// ---- Mesh view: the server's mesh, flat shaded, optionally with its wireframe ----------------
const meshView = {
  data: null,
  prog: null,
  canvasChanged() {
    if (state.viewMode === 'mesh') this.draw();
  },
  async load() {
    $('mesh-info').textContent = 'meshing…';
    const r = await post('/api/mesh', { document: state.doc, via: $('export-via').value });
    const body = await r.json();
    if (!r.ok) {
      $('mesh-info').textContent = body.error;
      return;
    }
    const rep = body.report;
    $('mesh-info').textContent = `${$('export-via').selectedOptions[0].text}: ${rep.triangles} triangles, ` +
      `${rep.closed_manifold ? 'closed manifold' : `NOT closed: ${rep.boundary_edges} boundary, ${rep.non_manifold_edges} non-manifold edges`}, ` +
      `genus ${rep.genus}, volume ${rep.volume.toFixed(4)}, ${(rep.seconds * 1000).toFixed(0)} ms`;
    this.data = body;
    this.upload();
    this.draw();
  },
  upload() {
    const gl = preview.gl;
    if (!gl || !this.data) return;
    const pos = this.data.positions, tri = this.data.triangles;
    // Unindexed, with per-face normals and barycentrics for the wireframe.
    const n = tri.length;
    const buf = new Float32Array(n * 9);
    for (let t = 0; t < n; t += 3) {
      const a = tri[t] * 3, b = tri[t + 1] * 3, c = tri[t + 2] * 3;
      const e1 = [pos[b] - pos[a], pos[b + 1] - pos[a + 1], pos[b + 2] - pos[a + 2]];
      const e2 = [pos[c] - pos[a], pos[c + 1] - pos[a + 1], pos[c + 2] - pos[a + 2]];
      const nn = norm(cross(e1, e2));
      [a, b, c].forEach((v, k) => {
        const o = (t + k) * 9;
        buf.set([pos[v], pos[v + 1], pos[v + 2], nn[0], nn[1], nn[2], k === 0 ? 1 : 0, k === 1 ? 1 : 0, k === 2 ? 1 : 0], o);
      });
    }
    if (!this.prog) {
      const vs = `#version 300 es
in vec3 aPos; in vec3 aNormal; in vec3 aBary;
uniform mat4 uViewProj; out vec3 vNormal; out vec3 vBary;
void main() { vNormal = aNormal; vBary = aBary; gl_Position = uViewProj * vec4(aPos, 1.0); }`;
      const fs = `#version 300 es
precision highp float; in vec3 vNormal; in vec3 vBary; uniform bool uWire; out vec4 o;
void main() {
  float l = 0.15 + 0.85 * max(dot(normalize(vNormal), normalize(vec3(-0.55, 1.0, 0.45))), 0.0);
  vec3 c = vec3(0.75) * l;
  if (uWire) { vec3 w = fwidth(vBary); vec3 e = smoothstep(vec3(0.0), w * 1.2, vBary); c = mix(vec3(0.1, 0.2, 0.45), c, min(min(e.x, e.y), e.z)); }
  o = vec4(pow(c, vec3(1.0 / 2.2)), 1.0);
}`;
      const sh = (type, src) => { const s = gl.createShader(type); gl.shaderSource(s, src); gl.compileShader(s); return s; };
      const p = gl.createProgram();
      gl.attachShader(p, sh(gl.VERTEX_SHADER, vs));
      gl.attachShader(p, sh(gl.FRAGMENT_SHADER, fs));
      gl.bindAttribLocation(p, 0, 'aPos');
      gl.bindAttribLocation(p, 1, 'aNormal');
      gl.bindAttribLocation(p, 2, 'aBary');
      gl.linkProgram(p);
      this.prog = p;
      this.vao = gl.createVertexArray();
      this.vbo = gl.createBuffer();
    }
    gl.bindVertexArray(this.vao);
    gl.bindBuffer(gl.ARRAY_BUFFER, this.vbo);
    gl.bufferData(gl.ARRAY_BUFFER, buf, gl.STATIC_DRAW);
    for (let k = 0; k < 3; k++) {
      gl.enableVertexAttribArray(k);
      gl.vertexAttribPointer(k, 3, gl.FLOAT, false, 36, k * 12);
    }
    gl.bindVertexArray(null);
    this.count = n;
  },
  draw() {
    const gl = preview.gl;
    if (!gl || !this.prog || !state.camera || state.viewMode !== 'mesh') return;
    const c = state.camera;
    const eye = cameraEye();
    const f = norm(sub(c.target, eye));
    const r = norm(cross(f, c.up));
    const u = cross(r, f);
    const w = preview.canvas.width, h = preview.canvas.height;
    const near = c.dist * 0.01, far = c.dist * 10;
    // View (rows r, u, -f) then perspective, column-major.
    const view = [r[0], u[0], -f[0], 0, r[1], u[1], -f[1], 0, r[2], u[2], -f[2], 0,
      -dot(r, eye), -dot(u, eye), dot(f, eye), 1];
    let proj;
    if (c.ortho > 0) {
      const hh = c.ortho / 2, hw = hh * w / h;
      proj = [1 / hw, 0, 0, 0, 0, 1 / hh, 0, 0, 0, 0, -2 / (far - near), 0, 0, 0, -(far + near) / (far - near), 1];
    } else {
      const t = 1 / Math.tan((c.fov * Math.PI) / 360);
      proj = [t * h / w, 0, 0, 0, 0, t, 0, 0, 0, 0, (far + near) / (near - far), -1, 0, 0, (2 * far * near) / (near - far), 0];
    }
    const m = new Float32Array(16);
    for (let i = 0; i < 4; i++) for (let j = 0; j < 4; j++) {
      let s = 0;
      for (let k = 0; k < 4; k++) s += proj[k * 4 + j] * view[i * 4 + k];
      m[i * 4 + j] = s;
    }
    gl.viewport(0, 0, w, h);
    gl.clearColor(0.07, 0.07, 0.08, 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST);
    gl.useProgram(this.prog);
    gl.uniformMatrix4fv(gl.getUniformLocation(this.prog, 'uViewProj'), false, m);
    gl.uniform1i(gl.getUniformLocation(this.prog, 'uWire'), $('wireframe').checked ? 1 : 0);
    gl.bindVertexArray(this.vao);
    gl.drawArrays(gl.TRIANGLES, 0, this.count);
    gl.bindVertexArray(null);
    gl.disable(gl.DEPTH_TEST);
  },
};
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];

// ---- Save, export, check --------------------------------------------------------------------
async function save() {
  const r = await post('/api/save', { document: state.doc });
  const body = await r.json();
  if (!r.ok) {
    lastFault = body.json_path ? body.json_path.replace('$.document', '$') : null;
    say(`not saved: ${body.error}`);
    markFault();
    return false;
  }
  say(`saved ${body.saved} (${body.bytes} bytes)`, true);
  logNote(`saved ${body.saved}`);
  return true;
}
// Saves and exports are logged too, after the action they followed; they are not undoable.
function logNote(text) {
  state.notes.push({ after: state.at, text, time: new Date() });
  renderLog();
}
async function exportMesh() {
  const format = $('export-format').value, via = $('export-via').value;
  $('report').textContent = `exporting ${format} by ${via}…`;
  const t0 = performance.now();
  const r = await post('/api/export', { document: state.doc, format, via });
  if (!r.ok) {
    const body = await r.json();
    $('report').textContent = `export failed: ${body.error}`;
    return;
  }
  const rep = JSON.parse(r.headers.get('X-Bspcsg-Report'));
  const blob = await r.blob();
  const ms = performance.now() - t0;
  $('report').textContent = `export ${format} by ${via}: ${blob.size} bytes, ${rep.triangles} triangles, ` +
    `${rep.closed_manifold ? 'closed manifold' : 'NOT a closed manifold'} (boundary ${rep.boundary_edges}, non-manifold ${rep.non_manifold_edges}), ` +
    `shells ${rep.shells}, genus ${rep.genus}, volume ${rep.volume.toFixed(5)}, meshing ${(rep.seconds * 1000).toFixed(0)} ms, round trip ${ms.toFixed(0)} ms`;
  state.lastExport = rep;
  const a = document.createElement('a');
  a.href = URL.createObjectURL(blob);
  const base = (($('file').textContent || 'scene').replace(/\.json$/, '')) || 'scene';
  a.download = `${base}.${format}`;
  document.body.appendChild(a);
  a.click();
  a.remove();
  logNote(`exported ${a.download}`);
}
async function check() {
  const via = $('export-via').value;
  $('report').textContent = `checking the ${via} export against the field…`;
  const r = await post('/api/check', { document: state.doc, via });
  const b = await r.json();
  if (!r.ok) {
    $('report').textContent = `check failed to run: ${b.error}`;
    return;
  }
  const f = (x) => x.toPrecision(4);
  $('report').textContent = `check (${via}): ${b.passed ? 'PASS' : 'FAIL'}  tolerance ${f(b.tolerance)}\n` +
    `surface  max ${f(b.surface.max)} p99 ${f(b.surface.p99)} (limit ${f(b.surface.limit)})\n` +
    `coverage max ${f(b.coverage.max)} (limit ${f(b.coverage.limit)})\n` +
    `rays     ${b.rays.agreement_pct.toFixed(3)} % agree, depth p99 ${f(b.rays.depth_p99)}\n` +
    `sign     ${b.sign.agreement_pct.toFixed(3)} % agree\n` +
    `mesh     ${b.mesh.triangles} triangles, ${b.mesh.closed_manifold ? 'closed manifold' : 'NOT closed'}\n` +
    (b.failures.length ? `failures: ${b.failures.join('; ')}\n` : '') +
    `${(b.seconds * 1000).toFixed(0)} ms`;
}

// ---- Start ----------------------------------------------------------------------------------
async function start() {
  const r = await fetch('/api/scene');
  const s = await r.json();
  let doc = s.document;
  // A bare node is edited inside an envelope (the envelope is what is saved).
  if (doc && (doc.op || (doc.kind && doc.kind !== 'sdf_scene'))) doc = { kind: 'sdf_scene', version: 1, tree: doc };
  state.doc = doc;
  $('file').textContent = s.file || '';
  state.history = [];
  state.at = -1;
  record(s.exists ? `open ${s.file}` : `new scene ${s.file}`);
  if (s.error) say(s.error);
  preview.init();
  renderAll();
  $('undo').onclick = undo;
  $('redo').onclick = redo;
  $('save').onclick = save;
  $('export').onclick = exportMesh;
  $('check').onclick = check;
  for (const k of Object.keys(NEW)) $(`add-${k}`).onclick = () => addNode(k);
  $('group').onclick = () => group($('group-op').value);
  $('move-up').onclick = () => move(-1);
  $('move-down').onclick = () => move(1);
  $('delete').onclick = remove;
  $('preview-size').onchange = () => preview.resize();
  $('reset-view').onclick = () => {
    state.autoFrame = true;
    if (state.serverCamera) setCamera(state.serverCamera);
    preview.draw();
    meshView.draw();
  };
  $('set-camera').onclick = () => {
    const c = state.camera;
    if (!c) return;
    act('set the scene camera to this view', (doc) => {
      doc.camera = { eye: cameraEye(), target: [...c.target], up: c.up };
      if (c.ortho > 0) { doc.camera.projection = 'orthographic'; doc.camera.height = c.ortho; } else doc.camera.fov_deg = c.fov;
    });
    renderDocFields();
  };
  $('view-mode').onchange = () => {
    state.viewMode = $('view-mode').value;
    if (state.viewMode === 'mesh') meshView.load(); else preview.draw();
  };
  $('wireframe').onchange = () => meshView.draw();
  document.addEventListener('keydown', (e) => {
    if (!(e.ctrlKey || e.metaKey) || e.target.tagName === 'INPUT' || e.target.tagName === 'TEXTAREA') return;
    if (e.key === 'z') { e.preventDefault(); undo(); renderAll(); }
    if (e.key === 'y') { e.preventDefault(); redo(); renderAll(); }
    if (e.key === 's') { e.preventDefault(); save(); }
  });
  $('undo').addEventListener('click', renderAll);
  $('redo').addEventListener('click', renderAll);
}

// What the end-to-end test reads.
window.editor = { state, measureFps, preview, pathString, setCamera };
start();
