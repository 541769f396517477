// Lists the RhinoCommon and Grasshopper API an assembly uses, read from its metadata with
// Mono.Cecil (no hand-kept list): every type reference, every member reference (methods,
// constructors, property accessors, event accessors, fields) into those assemblies, and every
// virtual member of its own types that overrides one of theirs. One line each:
//
//   T <type>
//   M <type>::<member>(<parameter types, '&' for ref, 'out ' prefix for out>)
//   O <type>::<member>(<parameter types>)        an override of a base-class member
//
// Types are written Namespace.Name (nested: Namespace.Outer/Inner, generic arity dropped).
// Usage:  mono ApiRefs.exe ASSEMBLY SEARCH_DIR...   (SEARCH_DIRs resolve the base classes)
// Mode:   mono ApiRefs.exe --definitions ASSEMBLY   lists the public and protected members an
//         assembly defines (used on the fakes, so they are checked against the stubs too).
using System;
using System.Collections.Generic;
using System.Linq;
using Mono.Cecil;

static class ApiRefs
{
    static readonly string[] Scopes = { "RhinoCommon", "Grasshopper" };

    static int Main(string[] args)
    {
        try
        {
            var lines = new SortedSet<string>(StringComparer.Ordinal);
            if (args.Length >= 2 && args[0] == "--definitions")
                Definitions(args[1], lines);
            else if (args.Length >= 1)
                References(args[0], args.Skip(1).ToArray(), lines);
            else
            {
                Console.Error.WriteLine("usage: ApiRefs.exe ASSEMBLY [SEARCH_DIR...] | --definitions ASSEMBLY");
                return 2;
            }
            foreach (var line in lines) Console.WriteLine(line);
            return 0;
        }
        catch (Exception e)
        {
            Console.Error.WriteLine("ApiRefs: " + e.Message);
            return 2;
        }
    }

    static bool InScope(TypeReference type)
    {
        while (type is TypeSpecification) type = ((TypeSpecification)type).ElementType;
        var scope = type.Scope;
        var name = scope is ModuleDefinition ? ((ModuleDefinition)scope).Assembly.Name.Name : scope == null ? "" : scope.Name;
        if (scope is AssemblyNameReference) name = ((AssemblyNameReference)scope).Name;
        return Scopes.Contains(name);
    }

    static string TypeName(TypeReference type)
    {
        if (type is ByReferenceType) return TypeName(((ByReferenceType)type).ElementType) + "&";
        if (type is ArrayType) return TypeName(((ArrayType)type).ElementType) + "[]";
        if (type is GenericInstanceType)
        {
            var g = (GenericInstanceType)type;
            return TypeName(g.ElementType) + "<" + string.Join(",", g.GenericArguments.Select(TypeName)) + ">";
        }
        if (type is GenericParameter) return type.Name;
        string name = type.Name;
        int tick = name.IndexOf('`');
        if (tick >= 0) name = name.Substring(0, tick);
        if (type.DeclaringType != null) return TypeName(type.DeclaringType) + "/" + name;
        return string.IsNullOrEmpty(type.Namespace) ? name : type.Namespace + "." + name;
    }

    /// <summary>The declaring type without generic arguments (members belong to the generic type).</summary>
    static string OwnerName(TypeReference type)
    {
        var g = type as GenericInstanceType;
        return TypeName(g != null ? g.ElementType : type);
    }

    static string Parameters(MethodReference method)
    {
        return string.Join(", ", method.Parameters.Select(p =>
        {
            var t = TypeName(p.ParameterType);
            var def = p as ParameterDefinition;
            return def != null && def.IsOut ? "out " + t.TrimEnd('&') : t;
        }));
    }

    static void References(string path, string[] searchDirs, SortedSet<string> lines)
    {
        var resolver = new DefaultAssemblyResolver();
        foreach (var dir in searchDirs) resolver.AddSearchDirectory(dir);
        var module = ModuleDefinition.ReadModule(path, new ReaderParameters { AssemblyResolver = resolver });
        foreach (var type in module.GetTypeReferences())
            if (InScope(type)) lines.Add("T " + TypeName(type));
        foreach (var member in module.GetMemberReferences())
        {
            if (!InScope(member.DeclaringType)) continue;
            var method = member as MethodReference;
            if (method != null)
            {
                // Out-ness lives on the definition: resolve it when the referenced assembly is found.
                MethodReference shown = method;
                try { shown = method.Resolve() ?? method; } catch (AssemblyResolutionException) { }
                lines.Add("M " + OwnerName(method.DeclaringType) + "::" + method.Name + "(" + Parameters(shown) + ")");
            }
            else lines.Add("M " + OwnerName(member.DeclaringType) + "::" + member.Name);
        }
        // Overrides: virtual methods of our types whose slot comes from a RhinoCommon or
        // Grasshopper base class (property and event accessors included).
        foreach (var type in module.GetTypes())
        {
            foreach (var method in type.Methods.Where(m => m.IsVirtual && !m.IsNewSlot))
            {
                var baseMethod = FindBase(type.BaseType, method);
                if (baseMethod != null && InScope(baseMethod.DeclaringType))
                    lines.Add("O " + OwnerName(baseMethod.DeclaringType) + "::" + baseMethod.Name + "(" + Parameters(baseMethod) + ")");
            }
        }
    }

    static MethodDefinition FindBase(TypeReference baseRef, MethodDefinition method)
    {
        while (baseRef != null)
        {
            TypeDefinition baseType;
            try { baseType = baseRef.Resolve(); }
            catch (AssemblyResolutionException) { return null; }
            if (baseType == null) return null;
            var match = baseType.Methods.FirstOrDefault(m => m.IsVirtual && m.Name == method.Name
                && m.Parameters.Count == method.Parameters.Count
                && m.Parameters.Select(p => TypeName(p.ParameterType)).SequenceEqual(method.Parameters.Select(p => TypeName(p.ParameterType))));
            if (match != null) return match;
            baseRef = baseType.BaseType;
        }
        return null;
    }

    static void Definitions(string path, SortedSet<string> lines)
    {
        var module = ModuleDefinition.ReadModule(path);
        foreach (var type in module.GetTypes().Where(t => (t.IsPublic || t.IsNestedPublic || t.IsNestedFamily) && t.Name != "<Module>"))
        {
            lines.Add("T " + TypeName(type));
            foreach (var method in type.Methods.Where(m => m.IsPublic || m.IsFamily))
                lines.Add("M " + TypeName(type) + "::" + method.Name + "(" + Parameters(method) + ")");
            foreach (var field in type.Fields.Where(f => (f.IsPublic || f.IsFamily) && !f.IsSpecialName))
                lines.Add("M " + TypeName(type) + "::" + field.Name + (type.IsEnum && field.HasConstant ? " = " + Convert.ToInt64(field.Constant) : ""));
        }
    }
}
