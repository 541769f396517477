//! The files: panels.json, panels.obj, bevels.csv, sheets.svg, sheets.dxf.
