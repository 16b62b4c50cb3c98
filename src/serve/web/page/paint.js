// The painter: the grid's changed cells onto two canvases.
//
// Every cell is a 1×2-pixel block of an ImageData (cols × 2·rows) scaled up by CSS with crisp
// pixels; that is all a half-block view needs. Cells that are not half-blocks (quadrant, sextant
// and octant blocks, box lines, text) are drawn over it on a second canvas at the screen's own
// resolution: blocks and lines as rectangles on whole pixels, text in a monospace font.

import { BLOCKS } from "./tables.js";
import { Grid, BOLD, DIM, ITALIC, UNDERLINE, REVERSE } from "./ansi.js";

const DEFAULT_FG = 0xe5e5e5;
const DEFAULT_BG = 0x000000;

export class Screen extends Grid {
  constructor(pixels, cells) {
    super(1, 1);
    this.pixels = pixels;
    this.cells = cells;
    this.px = pixels.getContext("2d");
    this.cx = cells.getContext("2d");
    this.cellW = 10;
    this.cellH = 20;
  }

  // A grid of cols × rows cells, each cellW × cellH CSS pixels.
  resize(cols, rows, cellW = this.cellW, cellH = this.cellH) {
    this.reset(cols, rows);
    this.cellW = cellW;
    this.cellH = cellH;
    this.over = new Uint8Array(cols * rows);
    this.pixels.width = cols;
    this.pixels.height = rows * 2;
    this.img = this.px.createImageData(cols, rows * 2);
    const dpr = window.devicePixelRatio || 1;
    const w = cols * cellW, h = rows * cellH;
    for (const c of [this.pixels, this.cells]) {
      c.style.width = w + "px";
      c.style.height = h + "px";
    }
    this.cells.width = Math.round(w * dpr);
    this.cells.height = Math.round(h * dpr);
    this.sx = this.cells.width / cols;
    this.sy = this.cells.height / rows;
    this.cx.textBaseline = "middle";
    this.cx.textAlign = "center";
    this.font = Math.floor(this.sy * 0.8) + "px ui-monospace, 'DejaVu Sans Mono', monospace";
    this.lastFont = null;
  }

  // Draws the cells that changed since the last call.
  paint() {
    if (!this.anyDirty) return;
    this.anyDirty = false;
    const d = this.img.data, cols = this.cols;
    let lo = this.rows, hi = -1;
    for (let r = 0; r < this.rows; r++) {
      for (let c = 0; c < cols; c++) {
        const i = r * cols + c;
        if (!this.dirty[i]) continue;
        this.dirty[i] = 0;
        if (r < lo) lo = r;
        if (r > hi) hi = r;
        let f = this.fg[i] < 0 ? DEFAULT_FG : this.fg[i];
        let b = this.bg[i] < 0 ? DEFAULT_BG : this.bg[i];
        if (this.at[i] & REVERSE) { const t = f; f = b; b = t; }
        const cp = this.ch[i];
        let top = b, bot = b, half = true;
        if (cp === 0x2580) top = f;
        else if (cp === 0x2584) bot = f;
        else if (cp === 0x2588) { top = f; bot = f; }
        else if (cp !== 32) half = false;
        let o = (2 * r * cols + c) * 4;
        d[o] = top >> 16; d[o + 1] = (top >> 8) & 255; d[o + 2] = top & 255; d[o + 3] = 255;
        o += cols * 4;
        d[o] = bot >> 16; d[o + 1] = (bot >> 8) & 255; d[o + 2] = bot & 255; d[o + 3] = 255;
        if (half) {
          if (this.over[i]) { this.over[i] = 0; this.clearCell(r, c); }
        } else {
          this.over[i] = 1;
          this.drawCell(r, c, cp, f, b, this.at[i]);
        }
      }
    }
    if (hi >= 0) this.px.putImageData(this.img, 0, 0, 0, lo * 2, cols, (hi - lo + 1) * 2);
  }

  edges(r, c) {
    const x0 = Math.round(c * this.sx), x1 = Math.round((c + 1) * this.sx);
    const y0 = Math.round(r * this.sy), y1 = Math.round((r + 1) * this.sy);
    return [x0, y0, x1, y1];
  }

  clearCell(r, c) {
    const [x0, y0, x1, y1] = this.edges(r, c);
    this.cx.clearRect(x0, y0, x1 - x0, y1 - y0);
  }

  drawCell(r, c, cp, f, b, at) {
    const cx = this.cx;
    const [x0, y0, x1, y1] = this.edges(r, c);
    cx.fillStyle = css(b);
    cx.fillRect(x0, y0, x1 - x0, y1 - y0);
    cx.fillStyle = css(f);
    const block = BLOCKS[cp];
    if (block) {
      const [rows, mask] = block;
      for (let k = 0; k < rows * 2; k++) {
        if (!(mask & (1 << k))) continue;
        const sx = k & 1, sy = k >> 1;
        const ax = x0 + Math.round(((x1 - x0) * sx) / 2), bx = x0 + Math.round(((x1 - x0) * (sx + 1)) / 2);
        const ay = y0 + Math.round(((y1 - y0) * sy) / rows), by = y0 + Math.round(((y1 - y0) * (sy + 1)) / rows);
        cx.fillRect(ax, ay, bx - ax, by - ay);
      }
      return;
    }
    if (boxLine(cx, cp, x0, y0, x1, y1)) return;
    const font = (at & BOLD ? "bold " : "") + (at & ITALIC ? "italic " : "") + this.font;
    // Setting a font parses it: only when it changes.
    if (font !== this.lastFont) { cx.font = font; this.lastFont = font; }
    if (at & DIM) cx.globalAlpha = 0.6;
    cx.fillText(String.fromCodePoint(cp), (x0 + x1) / 2, (y0 + y1) / 2);
    cx.globalAlpha = 1;
    if (at & UNDERLINE) cx.fillRect(x0, y1 - Math.max(1, Math.round(this.sy / 12)), x1 - x0, Math.max(1, Math.round(this.sy / 12)));
  }
}

// Light box lines (─ │ ┌ ┐ └ ┘ ├ ┤ ┬ ┴ ┼ and the rounded corners) as rectangles through the
// cell's middle, so neighbouring cells join without gaps; false for any other character.
const LINES = {
  0x2500: "lr", 0x2502: "ud", 0x250c: "rd", 0x2510: "ld", 0x2514: "ru", 0x2518: "lu",
  0x251c: "udr", 0x2524: "udl", 0x252c: "lrd", 0x2534: "lru", 0x253c: "lrud",
  0x256d: "rd", 0x256e: "ld", 0x256f: "lu", 0x2570: "ru",
};
function boxLine(cx, cp, x0, y0, x1, y1) {
  const arms = LINES[cp];
  if (!arms) return false;
  const t = Math.max(1, Math.round((y1 - y0) / 16));
  const mx = Math.round((x0 + x1 - t) / 2), my = Math.round((y0 + y1 - t) / 2);
  if (arms.includes("l")) cx.fillRect(x0, my, mx + t - x0, t);
  if (arms.includes("r")) cx.fillRect(mx, my, x1 - mx, t);
  if (arms.includes("u")) cx.fillRect(mx, y0, t, my + t - y0);
  if (arms.includes("d")) cx.fillRect(mx, my, t, y1 - my);
  return true;
}

function css(c) {
  return "#" + (c | 0x1000000).toString(16).slice(1);
}
