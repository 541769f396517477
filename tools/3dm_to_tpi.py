#!/usr/bin/env python3
"""Converts a Rhino .3dm file to tpi surface files, without Rhino (rhino3dm from PyPI).

Usage: 3dm_to_tpi.py MODEL.3dm --out DIR [--no-trims] [--no-polysurfaces] [--samples N]

Writes, into DIR:
  - one NURBS surface file per Brep face (Breps, polysurfaces, extrusions) and per bare surface
    (NURBS, plane, revolution, sum surfaces): STEM_oOBJECT_fFACE.json, the face's underlying
    surface in its NURBS form (`UnderlyingSurface().ToNurbsSurface()`), Rhino's knot convention,
    Euclidean control points (rhino3dm's Point4d divided by W), `weights` only when rational,
    and `units` from the file's `ModelUnitSystem` (omitted when Rhino says None: unitless);
  - STEM_index.json: one record per face (its file, the source object and face, degrees,
    closedness, periodicity, singular sides = poles, whether it is trimmed, its trim polylines,
    units, orientation) and the polysurface adjacency: for every Brep edge, the faces and trims
    that use it and the edge's 3D end points; an edge shared by two faces is listed under
    `shared_edges`, an edge used twice by one face is a seam; and one record per Brep of two or
    more faces under `polysurfaces` (below);
  - STEM_oOBJECT_polysurface.json, for every Brep of two or more faces whose faces are all
    untrimmed (each face's one loop runs along its domain's boundary) and all written:
    `{"type": "polysurface", "faces": [...], "units": ...}`, the faces' records as in their own
    files, in the Brep's face order. tpi lays such faces out as rows and columns when they share
    whole sides (docs/formats.md) and says which face does not fit otherwise. A Brep with a
    trimmed face gets no polysurface file (the format has no trims on polysurface faces yet):
    its index record says why and names the trimmed faces. `--no-polysurfaces` writes none
    (the index records remain, `file` null).

Trims. rhino3dm 8 exposes a face's loops (`BrepFace.Loops`, `BrepLoop.Trims`, each trim with
`EdgeIndex` and `IsReversed`) but not the trims' 2D parameter-space curves (no
`BrepTrim.To2dCurve`, no `Surface.ClosestPoint`). The trims are therefore rebuilt here: each
trim's 3D edge curve is sampled (reversed where the trim is) and every sample is projected onto
the face's NURBS surface (Gauss-Newton on the squared distance, finite-difference Jacobian,
continued from the previous sample; the first sample of a face is started from a grid search).
A singular trim (no edge: a pole) adds no point: the polyline runs straight along that side of
the domain, as the 2D trim does. The outer loop is made counter-clockwise, holes clockwise, in
the surface's own (u, v). A face whose one loop lies on the boundary of the domain (every sample
within 1e-9 of the domain size of a side) is untrimmed and gets no `trim`.

The surface file of each trimmed face gets `"trim": {"outer": [[u, v], ...], "holes": [[[u, v],
...], ...]}`; with `--no-trims` the polylines are in the index only (the untrimmed surfaces). `closed`, `periodic` and `poles` are always in the index only
(tpi's surface format has no such fields).

Limits: trims that cross the seam of a closed surface are projected to one side of the seam (a
warning names the face); faces of degree above 11 (never made by Rhino) are skipped with a
warning; meshes, curves and points are ignored.
"""

import argparse
import json
import math
import os
import sys

try:
    import rhino3dm
except ImportError:
    sys.stderr.write(
        "rhino3dm is not installed for this Python interpreter ({}).\n"
        "Install it with: {} -m pip install 'rhino3dm==8.*'\n".format(sys.executable, sys.executable)
    )
    sys.exit(3)

MAX_DEGREE = 11

# Rhino's UnitSystem names -> tpi's short names (docs/formats.md); others are unitless for tpi.
UNITS = {
    "Microns": "um",
    "Millimeters": "mm",
    "Centimeters": "cm",
    "Meters": "m",
    "Kilometers": "km",
    "Inches": "in",
    "Feet": "ft",
    "Yards": "yd",
    "Miles": "mi",
}

# IsSingular(side): 0 south (v min), 1 east (u max), 2 north (v max), 3 west (u min).
SIDES = ["south (v min)", "east (u max)", "north (v max)", "west (u min)"]


def warn(message):
    sys.stderr.write("3dm_to_tpi: " + message + "\n")


def nurbs_record(surface):
    """The NURBS surface file record of a rhino3dm NurbsSurface."""
    count_u, count_v = surface.Points.CountU, surface.Points.CountV
    record = {
        "type": "nurbs",
        "degree": [surface.Degree(0), surface.Degree(1)],
        "count": [count_u, count_v],
        "knots_u": [surface.KnotsU[k] for k in range(len(surface.KnotsU))],
        "knots_v": [surface.KnotsV[k] for k in range(len(surface.KnotsV))],
        "points": [],
    }
    weights = []
    for i in range(count_u):
        for j in range(count_v):
            # Points[i, j] is homogeneous (x w, y w, z w, w); GetPoint is Euclidean.
            p = surface.Points.GetPoint(i, j)
            record["points"].append([p.X, p.Y, p.Z])
            weights.append(surface.Points.GetControlPoint(i, j).W)
    if surface.IsRational:
        record["weights"] = weights
    return record


class Projector:
    """Closest points on a rhino3dm NurbsSurface, by Gauss-Newton from a start."""

    def __init__(self, surface):
        self.s = surface
        self.du = (surface.Domain(0).T0, surface.Domain(0).T1)
        self.dv = (surface.Domain(1).T0, surface.Domain(1).T1)
        self.closed = [surface.IsClosed(0), surface.IsClosed(1)]

    def point(self, u, v):
        p = self.s.PointAt(u, v)
        return (p.X, p.Y, p.Z)

    def clamp(self, u, v):
        return (min(max(u, self.du[0]), self.du[1]), min(max(v, self.dv[0]), self.dv[1]))

    def grid_start(self, target, n=24):
        best = None
        for a in range(n + 1):
            for b in range(n + 1):
                u = self.du[0] + (self.du[1] - self.du[0]) * a / n
                v = self.dv[0] + (self.dv[1] - self.dv[0]) * b / n
                d = dist2(self.point(u, v), target)
                if best is None or d < best[0]:
                    best = (d, u, v)
        return best[1], best[2]

    def project(self, target, start):
        u, v = start
        hu = 1e-6 * (self.du[1] - self.du[0])
        hv = 1e-6 * (self.dv[1] - self.dv[0])
        for _ in range(60):
            p = self.point(u, v)
            r = [p[k] - target[k] for k in range(3)]
            u0, u1 = max(u - hu, self.du[0]), min(u + hu, self.du[1])
            v0, v1 = max(v - hv, self.dv[0]), min(v + hv, self.dv[1])
            pu0, pu1 = self.point(u0, v), self.point(u1, v)
            pv0, pv1 = self.point(u, v0), self.point(u, v1)
            su = [(pu1[k] - pu0[k]) / (u1 - u0) for k in range(3)]
            sv = [(pv1[k] - pv0[k]) / (v1 - v0) for k in range(3)]
            a, b, c = dot(su, su), dot(su, sv), dot(sv, sv)
            g1, g2 = dot(su, r), dot(sv, r)
            det = a * c - b * b
            if det <= 1e-300 * max(a * c, 1e-300):
                # Degenerate (a pole): move along the non-degenerate direction only.
                step_u = -g1 / a if a > 0 else 0.0
                step_v = -g2 / c if c > 0 else 0.0
            else:
                step_u = -(c * g1 - b * g2) / det
                step_v = -(a * g2 - b * g1) / det
            nu, nv = self.clamp(u + step_u, v + step_v)
            moved = abs(nu - u) / (self.du[1] - self.du[0]) + abs(nv - v) / (self.dv[1] - self.dv[0])
            u, v = nu, nv
            if moved < 1e-14:
                break
        return u, v


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def dist2(a, b):
    return sum((a[k] - b[k]) ** 2 for k in range(3))


def signed_area(poly):
    return 0.5 * sum(
        poly[k][0] * poly[(k + 1) % len(poly)][1] - poly[(k + 1) % len(poly)][0] * poly[k][1]
        for k in range(len(poly))
    )


def edge_samples(edge, reversed_, samples):
    """Points along a Brep edge, in the trim's direction."""
    t0, t1 = edge.Domain.T0, edge.Domain.T1
    n = 1 if edge.IsLinear(1e-12) else max(samples, 4 * edge.SpanCount * max(edge.Degree, 1))
    ts = [t0 + (t1 - t0) * k / n for k in range(n + 1)]
    if reversed_:
        ts.reverse()
    return [(lambda p: (p.X, p.Y, p.Z))(edge.PointAt(t)) for t in ts]


def face_loops(brep, face, projector, samples, label):
    """Per loop: (kind, polyline in (u, v)), and whether any sample went off the surface."""
    loops = []
    previous = None
    # Points closer than this (per direction, 1e-9 of the domain) are one point: edges that
    # meet at a vertex project to the same (u, v) up to rounding.
    (u0, u1), (v0, v1) = projector.du, projector.dv
    tol = (1e-9 * (u1 - u0), 1e-9 * (v1 - v0))

    def same(a, b):
        return abs(a[0] - b[0]) <= tol[0] and abs(a[1] - b[1]) <= tol[1]

    for loop in face.Loops:
        poly = []
        for k in range(loop.TrimCount):
            trim = loop.Trims[k]
            if trim.EdgeIndex < 0:
                continue  # singular trim (pole): the polyline runs along that side
            for p in edge_samples(brep.Edges[trim.EdgeIndex], trim.IsReversed, samples):
                if previous is None:
                    previous = projector.grid_start(p)
                uv = projector.project(p, previous)
                # The first sample of a loop is also tried from a grid search (a loop's
                # previous point says nothing about where it starts).
                if not poly:
                    alt = projector.project(p, projector.grid_start(p))
                    if dist2(projector.point(*alt), p) < dist2(projector.point(*uv), p) - 1e-24:
                        uv = alt
                off = math.sqrt(dist2(projector.point(*uv), p))
                if off > 1e-6 * max(1.0, math.sqrt(dot(p, p))):
                    warn("{}: an edge point is {:.3g} from the surface".format(label, off))
                previous = uv
                if not poly or not same(poly[-1], uv):
                    poly.append([uv[0], uv[1]])
        if len(poly) > 1 and same(poly[0], poly[-1]):
            poly.pop()
        loops.append((str(loop.LoopType).split(".")[-1], poly))
    return loops


def on_boundary(poly, projector):
    (u0, u1), (v0, v1) = projector.du, projector.dv
    tu, tv = 1e-9 * (u1 - u0), 1e-9 * (v1 - v0)
    return all(
        abs(u - u0) <= tu or abs(u - u1) <= tu or abs(v - v0) <= tv or abs(v - v1) <= tv for u, v in poly
    )


def trim_record(loops, projector):
    """The `trim` field, or None for an untrimmed face (its one loop is the domain boundary)."""
    if len(loops) == 1 and on_boundary(loops[0][1], projector):
        return None
    outer, holes = None, []
    for kind, poly in loops:
        if len(poly) < 3:
            continue
        area = signed_area(poly)
        if kind == "Outer" and outer is None:
            outer = poly if area > 0 else poly[::-1]
        else:
            holes.append(poly if area < 0 else poly[::-1])
    if outer is None:
        return None
    return {"outer": outer, "holes": holes}


def surfaces_of(geometry):
    """(brep or None, list of (face index, face or surface)) for one object's geometry."""
    if isinstance(geometry, rhino3dm.Extrusion):
        geometry = geometry.ToBrep(True)
    if isinstance(geometry, rhino3dm.Brep):
        return geometry, [(k, geometry.Faces[k]) for k in range(len(geometry.Faces))]
    if isinstance(geometry, rhino3dm.Surface):
        return None, [(0, geometry)]
    return None, []


def polysurface_entry(index, obj, brep, written, faces, shared_edges):
    """The index record of one Brep of two or more faces (see the module doc).

    `written`: (face index in the Brep, index into `faces`) of the faces that have a surface
    file. The faces of the polysurface are listed in the Brep's order; `adjacency` gives, per
    edge shared by two of its faces, their positions in that list."""
    position = {global_index: k for k, (_, global_index) in enumerate(written)}
    adjacency = []
    for entry in shared_edges:
        users = sorted({u["face"] for u in entry["uses"]})
        if all(u in position for u in users):
            adjacency.append(
                {"edge": entry["edge"], "faces": [position[u] for u in users], "start": entry["start"], "end": entry["end"]}
            )
    missing = sorted(set(range(len(brep.Faces))) - {face for face, _ in written})
    trimmed = [faces[g]["file"] for _, g in written if faces[g]["trimmed"]]
    reasons = []
    if missing:
        reasons.append("faces {} have no surface file (see the warnings)".format(missing))
    if trimmed:
        reasons.append(
            "trimmed faces ({}): a polysurface's faces cannot carry trims yet".format(", ".join(trimmed))
        )
    return {
        "object": index,
        "object_id": str(obj.Attributes.Id),
        "object_name": obj.Attributes.Name or "",
        "file": None,
        "faces": [g for _, g in written],
        "face_files": [faces[g]["file"] for _, g in written],
        "adjacency": adjacency,
        "not_written": "; ".join(reasons) or None,
    }


def convert(path, out_dir, with_trims=True, samples=16, polysurfaces=True):
    model = rhino3dm.File3dm.Read(path)
    if model is None:
        raise SystemExit("3dm_to_tpi: cannot read {}".format(path))
    rhino_units = model.Settings.ModelUnitSystem.name
    units = UNITS.get(rhino_units)
    if units is None:
        warn("model units {}: not one tpi knows, the surfaces are written unitless".format(rhino_units))
    stem = os.path.splitext(os.path.basename(path))[0]
    os.makedirs(out_dir, exist_ok=True)
    faces, shared, seams, polys = [], [], [], []
    for index, obj in enumerate(model.Objects):
        brep, items = surfaces_of(obj.Geometry)
        edge_users = {}
        # (face index in the Brep, index into `faces`, the record written) per written face.
        written = []
        for face_index, face in items:
            label = "object {} face {}".format(index, face_index)
            if brep is not None:
                surface = face.UnderlyingSurface().ToNurbsSurface()
            else:
                surface = face.ToNurbsSurface()
            if surface is None:
                warn("{}: no NURBS form, skipped".format(label))
                continue
            if max(surface.Degree(0), surface.Degree(1)) > MAX_DEGREE:
                warn("{}: degree above {}, skipped".format(label, MAX_DEGREE))
                continue
            record = nurbs_record(surface)
            if units:
                record["units"] = units
            projector = Projector(surface)
            trim = None
            if brep is not None:
                loops = face_loops(brep, face, projector, samples, label)
                trim = trim_record(loops, projector)
                for loop_index, loop in enumerate(face.Loops):
                    for k in range(loop.TrimCount):
                        e = loop.Trims[k].EdgeIndex
                        if e >= 0:
                            edge_users.setdefault(e, []).append(
                                {"face": len(faces), "loop": loop_index, "trim": k}
                            )
                if trim is not None and any(surface.IsClosed(d) for d in (0, 1)):
                    warn("{}: trimmed face of a closed surface; trims across its seam are approximate".format(label))
            if trim is not None and with_trims:
                record["trim"] = trim
            written.append((face_index, len(faces), record))
            name = "{}_o{}_f{}.json".format(stem, index, face_index)
            with open(os.path.join(out_dir, name), "w") as out:
                json.dump(record, out)
                out.write("\n")
            faces.append(
                {
                    "file": name,
                    "object": index,
                    "object_id": str(obj.Attributes.Id),
                    "object_name": obj.Attributes.Name or "",
                    "object_type": type(obj.Geometry).__name__,
                    "face": face_index,
                    "degree": record["degree"],
                    "count": record["count"],
                    "rational": "weights" in record,
                    "domain_u": [projector.du[0], projector.du[1]],
                    "domain_v": [projector.dv[0], projector.dv[1]],
                    "closed": [surface.IsClosed(0), surface.IsClosed(1)],
                    "periodic": [surface.IsPeriodic(0), surface.IsPeriodic(1)],
                    "poles": [SIDES[side] for side in range(4) if surface.IsSingular(side)],
                    "reversed": bool(getattr(face, "OrientationIsReversed", False)),
                    "trimmed": trim is not None,
                    "trim_written": trim is not None and with_trims,
                    "trim": trim,
                    "units": units,
                    "neighbours": [],
                }
            )
        first_shared = len(shared)
        if brep is not None:
            for e, users in sorted(edge_users.items()):
                edge = brep.Edges[e]
                ends = [[q.X, q.Y, q.Z] for q in (edge.PointAtStart, edge.PointAtEnd)]
                distinct = sorted({u["face"] for u in users})
                entry = {"object": index, "edge": e, "uses": users, "start": ends[0], "end": ends[1]}
                if len(distinct) >= 2:
                    shared.append(entry)
                    for f in distinct:
                        faces[f]["neighbours"].extend(
                            {"face": g, "edge": e} for g in distinct if g != f
                        )
                elif len(users) >= 2:
                    seams.append(entry)
            if len(brep.Faces) >= 2:
                entry = polysurface_entry(
                    index, obj, brep, [(f, g) for f, g, _ in written], faces, shared[first_shared:]
                )
                if entry["not_written"] is None and not polysurfaces:
                    entry["not_written"] = "--no-polysurfaces"
                if entry["not_written"] is None:
                    name = "{}_o{}_polysurface.json".format(stem, index)
                    record = {"type": "polysurface", "faces": [r for _, _, r in written]}
                    if units:
                        record["units"] = units
                    with open(os.path.join(out_dir, name), "w") as out:
                        json.dump(record, out)
                        out.write("\n")
                    entry["file"] = name
                elif polysurfaces:
                    warn("object {}: no polysurface file: {}".format(index, entry["not_written"]))
                polys.append(entry)
    index_doc = {
        "source": os.path.basename(path),
        "generator": "tools/3dm_to_tpi.py, rhino3dm " + rhino3dm.__version__,
        "rhino_units": rhino_units,
        "units": units,
        "trims_in_surface_files": with_trims,
        "faces": faces,
        "shared_edges": shared,
        "seams": seams,
        "polysurfaces_written": polysurfaces,
        "polysurfaces": polys,
    }
    index_name = os.path.join(out_dir, stem + "_index.json")
    with open(index_name, "w") as out:
        json.dump(index_doc, out, indent=1)
        out.write("\n")
    return index_doc, index_name


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("model", help=".3dm file")
    parser.add_argument("--out", required=True, help="directory for the surface files and the index")
    parser.add_argument(
        "--no-trims",
        action="store_true",
        help="leave the `trim` field out of the surface files (the polylines stay in the index)",
    )
    parser.add_argument(
        "--no-polysurfaces",
        action="store_true",
        help="write no polysurface files (the Breps' records stay in the index)",
    )
    parser.add_argument("--samples", type=int, default=16, help="least samples per curved trim edge")
    args = parser.parse_args()
    doc, index_name = convert(args.model, args.out, not args.no_trims, args.samples, not args.no_polysurfaces)
    trimmed = sum(1 for f in doc["faces"] if f["trimmed"])
    polysurface_files = sum(1 for p in doc["polysurfaces"] if p["file"])
    sys.stderr.write(
        "3dm_to_tpi: {} faces ({} trimmed), {} shared edges, units {}; wrote {}, {} surface files "
        "and {} polysurface files (of {} Breps with several faces)\n".format(
            len(doc["faces"]),
            trimmed,
            len(doc["shared_edges"]),
            doc["units"] or "none (unitless)",
            index_name,
            len(doc["faces"]),
            polysurface_files,
            len(doc["polysurfaces"]),
        )
    )


if __name__ == "__main__":
    main()
