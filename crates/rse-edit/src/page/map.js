// The top-down map: the world's heights drawn as `preview.png` draws them
// (north up, `cell_pixels` pixels a cell, darker cell edges from 4 pixels
// on), an overlay with every obstacle's points, walls and random ranges, a
// legend, a readout of the cell under the pointer, zoom and pan, and
// editing: a click picks the obstacle under the pointer (the nearest point,
// a wall along its line, a rectangle from inside; again on one spot, the
// next one there) and a drag moves it; a new obstacle is placed by the next
// click, or drawn by a drag (a wall, long pit, stairs, pyramid or ramp
// corner to corner); a click on empty ground moves nothing. A line under
// the map says what a click will do. The keyboard does the same with the
// arrow keys and Enter.
"use strict";

import { FRAME_RGB, isFrame, legendHeights, palette } from "./colours.js";

// Which ends each type has on the map: a point, or a point and a second end.
const ENDS = {
  peak: [1], pit: [1], wall: [1, 2], long_pit: [1, 2], stairs: [1, 2], pyramid: [1, 2], pyramid_pit: [1, 2],
  ramp: [1, 2], crossing_ramps: [1, 2],
};
// The kinds whose two ends are the corners of a rectangle of cells.
const BOXES = new Set(["stairs", "pyramid", "pyramid_pit", "ramp", "crossing_ramps"]);

/** A row's end `k` as cell ranges `{x: [lo, hi], y: [lo, hi]}`, or null
 * when its fields are not all whole numbers. */
function endOf(row, k) {
  const part = (c) => {
    const lo = Number(String(row[`${c}.lo`] ?? "").trim());
    const hiText = String(row[`${c}.hi`] ?? "").trim();
    const hi = hiText === "" ? lo : Number(hiText);
    return String(row[`${c}.lo`] ?? "").trim() === "" || !Number.isInteger(lo) || !Number.isInteger(hi) ? null : [lo, hi];
  };
  const x = part(`x${k}`), y = part(`y${k}`);
  return x && y ? { x, y, range: x[0] !== x[1] || y[0] !== y[1] } : null;
}

export class TopView {
  /**
   * @param {object} page what the map edits through: rows(), selected(),
   *   select(i), change(i, fields) (a drag's step), done() (one undoable edit)
   */
  constructor(page) {
    this.page = page;
    this.canvas = document.getElementById("map");
    // Drawn from the CPU every edit: a canvas kept in memory takes the
    // pixels without a trip to the GPU.
    this.context = this.canvas.getContext("2d", { willReadFrequently: true });
    this.overlay = document.getElementById("map-overlay");
    this.readout = document.getElementById("readout");
    this.legend = document.getElementById("legend");
    this.preview = null;
    this.drag = null;
    this.cursor = null; // the keyboard's cell
    this.keyDrawing = false;
    this.placing = null; // the row the next click places, if any
    this.lastPick = null; // the cell pressed last: pressed again, the next obstacle there
    // Zoom and pan: the grid scaled by `zoom` and moved by (`panX`, `panY`)
    // CSS pixels inside the map's window.
    this.box = this.overlay.closest(".map-box");
    this.layer = document.getElementById("map-layer");
    this.zoom = 1; this.panX = 0; this.panY = 0;
    this.listen();
  }

  /** Draws a new preview (see colours.js `decodePreview`). */
  show(preview) {
    const { nx, ny } = preview;
    const cp = preview.cell_pixels;
    const changedSize = !this.preview || this.preview.nx !== nx || this.preview.ny !== ny || this.preview.cell_pixels !== cp;
    this.preview = preview;
    const width = nx * cp, height = ny * cp;
    if (changedSize) {
      for (const c of [this.canvas, this.overlay]) { c.width = width; c.height = height; }
      this.image = new ImageData(width, height);
      if (this.cursor && (this.cursor.x >= nx || this.cursor.y >= ny)) this.cursor = null;
      // Another grid: the whole of it again.
      if (!this.shownGrid || this.shownGrid[0] !== nx || this.shownGrid[1] !== ny) this.setView(1, 0, 0);
      this.shownGrid = [nx, ny];
    }
    // One 32-bit pixel at a time, a cell row's pixel line built once and
    // copied down the cell (only the darker bottom line differs).
    const pixels = new Uint32Array(this.image.data.buffer);
    const rgba = ([r, g, b]) => (255 << 24 | b << 16 | g << 8 | r) >>> 0; // little-endian RGBA
    const darker = (c) => c - Math.floor(c / 4);
    const edges = cp >= 4;
    // Each height's two pixels, looked up (a colour per cell was the cost).
    const span = Math.max(preview.hi - preview.lo + 1, 1);
    const plainOf = new Uint32Array(span), darkOf = new Uint32Array(span);
    for (let i = 0; i < span; i++) {
      const colour = palette(preview.lo + i, preview.lo, preview.hi);
      plainOf[i] = rgba(colour); darkOf[i] = rgba(colour.map(darker));
    }
    const framePlain = rgba(FRAME_RGB), frameDark = rgba(FRAME_RGB.map(darker));
    const period = preview.frame_period, heights = preview.heights, lo = preview.lo;
    const line = new Uint32Array(width), edgeLine = new Uint32Array(width);
    for (let y = 0; y < ny; y++) {
      for (let x = 0; x < nx; x++) {
        let plain, dark;
        if (isFrame(period, x, y)) { plain = framePlain; dark = frameDark; }
        else { const i = heights[y * nx + x] - lo; plain = plainOf[i]; dark = darkOf[i]; }
        line.fill(plain, x * cp, (x + 1) * cp);
        if (edges) line[(x + 1) * cp - 1] = dark;
        edgeLine.fill(dark, x * cp, (x + 1) * cp);
      }
      const top = (ny - 1 - y) * cp; // north up: row ny-1 is the image's first
      for (let py = 0; py < cp; py++) pixels.set(edges && py === cp - 1 ? edgeLine : line, (top + py) * width);
    }
    this.context.putImageData(this.image, 0, 0);
    this.drawOverlay();
    this.drawLegend();
  }

  drawLegend() {
    const p = this.preview;
    const items = legendHeights(p.lo, p.hi).map((h) => [palette(h, p.lo, p.hi), `${h} ${h === 1 ? "step" : "steps"}, ${metres(h * p.step_height)}`]);
    if (p.frame_period !== null) items.push([FRAME_RGB, "pallet frame"]);
    this.legend.replaceChildren(...items.map(([rgb, text]) => {
      const li = document.createElement("li");
      const swatch = document.createElement("span");
      swatch.className = "swatch"; swatch.style.background = `rgb(${rgb.join(",")})`;
      li.append(swatch, text);
      return li;
    }));
  }

  // --- zoom and pan ----------------------------------------------------------

  /** The most zoom: a block 48 CSS pixels wide (at least 24 asked). */
  maxZoom() {
    if (!this.preview) return 1;
    const perBlock = this.box.clientWidth / this.preview.nx;
    return Math.max(1, 48 / Math.max(perBlock, 1e-6));
  }

  /** Zoom `zoom`, the grid's corner at (`x`, `y`) in the window: kept so
   * that the grid always covers the window. */
  setView(zoom, x, y) {
    const z = Math.min(Math.max(zoom, 1), this.maxZoom());
    const w = this.box.clientWidth, h = this.box.clientHeight;
    this.zoom = z;
    this.panX = Math.min(0, Math.max(x, w - w * z));
    this.panY = Math.min(0, Math.max(y, h - h * z));
    this.layer.style.transform = z === 1 ? "" : `translate(${this.panX}px, ${this.panY}px) scale(${z})`;
    const out = document.getElementById("zoom-level");
    if (out && this.preview) {
      const block = (w * z) / this.preview.nx;
      out.textContent = z === 1 ? `whole grid, ${block.toFixed(0)} px a block` : `zoom ${z.toFixed(1)}×, ${block.toFixed(0)} px a block`;
    }
  }

  /** Zooms by `factor` about the point (`clientX`, `clientY`), which stays
   * where it is (the window's middle when not given). */
  zoomBy(factor, clientX, clientY) {
    const r = this.box.getBoundingClientRect();
    const px = clientX === undefined ? r.width / 2 : clientX - r.left;
    const py = clientY === undefined ? r.height / 2 : clientY - r.top;
    const z = Math.min(Math.max(this.zoom * factor, 1), this.maxZoom());
    const gx = (px - this.panX) / this.zoom, gy = (py - this.panY) / this.zoom;
    this.setView(z, px - gx * z, py - gy * z);
  }

  /** Pans so that `cell` is in the window (the keyboard's cursor). */
  showCell(cell) {
    if (!cell || !this.preview || this.zoom === 1) return;
    const { nx, ny } = this.preview;
    const w = this.box.clientWidth, h = this.box.clientHeight;
    const size = (w * this.zoom) / nx;
    const left = cell.x * size + this.panX, top = (ny - 1 - cell.y) * size + this.panY;
    let x = this.panX, y = this.panY;
    if (left < 0) x -= left; else if (left + size > w) x -= left + size - w;
    if (top < 0) y -= top; else if (top + size > h) y -= top + size - h;
    this.setView(this.zoom, x, y);
  }

  /** A press on empty ground: a pan of the zoomed map, or nothing. */
  panFrom(e) {
    return this.zoom > 1 ? { kind: "pan", x: e.clientX, y: e.clientY, panX: this.panX, panY: this.panY } : null;
  }

  panTo(e) {
    const d = this.drag;
    this.setView(this.zoom, d.panX + e.clientX - d.x, d.panY + e.clientY - d.y);
  }

  /** Every obstacle's ends; the selected row's bold, with handles. */
  drawOverlay() {
    if (!this.preview) return;
    const { nx, ny, cell_pixels: cp } = this.preview;
    const g = this.overlay.getContext("2d");
    g.clearRect(0, 0, this.overlay.width, this.overlay.height);
    const px = (x) => (x + 0.5) * cp, py = (y) => (ny - 1 - y + 0.5) * cp;
    const rows = this.page.rows();
    const order = rows.map((_, i) => i).filter((i) => i !== this.page.selected());
    if (this.page.selected() >= 0) order.push(this.page.selected()); // the selected one on top
    const unit = Math.max(cp, Math.max(nx, ny) / 60); // sizes readable on any grid
    for (const i of order) {
      const row = rows[i];
      const ends = (ENDS[row.type] ?? []).map((k) => endOf(row, k));
      const selected = i === this.page.selected();
      g.lineWidth = selected ? Math.max(2, unit / 4) : Math.max(1, unit / 8);
      g.strokeStyle = selected ? "#fff" : "rgba(255,255,255,0.6)";
      g.fillStyle = selected ? "rgba(0,0,0,0.75)" : "rgba(0,0,0,0.35)";
      if (ends.length === 2 && ends[0] && ends[1] && BOXES.has(row.type)) {
        // The rectangle between the corners' cells (their ranges' middles).
        const mid = (e, a) => Math.round((e[a][0] + e[a][1]) / 2);
        const [x0, x1] = [mid(ends[0], "x"), mid(ends[1], "x")].sort((a, b) => a - b);
        const [y0, y1] = [mid(ends[0], "y"), mid(ends[1], "y")].sort((a, b) => a - b);
        g.strokeRect(x0 * cp, (ny - 1 - y1) * cp, (x1 - x0 + 1) * cp, (y1 - y0 + 1) * cp);
      }
      if (ends.length === 2 && ends[0] && ends[1] && row.type !== "pyramid" && row.type !== "pyramid_pit") {
        // A wall's or long pit's line; a flight's or a ramp's climb, first
        // corner to second.
        g.beginPath();
        g.moveTo(px((ends[0].x[0] + ends[0].x[1]) / 2), py((ends[0].y[0] + ends[0].y[1]) / 2));
        g.lineTo(px((ends[1].x[0] + ends[1].x[1]) / 2), py((ends[1].y[0] + ends[1].y[1]) / 2));
        g.stroke();
      }
      for (const end of ends) {
        if (!end) continue;
        if (end.range) { // a random range: the rectangle of cells it draws from
          g.setLineDash([unit / 2, unit / 3]);
          g.strokeRect(end.x[0] * cp, (ny - 1 - end.y[1]) * cp, (end.x[1] - end.x[0] + 1) * cp, (end.y[1] - end.y[0] + 1) * cp);
          g.setLineDash([]);
        } else {
          g.beginPath();
          g.arc(px(end.x[0]), py(end.y[0]), Math.max(cp * 0.35, unit * 0.4), 0, 2 * Math.PI);
          g.fill(); g.stroke();
        }
      }
    }
    if (this.cursor && document.activeElement === this.overlay) {
      g.strokeStyle = "#ff0"; g.lineWidth = Math.max(2, unit / 4);
      g.strokeRect(this.cursor.x * cp, (ny - 1 - this.cursor.y) * cp, cp, cp);
    }
  }

  /** The cell under a pointer event, or null off the grid. */
  cellAt(e) {
    if (!this.preview) return null;
    const box = this.overlay.getBoundingClientRect();
    const { nx, ny } = this.preview;
    const x = Math.floor((e.clientX - box.left) / box.width * nx);
    const y = ny - 1 - Math.floor((e.clientY - box.top) / box.height * ny);
    return x >= 0 && x < nx && y >= 0 && y < ny ? { x, y } : null;
  }

  showReadout(cell) {
    const p = this.preview;
    if (!cell || !p) { this.readout.textContent = ""; return; }
    const h = p.heights[cell.y * p.nx + cell.x];
    const frame = isFrame(p.frame_period, cell.x, cell.y);
    this.readout.textContent = `column ${cell.x}, row ${cell.y}: height ${h} ${h === 1 ? "step" : "steps"} (${metres(p.base + h * p.step_height)})${frame ? ", pallet frame" : ""}`;
  }

  /** Every obstacle under `cell`, nearest first, one hit each:
   * `{row, k, end, d}` for one of its ends (a point within a cell of it,
   * or anywhere in a random range's rectangle), `{row, whole: true, d}` for
   * the obstacle itself (a wall's or long pit's line within a cell of it,
   * anywhere inside a stairs', pyramid's or ramp's rectangle). `d` orders
   * them: the nearest point first, whatever is selected (a busy map's
   * selected handle once kept a click on another obstacle's own point). */
  hits(cell) {
    const rows = this.page.rows();
    const found = [];
    rows.forEach((row, i) => {
      const ends = (ENDS[row?.type] ?? []).map((k) => ({ k, end: endOf(row, k) }));
      let best = null;
      const offer = (hit) => { if (!best || hit.d < best.d) best = hit; };
      for (const { k, end } of ends) {
        if (!end) continue;
        if (end.range) {
          if (cell.x >= end.x[0] && cell.x <= end.x[1] && cell.y >= end.y[0] && cell.y <= end.y[1]) offer({ row: i, k, end, d: 0.5 });
        } else {
          const d = Math.max(Math.abs(cell.x - end.x[0]), Math.abs(cell.y - end.y[0]));
          if (d <= 1) offer({ row: i, k, end, d });
        }
      }
      const [a, b] = ends.map((e) => e.end);
      if (ends.length === 2 && a && b) {
        const mid = (e, axis) => (e[axis][0] + e[axis][1]) / 2;
        if (BOXES.has(row.type)) {
          const [x0, x1] = [mid(a, "x"), mid(b, "x")].sort((p, q) => p - q);
          const [y0, y1] = [mid(a, "y"), mid(b, "y")].sort((p, q) => p - q);
          if (cell.x >= Math.round(x0) && cell.x <= Math.round(x1) && cell.y >= Math.round(y0) && cell.y <= Math.round(y1)) {
            offer({ row: i, whole: true, d: 1.5 });
          }
        } else {
          const d = segmentDistance(cell, [mid(a, "x"), mid(a, "y")], [mid(b, "x"), mid(b, "y")]);
          if (d <= 1) offer({ row: i, whole: true, d: 0.3 + d / 2 });
        }
      }
      if (best) found.push(best);
    });
    return found.sort((p, q) => p.d - q.d || p.row - q.row);
  }

  /** Starts placing row `i` (a new obstacle, or one just given points):
   * the next click or Enter puts it there, wherever other obstacles lie. */
  startPlacing(i) { this.placing = i; }

  /** Whether row `i` has points on the map. */
  placeable(i) { return Boolean(ENDS[this.page.rows()[i]?.type]); }

  /** Placing ends (another row selected, Escape). */
  stopPlacing() { this.placing = null; }

  /** What a press at `cell` does, as {act, row, …, text}: `place` the
   * obstacle being placed there; else `move` (select, and drag to move)
   * the obstacle under the pointer: the nearest of them, or, pressed again
   * on the same cell, the next one under it (every obstacle there in
   * turn); `none` on empty ground, where nothing moves. `text` says it in
   * words, for the hint under the map. */
  intent(cell) {
    const rows = this.page.rows();
    const selected = this.page.selected();
    const name = (i) => `${rows[i].type.replaceAll("_", " ")} ${i + 1}`;
    const placing = this.placing;
    if (placing !== null && placing !== undefined && ENDS[rows[placing]?.type]) {
      const what = ENDS[rows[placing].type].length === 2
        ? `place ${name(placing)} here (drag to draw it to its other end)`
        : `place ${name(placing)} here`;
      return { act: "place", row: placing, text: what };
    }
    const hits = this.hits(cell);
    if (!hits.length) return { act: "none", text: "nothing here (drag to pan a zoomed map)" };
    // Picked here last and still selected: a drag moves it, a click
    // selects the next obstacle here.
    const again = this.lastPick && this.lastPick.x === cell.x && this.lastPick.y === cell.y;
    const mine = hits.findIndex((h) => h.row === selected);
    if (again && mine >= 0) {
      const hit = hits[mine];
      if (hits.length === 1) return { act: "move", ...hit, text: `drag to move ${name(hit.row)}` };
      const next = hits[(mine + 1) % hits.length].row;
      return { act: "move", ...hit, next, text: `drag to move ${name(hit.row)}, or click for the next here, ${name(next)} (${hits.length} obstacles here)` };
    }
    const hit = hits[0];
    const more = hits.length > 1 ? ` (${hits.length} obstacles here: click again for the next)` : "";
    const text = hit.row === selected ? `drag to move ${name(hit.row)}` : `select ${name(hit.row)}, drag to move it`;
    return { act: "move", ...hit, text: text + more };
  }

  /** Says under the map (and by the pointer's shape) what a click or
   * Enter at `cell` would do. */
  showIntent(cell) {
    const hint = document.getElementById("map-hint");
    if (!cell || !this.preview) { hint.textContent = ""; this.overlay.style.cursor = ""; return; }
    const intent = this.intent(cell);
    hint.textContent = `Click: ${intent.text}`;
    this.overlay.style.cursor = { move: intent.row === this.page.selected() ? "move" : "pointer", place: "crosshair", none: "grab" }[intent.act];
  }

  /** The fields that put end `k` of a drag's start `end` moved by (dx, dy),
   * kept on the grid (a range keeps its width). */
  moved(end, k, dx, dy) {
    const { nx, ny } = this.preview;
    const shift = ([lo, hi], d, n) => { const by = Math.min(Math.max(d, -lo), n - 1 - hi); return [lo + by, hi + by]; };
    const x = shift(end.x, dx, nx), y = shift(end.y, dy, ny);
    // A range stays a range and a single value stays single, per axis.
    const hi = (moved, before) => (before[0] !== before[1] ? String(moved[1]) : "");
    return { [`x${k}.lo`]: String(x[0]), [`x${k}.hi`]: hi(x, end.x), [`y${k}.lo`]: String(y[0]), [`y${k}.hi`]: hi(y, end.y) };
  }

  /** The fields that move every end of `ends` (`[{k, end}]`) by (dx, dy),
   * as far as all of them stay on the grid: the obstacle keeps its shape. */
  movedAll(ends, dx, dy) {
    const { nx, ny } = this.preview;
    const room = (axis, d, n) => ends.reduce((by, { end }) => Math.min(Math.max(by, -end[axis][0]), n - 1 - end[axis][1]), d);
    const bx = room("x", dx, nx), by = room("y", dy, ny);
    return Object.assign({}, ...ends.map(({ k, end }) => this.moved(end, k, bx, by)));
  }

  /** A press at `cell`: does what `intent` says; the drag it starts, or
   * null. */
  press(cell) {
    const intent = this.intent(cell);
    if (intent.act === "none") { this.page.hint(`Click: ${intent.text}`); return null; }
    if (intent.act === "move") {
      this.lastPick = cell;
      if (intent.row !== this.page.selected()) this.page.select(intent.row);
      const row = this.page.rows()[intent.row];
      const ends = (ENDS[row.type] ?? []).map((k) => ({ k, end: endOf(row, k) })).filter((e) => e.end);
      return { kind: "move", start: cell, row: intent.row, k: intent.k, end: intent.end, whole: intent.whole === true, ends, next: intent.next, moved: false };
    }
    // Placing: the obstacle goes where the pointer is, and placing ends.
    const i = intent.row;
    this.placing = null;
    this.lastPick = null;
    const row = this.page.rows()[i];
    const ends = (ENDS[row.type] ?? []).map((k) => ({ k, end: endOf(row, k) })).filter((e) => e.end);
    const point = (k) => ({ [`x${k}.lo`]: String(cell.x), [`x${k}.hi`]: "", [`y${k}.lo`]: String(cell.y), [`y${k}.hi`]: "" });
    if (ENDS[row.type].length === 2) {
      // A click moves it whole, its first end here; a drag draws it anew
      // from here to where it ends.
      return { kind: "line", row: i, start: cell, ends, drawn: false };
    }
    this.page.change(i, point(1));
    return { kind: "move", start: cell, row: i, k: 1, end: endOf(this.page.rows()[i], 1), whole: false, ends: [] };
  }

  /** The pointer (or the keyboard's cursor) moved to `cell` mid-drag. */
  follow(cell) {
    const d = this.drag;
    if (!d || !cell) return;
    if (d.kind === "pan") return;
    if (d.kind === "line") {
      if (!d.drawn && cell.x === d.start.x && cell.y === d.start.y) return;
      d.drawn = true;
      const point = (k, c) => ({ [`x${k}.lo`]: String(c.x), [`x${k}.hi`]: "", [`y${k}.lo`]: String(c.y), [`y${k}.hi`]: "" });
      this.page.change(d.row, { ...point(1, d.start), ...point(2, cell) });
    } else {
      if (cell.x !== d.start.x || cell.y !== d.start.y) d.moved = true;
      if (d.whole) this.page.change(d.row, this.movedAll(d.ends, cell.x - d.start.x, cell.y - d.start.y));
      else if (d.end) this.page.change(d.row, this.moved(d.end, d.k, cell.x - d.start.x, cell.y - d.start.y));
    }
  }

  finish() {
    const d = this.drag;
    if (!d) return;
    this.drag = null;
    if (d.kind === "pan") return;
    if (d.kind === "line" && !d.drawn) {
      // Placed by a click: the whole obstacle moved, its first end here.
      const first = d.ends.find((e) => e.k === 1);
      if (first) this.page.change(d.row, this.movedAll(d.ends, d.start.x - first.end.x[0], d.start.y - first.end.y[0]));
    }
    // A click (no drag) again where this obstacle was picked: the next one there.
    if (d.kind === "move" && !d.moved && d.next !== undefined) this.page.select(d.next);
    this.page.done();
  }

  /** Ends a drag or keyboard grab under way as a finished edit (Undo and
   * Redo call it first: a grab still held is the newest step, not lost). */
  letGo() { this.keyDrawing = false; this.finish(); }

  listen() {
    const o = this.overlay;
    // The wheel (and a touchpad's pinch, which Chromium sends as a wheel
    // with Ctrl) zooms about the pointer; the buttons and + − 0 too.
    o.addEventListener("wheel", (e) => {
      e.preventDefault();
      this.zoomBy(Math.exp(-e.deltaY * (e.ctrlKey ? 0.01 : 0.0015)), e.clientX, e.clientY);
    }, { passive: false });
    document.getElementById("zoom-in").addEventListener("click", () => this.zoomBy(1.5));
    document.getElementById("zoom-out").addEventListener("click", () => this.zoomBy(1 / 1.5));
    document.getElementById("zoom-fit").addEventListener("click", () => this.setView(1, 0, 0));
    new ResizeObserver(() => this.setView(this.zoom, this.panX, this.panY)).observe(this.box);
    o.addEventListener("pointerdown", (e) => {
      const cell = this.cellAt(e);
      if (!cell || e.button !== 0) return;
      e.preventDefault();
      o.setPointerCapture(e.pointerId);
      this.drag = this.press(cell) ?? this.panFrom(e);
      this.page.rendered();
    });
    o.addEventListener("pointermove", (e) => {
      const cell = this.cellAt(e);
      this.showReadout(cell);
      if (!this.drag) this.showIntent(cell);
      if (this.drag?.kind === "pan") this.panTo(e);
      else if (this.drag) { this.follow(cell); this.page.rendered(); }
    });
    o.addEventListener("pointerup", () => { this.finish(); this.page.rendered(); });
    o.addEventListener("pointercancel", () => { this.finish(); this.page.rendered(); });
    o.addEventListener("pointerleave", () => { if (!this.drag) { this.showReadout(this.cursor); this.showIntent(document.activeElement === o ? this.cursor : null); } });
    o.addEventListener("focus", () => {
      if (!this.cursor && this.preview) this.cursor = { x: this.preview.nx >> 1, y: this.preview.ny >> 1 };
      this.showReadout(this.cursor); this.showIntent(this.cursor); this.drawOverlay();
    });
    o.addEventListener("blur", () => { if (this.keyDrawing) this.letGo(); this.drawOverlay(); });
    o.addEventListener("keydown", (e) => {
      if (!this.preview || !this.cursor) return;
      const step = { ArrowLeft: [-1, 0], ArrowRight: [1, 0], ArrowUp: [0, 1], ArrowDown: [0, -1] }[e.key];
      if (step) {
        e.preventDefault();
        const by = e.shiftKey ? 5 : 1;
        this.cursor = {
          x: Math.min(Math.max(this.cursor.x + step[0] * by, 0), this.preview.nx - 1),
          y: Math.min(Math.max(this.cursor.y + step[1] * by, 0), this.preview.ny - 1),
        };
        this.showReadout(this.cursor);
        this.showCell(this.cursor);
        if (!this.keyDrawing) this.showIntent(this.cursor);
        if (this.keyDrawing) this.follow(this.cursor);
        this.page.rendered();
      } else if (e.key === "Enter" || e.key === " ") {
        e.preventDefault();
        // Enter grabs or places at the cursor; the next Enter lets go.
        if (this.keyDrawing) { this.keyDrawing = false; this.finish(); } else {
          this.drag = this.press(this.cursor);
          this.keyDrawing = this.drag !== null;
        }
        this.page.rendered();
      } else if (e.key === "+" || e.key === "=") {
        e.preventDefault(); this.zoomBy(1.5); this.showCell(this.cursor);
      } else if (e.key === "-" || e.key === "_") {
        e.preventDefault(); this.zoomBy(1 / 1.5);
      } else if (e.key === "0") {
        e.preventDefault(); this.setView(1, 0, 0);
      } else if (e.key === "Escape" && this.keyDrawing) {
        this.keyDrawing = false; this.finish(); this.page.rendered();
      } else if (e.key === "Escape" && this.placing !== null) {
        this.placing = null; this.showIntent(this.cursor);
      }
    });
  }
}

function metres(m) { return `${Number(m.toFixed(4))} m`; }

/** The distance in cells from `cell` to the segment from `a` to `b`
 * (`[x, y]` cell coordinates). */
function segmentDistance(cell, a, b) {
  const [dx, dy] = [b[0] - a[0], b[1] - a[1]];
  const length2 = dx * dx + dy * dy;
  const t = length2 === 0 ? 0 : Math.min(1, Math.max(0, ((cell.x - a[0]) * dx + (cell.y - a[1]) * dy) / length2));
  return Math.hypot(cell.x - (a[0] + t * dx), cell.y - (a[1] + t * dy));
}
