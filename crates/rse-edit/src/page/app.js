// rse scheme editor: the page keeps the scheme as typed, asks the server
// (rse-core) for every preview and draws the answer's heights twice: the
// top-down map (map.js), which also edits points and walls, and the 3D view
// (view3d.js). Edits are undoable and kept in this browser until saved. No
// third-party script.
"use strict";

import { decodePreview, legendHeights, palette } from "./colours.js";
import { TopView } from "./map.js";
import { BlockView } from "./view3d.js";

// The global keys, columns, obstacle types, mesh modes and targets come
// from the server (GET /api/schema), which takes them from rse-core and
// rse-world, tooltips included.
let COLUMNS = [];
let TYPE_COLUMNS = {}; // type → column → "required" | "optional" | "unused"
let GLOBAL_DEFAULTS = {};
const $ = (id) => document.getElementById(id);

const state = { rows: [], selected: -1 };
// For tests and curious users: `requests` counts previews asked for,
// `answers` every answer (drawn or refused), `previews` the maps drawn,
// `views` the 3D views built.
window.rseEditor = {
  state, lastRoundTripMs: null, lastViewMs: null, previews: 0, answers: 0, requests: 0, views: 0, preview: null,
  inFlight: 0, mostInFlight: 0, // previews on their way now, and at most at once
  draftsSent: 0, draftPending: false, // drafts the server took, and one waiting or on its way
};

/** The server's JSON answer; throws `Lost` when the server cannot be
 * reached (then the page says so and retries, see `connectionLost`). */
class Lost extends Error {}
async function api(path, body) {
  let response;
  try {
    response = await fetch(path, body === undefined ? {} : {
      method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify(body),
    });
  } catch (e) {
    connectionLost();
    throw new Lost("the editor's server did not answer");
  }
  if (!response.ok) throw new Error(REFUSED_BECAUSE[response.status] ?? `the editor's server failed to answer (error ${response.status}); try again`);
  return response.json();
}

// The server's own refusals of a request, in words (its text is for
// programs: "payload too large").
const REFUSED_BECAUSE = {
  403: "the editor's server refused this page: open the editor at the address it printed when it started",
  413: "the scheme is too large to send to the editor's server (over 1 MiB)",
  431: "the editor's server refused this page's request (too long)",
};

// --- a lost server: say so, retry, carry on --------------------------------

let retrying = null;
function connectionLost() {
  const banner = $("connection");
  banner.textContent = "The editor's server is not answering (is `rse-gen edit` still running?). Retrying every 2 seconds; your edits are kept in this browser.";
  banner.hidden = false;
  if (retrying) return;
  retrying = setInterval(async () => {
    try {
      const response = await fetch("/api/schema");
      if (!response.ok) return;
    } catch (e) { return; }
    clearInterval(retrying); retrying = null;
    banner.hidden = true;
    $("status").textContent = "connected to the editor's server again";
    sendDraft(); // what was edited meanwhile
    refresh();
  }, 2000);
}

// --- never lose work: undo history and the draft kept in this browser -------
//
// Every edit records the page's scheme after it (typing in one field, until
// the focus leaves it, is one edit; a drag on the map is one edit; a
// selection alone is none). Undo and Redo move through the records. The draft — the page's scheme, unsaved or
// not, and its undo history — is kept by the server per file (any port,
// reload or browser finds it) and, for when the server is gone, in this
// browser's storage too.

const undoLog = { past: [], future: [], lastKey: null, restoring: false };
const file = {
  doc: "", // the document the draft belongs to: `server`, or `unnamed:ID` for a scheme in no file yet
  revision: 0, // the revision of its draft this tab read or wrote last
  path: "", // the file Save writes ("" : none yet, Save asks)
  name: "", // what the header shows
  server: "", // the file the server starts a reload from
  base: null, // the server's scheme for it, as JSON: a draft made from it is still good
  saved: null, // the page's scheme as that file holds it, as JSON (null: not on disk)
  suggestion: "", // the name of a file picked from this computer, offered by Save as
  opened: null, // the scheme of a document in no file as it was opened, as JSON
};

/** Where this browser keeps the draft of the document `of`. */
function draftKey(of = file.doc) { return `rse-editor:${of || "(unnamed)"}`; }

/** This page load's own name among the tabs on one draft. */
const TAB = newId();

/** A fresh id: for a tab, or for a document in no file yet. */
function newId() {
  if (crypto.randomUUID) return crypto.randomUUID();
  return `${Date.now().toString(36)}-${Math.random().toString(36).slice(2, 12)}`;
}

function snapshot() { return JSON.stringify({ scheme: pageScheme(), selected: state.selected }); }

function record(key) {
  if (undoLog.restoring) return;
  const text = snapshot();
  const top = undoLog.past[undoLog.past.length - 1];
  if (text === top) return;
  // Selecting changes nothing to undo: the newest step keeps the new
  // selection (once 19 Undo presses in a row did nothing visible).
  if (top && schemeOf(top) === JSON.stringify(pageScheme())) {
    undoLog.past[undoLog.past.length - 1] = text;
    return;
  }
  if (key !== null && key === undoLog.lastKey && undoLog.past.length > 1) {
    undoLog.past[undoLog.past.length - 1] = text;
  } else {
    undoLog.past.push(text);
  }
  undoLog.lastKey = key;
  undoLog.future = [];
  changed();
}

/** The scheme of a history step, as JSON text. */
function schemeOf(step) {
  try { return JSON.stringify(JSON.parse(step).scheme); } catch (e) { return ""; }
}

// A field's typing ends when the focus leaves it: the next is a new step.
document.addEventListener("focusout", () => { undoLog.lastKey = null; });

function restore(text) {
  undoLog.restoring = true;
  const focus = focusedField();
  const { scheme, selected } = JSON.parse(text);
  loadScheme(scheme, selected);
  refocus(focus);
  undoLog.restoring = false;
  changed();
}

/** Which field of the scheme has the focus (a table cell, a global, the
 * notes), to give it back after the table is drawn again. */
function focusedField() {
  const e = document.activeElement;
  if (!(e instanceof HTMLElement)) return null;
  if (e.dataset.global) return `[data-global="${e.dataset.global}"]`;
  if (e.id === "notes") return "#notes";
  const tr = e.closest("#table tbody tr");
  if (tr && e.dataset.field) {
    const part = e.dataset.part ? `[data-part="${e.dataset.part}"]` : "";
    return `#table tbody tr[data-row="${tr.dataset.row}"] [data-field="${e.dataset.field}"]${part}`;
  }
  return null;
}

function refocus(selector) {
  const e = selector && document.querySelector(selector);
  if (!e || e.disabled) return;
  e.focus();
  if (typeof e.value === "string" && e.setSelectionRange && e.type !== "checkbox") e.setSelectionRange(e.value.length, e.value.length);
}

// One user action is one step whatever made it: a map grab still held
// when Undo or Redo comes (by key, mid-drag) is let go first, so it is the
// step Undo takes back (and Redo brings back), not lost with the one
// before it.
function undo() {
  map.letGo();
  if (undoLog.past.length < 2) return;
  undoLog.future.push(undoLog.past.pop());
  undoLog.lastKey = null;
  restore(undoLog.past[undoLog.past.length - 1]);
}

function redo() {
  map.letGo();
  if (!undoLog.future.length) return;
  const text = undoLog.future.pop();
  undoLog.past.push(text);
  undoLog.lastKey = null;
  restore(text);
}

// The page's scheme differs from the file: say so, keep it in the browser.
function changed() {
  const scheme = JSON.stringify(pageScheme());
  const unsaved = scheme !== file.saved;
  $("unsaved").hidden = !unsaved;
  // "saved …" beside "unsaved" would say two things at once.
  if (unsaved && $("status").textContent.startsWith("saved ")) say("");
  // A file in the working folder (shown beside it) by its path from there.
  const folder = $("work-folder").textContent;
  const shown = folder && file.name.startsWith(`${folder}/`) ? file.name.slice(folder.length + 1) : file.name;
  $("file-name").textContent = shown || "(not saved yet)";
  $("file-name").title = file.name || "(not saved yet)";
  $("undo").disabled = undoLog.past.length < 2;
  $("redo").disabled = !undoLog.future.length;
  try {
    if (unsaved) localStorage.setItem(draftKey(), JSON.stringify(draft(true)));
    else localStorage.removeItem(draftKey());
  } catch (e) { /* storage full or refused: the page still works, only without the draft */ }
  keepDraft();
}

// --- the draft, kept by the server per file ------------------------------------

const DRAFT_DELAY_MS = 250; // edits a quarter second apart are sent once
const HISTORY_KEPT = 100; // undo steps kept each way
const DRAFT_MAX_CHARS = 900_000; // under the server's 1 MiB request cap
const drafts = { timer: null };

/** What a reload (on any port, in any browser) starts from: the page's
 * scheme, whether it differs from the file, what the file held when it was
 * made (a draft of an older file is not used), and the undo history: its
 * last HISTORY_KEPT steps each way, the oldest dropped first while the
 * draft is over DRAFT_MAX_CHARS (a long table's steps are large). */
function draft(unsaved) {
  let keep = HISTORY_KEPT;
  for (;;) {
    const kept = {
      scheme: pageScheme(), unsaved, base: file.base, path: file.path, name: file.name,
      suggestion: file.suggestion, opened: file.opened,
      past: undoLog.past.slice(-keep), future: undoLog.future.slice(-keep),
    };
    if (keep <= 1 || JSON.stringify(kept).length <= DRAFT_MAX_CHARS) return kept;
    keep = Math.floor(keep / 2);
  }
}

function keepDraft() {
  clearTimeout(drafts.timer);
  drafts.timer = setTimeout(sendDraft, DRAFT_DELAY_MS);
  window.rseEditor.draftPending = true;
}

/** Sends the draft of the page's document (`forget`: that there is none;
 * `of`: another document's). With the server gone it is not sent: the
 * browser's copy stands, and the next change (or the server's return)
 * sends it. Another tab's draft written since this tab read it is not
 * overwritten: the server answers with it, and the page offers both. */
function sendDraft({ keepalive = false, forget = false, of = file.doc, force = false } = {}) {
  clearTimeout(drafts.timer); drafts.timer = null;
  const mine = of === file.doc;
  const body = JSON.stringify({
    file: of, draft: forget ? null : draft(!$("unsaved").hidden),
    tab: TAB, base: mine ? file.revision : 0, force, current: mine && !forget,
  });
  window.rseEditor.draftPending = true;
  fetch("/api/draft", { method: "POST", headers: { "Content-Type": "application/json" }, body, keepalive })
    .then(async (response) => {
      if (!response.ok) return;
      const answer = await response.json();
      if (!answer.conflict) window.rseEditor.draftsSent += 1;
      if (!mine || of !== file.doc) return; // the page moved on meanwhile
      if (answer.conflict) offerBoth(answer.theirs, answer.revision);
      else if (answer.revision) file.revision = answer.revision;
    })
    .catch(() => {})
    .finally(() => { window.rseEditor.draftPending = drafts.timer !== null; });
}

/** Another tab (or window, or browser) changed this document's draft since
 * this page read it: nothing is overwritten unasked. The user keeps this
 * page's scheme (written over theirs) or takes theirs (this page's stays
 * one Undo away). */
let offering = false;
async function offerBoth(theirs, revision) {
  if (offering) return;
  offering = true;
  const dialog = $("conflict-dialog");
  dialog.returnValue = "";
  dialog.showModal();
  const choice = await new Promise((resolve) => dialog.addEventListener("close", () => resolve(dialog.returnValue), { once: true }));
  offering = false;
  file.revision = revision;
  if (choice === "theirs" && theirs && theirs.scheme) {
    loadScheme(theirs.scheme);
    record(null);
    say("took the other tab's version (Undo brings this tab's back)");
  } else {
    say("kept this tab's version");
  }
  sendDraft({ force: true });
}
// A reload or a closed tab within the quarter second still sends the last edit.
window.addEventListener("pagehide", () => { if (drafts.timer) sendDraft({ keepalive: true }); });

/** Forgets the draft of the document `of`: saved or discarded. */
function forgetDraft(of) {
  try { localStorage.removeItem(draftKey(of)); } catch (e) { /* nothing kept */ }
  sendDraft({ forget: true, of });
}

/** Empties Undo and Redo: a file opened is a new document. */
function forgetHistory() { undoLog.past = []; undoLog.future = []; undoLog.lastKey = null; }

/** Starts editing `scheme`, the server's file `server` (its answer), with
 * the draft the server kept for it (`kept`, or null): that draft, else one
 * this browser kept, wins if it was made from what the file still holds
 * (else the file changed since, and the file wins). A draft brings back
 * the unsaved scheme and the undo history. */
function startFile(scheme, server, kept, revision = 0, newFile = false) {
  file.server = server || "";
  file.doc = file.server;
  file.revision = revision;
  file.path = file.server; file.name = file.server;
  file.base = JSON.stringify(scheme);
  file.opened = null;
  forgetHistory();
  loadScheme(scheme);
  // A file named on the command line that is not there yet: a new scheme
  // Save writes there.
  file.saved = newFile ? null : JSON.stringify(pageScheme());
  let found = kept && kept.base === file.base ? kept : null;
  if (!found) {
    try {
      const local = JSON.parse(localStorage.getItem(draftKey()) ?? "null");
      if (local && local.base === file.base) found = local;
    } catch (e) { /* no draft */ }
  }
  if (found && found.unsaved !== false && found.scheme) {
    loadScheme(found.scheme);
    file.path = found.path ?? file.path; file.name = found.name ?? file.name;
    say("unsaved changes restored");
  }
  takeHistory(found);
  changed();
}

/** Undo and Redo from the draft `kept` (if it has them), ending at the
 * page's scheme (a draft's history does; a file's starts there). */
function takeHistory(kept) {
  if (kept && Array.isArray(kept.past) && kept.past.length) {
    undoLog.past = kept.past.filter((t) => typeof t === "string");
    undoLog.future = Array.isArray(kept.future) ? kept.future.filter((t) => typeof t === "string") : [];
  }
  const top = undoLog.past[undoLog.past.length - 1];
  if (!top || schemeOf(top) !== JSON.stringify(pageScheme())) undoLog.past.push(snapshot());
}

window.addEventListener("beforeunload", (e) => {
  if (!$("unsaved").hidden) { e.preventDefault(); e.returnValue = ""; }
});

// Ctrl+Z, Ctrl+Shift+Z and Ctrl+Y are the editor's Undo and Redo wherever
// the focus is, text fields included (their own undo once undid another
// field and the notes letter by letter, recorded as new edits, wiping
// Redo); only inside a dialog are they the dialog field's own. The
// browser's Edit menu undo is turned the same way.
function inDialog(target) { return target instanceof Element && target.closest("dialog") !== null; }
document.addEventListener("keydown", (e) => {
  if (!(e.ctrlKey || e.metaKey) || e.altKey || inDialog(e.target)) return;
  const key = e.key.toLowerCase();
  if (key === "z" && !e.shiftKey) { e.preventDefault(); undo(); }
  else if ((key === "z" && e.shiftKey) || key === "y") { e.preventDefault(); redo(); }
});
document.addEventListener("beforeinput", (e) => {
  if (inDialog(e.target)) return;
  if (e.inputType === "historyUndo") { e.preventDefault(); undo(); }
  else if (e.inputType === "historyRedo") { e.preventDefault(); redo(); }
});
$("undo").onclick = undo;
$("redo").onclick = redo;

function say(text) { $("status").textContent = text; }

// --- the scheme as the page holds it ----------------------------------------

/** A global's text as the file would hold it ("" : not given). */
function globalText(input) {
  if (input.type === "checkbox") return input.dataset.explicit === "1" ? String(input.checked) : "";
  return input.value.trim();
}

function pageScheme() {
  const globals = {};
  document.querySelectorAll("[data-global]").forEach((input) => { globals[input.dataset.global] = globalText(input); });
  const obstacles = state.rows.map((row) => {
    const out = { type: row.type };
    // Each column's two inputs as they are: the server joins a range.
    for (const c of COLUMNS) out[c] = [row[c + ".lo"] ?? "", row[c + ".hi"] ?? ""];
    return out;
  });
  return { globals, obstacles, notes: $("notes").value };
}

function loadScheme(scheme, selected) {
  document.querySelectorAll("[data-global]").forEach((input) => {
    const text = scheme.globals[input.dataset.global] ?? "";
    if (input.type === "checkbox") {
      input.dataset.explicit = text === "" ? "0" : "1";
      input.checked = (text === "" ? GLOBAL_DEFAULTS[input.dataset.global] : text) === "true";
    } else input.value = text;
  });
  $("notes").value = scheme.notes ?? "";
  state.rows = scheme.obstacles.map((o) => {
    const row = { type: o.type };
    for (const c of COLUMNS) { const [lo, hi] = o[c] ?? ["", ""]; row[c + ".lo"] = lo; row[c + ".hi"] = hi; }
    return row;
  });
  state.selected = selected ?? (state.rows.length ? 0 : -1);
  renderTable();
  updateGlobals();
  refresh();
}

// Columns shown only while a row uses them (or holds a value there): the
// table keeps the width it has for the paper's obstacles, which leave them
// unused, and gains them with a pyramid.
const SHOWN_WHEN_USED = new Set(["tread"]);

/** Whether the table shows column `c` now. */
function shown(c) {
  return !SHOWN_WHEN_USED.has(c) || state.rows.some((r) => TYPE_COLUMNS[r.type]?.[c] !== "unused" || r[`${c}.lo`] || r[`${c}.hi`]);
}

/** Whether `row` leaves column `c` unused (and empty: a value there stays
 * editable, so its error can be fixed). */
function unused(row, c) {
  return TYPE_COLUMNS[row.type]?.[c] === "unused" && !row[`${c}.lo`] && !row[`${c}.hi`];
}

function select(i) {
  if (i !== map.placing) map.stopPlacing();
  state.selected = i;
  document.querySelectorAll("#table tbody tr").forEach((r) => r.classList.toggle("selected", Number(r.dataset.row) === i));
  map.drawOverlay();
}

function renderTable() {
  for (const th of document.querySelectorAll("#table thead th[data-column]")) th.hidden = !shown(th.dataset.column);
  const body = document.querySelector("#table tbody");
  body.replaceChildren();
  state.rows.forEach((row, i) => {
    const tr = document.createElement("tr");
    tr.dataset.row = i;
    if (i === state.selected) tr.classList.add("selected");
    // The obstacle the user last touched, by pointer or keyboard, is the
    // one Delete, Copy, Move and the map act on.
    tr.addEventListener("click", () => select(i));
    tr.addEventListener("focusin", () => select(i));
    const num = document.createElement("td"); num.textContent = i + 1; tr.append(num);
    const typeCell = document.createElement("td");
    const choice = document.createElement("select");
    choice.dataset.field = "type";
    choice.setAttribute("aria-label", `type of obstacle ${i + 1}`);
    choice.title = COLUMN_DOCS.type ?? "";
    for (const t of Object.keys(TYPE_COLUMNS)) { const option = document.createElement("option"); option.value = option.textContent = t; choice.append(option); }
    choice.value = row.type;
    choice.addEventListener("change", () => {
      // A type leaves some columns unused: they are emptied (Undo brings
      // them back), as the scheme refuses a value there. The columns it
      // needs that are empty get a start that works (a new pit or wall
      // once began with red errors, one at a time): the obstacle stands
      // in the middle of the grid, and the next click on the map places
      // it.
      row.type = choice.value;
      for (const c of COLUMNS) if (TYPE_COLUMNS[row.type]?.[c] === "unused") { row[`${c}.lo`] = ""; row[`${c}.hi`] = ""; }
      const placed = startValid(row);
      renderTable(); record(null); refresh();
      if (placed) {
        map.startPlacing(i);
        say(`${row.type.replaceAll("_", " ")} ${i + 1} stands in the middle: click on the map to place it`);
      }
      document.querySelector(`#table tbody tr[data-row="${i}"] select`)?.focus();
    });
    typeCell.append(choice); tr.append(typeCell);
    for (const c of COLUMNS.filter(shown)) {
      const td = document.createElement("td");
      for (const part of ["lo", "hi"]) {
        const input = document.createElement("input");
        input.dataset.field = c; input.dataset.part = part;
        input.className = part; input.value = row[`${c}.${part}`] ?? "";
        input.inputMode = "decimal";
        input.disabled = unused(row, c);
        input.title = part === "lo" ? COLUMN_DOCS[c] : `${COLUMN_DOCS[c]}: the high end of a random range`;
        // Names a screen reader reads and tests find the fields by.
        input.setAttribute("aria-label", part === "lo" ? `${c} of obstacle ${i + 1}` : `${c} range high end of obstacle ${i + 1}`);
        input.addEventListener("input", () => { row[`${c}.${part}`] = input.value; record(`${i}.${c}.${part}`); refresh(); map.drawOverlay(); });
        td.append(input);
      }
      tr.append(td);
    }
    body.append(tr);
  });
  map.drawOverlay();
}

// --- a new obstacle starts valid ---------------------------------------------

/** The grid's columns and rows: the map's, else the size field's, else 20×20. */
function gridSize() {
  const p = map.preview;
  if (p) return [p.nx, p.ny];
  const m = /^\s*(\d+)\s*[xX×*]\s*(\d+)\s*$/.exec(document.querySelector('[data-global="size"]')?.value ?? "");
  return m ? [Number(m[1]), Number(m[2])] : [20, 20];
}

/** Fills each column `row`'s type needs that is empty with a start that
 * works on this grid: height 1, angle 45°, a tread of 1, a point in the
 * middle, a wall or long pit across the middle third, a rectangle of the
 * middle third. `true` when it gave the obstacle a place on the map. */
function startValid(row) {
  const [nx, ny] = gridSize();
  const [cx, cy] = [Math.floor(nx / 2), Math.floor(ny / 2)];
  const [qx, qy] = [Math.max(1, Math.floor(nx / 6)), Math.max(1, Math.floor(ny / 6))];
  const clampX = (x) => String(Math.min(Math.max(x, 0), nx - 1));
  const clampY = (y) => String(Math.min(Math.max(y, 0), ny - 1));
  const rectangle = ["stairs", "pyramid", "pyramid_pit", "ramp", "crossing_ramps"].includes(row.type);
  const starts = {
    height: "1", angle: "45", tread: "1", sigma: "3",
    x1: clampX(cx - (row.type === "peak" || row.type === "pit" ? 0 : qx)),
    y1: clampY(cy - (rectangle ? qy : 0)),
    x2: clampX(cx + qx),
    y2: clampY(cy + (rectangle ? qy : 0)),
  };
  let placed = false;
  for (const c of COLUMNS) {
    if (TYPE_COLUMNS[row.type]?.[c] !== "required" || (row[`${c}.lo`] ?? "") !== "" || !(c in starts)) continue;
    row[`${c}.lo`] = starts[c];
    if (/^[xy][12]$/.test(c)) placed = true;
  }
  return placed;
}

// --- table tools --------------------------------------------------------------

function edit(change) { change(); renderTable(); record(null); refresh(); }
/** Focus on row `i`'s first field (its type): where a new row is edited
 * next, not dozens of Tabs away on the button that made it. */
function focusRow(i) { document.querySelector(`#table tbody tr[data-row="${i}"] select`)?.focus(); }
$("add").onclick = () => {
  edit(() => { state.rows.push({ type: "random", "height.lo": "1" }); state.selected = state.rows.length - 1; });
  focusRow(state.selected);
};
$("copy").onclick = () => {
  if (state.selected < 0) return;
  edit(() => { state.rows.splice(state.selected + 1, 0, { ...state.rows[state.selected] }); state.selected += 1; });
  // The copy lies on the original: the next click on the map places it.
  if (map.placeable(state.selected)) {
    map.startPlacing(state.selected);
    say(`the copy, ${state.rows[state.selected].type.replaceAll("_", " ")} ${state.selected + 1}, lies on the original: click on the map to place it`);
  }
  focusRow(state.selected);
};
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

// --- the map edits rows too ----------------------------------------------------

const map = new TopView({
  rows: () => state.rows,
  selected: () => state.selected,
  select,
  change(i, fields) { Object.assign(state.rows[i], fields); },
  // A drag's steps show at once (table and preview); its end is one edit.
  rendered() { renderTable(); refresh(); },
  done() { record(null); },
  // What a click does is said under the map, never in the header (an old
  // "nothing here to select" once stayed there after a reload).
  hint: (text) => { $("map-hint").textContent = text; },
});
const blocks = new BlockView($("blocks"));

// --- errors where they are ---------------------------------------------------

/** Marks the field an error concerns (`aria-invalid`, the message as its
 * tooltip and beside it: under its row in the table, under a global or a
 * Generate field) and says it under the table too; `null` clears. The
 * message once stood only under the table, off the screen with 30 rows. */
function markError(error) {
  document.querySelectorAll("[aria-invalid]").forEach((e) => {
    e.classList.remove("invalid"); e.removeAttribute("aria-invalid"); e.removeAttribute("aria-describedby");
    if (e.dataset.title !== undefined) { e.title = e.dataset.title; delete e.dataset.title; }
  });
  document.querySelectorAll(".field-error").forEach((e) => e.remove());
  $("error").textContent = "";
  if (!error) return;
  let where = "";
  let targets = [];
  if (error.control) {
    const control = $(error.control === "path" ? "dialog-path" : error.control);
    if (control) targets = [control];
    where = `${control?.labels?.[0]?.textContent ?? error.control}: `;
  } else if (error.row !== null && error.row !== undefined) {
    where = `obstacle ${error.row + 1}${error.field ? ", " + error.field : ""}: `;
    const tr = document.querySelector(`#table tbody tr[data-row="${error.row}"]`);
    if (tr) targets = error.field ? [...tr.querySelectorAll(`[data-field="${error.field}"]:not(:disabled)`)] : [...tr.querySelectorAll("input:not(:disabled), select")];
    if (error.field && targets.length === 0 && tr) targets = [...tr.querySelectorAll(`[data-field="${error.field}"]`)];
  } else if (error.field) {
    where = `${error.field.replaceAll("_", " ")}: `;
    targets = [...document.querySelectorAll(`[data-global="${error.field}"]`)];
    if (error.field === "notes") targets = [$("notes")];
  }
  for (const t of targets) {
    t.classList.add("invalid"); t.setAttribute("aria-invalid", "true");
    t.dataset.title = t.title; t.title = error.message;
    t.setAttribute("aria-describedby", "field-error");
  }
  $("error").textContent = where + error.message;
  besideTheField(targets[0], where + error.message);
}

/** The message right under the field it names: a row of its own under an
 * obstacle's row, a line under a global or a Generate field. */
function besideTheField(target, text) {
  if (!target) return;
  const note = document.createElement(target.closest("#table") ? "td" : "p");
  note.id = "field-error"; note.className = "field-error-text"; note.textContent = text;
  note.setAttribute("role", "alert");
  const tr = target.closest("#table tbody tr");
  if (tr) {
    note.colSpan = tr.children.length;
    const row = document.createElement("tr");
    row.className = "field-error";
    row.append(note);
    tr.after(row);
    return;
  }
  note.classList.add("field-error");
  // In the globals' and Generate's grids: a line of its own after the
  // field's unit.
  const after = target.nextElementSibling?.matches(".unit, span") ? target.nextElementSibling : target;
  after.after(note);
}

/** Why the pictures can be out of date, in the user's words: the scheme,
 * a failure of the server's, or a server gone (none of the last two the
 * user's doing: the edits are kept). */
const STALE_BECAUSE = {
  error: "Out of date: the scheme has an error, so these pictures show the last scheme that worked.",
  failed: "Out of date: the editor's server could not draw this scheme (the message below says why), so these pictures show the last scheme it drew.",
  server: "Out of date: the editor's server is not answering, so these pictures show the last scheme it drew. Your edits are kept; the pictures come back by themselves when it answers.",
};

/** The pictures no longer show the scheme (`why`: it has an `error`, or
 * the `server` is gone): say which and grey them out until a new preview
 * is drawn. */
function stale(yes, why = "error") {
  $("pictures").classList.toggle("stale", yes);
  $("stale").hidden = !yes;
  if (yes) {
    $("stale").textContent = STALE_BECAUSE[why];
    $("timing").textContent = "";
  }
}

// --- preview: debounced and superseded ----------------------------------------
//
// One request at a time: an edit while one is on its way only marks the
// preview dirty, and when the answer comes back it is dropped (older than
// the page's scheme) and the newest scheme is asked for instead. Typing
// "200x200" sends two or three requests, not seven, and an old answer never
// overwrites a newer picture. Nothing waits on a timer, so a single edit is
// drawn as soon as the server answers. The round trip is timed from the
// first edit not yet shown to the new map on the page.
//
// The 3D view is rebuilt once edits pause for VIEW_DELAY_MS: a 200x200 world
// is a million vertices, which a software-rendered browser takes a few
// hundred milliseconds over, and the map must not wait for it.

const VIEW_DELAY_MS = 150;
const preview = { busy: false, dirty: false, since: null, view: null };

function refresh() {
  preview.since ??= performance.now();
  if (preview.busy) { preview.dirty = true; return; }
  send();
}

async function send() {
  preview.busy = true; preview.dirty = false;
  window.rseEditor.inFlight += 1;
  window.rseEditor.mostInFlight = Math.max(window.rseEditor.mostInFlight, window.rseEditor.inFlight);
  const since = preview.since;
  preview.since = null;
  window.rseEditor.requests += 1;
  let answer;
  try {
    answer = await api("/api/preview", { scheme: pageScheme(), seed: $("seed").value, index: $("index").value });
  } catch (e) {
    preview.busy = false;
    window.rseEditor.inFlight -= 1;
    stale(true, e instanceof Lost ? "server" : "failed");
    $("error").textContent = e instanceof Lost ? "" : String(e.message);
    return;
  }
  preview.busy = false;
  window.rseEditor.inFlight -= 1;
  if (preview.dirty) { // superseded while on its way: its edits wait for the next
    preview.since = Math.min(since, preview.since ?? since);
    send();
    return;
  }
  window.rseEditor.answers += 1;
  if (!answer.ok) { markError(answer.error); stale(true); return; }
  markError(null);
  const answered = performance.now();
  const drawn = decodePreview(answer);
  window.rseEditor.preview = drawn;
  const decoded = performance.now();
  map.show(drawn);
  stale(false);
  const shown = performance.now();
  const ms = shown - since;
  // Where the time goes, for bench/editor.py.
  window.rseEditor.lastBreakdownMs = {
    server: answer.server_ms, answer: answered - since, decode: decoded - answered, map: shown - decoded,
  };
  window.rseEditor.lastRoundTripMs = ms;
  window.rseEditor.previews += 1;
  $("timing").textContent = `${answer.nx}×${answer.ny}, preview in ${ms.toFixed(1)} ms`;
  if (palletsOn()) showGrid(`${answer.nx}×${answer.ny}`);
  clearTimeout(preview.view);
  preview.view = setTimeout(() => {
    const started = performance.now();
    blocks.show(drawn);
    window.rseEditor.lastViewMs = performance.now() - started;
    window.rseEditor.views += 1;
  }, VIEW_DELAY_MS);
}

// --- files ---------------------------------------------------------------------

/** Asks for a file path in the page's dialog; null when cancelled. */
function askPath(title, suggestion) {
  const dialog = $("path-dialog");
  $("dialog-title").textContent = title;
  $("dialog-path").value = suggestion;
  $("dialog-error").textContent = "";
  // Escape closes a dialog without setting its value: the last one would stay.
  dialog.returnValue = "";
  dialog.showModal();
  return new Promise((resolve) => {
    dialog.addEventListener("close", () => resolve(dialog.returnValue === "ok" ? $("dialog-path").value.trim() : null), { once: true });
  });
}

/** Before another scheme replaces the page's: `true` to go on. With edits
 * not saved it asks, as a desktop program does: save them first (going on
 * once they are), discard them (this browser's draft of the file too), or
 * cancel. `what` says what would replace them. */
async function mayReplace(what) {
  // Nothing to lose: the page is its file, or a new scheme or sample not
  // edited since it was opened.
  if ($("unsaved").hidden || JSON.stringify(pageScheme()) === file.opened) return true;
  const dialog = $("unsaved-dialog");
  $("unsaved-text").textContent = `${file.name || "This scheme"} has edits that are not saved. ${what} replaces them.`;
  dialog.returnValue = "";
  dialog.showModal();
  const choice = await new Promise((resolve) => dialog.addEventListener("close", () => resolve(dialog.returnValue), { once: true }));
  if (choice === "save") {
    if (file.path) return saveTo(file.path);
    await saveAs();
    return $("unsaved").hidden;
  }
  if (choice !== "discard") return false;
  forgetDraft(file.doc);
  return true;
}

async function openPath() {
  if (!(await mayReplace("Opening another file"))) return;
  const path = await askPath("Open a file", file.path);
  if (!path) return;
  let answer;
  try { answer = await api("/api/open", { path }); } catch (e) { say(`not opened: ${e.message}`); return; }
  if (!answer.ok) { say(`not opened: ${answer.error.message}`); $("error").textContent = answer.error.message; return; }
  // The draft of the file left behind stays in this browser: opening it
  // again brings it back.
  startFile(answer.scheme, answer.path, answer.draft, answer.revision);
  if (!$("status").textContent.startsWith("unsaved changes restored")) say(`opened ${answer.path}`);
}
$("open-path").onclick = openPath;

/** Starts a new document holding `scheme`, in no file yet (its first Save
 * asks where, offering `suggestion`), with its own history. */
function startUnnamed(scheme, name, suggestion) {
  file.server = file.path = "";
  file.doc = `unnamed:${newId()}`;
  file.revision = 0;
  file.name = name;
  file.base = null;
  file.saved = null;
  file.suggestion = suggestion;
  forgetHistory();
  loadScheme(scheme);
  file.opened = JSON.stringify(pageScheme());
  undoLog.past.push(snapshot());
  changed();
}

$("new").onclick = async () => {
  if (!(await mayReplace("A new scheme"))) return;
  startUnnamed(NEW_SCHEME, "", "scheme.csv");
  say("a new scheme");
};

/** The sample schemes (from the server's schema), each a button opening a copy. */
function listSamples(samples) {
  $("sample-list").replaceChildren(...samples.map((sample) => {
    const li = document.createElement("li");
    const button = document.createElement("button");
    button.type = "button"; button.textContent = sample.name;
    button.onclick = async () => {
      $("sample-dialog").close();
      if (!(await mayReplace("Opening a sample"))) return;
      startUnnamed(sample.scheme, `${sample.name} (a sample: Save asks where to write it)`, sample.name);
      say(`opened the sample ${sample.name}`);
    };
    const about = document.createElement("span");
    about.className = "hint"; about.textContent = sample.about;
    li.append(button, about);
    return li;
  }));
}
$("open-sample").onclick = () => $("sample-dialog").showModal();

// A file from this computer: its contents, but no path the editor's server
// can write (a browser does not tell), so Save asks where.
$("open-file").onclick = async () => { if (await mayReplace("Opening a file")) $("load").click(); };
$("load").addEventListener("change", async () => {
  const picked = $("load").files[0];
  if (!picked) return;
  let answer;
  try { answer = await api("/api/parse", { csv: await picked.text() }); } catch (e) { say(`not opened: ${e.message}`); return; }
  $("load").value = "";
  if (!answer.ok) { say(`not opened: ${picked.name}: ${answer.error.message}`); markError(answer.error); return; }
  // A new document, as a desktop program opens one: its own history (an
  // Undo never brings back the other file under this one's name).
  startUnnamed(answer.scheme, `${picked.name} (from this computer: Save asks where to write it)`, picked.name);
  say(`opened ${picked.name}`);
});

/** Asks whether to make `folder` for a file saved into it; `true`: make it. */
function askMakeFolder(folder) {
  const dialog = $("folder-dialog");
  $("folder-text").textContent = `The folder ${folder} does not exist. Create it and save the scheme there?`;
  dialog.returnValue = "";
  dialog.showModal();
  return new Promise((resolve) => dialog.addEventListener("close", () => resolve(dialog.returnValue === "make"), { once: true }));
}

async function saveTo(path, makeFolder = false) {
  let answer;
  try {
    answer = await api("/api/save", { scheme: pageScheme(), path, make_folder: makeFolder });
  } catch (e) {
    say(`not saved: ${e.message}; your edits are kept in this browser`);
    return false;
  }
  if (!answer.ok && answer.missing_folder && !makeFolder && (await askMakeFolder(answer.missing_folder))) {
    return saveTo(path, true);
  }
  if (!answer.ok) {
    say(`not saved: ${answer.error.message}`);
    if (answer.error.row !== null || answer.error.field !== null) markError(answer.error);
    return false;
  }
  // The file is now what the page holds: the draft of another file the
  // page held goes; `changed` below drops this browser's copy of this
  // file's and sends the server its saved state.
  if (file.doc !== answer.path) forgetDraft(file.doc);
  file.server = file.doc = file.path = file.name = answer.path;
  file.revision = 0;
  file.base = JSON.stringify(answer.scheme);
  file.saved = JSON.stringify(pageScheme());
  changed();
  say(`saved ${answer.path}`);
  return true;
}

async function saveAs() {
  const path = await askPath("Save as", file.path || file.suggestion || "scheme.csv");
  if (path) await saveTo(path);
}
$("save").onclick = () => (file.path ? saveTo(file.path) : saveAs());
$("save-as").onclick = saveAs;

/** The page's scheme as a CSV file written by the page itself, for
 * Download CSV with the server gone: the file's layout (notes, `# key:
 * value` globals, the table with the columns in use, `low..high` ranges)
 * with the values as typed, unchecked. */
function csvOfPage() {
  const scheme = pageScheme();
  const lines = scheme.notes.split("\n").filter((l) => l.trim() !== "").map((l) => `# ${l.trim()}`);
  for (const [key, value] of Object.entries(scheme.globals)) if (value !== "") lines.push(`# ${key}: ${value}`);
  const text = (o, c) => { const [lo, hi] = o[c].map((v) => v.trim()); return hi === "" ? lo : `${lo}..${hi}`; };
  const used = COLUMNS.filter((c) => scheme.obstacles.some((o) => text(o, c) !== ""));
  lines.push(["type", ...used].join(","));
  for (const o of scheme.obstacles) lines.push([o.type, ...used.map((c) => text(o, c))].join(","));
  return lines.join("\n") + "\n";
}

// The canonical CSV Save would write, as a file the browser saves: named
// as the file the page edits (or scheme.csv). With the server gone the
// page writes it itself, and says so.
$("download").onclick = async () => {
  let csv;
  try {
    const answer = await api("/api/csv", { scheme: pageScheme() });
    if (!answer.ok) { say("no download: the scheme has an error"); markError(answer.error); return; }
    csv = answer.csv;
  } catch (e) {
    if (!(e instanceof Lost)) { say(`no download: ${e.message}`); return; }
    csv = csvOfPage();
    say("downloaded as typed: the editor's server is not answering, so this page wrote the file without checking it");
  }
  const link = document.createElement("a");
  link.href = URL.createObjectURL(new Blob([csv], { type: "text/csv" }));
  link.download = (file.path.split(/[\\/]/).pop() || file.suggestion || "scheme.csv");
  document.body.append(link);
  link.click();
  link.remove();
  setTimeout(() => URL.revokeObjectURL(link.href), 1000);
};

// --- generate ------------------------------------------------------------------

/** Each written world's check, one row a world (its faults in words). */
function showWorlds(worlds) {
  $("gen-worlds").hidden = worlds.length === 0;
  $("gen-worlds").querySelector("tbody").replaceChildren(...worlds.map((w) => {
    const tr = document.createElement("tr");
    const name = document.createElement("td"); name.textContent = w.world;
    const verdict = document.createElement("td");
    verdict.textContent = w.ok ? "good" : `failed: ${w.faults.join("; ")}`;
    if (!w.ok) verdict.className = "failed";
    tr.append(name, verdict);
    return tr;
  }));
}

/** The first worlds' previews (`preview.png` of each folder, served by the
 * editor) with their legends: each height's colour in steps and metres,
 * as the map's. */
function showPreviews(worlds) {
  const shown = worlds.filter((w) => w.heights).slice(0, 24);
  $("gen-previews").replaceChildren(...shown.map((w) => {
    const figure = document.createElement("figure");
    figure.setAttribute("role", "listitem");
    const image = document.createElement("img");
    image.src = `/api/world-preview/${encodeURIComponent(w.world)}`;
    image.alt = `preview of ${w.world}`;
    image.title = w.path;
    const caption = document.createElement("figcaption");
    caption.textContent = w.world;
    const legend = document.createElement("ul");
    legend.className = "legend";
    legend.setAttribute("aria-label", `legend of ${w.world}: colour of each height`);
    const [lo, hi] = w.heights;
    legend.append(...legendHeights(lo, hi, 4).map((h) => {
      const li = document.createElement("li");
      const swatch = document.createElement("span");
      swatch.className = "swatch"; swatch.style.background = `rgb(${palette(h, lo, hi).join(",")})`;
      const metres = w.step_height ? `, ${Number((h * w.step_height).toFixed(4))} m` : "";
      li.append(swatch, `${h} ${h === 1 ? "step" : "steps"}${metres}`);
      return li;
    }));
    figure.append(image, caption, legend);
    return figure;
  }));
}

$("open-folder").onclick = async () => {
  let answer;
  try { answer = await api("/api/open-folder", {}); } catch (e) { say(`not opened: ${e.message}`); return; }
  say(answer.ok ? `opened ${answer.folder}` : `not opened: ${answer.error.message}`);
};

/** After a Generate into a folder holding other worlds: a button that
 * writes into `folder` (one that does not exist yet) instead. */
function offerFolder(folder) {
  const button = document.createElement("button");
  button.textContent = `Write into ${folder} instead`;
  button.onclick = () => { $("gen-out").value = folder; $("generate").click(); };
  $("gen-summary").append(" ", button);
}

$("generate").onclick = async () => {
  const targets = [...document.querySelectorAll("#gen-targets input:checked")].map((i) => i.value);
  $("gen-summary").textContent = ""; $("gen-check").textContent = "";
  $("gen-worlds").hidden = true; $("gen-folder").hidden = true;
  $("gen-previews").replaceChildren();
  let answer;
  try {
    answer = await api("/api/generate", {
      scheme: pageScheme(), out: $("gen-out").value.trim(), amount: $("gen-amount").value,
      seed: $("seed").value, targets, mesh: $("mesh").value || null, templates: $("gen-templates").value,
      options: Object.fromEntries([...document.querySelectorAll("[data-world-option]")]
        .map((i) => [i.dataset.worldOption, i.value.trim()]).filter(([, text]) => text)),
    });
  } catch (e) { $("gen-summary").textContent = `not started: ${e.message}`; return; }
  if (!answer.ok) { markError(answer.error); $("gen-summary").textContent = `not started: ${answer.error.message}`; return; }
  markError(null);
  const poll = async () => {
    let job;
    try { job = await api("/api/job"); } catch (e) { setTimeout(poll, 2000); return; }
    $("gen-progress").max = Math.max(1, job.total); $("gen-progress").value = job.done;
    if (job.running || (!job.summary && !job.error)) { setTimeout(poll, 100); return; }
    $("gen-summary").textContent = job.error ? `failed: ${job.error}` : job.summary;
    $("gen-check").textContent = job.check ?? "";
    if (job.error && job.suggestion) offerFolder(job.suggestion);
    $("gen-folder").hidden = Boolean(job.error) || !job.folder;
    $("gen-folder-path").textContent = job.folder ?? "";
    showWorlds(job.worlds ?? []);
    showPreviews(job.error ? [] : job.worlds ?? []);
  };
  poll();
};

// --- the fields the schema names ----------------------------------------------

let COLUMN_DOCS = {};
let NEW_SCHEME = null; // what New starts from (the schema's)

/** A step height above 1 m or a block size above 2 m is most likely
 * centimetres typed as metres: ask, offering the value in metres. */
const UNIT_LIMITS = { step_height: 1, block_size: 2 };
function askUnits() {
  const box = $("unit-question");
  for (const [key, limit] of Object.entries(UNIT_LIMITS)) {
    const input = document.querySelector(`[data-global="${key}"]`);
    const value = Number(input.value);
    if (input.value.trim() !== "" && value > limit && input.dataset.kept !== input.value) {
      const label = key.replaceAll("_", " ");
      const metres = String(value / 100);
      box.replaceChildren(`A ${label} of ${value} m: did you mean ${value} cm? `);
      const yes = document.createElement("button");
      yes.textContent = `Use ${metres} m`;
      yes.onclick = () => { input.value = metres; record(null); refresh(); askUnits(); input.focus(); };
      const no = document.createElement("button");
      no.textContent = `Keep ${value} m`;
      no.onclick = () => { input.dataset.kept = input.value; askUnits(); input.focus(); };
      box.append(yes, " ", no);
      box.hidden = false;
      return;
    }
  }
  box.hidden = true;
  box.replaceChildren();
}

/** `true` when the page's pallets are on (they set the grid). */
function palletsOn() {
  const pallets = document.querySelector('[data-global="pallets"]')?.value.trim().toLowerCase() ?? "";
  return pallets !== "" && pallets !== "off";
}

/** Pallet size and boundary mean something only with pallets, size only
 * without: greyed out when unused (unless they hold a value, which the
 * scheme then refuses, or for size ignores), and size says what sets the
 * grid instead. */
function updateGlobals() {
  const on = palletsOn();
  for (const key of ["pallet_size", "pallet_boundary"]) {
    const input = document.querySelector(`[data-global="${key}"]`);
    if (!input) continue;
    input.disabled = !on && globalText(input) === "";
  }
  const size = document.querySelector('[data-global="size"]');
  if (size) size.disabled = on && globalText(size) === "";
  showGrid(null);
  askUnits();
}

/** The line under size while pallets set the grid: `grid` the last
 * preview's cells (null: keep what it says). Called by each preview, so it
 * touches that line only. */
function showGrid(grid) {
  const note = $("grid-note");
  if (!note) return;
  note.hidden = !palletsOn();
  if (grid) note.textContent = `Size is not used: the pallets make the grid ${grid} cells.`;
  else if (!note.textContent) note.textContent = "Size is not used: the pallets set the grid.";
}

function buildFields(schema) {
  COLUMNS = schema.columns;
  TYPE_COLUMNS = Object.fromEntries(schema.types.map((t) => [t.name, t.columns]));
  COLUMN_DOCS = Object.fromEntries(schema.column_docs.map((c) => [c.name, c.doc]));
  const globals = $("global-fields");
  for (const g of schema.globals) {
    GLOBAL_DEFAULTS[g.key] = g.default;
    const label = document.createElement("label");
    const input = document.createElement("input");
    input.id = `global-${g.key}`;
    label.htmlFor = input.id;
    label.textContent = g.key.replaceAll("_", " ");
    input.dataset.global = g.key;
    input.title = g.doc;
    if (g.key === "pallet_boundary") {
      input.type = "checkbox";
      input.addEventListener("change", () => { input.dataset.explicit = "1"; record(null); refresh(); });
    } else {
      input.placeholder = g.default;
      input.addEventListener("input", () => { record(`global.${g.key}`); updateGlobals(); refresh(); });
    }
    const unit = document.createElement("span");
    unit.className = "unit"; unit.textContent = g.unit ?? "";
    globals.append(label, input, unit);
    if (g.key === "size") {
      // What sets the grid when pallets do (updateGlobals), on a line of
      // its own under the field.
      const note = document.createElement("p");
      note.id = "grid-note"; note.className = "hint grid-note"; note.hidden = true;
      globals.append(note);
    }
  }
  const head = document.querySelector("#table thead tr");
  for (const c of schema.column_docs.filter((c) => c.name !== "type")) {
    const th = document.createElement("th");
    th.scope = "col"; th.title = c.doc; th.textContent = c.name; th.dataset.column = c.name;
    const unit = document.createElement("span");
    unit.className = "unit"; unit.textContent = c.unit ?? "";
    // Each of the column's two fields is named above it: the value (or a
    // random range's low end) and the range's high end.
    const parts = document.createElement("span");
    parts.className = "parts";
    for (const [text, title] of [["low", "the value, or the low end of a random range"], ["high", "the high end of a random range (empty: the value alone)"]]) {
      const part = document.createElement("span");
      part.textContent = text; part.title = title;
      parts.append(part);
    }
    th.append(unit, parts);
    head.append(th);
  }
  head.children[1].title = COLUMN_DOCS.type;
  const names = { auto: "each target's best (auto)", single: "single mesh", blocks: "blocks (one box each)" };
  for (const m of schema.mesh_modes) {
    const option = document.createElement("option");
    // The default is sent as not given (null): the library's rule applies.
    option.value = m === schema.default_mesh ? "" : m; option.textContent = names[m] ?? m;
    $("mesh").append(option);
  }
  NEW_SCHEME = schema.new_scheme;
  listSamples(schema.samples);
  const targets = $("gen-targets");
  for (const t of schema.targets) {
    const label = document.createElement("label");
    const box = document.createElement("input");
    box.type = "checkbox"; box.value = t; box.checked = schema.default_targets.includes(t);
    label.append(box, ` ${t}`);
    targets.append(label);
  }
  // The other world options (rse-world's table): a field each, sent by
  // name, so an option added there is on the page with no edit here.
  const templatesLabel = document.querySelector('label[for="gen-templates"]');
  for (const o of schema.world_options.filter((o) => !["targets", "mesh"].includes(o.name))) {
    const label = document.createElement("label");
    const input = document.createElement("input");
    input.id = `gen-opt-${o.name}`; input.dataset.worldOption = o.name;
    label.htmlFor = input.id; label.textContent = o.name.replaceAll("_", " ");
    input.placeholder = o.default; input.title = o.help; input.size = 10;
    templatesLabel.before(label, input, document.createElement("span"));
  }
}

(async () => {
  let schema, answer;
  try {
    schema = await api("/api/schema");
    answer = await api("/api/state");
  } catch (e) { say(`the editor's server did not answer: ${e.message}; reload the page once it runs`); return; }
  buildFields(schema);
  $("work-folder").textContent = $("work-folder").title = $("dialog-folder").textContent = answer.folder;
  if (answer.document?.startsWith("unnamed:")) resumeUnnamed(answer);
  else {
    startFile(answer.scheme, answer.path, answer.draft, answer.revision, answer.new_file);
    if (answer.new_file) say(`a new scheme: Save writes ${answer.path}`);
  }
})();

/** Back on the scheme in no file yet the page was on (New, a sample, a
 * file from this computer), from its draft: its name, what Save offers,
 * its undo history. */
function resumeUnnamed(answer) {
  const kept = answer.draft;
  file.server = "";
  file.doc = answer.document;
  file.revision = answer.revision ?? 0;
  file.path = kept.path ?? "";
  file.name = kept.name ?? "";
  file.suggestion = kept.suggestion ?? "scheme.csv";
  file.opened = kept.opened ?? null;
  file.base = null; file.saved = null;
  forgetHistory();
  loadScheme(kept.scheme);
  takeHistory(kept);
  changed();
  say(JSON.stringify(pageScheme()) === file.opened ? `back on ${file.name || "a new scheme"}` : "unsaved changes restored");
}
