"""The browser page's screenshots in docs/: headless Chromium (Debian's, through Playwright) on
a `halfcast serve --web` this script starts (the default map), at an 800×480 window (80×24
cells) and a 1600×900 one (160×45); a 390×844 touch phone upright and sideways; the landing form;
and the notice an open page shows while its server restarts (SIGTERM, as systemd's restart).
`--lost` stops the server with SIGKILL instead (a lost connection: the back-off notice).

Needs `pip install playwright pillow`.

usage: python3 docs/screenshots/take_web.py BIN OUTDIR [--lost]
"""

import asyncio
import io
import os
import signal
import socket
import subprocess
import sys
import tempfile
import time

from PIL import Image

from playwright.async_api import async_playwright

ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
        "--disable-component-update", "--disable-sync", "--no-first-run"]
REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


def free_port():
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()
    return port


def serve(binary, home):
    """`halfcast serve` on the default map; (process, page URL)."""
    ssh, web = free_port(), free_port()
    srv = subprocess.Popen([binary, "serve", os.path.join(REPO, "maps", "default.cub"), "--listen",
                            f"127.0.0.1:{ssh}", "--web", f"127.0.0.1:{web}", "--host-key",
                            f"{home}/hk", "--db", "none", "--quiet", "--drain-seconds", "1"],
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    for _ in range(100):
        try:
            socket.create_connection(("127.0.0.1", web), timeout=1).close()
            break
        except OSError:
            time.sleep(0.1)
    return srv, f"http://127.0.0.1:{web}/"


async def save(page, path):
    # Lossless WebP: the same pixels as the PNG Chromium gives, at about a third of the size.
    png = await page.screenshot()
    Image.open(io.BytesIO(png)).save(path, lossless=True, method=6)


async def walk_in(page):
    """A few steps in and a turn, so the view shows the room."""
    await page.keyboard.down("w")
    await page.wait_for_timeout(700)
    await page.keyboard.up("w")
    await page.keyboard.down("d")
    await page.wait_for_timeout(350)
    await page.keyboard.up("d")
    await page.wait_for_timeout(1200)


async def desktop(browser, url, out):
    for (w, h, name) in [(800, 480, "web-80x24.webp"), (1600, 900, "web-160x45.webp")]:
        page = await browser.new_page(viewport={"width": w, "height": h})
        await page.goto(url + "?name=ada")
        if name == "web-80x24.webp":
            await page.wait_for_timeout(500)
            await save(page, f"{out}/web-landing.webp")
        await page.click("#play")
        await page.wait_for_function("() => halfcast.game.frames > 0")
        await walk_in(page)
        await save(page, f"{out}/{name}")
        await page.close()


async def phone(browser, url, out):
    context = await browser.new_context(viewport={"width": 390, "height": 844}, is_mobile=True,
                                        has_touch=True, device_scale_factor=2)
    page = await context.new_page()
    await page.goto(url + "?name=bo")
    await page.tap("#play")
    await page.wait_for_function("() => halfcast.game.frames > 0")
    await walk_in(page)
    await save(page, f"{out}/web-phone-portrait.webp")
    await page.set_viewport_size({"width": 844, "height": 390})
    await page.wait_for_timeout(1500)
    await save(page, f"{out}/web-phone-landscape.webp")
    await context.close()


async def main(binary, out, lost):
    with tempfile.TemporaryDirectory() as home:
        srv, url = serve(binary, home)
        try:
            async with async_playwright() as p:
                browser = await p.chromium.launch(executable_path="/usr/bin/chromium", args=ARGS)
                await desktop(browser, url, out)
                await phone(browser, url, out)
                page = await browser.new_page(viewport={"width": 800, "height": 480})
                await page.goto(url + "?name=ada")
                await page.click("#play")
                await page.wait_for_function("() => halfcast.game.frames > 0")
                await walk_in(page)
                srv.send_signal(signal.SIGKILL if lost else signal.SIGTERM)
                await page.wait_for_function(
                    "() => !document.getElementById('notice').classList.contains('hidden')", timeout=30000)
                await page.wait_for_timeout(300)
                await save(page, f"{out}/web-reconnecting.webp")
                await browser.close()
        finally:
            srv.kill()
            srv.wait()


asyncio.run(main(sys.argv[1], sys.argv[2], "--lost" in sys.argv[3:]))
