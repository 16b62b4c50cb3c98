// halfcast's page: draws the game's own frame bytes (the encoder's subset of ANSI) and sends
// key presses and releases. PALETTE and BLOCKS come first, from the server (page.rs).
//
// Drawing: every cell is a 1×2-pixel block of an ImageData (cols × 2·rows) scaled up by CSS
// with crisp pixels; that is all a half-block view needs. Cells that are not half-blocks
// (quadrant, sextant and octant blocks, box lines, text) are drawn over it on a second canvas at
// the screen's own resolution: blocks and lines as rectangles on whole pixels, text in a
// monospace font.

const CELL_W = 10;
const CELL_H = 20;
const DEFAULT_FG = 0xe5e5e5;
const DEFAULT_BG = 0x000000;
const ANSI16 = PALETTE.slice(0, 16).map(([r, g, b]) => (r << 16) | (g << 8) | b);
const P256 = PALETTE.map(([r, g, b]) => (r << 16) | (g << 8) | b);
const BOLD = 1, DIM = 2, ITALIC = 4, UNDERLINE = 8, REVERSE = 16;

class Screen {
  constructor(pixels, cells) {
    this.pixels = pixels;
    this.cells = cells;
    this.px = pixels.getContext("2d");
    this.cx = cells.getContext("2d");
    this.resize(80, 24);
  }

  resize(cols, rows) {
    this.cols = cols;
    this.rows = rows;
    const n = cols * rows;
    this.ch = new Uint32Array(n).fill(32);
    this.fg = new Int32Array(n).fill(-1);
    this.bg = new Int32Array(n).fill(-1);
    this.at = new Uint8Array(n);
    this.over = new Uint8Array(n);
    this.dirty = new Uint8Array(n).fill(1);
    this.anyDirty = true;
    this.pixels.width = cols;
    this.pixels.height = rows * 2;
    this.img = this.px.createImageData(cols, rows * 2);
    const dpr = window.devicePixelRatio || 1;
    const w = cols * CELL_W, h = rows * CELL_H;
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

// The browser keys play never takes from the browser, and the keys the page sends by name.
const NAMED = new Set(["ArrowUp", "ArrowDown", "ArrowLeft", "ArrowRight", "Home", "End", "PageUp",
  "PageDown", "Insert", "Delete", "Enter", "Tab", "Backspace", "Escape",
  "F1", "F2", "F3", "F4", "F5", "F6", "F7", "F8", "F9", "F10", "F11", "F12"]);

class Game {
  constructor(screen) {
    this.screen = screen;
    this.ws = null;
    this.held = new Map();
    this.frames = 0;
    this.paintMs = 0;
    this.bytes = 0;
  }

  grid() {
    return [Math.max(20, Math.floor(innerWidth / CELL_W)), Math.max(8, Math.floor(innerHeight / CELL_H))];
  }

  start(name, spectate) {
    const [cols, rows] = this.grid();
    this.screen.resize(cols, rows);
    const q = new URLSearchParams({ name, cols, rows });
    if (spectate) q.set("spectate", "");
    // Beside the page, wherever a proxy serves it; wss: when the page came over https:.
    const url = new URL("ws", location.href);
    url.protocol = location.protocol === "https:" ? "wss:" : "ws:";
    url.search = q.toString();
    const ws = new WebSocket(url);
    ws.binaryType = "arraybuffer";
    ws.onmessage = (e) => this.frame(e.data);
    ws.onclose = (e) => this.closed(e.reason || "the connection closed");
    this.ws = ws;
    this.frames = 0;
  }

  frame(data) {
    if (typeof data === "string") return;
    const t = performance.now();
    const bytes = new Uint8Array(data);
    this.screen.feed(bytes);
    this.screen.paint();
    this.paintMs += performance.now() - t;
    this.bytes += bytes.length;
    this.frames++;
    this.send({ ack: this.frames });
  }

  send(msg) {
    if (this.ws && this.ws.readyState === WebSocket.OPEN) this.ws.send(JSON.stringify(msg));
  }

  closed(reason) {
    this.ws = null;
    this.held.clear();
    document.getElementById("said").textContent = reason;
    document.getElementById("join").classList.remove("hidden");
  }

  resized() {
    if (!this.ws) return;
    const [cols, rows] = this.grid();
    if (cols === this.screen.cols && rows === this.screen.rows) return;
    this.screen.resize(cols, rows);
    this.send({ size: [cols, rows] });
  }

  key(e, down) {
    if (!this.ws) return;
    if (down) {
      e.preventDefault();
      if (e.repeat || this.held.has(e.code)) return;
      const named = NAMED.has(e.key);
      if (!named && [...e.key].length !== 1) return;
      const k = { key: e.key, ctrl: e.ctrlKey && !named && /^[a-z]$/i.test(e.key) };
      this.held.set(e.code, k);
      this.send(k.ctrl ? { key: k.key, down: true, ctrl: true } : { key: k.key, down: true });
    } else {
      const k = this.held.get(e.code);
      if (!k) return;
      e.preventDefault();
      this.held.delete(e.code);
      this.send(k.ctrl ? { key: k.key, down: false, ctrl: true } : { key: k.key, down: false });
    }
  }

  // Every held key let go: the page lost focus or was hidden, and will see no keyup.
  releaseAll() {
    for (const k of this.held.values()) {
      this.send(k.ctrl ? { key: k.key, down: false, ctrl: true } : { key: k.key, down: false });
    }
    this.held.clear();
  }
}

const screen = new Screen(document.getElementById("pixels"), document.getElementById("cells"));
const game = new Game(screen);
const form = document.getElementById("join");
const params = new URLSearchParams(location.search);
document.getElementById("name").value = params.get("name") || "";
form.addEventListener("submit", (e) => {
  e.preventDefault();
  form.classList.add("hidden");
  document.activeElement.blur();
  game.start(document.getElementById("name").value, params.has("spectate"));
});
addEventListener("keydown", (e) => game.key(e, true));
addEventListener("keyup", (e) => game.key(e, false));
addEventListener("blur", () => game.releaseAll());
document.addEventListener("visibilitychange", () => { if (document.hidden) game.releaseAll(); });
let resizing = 0;
addEventListener("resize", () => {
  clearTimeout(resizing);
  resizing = setTimeout(() => game.resized(), 100);
});
// For tests and the curious: the painter and its figures.
window.halfcast = { screen, game };
