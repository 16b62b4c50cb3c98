#!/usr/bin/env python3
"""What a browser player's link carries: bytes a frame, the colour level held, frames a second,
and how stale the view is after a release in the first seconds of play.

Runs `halfcast serve --web --web-compress MODE` and a WebSocket player that inflates and
acknowledges each frame as the page does, inside a fresh network namespace whose loopback is a
token bucket (the recipe of ../shared/tools/linklag.py), then:

- first: joins, turns (`d` held) from 0.3 s to 1.8 s after joining, releases, and reports how
  long frames that change the 3D view keep arriving after the release (the lag the page shows
  in its first seconds, before anything is known of the link);
- steady: after 6 s of play, holds `d` for HOLD s and reports frames a second, bytes a frame on
  the wire and inflated, and the level the status line names at the end.

A frame "changes the view" when any cell of the view's rows (from the server's `view` note)
differs after it, read through a terminal model (pyte) after the run: status-line-only frames do
not count, and the model's slowness never delays an acknowledgement.

  python3 weblevels.py BIN [--rate 3mbit|none] [--cols 80 --rows 24] [--compress auto|always|never]
                      [--hold S] [--timeline]
Prints one JSON line. Needs root (it re-runs itself under `unshare -rn`), `tc`, and
`pip install websockets pyte`.
"""
from pagelib import in_shaped_namespace, serving
import argparse, asyncio, json, re, time, zlib

import pyte


class Page:
    """A page's connection: frames inflated and acknowledged at once, as a browser that paints
    in a few milliseconds does; they are read into a terminal model (pyte, far slower than a
    page) only afterwards, so the model's time is never taken for the link's."""

    def __init__(self, ws, cols, rows):
        self.ws = ws
        self.cols, self.rows = cols, rows
        self.view = None  # (y, rows)
        self.got = []  # (arrival, wire bytes, frame bytes)
        self.n = 0

    async def read(self):
        async for msg in self.ws:
            if isinstance(msg, str):
                note = json.loads(msg)
                if "view" in note:
                    self.view = (note["view"]["y"], note["view"]["rows"])
                continue
            frame = zlib.decompress(msg[1:], -15) if msg[:1] == b"\x00" else msg
            self.n += 1
            await self.ws.send(json.dumps({"ack": self.n}))
            self.got.append((time.monotonic(), len(msg), frame))

    async def key(self, down):
        await self.ws.send(json.dumps({"key": "d", "down": down}))

    def replay(self):
        """Every frame read into the model: (arrival, wire, inflated, changed the view, status
        line after it)."""
        screen = pyte.Screen(self.cols, self.rows)
        stream = pyte.ByteStream(screen)
        y, rows = self.view or (0, 0)
        out = []
        for at, wire, frame in self.got:
            before = tuple(screen.display[y:y + rows])
            stream.feed(frame)
            changed = tuple(screen.display[y:y + rows]) != before
            out.append((at, wire, len(frame), changed, screen.display[-1]))
        return out

    def quiet_for(self, s):
        """Seconds since the last frame of more than a status line's bytes."""
        big = [at for (at, _, frame) in self.got if len(frame) > 300]
        return time.monotonic() - big[-1] if big else s


def last_view_change_after(log, t):
    changed = [e[0] for e in log if e[0] >= t and e[3]]
    return (max(changed) - t) if changed else 0.0


def level_at(log, t):
    """The level the status line named at time `t`."""
    status = [e[4] for e in log if e[0] <= t]
    m = LEVEL.search(status[-1]) if status else None
    return m.group(1) if m else None


async def quiet(page, s=1.0, limit=20):
    end = time.monotonic() + limit
    while time.monotonic() < end:
        await asyncio.sleep(0.1)
        if page.quiet_for(s) >= s:
            return


LEVEL = re.compile(r"(truecolor|256|16|mono) \((?:link|browser|key)\)")


async def measure(args, port):
    import websockets
    url = f"ws://127.0.0.1:{port}/ws?name=lv&cols={args.cols}&rows={args.rows}"
    async with websockets.connect(url, max_size=None) as ws:
        page = Page(ws, args.cols, args.rows)
        joined = time.monotonic()
        reader = asyncio.create_task(page.read())
        await asyncio.sleep(0.3)
        await page.key(True)
        await asyncio.sleep(1.5)
        up = time.monotonic()
        await page.key(False)
        await quiet(page, 1.0)
        first_seen = time.monotonic()
        await asyncio.sleep(max(0.0, 6 - (time.monotonic() - joined)))
        await quiet(page, 1.0)
        t0 = time.monotonic()
        await page.key(True)
        await asyncio.sleep(args.hold)
        t1 = time.monotonic()
        await page.key(False)
        await quiet(page, 1.0)
        end = time.monotonic()
        reader.cancel()
    log = page.replay()
    turning = [e for e in log if t0 + 1.0 <= e[0] <= t1 and e[3]]
    span = t1 - t0 - 1.0
    return {
        "rate": args.rate, "size": f"{args.cols}x{args.rows}", "compress": args.compress,
        "first_release_lag_ms": round(last_view_change_after([e for e in log if e[0] <= first_seen], up) * 1000),
        "first_level": level_at(log, first_seen),
        "turning_fps": round(len(turning) / span, 1),
        "wire_bytes_per_frame": round(sum(e[1] for e in turning) / max(1, len(turning))),
        "inflated_bytes_per_frame": round(sum(e[2] for e in turning) / max(1, len(turning))),
        "release_lag_ms": round(last_view_change_after(log, t1) * 1000),
        "level": level_at(log, end),
        **({"timeline": timeline(log, joined)} if args.timeline else {}),
    }


def timeline(log, joined):
    """Each second of the run: frames that changed the view, mean wire and inflated bytes of
    all frames, the share sent compressed, and the level named at its end."""
    out = []
    for s in range(int((log[-1][0] - joined) + 1) if log else 0):
        a, b = joined + s, joined + s + 1
        sec = [e for e in log if a <= e[0] < b]
        if not sec:
            continue
        out.append([s, sum(1 for e in sec if e[3]), round(sum(e[1] for e in sec) / len(sec)),
                    round(sum(e[2] for e in sec) / len(sec)), level_at(log, b)])
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("bin")
    ap.add_argument("--rate", default="3mbit")
    ap.add_argument("--queue-ms", type=int, default=200)
    ap.add_argument("--hold", type=float, default=4.0)
    ap.add_argument("--cols", type=int, default=80)
    ap.add_argument("--rows", type=int, default=24)
    ap.add_argument("--compress", default="auto")
    ap.add_argument("--timeline", action="store_true", help="add a line a second")
    ap.add_argument("--inside", action="store_true")
    args = ap.parse_args()
    in_shaped_namespace(args.rate, args.queue_ms)
    with serving(args.bin, ["--web-compress", args.compress]) as web:
        print(json.dumps(asyncio.run(measure(args, web))))


main()
