// Input: everything a player does goes out as `{"key":NAME,"down":bool}` (keys named as
// `KeyboardEvent.key`), built in one place (`message`). Keyboard keys and the touch controls
// (touch.js) share one press/release API, so a key held by a finger and one held on the
// keyboard are the same to the server. Escape is never sent: it closes the game's help, or the
// browser leaves fullscreen with it.

// The keys the page sends by name besides single characters (Escape is not one of them).
const NAMED = new Set(["ArrowUp", "ArrowDown", "ArrowLeft", "ArrowRight", "Home", "End", "PageUp",
  "PageDown", "Insert", "Delete", "Enter", "Tab", "Backspace",
  "F1", "F2", "F3", "F4", "F5", "F6", "F7", "F8", "F9", "F10", "F11", "F12"]);
// The game's help keys: each press shows or hides its help.
const HELP = new Set(["?", "h", "F1"]);

// The one message for a key going down or up.
export function message(key, down, ctrl = false) {
  return ctrl ? { key, down, ctrl: true } : { key, down };
}

export class Input {
  // `send(msg)` sends a message; `live()` says whether a game is on to send it to.
  constructor(send, live) {
    this.send = send;
    this.live = live;
    // Held keys by what holds them (a keyboard code, or a touch control's name).
    this.held = new Map();
    this.helpShown = false;
  }

  // `key` goes down, held by `by`; nothing when `by` already holds a key.
  press(by, key, ctrl = false) {
    if (!this.live() || this.held.has(by)) return;
    this.held.set(by, { key, ctrl });
    if (HELP.has(key)) this.helpShown = !this.helpShown;
    this.send(message(key, true, ctrl));
  }

  // What `by` holds goes up.
  release(by) {
    const k = this.held.get(by);
    if (!k) return;
    this.held.delete(by);
    this.send(message(k.key, false, k.ctrl));
  }

  // A press and its release at once: the server counts it as one tap's step.
  tap(key) {
    const by = "tap " + key;
    this.release(by);
    this.press(by, key);
    this.release(by);
  }

  // Every held key let go: the page lost focus or was hidden and will see no key-up, or the
  // connection ended.
  releaseAll() {
    for (const by of [...this.held.keys()]) this.release(by);
  }

  // The game ended or was lost: nothing is held, no help shows.
  forget() {
    this.held.clear();
    this.helpShown = false;
  }

  keydown(e) {
    if (!this.live()) return;
    if (e.key === "Escape") {
      // Never sent: it closes the game's help (the help key again); fullscreen is the browser's.
      e.preventDefault();
      if (this.helpShown) this.tap("?");
      else if (document.fullscreenElement) document.exitFullscreen();
      return;
    }
    e.preventDefault();
    if (e.repeat || this.held.has(e.code)) return;
    const named = NAMED.has(e.key);
    if (!named && [...e.key].length !== 1) return;
    this.press(e.code, e.key, e.ctrlKey && !named && /^[a-z]$/i.test(e.key));
  }

  keyup(e) {
    if (!this.held.has(e.code)) return;
    e.preventDefault();
    this.release(e.code);
  }

  // Listens on the window.
  attach() {
    addEventListener("keydown", (e) => this.keydown(e));
    addEventListener("keyup", (e) => this.keyup(e));
    addEventListener("blur", () => this.releaseAll());
    document.addEventListener("visibilitychange", () => { if (document.hidden) this.releaseAll(); });
  }
}
