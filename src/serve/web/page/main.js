// halfcast's page: wires the painter (paint.js over ansi.js), the connection (link.js), the
// keys and touch controls (input.js, touch.js), the layout (layout.js) and what shows around
// the game (landing.js). A panel module (such as the ray debugger) mounts through
// `window.halfcast`: `link.on(key, fn)` for the server's text messages, `touch.onViewTap` and
// `send(msg)`.

import { Screen } from "./paint.js";
import { Link } from "./link.js";
import { Input } from "./input.js";
import { Touch } from "./touch.js";
import { Landing, titled } from "./landing.js";
import { fit, same, touchScreen } from "./layout.js";
import { wireRays } from "./raywire.js";

const $ = (id) => document.getElementById(id);
const touch = touchScreen();
const screen = new Screen($("pixels"), $("cells"));
let shape = null;

// Lays the page out for the window now; true when the grid changed.
function layOut() {
  const next = fit(touch);
  if (shape && same(shape, next)) return false;
  shape = next;
  screen.resize(next.cols, next.rows, next.cellW, next.cellH);
  const s = $("screen").style;
  s.left = next.left + "px";
  s.top = next.top + "px";
  document.body.dataset.controls = next.controls;
  $("touch").style.height = next.controls === "below" ? next.pane + "px" : "";
  $("buttons").style.width = next.controls === "side" ? next.pane + "px" : "";
  return true;
}

// The game as the link sees it: frames painted and acked in order, with figures for tests.
const game = {
  frames: 0,
  connections: 0,
  paintMs: 0,
  bytes: 0,
  connected() {
    this.frames = 0;
    this.connections++;
  },
  frame(bytes) {
    const t = performance.now();
    screen.feed(bytes);
    screen.paint();
    this.paintMs += performance.now() - t;
    this.bytes += bytes.length;
    this.frames++;
    link.send({ ack: this.frames });
  },
  ended() {
    input.forget();
  },
};

const link = new Link(game, (state) => landing.show(state, link.who?.name));
// Keys count only on an open connection: a key pressed while connecting would otherwise be
// held here with its press never sent.
const input = new Input((msg) => link.send(msg), () => link.ws?.readyState === WebSocket.OPEN);
const spectate = new URLSearchParams(location.search).has("spectate");
const landing = new Landing({
  spectate,
  touch,
  play: (name, watch) => {
    layOut();
    link.start(name, watch, () => {
      layOut();
      return [screen.cols, screen.rows];
    });
  },
  quit: () => link.quit(),
});
const controls = new Touch(input, { pad: $("pad"), knob: $("knob"), buttons: $("touch"), view: $("screen") });
input.attach();
layOut();
titled();

// A new window size is a new session size (the server clamps it, as an SSH pty's).
let resizing = 0;
function resized() {
  clearTimeout(resizing);
  resizing = setTimeout(() => {
    if (layOut()) link.send({ size: [screen.cols, screen.rows] });
  }, 100);
}
addEventListener("resize", resized);
addEventListener("orientationchange", resized);
window.visualViewport?.addEventListener("resize", resized);

// The ray debugger: a click on the view debugs its column; `/?pos=…` shows a shared ray.
const rays = wireRays({
  link,
  grid: $("pixels"),
  dock: $("raydock"),
  touch: controls,
  cols: () => screen.cols,
  rows: () => screen.rows,
});

// For tests, panels and the curious.
window.halfcast = { screen, game, link, input, touch: controls, rays, send: (msg) => link.send(msg) };
