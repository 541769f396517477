#!/usr/bin/env python3
"""Runs tools/3dm_to_tpi.py on a model built here with rhino3dm, and records what the Rust test
native/tpi-core/tests/converter_3dm.rs checks against tpi-core.

Usage: check_3dm_to_tpi.py --out DIR [--seed N] [--samples N]

Builds the model of samples/make_example_3dm.py (a NURBS dome, a degree 7 x 5 rational surface,
a sphere, a box, a trimmed plane, a capped cylinder, a slab with a hole; millimetres), writes it to DIR/model.3dm,
converts it into DIR/plain (--no-trims) and DIR/trims (the default, with trims), then reads the .3dm
again (independently of the converter) and, for every face in the index, evaluates the source
geometry with rhino3dm at random parameters of the written NURBS surface's domain: bare surfaces
with their own PointAt, Brep faces with BrepFace.PointAt at the surface parameters that
`GetSurfaceParameterFromNurbsFormParameter` gives. Writes DIR/expected.json:
{"index": ..., "faces": [{"file", "samples": [{"u", "v", "point"}]}], "trim_distances": ...}.

Polysurfaces: a second model, DIR/polysurfaces.3dm (millimetres), of Breps with several faces,
converted into DIR/poly (the default) and DIR/poly-off (`--no-polysurfaces`):
  0. a hyperbolic paraboloid z = x y / HYPAR_SCALE over [-1500, 1500] x [-1000, 1000] mm as
     `Brep.CreateFromMesh` of a 3 x 2 quad mesh with its vertices on it: six bilinear faces
     (exactly pieces of the same surface) sharing whole sides; the mesh quads start at
     different corners and every other one runs the other way round, so that the faces'
     parameters come in various orientations (rhino3dm cannot join surfaces into a Brep, and
     its other multi-face Breps are closed or trimmed);
  1. a box (six untrimmed planar faces: a polysurface file tpi refuses, not a rectangle);
  2. a capped cylinder (trimmed caps: no polysurface file);
  3. an extrusion of the open polyline STRIP_PROFILE by STRIP_HEIGHT, uncapped: three planar
     wall faces (`Extrusion.ToBrep(True)` splits the kinks), a strip of faces.
"""

import argparse
import importlib.util
import json
import os
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

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")

# The hyperbolic paraboloid of the polysurface model: z = x y / HYPAR_SCALE over
# [-HYPAR_X, HYPAR_X] x [-HYPAR_Y, HYPAR_Y], HYPAR_QUADS quads (in x, in y).
HYPAR_SCALE = 2000.0
HYPAR_X, HYPAR_Y = 1500.0, 1000.0
HYPAR_QUADS = (3, 2)

# The extruded strip of the polysurface model: an open polyline in z = 0, extruded along z.
STRIP_PROFILE = [(0.0, 0.0), (1000.0, 0.0), (1500.0, 800.0), (1500.0, 2000.0)]
STRIP_HEIGHT = 500.0


def hypar_brep():
    """Bilinear faces of z = x y / HYPAR_SCALE (see the module doc)."""
    n, m = HYPAR_QUADS
    mesh = rhino3dm.Mesh()
    for i in range(n + 1):
        for j in range(m + 1):
            x, y = -HYPAR_X + 2 * HYPAR_X * i / n, -HYPAR_Y + 2 * HYPAR_Y * j / m
            mesh.Vertices.Add(x, y, x * y / HYPAR_SCALE)
    for k in range(n * m):
        i, j = divmod(k, m)
        a = i * (m + 1) + j
        quad = [a, a + m + 1, a + m + 2, a + 1]
        quad = quad[k % 4 :] + quad[: k % 4]
        if k % 2:
            quad.reverse()
        mesh.Faces.AddFace(*quad)
    brep = rhino3dm.Brep.CreateFromMesh(mesh, True)
    if brep is None or len(brep.Faces) != n * m:
        raise SystemExit("rhino3dm made no Brep of {} faces from the mesh".format(n * m))
    return brep


def polysurface_model():
    model = rhino3dm.File3dm()
    model.Settings.ModelUnitSystem = rhino3dm.UnitSystem.Millimeters
    model.Objects.AddBrep(hypar_brep())
    box = rhino3dm.Box(rhino3dm.BoundingBox(0, 6000, 0, 1000, 8000, 1500))
    model.Objects.AddBrep(rhino3dm.Brep.CreateFromBox(box))
    cylinder = rhino3dm.Cylinder(rhino3dm.Circle(rhino3dm.Point3d(6000, 6000, 0), 500.0), 2000.0)
    model.Objects.AddExtrusion(rhino3dm.Extrusion.CreateCylinderExtrusion(cylinder, True, True))
    profile = rhino3dm.Polyline(len(STRIP_PROFILE))
    for x, y in STRIP_PROFILE:
        profile.Add(x, y, 0.0)
    model.Objects.AddExtrusion(rhino3dm.Extrusion.Create(profile.ToNurbsCurve(), STRIP_HEIGHT, False))
    return model


def load(name, path):
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", required=True)
    parser.add_argument("--seed", type=int, default=16)
    parser.add_argument("--samples", type=int, default=40)
    args = parser.parse_args()

    example = load("make_example_3dm", os.path.join(ROOT, "samples", "make_example_3dm.py"))
    converter = load("three_dm_to_tpi", os.path.join(ROOT, "tools", "3dm_to_tpi.py"))
    os.makedirs(args.out, exist_ok=True)
    model_path = os.path.join(args.out, "model.3dm")
    if not example.build().Write(model_path, 8):
        raise SystemExit("cannot write " + model_path)
    plain, plain_index = converter.convert(model_path, os.path.join(args.out, "plain"), with_trims=False)
    trims, trims_index = converter.convert(model_path, os.path.join(args.out, "trims"))

    model = rhino3dm.File3dm.Read(model_path)
    objects = list(model.Objects)
    rng = random.Random(args.seed)
    faces = []
    for face in plain["faces"]:
        geometry = objects[face["object"]].Geometry
        if isinstance(geometry, rhino3dm.Extrusion):
            geometry = geometry.ToBrep(True)
        (u0, u1), (v0, v1) = face["domain_u"], face["domain_v"]
        samples = []
        for k in range(args.samples):
            u = u0 if k == 0 else u1 if k == 1 else rng.uniform(u0, u1)
            v = v0 if k == 0 else v1 if k == 1 else rng.uniform(v0, v1)
            if isinstance(geometry, rhino3dm.Brep):
                brep_face = geometry.Faces[face["face"]]
                ok, s, t = brep_face.UnderlyingSurface().GetSurfaceParameterFromNurbsFormParameter(u, v)
                if not ok:
                    raise SystemExit("no surface parameter for {} at {}, {}".format(face["file"], u, v))
                p = brep_face.PointAt(s, t)
            else:
                p = geometry.PointAt(u, v)
            samples.append({"u": u, "v": v, "point": [p.X, p.Y, p.Z]})
        faces.append({"file": face["file"], "samples": samples})

    # Units: one small model per unit system, converted; what the surface file says.
    unit_cases = []
    for name in ("Inches", "Meters", "Microns", "Yards", "None", "Parsecs"):
        small = rhino3dm.File3dm()
        small.Settings.ModelUnitSystem = getattr(rhino3dm.UnitSystem, name)
        small.Objects.AddSurface(example.nurbs_surface((2, 2), (3, 3), False, lambda s, t: s * t))
        path = os.path.join(args.out, "units-{}.3dm".format(name))
        if not small.Write(path, 8):
            raise SystemExit("cannot write " + path)
        doc, _ = converter.convert(path, os.path.join(args.out, "units-" + name))
        unit_cases.append(
            {
                "rhino": name,
                "index_units": doc["units"],
                "file": os.path.join("units-" + name, doc["faces"][0]["file"]),
            }
        )

    poly_path = os.path.join(args.out, "polysurfaces.3dm")
    if not polysurface_model().Write(poly_path, 8):
        raise SystemExit("cannot write " + poly_path)
    _, poly_index = converter.convert(poly_path, os.path.join(args.out, "poly"))
    _, poly_off_index = converter.convert(poly_path, os.path.join(args.out, "poly-off"), polysurfaces=False)

    document = {
        "poly_index": os.path.relpath(poly_index, args.out),
        "poly_off_index": os.path.relpath(poly_off_index, args.out),
        "hypar": {"scale": HYPAR_SCALE, "x": HYPAR_X, "y": HYPAR_Y, "quads": list(HYPAR_QUADS)},
        "strip": {"profile": [list(p) for p in STRIP_PROFILE], "height": STRIP_HEIGHT},
        "unit_cases": unit_cases,
        "rhino3dm": rhino3dm.__version__,
        "plain_index": os.path.relpath(plain_index, args.out),
        "trims_index": os.path.relpath(trims_index, args.out),
        "faces": faces,
    }
    with open(os.path.join(args.out, "expected.json"), "w") as out:
        json.dump(document, out)


if __name__ == "__main__":
    main()
