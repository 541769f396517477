// What a long discretisation shows under its Grasshopper component while it runs: the stage
// and how far it is, as short text ("4/6 facets 42%"), and the text of a cancelled solve.
// Rhino-free, so the Mono tests check it.
using System;
using System.Threading;
using Tpi.Native;

namespace Tpi.Logic
{
    /// <summary>The component message of a running or cancelled discretisation.</summary>
    public static class ProgressText
    {
        /// <summary>Number of stages a discretisation can report (TPI_STAGE_SAMPLES ... TPI_STAGE_REPORT).</summary>
        public const int StageCount = 6;

        /// <summary>The stage's name as the library and `tpi bench` write it ("samples" ... "report").</summary>
        public static string StageName(Stage stage)
        {
            switch (stage)
            {
                case Stage.Samples: return "samples";
                case Stage.Delaunay: return "delaunay";
                case Stage.Neighbours: return "neighbours";
                case Stage.Facets: return "facets";
                case Stage.Mesh: return "mesh";
                case Stage.Report: return "report";
                default: return "stage " + (uint)stage;
            }
        }

        /// <summary>
        /// "k/6 name p%": the stage's place in the pipeline, its name, and the share of its
        /// items done in whole percent rounded down (100% only when all are done); without the
        /// percentage when the stage cannot count its items (Total 0).
        /// </summary>
        public static string Format(DiscretisationProgress progress)
        {
            string head = ((uint)progress.Stage + 1) + "/" + StageCount + " " + StageName(progress.Stage);
            if (progress.Total == 0) return head;
            ulong done = Math.Min(progress.Done, progress.Total);
            // done * 100 cannot overflow for any real count (< 2^57 items).
            ulong percent = done * 100 / progress.Total;
            return head + " " + percent + "%";
        }

        /// <summary>The message of a cancelled solve.</summary>
        public const string Cancelled = "cancelled";
    }

    /// <summary>
    /// Turns a discretisation's progress reports into message texts and hands each text on
    /// only when it differs from the last one (a stage of a million items reports at most
    /// about a hundred times, each percent once). Safe to call from several threads.
    /// </summary>
    public sealed class ProgressMessages
    {
        readonly Action<string> _show;
        string _last;

        /// <summary>Hands new texts to <paramref name="show"/>.</summary>
        public ProgressMessages(Action<string> show)
        {
            if (show == null) throw new ArgumentNullException("show");
            _show = show;
        }

        /// <summary>The number of texts handed on so far.</summary>
        public int Shown { get; private set; }

        /// <summary>Takes one report.</summary>
        public void Report(DiscretisationProgress progress)
        {
            var text = ProgressText.Format(progress);
            lock (this)
            {
                if (text == _last) return;
                _last = text;
                Shown++;
            }
            _show(text);
        }
    }
}
