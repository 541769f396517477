"""Reads a DXF file with ezdxf (an independent reader) and prints what the fabrication test
checks, as JSON on stdout: the version, $INSUNITS, the layers, the audit's error count and
every LWPOLYLINE / POLYLINE of modelspace (layer, closed, points x y).

Usage: python3 read_dxf.py FILE.dxf   (needs `python3 -m pip install 'ezdxf==1.4.*'`)
"""
import json
import sys

import ezdxf


def main() -> None:
    doc = ezdxf.readfile(sys.argv[1])
    auditor = doc.audit()
    polylines = []
    for e in doc.modelspace():
        kind = e.dxftype()
        if kind == "LWPOLYLINE":
            points = [[p[0], p[1]] for p in e.get_points("xy")]
            polylines.append({"layer": e.dxf.layer, "closed": bool(e.closed), "points": points})
        elif kind == "POLYLINE":
            points = [[v.dxf.location.x, v.dxf.location.y] for v in e.vertices]
            polylines.append({"layer": e.dxf.layer, "closed": bool(e.is_closed), "points": points})
    print(json.dumps({
        "version": doc.dxfversion,
        "insunits": doc.header.get("$INSUNITS"),
        "layers": sorted(layer.dxf.name for layer in doc.layers),
        "audit_errors": len(auditor.errors),
        "polylines": polylines,
    }))


if __name__ == "__main__":
    main()
