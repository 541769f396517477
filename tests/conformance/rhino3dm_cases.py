#!/usr/bin/env python3
"""NURBS conformance cases from openNURBS, through the PyPI package rhino3dm.

Builds random NURBS surfaces with rhino3dm (fixed seed), evaluates NurbsSurface.PointAt and
NurbsSurface.NormalAt at random parameters, and writes the surfaces (as read back from rhino3dm,
in the project's surface-file NURBS format) with the samples to a JSON file. The Rust test
native/tpi-core/tests/nurbs_opennurbs.rs runs this script and compares tpi-core against it.

Usage: rhino3dm_cases.py --out cases.json [--seed N] [--surfaces N] [--samples N]

Surfaces: --surfaces of degrees 1..5 in each direction, control point counts degree+1 .. degree+6, rational
about half of the time (weights 0.3 .. 3), non-uniform knots with some repeated interior knots
(multiplicity <= degree), domains that do not start at 0; most knot vectors are clamped, some
are not (openNURBS evaluates both). The control net is a jittered, strictly monotone grid in
x (along u) and y (along v) with a random height, then rotated and moved: Su x Sv never vanishes,
so normals are well conditioned everywhere.

Then --high-degree-surfaces of degrees 6..11 (Rhino's limit, tpi's MAX_NURBS_DEGREE), every
degree in each direction, with degree+1 .. degree+3 control points per direction (same knots,
weights and nets otherwise).

Samples: the four domain corners, points on each of the four edges, points exactly on interior
knots (u, v or both), and uniformly random points in the domain.

How rhino3dm exposes control points (found by experiment with rhino3dm 8.x, see
`check_control_point_convention`): `surface.Points[i, j]` and `Points.GetControlPoint(i, j)` are
`Point4d` in HOMOGENEOUS form (x*w, y*w, z*w, w); assigning `Points[i, j] = Point4d(...)` also
takes homogeneous coordinates. `Points.GetPoint(i, j)` returns the Euclidean `Point3d`
(x, y, z). This differs from RhinoCommon's ControlPoint, whose Location is Euclidean. Knots
(`surface.KnotsU`, `surface.KnotsV`) are in Rhino's convention: count + degree - 1 values.
"""

import argparse
import json
import math
import random
import sys

try:
    import rhino3dm
except ImportError:
    sys.stderr.write(
        "rhino3dm is not installed for this Python interpreter ({}).\n"
        "Install it with: {} -m pip install 'rhino3dm==8.*'\n".format(sys.executable, sys.executable)
    )
    sys.exit(3)


def check_control_point_convention():
    """Fails loudly if rhino3dm's Point4d control points were not homogeneous."""
    surface = rhino3dm.NurbsSurface.Create(3, True, 2, 2, 2, 2)
    for direction_knots in (surface.KnotsU, surface.KnotsV):
        direction_knots[0] = 0.0
        direction_knots[1] = 1.0
    weight = 3.0
    surface.Points[0, 0] = rhino3dm.Point4d(0.0, 0.0, 0.0, 1.0)
    surface.Points[1, 0] = rhino3dm.Point4d(1.0 * weight, 0.0, 0.0, weight)
    surface.Points[0, 1] = rhino3dm.Point4d(0.0, 1.0, 0.0, 1.0)
    surface.Points[1, 1] = rhino3dm.Point4d(1.0, 1.0, 0.0, 1.0)
    euclidean = surface.Points.GetPoint(1, 0)
    at_corner = surface.PointAt(1.0, 0.0)
    # Homogeneous storage: Euclidean (1, 0, 0) with weight 3; S(0.5, 0) = (0 + 3) / (1 + 3).
    at_middle = surface.PointAt(0.5, 0.0)
    ok = (
        abs(euclidean.X - 1.0) < 1e-15
        and abs(at_corner.X - 1.0) < 1e-15
        and abs(at_middle.X - 0.75) < 1e-15
        and abs(surface.Points.GetControlPoint(1, 0).W - weight) < 1e-15
    )
    if not ok:
        sys.stderr.write("rhino3dm's control point convention is not the homogeneous one this script assumes\n")
        sys.exit(4)


def cumulative(values):
    total, out = 0.0, []
    for value in values:
        total += value
        out.append(total)
    return out


def random_knots(rng, degree, count, clamped):
    """Rhino-convention knots (count + degree - 1) over a random domain not starting at 0."""
    start = rng.uniform(0.1, 60.0) * rng.choice((-1.0, 1.0))
    length = 10.0 ** rng.uniform(-1.0, 1.5)
    end = start + length
    interior_count = count - degree - 1
    # Group interior knots into distinct values with multiplicities 1..degree.
    multiplicities = []
    remaining = interior_count
    while remaining > 0:
        if degree > 1 and rng.random() < 0.3:
            multiplicity = rng.randint(2, min(degree, remaining)) if remaining >= 2 else 1
        else:
            multiplicity = 1
        multiplicities.append(multiplicity)
        remaining -= multiplicity
    # Non-uniform gaps between breakpoints, none smaller than a fifth of the largest.
    gaps = [rng.uniform(0.2, 1.0) for _ in range(len(multiplicities) + 1)]
    scale = length / sum(gaps)
    breakpoints = [start + scale * c for c in cumulative(gaps)[:-1]]
    interior = []
    for value, multiplicity in zip(breakpoints, multiplicities):
        interior.extend([value] * multiplicity)

    if clamped:
        before = [start] * (degree - 1)
        after = [end] * (degree - 1)
    else:
        step = length / (len(multiplicities) + 1)
        before = [start - step * c for c in cumulative(rng.uniform(0.3, 1.0) for _ in range(degree - 1))][::-1]
        after = [end + step * c for c in cumulative(rng.uniform(0.3, 1.0) for _ in range(degree - 1))]
    knots = before + [start] + interior + [end] + after
    assert len(knots) == count + degree - 1
    assert all(a <= b for a, b in zip(knots, knots[1:]))
    return knots


def random_rotation(rng):
    """A random rotation matrix (rows) from a random unit quaternion."""
    while True:
        q = [rng.gauss(0.0, 1.0) for _ in range(4)]
        norm = math.sqrt(sum(c * c for c in q))
        if norm > 1e-3:
            break
    w, x, y, z = (c / norm for c in q)
    return [
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ]


def random_net(rng, count_u, count_v):
    """Euclidean control points, u-major: a jittered monotone grid with random heights."""
    size = 10.0 ** rng.uniform(-1.0, 2.0)
    xs = cumulative(rng.uniform(0.5, 1.5) for _ in range(count_u))
    ys = cumulative(rng.uniform(0.5, 1.5) for _ in range(count_v))
    rotation = random_rotation(rng)
    offset = [rng.uniform(-100.0, 100.0) for _ in range(3)]
    points = []
    for i in range(count_u):
        for j in range(count_v):
            local = [
                xs[i] + rng.uniform(-0.15, 0.15),
                ys[j] + rng.uniform(-0.15, 0.15),
                rng.uniform(-0.6, 0.6),
            ]
            points.append([offset[r] + size * sum(rotation[r][c] * local[c] for c in range(3)) for r in range(3)])
    return points


def make_surface(rng, index, degrees=None):
    """A random surface; `degrees` (du, dv) fixes the degrees (high-degree cases), which then get
    fewer spans (count degree+1 .. degree+3) to keep the run short."""
    if degrees is None:
        degree_u, degree_v = rng.randint(1, 5), rng.randint(1, 5)
        extra_u = extra_v = 6
    else:
        degree_u, degree_v = degrees
        extra_u = extra_v = 3
    count_u = rng.randint(degree_u + 1, degree_u + extra_u)
    count_v = rng.randint(degree_v + 1, degree_v + extra_v)
    rational = rng.random() < 0.5
    clamped = rng.random() < 0.8
    knots_u = random_knots(rng, degree_u, count_u, clamped)
    knots_v = random_knots(rng, degree_v, count_v, clamped)
    points = random_net(rng, count_u, count_v)
    weights = [rng.uniform(0.3, 3.0) for _ in points] if rational else [1.0] * len(points)

    surface = rhino3dm.NurbsSurface.Create(3, rational, degree_u + 1, degree_v + 1, count_u, count_v)
    for k, value in enumerate(knots_u):
        surface.KnotsU[k] = value
    for k, value in enumerate(knots_v):
        surface.KnotsV[k] = value
    for i in range(count_u):
        for j in range(count_v):
            x, y, z = points[i * count_v + j]
            w = weights[i * count_v + j]
            # Homogeneous, see the module doc.
            surface.Points[i, j] = rhino3dm.Point4d(x * w, y * w, z * w, w)
    if not surface.IsValid:
        raise RuntimeError("surface {} is not valid for openNURBS".format(index))
    return surface, rational, clamped


def read_back(surface, rational):
    """The surface as rhino3dm reports it, in the project's NURBS record format."""
    count_u, count_v = surface.Points.CountU, surface.Points.CountV
    record = {
        "degree": [surface.Degree(0), surface.Degree(1)],
        "count": [count_u, count_v],
        "knots_u": [surface.KnotsU[k] for k in range(len(surface.KnotsU))],
        "knots_v": [surface.KnotsV[k] for k in range(len(surface.KnotsV))],
        "points": [],
    }
    weights = []
    for i in range(count_u):
        for j in range(count_v):
            p = surface.Points.GetPoint(i, j)
            record["points"].append([p.X, p.Y, p.Z])
            weights.append(surface.Points.GetControlPoint(i, j).W)
    if rational:
        record["weights"] = weights
    return record


def sample_parameters(rng, surface, samples):
    (u0, u1), (v0, v1) = ((surface.Domain(d).T0, surface.Domain(d).T1) for d in (0, 1))
    interior_u = sorted({k for k in surface.KnotsU if u0 < k < u1})
    interior_v = sorted({k for k in surface.KnotsV if v0 < k < v1})
    uv = [(u0, v0), (u1, v0), (u0, v1), (u1, v1)]
    for _ in range(2):
        uv += [
            (rng.uniform(u0, u1), v0),
            (rng.uniform(u0, u1), v1),
            (u0, rng.uniform(v0, v1)),
            (u1, rng.uniform(v0, v1)),
        ]
    for knot in interior_u[:4]:
        uv.append((knot, rng.uniform(v0, v1)))
    for knot in interior_v[:4]:
        uv.append((rng.uniform(u0, u1), knot))
    for ku, kv in zip(interior_u[:3], interior_v[:3]):
        uv.append((ku, kv))
    if interior_u:
        uv.append((interior_u[-1], v1))
    if interior_v:
        uv.append((u0, interior_v[0]))
    while len(uv) < samples:
        uv.append((rng.uniform(u0, u1), rng.uniform(v0, v1)))
    return (u0, u1), (v0, v1), uv


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", required=True, help="JSON file to write")
    parser.add_argument("--seed", type=int, default=20240607)
    parser.add_argument("--surfaces", type=int, default=240)
    parser.add_argument("--samples", type=int, default=60)
    parser.add_argument(
        "--high-degree-surfaces",
        type=int,
        default=36,
        help="further surfaces of degrees 6..11 (Rhino's limit), each degree in each direction",
    )
    args = parser.parse_args()

    check_control_point_convention()
    rng = random.Random(args.seed)
    cases = []
    # Degrees 6..11 cycle in u, and in v with another phase, so that every pair of directions
    # sees each of them; the first high-degree case is 11 x 11.
    high = [(11 - k % 6, 11 - (k * 5 + k // 6) % 6) for k in range(args.high_degree_surfaces)]
    for index in range(args.surfaces + len(high)):
        degrees = high[index - args.surfaces] if index >= args.surfaces else None
        surface, rational, clamped = make_surface(rng, index, degrees)
        domain_u, domain_v, uv = sample_parameters(rng, surface, args.samples)
        samples = []
        for u, v in uv:
            p = surface.PointAt(u, v)
            n = surface.NormalAt(u, v)
            samples.append({"u": u, "v": v, "point": [p.X, p.Y, p.Z], "normal": [n.X, n.Y, n.Z]})
        cases.append(
            {
                "name": "surface {} (degree {}x{}, {}, {})".format(
                    index,
                    surface.Degree(0),
                    surface.Degree(1),
                    "rational" if rational else "non-rational",
                    "clamped" if clamped else "unclamped",
                ),
                "surface": read_back(surface, rational),
                "domain_u": list(domain_u),
                "domain_v": list(domain_v),
                "samples": samples,
            }
        )
    document = {"generator": "rhino3dm " + rhino3dm.__version__, "seed": args.seed, "cases": cases}
    with open(args.out, "w") as out:
        json.dump(document, out)


if __name__ == "__main__":
    main()
