using System;
using System.Collections.Generic;
using NUnit.Framework;
using Tpi.Native;

namespace Tpi.Tests
{
    /// <summary>
    /// Handles are released: 10,000 create/free cycles of all four handle kinds leave the
    /// binding's live-handle count at its start value and the process's resident memory
    /// (Linux /proc/self/statm) flat, while a control run that keeps its handles shows the
    /// growth a leak would cause.
    /// </summary>
    [TestFixture]
    public class LeakTests
    {
        const int Cycles = 10000;

        static void Cycle(List<IDisposable> keep)
        {
            var dome = TestData.Dome();
            var pattern = Pattern.Grid(3, 3);
            var mesh = Discretisation.Create(dome, pattern);
            var live = DiscreteSurface.Create(dome, pattern);
            live.MovePoint(0, 0.2, 0.2);
            live.Recompute();
            var snapshot = live.GetMesh();
            if (snapshot.FacetCount != 9 || mesh.VertexCount == 0) throw new Exception("unexpected mesh");
            // A change snapshot: its handle is created and freed inside TakeChanges.
            if (live.TakeChanges().FacetCount != 9) throw new Exception("unexpected changes");
            if (keep != null)
            {
                keep.Add(dome); keep.Add(pattern); keep.Add(mesh); keep.Add(live); keep.Add(snapshot);
                return;
            }
            snapshot.Dispose(); live.Dispose(); mesh.Dispose(); pattern.Dispose(); dome.Dispose();
        }

        static void Collect()
        {
            GC.Collect();
            GC.WaitForPendingFinalizers();
            GC.Collect();
        }

        [Test]
        public void TenThousandCreateFreeCyclesLeakNothing()
        {
            for (int i = 0; i < 2000; i++) Cycle(null); // warm up: JIT, allocator arenas, GC heap size
            Collect();
            long handlesBefore = TpiLibrary.LiveHandleCount;
            long rssBefore = TestData.ResidentBytes();
            for (int i = 0; i < Cycles; i++) Cycle(null);
            Collect();
            long rssAfter = TestData.ResidentBytes();
            long handlesAfter = TpiLibrary.LiveHandleCount;

            // Control: 2,000 cycles that keep every handle alive.
            var keep = new List<IDisposable>();
            long rssControlBefore = TestData.ResidentBytes();
            for (int i = 0; i < 2000; i++) Cycle(keep);
            long rssControlAfter = TestData.ResidentBytes();
            long liveKept = TpiLibrary.LiveHandleCount - handlesAfter;
            foreach (var d in keep) d.Dispose();
            Collect();

            double leakPerCycle = (rssControlAfter - rssControlBefore) / 2000.0;
            double growthPerCycle = (rssAfter - rssBefore) / (double)Cycles;
            Console.WriteLine("      leak check: {0} cycles, live handles {1} -> {2}, RSS {3:F1} -> {4:F1} MiB ({5:+0.0;-0.0} B/cycle); " +
                "control keeping {6} handles: {7:F0} B/cycle",
                Cycles, handlesBefore, handlesAfter, rssBefore / 1048576.0, rssAfter / 1048576.0, growthPerCycle, liveKept, leakPerCycle);
            Assert.AreEqual(handlesBefore, handlesAfter, "live handles after the cycles");
            Assert.AreEqual(10000, liveKept, "the control kept 5 handles per cycle");
            Assert.AreEqual(handlesBefore, TpiLibrary.LiveHandleCount, "control handles released");
            Assert.Greater(leakPerCycle, 1000.0, "the control shows what a leak looks like");
            Assert.Less(growthPerCycle, leakPerCycle / 20, "RSS growth per cycle is far below a leak's");
            Assert.Less(rssAfter - rssBefore, 8L << 20, "RSS grew by less than 8 MiB over 10,000 cycles");
        }

        [Test]
        public void FinalizerFreesForgottenHandles()
        {
            Collect();
            long before = TpiLibrary.LiveHandleCount;
            ForgetSome();
            Assert.AreEqual(before + 100, TpiLibrary.LiveHandleCount);
            Collect();
            // Mono scans stacks conservatively, so the last object may still look reachable.
            Assert.LessOrEqual(TpiLibrary.LiveHandleCount, before + 1);
        }

        static void ForgetSome()
        {
            for (int i = 0; i < 100; i++)
            {
                var p = Pattern.Grid(2, 2);
                GC.KeepAlive(p);
            }
        }
    }
}
