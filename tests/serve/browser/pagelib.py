"""What the browser checks share: Debian's Chromium under Playwright, the frames a page received
(inflated when the server sent them as raw DEFLATE, contract 1), the messages it sent, and
readings of its grid (the view's hash, the status line's angle); and for the link measurements
(weblag.py, weblevels.py), a shaped network namespace and a server on the still map."""

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


def in_shaped_namespace(rate, queue_ms):
    """Re-runs this script under `unshare -rn` (a network namespace of its own) unless it runs
    there already (`--inside`), then shapes that namespace's loopback as
    ../shared/tools/linklag.py does: MTU 1500 and, unless `rate` is "none", a token bucket of
    `rate` with a 16 kB burst and a `queue_ms` queue."""
    import os, subprocess, sys
    if "--inside" not in sys.argv:
        os.execvp("unshare", ["unshare", "-rn", sys.executable, *sys.argv, "--inside"])
    subprocess.run(["ip", "link", "set", "lo", "up", "mtu", "1500"], check=True)
    if rate != "none":
        subprocess.run(["tc", "qdisc", "add", "dev", "lo", "root", "tbf", "rate", rate,
                        "burst", "16kb", "latency", f"{queue_ms}ms"], check=True)


def free_port():
    """A port free now on 127.0.0.1."""
    import socket
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()
    return port


class serving:
    """`BIN serve` on the still map with its web port on 127.0.0.1, for a `with` block that gets
    the web port; `extra` flags are added. Stopped at the block's end."""

    def __init__(self, bin, extra=()):
        self.bin, self.extra = bin, list(extra)

    def __enter__(self):
        import subprocess, tempfile
        self.dir = tempfile.TemporaryDirectory()
        d = self.dir.name
        web = free_port()
        self.srv = subprocess.Popen(
            [self.bin, "serve", still_map(d), "--listen", f"127.0.0.1:{free_port()}",
             "--web", f"127.0.0.1:{web}", *self.extra, "--host-key", f"{d}/hk", "--db", "none",
             "--quiet"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        wait_for_port(web)
        return web

    def __exit__(self, *exc):
        self.srv.terminate()
        self.srv.wait()
        self.dir.cleanup()
