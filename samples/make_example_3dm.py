#!/usr/bin/env python3
"""Writes samples/example.3dm (or the file given) with rhino3dm, reproducibly: the model of the
README's converter example and of tests/converter (millimetres).

Objects, in this order:
  0. a convex bicubic NURBS dome 4 x 4 m, 1.5 m high, over a 5 x 5 control net (a bare
     surface);
  1. a rational NURBS surface of degree 7 x 5 (a bare surface, exercises high degrees);
  2. a sphere (a Brep of one face: closed in u, poles at both ends of v);
  3. a box (a polysurface of 6 faces, 12 shared edges);
  4. a plane trimmed by a circle (a Brep face with a curved outer loop);
  5. a capped cylinder (an Extrusion: one closed wall, two trimmed caps);
  6. a slab with a round hole (an Extrusion with an inner profile: caps with a hole).

Usage: make_example_3dm.py [OUT.3dm]
"""

import math
import os
import sys

import rhino3dm


def nurbs_surface(degree, count, rational, height):
    """Clamped uniform knots, a regular net over [0, 4000]^2 mm, heights from `height`."""
    surface = rhino3dm.NurbsSurface.Create(3, rational, degree[0] + 1, degree[1] + 1, count[0], count[1])
    for knots, d, n in ((surface.KnotsU, degree[0], count[0]), (surface.KnotsV, degree[1], count[1])):
        inner = n - d - 1
        values = [0.0] * (d - 1) + [k / (inner + 1) for k in range(inner + 2)] + [1.0] * (d - 1)
        for k, value in enumerate(values):
            knots[k] = value
    for i in range(count[0]):
        for j in range(count[1]):
            s, t = i / (count[0] - 1), j / (count[1] - 1)
            x, y, z = 4000.0 * s, 4000.0 * t, height(s, t)
            w = 1.0 + 0.5 * math.sin(3.0 * s + 2.0 * t) ** 2 if rational else 1.0
            surface.Points[i, j] = rhino3dm.Point4d(x * w, y * w, z * w, w)
    assert surface.IsValid
    return surface


def build():
    model = rhino3dm.File3dm()
    model.Settings.ModelUnitSystem = rhino3dm.UnitSystem.Millimeters
    dome = nurbs_surface((3, 3), (5, 5), False, lambda s, t: 1500.0 * (1.0 - 0.5 * ((2 * s - 1) ** 2 + (2 * t - 1) ** 2)))
    model.Objects.AddSurface(dome)
    high = nurbs_surface((7, 5), (9, 7), True, lambda s, t: 400.0 * math.sin(3.0 * s) * math.cos(2.0 * t))
    model.Objects.AddSurface(high)
    model.Objects.AddBrep(rhino3dm.Brep.CreateFromSphere(rhino3dm.Sphere(rhino3dm.Point3d(6000, 0, 0), 1000.0)))
    box = rhino3dm.Box(rhino3dm.BoundingBox(0, 6000, 0, 1000, 8000, 1500))
    model.Objects.AddBrep(rhino3dm.Brep.CreateFromBox(box))
    circle = rhino3dm.Circle(rhino3dm.Point3d(3000, 7000, 0), 800.0).ToNurbsCurve()
    model.Objects.AddBrep(rhino3dm.Brep.CreateTrimmedPlane(rhino3dm.Plane.WorldXY(), circle))
    cylinder = rhino3dm.Cylinder(rhino3dm.Circle(rhino3dm.Point3d(6000, 6000, 0), 500.0), 2000.0)
    model.Objects.AddExtrusion(rhino3dm.Extrusion.CreateCylinderExtrusion(cylinder, True, True))
    outline = rhino3dm.Polyline(5)
    for x, y in ((0, 0), (2000, 0), (2000, 1000), (0, 1000), (0, 0)):
        outline.Add(x, y, 0)
    slab = rhino3dm.Extrusion.Create(outline.ToNurbsCurve(), 300.0, True)
    # The inner profile is taken in the profile plane's coordinates (the world's XY here).
    slab.AddInnerProfile(rhino3dm.Circle(rhino3dm.Point3d(1000, 500, 0), 200.0).ToNurbsCurve())
    slab.Translate(rhino3dm.Vector3d(8000, 0, 0))
    model.Objects.AddExtrusion(slab)
    return model


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "example.3dm")
    if not build().Write(out, 8):
        raise SystemExit("cannot write " + out)
    sys.stderr.write("wrote {}\n".format(out))


if __name__ == "__main__":
    main()
