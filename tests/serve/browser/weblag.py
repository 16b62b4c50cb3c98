#!/usr/bin/env python3
"""How stale does a browser player's view get after a key's release, on a shaped link?

Runs `halfcast serve --web` and a WebSocket player that acknowledges each frame as the page does
({"ack":N} once the frame is read), inside a fresh network namespace whose loopback is shaped by a
token bucket (the recipe of ../shared/tools/linklag.py: lo at MTU 1500, `tc qdisc … tbf`), then:

- hold: `d` (turn right) pressed for HOLD s, then released; how long frames that change the view
  keep arriving after the release. The map is the default one with nothing that moves by itself,
  so every frame that draws on the view's rows after the release is a view still turning; a
  frame that writes only the header or the status line (its figures change twice a second, and
  at 160×48 such a frame is well over a few hundred bytes) is not a view frame.
- taps: `d` pressed and released 80 ms later, from idle; the same figure.

Whole repaints (a colour level step redraws the same view at the new level) are counted apart
(`level_repaints`), not as the view still turning.

Re-executes itself under `unshare -rn` when not already in a fresh namespace.

  python3 weblag.py BIN [--rate 1mbit|none] [--hold 3] [--cols 80 --rows 24] [--runs 3]
Prints one JSON line.
"""
from pagelib import in_shaped_namespace, serving
import argparse, asyncio, json, re, sys, time, zlib

CSI = re.compile(rb"\x1b\[([0-9;?<>=]*)([@-~])")


def frame_bytes(msg):
    """A binary message's frame: raw DEFLATE after a 0x00 byte, else the bytes themselves."""
    return zlib.decompressobj(-15).decompress(msg[1:]) if msg[:1] == b"\x00" else msg


def draws_view(frame, rows):
    """Whether the frame writes anything on the rows between the header (row 1) and the status
    line (the last row), following the encoder's cursor moves (CUP, CUU/CUD, CR LF)."""
    row, at = 1, 0

    def wrote(text):
        return any(b >= 0x20 and b != 0x7f for b in text.replace(b"\n", b"").replace(b"\r", b""))

    def text_rows(text, row):
        """The row after `text` (None when it writes on the view's rows)."""
        for k, part in enumerate(text.split(b"\n")):
            if k > 0:
                row = min(row + 1, rows)
            if 1 < row < rows and wrote(part):
                return None
        return row

    for m in CSI.finditer(frame):
        row = text_rows(frame[at:m.start()], row)
        if row is None:
            return True
        at = m.end()
        p, final = m.group(1), m.group(2)
        n = [int(x) if x.isdigit() else 0 for x in p.split(b";")] if p and p[:1].isdigit() else [0]
        if final in (b"H", b"f"):
            row = max(n[0], 1)
        elif final == b"A":
            row = max(row - max(n[0], 1), 1)
        elif final == b"B":
            row = min(row + max(n[0], 1), rows)
    return text_rows(frame[at:], row) is None


class Player:
    def __init__(self, ws, rows):
        self.ws = ws
        self.rows = rows
        self.log = []  # (monotonic arrival, bytes on the wire)
        # Whether each frame draws on the view's rows (not only the header or status line).
        self.view = []
        # Whether each frame is a whole repaint (a colour level step's): the same view redrawn,
        # counted apart from the view still turning.
        self.repaint = []
        self.raw = []
        self.keep = False
        self.n = 0

    async def read(self):
        async for msg in self.ws:
            if isinstance(msg, bytes):
                self.n += 1
                self.log.append((time.monotonic(), len(msg)))
                frame = frame_bytes(msg)
                self.view.append(draws_view(frame, self.rows))
                self.repaint.append(b"\x1b[2J" in frame)
                if self.keep:
                    self.raw.append(frame)
                await self.ws.send(json.dumps({"ack": self.n}))

    async def key(self, down):
        await self.ws.send(json.dumps({"key": "d", "down": down}))

    def last_big_after(self, t):
        big = [u for (u, _), v, r in zip(self.log, self.view, self.repaint) if u >= t and v and not r]
        return (max(big) - t) if big else 0.0

    def repaints_after(self, t):
        return len([u for u, r in zip(self.log, self.repaint) if u[0] >= t and r])

    def fps_between(self, a, b):
        return len([u for (u, _), v in zip(self.log, self.view) if a <= u <= b and v]) / (b - a)

    def bytes_between(self, a, b):
        return sum(n for (u, n) in self.log if a <= u <= b)


async def quiet(player, s=1.0, limit=30):
    """Waits until no view-changing frame came for `s` seconds."""
    end = time.monotonic() + limit
    while time.monotonic() < end:
        await asyncio.sleep(0.1)
        big = [u for (u, _), v in zip(player.log, player.view) if v]
        if not big or time.monotonic() - big[-1] > s:
            return


async def measure(args, port):
    import websockets
    url = f"ws://127.0.0.1:{port}/ws?name=lag&cols={args.cols}&rows={args.rows}"
    async with websockets.connect(url, max_size=None) as ws:
        p = Player(ws, args.rows)
        p.keep = args.verbose
        reader = asyncio.create_task(p.read())
        await asyncio.sleep(2)
        await quiet(p)
        holds, taps, fps, kbps = [], [], [], []
        start = time.monotonic()
        for _ in range(args.runs):
            t0 = time.monotonic()
            await p.key(True)
            await asyncio.sleep(args.hold)
            up = time.monotonic()
            await p.key(False)
            await quiet(p, 1.5)
            holds.append(p.last_big_after(up) * 1000)
            if args.verbose:
                print([(round((u - up) * 1000), n, r) for (u, n), r in zip(p.log, p.repaint) if u >= up - 0.1], file=sys.stderr)
            fps.append(p.fps_between(t0 + 0.5, up))
            kbps.append(p.bytes_between(t0 + 0.5, up) * 8 / 1000 / (up - t0 - 0.5))
            await p.key(True)
            await asyncio.sleep(0.08)
            up = time.monotonic()
            await p.key(False)
            await quiet(p, 1.5)
            taps.append(p.last_big_after(up) * 1000)
            if args.verbose:
                for (u, n), m in zip(p.log, p.raw or [b""] * len(p.log)):
                    if u > up + 0.1 and draws_view(m, args.rows):
                        print("late", round((u - up) * 1000), m[:120], m[-200:], file=sys.stderr)
                print("tap", [(round((u - up) * 1000), n) for (u, n) in p.log if u >= up - 0.2], file=sys.stderr)
        reader.cancel()
        return {"rate": args.rate, "cols": args.cols, "rows": args.rows,
                "release_lag_ms": [round(x) for x in holds], "tap_lag_ms": [round(x) for x in taps],
                "turning_fps": [round(x, 1) for x in fps], "kbit_s": [round(x) for x in kbps],
                "level_repaints": p.repaints_after(start)}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("bin")
    ap.add_argument("--rate", default="1mbit")
    ap.add_argument("--queue-ms", type=int, default=200)
    ap.add_argument("--hold", type=float, default=3.0)
    ap.add_argument("--cols", type=int, default=80)
    ap.add_argument("--rows", type=int, default=24)
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--inside", action="store_true")
    ap.add_argument("--verbose", action="store_true")
    args = ap.parse_args()
    in_shaped_namespace(args.rate, args.queue_ms)
    with serving(args.bin, ()) as web:
        print(json.dumps(asyncio.run(measure(args, web))))


main()
