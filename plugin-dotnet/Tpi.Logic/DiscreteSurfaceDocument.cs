using System;
using System.Collections.Generic;
using System.Linq;
using Tpi.Native;

namespace Tpi.Logic
{
    /// <summary>
    /// What a discrete surface object stores (in the .3dm, through its user data): the
    /// surface, the pattern points, the options, the generator it came from and the Rhino
    /// object its surface was taken from. Plain data, no native handles.
    /// </summary>
    public sealed class DiscreteSurfaceDocument
    {
        /// <summary>The surface.</summary>
        public SurfaceSpec Surface { get; set; }
        /// <summary>Pattern points, normalised.</summary>
        public List<PatternPoint> Points { get; set; }
        /// <summary>Options of the discretisation.</summary>
        public DiscretisationOptions Options { get; set; }
        /// <summary>The generator spec the points came from ("" if picked or edited by hand).</summary>
        public string Generator { get; set; }
        /// <summary>The Rhino surface object the surface follows (Guid.Empty: none).</summary>
        public Guid SourceSurfaceId { get; set; }

        /// <summary>An empty document with default-looking options (set the real ones before use).</summary>
        public DiscreteSurfaceDocument()
        {
            Points = new List<PatternPoint>();
            Generator = string.Empty;
        }

        /// <summary>A deep copy.</summary>
        public DiscreteSurfaceDocument Clone()
        {
            return new DiscreteSurfaceDocument
            {
                Surface = Surface,
                Points = Points.ToList(),
                Options = Options == null ? null : Options.Clone(),
                Generator = Generator,
                SourceSurfaceId = SourceSurfaceId,
            };
        }

        /// <summary>True if everything that is stored is equal.</summary>
        public bool SameAs(DiscreteSurfaceDocument other)
        {
            return other != null && Equals(Surface, other.Surface) && Points.SequenceEqual(other.Points)
                && Equals(Options, other.Options) && Generator == other.Generator && SourceSurfaceId == other.SourceSurfaceId;
        }
    }
}
