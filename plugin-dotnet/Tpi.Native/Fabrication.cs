using System;
using Tpi.Native.Interop;

namespace Tpi.Native
{
    /// <summary>Which side of the facets a panel is thickened to (TPI_SIDE_*).</summary>
    public enum PanelSide
    {
        /// <summary>Towards the centres of curvature (the concave side).</summary>
        Inside = 0,
        /// <summary>Away from the centres of curvature.</summary>
        Outside = 1,
    }

    /// <summary>The files of a fabrication (TPI_FILE_*).</summary>
    public enum FabricationFile
    {
        /// <summary>panels.json (the contract in docs/fabrication.md).</summary>
        PanelsJson = 0,
        /// <summary>panels.obj: one closed polyhedron per panel and cleat.</summary>
        PanelsObj = 1,
        /// <summary>sheets.svg: the nested flat parts.</summary>
        SheetsSvg = 2,
        /// <summary>sheets.dxf: the nested flat parts, ASCII DXF R2000.</summary>
        SheetsDxf = 3,
        /// <summary>bevels.csv: dihedral and bevel angles per joint.</summary>
        BevelsCsv = 4,
    }

    /// <summary>
    /// Panels made from a discretisation (TpiFabrication): solids of thickness T with mitred
    /// joints, cleat slots, flat parts nested on sheets, and toolpaths. Immutable.
    /// </summary>
    public sealed class Fabrication : IDisposable
    {
        readonly FabricationHandle _handle;

        Fabrication(FabricationHandle handle) { _handle = handle; }

        /// <summary>
        /// Panels of <paramref name="thickness"/> from <paramref name="mesh"/> (each facet's own
        /// plane, adjusted ones included), <paramref name="slotsPerEdge"/> cleat slots on every
        /// interior edge, nested on sheets of the given size with <paramref name="gap"/> between parts.
        /// </summary>
        public static Fabrication Create(Discretisation mesh, double thickness, PanelSide side, uint slotsPerEdge,
            double sheetWidth, double sheetHeight, double gap)
        {
            if (mesh == null) throw new ArgumentNullException("mesh");
            FabricationHandle h;
            var s = UnsafeNativeMethods.tpi_fabricate(mesh.Handle, thickness, (uint)side, slotsPerEdge, sheetWidth, sheetHeight, gap, out h);
            if (s != Status.Ok)
            {
                var error = new TpiException(s, TpiLibrary.LastErrorMessage(), "tpi_fabricate");
                if (h != null) h.Dispose();
                throw error;
            }
            h.Track();
            return new Fabrication(h);
        }

        /// <summary>Number of panels (one per facet).</summary>
        public int PanelCount { get { int panels, sheets; Counts(out panels, out sheets); return panels; } }

        /// <summary>Number of sheets the flat parts are nested on.</summary>
        public int SheetCount { get { int panels, sheets; Counts(out panels, out sheets); return sheets; } }

        void Counts(out int panels, out int sheets)
        {
            UIntPtr p, s;
            TpiLibrary.Check(UnsafeNativeMethods.tpi_fabrication_counts(_handle, out p, out s), "tpi_fabrication_counts");
            panels = checked((int)p.ToUInt64());
            sheets = checked((int)s.ToUInt64());
        }

        /// <summary>One of the files as text.</summary>
        public string File(FabricationFile file)
        {
            return TpiLibrary.CopyOutText((byte[] b, UIntPtr c, out UIntPtr n) =>
                UnsafeNativeMethods.tpi_fabrication_file(_handle, (uint)file, b, c, out n), "tpi_fabrication_file");
        }

        /// <summary>The G-code of the cut, for a tool of <paramref name="toolDiameter"/>.</summary>
        public string GCode(double toolDiameter)
        {
            return TpiLibrary.CopyOutText((byte[] b, UIntPtr c, out UIntPtr n) =>
                UnsafeNativeMethods.tpi_fabrication_gcode(_handle, toolDiameter, b, c, out n), "tpi_fabrication_gcode");
        }

        /// <summary>Whether the native object has been freed.</summary>
        public bool IsDisposed { get { return _handle.IsClosed; } }

        /// <inheritdoc/>
        public void Dispose() { _handle.Dispose(); }
    }
}
