// The top-down map: the world's heights drawn as `preview.png` draws them
// (north up, `cell_pixels` pixels a cell, darker cell edges from 4 pixels
// on), an overlay with every obstacle's points, walls and random ranges, a
// legend, a readout of the cell under the pointer, and drawing: click to
// place the selected peak or pit, drag to draw the selected wall, long pit,
// stairs, pyramid or ramp (corner to corner), drag a point or a range's
// rectangle to move it; another obstacle is
// picked by its own point or with Shift, and a line under the map says
// what a click will do. The keyboard does the same with the arrow keys and
// Enter.
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

  /** Row `i`'s end at `cell` as {row, k, end}, or null: inside a random
   * range's rectangle, or on a point or the cells around it (`near`), or
   * exactly on the point (not `near`). */
  endAt(i, cell, near) {
    const row = this.page.rows()[i];
    for (const k of ENDS[row?.type] ?? []) {
      const end = endOf(row, k);
      if (!end) continue;
      const reach = near ? 1 : 0;
      const inside = end.range
        ? cell.x >= end.x[0] && cell.x <= end.x[1] && cell.y >= end.y[0] && cell.y <= end.y[1]
        : Math.abs(cell.x - end.x[0]) <= reach && Math.abs(cell.y - end.y[0]) <= reach;
      if (inside) return { row: i, k, end };
    }
    return null;
  }

  /** What a press at `cell` does, as {act, row, …, text}: `move` an end
   * (selecting its row), `place` the selected row there, or `none`. The
   * selected obstacle comes first: a click places it, or moves it when on
   * its own point or range, wherever other obstacles lie (a busy map's
   * ranges cover its middle). Another obstacle is picked only by its own
   * point (the dot drawn on its cell) or, anywhere it reaches, with Shift
   * (`pick`). `text` says it in words, for the hint under the map. */
  intent(cell, pick) {
    const rows = this.page.rows();
    const selected = this.page.selected();
    const others = rows.map((_, i) => i).filter((i) => i !== selected);
    const name = (i) => `${rows[i].type.replaceAll("_", " ")} ${i + 1}`;
    const first = (order, near) => { for (const i of order) { const e = this.endAt(i, cell, near); if (e) return e; } return null; };
    const picked = (e) => ({ act: "move", ...e, text: e.row === selected ? `move ${name(e.row)}` : `select ${name(e.row)} and move it` });
    if (pick) {
      const e = first(others, true) ?? first([selected].filter((i) => i >= 0), true);
      return e ? picked(e) : { act: "none", text: "nothing here to select" };
    }
    const own = selected >= 0 ? this.endAt(selected, cell, true) : null;
    if (own) return picked(own);
    const dot = first(others, false);
    if (dot && !dot.end.range) return picked(dot);
    if (selected >= 0 && ENDS[rows[selected]?.type]) {
      const what = ENDS[rows[selected].type].length === 2 ? `start ${name(selected)} here (drag to its other end)` : `place ${name(selected)} here`;
      return { act: "place", row: selected, text: what };
    }
    // Nothing to place: a click picks what is there, as Shift would.
    const e = first(others, true);
    return e ? picked(e) : { act: "none", text: "select a peak, pit, wall, long pit, stairs, pyramid or ramp in the table to place it" };
  }

  /** Says under the map (and by the pointer's shape) what a click or
   * Enter at `cell` would do. */
  showIntent(cell, pick) {
    const hint = document.getElementById("map-hint");
    if (!cell || !this.preview) { hint.textContent = ""; this.overlay.style.cursor = ""; return; }
    const intent = this.intent(cell, pick);
    const shift = pick ? "" : " · Shift+click (Shift+Enter): select another obstacle here";
    hint.textContent = `Click: ${intent.text}${shift}`;
    this.overlay.style.cursor = { move: intent.row === this.page.selected() ? "move" : "pointer", place: "crosshair", none: "not-allowed" }[intent.act];
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

  /** A press at `cell` (`pick`: with Shift): does what `intent` says. */
  press(cell, pick) {
    const intent = this.intent(cell, pick);
    if (intent.act === "none") { this.page.hint(intent.text); return null; }
    if (intent.act === "move") {
      if (intent.row !== this.page.selected()) this.page.select(intent.row);
      return { kind: "move", start: cell, row: intent.row, k: intent.k, end: intent.end };
    }
    const i = intent.row;
    const ends = ENDS[this.page.rows()[i].type];
    const point = (k) => ({ [`x${k}.lo`]: String(cell.x), [`x${k}.hi`]: "", [`y${k}.lo`]: String(cell.y), [`y${k}.hi`]: "" });
    this.page.change(i, ends.length === 2 ? { ...point(1), ...point(2) } : point(1));
    return ends.length === 2 ? { kind: "line", row: i } : { kind: "move", start: cell, row: i, k: 1, end: endOf(this.page.rows()[i], 1) };
  }

  /** The pointer (or the keyboard's cursor) moved to `cell` mid-drag. */
  follow(cell) {
    const d = this.drag;
    if (!d || !cell) return;
    if (d.kind === "line") {
      this.page.change(d.row, { "x2.lo": String(cell.x), "x2.hi": "", "y2.lo": String(cell.y), "y2.hi": "" });
    } else {
      this.page.change(d.row, this.moved(d.end, d.k, cell.x - d.start.x, cell.y - d.start.y));
    }
  }

  finish() {
    if (this.drag) { this.drag = null; this.page.done(); }
  }

  /** Ends a drag or keyboard grab under way as a finished edit (Undo and
   * Redo call it first: a grab still held is the newest step, not lost). */
  letGo() { this.keyDrawing = false; this.finish(); }

  listen() {
    const o = this.overlay;
    o.addEventListener("pointerdown", (e) => {
      const cell = this.cellAt(e);
      if (!cell || e.button !== 0) return;
      e.preventDefault();
      o.setPointerCapture(e.pointerId);
      this.drag = this.press(cell, e.shiftKey);
      this.page.rendered();
    });
    o.addEventListener("pointermove", (e) => {
      const cell = this.cellAt(e);
      this.showReadout(cell);
      if (!this.drag) this.showIntent(cell, e.shiftKey);
      if (this.drag) { this.follow(cell); this.page.rendered(); }
    });
    o.addEventListener("pointerup", () => { this.finish(); this.page.rendered(); });
    o.addEventListener("pointercancel", () => { this.finish(); this.page.rendered(); });
    o.addEventListener("pointerleave", () => { if (!this.drag) { this.showReadout(this.cursor); this.showIntent(document.activeElement === o ? this.cursor : null, false); } });
    o.addEventListener("focus", () => {
      if (!this.cursor && this.preview) this.cursor = { x: this.preview.nx >> 1, y: this.preview.ny >> 1 };
      this.showReadout(this.cursor); this.showIntent(this.cursor, false); this.drawOverlay();
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
        if (!this.keyDrawing) this.showIntent(this.cursor, false);
        if (this.keyDrawing) this.follow(this.cursor);
        this.page.rendered();
      } else if (e.key === "Enter" || e.key === " ") {
        e.preventDefault();
        // Enter grabs or places at the cursor; the next Enter lets go.
        if (this.keyDrawing) { this.keyDrawing = false; this.finish(); } else {
          this.drag = this.press(this.cursor, e.shiftKey);
          this.keyDrawing = this.drag !== null;
        }
        this.page.rendered();
      } else if (e.key === "Escape" && this.keyDrawing) {
        this.keyDrawing = false; this.finish(); this.page.rendered();
      }
    });
  }
}

function metres(m) { return `${Number(m.toFixed(4))} m`; }
