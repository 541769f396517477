// Checked against: RhinoCommon 8 (rhino-stubs-typed 8.20.25157) — uses no RhinoCommon member.
// Rhino identifies a plug-in by its assembly Guid: never change it.
using System.Runtime.InteropServices;

[assembly: Guid("E2B7D4A0-5F1C-4C3E-8D69-7A0B1C2D3E4F")]
[assembly: ComVisible(false)]
