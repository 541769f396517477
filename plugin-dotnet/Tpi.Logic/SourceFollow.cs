// Whether a discrete surface can follow its source object after that object changed, and which
// surface it follows. A surface picked on a polysurface is one of its faces: the discrete
// surface stores the face index (UserDataFormat 2) and follows that face while the polysurface
// still has it. Face indices are Rhino's; an edit that renumbers faces without changing their
// count cannot be detected here (the person with Rhino should check the common edits). A
// discrete surface made from a whole polysurface (a PolysurfaceSpec) follows the whole object,
// whatever its faces become (the watcher joins them again, or says why it cannot).
using System;

namespace Tpi.Logic
{
    /// <summary>What the source object is now.</summary>
    public enum SourceShape
    {
        /// <summary>No object with the source id (deleted, or not in this document).</summary>
        Missing,
        /// <summary>A surface (or a polysurface of one face).</summary>
        Surface,
        /// <summary>A polysurface of several faces.</summary>
        Polysurface,
        /// <summary>Anything else (a mesh, a curve, ...).</summary>
        Other,
    }

    /// <summary>The answer of <see cref="SourceFollow.Decide"/>.</summary>
    public sealed class FollowDecision
    {
        /// <summary>True: take the surface (face <see cref="FaceIndex"/>, or the object's surface when -1).</summary>
        public bool Follow { get; internal set; }
        /// <summary>The face to take (-1: the object's only surface).</summary>
        public int FaceIndex { get; internal set; }
        /// <summary>True: take the whole object (all its faces joined); <see cref="FaceIndex"/> is -1.</summary>
        public bool WholeObject { get; internal set; }
        /// <summary>Why it does not follow (null when it follows or follows nothing).</summary>
        public string Message { get; internal set; }
    }

    /// <summary>The watcher's decision, Rhino-free.</summary>
    public static class SourceFollow
    {
        /// <summary>
        /// The decision for <paramref name="document"/> whose source object now has the shape
        /// <paramref name="shape"/> with <paramref name="faceCount"/> faces (polysurfaces).
        /// </summary>
        public static FollowDecision Decide(DiscreteSurfaceDocument document, SourceShape shape, int faceCount)
        {
            if (document == null) throw new ArgumentNullException("document");
            if (document.SourceSurfaceId == Guid.Empty) return new FollowDecision { FaceIndex = -1 };
            int face = document.SourceFaceIndex;
            if (document.Surface is PolysurfaceSpec)
            {
                if (shape == SourceShape.Missing) return Refuse("its source object is not in this document; it keeps its own surface");
                if (shape == SourceShape.Other) return Refuse("its source object is no longer a surface");
                return new FollowDecision { Follow = true, FaceIndex = -1, WholeObject = true };
            }
            switch (shape)
            {
                case SourceShape.Missing:
                    return Refuse("its source object is not in this document; it keeps its own surface");
                case SourceShape.Surface:
                    if (face > 0) return Refuse("it follows face " + face + " of a polysurface, which is now a single surface");
                    return new FollowDecision { Follow = true, FaceIndex = face };
                case SourceShape.Polysurface:
                    if (face < 0)
                        return Refuse("it was made from a single surface, which is now a polysurface of " + faceCount +
                            " faces; which face to follow is ambiguous (run TpiDiscreteSurface on the face)");
                    if (face >= faceCount)
                        return Refuse("it follows face " + face + " of a polysurface that now has " + faceCount + " faces");
                    return new FollowDecision { Follow = true, FaceIndex = face };
                default:
                    return Refuse("its source object is no longer a surface");
            }
        }

        static FollowDecision Refuse(string message)
        {
            return new FollowDecision { FaceIndex = -1, Message = message };
        }
    }
}
