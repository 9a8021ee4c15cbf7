#!/usr/bin/env python3
"""Draws examples/painting/villa_front.png: a stand-in for the photograph
seed 004 paints over (no photograph ships with lsys). A front elevation of
the villa in examples/painting/villa.lsys at 80 pixels a metre over
x -0.5..12.5, y -0.5..9.1 (the `// paint photo` line of that session):
brick below, rendered plaster above, roof tiles, glazed windows with
curtains, a planked door, a stone terrace edge and a timber porch.
Deterministic (seeded noise). Needs Pillow.

    python3 scripts/make_facade_photo.py examples/painting/villa_front.png
"""
import random
import sys

from PIL import Image, ImageDraw, ImageFilter

PX = 80  # pixels a metre
X0, Y0, X1, Y1 = -0.5, -0.5, 12.5, 9.1
W, H = round((X1 - X0) * PX), round((Y1 - Y0) * PX)
rng = random.Random(4)


def box(x0, y0, x1, y1):
    """A rectangle in metres (y up) as pixel corners (y down)."""
    return (round((x0 - X0) * PX), round((Y1 - y1) * PX), round((x1 - X0) * PX), round((Y1 - y0) * PX))


def noisy(d, rect, base, spread, step=3):
    x0, y0, x1, y1 = rect
    for y in range(y0, y1, step):
        for x in range(x0, x1, step):
            k = rng.randint(-spread, spread)
            d.rectangle((x, y, x + step - 1, y + step - 1), fill=tuple(max(0, min(255, c + k)) for c in base))


def bricks(d, x0, y0, x1, y1):
    r = box(x0, y0, x1, y1)
    d.rectangle(r, fill=(196, 188, 176))  # mortar
    bw, bh, joint = 0.24 * PX, 0.075 * PX, 0.012 * PX
    row = 0
    y = r[3]
    while y > r[1]:
        off = (bw / 2) * (row % 2)
        x = r[0] - off
        while x < r[2]:
            c = rng.choice([(150, 70, 50), (160, 78, 56), (140, 64, 46), (170, 88, 62)])
            d.rectangle((max(r[0], x + joint), max(r[1], y - bh + joint), min(r[2], x + bw - joint), y - joint), fill=c)
            x += bw
        y -= bh
        row += 1


def window(d, x0, y0, x1, y1):
    d.rectangle(box(x0, y0, x1, y1), fill=(70, 52, 36))
    f = 0.08
    glass = box(x0 + f, y0 + f, x1 - f, y1 - f)
    d.rectangle(glass, fill=(120, 150, 170))
    gx0, gy0, gx1, gy1 = glass
    # Sky reflected, curtains drawn aside, a mullion and a transom.
    d.polygon([(gx0, gy1), (gx0 + (gx1 - gx0) * 0.6, gy0), (gx1, gy0), (gx1, gy0 + (gy1 - gy0) * 0.3)], fill=(165, 190, 205))
    cw = (gx1 - gx0) * 0.18
    d.rectangle((gx0, gy0, gx0 + cw, gy1), fill=(225, 215, 190))
    d.rectangle((gx1 - cw, gy0, gx1, gy1), fill=(225, 215, 190))
    mx = (gx0 + gx1) // 2
    d.rectangle((mx - 3, gy0, mx + 3, gy1), fill=(70, 52, 36))
    ty = gy0 + (gy1 - gy0) // 3
    d.rectangle((gx0, ty - 3, gx1, ty + 3), fill=(70, 52, 36))
    # A sill.
    d.rectangle(box(x0 - 0.06, y0 - 0.06, x1 + 0.06, y0), fill=(205, 200, 190))


def door(d, x0, y0, x1, y1):
    d.rectangle(box(x0, y0, x1, y1), fill=(70, 52, 36))
    leaf = box(x0 + 0.08, y0, x1 - 0.08, y1 - 0.08)
    d.rectangle(leaf, fill=(128, 40, 32))
    lx0, ly0, lx1, ly1 = leaf
    for k in range(1, 6):
        x = lx0 + (lx1 - lx0) * k // 6
        d.line((x, ly0, x, ly1), fill=(100, 30, 24), width=2)
    d.ellipse((lx1 - 22, (ly0 + ly1) // 2 - 5, lx1 - 12, (ly0 + ly1) // 2 + 5), fill=(210, 180, 90))


def main(out):
    img = Image.new("RGB", (W, H))
    d = ImageDraw.Draw(img)
    for y in range(H):  # sky
        t = y / H
        d.line((0, y, W, y), fill=(int(150 + 60 * t), int(185 + 40 * t), int(225 + 20 * t)))
    d.rectangle(box(X0, Y0, X1, 0), fill=(96, 112, 72))  # grass
    bricks(d, 0, 0, 12, 3.4)  # the lower body
    noisy(d, box(0, 3.4, 7, 6.6), (226, 214, 190), 8)  # plaster above
    d.rectangle(box(0, 3.34, 12, 3.46), fill=(190, 184, 172))  # a string course
    noisy(d, box(7, 3.4, 12, 3.7), (168, 164, 156), 10)  # the terrace edge
    # Roof tiles: rows of dark glazed tiles, over the eaves' 0.3 overhang
    # at the gables (house.rules' EAVE).
    rx0, ry0, rx1, ry1 = box(-0.3, 6.6, 7.3, 8.6)
    d.rectangle((rx0, ry0, rx1, ry1), fill=(40, 70, 66))
    for k, y in enumerate(range(ry1, ry0, -int(0.18 * PX))):
        d.line((rx0, y, rx1, y), fill=(28, 50, 48), width=3)
        for x in range(rx0 + (k % 2) * 10, rx1, 20):
            d.line((x, y, x, y - int(0.18 * PX)), fill=(52, 86, 80), width=2)
    window(d, 1, 1, 2.4, 2.4)
    window(d, 2.8, 1, 3.7, 2.4)
    window(d, 1, 4.4, 2.4, 5.8)
    window(d, 4.6, 4.4, 6, 5.8)
    door(d, 4.2, 0, 5.4, 2.6)
    # The porch: a stone platform, timber posts and a rail.
    noisy(d, box(7.6, 0, 11.6, 0.68), (150, 146, 138), 12)
    for x in (7.6, 11.2):
        d.rectangle(box(x, 0.68, x + 0.4, 3.4), fill=(150, 50, 40))
    d.rectangle(box(8.0, 1.4, 11.2, 1.55), fill=(200, 160, 70))
    for k in range(12):
        x = 8.1 + k * 0.26
        d.rectangle(box(x, 0.68, x + 0.08, 1.4), fill=(190, 150, 64))
    img = img.filter(ImageFilter.GaussianBlur(0.6))
    img.save(out, optimize=True)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "villa_front.png")
