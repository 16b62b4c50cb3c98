#!/usr/bin/env python3
"""Screenshots of the glyph ladder in a terminal that draws sextants and octants itself.

Runs each frame inside VTE's test terminal (`vte-2.91`, VTE 0.78 or newer) on a private Xvfb
display and grabs the window with Pillow. Not part of CI: it needs Xvfb, Pillow and a VTE app
that you built or installed yourself (see docs/output.md, "Screenshots").

    python3 docs/screenshots/take.py --vte /path/to/vte-2.91 --halfcast target/release/halfcast
"""

import argparse
import os
import subprocess
import tempfile
import time

from PIL import Image, ImageChops, ImageDraw, ImageFont, ImageGrab

SETTINGS = ["half", "quadrant", "sextant", "octant"]
FONT = "DejaVu Sans Mono 12"
LABEL_FONT = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"
CLEAR = "\\033[?25l\\033[H\\033[2J"  # hide the cursor, clear what the terminal printed first


def grab(display, vte, command, size, wait, env):
    """Open the terminal at `size` cells running `command`, wait, and return its window's pixels."""
    cols, rows = size
    args = [vte, "--no-decorations", "--no-scrollbar", "--no-context-menu", "--no-systemd-scope",
            "--geometry", f"{cols}x{rows}", "-f", FONT, "--"] + command
    term = subprocess.Popen(args, env=dict(env, DISPLAY=display, NO_AT_BRIDGE="1"),
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        time.sleep(wait)
        screen = ImageGrab.grab(xdisplay=display).convert("RGB")
    finally:
        term.terminate()
        term.wait()
    # The root window is white (Xvfb -wr) and the terminal sits at the top left.
    box = ImageChops.difference(screen, Image.new("RGB", screen.size, "white")).getbbox()
    return screen.crop(box)


def still(halfcast, glyphs, tmp):
    """A command that shows one `render --format ansi` frame and holds it, the cursor hidden."""
    path = os.path.join(tmp, f"{glyphs}.ans")
    frame = subprocess.run([halfcast, "render", "--size", "80x24", "--glyphs", glyphs,
                            "--format", "ansi", "--colors", "truecolor"],
                           check=True, capture_output=True).stdout
    with open(path, "wb") as f:
        f.write(frame.rstrip(b"\n"))  # a last newline would scroll the 24th row away
    return ["sh", "-c", f"printf '{CLEAR}'; cat {path}; sleep 60"]


def check(halfcast, glyphs, shot, tmp):
    """Compares a shot with halfcast's own picture of the frame (`render --format png`): the
    centre of every sub-pixel, and whether any screen pixel is neither of its cell's two colours."""
    path = os.path.join(tmp, "ref.png")
    subprocess.run([halfcast, "render", "--size", "80x24", "--glyphs", glyphs, "--format", "png",
                    "-o", path], check=True)
    ref = Image.open(path).convert("RGB")
    (cw, ch), (rw, rh) = (shot.width // 80, shot.height // 24), (ref.width // 80, ref.height // 24)
    sx, sy = {"half": (1, 2), "quadrant": (2, 2), "sextant": (2, 3), "octant": (2, 4)}[glyphs]
    s, r = shot.load(), ref.load()

    def centre(w, h, col, row, i, j):  # the middle of sub-pixel (i, j) of a w x h cell
        return col * w + int((i + 0.5) * w / sx), row * h + int((j + 0.5) * h / sy)

    centres = stray = 0
    for row in range(24):
        for col in range(80):
            colours = {r[col * rw + x, row * rh + y] for x in range(rw) for y in range(rh)}
            stray += sum(s[col * cw + x, row * ch + y] not in colours
                         for x in range(cw) for y in range(ch))
            centres += sum(s[centre(cw, ch, col, row, i, j)] != r[centre(rw, rh, col, row, i, j)]
                           for i in range(sx) for j in range(sy))
    print(f"{glyphs}: cell {cw}x{ch} px; sub-pixel centres unlike halfcast's PNG: {centres} of "
          f"{80 * 24 * sx * sy}; pixels neither of their cell's colours: {stray} of "
          f"{shot.width * shot.height}")


def labelled(images, names, columns):
    """A grid of same-sized shots, each with its name above it."""
    font = ImageFont.truetype(LABEL_FONT, 18)
    w, h = images[0].size
    pad, label = 12, 26
    rows = (len(images) + columns - 1) // columns
    sheet = Image.new("RGB", (columns * (w + pad) + pad, rows * (h + label + pad) + pad), "white")
    draw = ImageDraw.Draw(sheet)
    for i, (im, name) in enumerate(zip(images, names)):
        x = pad + (i % columns) * (w + pad)
        y = pad + (i // columns) * (h + label + pad)
        draw.text((x, y), name, fill="black", font=font)
        sheet.paste(im, (x, y + label))
    return sheet


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--vte", required=True, help="VTE's test terminal, vte-2.91 (0.78+)")
    p.add_argument("--halfcast", default="target/release/halfcast")
    p.add_argument("--out", default="docs/screenshots")
    p.add_argument("--display", default=":77")
    a = p.parse_args()
    xvfb = subprocess.Popen(["Xvfb", a.display, "-screen", "0", "1600x1000x24", "-wr",
                             "-nolisten", "tcp"], stderr=subprocess.DEVNULL)
    time.sleep(2)
    try:
        with tempfile.TemporaryDirectory() as tmp:
            env = dict(os.environ, HOME=tmp, XDG_CONFIG_HOME=tmp, XDG_DATA_HOME=tmp)
            shots = [grab(a.display, a.vte, still(a.halfcast, g, tmp), (80, 24), 3, env)
                     for g in SETTINGS]
            for g, shot in zip(SETTINGS, shots):
                check(a.halfcast, g, shot, tmp)
            labelled(shots, [f"--glyphs {g}" for g in SETTINGS], 2).save(
                os.path.join(a.out, "glyphs-80x24.webp"), lossless=True, method=6)
            # The middle of the view, 3x, half-blocks beside octants: the bricks' mortar.
            box = (300, 120, 500, 240)
            zooms = [shots[i].crop(box).resize((600, 360), Image.NEAREST) for i in (0, 3)]
            labelled(zooms, ["half, 3x", "octant, 3x"], 2).save(
                os.path.join(a.out, "glyphs-zoom.webp"), lossless=True, method=6)
            card = grab(a.display, a.vte, ["sh", "-c", f"printf '{CLEAR}'; {a.halfcast} glyphs"
                                           " --colors truecolor; sleep 60"], (90, 26), 3, env)
            card.save(os.path.join(a.out, "glyphs-card.webp"), lossless=True, method=6)
            plays = [grab(a.display, a.vte, [a.halfcast, "play", "--glyphs", g, "--seed", "1",
                                             "--no-mouse"], (80, 24), 4, env) for g in SETTINGS]
            labelled(plays, [f"halfcast play --glyphs {g}" for g in SETTINGS], 2).save(
                os.path.join(a.out, "play-80x24.webp"), lossless=True, method=6)
    finally:
        xvfb.terminate()
        xvfb.wait()


if __name__ == "__main__":
    main()
