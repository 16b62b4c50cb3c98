// Touch controls, sending through input.js's press/release API like the keyboard:
// - the stick (a thumb anywhere on the pad): up walks (w), down walks back (s), sideways
//   strafes (z / x), held as long as the thumb stays there;
// - a horizontal drag on the view turns: each TURN_PX of drag is one tap of a / d (one tap's
//   step of turn, the same as a key tap);
// - buttons: turn (held), use, jump, crouch (held), the map and ray panes, help;
// - a touch on the view that does not move is a tap on the view (`onViewTap`, for a panel such
//   as the ray debugger to use).

// Pixels of thumb travel before the stick counts a direction.
const DEAD = 14;
// Pixels of horizontal drag per tap of turn.
const TURN_PX = 18;
// Pixels a touch on the view may move and still be a tap.
const STILL = 8;

export class Touch {
  // `input` is input.js's Input; `pad`, `knob`, `buttons` and `view` are the page's elements.
  constructor(input, { pad, knob, buttons, view }) {
    this.input = input;
    this.knob = knob;
    this.onViewTap = null;
    this.stick(pad);
    this.drag(view);
    for (const b of buttons.querySelectorAll("button[data-key]")) this.button(b);
  }

  stick(pad) {
    let id = null, x0 = 0, y0 = 0;
    const set = (axis, key) => {
      const by = "stick " + axis, now = this.input.held.get(by);
      if (now && now.key === key) return;
      this.input.release(by);
      if (key) this.input.press(by, key);
    };
    const move = (e) => {
      const dx = e.clientX - x0, dy = e.clientY - y0;
      set("y", dy < -DEAD ? "w" : dy > DEAD ? "s" : null);
      set("x", dx < -DEAD ? "z" : dx > DEAD ? "x" : null);
      const r = Math.min(1, 48 / Math.max(1, Math.hypot(dx, dy)));
      this.knob.style.transform = `translate(${dx * r}px, ${dy * r}px)`;
    };
    const end = (e) => {
      if (e.pointerId !== id) return;
      id = null;
      set("y", null);
      set("x", null);
      this.knob.style.transform = "";
    };
    pad.addEventListener("pointerdown", (e) => {
      if (id !== null) return;
      e.preventDefault();
      id = e.pointerId;
      x0 = e.clientX; y0 = e.clientY;
      pad.setPointerCapture?.(id);
    });
    pad.addEventListener("pointermove", (e) => { if (e.pointerId === id) move(e); });
    pad.addEventListener("pointerup", end);
    pad.addEventListener("pointercancel", end);
  }

  drag(view) {
    const drags = new Map();
    view.addEventListener("pointerdown", (e) => {
      if (e.pointerType !== "touch") return;
      e.preventDefault();
      drags.set(e.pointerId, { x: e.clientX, y: e.clientY, x0: e.clientX, y0: e.clientY, moved: false });
      view.setPointerCapture?.(e.pointerId);
    });
    view.addEventListener("pointermove", (e) => {
      const d = drags.get(e.pointerId);
      if (!d) return;
      if (Math.hypot(e.clientX - d.x0, e.clientY - d.y0) > STILL) d.moved = true;
      while (e.clientX - d.x >= TURN_PX) { this.input.tap("d"); d.x += TURN_PX; }
      while (d.x - e.clientX >= TURN_PX) { this.input.tap("a"); d.x -= TURN_PX; }
    });
    const end = (e) => {
      const d = drags.get(e.pointerId);
      if (!d) return;
      drags.delete(e.pointerId);
      if (!d.moved && e.type === "pointerup" && this.onViewTap) this.onViewTap(e.clientX, e.clientY);
    };
    view.addEventListener("pointerup", end);
    view.addEventListener("pointercancel", end);
  }

  // A button sends its key: held while touched (`data-hold`), else one tap.
  button(b) {
    const key = b.dataset.key, by = "button " + key, hold = "hold" in b.dataset;
    b.addEventListener("pointerdown", (e) => {
      e.preventDefault();
      b.classList.add("down");
      if (hold) this.input.press(by, key);
      else this.input.tap(key);
    });
    const up = () => {
      b.classList.remove("down");
      if (hold) this.input.release(by);
    };
    b.addEventListener("pointerup", up);
    b.addEventListener("pointercancel", up);
    b.addEventListener("pointerleave", up);
    // No text selection, callout or double-tap zoom from a long press.
    b.addEventListener("contextmenu", (e) => e.preventDefault());
  }
}
