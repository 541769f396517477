// The bytes a discrete surface stores in the .3dm (the Rhino adapter writes them with
// BinaryArchiveWriter.WriteByteArray inside its UserData.Write). Versioned, little-endian,
// self-checking:
//
//   magic      4 bytes  "TPDS"
//   version    uint16   FormatVersion (readers reject a newer major format with a clear message)
//   flags      uint16   0
//   surface    byte kind: 1 = NURBS, 2 = analytic, 3 = polysurface (format 3 and later)
//     NURBS:    int32 degreeU, degreeV, countU, countV; array knotsU; array knotsV;
//               array points (3 per control point, u-major, Euclidean); byte rational; [array weights]
//     analytic: int32 kind; array parameters
//     (format 3 and later, after a NURBS or analytic record) trim: byte 0 (none) or 1, then
//               array outer (u, v per point), int32 hole count, each hole an array
//     polysurface: int32 face count, then each face as a surface of kind 1 or 2
//   pattern    array s0, t0, s1, t1, ...
//   options    int32 byte length L, then L bytes: byte envelopeRepair, byte qualityReport,
//              double farVertexFactor, weldTolerance, flatTolerance, (format 3) byte planes
//              (0 exact, 1 adjusted) (later versions append; a reader skips what it does not
//              know and gives missing fields their defaults)
//   generator  int32 byte length, UTF-8
//   source     16 bytes Guid
//   follow     (format 2 and later) int32 byte length L, then L bytes: 16 doubles source
//              transform (row-major), int32 source face index (later versions append; a reader
//              skips what it does not know)
//   crc32      uint32 of everything before it (IEEE polynomial)
//
// where "array" is int32 count followed by count doubles.
//
// Versions: 1 (TPI 0.1, commit 9e2b174; Tpi.Tests/Fixtures/discrete-surface-v1.bin is such a
// blob) has no follow block: it reads as source face -1 and the identity source transform.
// 2 adds the follow block. 3 adds polysurfaces (kind 3; a discrete surface made from a whole
// Brep of several faces, source face -1 then meaning the whole object), each surface's trim and
// the plane mode, so that a trimmed or adjusted discrete surface reopens as it was saved. A reader rejects a newer version than its own (FormatException
// naming both), so an older plug-in never follows a source with a transform it cannot see.
using System;
using System.IO;
using System.Linq;
using System.Text;
using Tpi.Native;

namespace Tpi.Logic
{
    /// <summary>Serialises a <see cref="DiscreteSurfaceDocument"/> to bytes and back.</summary>
    public static class UserDataFormat
    {
        /// <summary>The format version written.</summary>
        public const ushort FormatVersion = 3;
        /// <summary>The oldest format version read (and migrated on read).</summary>
        public const ushort OldestReadableVersion = 1;
        static readonly byte[] Magic = { (byte)'T', (byte)'P', (byte)'D', (byte)'S' };
        const int MaxArray = 1 << 27;
        const int OptionsV1Length = 2 + 3 * 8;
        const int OptionsV3Length = OptionsV1Length + 1;
        const int FollowV2Length = 16 * 8 + 4;
        const int MaxFaces = 1000;
        const int MaxHoles = 1 << 20;

        /// <summary>The bytes of <paramref name="document"/>.</summary>
        public static byte[] Write(DiscreteSurfaceDocument document)
        {
            if (document == null) throw new ArgumentNullException("document");
            if (document.Surface == null) throw new ArgumentException("the document has no surface", "document");
            using (var stream = new MemoryStream())
            {
                using (var w = new BinaryWriter(stream, Encoding.UTF8, true))
                {
                    w.Write(Magic);
                    w.Write(FormatVersion);
                    w.Write((ushort)0);
                    var polysurface = document.Surface as PolysurfaceSpec;
                    if (polysurface != null)
                    {
                        w.Write((byte)3);
                        w.Write(polysurface.Faces.Count);
                        foreach (var face in polysurface.Faces) WriteSurface(w, face);
                    }
                    else WriteSurface(w, document.Surface);
                    w.Write(document.Points.Count * 2);
                    foreach (var p in document.Points) { w.Write(p.S); w.Write(p.T); }
                    var o = document.Options ?? DiscretisationOptions.Default();
                    w.Write(OptionsV3Length);
                    w.Write((byte)(o.EnvelopeRepair ? 1 : 0));
                    w.Write((byte)(o.QualityReport ? 1 : 0));
                    w.Write(o.FarVertexFactor); w.Write(o.WeldTolerance); w.Write(o.FlatTolerance);
                    w.Write((byte)(o.Planes == PlaneMode.Adjusted ? 1 : 0));
                    var generator = Encoding.UTF8.GetBytes(document.Generator ?? string.Empty);
                    w.Write(generator.Length); w.Write(generator);
                    w.Write(document.SourceSurfaceId.ToByteArray());
                    w.Write(FollowV2Length);
                    foreach (var x in document.SourceTransform) w.Write(x);
                    w.Write(document.SourceFaceIndex);
                }
                var body = stream.ToArray();
                var crc = Crc32(body, 0, body.Length);
                var all = new byte[body.Length + 4];
                Buffer.BlockCopy(body, 0, all, 0, body.Length);
                BitConverter.GetBytes(crc).CopyTo(all, body.Length);
                if (!BitConverter.IsLittleEndian) Array.Reverse(all, body.Length, 4);
                return all;
            }
        }

        /// <summary>Reads bytes written by <see cref="Write"/>; a <see cref="FormatException"/> says what is wrong.</summary>
        public static DiscreteSurfaceDocument Read(byte[] bytes)
        {
            ushort version;
            return Read(bytes, out version);
        }

        /// <summary>
        /// Reads bytes of any version from <see cref="OldestReadableVersion"/> to
        /// <see cref="FormatVersion"/>; <paramref name="version"/> is the version found (less
        /// than FormatVersion: the caller should store the migrated document again).
        /// </summary>
        public static DiscreteSurfaceDocument Read(byte[] bytes, out ushort version)
        {
            version = 0;
            if (bytes == null) throw new ArgumentNullException("bytes");
            if (bytes.Length < Magic.Length + 4 + 4) throw new FormatException("discrete surface data is truncated (" + bytes.Length + " bytes)");
            for (int i = 0; i < Magic.Length; i++)
                if (bytes[i] != Magic[i]) throw new FormatException("not discrete surface data (wrong magic)");
            uint stored = (uint)(bytes[bytes.Length - 4] | bytes[bytes.Length - 3] << 8 | bytes[bytes.Length - 2] << 16 | bytes[bytes.Length - 1] << 24);
            if (stored != Crc32(bytes, 0, bytes.Length - 4)) throw new FormatException("discrete surface data is corrupt (checksum mismatch)");
            try
            {
                using (var r = new BinaryReader(new MemoryStream(bytes, 0, bytes.Length - 4), Encoding.UTF8))
                {
                    r.ReadBytes(Magic.Length);
                    version = r.ReadUInt16();
                    if (version < OldestReadableVersion) throw new FormatException("discrete surface data of format " + version + " is not a known format");
                    if (version > FormatVersion)
                        throw new FormatException("discrete surface data of format " + version + " was written by a newer TPI plugin (this one reads up to " + FormatVersion + ")");
                    r.ReadUInt16();
                    var document = new DiscreteSurfaceDocument();
                    byte kind = r.ReadByte();
                    if (kind == 3 && version >= 3)
                    {
                        int count = r.ReadInt32();
                        if (count < 1 || count > MaxFaces) throw new FormatException("bad polysurface face count " + count);
                        var faces = new SurfaceSpec[count];
                        for (int k = 0; k < count; k++) faces[k] = ReadSurface(r, r.ReadByte(), version);
                        document.Surface = new PolysurfaceSpec(faces);
                    }
                    else document.Surface = ReadSurface(r, kind, version);
                    var st = ReadArray(r);
                    if (st.Length % 2 != 0) throw new FormatException("odd number of pattern coordinates");
                    for (int i = 0; i < st.Length; i += 2) document.Points.Add(new PatternPoint(st[i], st[i + 1]));
                    int optionsLength = r.ReadInt32();
                    if (optionsLength < OptionsV1Length || optionsLength > 4096) throw new FormatException("bad options length " + optionsLength);
                    var options = new DiscretisationOptions
                    {
                        EnvelopeRepair = r.ReadByte() != 0,
                        QualityReport = r.ReadByte() != 0,
                        FarVertexFactor = r.ReadDouble(),
                        WeldTolerance = r.ReadDouble(),
                        FlatTolerance = r.ReadDouble(),
                    };
                    int known = OptionsV1Length;
                    if (version >= 3 && optionsLength >= OptionsV3Length)
                    {
                        byte planes = r.ReadByte();
                        if (planes > 1) throw new FormatException("bad plane mode " + planes);
                        options.Planes = planes == 1 ? PlaneMode.Adjusted : PlaneMode.Exact;
                        known = OptionsV3Length;
                    }
                    Exact(r, optionsLength - known); // fields of later versions
                    document.Options = options;
                    int generatorLength = r.ReadInt32();
                    if (generatorLength < 0 || generatorLength > 65536) throw new FormatException("bad generator length " + generatorLength);
                    document.Generator = Encoding.UTF8.GetString(Exact(r, generatorLength));
                    document.SourceSurfaceId = new Guid(Exact(r, 16));
                    if (version >= 2)
                    {
                        int followLength = r.ReadInt32();
                        if (followLength < FollowV2Length || followLength > 4096) throw new FormatException("bad follow block length " + followLength);
                        var transform = new double[16];
                        for (int i = 0; i < 16; i++) transform[i] = r.ReadDouble();
                        try { document.SourceTransform = transform; }
                        catch (ArgumentException e) { throw new FormatException("bad source transform: " + e.Message); }
                        int face = r.ReadInt32();
                        if (face < -1) throw new FormatException("bad source face index " + face);
                        document.SourceFaceIndex = face;
                        Exact(r, followLength - FollowV2Length); // fields of later versions
                    }
                    if (r.BaseStream.Position != r.BaseStream.Length)
                        throw new FormatException("discrete surface data has " + (r.BaseStream.Length - r.BaseStream.Position) + " unexpected trailing bytes");
                    return document;
                }
            }
            catch (EndOfStreamException)
            {
                throw new FormatException("discrete surface data is truncated");
            }
        }

        /// <summary>A NURBS or analytic surface: its kind byte and its record.</summary>
        static void WriteSurface(BinaryWriter w, SurfaceSpec surface)
        {
            var nurbs = surface as NurbsSurfaceSpec;
            var analytic = surface as AnalyticSurfaceSpec;
            if (nurbs != null)
            {
                w.Write((byte)1);
                w.Write(nurbs.DegreeU); w.Write(nurbs.DegreeV); w.Write(nurbs.CountU); w.Write(nurbs.CountV);
                WriteArray(w, nurbs.KnotsU); WriteArray(w, nurbs.KnotsV); WriteArray(w, nurbs.Points);
                w.Write((byte)(nurbs.IsRational ? 1 : 0));
                if (nurbs.IsRational) WriteArray(w, nurbs.Weights);
            }
            else if (analytic != null)
            {
                w.Write((byte)2);
                w.Write((int)analytic.Kind);
                WriteArray(w, analytic.Parameters);
            }
            else throw new ArgumentException("unknown surface type " + surface.GetType().Name, "document");
            var trim = surface.Trim;
            w.Write((byte)(trim == null ? 0 : 1));
            if (trim != null)
            {
                WriteArray(w, trim.Outer);
                w.Write(trim.Holes.Count);
                foreach (var hole in trim.Holes) WriteArray(w, hole);
            }
        }

        /// <summary>The record of a NURBS (kind 1) or analytic (kind 2) surface, with its trim from format 3 on.</summary>
        static SurfaceSpec ReadSurface(BinaryReader r, byte kind, ushort version)
        {
            var surface = ReadUntrimmed(r, kind);
            if (version < 3) return surface;
            byte hasTrim = r.ReadByte();
            if (hasTrim == 0) return surface;
            if (hasTrim != 1) throw new FormatException("bad trim flag " + hasTrim);
            var outer = ReadArray(r);
            int holeCount = r.ReadInt32();
            if (holeCount < 0 || holeCount > MaxHoles) throw new FormatException("bad trim hole count " + holeCount);
            var holes = new double[holeCount][];
            for (int k = 0; k < holeCount; k++) holes[k] = ReadArray(r);
            if (outer.Length % 2 != 0 || holes.Any(h => h.Length % 2 != 0)) throw new FormatException("odd number of trim coordinates");
            return surface.WithTrim(new SurfaceTrim(outer, holes));
        }

        static SurfaceSpec ReadUntrimmed(BinaryReader r, byte kind)
        {
            if (kind == 1)
            {
                int du = r.ReadInt32(), dv = r.ReadInt32(), cu = r.ReadInt32(), cv = r.ReadInt32();
                var ku = ReadArray(r); var kv = ReadArray(r); var points = ReadArray(r);
                var weights = r.ReadByte() != 0 ? ReadArray(r) : null;
                return new NurbsSurfaceSpec(du, dv, cu, cv, ku, kv, points, weights);
            }
            if (kind == 2)
            {
                var analyticKind = (AnalyticKind)r.ReadInt32();
                var parameters = ReadArray(r);
                try { return new AnalyticSurfaceSpec(analyticKind, parameters); }
                catch (ArgumentException e) { throw new FormatException("bad analytic surface: " + e.Message); }
            }
            throw new FormatException("unknown surface kind " + kind);
        }

        static void WriteArray(BinaryWriter w, System.Collections.Generic.IReadOnlyList<double> values)
        {
            w.Write(values.Count);
            for (int i = 0; i < values.Count; i++) w.Write(values[i]);
        }

        static double[] ReadArray(BinaryReader r)
        {
            int count = r.ReadInt32();
            long left = r.BaseStream.Length - r.BaseStream.Position;
            if (count < 0 || count > MaxArray || 8L * count > left) throw new FormatException("bad array length " + count);
            var values = new double[count];
            for (int i = 0; i < count; i++) values[i] = r.ReadDouble();
            return values;
        }

        static byte[] Exact(BinaryReader r, int count)
        {
            var bytes = r.ReadBytes(count);
            if (bytes.Length != count) throw new EndOfStreamException();
            return bytes;
        }

        static uint[] s_table;

        /// <summary>CRC-32 (IEEE 802.3, as zlib's crc32).</summary>
        public static uint Crc32(byte[] data, int offset, int count)
        {
            var table = s_table;
            if (table == null)
            {
                table = new uint[256];
                for (uint n = 0; n < 256; n++)
                {
                    uint c = n;
                    for (int k = 0; k < 8; k++) c = (c & 1) != 0 ? 0xEDB88320u ^ (c >> 1) : c >> 1;
                    table[n] = c;
                }
                s_table = table;
            }
            uint crc = 0xFFFFFFFFu;
            for (int i = offset; i < offset + count; i++) crc = table[(crc ^ data[i]) & 0xFF] ^ (crc >> 8);
            return crc ^ 0xFFFFFFFFu;
        }
    }
}
