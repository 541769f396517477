// A polysurface as plain data: the faces of a Brep (each as its untrimmed surface spec), joined
// by the library into one surface (tpi_surface_new_polysurface) whose rows and columns it finds
// from the geometry. FromFaces is the Rhino-free decision the Rhino command, the Grasshopper
// component and the source watcher share: one face stays that face (with its trim); several
// faces become a polysurface, unless a face is trimmed, which polysurfaces do not support yet.
using System;
using System.Collections.Generic;
using System.Linq;
using Tpi.Native;

namespace Tpi.Logic
{
    /// <summary>Several faces sharing whole sides, discretised as one surface.</summary>
    public sealed class PolysurfaceSpec : SurfaceSpec
    {
        readonly SurfaceSpec[] _faces;

        /// <summary>The faces, copied. Nothing is validated here: the library lays them out (or says why not) when the surface is made.</summary>
        public PolysurfaceSpec(IEnumerable<SurfaceSpec> faces)
        {
            if (faces == null) throw new ArgumentNullException("faces");
            _faces = faces.ToArray();
            if (_faces.Any(f => f == null)) throw new ArgumentException("a face is null", "faces");
            if (_faces.Any(f => f is PolysurfaceSpec)) throw new ArgumentException("a face is itself a polysurface; list its faces", "faces");
        }

        /// <summary>The faces in the order given (Rhino's face order for a Brep).</summary>
        public IReadOnlyList<SurfaceSpec> Faces { get { return Array.AsReadOnly(_faces); } }

        /// <summary>
        /// The surface of a Brep's faces: null (with <paramref name="error"/>) for no faces, or
        /// when several faces are given and one of them is trimmed beyond its natural boundary
        /// (its spec has a <see cref="SurfaceSpec.Trim"/>); the face itself (trim and all) for
        /// one face; a <see cref="PolysurfaceSpec"/> otherwise. The message names the face by
        /// its index, as Rhino numbers a Brep's faces.
        /// </summary>
        public static SurfaceSpec FromFaces(IList<SurfaceSpec> faces, out string error)
        {
            error = null;
            if (faces == null || faces.Count == 0) { error = "the Brep has no faces"; return null; }
            for (int k = 0; k < faces.Count; k++)
                if (faces[k] == null) { error = "face " + k + " of the Brep has no NURBS form"; return null; }
            if (faces.Count == 1) return faces[0];
            var trimmed = Enumerable.Range(0, faces.Count).Where(k => faces[k].Trim != null).ToList();
            if (trimmed.Count > 0)
            {
                error = "face" + (trimmed.Count == 1 ? " " : "s ") + string.Join(", ", trimmed) + " of the " + faces.Count +
                    "-face polysurface " + (trimmed.Count == 1 ? "is" : "are") + " trimmed: trimmed faces are not supported " +
                    "in a polysurface yet (the faces must be whole four-sided surfaces sharing whole sides). Shrink or untrim " +
                    "the face (ShrinkTrimmedSrf, Untrim), or discretise a face on its own (pick it with Ctrl+Shift).";
                return null;
            }
            return new PolysurfaceSpec(faces);
        }

        /// <inheritdoc/>
        protected override Surface CreateUntrimmed()
        {
            var natives = new List<Surface>(_faces.Length);
            try
            {
                foreach (var face in _faces) natives.Add(face.CreateNative());
                return Surface.Join(natives);
            }
            finally
            {
                foreach (var n in natives) n.Dispose();
            }
        }

        /// <summary>Every face moved by <paramref name="m"/> (an analytic face cannot be: NotSupportedException).</summary>
        public override SurfaceSpec Transformed(double[] m)
        {
            return new PolysurfaceSpec(_faces.Select(f => f.Transformed(m))).WithTrim(Trim);
        }

        /// <inheritdoc/>
        public override bool Equals(SurfaceSpec other)
        {
            var o = other as PolysurfaceSpec;
            return o != null && o._faces.Length == _faces.Length
                && _faces.Zip(o._faces, (a, b) => a.Equals(b)).All(x => x) && SameTrim(o);
        }

        /// <inheritdoc/>
        public override int GetHashCode() { return 97 * _faces.Length + (_faces.Length > 0 ? _faces[0].GetHashCode() : 0); }
    }
}
