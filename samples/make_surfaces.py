#!/usr/bin/env python3
"""Writes the sample surface files of this folder (run from anywhere; standard library only).

The NURBS samples place their control points at the Greville abscissae of their knot
vectors, so that x and y are exactly linear in u and v and z follows the design function
closely; `tpi info` on each file shows the curvature this gives.
"""
import json
import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))


def write(name, record):
    with open(os.path.join(HERE, name), "w") as f:
        f.write(format_record(record))


def num(x):
    x = round(x, 12) + 0.0
    return json.dumps(int(x) if x == int(x) and abs(x) < 1e15 else x)


def format_record(r):
    """JSON with one control point per line, everything else compact."""
    lines = ["{"]
    items = list(r.items())
    for k, (key, value) in enumerate(items):
        end = "," if k + 1 < len(items) else ""
        if key == "points":
            lines.append('  "points": [')
            for i, p in enumerate(value):
                lines.append("    [" + ", ".join(num(c) for c in p) + "]" + ("," if i + 1 < len(value) else ""))
            lines.append("  ]" + end)
        elif isinstance(value, list):
            lines.append(f'  "{key}": [' + ", ".join(num(c) for c in value) + "]" + end)
        elif isinstance(value, str):
            lines.append(f'  "{key}": "{value}"' + end)
        else:
            lines.append(f'  "{key}": {num(value)}' + end)
    lines.append("}")
    return "\n".join(lines) + "\n"


def greville(knots, degree, count):
    """Greville abscissae from Rhino-convention knots (count + degree - 1 of them)."""
    return [sum(knots[i:i + degree]) / degree for i in range(count)]


def graph_nurbs(knots_u, knots_v, degree, x_range, y_range, height):
    nu = len(knots_u) - degree + 1
    nv = len(knots_v) - degree + 1
    gu = greville(knots_u, degree, nu)
    gv = greville(knots_v, degree, nv)
    u0, u1 = knots_u[degree - 1], knots_u[nu - 1]
    v0, v1 = knots_v[degree - 1], knots_v[nv - 1]
    points = []
    for i in range(nu):  # u-major: point (i, j) at i * nv + j
        x = x_range[0] + (gu[i] - u0) / (u1 - u0) * (x_range[1] - x_range[0])
        for j in range(nv):
            y = y_range[0] + (gv[j] - v0) / (v1 - v0) * (y_range[1] - y_range[0])
            points.append([x, y, height(x, y)])
    return {
        "type": "nurbs",
        "degree": [degree, degree],
        "count": [nu, nv],
        "knots_u": knots_u,
        "knots_v": knots_v,
        "points": points,
    }


def biquadratic_patch(points, weights):
    """A single rational biquadratic Bezier patch (3 x 3 control points, u-major)."""
    return {
        "type": "nurbs",
        "degree": [2, 2],
        "count": [3, 3],
        "knots_u": [0, 0, 1, 1],
        "knots_v": [0, 0, 1, 1],
        "points": points,
        "weights": weights,
    }


def main():
    # Paraboloid of revolution z = -0.08 (x^2 + y^2): a shallow dome, top view of its
    # mesh = Voronoi diagram of the projected points.
    write("paraboloid.json", {"type": "elliptic_paraboloid", "a": -0.08, "b": -0.08, "x": [-5, 5], "y": [-5, 5]})
    # Anisotropic dome: curvature ratio 8 between x and y.
    write("anisotropic-dome.json", {"type": "elliptic_paraboloid", "a": -0.16, "b": -0.02, "x": [-5, 5], "y": [-5, 5]})
    # Hyperbolic paraboloid z = 0.08 (x^2 - y^2): K < 0 everywhere.
    write("hypar.json", {"type": "hyperbolic_paraboloid", "a": 0.08, "b": 0.08, "x": [-5, 5], "y": [-5, 5]})

    # Free-form bicubic dome, 7 x 6 control points, non-uniform clamped knots (Rhino
    # convention: count + degree - 1), strictly convex: a concave quadratic plus a tilt, a
    # twist and a cubic lean, which keep the Hessian negative definite.
    def dome(x, y):
        return 4.0 * (1 - (x / 7.5) ** 2 - (y / 6.5) ** 2) + 0.3 * x / 6 + 0.25 * (x / 6) * (y / 5) + 0.35 * (x / 6) ** 3

    write("nurbs-dome.json", graph_nurbs([0, 0, 0, 1.5, 4, 7.5, 10, 10, 10], [0, 0, 0, 3, 5.5, 8, 8, 8], 3, [-6, 6], [-5, 5], dome))

    # Mixed-curvature roof, 9 x 7 bicubic: a dome in the middle (K > 0) flowing into
    # saddle-shaped ends (K < 0, convex along x, concave along y), K = 0 between.
    def roof(x, y):
        return (1 - (y / 7.0) ** 2) * (3.0 + 1.5 * math.cos(math.pi * x / 9.0))

    write(
        "mixed-roof.json",
        graph_nurbs([0, 0, 0, 1, 2.5, 4, 5.5, 7, 8, 8, 8], [0, 0, 0, 1.5, 3, 4.5, 6, 6, 6], 3, [-10, 10], [-6, 6], roof),
    )

    # Rational biquadratic patch on a sphere of radius 10: a meridian arc of +-40 deg in
    # the xz-plane revolved by +-40 deg about the x axis. Exact sphere; weights cos 40 deg
    # on the middle row and column, their product in the centre.
    r, a, b = 10.0, math.radians(40), math.radians(40)
    profile = [(-r * math.sin(a), r * math.cos(a), 1.0), (0.0, r / math.cos(a), math.cos(a)), (r * math.sin(a), r * math.cos(a), 1.0)]
    arc = [(-math.sin(b), math.cos(b), 1.0), (0.0, 1.0 / math.cos(b), math.cos(b)), (math.sin(b), math.cos(b), 1.0)]
    points, weights = [], []
    for x, rad, wi in profile:
        for cy, cz, wj in arc:
            points.append([x, rad * cy, rad * cz])
            weights.append(wi * wj)
    write("rational-dome.json", biquadratic_patch(points, weights))

    # Free-form saddle, 8 x 6 bicubic: K < 0 everywhere, curvature varying across the
    # domain (a cubic lean along x and a twist).
    def saddle(x, y):
        return 0.05 * x * x - 0.09 * y * y + 0.03 * x * y + 0.003 * x ** 3

    write(
        "saddle.json",
        graph_nurbs([0, 0, 0, 1.5, 3, 5, 7, 8.5, 10, 10, 10], [0, 0, 0, 2, 4, 6, 8, 8, 8], 3, [-6, 6], [-4.5, 4.5], saddle),
    )

    # Torus band: the inner part of a torus (major radius 10, tube radius 3) facing its
    # hole, tube angle 120..240 deg and revolution angle -45..45 deg, K < 0 everywhere. An
    # exact rational biquadratic patch: a tube arc revolved about the z axis.
    big, small = 10.0, 3.0
    p0, p1 = math.radians(120), math.radians(240)
    t0, t1 = math.radians(-45), math.radians(45)

    def arc(a0, a1):
        half, mid = 0.5 * (a1 - a0), 0.5 * (a0 + a1)
        w = math.cos(half)
        return [(math.cos(a0), math.sin(a0), 1.0), (math.cos(mid) / w, math.sin(mid) / w, w), (math.cos(a1), math.sin(a1), 1.0)]

    points, weights = [], []
    for cx, cy, wu in arc(t0, t1):
        for px, pz, wv in arc(p0, p1):
            radial = big + small * px
            points.append([radial * cx, radial * cy, small * pz])
            weights.append(wu * wv)
    write("torus-band.json", biquadratic_patch(points, weights))

    # Ellipsoid of one face, semi-axes 12, 8 and 5, as Rhino makes a sphere: a rational
    # quadratic full circle in u (9 control points, closed) times a half circle from pole to
    # pole in v (5 control points), scaled per axis (an affine image stays exact).
    w = math.sqrt(0.5)
    circle = [(1, 0, 1), (1, 1, w), (0, 1, 1), (-1, 1, w), (-1, 0, 1), (-1, -1, w), (0, -1, 1), (1, -1, w), (1, 0, 1)]
    meridian = [(0, -1, 1), (1, -1, w), (1, 0, 1), (1, 1, w), (0, 1, 1)]
    points, weights = [], []
    for x, y, wu in circle:
        for r, z, wv in meridian:
            points.append([12.0 * x * r, 8.0 * y * r, 5.0 * z])
            weights.append(wu * wv)
    write("ellipsoid.json", {
        "type": "nurbs",
        "degree": [2, 2],
        "count": [9, 5],
        "knots_u": [0, 0, 1, 1, 2, 2, 3, 3, 4, 4],
        "knots_v": [0, 0, 1, 1, 2, 2],
        "points": points,
        "weights": weights,
    })

    # A polysurface: a vault with a ridge along x = 0, made of four bicubic faces (two each
    # side of the ridge, split again at y = 0), listed out of order and the right-hand faces
    # with u and v swapped, as a model's faces come. Convex everywhere, creased at the ridge.
    def vault(x, y):
        return 3.5 * (1 - (y / 9.0) ** 2) - 0.03 * x * x - 0.25 * abs(x)

    knots = [0, 0, 0, 1, 2, 3, 3, 3]

    def quarter(x_range, y_range, swap=False):
        face = graph_nurbs(knots, knots, 3, x_range, y_range, vault)
        if swap:
            n = len(knots) - 3 + 1
            face["points"] = [face["points"][i * n + j] for j in range(n) for i in range(n)]
        return face

    with open(os.path.join(HERE, "ridge-vault.json"), "w") as f:
        faces = [quarter([0, 8], [0, 6], True), quarter([-8, 0], [-6, 0]), quarter([-8, 0], [0, 6]), quarter([0, 8], [-6, 0], True)]
        f.write('{\n  "type": "polysurface",\n  "faces": [\n')
        f.write(",\n".join("    " + json.dumps(face, separators=(", ", ": ")) for face in faces))
        f.write("\n  ]\n}\n")


if __name__ == "__main__":
    main()
