#!/usr/bin/env python3
"""What a page on a fast link gets while turning: joins at 800×480 (an 80×24 grid), stays still
for 3 s, holds `d` for 4 s, and reports the frames that came during the turn (how many, how
many compressed, their mean bytes as sent) and the colour level the status line names at the
end. On a link that carries raw frames none should be compressed after the first seconds, and
the level should stay where the page started. Also reads the Quit bar's opacity: with the mouse
still since joining (it shows only while the mouse moves), and just after a move.

  python3 levels_check.py BASE_URL OUT_DIR
Prints one JSON line."""

import asyncio
import json
import sys
import time

from playwright.async_api import async_playwright

from pagelib import ARGS, CHROMIUM, STATUS


async def main(base, out):
    turn = []
    moving = [False]

    def on_ws(ws):
        def got(payload):
            if moving[0] and isinstance(payload, bytes) and len(payload) > 1000:
                turn.append((payload[:1] == b"\x00", len(payload)))
        ws.on("framereceived", got)

    async with async_playwright() as p:
        browser = await p.chromium.launch(executable_path=CHROMIUM, args=ARGS)
        page = await (await browser.new_context(viewport={"width": 800, "height": 480})).new_page()
        errors = []
        page.on("pageerror", lambda e: errors.append(str(e)))
        page.on("websocket", on_ws)
        await page.goto(base)
        # The form's handler is the page's module's: a name sent before it loaded would reload
        # the page instead.
        await page.wait_for_function("() => window.halfcast !== undefined")
        await page.fill("#name", "levels")
        await page.press("#name", "Enter")
        # A still world may send no frame after the first few: one is enough.
        await page.wait_for_function("() => halfcast.game.frames > 0", timeout=20000)
        await page.wait_for_timeout(3000)
        moving[0] = True
        started = time.monotonic()
        await page.keyboard.down("d")
        await page.wait_for_timeout(4000)
        await page.keyboard.up("d")
        held = time.monotonic() - started
        moving[0] = False
        bar = "() => Number(getComputedStyle(document.getElementById('bar')).opacity)"
        bar_still = await page.evaluate(bar)
        await page.mouse.move(300, 200)
        await page.mouse.move(320, 210)
        await page.wait_for_timeout(500)
        bar_moved = await page.evaluate(bar)
        status = await page.evaluate(STATUS)
        grid = await page.evaluate("() => [halfcast.screen.cols, halfcast.screen.rows]")
        await page.screenshot(path=f"{out}/levels.png")
        await browser.close()
    print(json.dumps({
        "grid": grid,
        "turn_frames": len(turn),
        "turn_fps": round(len(turn) / held, 1),
        "compressed": sum(1 for c, _ in turn if c),
        "mean_bytes": sum(n for _, n in turn) // max(1, len(turn)),
        "status": status.strip(),
        "bar_opacity_still": bar_still,
        "bar_opacity_moved": bar_moved,
        "page_errors": errors,
    }))


asyncio.run(main(sys.argv[1], sys.argv[2]))
