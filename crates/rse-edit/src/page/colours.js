// One colour scale for both views: rse-core's `preview::palette` and
// `FRAME_RGB`, in the same integer maths, so the top-down view is
// `preview.png` pixel for pixel and the 3D view colours a height alike.
"use strict";

/** Pallet frame cells: wood, outside the blue–green–red scale. */
export const FRAME_RGB = [150, 111, 71];

/** The colour of height `h` on a map spanning `lo..=hi` steps. */
export function palette(h, lo, hi) {
  const t = hi > lo ? Math.floor(Math.max(h - lo, 0) * 510 / (hi - lo)) : 0;
  return t <= 255 ? [0, t, 255 - t] : [t - 255, 510 - t, 0];
}

/** Whether cell (x, y) is on a pallet frame line (`period`: null without frames). */
export function isFrame(period, x, y) {
  return period !== null && period !== undefined && (x % period === 0 || y % period === 0);
}

/** The cell's colour: wood for frame, else the scale's. */
export function cellColour(preview, x, y) {
  return isFrame(preview.frame_period, x, y)
    ? FRAME_RGB
    : palette(preview.heights[y * preview.nx + x], preview.lo, preview.hi);
}

/** The server's preview answer with its base64 heights decoded into
 * `heights` (row y = 0 first, x fastest): one or two bytes a cell. */
export function decodePreview(answer) {
  const text = atob(answer.heights);
  const bytes = new Uint8Array(text.length);
  for (let i = 0; i < text.length; i++) bytes[i] = text.charCodeAt(i);
  // Two bytes a cell are little-endian, as every browser's typed arrays.
  const heights = answer.bytes_per_height === 2
    ? new Uint16Array(bytes.buffer, 0, bytes.length / 2)
    : bytes;
  return { ...answer, heights };
}

/** The heights of a legend: every height when there are few, else about
 * `count` evenly spread from lo to hi. */
export function legendHeights(lo, hi, count = 7) {
  if (hi < lo) return [];
  if (hi - lo + 1 <= count) return Array.from({ length: hi - lo + 1 }, (_, i) => lo + i);
  return Array.from({ length: count }, (_, i) => Math.round(lo + (hi - lo) * i / (count - 1)));
}
