// What shows around the game: the name form (keys and touch help, a fullscreen button, Play
// or Watch), the notice while the page reconnects, the Quit and fullscreen buttons while
// playing (over the header's right end, so shown only while the mouse moves or rests on them),
// and the document's title naming the world and who is there (from /info.json).

const $ = (id) => document.getElementById(id);
// How long the Quit and fullscreen buttons stay after the mouse last moved.
const BAR_SHOWN_MS = 2500;

// The world and its players, for the title: "default.cub · 2 playing · halfcast".
export async function titled() {
  try {
    const r = await fetch("info.json", { cache: "no-store" });
    const info = await r.json();
    let t = `${info.world} · ${info.players} playing`;
    if (info.watching > 0) t += `, ${info.watching} watching`;
    document.title = `${t} · halfcast`;
    $("world").textContent = `${info.world} (${info.mode}): ${info.players} playing now`;
  } catch {
    document.title = "halfcast";
  }
}

// Fullscreen on or off (a button's doing: browsers allow it only from a user's gesture).
export function toggleFullscreen() {
  if (document.fullscreenElement) document.exitFullscreen();
  else document.documentElement.requestFullscreen?.().catch(() => {});
}

export class Landing {
  // `play(name, spectate)` starts the game; `quit()` leaves it.
  constructor({ spectate, touch, play, quit }) {
    this.form = $("join");
    this.notice = $("notice");
    this.spectate = spectate;
    this.tick = 0;
    const params = new URLSearchParams(location.search);
    $("name").value = params.get("name") || localStorage.getItem("halfcast.name") || "";
    if (spectate) {
      $("play").textContent = "Watch";
      $("name-row").classList.add("hidden");
    }
    $(touch ? "touch-help" : "keys-help").classList.remove("hidden");
    this.form.addEventListener("submit", (e) => {
      e.preventDefault();
      const name = $("name").value.trim();
      if (name) localStorage.setItem("halfcast.name", name);
      document.activeElement?.blur();
      play(name, spectate);
    });
    // Enter plays wherever the focus is while the form shows.
    addEventListener("keydown", (e) => {
      if (e.key === "Enter" && this.shown() && !(e.target instanceof HTMLButtonElement)) {
        e.preventDefault();
        this.form.requestSubmit();
      }
    });
    for (const b of document.querySelectorAll(".fullscreen")) b.addEventListener("click", toggleFullscreen);
    for (const b of document.querySelectorAll(".quit")) b.addEventListener("click", quit);
    this.barTimer = 0;
    addEventListener("mousemove", () => this.pointing());
  }

  // The mouse moved: the buttons over the header show for a while.
  pointing() {
    document.body.classList.add("pointing");
    clearTimeout(this.barTimer);
    this.barTimer = setTimeout(() => document.body.classList.remove("pointing"), BAR_SHOWN_MS);
  }

  shown() {
    return !this.form.classList.contains("hidden");
  }

  // What the connection says: { kind, why, until, attempt } (see link.js).
  show(state, name) {
    clearInterval(this.tick);
    const playing = state.kind !== "form";
    this.form.classList.toggle("hidden", playing);
    document.body.classList.toggle("playing", playing);
    document.body.classList.toggle("waiting", state.kind === "waiting");
    this.notice.classList.toggle("hidden", state.kind !== "waiting" && !(state.kind === "connecting" && state.attempt > 0));
    if (state.kind === "form") {
      $("said").textContent = state.why || "";
      titled();
      $("name").focus();
    } else if (state.kind === "waiting") {
      const who = this.spectate ? "watching" : `as ${name || "a new player"}`;
      const say = () => {
        const s = Math.max(0, Math.ceil((state.until - performance.now()) / 1000));
        $("notice-text").textContent = `${state.why}: reconnecting ${who} in ${s} s` +
          (state.attempt > 1 ? ` (attempt ${state.attempt})` : "");
      };
      say();
      this.tick = setInterval(say, 250);
    } else if (state.kind === "connecting" && state.attempt > 0) {
      $("notice-text").textContent = `reconnecting ${this.spectate ? "" : `as ${name || "a new player"} `}now…`;
    } else if (state.kind === "playing") {
      titled();
      // Shown as the game starts, so a player learns where Quit is.
      this.pointing();
    }
  }
}
