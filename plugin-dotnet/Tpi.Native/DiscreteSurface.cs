using System;
using System.Collections.Generic;
using Tpi.Native.Interop;

namespace Tpi.Native
{
    /// <summary>
    /// A live discrete surface (TpiDiscreteSurface): a copy of a surface, its pattern points
    /// and the mesh of the last successful recompute. Edits are pending until
    /// <see cref="Recompute"/>; a failed recompute leaves the edits pending and the previous
    /// mesh current. Calls on one object are serialised by a lock inside the library.
    /// </summary>
    public sealed class DiscreteSurface : IDisposable
    {
        internal readonly DiscreteSurfaceHandle Handle;

        DiscreteSurface(DiscreteSurfaceHandle handle) { Handle = handle; }

        /// <summary>Copies <paramref name="surface"/> and <paramref name="pattern"/> (the caller may dispose them) and computes the first mesh.</summary>
        public static DiscreteSurface Create(Surface surface, Pattern pattern, DiscretisationOptions options = null)
        {
            DiscreteSurfaceHandle h;
            Status s;
            if (options == null)
            {
                s = UnsafeNativeMethods.tpi_discrete_surface_new_defaults(Surface.HandleOf(surface), Pattern.HandleOf(pattern), IntPtr.Zero, out h);
            }
            else
            {
                var native = options.ToNative();
                s = UnsafeNativeMethods.tpi_discrete_surface_new(Surface.HandleOf(surface), Pattern.HandleOf(pattern), ref native, out h);
            }
            if (s != Status.Ok)
            {
                var error = new TpiException(s, TpiLibrary.LastErrorMessage(), "tpi_discrete_surface_new");
                if (h != null) h.Dispose();
                throw error;
            }
            h.Track();
            return new DiscreteSurface(h);
        }

        /// <summary>Current number of pattern points (edits included).</summary>
        public int PointCount
        {
            get
            {
                UIntPtr n;
                TpiLibrary.Check(UnsafeNativeMethods.tpi_discrete_surface_point_count(Handle, out n), "tpi_discrete_surface_point_count");
                return TpiLibrary.ToInt(n);
            }
        }

        /// <summary>Current pattern points s0, t0, s1, t1, ... (edits included).</summary>
        public double[] GetPointArray()
        {
            return TpiLibrary.CopyOut<double>((double[] b, UIntPtr c, out UIntPtr n) =>
                UnsafeNativeMethods.tpi_discrete_surface_points(Handle, b, c, out n), "tpi_discrete_surface_points");
        }

        /// <summary>Current pattern points (a snapshot).</summary>
        public IReadOnlyList<PatternPoint> Points { get { return Array.AsReadOnly(Pattern.ToPoints(GetPointArray())); } }

        /// <summary>Moves point <paramref name="index"/> to (s, t) (pending).</summary>
        public void MovePoint(int index, double s, double t)
        {
            TpiLibrary.Check(UnsafeNativeMethods.tpi_discrete_surface_move_point(Handle, TpiLibrary.Size(index), s, t),
                "tpi_discrete_surface_move_point");
        }

        /// <summary>Appends (s, t) (pending); returns its index.</summary>
        public int AddPoint(double s, double t)
        {
            UIntPtr index;
            TpiLibrary.Check(UnsafeNativeMethods.tpi_discrete_surface_add_point(Handle, s, t, out index), "tpi_discrete_surface_add_point");
            return TpiLibrary.ToInt(index);
        }

        /// <summary>Removes point <paramref name="index"/>; later points move down by one (pending).</summary>
        public void RemovePoint(int index)
        {
            TpiLibrary.Check(UnsafeNativeMethods.tpi_discrete_surface_remove_point(Handle, TpiLibrary.Size(index)),
                "tpi_discrete_surface_remove_point");
        }

        /// <summary>Replaces the surface with a copy of <paramref name="surface"/> (pending); pattern points keep their (s, t).</summary>
        public void ReplaceSurface(Surface surface)
        {
            TpiLibrary.Check(UnsafeNativeMethods.tpi_discrete_surface_set_surface(Handle, Surface.HandleOf(surface)),
                "tpi_discrete_surface_set_surface");
        }

        /// <summary>Edits since the last successful recompute; 0 means the mesh is up to date.</summary>
        public int PendingEdits
        {
            get
            {
                UIntPtr n;
                TpiLibrary.Check(UnsafeNativeMethods.tpi_discrete_surface_pending_edits(Handle, out n), "tpi_discrete_surface_pending_edits");
                return TpiLibrary.ToInt(n);
            }
        }

        /// <summary>Brings the mesh up to date; on failure the edits stay pending and the previous mesh stays current.</summary>
        public void Recompute()
        {
            TpiLibrary.Check(UnsafeNativeMethods.tpi_discrete_surface_recompute(Handle), "tpi_discrete_surface_recompute");
        }

        /// <summary>
        /// A snapshot of the current mesh (that of the last successful recompute). The caller
        /// owns and disposes it; it outlives later edits and this object.
        /// </summary>
        public Discretisation GetMesh()
        {
            DiscretisationHandle h;
            var s = UnsafeNativeMethods.tpi_discrete_surface_mesh(Handle, out h);
            return Discretisation.Created(s, h, "tpi_discrete_surface_mesh");
        }

        /// <summary>
        /// What changed in the mesh since the last call (the first call: everything), copied
        /// out: after one edit recomputed by live editing the few facets around it, in
        /// microseconds whatever the mesh's size. Pending edits do not count until recomputed.
        /// </summary>
        public MeshChanges TakeChanges()
        {
            MeshChangesHandle h;
            var s = UnsafeNativeMethods.tpi_discrete_surface_changes(Handle, out h);
            if (s != Status.Ok)
            {
                var error = new TpiException(s, TpiLibrary.LastErrorMessage(), "tpi_discrete_surface_changes");
                if (h != null) h.Dispose();
                throw error;
            }
            h.Track();
            using (h) return MeshChanges.Read(h);
        }

        /// <summary>True once disposed.</summary>
        public bool IsDisposed { get { return Handle.IsClosed; } }

        /// <summary>Frees the native object (meshes taken from it stay valid).</summary>
        public void Dispose() { Handle.Dispose(); }
    }
}
