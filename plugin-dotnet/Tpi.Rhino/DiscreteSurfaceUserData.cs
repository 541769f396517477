// Checked against: RhinoCommon 8 (rhino-stubs-typed 8.20.25157; the protected virtuals of
// UserData against the RhinoCommon source). Members used: see plugin-dotnet/API-CHECK.md.
//
// The discrete surface's data (surface, pattern points, options, source surface id) as user
// data on the object's mesh, written into the .3dm as the bytes of Tpi.Logic.UserDataFormat.
// It travels with the geometry: copies (OnDuplicate), transforms (OnTransform moves the stored
// surface with the mesh), undo (Rhino keeps the replaced object with its user data).
using System;
using System.Linq;
using System.Runtime.InteropServices;
using Rhino.DocObjects.Custom;
using Rhino.FileIO;
using Rhino.Geometry;
using Tpi.Logic;

namespace Tpi.RhinoPlugIn
{
    /// <summary>The stored data of a discrete surface.</summary>
    [Guid("5B0C9E0E-7C1F-4B8B-9A57-2E6F1D3C4A01")]
    public sealed class DiscreteSurfaceUserData : UserData
    {
        /// <summary>Chunk version written around the bytes (the bytes carry their own format version).</summary>
        const int ChunkMajor = 1, ChunkMinor = 0;

        /// <summary>Bytes of <see cref="UserDataFormat"/>.</summary>
        public byte[] Data { get; set; }

        /// <summary>Needed by Rhino to read the data back.</summary>
        public DiscreteSurfaceUserData() { }

        /// <summary>Stores <paramref name="document"/>.</summary>
        public DiscreteSurfaceUserData(DiscreteSurfaceDocument document) { Data = UserDataFormat.Write(document); }

        /// <summary>The stored document.</summary>
        public DiscreteSurfaceDocument Document { get { return UserDataFormat.Read(Data); } }

        /// <inheritdoc/>
        public override string Description { get { return "TPI discrete surface"; } }

        /// <inheritdoc/>
        public override bool ShouldWrite { get { return Data != null; } }

        /// <inheritdoc/>
        protected override bool Write(BinaryArchiveWriter archive)
        {
            archive.Write3dmChunkVersion(ChunkMajor, ChunkMinor);
            archive.WriteByteArray(Data);
            return true;
        }

        /// <inheritdoc/>
        protected override bool Read(BinaryArchiveReader archive)
        {
            int major, minor;
            archive.Read3dmChunkVersion(out major, out minor);
            if (major != ChunkMajor) return false;
            Data = archive.ReadByteArray().ToArray();
            return Data != null;
        }

        /// <inheritdoc/>
        protected override void OnDuplicate(UserData source)
        {
            var other = source as DiscreteSurfaceUserData;
            if (other != null && other.Data != null) Data = (byte[])other.Data.Clone();
        }

        /// <inheritdoc/>
        protected override void OnTransform(Transform transform)
        {
            base.OnTransform(transform);
            if (Data == null) return;
            var document = UserDataFormat.Read(Data);
            if (document.Surface is NurbsSurfaceSpec)
            {
                document.Surface = document.Surface.Transformed(RhinoConvert.ToMatrix(transform));
                Data = UserDataFormat.Write(document);
            }
        }

        /// <summary>The data attached to <paramref name="geometry"/>, or null.</summary>
        public static DiscreteSurfaceUserData Find(GeometryBase geometry)
        {
            return geometry == null ? null : geometry.UserData.Find(typeof(DiscreteSurfaceUserData)) as DiscreteSurfaceUserData;
        }
    }
}
