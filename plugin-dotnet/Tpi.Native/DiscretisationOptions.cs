using System;
using Tpi.Native.Interop;

namespace Tpi.Native
{
    /// <summary>Which planes the facets lie in (TPI_PLANES_*).</summary>
    public enum PlaneMode
    {
        /// <summary>Every facet in the exact tangent plane at its seed.</summary>
        Exact = 0,
        /// <summary>
        /// Exact tangent planes, except where they cannot give a valid facet on a surface that
        /// is not convex everywhere: there a few planes are tilted by at most 5 degrees
        /// (<see cref="Discretisation.Planes"/> gives each facet's plane).
        /// </summary>
        Adjusted = 1,
    }

    /// <summary>
    /// Options of a discretisation (TpiOptions). Start from <see cref="Default"/>, which asks
    /// the library for its defaults, so a newer library's defaults are kept.
    /// </summary>
    public sealed class DiscretisationOptions : IEquatable<DiscretisationOptions>
    {
        /// <summary>Verify and repair the neighbours against the envelope where K &gt; 0. Default value: true.</summary>
        public bool EnvelopeRepair { get; set; }
        /// <summary>Compute the quality report and per-facet flags. Default value: true.</summary>
        public bool QualityReport { get; set; }
        /// <summary>Ill-conditioned vertex threshold (times the dual triangle's longest side). Finite, &gt; 0. Default value: 8.</summary>
        public double FarVertexFactor { get; set; }
        /// <summary>Weld tolerance relative to the bounding-box diagonal. Finite, &gt;= 0. Default value: 1e-10.</summary>
        public double WeldTolerance { get; set; }
        /// <summary>Flat when |K| &lt;= FlatTolerance * max(k1^2, k2^2). Finite, &gt;= 0. Default value: 1e-6.</summary>
        public double FlatTolerance { get; set; }
        /// <summary>Which planes the facets lie in. Default value: <see cref="PlaneMode.Exact"/>.</summary>
        public PlaneMode Planes { get; set; }

        /// <summary>The library's defaults.</summary>
        public static DiscretisationOptions Default()
        {
            var native = new NativeOptions { StructSize = NativeOptions.SizeV2 };
            TpiLibrary.Check(UnsafeNativeMethods.tpi_options_default(ref native), "tpi_options_default");
            return FromNative(native);
        }

        /// <summary>A copy.</summary>
        public DiscretisationOptions Clone()
        {
            return (DiscretisationOptions)MemberwiseClone();
        }

        internal static DiscretisationOptions FromNative(NativeOptions native)
        {
            return new DiscretisationOptions
            {
                EnvelopeRepair = native.EnvelopeRepair != 0,
                QualityReport = native.QualityReport != 0,
                FarVertexFactor = native.FarVertexFactor,
                WeldTolerance = native.WeldTolerance,
                FlatTolerance = native.FlatTolerance,
                Planes = (PlaneMode)native.PlaneMode,
            };
        }

        internal NativeOptions ToNative()
        {
            return new NativeOptions
            {
                StructSize = NativeOptions.SizeV2,
                EnvelopeRepair = EnvelopeRepair ? 1u : 0u,
                QualityReport = QualityReport ? 1u : 0u,
                Reserved = 0,
                FarVertexFactor = FarVertexFactor,
                WeldTolerance = WeldTolerance,
                FlatTolerance = FlatTolerance,
                PlaneMode = (uint)Planes,
                Reserved2 = 0,
            };
        }

        /// <inheritdoc/>
        public bool Equals(DiscretisationOptions other)
        {
            return other != null && EnvelopeRepair == other.EnvelopeRepair && QualityReport == other.QualityReport
                && FarVertexFactor.Equals(other.FarVertexFactor) && WeldTolerance.Equals(other.WeldTolerance)
                && FlatTolerance.Equals(other.FlatTolerance) && Planes == other.Planes;
        }

        /// <inheritdoc/>
        public override bool Equals(object obj) { return Equals(obj as DiscretisationOptions); }

        /// <inheritdoc/>
        public override int GetHashCode()
        {
            return FarVertexFactor.GetHashCode() ^ WeldTolerance.GetHashCode() ^ FlatTolerance.GetHashCode()
                ^ (EnvelopeRepair ? 1 : 0) ^ (QualityReport ? 2 : 0) ^ ((int)Planes << 2);
        }
    }
}
