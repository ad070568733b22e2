// rse scheme editor: the page keeps the scheme as typed, asks the server
// (rse-core) for every preview, and draws the answer: a top-down PNG and a
// WebGL view of the box set. No third-party script.
"use strict";

// The global keys, columns, obstacle types and targets come from the
// server (GET /api/schema), which takes them from rse-core and rse-world.
let COLUMNS = [];
let TYPES = [];
const $ = (id) => document.getElementById(id);

const state = { rows: [], selected: -1, request: 0, shown: 0, lastBoxes: null, view: { yaw: -0.6, pitch: 0.9, zoom: 1.0 } };
// For tests and curious users: answers counts every preview answer (drawn
// or refused), previews the drawn ones.
window.rseEditor = { state, lastRoundTripMs: null, previews: 0, answers: 0 };

async function api(path, body) {
  const response = await fetch(path, body === undefined ? {} : {
    method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify(body),
  });
  if (!response.ok) throw new Error(`${path}: ${response.status} ${await response.text()}`);
  return response.json();
}

// --- never lose work: undo history and the draft kept in this browser -------
//
// Every edit records the page's scheme after it (typing in one field within
// HISTORY_MERGE_MS is one edit). Undo and Redo move through the records; the
// newest is also kept in the browser's storage under the file's name until it
// is saved, so a reload or a restart of the browser brings it back.

const HISTORY_MERGE_MS = 600;
const undoLog = { past: [], future: [], lastKey: null, lastAt: 0, restoring: false };
let savedText = null; // the page's scheme as the file holds it, as JSON
let fileText = null; // the server's answer for the file: a draft made from it is still good
let filePath = "";

function draftKey() { return `rse-editor:${filePath || "(unnamed)"}`; }

function snapshot() { return JSON.stringify({ scheme: pageScheme(), selected: state.selected }); }

function record(key) {
  if (undoLog.restoring) return;
  const now = performance.now();
  const text = snapshot();
  const top = undoLog.past[undoLog.past.length - 1];
  if (text === top) return;
  if (key !== null && key === undoLog.lastKey && now - undoLog.lastAt < HISTORY_MERGE_MS && undoLog.past.length > 1) {
    undoLog.past[undoLog.past.length - 1] = text;
  } else {
    undoLog.past.push(text);
  }
  undoLog.lastKey = key; undoLog.lastAt = now;
  undoLog.future = [];
  changed();
}

function restore(text) {
  undoLog.restoring = true;
  const { scheme, selected } = JSON.parse(text);
  loadScheme(scheme, selected);
  undoLog.restoring = false;
  changed();
}

function undo() {
  if (undoLog.past.length < 2) return;
  undoLog.future.push(undoLog.past.pop());
  undoLog.lastKey = null;
  restore(undoLog.past[undoLog.past.length - 1]);
}

function redo() {
  if (!undoLog.future.length) return;
  const text = undoLog.future.pop();
  undoLog.past.push(text);
  undoLog.lastKey = null;
  restore(text);
}

// The page's scheme differs from the file: say so, keep it in the browser.
function changed() {
  const scheme = JSON.stringify(pageScheme());
  const unsaved = savedText !== null && scheme !== savedText;
  $("unsaved").hidden = !unsaved;
  $("undo").disabled = undoLog.past.length < 2;
  $("redo").disabled = !undoLog.future.length;
  try {
    if (unsaved) localStorage.setItem(draftKey(), JSON.stringify({ scheme: pageScheme(), base: fileText }));
    else localStorage.removeItem(draftKey());
  } catch (e) { /* storage full or refused: the page still works, only without the draft */ }
}

function startHistory(scheme, path, draft) {
  filePath = path || "";
  $("file-name").textContent = filePath || "(not saved yet)";
  fileText = JSON.stringify(scheme);
  undoLog.past = []; undoLog.future = []; undoLog.lastKey = null;
  loadScheme(scheme);
  savedText = JSON.stringify(pageScheme());
  if (draft) loadScheme(draft);
  undoLog.past.push(snapshot());
  changed();
}

window.addEventListener("beforeunload", (e) => {
  if (!$("unsaved").hidden) { e.preventDefault(); e.returnValue = ""; }
});

// Ctrl+Z, Ctrl+Shift+Z and Ctrl+Y outside text fields (inside one they are
// the field's own undo).
document.addEventListener("keydown", (e) => {
  const typing = e.target instanceof HTMLElement && e.target.matches("input:not([type=checkbox]):not([type=file]), textarea");
  if (typing || !(e.ctrlKey || e.metaKey)) return;
  const key = e.key.toLowerCase();
  if (key === "z" && !e.shiftKey) { e.preventDefault(); undo(); }
  else if ((key === "z" && e.shiftKey) || key === "y") { e.preventDefault(); redo(); }
});
$("undo").onclick = undo;
$("redo").onclick = redo;

// --- the scheme as the page holds it ----------------------------------------

function pageScheme() {
  const globals = {};
  document.querySelectorAll("[data-global]").forEach((input) => { globals[input.dataset.global] = input.value.trim(); });
  const obstacles = state.rows.map((row) => {
    const out = { type: row.type };
    // Each column's two inputs as they are: the server joins a range.
    for (const c of COLUMNS) out[c] = [row[c + ".lo"] ?? "", row[c + ".hi"] ?? ""];
    return out;
  });
  return { globals, obstacles, notes: $("notes").value };
}

function loadScheme(scheme, selected) {
  document.querySelectorAll("[data-global]").forEach((input) => { input.value = scheme.globals[input.dataset.global] ?? ""; });
  $("notes").value = scheme.notes ?? "";
  state.rows = scheme.obstacles.map((o) => {
    const row = { type: o.type };
    for (const c of COLUMNS) { const [lo, hi] = o[c] ?? ["", ""]; row[c + ".lo"] = lo; row[c + ".hi"] = hi; }
    return row;
  });
  state.selected = selected ?? (state.rows.length ? 0 : -1);
  renderTable();
  refresh();
}

function renderTable() {
  const body = document.querySelector("#table tbody");
  body.replaceChildren();
  state.rows.forEach((row, i) => {
    const tr = document.createElement("tr");
    tr.dataset.row = i;
    if (i === state.selected) tr.classList.add("selected");
    // The obstacle the user last touched, by pointer or keyboard, is the
    // one Delete, Copy and Move act on.
    const select_row = () => { state.selected = i; document.querySelectorAll("#table tbody tr").forEach((r) => r.classList.toggle("selected", Number(r.dataset.row) === i)); };
    tr.addEventListener("click", select_row);
    tr.addEventListener("focusin", select_row);
    const num = document.createElement("td"); num.textContent = i + 1; tr.append(num);
    const typeCell = document.createElement("td");
    const select = document.createElement("select");
    select.dataset.field = "type";
    select.setAttribute("aria-label", `type of obstacle ${i + 1}`);
    for (const t of TYPES) { const option = document.createElement("option"); option.value = option.textContent = t; select.append(option); }
    select.value = row.type;
    select.addEventListener("change", () => { row.type = select.value; record(null); refresh(); });
    typeCell.append(select); tr.append(typeCell);
    for (const c of COLUMNS) {
      const td = document.createElement("td");
      for (const part of ["lo", "hi"]) {
        const input = document.createElement("input");
        input.dataset.field = c; input.dataset.part = part;
        input.className = part; input.value = row[`${c}.${part}`] ?? "";
        input.title = part === "lo" ? c : `${c}: high end of a random range`;
        // Names a screen reader reads and tests find the fields by.
        input.setAttribute("aria-label", part === "lo" ? `${c} of obstacle ${i + 1}` : `${c} range high end of obstacle ${i + 1}`);
        input.addEventListener("input", () => { row[`${c}.${part}`] = input.value; record(`${i}.${c}.${part}`); refresh(); });
        td.append(input);
      }
      tr.append(td);
    }
    body.append(tr);
  });
}

// --- table tools --------------------------------------------------------------

function edit(change) { change(); renderTable(); record(null); refresh(); }
$("add").onclick = () => edit(() => { state.rows.push({ type: "random", "height.lo": "1" }); state.selected = state.rows.length - 1; });
$("copy").onclick = () => edit(() => { if (state.selected < 0) return; state.rows.splice(state.selected + 1, 0, { ...state.rows[state.selected] }); state.selected += 1; });
$("delete").onclick = () => edit(() => { if (state.selected < 0) return; state.rows.splice(state.selected, 1); state.selected = Math.min(state.selected, state.rows.length - 1); });
function move(by) {
  const i = state.selected, j = i + by;
  if (i < 0 || j < 0 || j >= state.rows.length) return;
  [state.rows[i], state.rows[j]] = [state.rows[j], state.rows[i]];
  state.selected = j;
}
$("up").onclick = () => edit(() => move(-1));
$("down").onclick = () => edit(() => move(1));
$("notes").addEventListener("input", () => { record("notes"); refresh(); });
$("seed").addEventListener("input", refresh);
$("index").addEventListener("input", refresh);
$("redraw").onclick = () => { $("index").value = String((Number($("index").value) || 0) + 1); refresh(); };

// --- preview -----------------------------------------------------------------

function markError(error) {
  document.querySelectorAll(".invalid").forEach((e) => { e.classList.remove("invalid"); e.removeAttribute("aria-invalid"); });
  $("error").textContent = "";
  if (!error) return;
  let where = "";
  let targets = [];
  if (error.row !== null && error.row !== undefined) {
    where = `obstacle ${error.row + 1}${error.field ? ", " + error.field : ""}: `;
    const tr = document.querySelector(`#table tbody tr[data-row="${error.row}"]`);
    if (tr) targets = error.field ? [...tr.querySelectorAll(`[data-field="${error.field}"]`)] : [...tr.querySelectorAll("input, select")];
  } else if (error.field) {
    where = `${error.field}: `;
    targets = [...document.querySelectorAll(`[data-global="${error.field}"]`)];
  }
  for (const t of targets) { t.classList.add("invalid"); t.setAttribute("aria-invalid", "true"); t.title = error.message; }
  $("error").textContent = where + error.message;
}

// A number field as the API takes it: null when empty, so the server's
// default rules (the scheme's `# seed:` and `# amount:`).
function given(id) {
  const text = $(id).value.trim();
  return text === "" ? null : Number(text);
}

async function refresh() {
  const id = ++state.request;
  const started = performance.now();
  let answer;
  try {
    answer = await api("/api/preview", { scheme: pageScheme(), seed: given("seed"), index: given("index") });
  } catch (e) { $("error").textContent = String(e.message); return; }
  if (id < state.shown) return; // an older answer arriving late
  state.shown = id;
  if (!answer.ok) { markError(answer.error); window.rseEditor.answers += 1; return; }
  markError(null);
  const img = $("heatmap");
  await new Promise((resolve) => { img.onload = resolve; img.onerror = resolve; img.src = answer.png; });
  drawBlocks(answer);
  const ms = performance.now() - started;
  window.rseEditor.lastRoundTripMs = ms;
  window.rseEditor.previews += 1;
  window.rseEditor.answers += 1;
  $("timing").textContent = `${answer.nx}×${answer.ny}, preview in ${ms.toFixed(1)} ms`;
}

// --- the 3D view: the box set in WebGL -------------------------------------------

const gl = $("blocks").getContext("webgl", { preserveDrawingBuffer: true });
const program = (() => {
  const compile = (type, source) => { const s = gl.createShader(type); gl.shaderSource(s, source); gl.compileShader(s); return s; };
  const p = gl.createProgram();
  gl.attachShader(p, compile(gl.VERTEX_SHADER, `
    attribute vec3 position; attribute vec3 normal; attribute vec3 colour;
    uniform mat4 view; varying vec3 shade;
    void main() {
      float light = 0.45 + 0.55 * max(dot(normal, normalize(vec3(0.4, 0.3, 0.85))), 0.0);
      shade = colour * light; gl_Position = view * vec4(position, 1.0);
    }`));
  gl.attachShader(p, compile(gl.FRAGMENT_SHADER, `
    precision mediump float; varying vec3 shade;
    void main() { gl_FragColor = vec4(shade, 1.0); }`));
  gl.linkProgram(p);
  return p;
})();
const buffer = gl.createBuffer();
let vertexCount = 0, sceneSize = 1, sceneCentre = [0, 0, 0];

function palette(t) { // blue → green → red, as the preview
  const v = Math.round(t * 510);
  return v <= 255 ? [0, v / 255, (255 - v) / 255] : [(v - 255) / 255, (510 - v) / 255, 0];
}

function drawBlocks(answer) {
  // Filled in place (5 faces x 6 vertices x 9 floats a box): building a JS
  // array with push(...) first cost more than the server's whole answer.
  const data = new Float32Array(answer.boxes.length * 5 * 6 * 9);
  let n = 0;
  let maxTop = 1e-9, minTop = Infinity;
  for (const b of answer.boxes) { maxTop = Math.max(maxTop, 2 * b[5]); minTop = Math.min(minTop, 2 * b[5]); }
  minTop = Math.min(minTop, maxTop);
  const faces = [ // normal, then four corners as signs of the half sizes
    [[0, 0, 1], [[-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]]],
    [[1, 0, 0], [[1, -1, -1], [1, 1, -1], [1, 1, 1], [1, -1, 1]]],
    [[-1, 0, 0], [[-1, 1, -1], [-1, -1, -1], [-1, -1, 1], [-1, 1, 1]]],
    [[0, 1, 0], [[1, 1, -1], [-1, 1, -1], [-1, 1, 1], [1, 1, 1]]],
    [[0, -1, 0], [[-1, -1, -1], [1, -1, -1], [1, -1, 1], [-1, -1, 1]]],
  ];
  for (const [cx, cy, cz, hx, hy, hz] of answer.boxes) {
    const colour = palette(maxTop > minTop ? (2 * hz - minTop) / (maxTop - minTop) : 0.5);
    for (const [normal, corners] of faces) {
      const p = corners.map(([sx, sy, sz]) => [cx + sx * hx, cy + sy * hy, cz + sz * hz]);
      for (const k of [0, 1, 2, 0, 2, 3]) { data.set(p[k], n); data.set(normal, n + 3); data.set(colour, n + 6); n += 9; }
    }
  }
  vertexCount = data.length / 9;
  const s = answer.block_size;
  sceneSize = Math.max(answer.nx, answer.ny) * s;
  sceneCentre = [answer.nx * s / 2, answer.ny * s / 2, 0];
  gl.bindBuffer(gl.ARRAY_BUFFER, buffer);
  gl.bufferData(gl.ARRAY_BUFFER, data, gl.STATIC_DRAW);
  render();
}

function multiply(a, b) {
  const out = new Array(16).fill(0);
  for (let i = 0; i < 4; i++) for (let j = 0; j < 4; j++) for (let k = 0; k < 4; k++) out[j * 4 + i] += a[k * 4 + i] * b[j * 4 + k];
  return out;
}

function render() {
  const { yaw, pitch, zoom } = state.view;
  const distance = 1.6 * sceneSize / zoom;
  const eye = [
    sceneCentre[0] + distance * Math.cos(pitch) * Math.sin(yaw),
    sceneCentre[1] - distance * Math.cos(pitch) * Math.cos(yaw),
    sceneCentre[2] + distance * Math.sin(pitch),
  ];
  const f = sceneCentre.map((c, i) => c - eye[i]); const fl = Math.hypot(...f); f.forEach((v, i) => { f[i] = v / fl; });
  const up = [0, 0, 1];
  const r = [f[1] * up[2] - f[2] * up[1], f[2] * up[0] - f[0] * up[2], f[0] * up[1] - f[1] * up[0]];
  const rl = Math.hypot(...r) || 1; r.forEach((v, i) => { r[i] = v / rl; });
  const u = [r[1] * f[2] - r[2] * f[1], r[2] * f[0] - r[0] * f[2], r[0] * f[1] - r[1] * f[0]];
  const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const lookAt = [r[0], u[0], -f[0], 0, r[1], u[1], -f[1], 0, r[2], u[2], -f[2], 0, -dot(r, eye), -dot(u, eye), dot(f, eye), 1];
  const aspect = gl.canvas.width / gl.canvas.height, near = distance / 50, far = distance * 4, t = 1 / Math.tan(0.4);
  const perspective = [t / aspect, 0, 0, 0, 0, t, 0, 0, 0, 0, (far + near) / (near - far), -1, 0, 0, 2 * far * near / (near - far), 0];
  gl.viewport(0, 0, gl.canvas.width, gl.canvas.height);
  gl.clearColor(0.87, 0.87, 0.92, 1); gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
  gl.enable(gl.DEPTH_TEST);
  gl.useProgram(program);
  gl.uniformMatrix4fv(gl.getUniformLocation(program, "view"), false, new Float32Array(multiply(perspective, lookAt)));
  gl.bindBuffer(gl.ARRAY_BUFFER, buffer);
  const attribute = (name, offset) => { const a = gl.getAttribLocation(program, name); gl.enableVertexAttribArray(a); gl.vertexAttribPointer(a, 3, gl.FLOAT, false, 36, offset); };
  attribute("position", 0); attribute("normal", 12); attribute("colour", 24);
  gl.drawArrays(gl.TRIANGLES, 0, vertexCount);
}

(() => { // orbit with the mouse, zoom with the wheel
  const canvas = $("blocks");
  let drag = null;
  canvas.addEventListener("mousedown", (e) => { drag = [e.clientX, e.clientY]; });
  window.addEventListener("mouseup", () => { drag = null; });
  window.addEventListener("mousemove", (e) => {
    if (!drag) return;
    state.view.yaw += (e.clientX - drag[0]) * 0.01;
    state.view.pitch = Math.min(1.5, Math.max(0.05, state.view.pitch + (e.clientY - drag[1]) * 0.01));
    drag = [e.clientX, e.clientY];
    render();
  });
  canvas.addEventListener("wheel", (e) => { e.preventDefault(); state.view.zoom = Math.min(8, Math.max(0.3, state.view.zoom * (e.deltaY < 0 ? 1.1 : 0.9))); render(); });
})();

// --- files and generation ----------------------------------------------------

$("load").addEventListener("change", async () => {
  const file = $("load").files[0];
  if (!file) return;
  const answer = await api("/api/parse", { csv: await file.text() });
  if (answer.ok) { loadScheme(answer.scheme); record(null); } else markError(answer.error);
});

$("save").onclick = async () => {
  const path = $("save-path").value.trim();
  let answer;
  try {
    answer = await api("/api/save", { scheme: pageScheme(), path });
  } catch (e) {
    $("status").textContent = `not saved: the editor's server did not answer (${e.message}); your edits are kept in this browser`;
    return;
  }
  if (!answer.ok) { $("status").textContent = "not saved"; markError(answer.error); return; }
  $("status").textContent = `saved ${answer.path}`;
  // The file is now what the page holds: the draft goes, the name stays.
  try { localStorage.removeItem(draftKey()); } catch (e) { /* nothing kept */ }
  filePath = answer.path;
  $("file-name").textContent = filePath;
  fileText = JSON.stringify(answer.scheme);
  savedText = JSON.stringify(pageScheme());
  changed();
};

// The canonical CSV Save would write, as a file the browser saves: named
// as the file the page edits (or scheme.csv).
$("download").onclick = async () => {
  let answer;
  try {
    answer = await api("/api/csv", { scheme: pageScheme() });
  } catch (e) {
    $("status").textContent = `no download: the editor's server did not answer (${e.message})`;
    return;
  }
  if (!answer.ok) { $("status").textContent = "no download: the scheme has an error"; markError(answer.error); return; }
  const link = document.createElement("a");
  link.href = URL.createObjectURL(new Blob([answer.csv], { type: "text/csv" }));
  link.download = (filePath.split(/[\\/]/).pop() || "scheme.csv");
  document.body.append(link);
  link.click();
  link.remove();
  setTimeout(() => URL.revokeObjectURL(link.href), 1000);
};

$("generate").onclick = async () => {
  const targets = [...document.querySelectorAll("#gen-targets input:checked")].map((i) => i.value);
  $("gen-summary").textContent = ""; $("gen-check").textContent = "";
  const answer = await api("/api/generate", {
    scheme: pageScheme(), out: $("gen-out").value.trim(), amount: given("gen-amount"),
    seed: given("seed"), targets,
  });
  if (!answer.ok) { markError(answer.error); return; }
  const poll = async () => {
    const job = await api("/api/job");
    $("gen-progress").max = Math.max(1, job.total); $("gen-progress").value = job.done;
    if (job.running || (!job.summary && !job.error)) { setTimeout(poll, 100); return; }
    $("gen-summary").textContent = job.error ? `failed: ${job.error}` : job.summary;
    $("gen-check").textContent = job.check ?? "";
  };
  poll();
};

// The fields the schema names: one input per global, a header cell per
// column, a checkbox per target (the default ones ticked).
function buildFields(schema) {
  COLUMNS = schema.columns;
  TYPES = schema.types.map((t) => t.name);
  const globals = $("global-fields");
  for (const g of schema.globals) {
    const label = document.createElement("label");
    const input = document.createElement("input");
    input.dataset.global = g.key; input.placeholder = g.default;
    input.addEventListener("input", () => { record(`global.${g.key}`); refresh(); });
    label.append(`${g.key.replaceAll("_", " ")}${g.unit ? ` (${g.unit})` : ""} `, input);
    globals.append(label);
  }
  const head = document.querySelector("#table thead tr");
  for (const c of COLUMNS) { const th = document.createElement("th"); th.textContent = c; head.append(th); }
  const targets = $("gen-targets");
  for (const t of schema.targets) {
    const label = document.createElement("label");
    const box = document.createElement("input");
    box.type = "checkbox"; box.value = t; box.checked = schema.default_targets.includes(t);
    label.append(box, ` ${t}`);
    targets.append(label);
  }
}

api("/api/schema").then(async (schema) => {
  buildFields(schema);
  const answer = await api("/api/state");
  if (answer.path) $("save-path").value = answer.path;
  // A draft this browser kept for this file wins, if it was made from what
  // the file still holds (else the file changed since: the file wins).
  let draft = null;
  try {
    const kept = JSON.parse(localStorage.getItem(`rse-editor:${answer.path || "(unnamed)"}`) ?? "null");
    if (kept && kept.base === JSON.stringify(answer.scheme)) draft = kept.scheme;
  } catch (e) { /* no draft */ }
  startHistory(answer.scheme, answer.path, draft);
  if (draft) $("status").textContent = "unsaved changes restored from this browser";
});
