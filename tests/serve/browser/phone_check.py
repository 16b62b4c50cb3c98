"""A phone plays halfcast's page: headless Chromium (Debian's, through Playwright) as a 390×844
touch phone (is_mobile, has_touch). Checks the page fits the screen before and after Play (no
horizontal overflow, the whole grid and the controls on screen), walks with the stick and turns
by dragging across the view (real touch events through the DevTools protocol), sends only key
messages for it, then turns the phone sideways and checks the fit again. Saves screenshots.
Prints one JSON object of figures on its last line.

usage: phone_check.py URL OUTDIR
"""

import asyncio
import json
import sys

from playwright.async_api import async_playwright

from pagelib import ARGS, CHROMIUM, VIEW_HASH, Wire, settle

FIT = """() => {
  const de = document.documentElement, r = (id) => document.getElementById(id).getBoundingClientRect();
  const grid = r('screen'), s = halfcast.screen;
  const gw = s.cols * s.cellW, gh = s.rows * s.cellH;
  const box = (b) => [Math.round(b.left), Math.round(b.top), Math.round(b.right), Math.round(b.bottom)];
  return { inner: [innerWidth, innerHeight], scroll: [de.scrollWidth, de.scrollHeight],
           grid: [s.cols, s.rows], cell: [s.cellW, s.cellH],
           grid_box: [Math.round(grid.left), Math.round(grid.top), Math.round(grid.left + gw), Math.round(grid.top + gh)],
           form_box: box(r('join')), form_shown: !document.getElementById('join').classList.contains('hidden'),
           pad_box: box(r('pad')), buttons_box: box(r('buttons')) };
}"""


async def touch(cdp, kind, points):
    await cdp.send("Input.dispatchTouchEvent", {
        "type": kind, "touchPoints": [{"x": x, "y": y, "id": i} for i, (x, y) in enumerate(points)]})


async def drag(page, cdp, start, end, steps=12, hold_ms=0):
    """One finger from start to end in steps, then held hold_ms, then lifted."""
    await touch(cdp, "touchStart", [start])
    for k in range(1, steps + 1):
        x = start[0] + (end[0] - start[0]) * k / steps
        y = start[1] + (end[1] - start[1]) * k / steps
        await touch(cdp, "touchMove", [(x, y)])
        await page.wait_for_timeout(16)
    if hold_ms:
        await page.wait_for_timeout(hold_ms)
    await touch(cdp, "touchEnd", [])


def centre(box):
    return ((box[0] + box[2]) / 2, (box[1] + box[3]) / 2)


async def main(url, out):
    figures = {}
    async with async_playwright() as p:
        browser = await p.chromium.launch(executable_path=CHROMIUM, args=ARGS)
        context = await browser.new_context(viewport={"width": 390, "height": 844}, is_mobile=True,
                                            has_touch=True, device_scale_factor=3)
        page = await context.new_page()
        errors = []
        page.on("pageerror", lambda e: errors.append(str(e)))
        wire = Wire(page)
        await page.goto(url + "?name=phoney")
        await page.wait_for_function("() => window.halfcast !== undefined")
        await page.wait_for_timeout(300)
        figures["landing"] = await page.evaluate(FIT)
        figures["touch_help_shown"] = await page.evaluate(
            "!document.getElementById('touch-help').classList.contains('hidden')")
        await page.screenshot(path=f"{out}/phone-landing.png")
        await page.tap("#play")
        await page.wait_for_function("() => halfcast.game.frames > 0", timeout=20000)
        await page.wait_for_timeout(1000)
        figures["portrait"] = await page.evaluate(FIT)
        await page.screenshot(path=f"{out}/phone-portrait.png")
        cdp = await context.new_cdp_session(page)

        # Walk: the left thumb on the pad, pushed up and held.
        await settle(page)
        pad = centre(figures["portrait"]["pad_box"])
        before, h = len(wire.sent), await page.evaluate(VIEW_HASH)
        await drag(page, cdp, pad, (pad[0], pad[1] - 60), steps=6, hold_ms=700)
        await page.wait_for_timeout(300)
        figures["walk_keys"] = [(m["key"], m["down"]) for m in wire.sent[before:] if "key" in m]
        figures["walk_moved"] = (await page.evaluate(VIEW_HASH)) != h

        # Turn: a finger dragged right across the view.
        await settle(page)
        grid = figures["portrait"]["grid_box"]
        y = (grid[1] + grid[3]) / 2
        before, h = len(wire.sent), await page.evaluate(VIEW_HASH)
        await drag(page, cdp, (grid[0] + 60, y), (grid[0] + 60 + 90, y))
        await page.wait_for_timeout(600)
        figures["turn_keys"] = [(m["key"], m["down"]) for m in wire.sent[before:] if "key" in m]
        figures["turn_moved"] = (await page.evaluate(VIEW_HASH)) != h
        figures["other_messages"] = [m for m in wire.sent if not ({"key", "down"} >= m.keys() or "ack" in m or "size" in m)]

        # Sideways.
        await page.set_viewport_size({"width": 844, "height": 390})
        await page.wait_for_timeout(1500)
        figures["landscape"] = await page.evaluate(FIT)
        figures["sizes_sent"] = [m["size"] for m in wire.sent if "size" in m]
        await page.screenshot(path=f"{out}/phone-landscape.png")
        figures["page_errors"] = errors
        await browser.close()
    print(json.dumps(figures))


asyncio.run(main(sys.argv[1], sys.argv[2]))
