"""Drives the ray debugger's page in headless Chromium (Debian's, through Playwright) for
tests/serve/serve_ray_debugger.rs: opens each ray's address in a fresh browser context (no
cookies, no storage: as a link sent to someone else), reads what the page shows (the
derivation's text, the figure's crossings, hit cell and perp), steps to the start, forward and
back with keys and buttons, hovers a crossing, previews another column, and writes screenshots
when asked. Also opens a ray `trace` refuses. Prints one JSON object on its last line: {"rays": [one per
ray], "refused": the page's message}.

usage: ray_check.py BASE_URL CASES_JSON OUTDIR
CASES_JSON: [{"name": ..., "address": "pos=..&angle=..", "preview": C, "shots": [[w, h], ...]}]
"""

import asyncio
import json
import sys

from playwright.async_api import async_playwright

ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
        "--disable-component-update", "--disable-sync", "--no-first-run"]

# What the figure shows: every crossing (its step, side, label, point in map units and where
# its circle is drawn), the hit cell, the perp label, the cell size and the grid's corner.
FIGURE = """() => {
  const svg = document.querySelector('.ray-svg');
  const crossings = [...svg.querySelectorAll('g.crossing')].map((g) => {
    const c = g.querySelector('circle');
    return { step: Number(g.dataset.step), side: g.classList.contains('x') ? 'x' : 'y',
      label: g.querySelector('text').textContent, x: Number(g.dataset.x), y: Number(g.dataset.y),
      cx: Number(c.getAttribute('cx')), cy: Number(c.getAttribute('cy')),
      current: g.classList.contains('current'), later: g.classList.contains('later') };
  });
  const hit = svg.querySelector('rect.hit-cell');
  const perp = svg.querySelector('text.perp');
  return { crossings, hit_rect: hit && [Number(hit.getAttribute('x')), Number(hit.getAttribute('y')),
    Number(hit.getAttribute('width'))], perp: perp && perp.textContent };
}"""

STATE = """() => ({
  part: document.querySelector('.ray-part').textContent,
  now: document.querySelector('.ray-now').textContent,
  current: [...document.querySelectorAll('.ray-text .line.current')].map((l) => l.textContent),
  title: document.querySelector('.ray-title').textContent,
  error: document.querySelector('.ray-error') ? document.querySelector('.ray-error').textContent : '',
})"""


async def settle(page):
    await page.wait_for_selector(".ray-text .line", timeout=20000)


async def one(browser, base, case, out):
    ctx = await browser.new_context(viewport={"width": 1280, "height": 900})
    page = await ctx.new_page()
    errors = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    await page.goto(f"{base}/ray?{case['address']}")
    await settle(page)
    got = {"name": case["name"], "url": page.url}
    got["text"] = await page.inner_text(".ray-text")
    got["figure"] = await page.evaluate(FIGURE)
    got["at_hit"] = await page.evaluate(STATE)
    got["export"] = [await page.get_attribute(".ray-export-svg", "href"),
                     await page.get_attribute(".ray-export-png", "href")]
    # Stepping: Home is the setup; → step 1; → step 2; ← step 1; the buttons; End the hit.
    walk = []
    await page.keyboard.press("Home")
    walk.append(await page.evaluate(STATE))
    await page.keyboard.press("ArrowRight")
    walk.append(await page.evaluate(STATE))
    got["figure_step1"] = await page.evaluate(FIGURE)
    await page.keyboard.press("ArrowRight")
    walk.append(await page.evaluate(STATE))
    await page.keyboard.press("ArrowLeft")
    walk.append(await page.evaluate(STATE))
    await page.click(".ray-next")
    walk.append(await page.evaluate(STATE))
    await page.click(".ray-prev")
    walk.append(await page.evaluate(STATE))
    await page.keyboard.press("End")
    walk.append(await page.evaluate(STATE))
    got["walk"] = walk
    # Hovering the last crossing (drawn over the others) names it.
    last = page.locator("g.crossing circle").last
    if await last.count() > 0:
        await last.hover()
        got["hover"] = await page.inner_text(".ray-hover")
    # Another column's ray, previewed, then back.
    if case.get("preview") is not None:
        await page.evaluate(f"() => window.halfcastRay.previewColumn({case['preview']})")
        await page.wait_for_function(
            f"() => document.querySelector('.ray-title').textContent.includes('column {case['preview']} ')",
            timeout=20000)
        got["preview_title"] = (await page.evaluate(STATE))["title"]
        await page.evaluate("() => window.halfcastRay.previewColumn(null)")
        got["after_preview_title"] = (await page.evaluate(STATE))["title"]
    for w, h in case.get("shots", []):
        await page.set_viewport_size({"width": w, "height": h})
        await page.keyboard.press("Home")
        for _ in range(case.get("shot_step", 3)):
            await page.keyboard.press("ArrowRight")
        await page.screenshot(path=f"{out}/{case['name']}-{w}x{h}.png")
    got["errors"] = errors
    await ctx.close()
    return got


async def main(base, cases_path, out):
    cases = json.load(open(cases_path))
    async with async_playwright() as p:
        browser = await p.chromium.launch(executable_path="/usr/bin/chromium", args=ARGS)
        results = [await one(browser, base, c, out) for c in cases]
        # A ray trace would refuse: the page says trace's message.
        page = await browser.new_page()
        await page.goto(f"{base}/ray?pos=0.5,0.5&angle=0&column=1&size=80x24")
        await page.wait_for_function("() => document.querySelector('.ray-error').textContent !== ''")
        refused = await page.inner_text(".ray-error")
        # The page's numbers as Rust prints them, ties and huge values included.
        numbers = await page.evaluate("""async () => {
          const m = await import('/js/ray_text.js');
          return [0.125, 0.375, 0.625, -0.125, 2.5, 1e30, 5e29, -0.001, 2.876, 1234567].map((v) => m.num(v));
        }""")
        await page.close()
        await browser.close()
    print(json.dumps({"rays": results, "refused": refused, "numbers": numbers}))


if __name__ == "__main__":
    asyncio.run(main(sys.argv[1].rstrip("/"), sys.argv[2], sys.argv[3]))
