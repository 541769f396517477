// Warnings read from a discretisation's quality report, worded as the CLI's (tpi discretise):
// shown by the Grasshopper component beside the flagged facets and the diagnostics.
// Rhino-free, so the Mono tests check it.
using System.Globalization;
using Tpi.Native;

namespace Tpi.Logic
{
    /// <summary>Warnings read from a quality report.</summary>
    public static class QualityWarnings
    {
        /// <summary>The warning when the native report flags facets with a vertex far off the
        /// surface (<see cref="FacetFlags.FarVertex"/>: more than tpi_core::tolerance::FAR_VERTEX_SPACINGS
        /// local pattern spacings; exact tangent planes that are nearly parallel meet far away),
        /// or null. The library judges; this only words it.</summary>
        public static string FarVertex(QualityReport q)
        {
            if (q.FarVertexFacets == 0) return null;
            return string.Format(CultureInfo.InvariantCulture,
                "{0} facets have a vertex far off the surface (largest deviation {1:G4}; up to {2:F0} local pattern spacings): where neighbouring tangent planes are nearly parallel (at a parabolic line, K = 0, or at seeds close together) they meet far from it; the facets are flagged FarVertex, and adjusted planes hold facets near their seeds",
                q.FarVertexFacets, q.MaxDeviation, q.MaxDeviationSpacings);
        }
    }
}
