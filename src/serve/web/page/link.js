// The connection: one WebSocket to /ws at a time. Frames come in as binary messages, raw or
// (first byte 0x00) raw DEFLATE, and are handed to the game strictly in order, each acked once
// drawn; text messages are one JSON object each, dispatched on their key. When the connection
// is lost the link comes back by itself with the same name (a restart's own wait, else back-off
// with jitter) and says so; a normal close or a policy close goes back to the form.

// Back-off between attempts after an abnormal loss, in seconds (the last repeats).
const BACKOFF = [1, 2, 4, 8, 15];
// Close codes that end the game for good: the form shows their reason.
const FINAL = new Set([1000, 1003, 1008, 1009]);
// "service restart": the reason ends `reconnect to continue in N s`.
const RESTART = 1012;

// What to do after a close: `{ wait, why }` (seconds before the next attempt, and what to show)
// or `null` for the form. `attempt` counts failures since the last frame.
export function afterClose(code, reason, attempt) {
  if (FINAL.has(code)) return null;
  const jitter = Math.random();
  if (code === RESTART) {
    const m = /in (\d+) s/.exec(reason || "");
    return { wait: (m ? Number(m[1]) : 5) + jitter, why: "the world restarts" };
  }
  const step = BACKOFF[Math.min(attempt, BACKOFF.length - 1)];
  return { wait: step + jitter, why: reason || "the connection was lost" };
}

async function inflate(bytes) {
  const stream = new Blob([bytes]).stream().pipeThrough(new DecompressionStream("deflate-raw"));
  return new Uint8Array(await new Response(stream).arrayBuffer());
}

export class Link {
  // `game` takes `connected()`, `frame(bytes)` and `ended()`; `show(state)` is told of
  // { kind: "connecting" | "playing" | "waiting" | "form", why, until, attempt }.
  constructor(game, show) {
    this.game = game;
    this.show = show;
    this.ws = null;
    this.handlers = new Map();
    this.attempt = 0;
    this.timer = 0;
    this.who = null;
  }

  // A handler for the server's text messages named `key` (contract: one top-level key each).
  on(key, fn) {
    this.handlers.set(key, fn);
  }

  // Plays as `name` (a spectator when `spectate`) at `size` = [cols, rows], and keeps playing
  // across restarts until `quit()` or a final close.
  start(name, spectate, size) {
    this.who = { name, spectate };
    this.attempt = 0;
    this.connect(size);
  }

  connect(size) {
    clearTimeout(this.timer);
    const [cols, rows] = size();
    const q = new URLSearchParams({ name: this.who.name, cols, rows });
    if (this.who.spectate) q.set("spectate", "");
    // Beside the page, wherever a proxy serves it; wss: when the page came over https:.
    const url = new URL("ws", location.href);
    url.protocol = location.protocol === "https:" ? "wss:" : "ws:";
    url.search = q.toString();
    const ws = new WebSocket(url);
    ws.binaryType = "arraybuffer";
    this.ws = ws;
    this.chain = Promise.resolve();
    this.pending = 0;
    this.show({ kind: "connecting", attempt: this.attempt });
    ws.onopen = () => { if (ws === this.ws) this.game.connected(); };
    ws.onmessage = (e) => { if (ws === this.ws) this.message(ws, e.data); };
    ws.onclose = (e) => { if (ws === this.ws) this.closed(e.code, e.reason, size); };
  }

  message(ws, data) {
    if (typeof data === "string") {
      this.inOrder(ws, data, (text) => this.text(text));
      return;
    }
    const bytes = new Uint8Array(data);
    if (this.attempt !== 0 || this.playing !== ws) {
      this.attempt = 0;
      this.playing = ws;
      this.show({ kind: "playing" });
    }
    const frame = bytes.length > 0 && bytes[0] === 0 ? inflate(bytes.subarray(1)) : bytes;
    this.inOrder(ws, frame, (f) => this.game.frame(f));
  }

  // Hands `v` (a value, or a promise of one) to `use` after everything that came before it on
  // `ws`: at once when nothing waits, else after the inflating frames before it.
  inOrder(ws, v, use) {
    if (this.pending === 0 && !(v instanceof Promise)) {
      use(v);
      return;
    }
    this.pending++;
    this.chain = this.chain.then(() => v).then(
      (got) => { this.pending--; if (ws === this.ws) use(got); },
      // A frame that does not inflate is a broken connection (4000, ours): connect again.
      () => { this.pending--; if (ws === this.ws) ws.close(4000, "a frame did not inflate"); },
    );
  }

  text(text) {
    let msg;
    try { msg = JSON.parse(text); } catch { return; }
    if (!msg || typeof msg !== "object") return;
    for (const [key, value] of Object.entries(msg)) {
      const fn = this.handlers.get(key);
      if (fn) fn(value);
    }
  }

  send(msg) {
    if (this.ws && this.ws.readyState === WebSocket.OPEN) this.ws.send(JSON.stringify(msg));
  }

  closed(code, reason, size) {
    this.ws = null;
    this.playing = null;
    this.game.ended();
    const next = this.quitting ? null : afterClose(code, reason, this.attempt);
    if (!next) {
      this.who = null;
      this.show({ kind: "form", why: this.quitting ? "you left the game" : reason || "the game ended" });
      this.quitting = false;
      return;
    }
    this.attempt++;
    this.show({ kind: "waiting", why: next.why, until: performance.now() + next.wait * 1000, attempt: this.attempt });
    this.timer = setTimeout(() => this.connect(size), next.wait * 1000);
  }

  // Leaves the game (the Quit button): closes normally, no reconnecting.
  quit() {
    clearTimeout(this.timer);
    if (this.ws) {
      this.quitting = true;
      this.ws.close(1000, "quit");
    } else if (this.who) {
      this.who = null;
      this.show({ kind: "form", why: "you left the game" });
    }
  }
}
