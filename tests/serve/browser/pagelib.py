"""What the browser checks share: Debian's Chromium under Playwright, the frames a page received
(inflated when the server sent them as raw DEFLATE, contract 1), the messages it sent, and
readings of its grid (the view's hash, the status line's angle)."""

import json
import re
import zlib

ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
        "--disable-component-update", "--disable-sync", "--no-first-run"]
CHROMIUM = "/usr/bin/chromium"


def frame_bytes(payload):
    """A binary message's frame: the rest inflated when the first byte is 0x00, else itself."""
    if payload[:1] == b"\x00":
        return zlib.decompressobj(-15).decompress(payload[1:])
    return payload


class Wire:
    """Every frame a page received and every JSON message it sent, on all its sockets."""

    def __init__(self, page):
        self.frames = []
        self.sent = []
        self.urls = []
        page.on("websocket", self.on_ws)

    def on_ws(self, ws):
        self.urls.append(ws.url)
        ws.on("framereceived", lambda p: self.frames.append(frame_bytes(p)) if isinstance(p, bytes) else None)
        ws.on("framesent", lambda p: self.sent.append(json.loads(p)) if isinstance(p, str) else None)

    def keys(self):
        """The key messages sent, as (key, down)."""
        return [(m["key"], m["down"]) for m in self.sent if "key" in m]


# A hash of the pixel canvas between the header's and the status line's rows.
VIEW_HASH = """() => {
  const s = halfcast.screen, d = s.img.data, w = s.cols * 4;
  let h = 0;
  for (let i = 2 * w; i < d.length - 2 * w; i += 4) h = (Math.imul(h, 31) + d[i] + (d[i + 1] << 8) + (d[i + 2] << 16)) | 0;
  return h;
}"""

STATUS = "() => halfcast.screen.text(halfcast.screen.rows - 1)"


async def angle(page):
    """The heading the status line shows, in degrees, or None when the line has no room for it."""
    m = re.search(r"angle (-?\d+(?:\.\d)?)", await page.evaluate(STATUS))
    return float(m.group(1)) if m else None


def turned(a, b):
    """Degrees from heading a to heading b, in -180..180."""
    return round((b - a + 540) % 360 - 180, 1)


async def settle(page, quiet_ms=500, limit_ms=8000):
    """Waits until the view has not changed for quiet_ms."""
    last, same_since, waited = None, 0, 0
    while waited < limit_ms:
        h = await page.evaluate(VIEW_HASH)
        if h == last:
            same_since += 100
            if same_since >= quiet_ms:
                return
        else:
            last, same_since = h, 0
        await page.wait_for_timeout(100)
        waited += 100


def still_map(d):
    """Writes `d/maps/still.cub`, the default map with nothing that moves by itself (creatures,
    animated sprites) and nothing to pick up, beside a link to the textures; returns its path."""
    import os
    repo = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
    os.symlink(os.path.join(repo, "textures"), f"{d}/textures")
    os.mkdir(f"{d}/maps")
    with open(os.path.join(repo, "maps", "default.cub")) as f:
        lines = [l for l in f if not l.startswith(("ITEM ", "DOORLOCK ", "EXIT ", "CREATURE "))
                 and "frames=" not in l]
    with open(f"{d}/maps/still.cub", "w") as f:
        f.writelines(lines)
    return f"{d}/maps/still.cub"


def wait_for_port(port, tries=100):
    """Waits until something listens on 127.0.0.1:`port`."""
    import socket, time
    for _ in range(tries):
        try:
            socket.create_connection(("127.0.0.1", port), timeout=1).close()
            return
        except OSError:
            time.sleep(0.1)
