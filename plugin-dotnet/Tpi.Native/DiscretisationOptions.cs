using System;
using Tpi.Native.Interop;

namespace Tpi.Native
{
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

        /// <summary>The library's defaults.</summary>
        public static DiscretisationOptions Default()
        {
            var native = new NativeOptions { StructSize = NativeOptions.SizeV1 };
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
            };
        }

        internal NativeOptions ToNative()
        {
            return new NativeOptions
            {
                StructSize = NativeOptions.SizeV1,
                EnvelopeRepair = EnvelopeRepair ? 1u : 0u,
                QualityReport = QualityReport ? 1u : 0u,
                Reserved = 0,
                FarVertexFactor = FarVertexFactor,
                WeldTolerance = WeldTolerance,
                FlatTolerance = FlatTolerance,
            };
        }

        /// <inheritdoc/>
        public bool Equals(DiscretisationOptions other)
        {
            return other != null && EnvelopeRepair == other.EnvelopeRepair && QualityReport == other.QualityReport
                && FarVertexFactor.Equals(other.FarVertexFactor) && WeldTolerance.Equals(other.WeldTolerance)
                && FlatTolerance.Equals(other.FlatTolerance);
        }

        /// <inheritdoc/>
        public override bool Equals(object obj) { return Equals(obj as DiscretisationOptions); }

        /// <inheritdoc/>
        public override int GetHashCode()
        {
            return FarVertexFactor.GetHashCode() ^ WeldTolerance.GetHashCode() ^ FlatTolerance.GetHashCode()
                ^ (EnvelopeRepair ? 1 : 0) ^ (QualityReport ? 2 : 0);
        }
    }
}
