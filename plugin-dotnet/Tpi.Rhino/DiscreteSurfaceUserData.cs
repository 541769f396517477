// Checked against: RhinoCommon 8 (rhino-stubs-typed 8.20.25157; the protected virtuals of
// UserData against the RhinoCommon source). Members used: read from the compiled adapter and checked against the stubs (plugin-dotnet/API-CHECK.md).
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
            if (other != null && other.Data != null) { Data = (byte[])other.Data.Clone(); NeedsRecompute = other.NeedsRecompute; }
        }

        /// <summary>
        /// Set (never stored) when a transform that is not a similarity moved the data: the
        /// mesh Rhino transformed is then not the recomputed one, and the watcher recomputes
        /// the object when the document is idle.
        /// </summary>
        public bool NeedsRecompute { get; private set; }

        /// <inheritdoc/>
        protected override void OnTransform(Transform transform)
        {
            base.OnTransform(transform);
            if (Data == null) return;
            DiscreteSurfaceDocument document;
            try { document = UserDataFormat.Read(Data); }
            catch (FormatException) { return; } // unreadable data stays as it is (the upgrade reports it)
            var m = RhinoConvert.ToMatrix(transform);
            try
            {
                // The surface moves with the mesh, the pattern with the surface, and the source
                // transform remembers the move so the source keeps being followed.
                Data = UserDataFormat.Write(document.Transformed(m));
                if (Transforms.Classify(m) != TransformKind.Similarity) NeedsRecompute = true;
            }
            catch (NotSupportedException)
            {
                // An analytic surface (made in Grasshopper) has no transformed form: the mesh
                // moved, the stored surface did not; a recompute would jump back, so none is asked.
            }
        }

        /// <summary>The data attached to <paramref name="geometry"/>, or null.</summary>
        public static DiscreteSurfaceUserData Find(GeometryBase geometry)
        {
            return geometry == null ? null : geometry.UserData.Find(typeof(DiscreteSurfaceUserData)) as DiscreteSurfaceUserData;
        }
    }
}
