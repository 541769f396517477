// The pattern generators as plain data: what the TpiPattern command and the "TPI Pattern"
// component offer, turned into the library's generator calls or its spec syntax.
using System;
using System.Globalization;
using Tpi.Native;

namespace Tpi.Logic
{
    /// <summary>The generator schemes of the library.</summary>
    public enum GeneratorKind
    {
        /// <summary>Square grid of NU x NV cell centres.</summary>
        Grid = 0,
        /// <summary>Hexagonal grid of NU x NV points.</summary>
        Hex = 1,
        /// <summary>Jittered grid: NU x NV, amount, seed.</summary>
        Jitter = 2,
        /// <summary>Uniform random: count, seed.</summary>
        Random = 3,
        /// <summary>Poisson-disk: radius, seed.</summary>
        Poisson = 4,
    }

    /// <summary>A generator and its parameters. Validation is the library's.</summary>
    public sealed class PatternGenerator : IEquatable<PatternGenerator>
    {
        /// <summary>The scheme.</summary>
        public GeneratorKind Kind { get; set; }
        /// <summary>Points (or cells) in u; the point count for <see cref="GeneratorKind.Random"/>.</summary>
        public int CountU { get; set; }
        /// <summary>Points (or cells) in v.</summary>
        public int CountV { get; set; }
        /// <summary>Jitter amount in [0, 1].</summary>
        public double Amount { get; set; }
        /// <summary>Poisson-disk minimum distance (normalised units, &gt;= 0.001).</summary>
        public double Radius { get; set; }
        /// <summary>Random seed.</summary>
        public ulong Seed { get; set; }

        /// <summary>hex:10x10, the commands' default.</summary>
        public PatternGenerator()
        {
            Kind = GeneratorKind.Hex; CountU = 10; CountV = 10; Amount = 0.5; Radius = 0.08; Seed = 1;
        }

        /// <summary>Runs the generator.</summary>
        public Pattern Create()
        {
            switch (Kind)
            {
                case GeneratorKind.Grid: return Pattern.Grid(CountU, CountV);
                case GeneratorKind.Hex: return Pattern.Hex(CountU, CountV);
                case GeneratorKind.Jitter: return Pattern.Jitter(CountU, CountV, Amount, Seed);
                case GeneratorKind.Random: return Pattern.Random(CountU, Seed);
                case GeneratorKind.Poisson: return Pattern.Poisson(Radius, Seed);
                default: throw new InvalidOperationException("unknown generator " + Kind);
            }
        }

        /// <summary>The library's spec syntax, e.g. "jitter:8x6:amount=0.5:seed=3" (stored as provenance).</summary>
        public string ToSpec()
        {
            var c = CultureInfo.InvariantCulture;
            switch (Kind)
            {
                case GeneratorKind.Grid: return string.Format(c, "grid:{0}x{1}", CountU, CountV);
                case GeneratorKind.Hex: return string.Format(c, "hex:{0}x{1}", CountU, CountV);
                case GeneratorKind.Jitter: return string.Format(c, "jitter:{0}x{1}:amount={2:R}:seed={3}", CountU, CountV, Amount, Seed);
                case GeneratorKind.Random: return string.Format(c, "random:{0}:seed={1}", CountU, Seed);
                case GeneratorKind.Poisson: return string.Format(c, "poisson:{0:R}:seed={1}", Radius, Seed);
                default: throw new InvalidOperationException("unknown generator " + Kind);
            }
        }

        /// <summary>Parses a generator name as the UI offers it ("grid", "hex", ...), case-insensitive.</summary>
        public static bool TryParseKind(string name, out GeneratorKind kind)
        {
            kind = GeneratorKind.Hex;
            if (string.IsNullOrEmpty(name)) return false;
            return Enum.TryParse(name.Trim(), true, out kind) && Enum.IsDefined(typeof(GeneratorKind), kind);
        }

        /// <inheritdoc/>
        public bool Equals(PatternGenerator other)
        {
            return other != null && other.ToSpec() == ToSpec();
        }

        /// <inheritdoc/>
        public override bool Equals(object obj) { return Equals(obj as PatternGenerator); }

        /// <inheritdoc/>
        public override int GetHashCode() { return ToSpec().GetHashCode(); }
    }
}
