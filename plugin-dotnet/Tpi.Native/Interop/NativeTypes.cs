// Blittable mirrors of the structs and enums of include/tpi.h (ABI 0.1). Every struct has
// LayoutKind.Sequential and only double / uint / ulong / long fields (or structs of them), so
// it crosses the boundary without marshalling code and arrays of it are pinned, not copied.
// Sizes are checked against the header by the tests (NativeLayoutTests).
using System;
using System.Runtime.InteropServices;

namespace Tpi.Native
{
    /// <summary>The result of every fallible call (TpiStatus). The numbers are part of the ABI.</summary>
    public enum Status : uint
    {
        /// <summary>TPI_STATUS_OK: success.</summary>
        Ok = 0,
        /// <summary>TPI_STATUS_NULL_POINTER: a required handle or pointer was NULL.</summary>
        NullPointer = 1,
        /// <summary>TPI_STATUS_INVALID_ARGUMENT: a length, option or parameter that does not fit.</summary>
        InvalidArgument = 2,
        /// <summary>TPI_STATUS_BUFFER_TOO_SMALL: an output buffer was too small.</summary>
        BufferTooSmall = 3,
        /// <summary>TPI_STATUS_INDEX_OUT_OF_RANGE: a pattern point index was not below the point count.</summary>
        IndexOutOfRange = 4,
        /// <summary>TPI_STATUS_NON_FINITE: a NaN or infinite number.</summary>
        NonFinite = 5,
        /// <summary>TPI_STATUS_INVALID_NURBS: degrees, counts, knots, points or weights inconsistent.</summary>
        InvalidNurbs = 6,
        /// <summary>TPI_STATUS_INVALID_PATTERN: a point outside [0, 1]^2, duplicates, too few or collinear points, a bad generator.</summary>
        InvalidPattern = 7,
        /// <summary>TPI_STATUS_DEGENERATE: flat or developable at every pattern point.</summary>
        Degenerate = 8,
        /// <summary>TPI_STATUS_PANIC: an internal error was caught at the boundary.</summary>
        Panic = 9,
        /// <summary>TPI_STATUS_OUT_OF_DOMAIN: a (u, v) pair outside the surface's domain.</summary>
        OutOfDomain = 10,
        /// <summary>TPI_STATUS_UNAVAILABLE: the data was not computed (quality report switched off).</summary>
        Unavailable = 11,
        /// <summary>TPI_STATUS_INVALID_HANDLE: a handle of another kind, or one already freed.</summary>
        InvalidHandle = 12,
        /// <summary>TPI_STATUS_CANCELLED: the progress callback asked the discretisation to stop; nothing was created.</summary>
        Cancelled = 13,
    }

    /// <summary>A stage of a discretisation as reported to progress (TPI_STAGE_*), in pipeline order.</summary>
    public enum Stage : uint
    {
        /// <summary>TPI_STAGE_SAMPLES: evaluation and curvature at every pattern point.</summary>
        Samples = 0,
        /// <summary>TPI_STAGE_DELAUNAY: the candidate triangulation.</summary>
        Delaunay = 1,
        /// <summary>TPI_STAGE_NEIGHBOURS: the neighbour decision.</summary>
        Neighbours = 2,
        /// <summary>TPI_STAGE_FACETS: facet vertices and loops.</summary>
        Facets = 3,
        /// <summary>TPI_STAGE_MESH: mesh assembly.</summary>
        Mesh = 4,
        /// <summary>TPI_STAGE_REPORT: the quality report.</summary>
        Report = 5,
    }

    /// <summary>
    /// One progress report of a discretisation: <see cref="Done"/> of <see cref="Total"/> work
    /// items of <see cref="Stage"/> (Total 0: the stage cannot count its items beforehand).
    /// </summary>
    public struct DiscretisationProgress
    {
        /// <summary>The stage running.</summary>
        public Stage Stage;
        /// <summary>Items of the stage done so far (0 when it starts, Total when it ends).</summary>
        public ulong Done;
        /// <summary>The stage's items, 0 when unknown.</summary>
        public ulong Total;

        /// <summary>Makes a report.</summary>
        public DiscretisationProgress(Stage stage, ulong done, ulong total) { Stage = stage; Done = done; Total = total; }
    }

    /// <summary>What a diagnostic is about (TpiDiagnosticKind).</summary>
    public enum DiagnosticKind : uint
    {
        /// <summary>Three tangent planes nearly parallel: a stand-in vertex was used.</summary>
        IllConditionedVertex = 1,
        /// <summary>Two neighbouring tangent planes at the boundary are parallel.</summary>
        ParallelPlanes = 2,
        /// <summary>The common edge of two facets never reaches the boundary.</summary>
        BoundaryNotReached = 3,
        /// <summary>A facet could not be closed consistently along the boundary.</summary>
        OpenFacet = 4,
        /// <summary>The plane of a corner facet is parallel to the corner's normal.</summary>
        CornerUnreachable = 5,
        /// <summary>A domain corner was claimed by no facet or by several.</summary>
        CornerClaims = 6,
        /// <summary>The point has (nearly) zero Gaussian curvature.</summary>
        FlatPoint = 7,
        /// <summary>Neighbouring facets with coincident tangent planes were separated by the bisector of their seeds.</summary>
        CoincidentPlanes = 8,
        /// <summary>The surface is closed in a direction but was discretised as an open patch: its seam stays open.</summary>
        SeamLeftOpen = 9,
        /// <summary>The mesh's Euler characteristic or boundary loops are not those expected: a gap or a double cover between facets.</summary>
        UnexpectedTopology = 10,
        /// <summary>The surface is developable with its rulings along parameter lines: its facets are strips between the lines where the tangent planes of neighbouring rulings meet.</summary>
        RulingStrips = 11,
        /// <summary>The boundary or trim cuts the point's facet into several parts: it keeps the part around its seed, the others are left out as gaps beside the boundary.</summary>
        FacetPartsLeftOut = 12,
    }

    /// <summary>Per-facet flags (TPI_FACET_* bits).</summary>
    [Flags]
    public enum FacetFlags : byte
    {
        /// <summary>No flag.</summary>
        None = 0,
        /// <summary>TPI_FACET_NON_CONVEX: not convex where the envelope makes facets convex (K &gt; 0 at the seed and its neighbours' seeds, none of their planes adjusted).</summary>
        NonConvex = 1,
        /// <summary>TPI_FACET_NON_SIMPLE: not a simple polygon (invalid).</summary>
        NonSimple = 2,
        /// <summary>TPI_FACET_OVERLAP: overlaps a facet it shares a vertex with (invalid).</summary>
        Overlap = 4,
        /// <summary>TPI_FACET_DIAGNOSTIC: a diagnostic names this facet's pattern point.</summary>
        Diagnostic = 8,
        /// <summary>TPI_FACET_OPEN: fewer than three distinct vertices (invalid).</summary>
        Open = 16,
        /// <summary>TPI_FACET_FAR_VERTEX: a vertex stands farther from the surface than 3 local
        /// pattern spacings (exact tangent planes nearly parallel met far away; not invalid).</summary>
        FarVertex = 32,
    }

    /// <summary>Three doubles x, y, z: the layout of a C <c>double[3]</c>.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct Vec3 : IEquatable<Vec3>
    {
        /// <summary>x.</summary>
        public double X;
        /// <summary>y.</summary>
        public double Y;
        /// <summary>z.</summary>
        public double Z;

        /// <summary>Makes (x, y, z).</summary>
        public Vec3(double x, double y, double z) { X = x; Y = y; Z = z; }

        /// <summary>Component-wise difference.</summary>
        public static Vec3 operator -(Vec3 a, Vec3 b) { return new Vec3(a.X - b.X, a.Y - b.Y, a.Z - b.Z); }
        /// <summary>Component-wise sum.</summary>
        public static Vec3 operator +(Vec3 a, Vec3 b) { return new Vec3(a.X + b.X, a.Y + b.Y, a.Z + b.Z); }
        /// <summary>Scaling.</summary>
        public static Vec3 operator *(double s, Vec3 a) { return new Vec3(s * a.X, s * a.Y, s * a.Z); }
        /// <summary>Dot product.</summary>
        public static double Dot(Vec3 a, Vec3 b) { return a.X * b.X + a.Y * b.Y + a.Z * b.Z; }
        /// <summary>Cross product.</summary>
        public static Vec3 Cross(Vec3 a, Vec3 b)
        {
            return new Vec3(a.Y * b.Z - a.Z * b.Y, a.Z * b.X - a.X * b.Z, a.X * b.Y - a.Y * b.X);
        }
        /// <summary>Euclidean length.</summary>
        public double Length { get { return Math.Sqrt(Dot(this, this)); } }
        /// <summary>True if all three coordinates are finite.</summary>
        public bool IsFinite
        {
            get { return !(double.IsNaN(X) || double.IsInfinity(X) || double.IsNaN(Y) || double.IsInfinity(Y) || double.IsNaN(Z) || double.IsInfinity(Z)); }
        }
        /// <inheritdoc/>
        public bool Equals(Vec3 other) { return X.Equals(other.X) && Y.Equals(other.Y) && Z.Equals(other.Z); }
        /// <inheritdoc/>
        public override bool Equals(object obj) { return obj is Vec3 && Equals((Vec3)obj); }
        /// <inheritdoc/>
        public override int GetHashCode() { return X.GetHashCode() ^ (Y.GetHashCode() * 397) ^ (Z.GetHashCode() * 7919); }
        /// <inheritdoc/>
        public override string ToString() { return string.Format(System.Globalization.CultureInfo.InvariantCulture, "({0}, {1}, {2})", X, Y, Z); }
    }

    /// <summary>A normalised pattern point (s, t) in [0, 1]^2.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct PatternPoint : IEquatable<PatternPoint>
    {
        /// <summary>s: normalised u.</summary>
        public double S;
        /// <summary>t: normalised v.</summary>
        public double T;

        /// <summary>Makes (s, t).</summary>
        public PatternPoint(double s, double t) { S = s; T = t; }
        /// <inheritdoc/>
        public bool Equals(PatternPoint other) { return S.Equals(other.S) && T.Equals(other.T); }
        /// <inheritdoc/>
        public override bool Equals(object obj) { return obj is PatternPoint && Equals((PatternPoint)obj); }
        /// <inheritdoc/>
        public override int GetHashCode() { return S.GetHashCode() ^ (T.GetHashCode() * 397); }
        /// <inheritdoc/>
        public override string ToString() { return string.Format(System.Globalization.CultureInfo.InvariantCulture, "({0}, {1})", S, T); }
    }

    /// <summary>TpiDomain: [UMin, UMax] x [VMin, VMax].</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct Domain
    {
        /// <summary>Start of the u interval.</summary>
        public double UMin;
        /// <summary>End of the u interval.</summary>
        public double UMax;
        /// <summary>Start of the v interval.</summary>
        public double VMin;
        /// <summary>End of the v interval.</summary>
        public double VMax;

        /// <summary>Makes the domain.</summary>
        public Domain(double uMin, double uMax, double vMin, double vMax) { UMin = uMin; UMax = uMax; VMin = vMin; VMax = vMax; }

        /// <summary>Maps a normalised (s, t) onto (u, v): u = UMin + s (UMax - UMin).</summary>
        public void ToUv(double s, double t, out double u, out double v)
        {
            u = UMin + s * (UMax - UMin);
            v = VMin + t * (VMax - VMin);
        }

        /// <summary>Maps (u, v) onto the normalised square (no clamping).</summary>
        public PatternPoint ToNormalised(double u, double v)
        {
            return new PatternPoint((u - UMin) / (UMax - UMin), (v - VMin) / (VMax - VMin));
        }
    }

    /// <summary>TpiSample: point, unit normal (Su x Sv), principal curvatures k1 &lt;= k2 and directions at one (u, v).</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct Sample
    {
        /// <summary>Surface point.</summary>
        public Vec3 Point;
        /// <summary>Unit normal.</summary>
        public Vec3 Normal;
        /// <summary>k1 (the smaller principal curvature, signed relative to the normal).</summary>
        public double K1;
        /// <summary>k2.</summary>
        public double K2;
        /// <summary>Unit principal direction of k1.</summary>
        public Vec3 D1;
        /// <summary>Unit principal direction of k2.</summary>
        public Vec3 D2;
        /// <summary>1 where the surface is regular, 0 where Su x Sv vanishes.</summary>
        public uint Regular;
        /// <summary>Always 0 (padding).</summary>
        public uint Reserved;

        /// <summary>True where Su x Sv does not vanish.</summary>
        public bool IsRegular { get { return Regular != 0; } }
    }

    /// <summary>TpiSeed: the pattern point behind a facet.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct Seed
    {
        /// <summary>u in the surface's domain.</summary>
        public double U;
        /// <summary>v in the surface's domain.</summary>
        public double V;
        /// <summary>Surface point.</summary>
        public Vec3 Point;
        /// <summary>Unit normal.</summary>
        public Vec3 Normal;
        /// <summary>k1 &lt;= k2.</summary>
        public double K1;
        /// <summary>k2.</summary>
        public double K2;
    }

    /// <summary>TpiPlane: a facet's tangent plane through Point with unit Normal.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct FacetPlane
    {
        /// <summary>A point of the plane (the seed's surface point).</summary>
        public Vec3 Point;
        /// <summary>Unit normal.</summary>
        public Vec3 Normal;

        /// <summary>Signed distance of <paramref name="x"/> from the plane.</summary>
        public double SignedDistance(Vec3 x) { return Vec3.Dot(Normal, x - Point); }
    }

    /// <summary>TpiDiagnosticEntry: one (pattern point, diagnostic) pair.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct DiagnosticEntry
    {
        /// <summary>TPI_NO_POINT: the entry concerns no single point.</summary>
        public const uint NoPoint = 4294967295;
        /// <summary>The pattern point (= facet) index, or <see cref="NoPoint"/>.</summary>
        public uint Point;
        /// <summary>The kind (a <see cref="DiagnosticKind"/> value).</summary>
        public DiagnosticKind Kind;
        /// <summary>Index of the diagnostic in the JSON array.</summary>
        public uint Diagnostic;
    }

    /// <summary>TpiFitReport (first version, 40 bytes): how a fit:D pattern went. See include/tpi.h.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct FitReport
    {
        /// <summary>TPI_FIT_REPORT_SIZE_V1.</summary>
        public const int SizeV1 = 40;
        /// <summary>On return: how many bytes the library filled in.</summary>
        public uint StructSize;
        /// <summary>1 if every vertex of the pattern's mesh lies within Tolerance of the surface.</summary>
        public uint Met;
        /// <summary>The tolerance asked for (model units).</summary>
        public double Tolerance;
        /// <summary>The largest vertex deviation of the pattern's mesh (model units).</summary>
        public double MaxDeviation;
        /// <summary>Invalid facets of the pattern's mesh.</summary>
        public ulong InvalidFacets;
        /// <summary>Discretisations run to find the pattern.</summary>
        public ulong Discretisations;
    }

    /// <summary>TpiQualityReport (third version, 248 bytes). See include/tpi.h for each field.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct QualityReport
    {
        /// <summary>TPI_QUALITY_REPORT_SIZE_V1.</summary>
        public const int SizeV1 = 200;
        /// <summary>TPI_QUALITY_REPORT_SIZE_V2.</summary>
        public const int SizeV2 = 232;
        /// <summary>TPI_QUALITY_REPORT_SIZE_V3.</summary>
        public const int SizeV3 = 248;
        /// <summary>On return: how many bytes the library filled in.</summary>
        public uint StructSize;
        /// <summary>1 if every vertex coordinate is finite.</summary>
        public uint AllFinite;
        /// <summary>Number of facets.</summary>
        public ulong FacetCount;
        /// <summary>Number of vertices.</summary>
        public ulong VertexCount;
        /// <summary>Number of edges.</summary>
        public ulong EdgeCount;
        /// <summary>Vertices not on the boundary.</summary>
        public ulong InteriorVertexCount;
        /// <summary>Fraction of interior vertices where exactly three facets meet.</summary>
        public double TrivalentFraction;
        /// <summary>Largest vertex distance from its facet's plane / bounding-box diagonal.</summary>
        public double MaxPlanarityError;
        /// <summary>Largest vertex distance from the surface (model units).</summary>
        public double MaxDeviation;
        /// <summary>Mean vertex distance from the surface (model units).</summary>
        public double MeanDeviation;
        /// <summary>Facets that are not convex.</summary>
        public ulong NonConvexFacets;
        /// <summary>Facets that are not simple.</summary>
        public ulong NonSimpleFacets;
        /// <summary>Overlapping neighbour pairs.</summary>
        public ulong OverlappingPairs;
        /// <summary>Facets with any flag.</summary>
        public ulong FlaggedFacets;
        /// <summary>V - E + F.</summary>
        public long EulerCharacteristic;
        /// <summary>Boundary loops.</summary>
        public ulong BoundaryLoops;
        /// <summary>Edges shared by more than two facets.</summary>
        public ulong NonManifoldEdges;
        /// <summary>Smallest facet area.</summary>
        public double MinFacetArea;
        /// <summary>Largest facet area.</summary>
        public double MaxFacetArea;
        /// <summary>Shortest edge.</summary>
        public double MinEdgeLength;
        /// <summary>Longest edge.</summary>
        public double MaxEdgeLength;
        /// <summary>Bounding-box diagonal.</summary>
        public double BoundingBoxDiagonal;
        /// <summary>Flips by the curvature-compensated in-circle test.</summary>
        public ulong CompensationFlips;
        /// <summary>Flips by the envelope repair.</summary>
        public ulong EnvelopeRepairs;
        /// <summary>Edges the envelope rejects that could not be flipped.</summary>
        public ulong EnvelopeUnresolved;
        /// <summary>Number of diagnostics.</summary>
        public ulong DiagnosticCount;
        /// <summary>Open, non-simple or overlapping facets: 0 for a valid mesh (V2).</summary>
        public ulong InvalidFacets;
        /// <summary>Facets with fewer than three distinct vertices (V2).</summary>
        public ulong OpenFacets;
        /// <summary>Flips kept by the validity repair (V2).</summary>
        public ulong ValidityFlips;
        /// <summary>Facets the validity repair could not make valid (V2).</summary>
        public ulong ValidityUnresolved;
        /// <summary>Facets with a vertex farther from the surface than 3 local pattern spacings,
        /// flagged <see cref="FacetFlags.FarVertex"/> (V3).</summary>
        public ulong FarVertexFacets;
        /// <summary>The largest, over the facets, of the farthest vertex's deviation over the
        /// facet's local spacing: below 1 on a mesh that hugs its surface (V3).</summary>
        public double MaxDeviationSpacings;
    }

    /// <summary>TpiOptions as it crosses the boundary (second version, 48 bytes).</summary>
    [StructLayout(LayoutKind.Sequential)]
    internal struct NativeOptions
    {
        public const int SizeV1 = 40;
        public const int SizeV2 = 48;
        public uint StructSize;
        public uint EnvelopeRepair;
        public uint QualityReport;
        public uint Reserved;
        public double FarVertexFactor;
        public double WeldTolerance;
        public double FlatTolerance;
        /// <summary>TPI_PLANES_EXACT (0) or TPI_PLANES_ADJUSTED (1).</summary>
        public uint PlaneMode;
        public uint Reserved2;
    }
}
