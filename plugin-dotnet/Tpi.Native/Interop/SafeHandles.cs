// SafeHandle wrappers for the opaque handles of include/tpi.h. Each owns one native
// handle and frees it exactly once with the matching tpi_*_free call (from Dispose or, if the
// owner forgot, from the finalizer). SafeHandle's reference counting keeps a handle alive for
// the duration of every P/Invoke call that receives it, so a Dispose on another thread can
// never free it in the middle of a call (the header's "a *_free call must not overlap any
// other call on the same handle").
using System;
using System.Runtime.InteropServices;
using System.Threading;

namespace Tpi.Native.Interop
{
    /// <summary>Base of the handle types: NULL is invalid, and live handles are counted.</summary>
    public abstract class TpiHandle : SafeHandle
    {
        static long s_live;

        /// <summary>Handles created through this binding and not yet freed (all kinds).</summary>
        public static long LiveCount { get { return Interlocked.Read(ref s_live); } }

        /// <summary>A handle with no native object yet (filled in by the marshaller).</summary>
        protected TpiHandle() : base(IntPtr.Zero, true) { }

        /// <inheritdoc/>
        public override bool IsInvalid { get { return handle == IntPtr.Zero; } }

        /// <summary>Called once after a successful create: counts the handle as live.</summary>
        internal void Track()
        {
            if (!IsInvalid) Interlocked.Increment(ref s_live);
        }

        /// <inheritdoc/>
        protected sealed override bool ReleaseHandle()
        {
            Free(handle);
            Interlocked.Decrement(ref s_live);
            return true;
        }

        /// <summary>Calls the matching tpi_*_free.</summary>
        protected abstract void Free(IntPtr native);
    }

    /// <summary>Owns a TpiSurface.</summary>
    public sealed class SurfaceHandle : TpiHandle
    {
        /// <summary>Used by the marshaller.</summary>
        public SurfaceHandle() { }
        /// <inheritdoc/>
        protected override void Free(IntPtr native) { UnsafeNativeMethods.tpi_surface_free(native); }
    }

    /// <summary>Owns a TpiPattern.</summary>
    public sealed class PatternHandle : TpiHandle
    {
        /// <summary>Used by the marshaller.</summary>
        public PatternHandle() { }
        /// <inheritdoc/>
        protected override void Free(IntPtr native) { UnsafeNativeMethods.tpi_pattern_free(native); }
    }

    /// <summary>Owns a TpiDiscretisation.</summary>
    public sealed class DiscretisationHandle : TpiHandle
    {
        /// <summary>Used by the marshaller.</summary>
        public DiscretisationHandle() { }
        /// <inheritdoc/>
        protected override void Free(IntPtr native) { UnsafeNativeMethods.tpi_discretisation_free(native); }
    }

    /// <summary>Owns a TpiFabrication.</summary>
    public sealed class FabricationHandle : TpiHandle
    {
        /// <summary>Used by the marshaller.</summary>
        public FabricationHandle() { }
        /// <inheritdoc/>
        protected override void Free(IntPtr native) { UnsafeNativeMethods.tpi_fabrication_free(native); }
    }

    /// <summary>Owns a TpiDiscreteSurface.</summary>
    public sealed class DiscreteSurfaceHandle : TpiHandle
    {
        /// <summary>Used by the marshaller.</summary>
        public DiscreteSurfaceHandle() { }
        /// <inheritdoc/>
        protected override void Free(IntPtr native) { UnsafeNativeMethods.tpi_discrete_surface_free(native); }
    }

    /// <summary>Owns a TpiMeshChanges.</summary>
    public sealed class MeshChangesHandle : TpiHandle
    {
        /// <summary>Used by the marshaller.</summary>
        public MeshChangesHandle() { }
        /// <inheritdoc/>
        protected override void Free(IntPtr native) { UnsafeNativeMethods.tpi_mesh_changes_free(native); }
    }
}
