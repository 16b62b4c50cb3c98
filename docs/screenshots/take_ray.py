"""The ray debugger's screenshots in docs/: headless Chromium (Debian's, through Playwright) on
a running `halfcast serve --web`, the ray of docs/learning-dda.md opened at its address and
stepped to step 3, at an 800×480 window (the size of an 80×24 page) and a 1600×900 one.

Needs `pip install playwright pillow`.

usage: python3 docs/screenshots/take_ray.py http://127.0.0.1:8080/ OUTDIR
"""

import asyncio
import io
import sys

from PIL import Image

from playwright.async_api import async_playwright

ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
        "--disable-component-update", "--disable-sync", "--no-first-run"]
RAY = "ray?pos=15.3,5.6&angle=62&column=39&size=50x23"


async def main(url, out):
    async with async_playwright() as p:
        browser = await p.chromium.launch(executable_path="/usr/bin/chromium", args=ARGS)
        for (w, h, name) in [(800, 480, "ray-80x24.webp"), (1600, 900, "ray-160x45.webp")]:
            page = await browser.new_page(viewport={"width": w, "height": h})
            await page.goto(url + RAY)
            await page.wait_for_selector(".ray-text .line")
            await page.keyboard.press("Home")
            for _ in range(3):
                await page.keyboard.press("ArrowRight")
            # Lossless WebP: the same pixels as the PNG Chromium gives.
            png = await page.screenshot()
            Image.open(io.BytesIO(png)).save(f"{out}/{name}", lossless=True, method=6)
            await page.close()
        await browser.close()


if __name__ == "__main__":
    asyncio.run(main(sys.argv[1], sys.argv[2]))
