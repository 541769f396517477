// Undo records of a discrete surface: each edit knows how to apply itself and its inverse.
// The Rhino plugin records them inside TpiEditPattern (its own Undo option) and Rhino's undo
// covers the command as a whole through the object replace.
using System;
using System.Collections.Generic;
using System.Linq;
using Tpi.Native;

namespace Tpi.Logic
{
    /// <summary>One undoable edit.</summary>
    public abstract class EditRecord
    {
        /// <summary>What the edit did, for the command line ("move point 3").</summary>
        public abstract string Description { get; }
        /// <summary>Applies the edit.</summary>
        internal abstract void Apply(DiscreteSurfaceState state);
        /// <summary>The edit that undoes this one.</summary>
        public abstract EditRecord Inverse();
    }

    /// <summary>Point Index moved from From to To.</summary>
    public sealed class MovePointEdit : EditRecord
    {
        /// <summary>The point.</summary>
        public int Index { get; private set; }
        /// <summary>Where it was.</summary>
        public PatternPoint From { get; private set; }
        /// <summary>Where it goes.</summary>
        public PatternPoint To { get; private set; }
        /// <summary>Makes the record.</summary>
        public MovePointEdit(int index, PatternPoint from, PatternPoint to) { Index = index; From = from; To = to; }
        /// <inheritdoc/>
        public override string Description { get { return "move point " + Index; } }
        internal override void Apply(DiscreteSurfaceState state) { state.ApplyMove(Index, To); }
        /// <inheritdoc/>
        public override EditRecord Inverse() { return new MovePointEdit(Index, To, From); }
    }

    /// <summary>Point inserted at Index (appended when Index is the point count).</summary>
    public sealed class InsertPointEdit : EditRecord
    {
        /// <summary>Its index.</summary>
        public int Index { get; private set; }
        /// <summary>The point.</summary>
        public PatternPoint Point { get; private set; }
        /// <summary>Makes the record.</summary>
        public InsertPointEdit(int index, PatternPoint point) { Index = index; Point = point; }
        /// <inheritdoc/>
        public override string Description { get { return "add point " + Index; } }
        internal override void Apply(DiscreteSurfaceState state) { state.ApplyInsert(Index, Point); }
        /// <inheritdoc/>
        public override EditRecord Inverse() { return new RemovePointEdit(Index, Point); }
    }

    /// <summary>Point Index (which was at Point) removed.</summary>
    public sealed class RemovePointEdit : EditRecord
    {
        /// <summary>Its index.</summary>
        public int Index { get; private set; }
        /// <summary>Where it was.</summary>
        public PatternPoint Point { get; private set; }
        /// <summary>Makes the record.</summary>
        public RemovePointEdit(int index, PatternPoint point) { Index = index; Point = point; }
        /// <inheritdoc/>
        public override string Description { get { return "remove point " + Index; } }
        internal override void Apply(DiscreteSurfaceState state) { state.ApplyRemove(Index); }
        /// <inheritdoc/>
        public override EditRecord Inverse() { return new InsertPointEdit(Index, Point); }
    }

    /// <summary>The surface replaced.</summary>
    public sealed class ReplaceSurfaceEdit : EditRecord
    {
        /// <summary>The old surface.</summary>
        public SurfaceSpec From { get; private set; }
        /// <summary>The new surface.</summary>
        public SurfaceSpec To { get; private set; }
        /// <summary>Makes the record.</summary>
        public ReplaceSurfaceEdit(SurfaceSpec from, SurfaceSpec to) { From = from; To = to; }
        /// <inheritdoc/>
        public override string Description { get { return "replace surface"; } }
        internal override void Apply(DiscreteSurfaceState state) { state.ApplyReplaceSurface(To); }
        /// <inheritdoc/>
        public override EditRecord Inverse() { return new ReplaceSurfaceEdit(To, From); }
    }

    /// <summary>Several edits made as one (e.g. several grips dragged together).</summary>
    public sealed class CompoundEdit : EditRecord
    {
        readonly EditRecord[] _edits;
        /// <summary>Makes the record.</summary>
        public CompoundEdit(IEnumerable<EditRecord> edits) { _edits = edits.ToArray(); }
        /// <summary>The parts, in order.</summary>
        public IReadOnlyList<EditRecord> Edits { get { return Array.AsReadOnly(_edits); } }
        /// <inheritdoc/>
        public override string Description { get { return string.Join(", ", _edits.Select(e => e.Description)); } }
        internal override void Apply(DiscreteSurfaceState state) { foreach (var e in _edits) e.Apply(state); }
        /// <inheritdoc/>
        public override EditRecord Inverse() { return new CompoundEdit(_edits.Reverse().Select(e => e.Inverse())); }
    }
}
