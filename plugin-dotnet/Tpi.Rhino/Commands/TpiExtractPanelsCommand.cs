// Checked against: RhinoCommon 8 (rhino-stubs-typed 8.20.25157). Members used: read from
// the compiled adapter and checked against the stubs (plugin-dotnet/API-CHECK.md).
using Rhino;
using Rhino.Commands;
using Rhino.DocObjects;
using Rhino.Input;
using Rhino.Input.Custom;
using Tpi.Logic;

namespace Tpi.RhinoPlugIn
{
    /// <summary>TpiExtractPanels: bake the planar panels of discrete surfaces as closed polylines or as a mesh with n-gons.</summary>
    public sealed class TpiExtractPanelsCommand : Command
    {
        static int s_output; // 0: polylines, 1: mesh

        /// <inheritdoc/>
        public override string EnglishName { get { return "TpiExtractPanels"; } }

        /// <inheritdoc/>
        protected override Result RunCommand(RhinoDoc doc, RunMode mode)
        {
            var get = new GetObject();
            get.SetCommandPrompt("Select discrete surfaces");
            get.GeometryFilter = ObjectType.Mesh;
            get.SetCustomGeometryFilter((obj, geometry, ci) => DiscreteSurfaceObject.IsDiscreteSurface(obj));
            int outputIndex = get.AddOptionList("Output", new[] { "Polylines", "Mesh" }, s_output);
            while (true)
            {
                var result = get.GetMultiple(1, 0);
                if (result == GetResult.Option)
                {
                    if (get.Option().Index == outputIndex) s_output = get.Option().CurrentListOptionIndex;
                    continue;
                }
                if (result != GetResult.Object) return get.CommandResult();
                break;
            }

            int panels = 0;
            for (int i = 0; i < get.ObjectCount; i++)
            {
                var document = DiscreteSurfaceObject.StoredDocumentOf(get.Object(i).Object());
                if (document == null) continue;
                MeshData mesh;
                try
                {
                    // The stored data recomputes to exactly the mesh that was shown.
                    using (var state = new DiscreteSurfaceState(document)) mesh = state.Mesh;
                }
                catch (Tpi.Native.TpiException e)
                {
                    RhinoApp.WriteLine("TPI: " + e.NativeMessage);
                    continue;
                }
                if (s_output == 0)
                {
                    foreach (var polyline in MeshConversion.FacetPolylines(mesh))
                        doc.Objects.AddPolyline(RhinoConvert.ToPolyline(polyline));
                }
                else
                {
                    doc.Objects.AddMesh(RhinoConvert.ToMesh(mesh));
                }
                panels += mesh.FacetCount;
            }
            RhinoApp.WriteLine("TPI: extracted {0} panels.", panels);
            doc.Views.Redraw();
            return Result.Success;
        }
    }
}
