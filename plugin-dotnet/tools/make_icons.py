#!/usr/bin/env python3
"""Writes the 24x24 Grasshopper icons of Tpi.Grasshopper/Icons/ as PNG (standard library only).

    python3 plugin-dotnet/tools/make_icons.py

discretise.png: three planar hexagonal panels; pattern.png: pattern points in a hex grid;
quality.png: a panel with bars; fabricate.png: flat hexagonal parts nested on a sheet. Drawn with anti-aliasing by 4x4 supersampling.
"""
import math
import os
import struct
import zlib

SIZE = 24
SS = 4  # supersampling per axis


def png(path, pixels):
    raw = b"".join(b"\x00" + bytes(row) for row in pixels)

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    data = b"\x89PNG\r\n\x1a\n"
    data += chunk(b"IHDR", struct.pack(">IIBBBBB", SIZE, SIZE, 8, 6, 0, 0, 0))
    data += chunk(b"IDAT", zlib.compress(raw, 9))
    data += chunk(b"IEND", b"")
    with open(path, "wb") as f:
        f.write(data)


def hexagon(cx, cy, r):
    return [(cx + r * math.cos(math.pi / 6 + k * math.pi / 3), cy + r * math.sin(math.pi / 6 + k * math.pi / 3)) for k in range(6)]


def inside(poly, x, y):
    c = False
    n = len(poly)
    for i in range(n):
        (x1, y1), (x2, y2) = poly[i], poly[(i + 1) % n]
        if (y1 > y) != (y2 > y) and x < x1 + (y - y1) * (x2 - x1) / (y2 - y1):
            c = not c
    return c


def near_edge(poly, x, y, width):
    n = len(poly)
    for i in range(n):
        (x1, y1), (x2, y2) = poly[i], poly[(i + 1) % n]
        dx, dy = x2 - x1, y2 - y1
        t = max(0.0, min(1.0, ((x - x1) * dx + (y - y1) * dy) / (dx * dx + dy * dy)))
        if math.hypot(x - x1 - t * dx, y - y1 - t * dy) <= width / 2:
            return True
    return False


def render(shapes):
    """shapes: list of (kind, geometry, rgba) drawn in order; kinds: fill, outline, disc."""
    pixels = []
    for py in range(SIZE):
        row = []
        for px in range(SIZE):
            acc = [0.0, 0.0, 0.0, 0.0]
            for sy in range(SS):
                for sx in range(SS):
                    x = px + (sx + 0.5) / SS
                    y = py + (sy + 0.5) / SS
                    colour = (0, 0, 0, 0)
                    for kind, geometry, rgba in shapes:
                        if kind == "fill" and inside(geometry, x, y):
                            colour = rgba
                        elif kind == "outline" and near_edge(geometry, x, y, 1.2):
                            colour = rgba
                        elif kind == "disc" and math.hypot(x - geometry[0], y - geometry[1]) <= geometry[2]:
                            colour = rgba
                    a = colour[3] / 255.0
                    for c in range(3):
                        acc[c] += colour[c] * a
                    acc[3] += a
            n = SS * SS
            alpha = acc[3] / n
            if alpha > 0:
                row += [int(round(acc[c] / acc[3])) for c in range(3)] + [int(round(255 * alpha))]
            else:
                row += [0, 0, 0, 0]
        pixels.append(row)
    return pixels


BLUE = (40, 110, 190, 255)
LIGHT = (170, 205, 240, 255)
DARK = (30, 40, 60, 255)
ORANGE = (230, 120, 30, 255)


def discretise():
    shapes = []
    for cx, cy in [(7.5, 8.5), (16.5, 8.5), (12.0, 16.3)]:
        h = hexagon(cx, cy, 5.0)
        shapes += [("fill", h, LIGHT), ("outline", h, BLUE)]
    return render(shapes)


def pattern():
    shapes = []
    for j in range(4):
        for i in range(4):
            x = 3.5 + 5.5 * i + (2.75 if j % 2 else 0)
            y = 3.5 + 5.5 * j
            if x + 1.6 < 23.5:
                shapes.append(("disc", (x, y, 1.6), DARK))
    return render(shapes)


def quality():
    h = hexagon(12, 12, 10.5)
    shapes = [("fill", h, LIGHT), ("outline", h, BLUE)]
    for i, height in enumerate([5, 9, 7]):
        x0 = 7 + 4 * i
        shapes.append(("fill", [(x0, 17), (x0 + 2.6, 17), (x0 + 2.6, 17 - height), (x0, 17 - height)], ORANGE))
    return render(shapes)


def fabricate():
    sheet = [(1.5, 4.5), (22.5, 4.5), (22.5, 19.5), (1.5, 19.5)]
    shapes = [("fill", sheet, (245, 235, 215, 255)), ("outline", sheet, DARK)]
    for cx, cy in [(7.0, 9.2), (16.5, 9.2), (11.75, 15.0)]:
        h = hexagon(cx, cy, 3.8)
        shapes += [("fill", h, LIGHT), ("outline", h, ORANGE)]
    return render(shapes)


if __name__ == "__main__":
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "Tpi.Grasshopper", "Icons")
    os.makedirs(out, exist_ok=True)
    for name, make in [("discretise", discretise), ("pattern", pattern), ("quality", quality), ("fabricate", fabricate)]:
        png(os.path.join(out, name + ".png"), make())
        print("wrote", os.path.join(out, name + ".png"))
