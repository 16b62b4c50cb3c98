// Where things go on the screen: the cell size and grid that fit the window (never wider than
// the device), and where the touch controls sit: below the view on a tall screen; on a wide one
// the buttons in a column beside it and the stick over the view's lower left.

// The fewest columns a narrow screen gets: cells shrink (down to MIN_CELL_W) rather than show
// less of the game than this.
const WANT_COLS = 60;
const MAX_CELL_W = 10;
const MIN_CELL_W = 5;
// On a tall touch screen, the share of the height the controls take below the view (at most
// CONTROLS_MAX px).
const CONTROLS_SHARE = 0.36;
const CONTROLS_MAX = 320;
// On a wide touch screen, the width of the buttons' column beside the view.
const SIDE_W = 136;

// Whether the screen is touched rather than pointed at: touch controls show.
export function touchScreen() {
  return navigator.maxTouchPoints > 0 || matchMedia("(pointer: coarse)").matches;
}

// The visible area in CSS pixels (the visual viewport where the browser has one: it leaves out
// an on-screen keyboard and pinch zoom).
export function viewport() {
  const v = window.visualViewport;
  const w = Math.floor(v ? Math.min(v.width, innerWidth) : innerWidth);
  const h = Math.floor(v ? Math.min(v.height, innerHeight) : innerHeight);
  return [w, h];
}

// The layout for a `w` × `h` screen: cells of cellW × cellH px, a cols × rows grid at
// (left, top), and `controls`: "none", "below" (a pane of `pane` px under the grid) or "side"
// (a column of `pane` px at the right).
export function fit(touch, [w, h] = viewport()) {
  let controls = "none", gridW = w, gridH = h, pane = 0;
  if (touch && h > w) {
    controls = "below";
    pane = Math.min(Math.round(h * CONTROLS_SHARE), CONTROLS_MAX);
    gridH = h - pane;
  } else if (touch) {
    controls = "side";
    pane = Math.min(SIDE_W, Math.floor(w / 4));
    gridW = w - pane;
  }
  const cellW = Math.max(MIN_CELL_W, Math.min(MAX_CELL_W, Math.floor(gridW / WANT_COLS)));
  const cellH = 2 * cellW;
  const cols = Math.max(1, Math.floor(gridW / cellW));
  const rows = Math.max(1, Math.floor(gridH / cellH));
  const left = Math.floor((gridW - cols * cellW) / 2);
  const top = controls === "below" ? 0 : Math.floor((gridH - rows * cellH) / 2);
  return { w, h, cellW, cellH, cols, rows, left, top, controls, pane };
}

// Whether two layouts draw the same grid the same way.
export function same(a, b) {
  return a.cols === b.cols && a.rows === b.rows && a.cellW === b.cellW && a.controls === b.controls
    && a.left === b.left && a.top === b.top;
}
