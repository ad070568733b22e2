// The 3D view: every cell a column from the ground to its top (base +
// height·step), in WebGL, coloured by the top-down map's scale (colours.js)
// with pallet frames in wood. Every cell has a top, zero-height ones too, so
// the ground has no holes; a side is drawn only where a neighbour is lower.
// A ramp is drawn as its wedge over the columns of its staircase: its plane
// coloured from its foot's height to its top's, its sides and its head.
// Orbit with the mouse (drag, wheel) or the keyboard (arrows, + and −).
"use strict";

import { cellColour, palette } from "./colours.js";

const VERTEX_BYTES = 16; // position: 3 floats; colour: 3 bytes; a byte for the face's normal

// Each face's normal, by the index a vertex carries (the shader looks it up).
const NORMALS = [[0, 0, 1], [1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0]];

export class BlockView {
  constructor(canvas) {
    this.canvas = canvas;
    this.view = { yaw: -0.6, pitch: 0.9, zoom: 1.0 };
    this.size = 1; this.centre = [0, 0, 0]; this.count = 0;
    const gl = canvas.getContext("webgl", { preserveDrawingBuffer: true });
    this.gl = gl;
    if (!gl) return; // no WebGL: the map and the legend still work
    const compile = (type, source) => { const s = gl.createShader(type); gl.shaderSource(s, source); gl.compileShader(s); return s; };
    const p = gl.createProgram();
    gl.attachShader(p, compile(gl.VERTEX_SHADER, `
      attribute vec3 position; attribute vec3 colour; attribute float face;
      uniform mat4 view; uniform vec3 normals[5]; varying vec3 shade;
      void main() {
        vec3 normal = normals[int(face + 0.5)];
        float light = 0.45 + 0.55 * max(dot(normal, normalize(vec3(0.4, 0.3, 0.85))), 0.0);
        shade = colour * light; gl_Position = view * vec4(position, 1.0);
      }`));
    gl.attachShader(p, compile(gl.FRAGMENT_SHADER, `
      precision mediump float; varying vec3 shade;
      void main() { gl_FragColor = vec4(shade, 1.0); }`));
    gl.linkProgram(p);
    this.program = p;
    this.buffer = gl.createBuffer();
    gl.useProgram(p);
    gl.uniform3fv(gl.getUniformLocation(p, "normals"), new Float32Array(NORMALS.flat()));
    this.listen();
  }

  /** Builds the columns of a new preview (colours.js `decodePreview`). */
  show(preview) {
    if (!this.gl) return;
    const { nx, ny, heights } = preview;
    const s = preview.block_size, step = preview.step_height, base = preview.base;
    const top = (x, y) => base + heights[y * nx + x] * step;
    const near = (x, y) => (x < 0 || y < 0 || x >= nx || y >= ny ? 0 : top(x, y));
    // A ramp's staircase lies inside its wedge: its columns are not drawn
    // (their sides would flicker through the wedge's, in one plane).
    const ramps = (preview.ramps ?? []).filter((r) => r.rise > 0);
    const hidden = new Uint8Array(nx * ny);
    for (const r of ramps) {
      const [x0, y0, x1, y1] = r.cells;
      const run = r.along_y ? y1 - y0 + 1 : x1 - x0 + 1;
      for (let y = y0; y <= y1; y++) for (let x = x0; x <= x1; x++) {
        const i = r.along_y ? (r.ascending ? y - y0 : y1 - y) : (r.ascending ? x - x0 : x1 - x);
        // The plane's lowest point on the cell: at its edge nearer the foot.
        if (top(x, y) <= base + r.rise * step * i / run + 1e-9) hidden[y * nx + x] = 1;
      }
    }
    // Count first: one buffer, filled in place (a JS array grown by push
    // cost more than the server's whole answer).
    let quads = 0;
    for (let y = 0; y < ny; y++) for (let x = 0; x < nx; x++) {
      if (hidden[y * nx + x]) continue;
      const z = top(x, y);
      quads += 1;
      quads += (near(x + 1, y) < z) + (near(x - 1, y) < z) + (near(x, y + 1) < z) + (near(x, y - 1) < z);
    }
    quads += ramps.length * (base > 0 ? 5 : 4);
    const bytes = new ArrayBuffer(quads * 6 * VERTEX_BYTES);
    const f32 = new Float32Array(bytes), u8 = new Uint8Array(bytes);
    let v = 0;
    // `colour`: one for the quad, or one per corner (a function of it).
    const quad = (corners, colour, face) => {
      for (const k of [0, 1, 2, 0, 2, 3]) {
        const [px, py, pz] = corners[k];
        const c = typeof colour === "function" ? colour(k) : colour;
        const f = v * 4, b = v * VERTEX_BYTES + 12;
        f32[f] = px; f32[f + 1] = py; f32[f + 2] = pz;
        u8[b] = c[0]; u8[b + 1] = c[1]; u8[b + 2] = c[2]; u8[b + 3] = face;
        v += 1;
      }
    };
    for (let y = 0; y < ny; y++) for (let x = 0; x < nx; x++) {
      if (hidden[y * nx + x]) continue;
      const z = top(x, y), colour = cellColour(preview, x, y);
      const x0 = x * s, x1 = x0 + s, y0 = y * s, y1 = y0 + s;
      quad([[x0, y0, z], [x1, y0, z], [x1, y1, z], [x0, y1, z]], colour, 0);
      let n = near(x + 1, y);
      if (n < z) quad([[x1, y0, n], [x1, y1, n], [x1, y1, z], [x1, y0, z]], colour, 1);
      n = near(x - 1, y);
      if (n < z) quad([[x0, y1, n], [x0, y0, n], [x0, y0, z], [x0, y1, z]], colour, 2);
      n = near(x, y + 1);
      if (n < z) quad([[x1, y1, n], [x0, y1, n], [x0, y1, z], [x1, y1, z]], colour, 3);
      n = near(x, y - 1);
      if (n < z) quad([[x0, y0, n], [x1, y0, n], [x1, y0, z], [x0, y0, z]], colour, 4);
    }
    for (const r of ramps) this.wedge(r, { s, step, base, preview, quad });
    this.count = v;
    this.size = Math.max(nx, ny) * s;
    this.centre = [nx * s / 2, ny * s / 2, 0];
    const gl = this.gl;
    gl.bindBuffer(gl.ARRAY_BUFFER, this.buffer);
    gl.bufferData(gl.ARRAY_BUFFER, bytes, gl.STATIC_DRAW);
    this.render();
  }

  /** A ramp's wedge (docs/schemes.md, "Ramps"): drawn in its own frame, u
   * along its climb from the foot edge and v across, then placed. */
  wedge(ramp, { s, step, base, preview, quad }) {
    const [x0, y0, x1, y1] = ramp.cells;
    const along = ramp.along_y;
    const [lo, hi] = along ? [y0, y1 + 1] : [x0, x1 + 1];
    const [across0, across1] = along ? [x0, x1 + 1] : [y0, y1 + 1];
    const top = base + ramp.rise * step;
    // (u, v) in cells, u from the foot edge: the point in metres.
    const at = (u, v, z) => {
      const c = ramp.ascending ? lo + u : hi - u;
      return along ? [v * s, c * s, z] : [c * s, v * s, z];
    };
    const run = hi - lo, foot = palette(0, preview.lo, preview.hi), head = palette(ramp.rise, preview.lo, preview.hi);
    const [a, b] = [across0, across1];
    // The plane, foot to head (its colours as the map's at each end).
    quad([at(0, a, base), at(run, a, top), at(run, b, top), at(0, b, base)], (k) => (k === 1 || k === 2 ? head : foot), 0);
    // Which face index looks along +u, and along +v, once placed.
    const sign = ramp.ascending ? 1 : -1;
    const face = (dx, dy) => (dx > 0 ? 1 : dx < 0 ? 2 : dy > 0 ? 3 : 4);
    const [plusU, plusV] = along ? [face(0, sign), face(1, 0)] : [face(sign, 0), face(0, 1)];
    const minus = { 1: 2, 2: 1, 3: 4, 4: 3 };
    quad([at(run, a, 0), at(run, b, 0), at(run, b, top), at(run, a, top)], head, plusU);
    quad([at(0, a, 0), at(run, a, 0), at(run, a, top), at(0, a, base)], head, minus[plusV]);
    quad([at(run, b, 0), at(0, b, 0), at(0, b, base), at(run, b, top)], head, plusV);
    if (base > 0) quad([at(0, b, 0), at(0, a, 0), at(0, a, base), at(0, b, base)], foot, minus[plusU]);
  }

  /** Matches the canvas's pixels to its size on the page (it is as wide as
   * its column) and draws again. */
  fit() {
    const c = this.canvas;
    const width = Math.max(1, Math.round(c.clientWidth * (window.devicePixelRatio || 1)));
    const height = Math.round(width * 0.75);
    if (c.width !== width || c.height !== height) { c.width = width; c.height = height; this.render(); }
  }

  render() {
    const gl = this.gl;
    if (!gl) return;
    const { yaw, pitch, zoom } = this.view;
    const distance = 1.6 * this.size / zoom;
    const c = this.centre;
    const eye = [
      c[0] + distance * Math.cos(pitch) * Math.sin(yaw),
      c[1] - distance * Math.cos(pitch) * Math.cos(yaw),
      c[2] + distance * Math.sin(pitch),
    ];
    const f = normalise(c.map((ci, i) => ci - eye[i]));
    const r = normalise(cross(f, [0, 0, 1]));
    const u = cross(r, f);
    const lookAt = [r[0], u[0], -f[0], 0, r[1], u[1], -f[1], 0, r[2], u[2], -f[2], 0, -dot(r, eye), -dot(u, eye), dot(f, eye), 1];
    const aspect = gl.canvas.width / gl.canvas.height, near = distance / 50, far = distance * 4, t = 1 / Math.tan(0.4);
    const perspective = [t / aspect, 0, 0, 0, 0, t, 0, 0, 0, 0, (far + near) / (near - far), -1, 0, 0, 2 * far * near / (near - far), 0];
    gl.viewport(0, 0, gl.canvas.width, gl.canvas.height);
    gl.clearColor(0.87, 0.87, 0.92, 1); gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST);
    gl.useProgram(this.program);
    gl.uniformMatrix4fv(gl.getUniformLocation(this.program, "view"), false, new Float32Array(multiply(perspective, lookAt)));
    gl.bindBuffer(gl.ARRAY_BUFFER, this.buffer);
    const attribute = (name, size, type, normalised, offset) => {
      const a = gl.getAttribLocation(this.program, name);
      gl.enableVertexAttribArray(a);
      gl.vertexAttribPointer(a, size, type, normalised, VERTEX_BYTES, offset);
    };
    attribute("position", 3, gl.FLOAT, false, 0);
    attribute("colour", 3, gl.UNSIGNED_BYTE, true, 12);
    attribute("face", 1, gl.UNSIGNED_BYTE, false, 15);
    gl.drawArrays(gl.TRIANGLES, 0, this.count);
  }

  turn(yaw, pitch) {
    this.view.yaw += yaw;
    this.view.pitch = Math.min(1.5, Math.max(0.05, this.view.pitch + pitch));
    this.render();
  }

  zoomBy(factor) {
    this.view.zoom = Math.min(8, Math.max(0.3, this.view.zoom * factor));
    this.render();
  }

  listen() {
    const canvas = this.canvas;
    let drag = null;
    canvas.addEventListener("pointerdown", (e) => { drag = [e.clientX, e.clientY]; canvas.setPointerCapture(e.pointerId); });
    canvas.addEventListener("pointerup", () => { drag = null; });
    canvas.addEventListener("pointermove", (e) => {
      if (!drag) return;
      this.turn((e.clientX - drag[0]) * 0.01, (e.clientY - drag[1]) * 0.01);
      drag = [e.clientX, e.clientY];
    });
    canvas.addEventListener("wheel", (e) => { e.preventDefault(); this.zoomBy(e.deltaY < 0 ? 1.1 : 0.9); });
    canvas.addEventListener("keydown", (e) => {
      const turns = { ArrowLeft: [-0.1, 0], ArrowRight: [0.1, 0], ArrowUp: [0, 0.1], ArrowDown: [0, -0.1] };
      if (turns[e.key]) { e.preventDefault(); this.turn(...turns[e.key]); }
      else if (e.key === "+" || e.key === "=") { e.preventDefault(); this.zoomBy(1.1); }
      else if (e.key === "-" || e.key === "_") { e.preventDefault(); this.zoomBy(0.9); }
    });
    new ResizeObserver(() => this.fit()).observe(canvas);
  }
}

function cross(a, b) { return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]; }
function dot(a, b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
function normalise(a) { const l = Math.hypot(...a) || 1; return a.map((v) => v / l); }
function multiply(a, b) {
  const out = new Array(16).fill(0);
  for (let i = 0; i < 4; i++) for (let j = 0; j < 4; j++) for (let k = 0; k < 4; k++) out[j * 4 + i] += a[k * 4 + i] * b[j * 4 + k];
  return out;
}
