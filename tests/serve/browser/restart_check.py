"""An open page comes back by itself after its server restarts: joins as `chromey`, then (while
tests/serve/serve_browser.rs drains, stops and starts the server again on the same port) waits
for the page to say it is reconnecting, then to play again on a new connection, with no click or
key. Prints "playing" once the first connection plays (the Rust side then drains the server),
then one JSON object of figures, and keeps the page open until its stdin closes.

usage: restart_check.py URL OUTDIR
"""

import asyncio
import json
import sys

from playwright.async_api import async_playwright

from pagelib import ARGS, CHROMIUM, Wire

NOTICE = """() => {
  const n = document.getElementById('notice');
  return n.classList.contains('hidden') ? null : document.getElementById('notice-text').textContent;
}"""

FORM = "!document.getElementById('join').classList.contains('hidden')"


async def main(url, out):
    figures = {"notices": []}
    async with async_playwright() as p:
        browser = await p.chromium.launch(executable_path=CHROMIUM, args=ARGS)
        page = await browser.new_page(viewport={"width": 800, "height": 480})
        errors = []
        page.on("pageerror", lambda e: errors.append(str(e)))
        wire = Wire(page)
        await page.goto(url + "?name=chromey")
        await page.click("#play")
        await page.wait_for_function("() => halfcast.game.frames > 0", timeout=20000)
        print("playing", flush=True)
        # The server drains and stops: the page says what it does while it waits (or, wrongly,
        # goes back to its form: then say so at once).
        await page.wait_for_function(f"() => ({NOTICE})() !== null || {FORM}", timeout=60000, polling=100)
        if await page.evaluate(FORM):
            figures["form_instead"] = await page.evaluate("document.getElementById('said').textContent")
            figures["page_errors"] = errors
            print(json.dumps(figures))
            await browser.close()
            return
        figures["notices"].append(await page.evaluate(NOTICE))
        await page.screenshot(path=f"{out}/reconnecting.png")
        # Back on a new connection, playing, with no click.
        await page.wait_for_function(
            "() => halfcast.game.connections >= 2 && halfcast.game.frames > 0", timeout=90000, polling=100)
        await page.wait_for_timeout(500)
        figures["sockets"] = wire.urls
        figures["form_shown"] = await page.evaluate(
            "!document.getElementById('join').classList.contains('hidden')")
        figures["notice_after"] = await page.evaluate(NOTICE)
        figures["frames_after"] = await page.evaluate("halfcast.game.frames")
        figures["page_errors"] = errors
        print(json.dumps(figures), flush=True)
        # Still playing while the caller looks from the server's side; it closes stdin when done.
        await asyncio.get_running_loop().run_in_executor(None, sys.stdin.readline)
        await browser.close()


asyncio.run(main(sys.argv[1], sys.argv[2]))
