// What the Rhino plug-in does to keep a discrete surface a discrete surface, decided without
// RhinoCommon so it is tested here:
//
// - A .3dm stores the mesh and its user data, not the managed class. After open, paste,
//   import or worksession attach an object comes back as a plain mesh object carrying the
//   discrete surface's data: it is upgraded (replaced by a DiscreteSurfaceObject) when the
//   document is idle again (the document must not be changed inside its own events).
// - User data of an older format is read and stored again in the current one (migration).
// - Data that cannot be read (newer plug-in, damaged) leaves a plain mesh and one message.
// - The source-surface watcher's state: which sources changed, which objects wait for an
//   upgrade or a recompute, per document (Rhino for Mac has several documents open).
using System;
using System.Collections.Generic;
using System.Linq;

namespace Tpi.Logic
{
    /// <summary>What to do with one object.</summary>
    public enum UpgradeAction
    {
        /// <summary>Nothing: not ours, or already a discrete surface with current data.</summary>
        Keep,
        /// <summary>Replace it by a discrete surface object showing the same mesh (and store the data again if it was migrated).</summary>
        Upgrade,
        /// <summary>It carries our data but the data cannot be used: leave it and tell the user once (<see cref="UpgradeDecision.Message"/>).</summary>
        Refuse,
    }

    /// <summary>The decision for one object.</summary>
    public sealed class UpgradeDecision
    {
        /// <summary>What to do.</summary>
        public UpgradeAction Action { get; internal set; }
        /// <summary>The stored document (Upgrade, and Keep of a current discrete surface), else null.</summary>
        public DiscreteSurfaceDocument Document { get; internal set; }
        /// <summary>The format version found in the data (0 when there was none or it was unreadable).</summary>
        public int FoundVersion { get; internal set; }
        /// <summary>True when the data was of an older format: store <see cref="Document"/> again.</summary>
        public bool Migrated { get { return FoundVersion != 0 && FoundVersion < UserDataFormat.FormatVersion; } }
        /// <summary>Why (Refuse), or null.</summary>
        public string Message { get; internal set; }
    }

    /// <summary>Which objects become discrete surface objects.</summary>
    public static class DiscreteSurfaceUpgrade
    {
        /// <summary>
        /// The decision for an object whose geometry is a mesh (<paramref name="isMesh"/>),
        /// whose managed class is or is not already the discrete surface object, and whose
        /// geometry carries <paramref name="userData"/> (the discrete surface user data's bytes,
        /// null when it has none).
        /// </summary>
        public static UpgradeDecision Decide(bool isMesh, bool isDiscreteSurfaceObject, byte[] userData)
        {
            if (userData == null) return new UpgradeDecision { Action = UpgradeAction.Keep };
            if (!isMesh)
                return new UpgradeDecision { Action = UpgradeAction.Refuse, Message = "carries discrete surface data but is not a mesh; left as it is" };
            DiscreteSurfaceDocument document;
            ushort version;
            try
            {
                document = UserDataFormat.Read(userData, out version);
            }
            catch (FormatException e)
            {
                return new UpgradeDecision
                {
                    Action = UpgradeAction.Refuse,
                    Message = "stays a plain mesh: its discrete surface data cannot be read (" + e.Message + ")",
                };
            }
            var decision = new UpgradeDecision { Document = document, FoundVersion = version };
            decision.Action = !isDiscreteSurfaceObject || decision.Migrated ? UpgradeAction.Upgrade : UpgradeAction.Keep;
            return decision;
        }
    }

    /// <summary>The work one document has waiting, taken at once by <see cref="DocumentWorkQueue.Take"/>.</summary>
    public sealed class DocumentWork
    {
        /// <summary>The document's runtime serial number.</summary>
        public uint Document { get; internal set; }
        /// <summary>Objects to pass to <see cref="DiscreteSurfaceUpgrade.Decide"/>, in the order they came.</summary>
        public IReadOnlyList<Guid> Upgrades { get; internal set; }
        /// <summary>Source surface objects that were replaced (edited): their followers recompute.</summary>
        public IReadOnlyList<Guid> ChangedSources { get; internal set; }
        /// <summary>Discrete surfaces to recompute (e.g. after a transform that is not a similarity).</summary>
        public IReadOnlyList<Guid> Recompute { get; internal set; }
        /// <summary>True if there is nothing to do.</summary>
        public bool IsEmpty { get { return Upgrades.Count == 0 && ChangedSources.Count == 0 && Recompute.Count == 0; } }
    }

    /// <summary>
    /// Per-document bookkeeping of the plug-in's event handlers (thread-safe: Rhino raises
    /// some events off the UI thread). Events only record; the Idle handler takes a document's
    /// work and does it inside one undo record.
    /// </summary>
    public sealed class DocumentWorkQueue
    {
        /// <summary>Ids in the order they came, each once (a file read may report an object twice).</summary>
        sealed class OrderedIds
        {
            readonly List<Guid> _order = new List<Guid>();
            readonly HashSet<Guid> _set = new HashSet<Guid>();
            public int Count { get { return _order.Count; } }
            public void Add(Guid id) { if (id != Guid.Empty && _set.Add(id)) _order.Add(id); }
            public Guid[] Take() { var ids = _order.ToArray(); _order.Clear(); _set.Clear(); return ids; }
        }

        sealed class PerDocument
        {
            public readonly OrderedIds Upgrades = new OrderedIds();
            public readonly OrderedIds ChangedSources = new OrderedIds();
            public readonly OrderedIds Recompute = new OrderedIds();
            public readonly HashSet<Guid> Reported = new HashSet<Guid>();
            public bool Opening;
        }

        readonly object _lock = new object();
        readonly Dictionary<uint, PerDocument> _documents = new Dictionary<uint, PerDocument>();

        PerDocument Get(uint document)
        {
            PerDocument state;
            if (!_documents.TryGetValue(document, out state)) _documents[document] = state = new PerDocument();
            return state;
        }

        /// <summary>
        /// A document starts reading a file (open, import, worksession attach): objects added
        /// until <see cref="EndOpen"/> are still recorded, but <see cref="HasWork"/> says no for
        /// it, so nothing runs half-way through the read.
        /// </summary>
        public void BeginOpen(uint document) { lock (_lock) Get(document).Opening = true; }

        /// <summary>The read is finished; the objects it added can be upgraded.</summary>
        public void EndOpen(uint document) { lock (_lock) Get(document).Opening = false; }

        /// <summary>
        /// An object was added (new, pasted, imported, read from a file, undeleted by undo).
        /// Recorded only if its geometry carries discrete surface data and it is not already a
        /// discrete surface object (our own replacements add discrete surface objects and are
        /// ignored, so an upgrade never feeds itself).
        /// </summary>
        public void ObjectAdded(uint document, Guid id, bool carriesData, bool isDiscreteSurfaceObject)
        {
            if (!carriesData || isDiscreteSurfaceObject) return;
            lock (_lock) Get(document).Upgrades.Add(id);
        }

        /// <summary>
        /// An object was replaced. If the new object is a discrete surface nothing follows
        /// (it is our own update, or an edit of the discrete surface itself); otherwise the old
        /// object's id may be a source that discrete surfaces follow.
        /// </summary>
        public void ObjectReplaced(uint document, Guid id, bool newIsDiscreteSurfaceObject)
        {
            if (newIsDiscreteSurfaceObject) return;
            lock (_lock) Get(document).ChangedSources.Add(id);
        }

        /// <summary>A discrete surface must be recomputed from its stored data.</summary>
        public void RecomputeLater(uint document, Guid id)
        {
            lock (_lock) Get(document).Recompute.Add(id);
        }

        /// <summary>The document closed: everything recorded for it is dropped.</summary>
        public void DocumentClosed(uint document) { lock (_lock) _documents.Remove(document); }

        /// <summary>True if <paramref name="document"/> has work and is not in the middle of reading a file.</summary>
        public bool HasWork(uint document)
        {
            lock (_lock)
            {
                PerDocument state;
                return _documents.TryGetValue(document, out state) && !state.Opening
                    && (state.Upgrades.Count > 0 || state.ChangedSources.Count > 0 || state.Recompute.Count > 0);
            }
        }

        /// <summary>The documents that have work now, in ascending serial order.</summary>
        public IReadOnlyList<uint> DocumentsWithWork()
        {
            lock (_lock) return _documents.Keys.Where(HasWorkLocked).OrderBy(d => d).ToArray();
        }

        bool HasWorkLocked(uint document)
        {
            var state = _documents[document];
            return !state.Opening && (state.Upgrades.Count > 0 || state.ChangedSources.Count > 0 || state.Recompute.Count > 0);
        }

        /// <summary>Takes (and clears) the work of <paramref name="document"/>; empty while it is reading a file.</summary>
        public DocumentWork Take(uint document)
        {
            lock (_lock)
            {
                PerDocument state;
                var work = new DocumentWork { Document = document, Upgrades = new Guid[0], ChangedSources = new Guid[0], Recompute = new Guid[0] };
                if (!_documents.TryGetValue(document, out state) || state.Opening) return work;
                work.Upgrades = state.Upgrades.Take();
                work.ChangedSources = state.ChangedSources.Take();
                // An upgrade recomputes nothing, so a recompute asked for an object that is also
                // upgraded still runs after it.
                work.Recompute = state.Recompute.Take();
                return work;
            }
        }

        /// <summary>True the first time it is asked for (document, object): report a refusal once, not on every event.</summary>
        public bool ShouldReport(uint document, Guid id)
        {
            lock (_lock) return Get(document).Reported.Add(id);
        }
    }
}
