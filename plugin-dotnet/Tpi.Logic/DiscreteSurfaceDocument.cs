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
        /// <summary>
        /// The face of the source object the surface was taken from when that object is a
        /// polysurface (-1: the object is a surface). Format 2 and later; format 1 reads as -1.
        /// </summary>
        public int SourceFaceIndex { get; set; }
        /// <summary>
        /// The transform (16 numbers, row-major, <see cref="SurfaceSpec.Transformed"/>'s
        /// convention) from the source object's space to this object's: the transforms applied to
        /// the discrete surface since it was made. The source's surface, mapped by it, is this
        /// surface, so the discrete surface keeps following its source after a Move or Rotate.
        /// Format 2 and later; format 1 reads as the identity.
        /// </summary>
        public double[] SourceTransform
        {
            get { return (double[])_sourceTransform.Clone(); }
            set
            {
                if (value == null || value.Length != 16) throw new ArgumentException("a transform has 16 numbers", "value");
                foreach (var x in value)
                    if (double.IsNaN(x) || double.IsInfinity(x)) throw new ArgumentException("a transform has finite numbers", "value");
                _sourceTransform = (double[])value.Clone();
            }
        }
        double[] _sourceTransform = Transforms.Identity();

        /// <summary>An empty document with default-looking options (set the real ones before use).</summary>
        public DiscreteSurfaceDocument()
        {
            Points = new List<PatternPoint>();
            Generator = string.Empty;
            SourceFaceIndex = -1;
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
                SourceFaceIndex = SourceFaceIndex,
                _sourceTransform = (double[])_sourceTransform.Clone(),
            };
        }

        /// <summary>
        /// This document moved by <paramref name="m"/> (row-major 4x4): the surface transformed,
        /// the pattern unchanged (it lives in the surface's normalised parameters, so it moves
        /// with the surface), the source transform composed (m after the old one). Raises
        /// NotSupportedException for an analytic surface, which has no transformed form.
        /// </summary>
        public DiscreteSurfaceDocument Transformed(double[] m)
        {
            if (Surface == null) throw new InvalidOperationException("the document has no surface");
            var moved = Clone();
            moved.Surface = Surface.Transformed(m);
            moved.SourceTransform = Transforms.Multiply(m, _sourceTransform);
            return moved;
        }

        /// <summary>
        /// The surface this document should have when its source object's surface is
        /// <paramref name="source"/>: the source mapped by <see cref="SourceTransform"/>.
        /// </summary>
        public SurfaceSpec SurfaceFromSource(SurfaceSpec source)
        {
            if (source == null) throw new ArgumentNullException("source");
            return Transforms.IsIdentity(_sourceTransform) ? source : source.Transformed(_sourceTransform);
        }

        /// <summary>True if everything that is stored is equal.</summary>
        public bool SameAs(DiscreteSurfaceDocument other)
        {
            return other != null && Equals(Surface, other.Surface) && Points.SequenceEqual(other.Points)
                && Equals(Options, other.Options) && Generator == other.Generator && SourceSurfaceId == other.SourceSurfaceId
                && SourceFaceIndex == other.SourceFaceIndex && _sourceTransform.SequenceEqual(other._sourceTransform);
        }
    }
}
