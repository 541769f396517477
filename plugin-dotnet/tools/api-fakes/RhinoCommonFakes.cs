// Fakes of the RhinoCommon 8 members the Rhino adapters use, with the C# signatures the stubs
// and the RhinoCommon source give. Bodies do nothing. They exist only so
// tests/run_dotnet_tests.sh can type-check the Rhino adapters with Mono (no RhinoCommon here):
// a call the adapters make that is not here, or that does not match its signature, fails that
// check. Every member here is itself checked against the typed stubs (tools/api-check, see
// API-CHECK.md), so the fakes cannot drift from the real API.
#pragma warning disable 67, 649, 1591
using System;
using System.Collections.Generic;
using System.Drawing;

namespace Rhino
{
    public enum UnitSystem { Microns = 1, Millimeters = 2, Centimeters = 3, Meters = 4, Kilometers = 5, Inches = 8, Feet = 9, Miles = 10, Yards = 19 }

    public class RhinoDoc
    {
        public static RhinoDoc ActiveDoc { get { return null; } }
        public UnitSystem ModelUnitSystem { get; set; }
        public DocObjects.Tables.LayerTable Layers { get { return null; } }
        public static event EventHandler<DocObjects.RhinoReplaceObjectEventArgs> ReplaceRhinoObject;
        public static event EventHandler<DocumentOpenEventArgs> BeginOpenDocument;
        public static event EventHandler<DocumentOpenEventArgs> EndOpenDocument;
        public static event EventHandler<DocumentEventArgs> CloseDocument;
        public static event EventHandler<DocObjects.RhinoObjectEventArgs> AddRhinoObject;
        public static event EventHandler<DocObjects.RhinoObjectEventArgs> UndeleteRhinoObject;
        public uint BeginUndoRecord(string description) { return 0; }
        public bool EndUndoRecord(uint undoRecordSerialNumber) { return false; }
        public bool UndoRecordingEnabled { get; set; }
        public static RhinoDoc FromRuntimeSerialNumber(uint serialNumber) { return null; }
        public uint RuntimeSerialNumber { get { return 0; } }
        public DocObjects.Tables.ObjectTable Objects { get { return null; } }
        public DocObjects.Tables.ViewTable Views { get { return null; } }
    }

    public class DocumentEventArgs : EventArgs
    {
        public RhinoDoc Document { get { return null; } }
        public uint DocumentSerialNumber { get { return 0; } }
    }

    public class DocumentOpenEventArgs : DocumentEventArgs
    {
        public string FileName { get { return null; } }
        public bool Merge { get { return false; } }
        public bool Reference { get { return false; } }
    }

    public static class RhinoApp
    {
        public static event EventHandler Idle;
        public static event EventHandler EscapeKeyPressed;
        public static void Wait() { }
        public static void SetCommandPrompt(string prompt) { }
        public static void WriteLine(string message) { }
        public static void WriteLine(string format, object arg0) { }
        public static void WriteLine(string format, object arg0, object arg1) { }
        public static void InvokeOnUiThread(Delegate method, params object[] args) { }
    }
}

namespace Rhino.PlugIns
{
    public enum PlugInLoadTime { Disabled = 0, AtStartup = 1, WhenNeeded = 2, WhenNeededIgnoreDockingBars = 6, WhenNeededOrOptionsDialog = 10, WhenNeededOrTabbedDockBar = 18 }
    public enum LoadReturnCode { ErrorShowDialog = 0, Success = 1, ErrorNoDialog = -1 }

    public abstract class PlugIn
    {
        public Guid Id { get { return Guid.Empty; } }
        public static string PathFromId(Guid pluginId) { return null; }
        public virtual PlugInLoadTime LoadTime { get { return PlugInLoadTime.WhenNeeded; } }
        protected virtual LoadReturnCode OnLoad(ref string errorMessage) { return LoadReturnCode.Success; }
    }
}

namespace Rhino.Commands
{
    public enum Result { Success = 0, Cancel = 1, Nothing = 2, Failure = 3, UnknownCommand = 4, CancelModelessDialog = 5, ExitRhino = 268435455 }
    public enum RunMode { Interactive = 0, Scripted = 1 }

    public abstract class Command
    {
        public abstract string EnglishName { get; }
        protected abstract Result RunCommand(RhinoDoc doc, RunMode mode);
        public static bool InCommand() { return false; }
    }
}

namespace Rhino.FileIO
{
    public class BinaryArchiveWriter
    {
        public void Write3dmChunkVersion(int major, int minor) { }
        public void WriteByteArray(IEnumerable<byte> value) { }
    }

    public class BinaryArchiveReader
    {
        public void Read3dmChunkVersion(out int major, out int minor) { major = 0; minor = 0; }
        public byte[] ReadByteArray() { return null; }
    }
}

namespace Rhino.DocObjects
{
    [Flags]
    public enum ObjectType : uint { None = 0, Point = 1, Surface = 8, Brep = 16, Mesh = 32, AnyObject = 4294967295 }

    public class RhinoObject
    {
        public Guid Id { get { return Guid.Empty; } }
        public Geometry.GeometryBase Geometry { get { return null; } }
        public RhinoDoc Document { get { return null; } }
        public bool IsDeleted { get { return false; } }
        public virtual string ShortDescription(bool plural) { return null; }
    }

    public class Layer
    {
        public int Index { get { return 0; } }
    }

    public class ObjectAttributes
    {
        public ObjectAttributes() { }
        public int LayerIndex { get; set; }
        public string Name { get; set; }
    }

    public class MeshObject : RhinoObject
    {
        public Geometry.Mesh MeshGeometry { get { return null; } }
    }

    public class ObjRef
    {
        public ObjRef(RhinoDoc doc, Guid id) { }
        public Geometry.Surface Surface() { return null; }
        public Geometry.Brep Brep() { return null; }
        public Geometry.ComponentIndex GeometryComponentIndex { get { return new Geometry.ComponentIndex(); } }
        public Geometry.Point Point() { return null; }
        public RhinoObject Object() { return null; }
        public Guid ObjectId { get { return Guid.Empty; } }
    }

    public class ObjectEnumeratorSettings
    {
        public bool HiddenObjects { get; set; }
        public bool LockedObjects { get; set; }
    }

    public class RhinoObjectEventArgs : EventArgs
    {
        public Guid ObjectId { get { return Guid.Empty; } }
        public RhinoObject TheObject { get { return null; } }
    }

    public class RhinoReplaceObjectEventArgs : EventArgs
    {
        public Guid ObjectId { get { return Guid.Empty; } }
        public RhinoObject NewRhinoObject { get { return null; } }
        public RhinoObject OldRhinoObject { get { return null; } }
        public RhinoDoc Document { get { return null; } }
    }
}

namespace Rhino.DocObjects.Tables
{
    public class ObjectTable
    {
        public void AddRhinoObject(Custom.CustomMeshObject meshObject) { }
        public bool Replace(ObjRef objref, RhinoObject newObject) { return false; }
        public RhinoObject FindId(Guid id) { return null; }
        public Guid AddPoint(Geometry.Point3d point) { return Guid.Empty; }
        public Guid AddPolyline(IEnumerable<Geometry.Point3d> points) { return Guid.Empty; }
        public Guid AddMesh(Geometry.Mesh mesh) { return Guid.Empty; }
        public Guid AddPolyline(IEnumerable<Geometry.Point3d> points, ObjectAttributes attributes) { return Guid.Empty; }
        public Guid AddMesh(Geometry.Mesh mesh, ObjectAttributes attributes) { return Guid.Empty; }
        public IEnumerable<RhinoObject> GetObjectList(ObjectEnumeratorSettings settings) { return null; }
    }

    public class LayerTable
    {
        public int Add(string layerName, Color layerColor) { return 0; }
        public Layer FindName(string layerName) { return null; }
    }

    public class ViewTable
    {
        public void Redraw() { }
    }
}

namespace Rhino.DocObjects.Custom
{
    public abstract class CustomMeshObject : MeshObject, IDisposable
    {
        protected CustomMeshObject() { }
        protected CustomMeshObject(Geometry.Mesh mesh) { }
        public void Dispose() { }
    }

    public abstract class UserData
    {
        public virtual string Description { get { return null; } }
        public virtual bool ShouldWrite { get { return false; } }
        protected virtual bool Write(FileIO.BinaryArchiveWriter archive) { return false; }
        protected virtual bool Read(FileIO.BinaryArchiveReader archive) { return false; }
        protected virtual void OnTransform(Geometry.Transform transform) { }
        protected virtual void OnDuplicate(UserData source) { }
    }

    public class UserDataList
    {
        public bool Add(UserData userdata) { return false; }
        public UserData Find(Type userdataType) { return null; }
    }
}

namespace Rhino.Input
{
    public enum GetResult { NoResult = 0, Cancel = 1, Nothing = 2, Option = 3, Number = 4, Color = 5, Undo = 6, Miss = 7, Point = 8, Point2d = 9, Line2d = 10, Rectangle2d = 11, Object = 12, String = 13, Timeout = 15, ExitRhino = 268435455 }

    public static class RhinoGet
    {
        public static Commands.Result GetOneObject(string prompt, bool acceptNothing, DocObjects.ObjectType filter, out DocObjects.ObjRef rhObject) { rhObject = null; return 0; }
        public static Commands.Result GetString(string prompt, bool acceptNothing, ref string outputString) { return 0; }
        public static Commands.Result GetMultipleObjects(string prompt, bool acceptNothing, DocObjects.ObjectType filter, out DocObjects.ObjRef[] rhObjects) { rhObjects = null; return 0; }
    }
}

namespace Rhino.Input.Custom
{
    public delegate bool GetObjectGeometryFilter(DocObjects.RhinoObject rhObject, Geometry.GeometryBase geometry, Geometry.ComponentIndex componentIndex);

    public class CommandLineOption
    {
        public int Index { get { return 0; } }
        public int CurrentListOptionIndex { get { return 0; } }
    }

    public class OptionInteger
    {
        public OptionInteger(int initialValue, int lowerLimit, int upperLimit) { }
        public int CurrentValue { get; set; }
    }

    public class OptionToggle
    {
        public OptionToggle(bool initialValue, string offValue, string onValue) { }
        public bool CurrentValue { get; set; }
    }

    public class OptionDouble
    {
        public OptionDouble(double initialValue, double lowerLimit, double upperLimit) { }
        public double CurrentValue { get; set; }
    }

    public abstract class GetBaseClass
    {
        public void SetCommandPrompt(string prompt) { }
        public void AcceptNothing(bool enable) { }
        public void ClearCommandOptions() { }
        public int AddOption(string englishOption) { return 0; }
        public int AddOptionList(string englishOptionName, IEnumerable<string> listValues, int listCurrentIndex) { return 0; }
        public int AddOptionInteger(string englishName, ref OptionInteger intValue) { return 0; }
        public int AddOptionDouble(string englishName, ref OptionDouble numberValue) { return 0; }
        public int AddOptionToggle(string englishName, ref OptionToggle toggleValue) { return 0; }
        public CommandLineOption Option() { return null; }
        public Commands.Result CommandResult() { return 0; }
        public Geometry.Point3d Point() { return new Geometry.Point3d(); }
    }

    public class GetOption : GetBaseClass
    {
        public GetResult Get() { return 0; }
    }

    public class GetObject : GetBaseClass
    {
        public DocObjects.ObjectType GeometryFilter { get; set; }
        public void SetCustomGeometryFilter(GetObjectGeometryFilter filter) { }
        public GetResult Get() { return 0; }
        public GetResult GetMultiple(int minimumNumber, int maximumNumber) { return 0; }
        public int ObjectCount { get { return 0; } }
        public DocObjects.ObjRef Object(int index) { return null; }
    }

    public class GetPointDrawEventArgs : Display.DrawEventArgs
    {
        public Geometry.Point3d CurrentPoint { get { return new Geometry.Point3d(); } }
    }

    public class GetPoint : GetBaseClass
    {
        public event EventHandler<GetPointDrawEventArgs> DynamicDraw;
        public bool Constrain(Geometry.Surface surface, bool allowPickingPointOffObject) { return false; }
        public void SetBasePoint(Geometry.Point3d basePoint, bool showDistanceInStatusBar) { }
        public GetResult Get() { return 0; }
    }
}

namespace Rhino.Display
{
    public enum PointStyle { Simple = 0, ControlPoint = 1, ActivePoint = 2, X = 3, RoundControlPoint = 5, RoundActivePoint = 6 }

    public class DisplayPipeline
    {
        public void DrawPolyline(IEnumerable<Geometry.Point3d> polyline, Color color, int thickness) { }
        public void DrawPoints(IEnumerable<Geometry.Point3d> points, PointStyle style, int radius, Color color) { }
        public void DrawLine(Geometry.Point3d from, Geometry.Point3d to, Color color) { }
    }

    public class DrawEventArgs : EventArgs
    {
        public DisplayPipeline Display { get { return null; } }
    }

    public class CalculateBoundingBoxEventArgs : DrawEventArgs
    {
        public void IncludeBoundingBox(Geometry.BoundingBox box) { }
    }

    public abstract class DisplayConduit
    {
        public bool Enabled { get; set; }
        protected virtual void CalculateBoundingBox(CalculateBoundingBoxEventArgs e) { }
        protected virtual void PostDrawObjects(DrawEventArgs e) { }
    }
}

namespace Rhino.Geometry
{
    public struct Point3d
    {
        public Point3d(double x, double y, double z) { X = x; Y = y; Z = z; }
        public double X { get; set; }
        public double Y { get; set; }
        public double Z { get; set; }
    }

    public struct Vector3d
    {
        public Vector3d(double x, double y, double z) { X = x; Y = y; Z = z; }
        public double X { get; set; }
        public double Y { get; set; }
        public double Z { get; set; }
        public double Length { get { return 0; } }
    }

    public struct Plane
    {
        public Plane(Point3d origin, Vector3d normal) { }
    }

    public struct Interval
    {
        public double T0 { get; set; }
        public double T1 { get; set; }
    }

    public enum ComponentIndexType { InvalidType = 0, BrepVertex = 1, BrepEdge = 2, BrepFace = 3, BrepTrim = 4, BrepLoop = 5 }

    public struct ComponentIndex
    {
        public ComponentIndexType ComponentIndexType { get { return 0; } }
        public int Index { get { return 0; } }
    }

    public struct Transform
    {
        public double this[int row, int column] { get { return 0; } set { } }
    }

    public struct ControlPoint
    {
        public ControlPoint(double x, double y, double z, double weight) { }
        public Point3d Location { get { return new Point3d(); } set { } }
        public double Weight { get { return 0; } set { } }
    }

    public struct BoundingBox
    {
        public BoundingBox(IEnumerable<Point3d> points) { }
        public static BoundingBox Empty { get { return new BoundingBox(); } }
        public void Union(BoundingBox other) { }
        public bool IsValid { get { return false; } }
        public Vector3d Diagonal { get { return new Vector3d(); } }
    }

    public class GeometryBase : Runtime.CommonObject { }

    public class Point : GeometryBase
    {
        internal Point() { }
        public Point3d Location { get { return new Point3d(); } set { } }
    }

    public class Curve : GeometryBase
    {
        public PolylineCurve ToPolyline(double tolerance, double angleTolerance, double minimumLength, double maximumLength) { return null; }
    }

    public class PolylineCurve : Curve
    {
        public PolylineCurve(IEnumerable<Point3d> points) { }
        public int PointCount { get { return 0; } }
        public Point3d Point(int index) { return new Point3d(); }
    }

    public class Polyline : List<Point3d>
    {
        public Polyline(IEnumerable<Point3d> collection) : base(collection) { }
    }

    public class Surface : GeometryBase
    {
        public NurbsSurface ToNurbsSurface() { return null; }
        public bool ClosestPoint(Point3d testPoint, out double u, out double v) { u = 0; v = 0; return false; }
        public Interval Domain(int direction) { return new Interval(); }
        public Point3d PointAt(double u, double v) { return new Point3d(); }
    }

    public class SurfaceProxy : Surface { }

    public class BrepFace : SurfaceProxy
    {
        public Collections.BrepLoopList Loops { get { return null; } }
    }

    public enum BrepLoopType { Unknown = 0, Outer = 1, Inner = 2, Slit = 3, CurveOnSurface = 4, PointOnSurface = 5 }

    public class BrepLoop : GeometryBase
    {
        public BrepLoopType LoopType { get { return BrepLoopType.Unknown; } }
        public Curve To2dCurve() { return null; }
    }

    public class Brep : GeometryBase
    {
        public Collections.BrepFaceList Faces { get { return null; } }
    }

    public class NurbsSurface : Surface
    {
        internal NurbsSurface() { }
        public static NurbsSurface Create(int dimension, bool isRational, int order0, int order1, int controlPointCount0, int controlPointCount1) { return null; }
        public Collections.NurbsSurfacePointList Points { get { return null; } }
        public Collections.NurbsSurfaceKnotList KnotsU { get { return null; } }
        public Collections.NurbsSurfaceKnotList KnotsV { get { return null; } }
        public bool IsRational { get { return false; } }
        public int Degree(int direction) { return 0; }
        public bool IsValid { get { return false; } }
    }

    public class MeshNgon
    {
        public static MeshNgon Create(IList<int> meshVertexIndexList, IList<int> meshFaceIndexList) { return null; }
    }

    public class Mesh : GeometryBase
    {
        public Mesh() { }
        public Collections.MeshVertexList Vertices { get { return null; } }
        public Collections.MeshFaceList Faces { get { return null; } }
        public Collections.MeshNgonList Ngons { get { return null; } }
        public Collections.MeshVertexNormalList Normals { get { return null; } }
        public Mesh DuplicateMesh() { return null; }
    }
}

namespace Rhino.Runtime
{
    public class CommonObject
    {
        public DocObjects.Custom.UserDataList UserData { get { return null; } }
    }
}

namespace Rhino.Geometry.Collections
{
    public class BrepLoopList
    {
        public int Count { get { return 0; } }
        public BrepLoop this[int index] { get { return null; } }
    }

    public class BrepFaceList
    {
        public int Count { get { return 0; } }
        public BrepFace this[int index] { get { return null; } }
    }

    public class NurbsSurfacePointList
    {
        public int CountU { get { return 0; } }
        public int CountV { get { return 0; } }
        public ControlPoint GetControlPoint(int u, int v) { return new ControlPoint(); }
        public bool SetControlPoint(int u, int v, ControlPoint cp) { return false; }
    }

    public class NurbsSurfaceKnotList
    {
        public int Count { get { return 0; } }
        public double this[int index] { get { return 0; } set { } }
    }

    public class MeshVertexList
    {
        public bool UseDoublePrecisionVertices { get; set; }
        public int Add(double x, double y, double z) { return 0; }
    }

    public class MeshFaceList
    {
        public int AddFace(int vertex1, int vertex2, int vertex3) { return 0; }
    }

    public class MeshNgonList
    {
        public int AddNgon(MeshNgon ngon) { return 0; }
    }

    public class MeshVertexNormalList
    {
        public bool ComputeNormals() { return false; }
    }
}
