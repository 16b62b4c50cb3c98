"""Drives halfcast's page in headless Chromium (Debian's, through Playwright) for
tests/serve/serve_browser.rs: loads the page and joins, checks the view is drawn, holds `d` and
releases it (how long the view goes on changing after the release, and frames a second while
turning), taps `d` once, holds `d` while the window loses focus (the page lets go), takes the painter's pixels and the frame bytes they were drawn from,
resizes the window and does the same again; taps `d` for 0 ms and 20 ms and reads how far each
tap turned from the status line's angle; presses Escape (with and without the game's help shown)
and checks the game goes on. Prints one JSON object of figures on its last line.

usage: page_check.py URL OUTDIR
"""

import asyncio
import json
import sys

from playwright.async_api import async_playwright

from pagelib import ARGS, CHROMIUM, VIEW_HASH, Wire, angle, settle, turned

# After each painted frame: when, and a hash of the pixel canvas between the header's and the
# status line's rows (the view, the minimap and the ray pane).
HOOK = """() => {
  window.__log = [];
  window.__up = null; window.__down = null;
  addEventListener('keydown', () => { if (window.__down === null) window.__down = performance.now(); });
  addEventListener('keyup', () => { window.__up = performance.now(); });
  const g = halfcast.game;
  const paint = g.frame.bind(g);
  g.frame = (data) => {
    paint(data);
    const s = halfcast.screen, d = s.img.data, w = s.cols * 4;
    let h = 0;
    for (let i = 2 * w; i < d.length - 2 * w; i += 4) h = (Math.imul(h, 31) + d[i] + (d[i + 1] << 8) + (d[i + 2] << 16)) | 0;
    window.__log.push([performance.now(), h]);
  };
}"""

SHOWN = "!document.getElementById('join').classList.contains('hidden')"

RESET = "() => { window.__log = []; window.__up = null; window.__down = null; }"

SNAPSHOT = """() => {
  const s = halfcast.screen;
  return { frames: halfcast.game.frames, cols: s.cols, rows: s.rows,
           pixels: Array.from(s.img.data), over: Array.from(s.over) };
}"""

# The glyph canvas sampled at the middle of each of a cell's 2×4 octant pixels, for every cell.
SAMPLES = """() => {
  const s = halfcast.screen, W = s.cells.width;
  const d = s.cx.getImageData(0, 0, W, s.cells.height).data;
  const out = [];
  for (let r = 0; r < s.rows; r++) for (let c = 0; c < s.cols; c++) {
    const [x0, y0, x1, y1] = s.edges(r, c);
    for (let k = 0; k < 8; k++) {
      const px = Math.floor(x0 + (x1 - x0) * ((k & 1) + 0.5) / 2);
      const py = Math.floor(y0 + (y1 - y0) * ((k >> 1) + 0.5) / 4);
      const i = (py * W + px) * 4;
      out.push((d[i] << 16) | (d[i + 1] << 8) | d[i + 2]);
    }
  }
  return out;
}"""

OCTANTS = "() => halfcast.screen.ch.some((c) => c >= 0x1cd00 && c <= 0x1cdff)"

DISTINCT = """() => {
  const s = halfcast.screen, d = s.img.data, seen = new Set();
  for (let i = 0; i < d.length; i += 4) seen.add((d[i] << 16) | (d[i + 1] << 8) | d[i + 2]);
  return seen.size;
}"""


def changes(log, since):
    """Times of painted frames after `since` whose view differed from the frame before."""
    out = []
    for (t0, h0), (t1, h1) in zip(log, log[1:]):
        if t1 > since and h1 != h0:
            out.append(t1)
    return out


async def snapshot(page, frames, out, name, samples=False):
    snap = await page.evaluate(SNAPSHOT)
    if samples:
        snap["samples"] = await page.evaluate(SAMPLES)
    for _ in range(100):
        if len(frames) >= snap["frames"]:
            break
        await asyncio.sleep(0.05)
    with open(f"{out}/{name}.frames", "wb") as f:
        for b in frames[: snap["frames"]]:
            f.write(len(b).to_bytes(4, "big"))
            f.write(b)
    with open(f"{out}/{name}.json", "w") as f:
        json.dump(snap, f)
    return snap["cols"], snap["rows"]


# One tap of `d` made in the page itself, so no round trip to Playwright falls between the press
# and its release: both in one task for 0 ms, else the release a timer of `ms` later. Gives the
# milliseconds the page saw between them.
TAP = """(ms) => new Promise((done) => {
  const key = (type) => dispatchEvent(new KeyboardEvent(type, { key: "d", code: "KeyD" }));
  const t0 = performance.now();
  key("keydown");
  const up = () => { key("keyup"); done(performance.now() - t0); };
  if (ms === 0) up(); else setTimeout(up, ms);
})"""


async def taps(page):
    """Taps of `d` held 0 ms and 20 ms, three each: the degrees each turned (the status line's
    angle before and after), whether the view changed, and the hold the page made."""
    out = {}
    await settle(page)
    for ms in (0, 20):
        steps, moved, held = [], [], []
        for _ in range(3):
            a, h = await angle(page), await page.evaluate(VIEW_HASH)
            held.append(round(await page.evaluate(TAP, ms), 1))
            await page.wait_for_timeout(300)
            await settle(page)
            b, h2 = await angle(page), await page.evaluate(VIEW_HASH)
            steps.append(turned(a, b) if a is not None and b is not None else None)
            moved.append(h2 != h)
        out[f"tap_{ms}ms_degrees"] = steps
        out[f"tap_{ms}ms_view_moved"] = moved
        out[f"tap_{ms}ms_held_ms"] = held
    return out


async def escape(page, wire):
    """Escape while playing, then with the game's help shown: nothing named Escape is sent, the
    help closes (the help key again), the connection stays and `d` still turns the view."""
    before = len(wire.sent)
    await page.keyboard.press("Escape")
    await page.keyboard.press("?")
    await page.wait_for_timeout(300)
    await page.keyboard.press("Escape")
    await page.wait_for_timeout(600)
    sent = [(m["key"], m["down"]) for m in wire.sent[before:] if "key" in m]
    h = await page.evaluate(VIEW_HASH)
    await page.keyboard.down("d")
    await page.wait_for_timeout(400)
    await page.keyboard.up("d")
    await page.wait_for_timeout(300)
    return {
        "escape_sent": sent,
        "escape_playing": await page.evaluate("halfcast.link.ws !== null && halfcast.link.ws.readyState === 1"),
        "escape_form_hidden": await page.evaluate("document.getElementById('join').classList.contains('hidden')"),
        "escape_then_turned": (await page.evaluate(VIEW_HASH)) != h,
    }


async def first_visit(browser, url):
    """A spectator's first visit: the form shows Watch (no name), the keys and a fullscreen
    button; Enter with the focus nowhere in particular starts watching; the title names the
    world and the player count."""
    page = await browser.new_page(viewport={"width": 800, "height": 480})
    await page.goto(url + "?spectate")
    await page.wait_for_function("() => document.title !== 'halfcast'", timeout=20000)
    shown = lambda sel: page.evaluate(f"!document.querySelector('{sel}').closest('.hidden')")
    out = {
        "spectate_button": await page.inner_text("#play"),
        "spectate_name_shown": await shown("#name"),
        "keys_help_shown": await shown("#keys-help"),
        "fullscreen_button": await shown("#join .fullscreen"),
        "title": await page.title(),
        "info": await page.evaluate("fetch('info.json').then((r) => r.json())"),
    }
    await page.evaluate("document.activeElement.blur()")
    await page.keyboard.press("Enter")
    await page.wait_for_function("() => halfcast.game.frames > 0", timeout=20000)
    out["enter_watches"] = True
    await page.close()
    return out


# Contract 1 and 3 on the page's side, without a server that compresses: binary messages whose
# first byte is 0x00 are raw DEFLATE, inflated by the page; raw frames and text messages that
# come after an inflating frame wait for it. The game's frame (paint and ack) records these
# made-up frames instead, so no ack for them reaches the server; the server's own frames pass.
ORDER = """async () => {
  const link = halfcast.link, game = halfcast.game, ws = link.ws, got = [];
  const enc = new TextEncoder(), dec = new TextDecoder();
  const deflated = async (text) => {
    const s = new Blob([enc.encode(text)]).stream().pipeThrough(new CompressionStream("deflate-raw"));
    const z = new Uint8Array(await new Response(s).arrayBuffer());
    const m = new Uint8Array(z.length + 1); m.set(z, 1); return m.buffer;
  };
  const one = await deflated("one"), three = await deflated("three".repeat(2000));
  const mine = new Set(["one", "two", "three".repeat(2000), "four"]), frame = game.frame;
  game.frame = (bytes) => {
    const t = dec.decode(bytes);
    if (mine.has(t)) got.push(t); else frame.call(game, bytes);
  };
  link.on("probe", (v) => got.push("probe " + v));
  link.message(ws, one);
  link.message(ws, enc.encode("two").buffer);
  link.message(ws, '{"probe":1,"unknown":2}');
  link.message(ws, three);
  link.message(ws, enc.encode("four").buffer);
  await new Promise((r) => setTimeout(r, 500));
  game.frame = frame;
  return got.map((g) => g.length > 20 ? g.slice(0, 5) + "…" + g.length : g);
}"""


async def main(url, out):
    figures = {}
    async with async_playwright() as p:
        browser = await p.chromium.launch(executable_path=CHROMIUM, args=ARGS)
        page = await browser.new_page(viewport={"width": 800, "height": 480})
        errors = []
        page.on("pageerror", lambda e: errors.append(str(e)))
        wire = Wire(page)
        frames = wire.frames
        await page.goto(url + "?name=chromey")
        await page.click("#play")
        await page.wait_for_function("() => halfcast.game.frames > 0", timeout=20000)
        await page.wait_for_timeout(1000)
        figures["distinct_colours"] = await page.evaluate(DISTINCT)
        figures["grid"] = await page.evaluate("[halfcast.screen.cols, halfcast.screen.rows]")
        await page.screenshot(path=f"{out}/page-80x24.png")
        await page.evaluate(HOOK)

        # Hold d (turning right) for two seconds, then let go.
        await page.keyboard.down("d")
        await page.wait_for_timeout(2000)
        await page.keyboard.up("d")
        await page.wait_for_timeout(1500)
        log = await page.evaluate("window.__log")
        down, up = await page.evaluate("[window.__down, window.__up]")
        turning = [t for t in changes(log, down + 300) if t <= up]
        figures["turning_fps"] = len(turning) / ((up - down - 300) / 1000)
        after = changes(log, up)
        figures["release_lag_ms"] = (after[-1] - up) if after else 0.0
        figures["frames_after_release"] = len([t for t, _ in log if t > up])

        # One tap.
        await page.evaluate(RESET)
        await page.keyboard.press("d", delay=80)
        await page.wait_for_timeout(1500)
        log = await page.evaluate("window.__log")
        up = await page.evaluate("window.__up")
        after = changes(log, up - 100)
        figures["tap_changes"] = len(after)
        figures["tap_lag_ms"] = max(0.0, after[-1] - up) if after else None

        # Held while the tab loses focus: the page lets go of it, so the view stops.
        await page.evaluate(RESET)
        await page.keyboard.down("d")
        await page.wait_for_timeout(600)
        blurred = await page.evaluate("() => { dispatchEvent(new Event('blur')); return performance.now(); }")
        await page.wait_for_timeout(1500)
        log = await page.evaluate("window.__log")
        turned = changes(log, 0)
        figures["blur_turned"] = len([t for t in turned if t < blurred])
        after = changes(log, blurred)
        figures["blur_lag_ms"] = (after[-1] - blurred) if after else 0.0
        await page.keyboard.up("d")
        await page.wait_for_timeout(300)

        figures["small_paint_ms"] = await page.evaluate("halfcast.game.paintMs / halfcast.game.frames")
        figures["small"] = await snapshot(page, frames, out, "small")

        # A larger window is a larger session.
        await page.set_viewport_size({"width": 1600, "height": 900})
        await page.wait_for_function("() => halfcast.screen.cols === 160 && halfcast.screen.rows === 45", timeout=20000)
        await page.wait_for_timeout(1500)
        figures["large"] = await snapshot(page, frames, out, "large")
        # Turning at the larger size: frames a second painted and the painter's time per frame.
        await page.evaluate(RESET)
        before = await page.evaluate("[halfcast.game.paintMs, halfcast.game.frames]")
        await page.keyboard.down("d")
        await page.wait_for_timeout(2000)
        await page.keyboard.up("d")
        after = await page.evaluate("[halfcast.game.paintMs, halfcast.game.frames]")
        log = await page.evaluate("window.__log")
        down, up = await page.evaluate("[window.__down, window.__up]")
        turning = [t for t in changes(log, down + 300) if t <= up]
        figures["large_turning_fps"] = len(turning) / ((up - down - 300) / 1000)
        figures["large_paint_ms"] = (after[0] - before[0]) / max(1, after[1] - before[1])
        await page.wait_for_timeout(1000)
        figures["large"] = await snapshot(page, frames, out, "large")
        await page.screenshot(path=f"{out}/page-160x45.png")

        figures.update(await taps(page))
        figures.update(await escape(page, wire))
        figures["large"] = await snapshot(page, frames, out, "large")

        # The glyph key (u) three times: quadrants, sextants, then octants, drawn as rectangles.
        for _ in range(3):
            await page.keyboard.press("u", delay=60)
            await page.wait_for_timeout(300)
        await page.wait_for_function(OCTANTS, timeout=20000)
        await page.wait_for_timeout(1500)
        figures["octant"] = await snapshot(page, frames, out, "octant", samples=True)
        figures["inflate_order"] = await page.evaluate(ORDER)
        figures.update(await first_visit(browser, url))
        # The visible Quit leaves: the form shows again, saying so.
        await page.click("#quit")
        await page.wait_for_function(f"() => {SHOWN}", timeout=20000)
        figures["quit_said"] = await page.inner_text("#said")
        figures["page_errors"] = errors
        figures["bytes"] = await page.evaluate("halfcast.game.bytes")
        figures["frames"] = await page.evaluate("halfcast.game.frames")
        await browser.close()
    print(json.dumps(figures))


asyncio.run(main(sys.argv[1], sys.argv[2]))
