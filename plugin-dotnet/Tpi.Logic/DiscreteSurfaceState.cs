// The live state of one discrete surface in a document: its stored data (surface, pattern
// points, options) and the native TpiDiscreteSurface that computes its mesh, kept in step.
// Every edit goes to the library first, so an edit the library rejects (index out of range,
// NaN, a point outside the square) raises its TpiException and changes nothing here either.
//
// After each recompute the state takes the library's change snapshot (MeshChanges) into
// LiveMesh: a dragged point costs the few facets around it, not a copy of the whole mesh. The
// whole mesh (Mesh: with flags, seeds, the quality report, diagnostics) is copied out only when
// it is asked for, once per recompute.
using System;
using System.Collections.Generic;
using System.Linq;
using Tpi.Native;

namespace Tpi.Logic
{
    /// <summary>A discrete surface being edited: document data + native object + undo history.</summary>
    public sealed class DiscreteSurfaceState : IDisposable
    {
        readonly DiscreteSurfaceDocument _document;
        DiscreteSurface _native;
        readonly Stack<EditRecord> _undo = new Stack<EditRecord>();
        readonly Stack<EditRecord> _redo = new Stack<EditRecord>();
        readonly object _lock = new object();
        readonly LiveMeshData _live = new LiveMeshData();
        MeshData _mesh;

        /// <summary>
        /// Creates the native object and computes the first mesh. Raises the library's
        /// TpiException if the surface or the pattern is invalid.
        /// </summary>
        public DiscreteSurfaceState(DiscreteSurfaceDocument document)
        {
            if (document == null) throw new ArgumentNullException("document");
            if (document.Surface == null) throw new ArgumentException("the document has no surface", "document");
            _document = document.Clone();
            if (_document.Options == null) _document.Options = DiscretisationOptions.Default();
            using (var surface = _document.Surface.CreateNative())
            using (var pattern = Pattern.FromPoints(_document.Points))
                _native = DiscreteSurface.Create(surface, pattern, _document.Options);
            _live.Apply(_native.TakeChanges());
        }

        /// <summary>Shorthand: a state from a surface and points with the library's default options.</summary>
        public DiscreteSurfaceState(SurfaceSpec surface, IEnumerable<PatternPoint> points, DiscretisationOptions options = null)
            : this(new DiscreteSurfaceDocument { Surface = surface, Points = points.ToList(), Options = options })
        {
        }

        /// <summary>Reads a state from user-data bytes (<see cref="UserDataFormat"/>).</summary>
        public static DiscreteSurfaceState FromBytes(byte[] bytes)
        {
            return new DiscreteSurfaceState(UserDataFormat.Read(bytes));
        }

        /// <summary>The stored data as user-data bytes (<see cref="UserDataFormat"/>).</summary>
        public byte[] ToBytes() { return UserDataFormat.Write(Document); }

        /// <summary>A copy of the stored data.</summary>
        public DiscreteSurfaceDocument Document { get { lock (_lock) return _document.Clone(); } }

        /// <summary>The surface.</summary>
        public SurfaceSpec Surface { get { return _document.Surface; } }

        /// <summary>The current pattern points (edits included, recomputed or not).</summary>
        public IReadOnlyList<PatternPoint> Points { get { lock (_lock) return _document.Points.ToArray(); } }

        /// <summary>The options.</summary>
        public DiscretisationOptions Options { get { return _document.Options.Clone(); } }

        /// <summary>
        /// The mesh of the last successful recompute, copied out of the library whole (O(n)) the
        /// first time it is asked for after each recompute. What a drag redraws is <see cref="LiveMesh"/>.
        /// </summary>
        public MeshData Mesh
        {
            get
            {
                lock (_lock)
                {
                    if (_mesh == null)
                        using (var mesh = Native.GetMesh()) _mesh = MeshData.From(mesh);
                    return _mesh;
                }
            }
        }

        /// <summary>
        /// The mesh of the last successful recompute kept in step with the library's changes
        /// (vertex positions, facet loops and planes; updated in place by each recompute, for
        /// <see cref="PanelDisplay.Update(LiveMeshData)"/>). Read it on the thread that recomputes.
        /// </summary>
        public LiveMeshData LiveMesh { get { return _live; } }

        /// <summary>Edits not yet recomputed.</summary>
        public int PendingEdits { get { return Native.PendingEdits; } }

        /// <summary>True if there is an edit to undo.</summary>
        public bool CanUndo { get { return _undo.Count > 0; } }

        /// <summary>True if there is an undone edit to redo.</summary>
        public bool CanRedo { get { return _redo.Count > 0; } }

        DiscreteSurface Native
        {
            get
            {
                if (_native == null) throw new ObjectDisposedException("DiscreteSurfaceState");
                return _native;
            }
        }

        /// <summary>Moves point <paramref name="index"/> to (s, t) (pending until <see cref="Recompute"/>).</summary>
        public EditRecord MovePoint(int index, double s, double t)
        {
            lock (_lock)
            {
                Native.MovePoint(index, s, t); // the library validates first
                var edit = new MovePointEdit(index, _document.Points[index], new PatternPoint(s, t));
                _document.Points[index] = edit.To;
                return Recorded(edit);
            }
        }

        /// <summary>Appends (s, t); returns its index.</summary>
        public int AddPoint(double s, double t)
        {
            lock (_lock)
            {
                int index = Native.AddPoint(s, t);
                _document.Points.Add(new PatternPoint(s, t));
                Recorded(new InsertPointEdit(index, new PatternPoint(s, t)));
                return index;
            }
        }

        /// <summary>Removes point <paramref name="index"/>; later points move down by one.</summary>
        public EditRecord RemovePoint(int index)
        {
            lock (_lock)
            {
                Native.RemovePoint(index);
                var edit = new RemovePointEdit(index, _document.Points[index]);
                _document.Points.RemoveAt(index);
                return Recorded(edit);
            }
        }

        /// <summary>Replaces the surface (e.g. its control points were edited in Rhino); the points keep their (s, t).</summary>
        public EditRecord ReplaceSurface(SurfaceSpec surface)
        {
            if (surface == null) throw new ArgumentNullException("surface");
            lock (_lock)
            {
                var edit = new ReplaceSurfaceEdit(_document.Surface, surface);
                ApplyReplaceSurface(surface);
                return Recorded(edit);
            }
        }

        /// <summary>Applies a recorded edit (e.g. from another state) as a new undoable edit.</summary>
        public void Apply(EditRecord edit)
        {
            lock (_lock)
            {
                edit.Apply(this);
                Recorded(edit);
            }
        }

        EditRecord Recorded(EditRecord edit)
        {
            _undo.Push(edit);
            _redo.Clear();
            return edit;
        }

        /// <summary>Undoes the last edit (pending until <see cref="Recompute"/>); false if there is none.</summary>
        public bool Undo()
        {
            lock (_lock)
            {
                if (_undo.Count == 0) return false;
                var edit = _undo.Pop();
                edit.Inverse().Apply(this);
                _redo.Push(edit);
                return true;
            }
        }

        /// <summary>Redoes the last undone edit; false if there is none.</summary>
        public bool Redo()
        {
            lock (_lock)
            {
                if (_redo.Count == 0) return false;
                var edit = _redo.Pop();
                edit.Apply(this);
                _undo.Push(edit);
                return true;
            }
        }

        /// <summary>
        /// Brings the mesh up to date and returns it (copied out whole: see <see cref="Mesh"/>).
        /// On a TpiException (e.g. a moved point now duplicates another) the edits stay pending
        /// and <see cref="Mesh"/> stays the previous one.
        /// </summary>
        public MeshData Recompute()
        {
            lock (_lock)
            {
                RecomputeChanges();
                return Mesh;
            }
        }

        /// <summary>
        /// Brings the mesh up to date and applies the library's changes to <see cref="LiveMesh"/>;
        /// returns the facets they listed (empty when nothing was pending). The whole mesh is not
        /// copied. On a TpiException the edits stay pending and nothing changes here.
        /// </summary>
        public int[] RecomputeChanges()
        {
            lock (_lock)
            {
                if (Native.PendingEdits == 0) return new int[0];
                Native.Recompute();
                _mesh = null;
                return _live.Apply(Native.TakeChanges());
            }
        }

        /// <summary>
        /// Like <see cref="RecomputeChanges"/> (the whole mesh is not copied), but reports failure
        /// as the library's message.
        /// </summary>
        public bool TryRecompute(out string error)
        {
            try
            {
                RecomputeChanges();
                error = null;
                return true;
            }
            catch (TpiException e)
            {
                error = e.NativeMessage;
                return false;
            }
        }

        // ---- edits as the undo records apply them (no recording) ----------------------

        internal void ApplyMove(int index, PatternPoint to)
        {
            Native.MovePoint(index, to.S, to.T);
            _document.Points[index] = to;
        }

        internal void ApplyRemove(int index)
        {
            Native.RemovePoint(index);
            _document.Points.RemoveAt(index);
        }

        internal void ApplyInsert(int index, PatternPoint point)
        {
            if (index < 0 || index > _document.Points.Count)
                throw new ArgumentOutOfRangeException("index", index, "there are " + _document.Points.Count + " points");
            // The library only appends: append, then shift the later points up one place by
            // moves (duplicates in between are fine: only a recompute checks for them).
            int last = Native.AddPoint(point.S, point.T);
            for (int k = last; k > index; k--)
            {
                var p = _document.Points[k - 1];
                Native.MovePoint(k, p.S, p.T);
            }
            if (index < last) Native.MovePoint(index, point.S, point.T);
            _document.Points.Insert(index, point);
        }

        internal void ApplyReplaceSurface(SurfaceSpec surface)
        {
            using (var native = surface.CreateNative()) Native.ReplaceSurface(native);
            _document.Surface = surface;
        }

        /// <summary>Frees the native object.</summary>
        public void Dispose()
        {
            lock (_lock)
            {
                if (_native != null) _native.Dispose();
                _native = null;
            }
        }
    }
}
