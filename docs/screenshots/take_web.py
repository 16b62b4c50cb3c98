"""The browser page's screenshots in docs/: headless Chromium (Debian's, through Playwright) on
a running `halfcast serve --web`, at an 800×480 window (80×24 cells) and a 1600×900 one (160×45).

Needs `pip install playwright pillow`.

usage: python3 docs/screenshots/take_web.py http://127.0.0.1:8080/ OUTDIR
"""

import asyncio
import io
import sys

from PIL import Image

from playwright.async_api import async_playwright

ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
        "--disable-component-update", "--disable-sync", "--no-first-run"]


async def main(url, out):
    async with async_playwright() as p:
        browser = await p.chromium.launch(executable_path="/usr/bin/chromium", args=ARGS)
        for (w, h, name) in [(800, 480, "web-80x24.webp"), (1600, 900, "web-160x45.webp")]:
            page = await browser.new_page(viewport={"width": w, "height": h})
            await page.goto(url + "?name=ada")
            await page.click("#play")
            await page.wait_for_function("() => halfcast.game.frames > 0")
            # A few steps in and a turn, so the view shows the room.
            await page.keyboard.down("w")
            await page.wait_for_timeout(700)
            await page.keyboard.up("w")
            await page.keyboard.down("d")
            await page.wait_for_timeout(350)
            await page.keyboard.up("d")
            await page.wait_for_timeout(1200)
            # Lossless WebP: the same pixels as the PNG Chromium gives, at about a third of the size.
            png = await page.screenshot()
            Image.open(io.BytesIO(png)).save(f"{out}/{name}", lossless=True, method=6)
            await page.close()
        await browser.close()


asyncio.run(main(sys.argv[1], sys.argv[2]))
