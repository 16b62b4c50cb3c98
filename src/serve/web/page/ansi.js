// The ANSI reader: the encoder's subset of ANSI (cursor moves, erases, SGR colours and
// attributes, UTF-8 text) read into a grid of cells. It draws nothing; paint.js does.

import { PALETTE } from "./tables.js";

export const ANSI16 = PALETTE.slice(0, 16).map(([r, g, b]) => (r << 16) | (g << 8) | b);
export const P256 = PALETTE.map(([r, g, b]) => (r << 16) | (g << 8) | b);
export const BOLD = 1, DIM = 2, ITALIC = 4, UNDERLINE = 8, REVERSE = 16;

// Cells as parallel arrays: code point, foreground and background (0xRRGGBB, -1 for the
// default), attributes, and whether the cell changed since the painter last drew it.
export class Grid {
  constructor(cols, rows) {
    this.reset(cols, rows);
  }

  reset(cols, rows) {
    this.cols = cols;
    this.rows = rows;
    const n = cols * rows;
    this.ch = new Uint32Array(n).fill(32);
    this.fg = new Int32Array(n).fill(-1);
    this.bg = new Int32Array(n).fill(-1);
    this.at = new Uint8Array(n);
    this.dirty = new Uint8Array(n).fill(1);
    this.anyDirty = true;
    this.row = 0; this.col = 0; this.cfg = -1; this.cbg = -1; this.cat = 0;
    this.esc = 0; this.params = ""; this.utf = 0; this.need = 0;
  }

  // Reads one frame's bytes into the grid.
  feed(bytes) {
    for (let i = 0; i < bytes.length; i++) {
      const b = bytes[i];
      if (this.need > 0) {
        if ((b & 0xc0) === 0x80) {
          this.utf = (this.utf << 6) | (b & 0x3f);
          if (--this.need === 0) this.put(this.utf);
          continue;
        }
        this.need = 0;
      }
      if (this.esc === 1) {
        this.esc = b === 0x5b ? 2 : 0;
        this.params = "";
        continue;
      }
      if (this.esc === 2) {
        if (b >= 0x40 && b <= 0x7e) {
          this.esc = 0;
          this.csi(b, this.params);
        } else if (this.params.length < 64) {
          this.params += String.fromCharCode(b);
        }
        continue;
      }
      if (b === 0x1b) this.esc = 1;
      else if (b === 0x0d) this.col = 0;
      else if (b === 0x0a) this.row = Math.min(this.row + 1, this.rows - 1);
      else if (b === 0x08) this.col = Math.max(this.col - 1, 0);
      else if (b < 0x20 || b === 0x7f) { /* other controls draw nothing */ }
      else if (b < 0x80) this.put(b);
      else if ((b & 0xe0) === 0xc0) { this.utf = b & 0x1f; this.need = 1; }
      else if ((b & 0xf0) === 0xe0) { this.utf = b & 0x0f; this.need = 2; }
      else if ((b & 0xf8) === 0xf0) { this.utf = b & 0x07; this.need = 3; }
    }
  }

  put(cp) {
    if (this.col >= this.cols) {
      this.col = 0;
      this.row = Math.min(this.row + 1, this.rows - 1);
    }
    const i = this.row * this.cols + this.col;
    if (this.ch[i] !== cp || this.fg[i] !== this.cfg || this.bg[i] !== this.cbg || this.at[i] !== this.cat) {
      this.ch[i] = cp; this.fg[i] = this.cfg; this.bg[i] = this.cbg; this.at[i] = this.cat;
      this.dirty[i] = 1;
      this.anyDirty = true;
    }
    this.col++;
  }

  csi(final, p) {
    if (p.startsWith("?") || p.startsWith(">") || p.startsWith("<") || p.startsWith("=")) return;
    const n = p.split(";").map((s) => (s === "" ? 0 : parseInt(s, 10) || 0));
    switch (final) {
      case 0x48: case 0x66: // H, f
        this.row = Math.min(Math.max((n[0] || 1) - 1, 0), this.rows - 1);
        this.col = Math.min(Math.max((n[1] || 1) - 1, 0), this.cols - 1);
        break;
      case 0x43: this.col = Math.min(this.col + (n[0] || 1), this.cols - 1); break; // C
      case 0x44: this.col = Math.max(this.col - (n[0] || 1), 0); break; // D
      case 0x41: this.row = Math.max(this.row - (n[0] || 1), 0); break; // A
      case 0x42: this.row = Math.min(this.row + (n[0] || 1), this.rows - 1); break; // B
      case 0x47: this.col = Math.min(Math.max((n[0] || 1) - 1, 0), this.cols - 1); break; // G
      case 0x4a: if (n[0] === 2 || n[0] === 3) this.clear(0, this.cols * this.rows); break; // J
      case 0x4b: this.clear(this.row * this.cols + this.col, (this.row + 1) * this.cols); break; // K
      case 0x6d: this.sgr(n); break; // m
    }
  }

  clear(from, to) {
    for (let i = from; i < to; i++) {
      this.ch[i] = 32; this.fg[i] = this.cfg; this.bg[i] = this.cbg; this.at[i] = 0;
      this.dirty[i] = 1;
    }
    this.anyDirty = true;
  }

  sgr(n) {
    for (let k = 0; k < n.length; k++) {
      const v = n[k];
      if (v === 0) { this.cfg = -1; this.cbg = -1; this.cat = 0; }
      else if (v === 1) this.cat |= BOLD;
      else if (v === 2) this.cat |= DIM;
      else if (v === 3) this.cat |= ITALIC;
      else if (v === 4) this.cat |= UNDERLINE;
      else if (v === 7) this.cat |= REVERSE;
      else if (v === 22) this.cat &= ~(BOLD | DIM);
      else if (v === 23) this.cat &= ~ITALIC;
      else if (v === 24) this.cat &= ~UNDERLINE;
      else if (v === 27) this.cat &= ~REVERSE;
      else if (v >= 30 && v <= 37) this.cfg = ANSI16[v - 30];
      else if (v >= 90 && v <= 97) this.cfg = ANSI16[v - 82];
      else if (v >= 40 && v <= 47) this.cbg = ANSI16[v - 40];
      else if (v >= 100 && v <= 107) this.cbg = ANSI16[v - 92];
      else if (v === 39) this.cfg = -1;
      else if (v === 49) this.cbg = -1;
      else if (v === 38 || v === 48) {
        let c = -1;
        if (n[k + 1] === 2) { c = ((n[k + 2] & 255) << 16) | ((n[k + 3] & 255) << 8) | (n[k + 4] & 255); k += 4; }
        else if (n[k + 1] === 5) { c = P256[n[k + 2] & 255]; k += 2; }
        if (v === 38) this.cfg = c; else this.cbg = c;
      }
    }
  }

  // The text of row `r` (for tests and the curious: the status line's figures).
  text(r) {
    let s = "";
    for (let c = 0; c < this.cols; c++) s += String.fromCodePoint(this.ch[r * this.cols + c]);
    return s;
  }
}
