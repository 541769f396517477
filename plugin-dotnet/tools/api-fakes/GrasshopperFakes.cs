// Fakes of the Grasshopper 8 members the components use (stubs and the Grasshopper SDK
// reference), for the Mono type check of the components only. Every member here is itself
// checked against the typed stubs (tools/api-check, see API-CHECK.md), except those listed with
// their reason in tools/api-check/not-in-stubs.txt.
#pragma warning disable 67, 649, 1591
using System;
using System.Collections;
using System.Collections.Generic;
using System.Drawing;
using System.Threading;
using System.Threading.Tasks;

namespace Grasshopper
{
    public static class Instances
    {
        public static Kernel.GH_ComponentServer ComponentServer { get { return null; } }
        public static void RedrawCanvas() { }
    }
}

namespace Grasshopper.Kernel
{
    public enum GH_Exposure { hidden = -1, primary = 2, secondary = 4, tertiary = 8, quarternary = 16, quinary = 32, senary = 64, septenary = 128, octonary = 256, last = 256, dropdown = 65536, obscure = 65536 }
    public enum GH_ParamAccess { item = 0, list = 1, tree = 2 }
    public enum GH_RuntimeMessageLevel { Blank = 0, Warning = 10, Error = 20, Remark = 255 }

    public interface IGH_Param
    {
        bool Optional { get; set; }
    }

    public interface IGH_DataAccess
    {
        bool GetData<T>(int index, ref T destination);
        bool GetDataList<T>(int index, List<T> list);
        bool SetData(int paramIndex, object data);
        bool SetDataList(int paramIndex, IEnumerable data);
    }

    public class GH_ComponentServer
    {
        public GH_AssemblyInfo FindAssembly(Guid libraryId) { return null; }
    }

    public abstract class GH_AssemblyInfo
    {
        public string Location { get { return null; } }
        public virtual string Name { get { return null; } }
        public virtual Bitmap Icon { get { return null; } }
        public virtual string Description { get { return null; } }
        public virtual Guid Id { get { return Guid.Empty; } }
        public virtual string AuthorName { get { return null; } }
        public virtual string AuthorContact { get { return null; } }
        public virtual string Version { get { return null; } }
    }

    public abstract class GH_Component
    {
        protected GH_Component(string name, string nickname, string description, string category, string subCategory) { }
        public abstract Guid ComponentGuid { get; }
        protected virtual Bitmap Icon { get { return null; } }
        protected abstract void RegisterInputParams(GH_InputParamManager pManager);
        protected abstract void RegisterOutputParams(GH_OutputParamManager pManager);
        protected abstract void SolveInstance(IGH_DataAccess DA);
        public void AddRuntimeMessage(GH_RuntimeMessageLevel level, string text) { }
        public virtual GH_Exposure Exposure { get { return GH_Exposure.primary; } }
        public string Message { get; set; }

        protected class GH_InputParamManager
        {
            public IGH_Param this[int index] { get { return null; } }
            public int AddSurfaceParameter(string name, string nickname, string description, GH_ParamAccess access) { return 0; }
            public int AddBrepParameter(string name, string nickname, string description, GH_ParamAccess access) { return 0; }
            public int AddPointParameter(string name, string nickname, string description, GH_ParamAccess access) { return 0; }
            public int AddBooleanParameter(string name, string nickname, string description, GH_ParamAccess access, bool @default) { return 0; }
            public int AddTextParameter(string name, string nickname, string description, GH_ParamAccess access) { return 0; }
            public int AddTextParameter(string name, string nickname, string description, GH_ParamAccess access, string @default) { return 0; }
            public int AddIntegerParameter(string name, string nickname, string description, GH_ParamAccess access, int @default) { return 0; }
            public int AddNumberParameter(string name, string nickname, string description, GH_ParamAccess access, double @default) { return 0; }
            public int AddNumberParameter(string name, string nickname, string description, GH_ParamAccess access) { return 0; }
            public int AddGenericParameter(string name, string nickname, string description, GH_ParamAccess access) { return 0; }
        }

        protected class GH_OutputParamManager
        {
            public int AddCurveParameter(string name, string nickname, string description, GH_ParamAccess access) { return 0; }
            public int AddPlaneParameter(string name, string nickname, string description, GH_ParamAccess access) { return 0; }
            public int AddMeshParameter(string name, string nickname, string description, GH_ParamAccess access) { return 0; }
            public int AddTextParameter(string name, string nickname, string description, GH_ParamAccess access) { return 0; }
            public int AddGenericParameter(string name, string nickname, string description, GH_ParamAccess access) { return 0; }
            public int AddPointParameter(string name, string nickname, string description, GH_ParamAccess access) { return 0; }
            public int AddNumberParameter(string name, string nickname, string description, GH_ParamAccess access) { return 0; }
            public int AddIntegerParameter(string name, string nickname, string description, GH_ParamAccess access) { return 0; }
        }
    }

    public abstract class GH_TaskCapableComponent<T> : GH_Component
    {
        protected GH_TaskCapableComponent(string name, string nickname, string description, string category, string subCategory)
            : base(name, nickname, description, category, subCategory) { }
        public bool InPreSolve { get; set; }
        protected List<Task<T>> TaskList { get { return null; } }
        protected CancellationToken CancelToken { get { return CancellationToken.None; } }
        protected bool GetSolveResults(IGH_DataAccess data, out T result) { result = default(T); return false; }
    }
}

namespace Grasshopper.Kernel.Types
{
    public class GH_ObjectWrapper
    {
        public GH_ObjectWrapper(object obj) { }
        public object Value { get; set; }
    }
}
