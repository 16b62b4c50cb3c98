#!/usr/bin/env python3
"""The ray debugger as a player meets it on the game page: plays, clicks a column of the 3D
view, reads the address the page then shows and the derivation's text, steps back and forward,
then opens that address in a fresh browser and reads the same text again, without playing.

  python3 click_check.py BASE_URL COLUMN OUT_DIR
Prints one JSON line: the address, the texts, the parts stepped through, page errors."""

import asyncio
import json
import sys

from playwright.async_api import async_playwright

from pagelib import ARGS, CHROMIUM

PART = "() => document.querySelector('.ray-part').textContent"


async def main(base, column, out):
    async with async_playwright() as p:
        browser = await p.chromium.launch(executable_path=CHROMIUM, args=ARGS)
        ctx = await browser.new_context(viewport={"width": 1400, "height": 800})
        page = await ctx.new_page()
        errors = []
        page.on("pageerror", lambda e: errors.append(str(e)))
        await page.goto(base + "/")
        await page.fill("#name", "clicker")
        await page.press("#name", "Enter")
        await page.wait_for_function("() => halfcast.game.frames > 3 && halfcast.rays.view", timeout=20000)
        # The middle row of the view, at the asked column's centre.
        at = await page.evaluate(f"""() => {{
          const v = halfcast.rays.view, r = document.getElementById('pixels').getBoundingClientRect();
          const w = r.width / halfcast.screen.cols, h = r.height / halfcast.screen.rows;
          return [r.left + (v.x + {column} + 0.5) * w, r.top + (v.y + v.rows / 2) * h];
        }}""")
        await page.mouse.click(at[0], at[1])
        await page.wait_for_selector("#raydock .ray-text .line", timeout=20000)
        await page.wait_for_function("() => location.search.includes('pos=')", timeout=20000)
        address = await page.evaluate("() => location.search.slice(1)")
        text = await page.inner_text("#raydock .ray-text")
        parts = [await page.evaluate(PART)]
        for key in ["Home", "ArrowRight", "ArrowRight", "ArrowLeft", "End"]:
            await page.keyboard.press(key)
            parts.append(await page.evaluate(PART))
        await page.screenshot(path=f"{out}/clicked.png")
        # The same address in a fresh browser: the same ray, without playing.
        fresh = await browser.new_context(viewport={"width": 1400, "height": 800})
        again = await fresh.new_page()
        again.on("pageerror", lambda e: errors.append(str(e)))
        await again.goto(f"{base}/?{address}")
        await again.wait_for_selector("#raydock .ray-text .line", timeout=20000)
        fresh_text = await again.inner_text("#raydock .ray-text")
        playing = await again.evaluate("() => halfcast.game.frames")
        await browser.close()
        print(json.dumps({"address": address, "text": text, "fresh_text": fresh_text,
                          "parts": parts, "fresh_frames": playing, "errors": errors}))


asyncio.run(main(sys.argv[1], int(sys.argv[2]), sys.argv[3]))
