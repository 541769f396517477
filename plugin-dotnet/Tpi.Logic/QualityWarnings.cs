// Warnings read from a discretisation's quality report, worded as the CLI's (tpi discretise):
// shown by the Grasshopper component beside the flagged facets and the diagnostics.
// Rhino-free, so the Mono tests check it.
using System;
using System.Globalization;
using Tpi.Native;

namespace Tpi.Logic
{
    /// <summary>Warnings read from a quality report.</summary>
    public static class QualityWarnings
    {
        /// <summary>Pattern spacings (the seeds' bounding-box diagonal over the square root of the
        /// facet count) beyond which a vertex's distance from the surface is warned about: the
        /// native library's tpi_core::tolerance::FAR_VERTEX_SPACINGS, which the CLI uses. A TPI
        /// vertex of a convex patch stays within about one spacing.</summary>
        public const double FarVertexSpacings = 3.0;

        /// <summary>The warning when a vertex stands farther than <see cref="FarVertexSpacings"/>
        /// pattern spacings off the surface (exact tangent planes that are nearly parallel meet
        /// far away), or null.</summary>
        public static string FarVertex(QualityReport q)
        {
            if (q.FacetCount == 0 || !(q.BoundingBoxDiagonal > 0)) return null;
            double spacing = q.BoundingBoxDiagonal / Math.Sqrt(q.FacetCount);
            double spacings = q.MaxDeviation / spacing;
            if (!(spacings > FarVertexSpacings)) return null;
            return string.Format(CultureInfo.InvariantCulture,
                "a vertex stands {0:G4} off the surface, {1:F0} pattern spacings of about {2:G4}: where neighbouring tangent planes are nearly parallel (at a parabolic line, K = 0, or at seeds close together) they meet far from it; adjusted planes hold facets near their seeds",
                q.MaxDeviation, spacings, spacing);
        }
    }
}
