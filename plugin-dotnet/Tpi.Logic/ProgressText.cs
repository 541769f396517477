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

        /// <summary>
        /// "run k: " and <see cref="Format"/>: the progress of the k-th of the many
        /// discretisations a pattern made on a surface runs (a fit, a relaxation).
        /// </summary>
        public static string FormatRun(int run, DiscretisationProgress progress)
        {
            return "run " + run + ": " + Format(progress);
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

        readonly bool _countRuns;

        /// <summary>Hands new texts to <paramref name="show"/>.</summary>
        public ProgressMessages(Action<string> show) : this(show, false)
        {
        }

        /// <summary>
        /// Hands new texts to <paramref name="show"/>; with <paramref name="countRuns"/>, for
        /// a call that runs many discretisations, each start of a samples stage begins the next
        /// run and the texts are <see cref="ProgressText.FormatRun"/>'s.
        /// </summary>
        public ProgressMessages(Action<string> show, bool countRuns)
        {
            if (show == null) throw new ArgumentNullException("show");
            _show = show;
            _countRuns = countRuns;
        }

        /// <summary>The discretisations seen to start so far (counted only with countRuns).</summary>
        public int Runs { get; private set; }

        /// <summary>The number of texts handed on so far.</summary>
        public int Shown { get; private set; }

        /// <summary>Takes one report.</summary>
        public void Report(DiscretisationProgress progress)
        {
            string text;
            lock (this)
            {
                if (_countRuns && progress.Stage == Stage.Samples && progress.Done == 0) Runs++;
                text = _countRuns ? ProgressText.FormatRun(Runs, progress) : ProgressText.Format(progress);
                if (text == _last) return;
                _last = text;
                Shown++;
            }
            _show(text);
        }
    }
}
