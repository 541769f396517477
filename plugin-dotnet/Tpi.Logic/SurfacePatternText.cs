// The "TPI Pattern" component's surface-aware inputs (tolerance, relaxation, alignment,
// density) written as one pattern spec in the library's grammar (tpi_pattern_new_for_surface,
// `tpi discretise --pattern`): the library parses and checks it; this only puts the pieces in
// their places and refuses combinations the grammar has no form for.
using System;
using System.Globalization;

namespace Tpi.Logic
{
    /// <summary>The surface-aware inputs of a pattern, turned into a pattern spec.</summary>
    public sealed class SurfacePatternInputs
    {
        /// <summary>Largest vertex deviation (model units) for a tolerance-driven pattern (fit:D); 0 or less: none.</summary>
        public double MaxDeviation { get; set; }
        /// <summary>Lloyd iterations on the surface (relax:N:...); 0: none.</summary>
        public int Relax { get; set; }
        /// <summary>Direction field of an aligned hex or grid lattice: principal, asymptotic, uv:ANGLE or a direction field's JSON; empty: not aligned.</summary>
        public string Align { get; set; }
        /// <summary>A density field's JSON (density:{...}); empty: none.</summary>
        public string DensityJson { get; set; }

        /// <summary>
        /// The alignment choices a Rhino command offers, in order: not aligned, then the
        /// library's two curvature fields (principal directions; asymptotic directions where
        /// K &lt; 0, which keep hexagons valid on saddles).
        /// </summary>
        public static readonly string[] AlignChoices = { "None", "Principal", "Asymptotic" };

        /// <summary>The <see cref="Align"/> value of choice <paramref name="index"/> of <see cref="AlignChoices"/>: the field's name in the spec grammar, or null for "None" and an index out of range.</summary>
        public static string AlignField(int index)
        {
            return index > 0 && index < AlignChoices.Length ? AlignChoices[index].ToLowerInvariant() : null;
        }

        /// <summary>The index in <see cref="AlignChoices"/> of an <see cref="Align"/> value (0, "None", for no alignment or a field the choices do not name).</summary>
        public static int AlignChoiceOf(string align)
        {
            if (string.IsNullOrWhiteSpace(align)) return 0;
            for (int i = 1; i < AlignChoices.Length; i++)
                if (string.Equals(AlignChoices[i], align.Trim(), StringComparison.OrdinalIgnoreCase)) return i;
            return 0;
        }

        /// <summary>True when any input asks for a pattern made on the surface.</summary>
        public bool Any
        {
            get
            {
                return MaxDeviation > 0 || Relax != 0 || !string.IsNullOrWhiteSpace(Align) || !string.IsNullOrWhiteSpace(DensityJson);
            }
        }

        /// <summary>True for a spec of a form made on a surface (fit:, relax:, align:, density:).</summary>
        public static bool NeedsSurface(string spec)
        {
            if (string.IsNullOrWhiteSpace(spec)) return false;
            var t = spec.TrimStart();
            foreach (var form in new[] { "fit:", "relax:", "align:", "density:" })
                if (t.StartsWith(form, StringComparison.Ordinal)) return true;
            return false;
        }

        /// <summary>
        /// The spec: <c>fit:D</c>; else <c>density:JSON</c>, <c>align:GENERATOR:FIELD</c> or the
        /// generator itself, wrapped in <c>relax:N:</c> when <see cref="Relax"/> &gt; 0. False with a
        /// message for inputs the grammar cannot combine (a tolerance with anything else, alignment
        /// with a density, a negative iteration count, a non-finite tolerance).
        /// </summary>
        public bool TryCompose(string generatorSpec, out string spec, out string error)
        {
            spec = null;
            error = null;
            var c = CultureInfo.InvariantCulture;
            bool align = !string.IsNullOrWhiteSpace(Align);
            bool density = !string.IsNullOrWhiteSpace(DensityJson);
            if (double.IsNaN(MaxDeviation) || double.IsInfinity(MaxDeviation))
            {
                error = "the tolerance is not a finite number";
                return false;
            }
            if (Relax < 0)
            {
                error = "relaxation iterations must be 0 or more, not " + Relax.ToString(c);
                return false;
            }
            if (MaxDeviation > 0)
            {
                if (Relax != 0 || align || density)
                {
                    error = "a tolerance-driven pattern (fit) makes and relaxes its own points: give no relaxation, alignment or density with a tolerance";
                    return false;
                }
                spec = "fit:" + MaxDeviation.ToString("R", c);
                return true;
            }
            if (align && density)
            {
                error = "give an alignment field or a density, not both";
                return false;
            }
            string body;
            if (density)
            {
                body = "density:" + DensityJson.Trim();
            }
            else
            {
                if (string.IsNullOrWhiteSpace(generatorSpec))
                {
                    error = "no generator";
                    return false;
                }
                body = align ? "align:" + generatorSpec.Trim() + ":" + Align.Trim() : generatorSpec.Trim();
            }
            spec = Relax > 0 ? "relax:" + Relax.ToString(c) + ":" + body : body;
            return true;
        }
    }
}
