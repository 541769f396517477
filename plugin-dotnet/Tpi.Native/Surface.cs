using System;
using System.Collections.Generic;
using Tpi.Native.Interop;

namespace Tpi.Native
{
    /// <summary>
    /// A surface (TpiSurface): NURBS as RhinoCommon hands it over, or one of the analytic
    /// test surfaces. Immutable; may be used from several threads. Dispose it when done (the
    /// finalizer frees it otherwise).
    /// </summary>
    public sealed class Surface : IDisposable
    {
        internal readonly SurfaceHandle Handle;
        static readonly SurfaceHandle NullHandle = new SurfaceHandle();

        Surface(SurfaceHandle handle) { Handle = handle; }

        internal static SurfaceHandle HandleOf(Surface surface)
        {
            // A null Surface reaches the library as NULL, which reports it with its own message.
            return surface == null ? NullHandle : surface.Handle;
        }

        static Surface Created(Status status, SurfaceHandle handle, string function)
        {
            if (status != Status.Ok)
            {
                var error = new TpiException(status, TpiLibrary.LastErrorMessage(), function);
                if (handle != null) handle.Dispose();
                throw error;
            }
            handle.Track();
            return new Surface(handle);
        }

        /// <summary>
        /// A NURBS surface from the arrays RhinoCommon gives: knots in Rhino's convention
        /// (count + degree - 1 per direction, <c>NurbsSurface.KnotsU</c>), Euclidean control
        /// points u-major (point (i, j) at <c>3 * (i * countV + j)</c>, i.e.
        /// <c>Points.GetControlPoint(i, j).Location</c>), weights in the same order or null for a
        /// non-rational surface. All validation is the library's: a mistake raises a
        /// <see cref="TpiException"/> whose message names the argument.
        /// </summary>
        public static Surface FromNurbs(int degreeU, int degreeV, int countU, int countV,
            IList<double> knotsU, IList<double> knotsV, IList<double> points, IList<double> weights = null)
        {
            var ku = TpiLibrary.ArrayOrNull(knotsU);
            var kv = TpiLibrary.ArrayOrNull(knotsV);
            var p = TpiLibrary.ArrayOrNull(points);
            var w = TpiLibrary.ArrayOrNull(weights);
            SurfaceHandle handle;
            var status = UnsafeNativeMethods.tpi_surface_new_nurbs(TpiLibrary.Size(degreeU), TpiLibrary.Size(degreeV),
                TpiLibrary.Size(countU), TpiLibrary.Size(countV), ku, TpiLibrary.Length(ku), kv, TpiLibrary.Length(kv),
                p, TpiLibrary.Length(p), w, TpiLibrary.Length(w), out handle);
            return Created(status, handle, "tpi_surface_new_nurbs");
        }

        /// <summary>z = a x^2 + b y^2 over [x0, x1] x [y0, y1].</summary>
        public static Surface EllipticParaboloid(double a, double b, double x0, double x1, double y0, double y1)
        {
            SurfaceHandle h;
            var s = UnsafeNativeMethods.tpi_surface_new_elliptic_paraboloid(a, b, x0, x1, y0, y1, out h);
            return Created(s, h, "tpi_surface_new_elliptic_paraboloid");
        }

        /// <summary>z = a x^2 - b y^2 over [x0, x1] x [y0, y1].</summary>
        public static Surface HyperbolicParaboloid(double a, double b, double x0, double x1, double y0, double y1)
        {
            SurfaceHandle h;
            var s = UnsafeNativeMethods.tpi_surface_new_hyperbolic_paraboloid(a, b, x0, x1, y0, y1, out h);
            return Created(s, h, "tpi_surface_new_hyperbolic_paraboloid");
        }

        /// <summary>z = sqrt(r^2 - x^2 - y^2) over [x0, x1] x [y0, y1].</summary>
        public static Surface SphereCap(double radius, double x0, double x1, double y0, double y1)
        {
            SurfaceHandle h;
            var s = UnsafeNativeMethods.tpi_surface_new_sphere_cap(radius, x0, x1, y0, y1, out h);
            return Created(s, h, "tpi_surface_new_sphere_cap");
        }

        /// <summary>The sphere cap over [-h, h]^2.</summary>
        public static Surface SphereCapSquare(double radius, double halfWidth)
        {
            SurfaceHandle h;
            var s = UnsafeNativeMethods.tpi_surface_new_sphere_cap_square(radius, halfWidth, out h);
            return Created(s, h, "tpi_surface_new_sphere_cap_square");
        }

        /// <summary>z = c sqrt(1 - x^2/a^2 - y^2/b^2) over [x0, x1] x [y0, y1].</summary>
        public static Surface EllipsoidCap(double a, double b, double c, double x0, double x1, double y0, double y1)
        {
            SurfaceHandle h;
            var s = UnsafeNativeMethods.tpi_surface_new_ellipsoid_cap(a, b, c, x0, x1, y0, y1, out h);
            return Created(s, h, "tpi_surface_new_ellipsoid_cap");
        }

        /// <summary>z = A sin(x) sin(y) over [x0, x1] x [y0, y1].</summary>
        public static Surface EggCrate(double amplitude, double x0, double x1, double y0, double y1)
        {
            SurfaceHandle h;
            var s = UnsafeNativeMethods.tpi_surface_new_egg_crate(amplitude, x0, x1, y0, y1, out h);
            return Created(s, h, "tpi_surface_new_egg_crate");
        }

        /// <summary>z = sqrt(r^2 - x^2) (developable: facets on one ruling are separated by the bisectors of their seeds).</summary>
        public static Surface Cylinder(double radius, double x0, double x1, double y0, double y1)
        {
            SurfaceHandle h;
            var s = UnsafeNativeMethods.tpi_surface_new_cylinder(radius, x0, x1, y0, y1, out h);
            return Created(s, h, "tpi_surface_new_cylinder");
        }

        /// <summary>z = p x + q y + c0 (flat: the facets are the Voronoi cells of their seeds).</summary>
        public static Surface Plane(double p, double q, double c0, double x0, double x1, double y0, double y1)
        {
            SurfaceHandle h;
            var s = UnsafeNativeMethods.tpi_surface_new_plane(p, q, c0, x0, x1, y0, y1, out h);
            return Created(s, h, "tpi_surface_new_plane");
        }

        /// <summary>
        /// A copy of this surface with the model's length units: a value of Rhino's
        /// <c>UnitSystem</c> (<c>(int)doc.ModelUnitSystem</c>; 0 = none, 2 = millimetres, 4 =
        /// metres, 8 = inches, 9 = feet, ...: the <c>TPI_UNITS_*</c> of include/tpi.h). Nothing is
        /// rescaled: the units go to the outputs (the result JSON, the fabrication's DXF). An
        /// unsupported unit system raises a <see cref="TpiException"/> listing the supported ones.
        /// </summary>
        public Surface WithUnits(int rhinoUnitSystem)
        {
            SurfaceHandle h;
            var s = UnsafeNativeMethods.tpi_surface_with_units(Handle, rhinoUnitSystem, out h);
            return Created(s, h, "tpi_surface_with_units");
        }

        /// <summary>
        /// A copy of this surface trimmed to closed polylines in its own (u, v) parameters (not
        /// normalised), flat u, v per point: the outer loop counter-clockwise, the holes (may be
        /// null) clockwise. The closing segment is implied. Discretising it leaves the pattern
        /// points outside the trim out; a discrete surface (live editing) refuses it. Every
        /// mistake (a clockwise outer loop, a point outside the domain, crossing loops, an odd
        /// count) raises a <see cref="TpiException"/> naming the loop and point.
        /// </summary>
        public Surface WithTrim(IList<double> outerUv, IList<IList<double>> holesUv = null)
        {
            var outer = TpiLibrary.ArrayOrNull(outerUv);
            var flat = new List<double>();
            var counts = new UIntPtr[holesUv == null ? 0 : holesUv.Count];
            for (int k = 0; k < counts.Length; k++)
            {
                var hole = holesUv[k] ?? new double[0];
                // An odd hole is passed whole: the library reports the odd total or the counts.
                counts[k] = new UIntPtr((ulong)(hole.Count / 2));
                flat.AddRange(hole);
            }
            var holes = flat.ToArray();
            SurfaceHandle h;
            var s = UnsafeNativeMethods.tpi_surface_with_trim(Handle, outer, TpiLibrary.Length(outer),
                holes, TpiLibrary.Length(holes), counts, TpiLibrary.Length(counts), out h);
            return Created(s, h, "tpi_surface_with_trim");
        }

        /// <summary>
        /// A polysurface: <paramref name="faces"/> (untrimmed four-sided faces that share whole
        /// sides, in any order and orientation, e.g. the faces of a Brep) joined into one surface
        /// whose tangent planes are the faces' own. The faces are borrowed: the polysurface holds
        /// its own copies, dispose the faces as usual. Its domain is [0, W] x [0, H] (sums of the
        /// faces' mid-line lengths), so a normalised pattern spreads over the faces by length.
        /// Faces that cannot be joined (trimmed, apart, not a rectangle of rows and columns, units
        /// that differ) raise a <see cref="TpiException"/> naming the face (<c>faces[1]: ...</c>);
        /// a null list or a null element raise it too, naming the argument; a disposed face raises
        /// <see cref="ObjectDisposedException"/>.
        /// </summary>
        public static Surface Join(IReadOnlyList<Surface> faces)
        {
            int count = faces == null ? 0 : faces.Count;
            var raw = faces == null ? null : new IntPtr[count];
            var added = new List<SurfaceHandle>(count);
            try
            {
                for (int k = 0; k < count; k++)
                {
                    var face = faces[k];
                    if (face == null) continue; // NULL: the library names faces[k]
                    // Throws ObjectDisposedException for a disposed face, as every other call.
                    bool ok = false;
                    face.Handle.DangerousAddRef(ref ok);
                    if (ok) { added.Add(face.Handle); raw[k] = face.Handle.DangerousGetHandle(); }
                }
                SurfaceHandle h;
                // A null list with count 0 reaches the library as NULL, 0: "faces: ... found 0".
                var s = UnsafeNativeMethods.tpi_surface_new_polysurface(raw, TpiLibrary.Size(count), out h);
                return Created(s, h, "tpi_surface_new_polysurface");
            }
            finally
            {
                foreach (var handle in added) handle.DangerousRelease();
            }
        }

        /// <summary>The model's length units as Rhino's <c>UnitSystem</c> value, 0 when unitless.</summary>
        public int Units
        {
            get
            {
                int units;
                TpiLibrary.Check(UnsafeNativeMethods.tpi_surface_units(Handle, out units), "tpi_surface_units");
                return units;
            }
        }

        /// <summary>The parameter domain.</summary>
        public Domain Domain
        {
            get
            {
                Domain d;
                TpiLibrary.Check(UnsafeNativeMethods.tpi_surface_domain(Handle, out d), "tpi_surface_domain");
                return d;
            }
        }

        /// <summary>Point, normal and curvatures at (u, v) in the surface's own domain.</summary>
        public Sample Evaluate(double u, double v)
        {
            return Evaluate(new[] { u, v })[0];
        }

        /// <summary>Samples at (u0, v0, u1, v1, ...) in the surface's own domain.</summary>
        public Sample[] Evaluate(double[] uv)
        {
            int count = uv == null ? 0 : uv.Length / 2;
            var samples = new Sample[count];
            TpiLibrary.Check(UnsafeNativeMethods.tpi_surface_evaluate(Handle, uv, TpiLibrary.Length(uv), samples,
                TpiLibrary.Size(count)), "tpi_surface_evaluate");
            return samples;
        }

        /// <summary>True once disposed.</summary>
        public bool IsDisposed { get { return Handle.IsClosed; } }

        /// <summary>Frees the native surface.</summary>
        public void Dispose() { Handle.Dispose(); }
    }
}
