#!/usr/bin/env python3
"""Checks RhinoCommon/Grasshopper API uses against the official typed stubs.

Input: lines written by ApiRefs.exe (read from a compiled assembly's metadata, not from a
hand-kept list):

    T <type>                         a type the assembly refers to
    M <type>::<member>(<params>)     a method, constructor, accessor or event accessor it calls
    M <type>::<field>[ = value]      a field or enum value it uses (value: definitions mode)
    O <type>::<member>(<params>)     a base-class member it overrides

Stubs: the folders of the PyPI packages rhino-stubs-typed and grasshopper-stubs-typed
(Rhino/..., Grasshopper/... with __init__.pyi per namespace), generated from the real
assemblies. Each use must name a type the stubs have, a member of that type or of one of its
stub base classes, and for methods an overload taking the same number of arguments (out
parameters are returned as a tuple in the stubs, so they do not count) whose parameter types
agree (C# primitives mapped to Python's names, collections to any collection type, otherwise
the type's name). Enum values in definitions mode must have the stub's number.

What the stubs cannot show (protected members, nested types, GH_TaskCapableComponent) is listed
with the reason in not-in-stubs.txt; an entry there that nothing uses is an error too, so the
list cannot grow stale.

Usage: check_api.py --stubs DIR [--stubs DIR] --allow not-in-stubs.txt REFS_FILE...
Exit status 0 when every use is found, 1 otherwise (each miss printed with what the stubs have).
"""
import argparse
import os
import re
import sys

COLLECTIONS = {"Iterable", "Sequence", "MutableSequence", "list", "List", "Array", "IEnumerable",
               "IList", "ICollection", "IReadOnlyList", "Collection", "Set", "Tuple", "tuple"}
PRIMITIVES = {
    "System.Double": "float", "System.Single": "float",
    "System.Int32": "int", "System.UInt32": "int", "System.Int64": "int", "System.UInt64": "int",
    "System.Int16": "int", "System.UInt16": "int", "System.Byte": "int", "System.SByte": "int",
    "System.Boolean": "bool", "System.String": "str", "System.Object": "object", "System.Type": "type",
    "System.Char": "str",
}


class StubClass:
    def __init__(self, namespace, name, bases):
        self.namespace, self.name, self.bases = namespace, name, bases
        self.members = {}   # name -> list of parameter-type lists (None for non-methods)
        self.values = {}    # enum value name -> int
        self.setters = set()

    @property
    def full(self):
        return self.namespace + "." + self.name


def split_params(text):
    """'self, a: X[Y, Z], b: int' -> ['self', 'a: X[Y, Z]', 'b: int'] (brackets respected)."""
    parts, depth, cur = [], 0, ""
    for ch in text:
        if ch in "[(":
            depth += 1
        elif ch in "])":
            depth -= 1
        if ch == "," and depth == 0:
            parts.append(cur.strip())
            cur = ""
        else:
            cur += ch
    if cur.strip():
        parts.append(cur.strip())
    return parts


def load_stubs(roots):
    classes = {}
    by_short = {}
    for root in roots:
        for folder, _, files in os.walk(root):
            for f in files:
                if f != "__init__.pyi":
                    continue
                rel = os.path.relpath(folder, root)
                if rel == "." or rel.split(os.sep)[0] not in ("Rhino", "Grasshopper"):
                    continue
                namespace = rel.replace(os.sep, ".")
                current = None
                decorators = []
                with open(os.path.join(folder, f), encoding="utf-8") as fh:
                    for line in fh:
                        m = re.match(r"class (\w+)(?:\((.*)\))?:", line)
                        if m:
                            bases = [b.strip() for b in split_params(m.group(2) or "")]
                            current = StubClass(namespace, m.group(1), bases)
                            classes[current.full] = current
                            by_short.setdefault(current.name, []).append(current)
                            decorators = []
                            continue
                        if current is None or not line.startswith("    ") or line.startswith("     "):
                            if not line.startswith("    "):
                                current = None if line.strip() and not line.startswith("#") and not line.startswith("@") else current
                            continue
                        body = line.strip()
                        if body.startswith("@"):
                            decorators.append(body)
                            sm = re.match(r"@(\w+)\.setter", body)
                            if sm:
                                current.setters.add(sm.group(1))
                            continue
                        dm = re.match(r"def (\w+)\((.*)\)\s*(?:->.*)?:", body)
                        if dm:
                            name, params = dm.group(1), split_params(dm.group(2))
                            if params and params[0] in ("self", "cls"):
                                params = params[1:]
                            types = [p.split(":", 1)[1].strip() if ":" in p else "Any" for p in params]
                            is_setter = any(d.endswith(".setter") for d in decorators)
                            if not is_setter:
                                current.members.setdefault(name, []).append(types)
                            decorators = []
                            continue
                        vm = re.match(r"(\w+)\s*=\s*(-?\d+)", body)
                        if vm:
                            current.values[vm.group(1)] = int(vm.group(2))
                            current.members.setdefault(vm.group(1), []).append(None)
                        decorators = []
    return classes, by_short


def find_class(classes, by_short, full):
    if full in classes:
        return classes[full]
    return None


def lineage(classes, by_short, cls, seen=None):
    """cls and its stub base classes, nearest first."""
    seen = seen or set()
    if cls is None or cls.full in seen:
        return []
    seen.add(cls.full)
    out = [cls]
    for base in cls.bases:
        short = re.sub(r"\[.*", "", base).split(".")[-1]
        candidates = by_short.get(short, [])
        same = [c for c in candidates if c.namespace == cls.namespace]
        for c in (same or candidates)[:1]:
            out += lineage(classes, by_short, c, seen)
    return out


def cs_type_ok(cs, stub):
    """True if the C# parameter type cs agrees with the stub's annotation."""
    cs = cs.rstrip("&")
    stub_base = re.sub(r"\[.*", "", stub).strip()
    if len(cs) <= 2 and cs[:1].isupper() and "." not in cs:  # a generic parameter (T)
        return True
    if stub_base in ("Any",):
        return True
    if cs in PRIMITIVES:
        return PRIMITIVES[cs] == stub_base or (cs == "System.String" and stub_base == "str")
    if cs.endswith("[]") or re.match(r"System\.Collections(\.Generic)?\.(IEnumerable|IList|List|ICollection|IReadOnlyList)\b", cs):
        return stub_base in COLLECTIONS
    if cs.startswith("System.EventHandler"):
        return stub_base == "EventHandler"
    short = re.sub(r"<.*", "", cs).replace("/", ".").split(".")[-1]
    return short == stub_base.split(".")[-1]


def parse_ref(line):
    kind, rest = line[0], line[2:].strip()
    if kind == "T":
        return kind, rest, None, None, None
    m = re.match(r"([^:]+)::([^(= ]+)(?:\((.*)\))?(?:\s*=\s*(-?\d+))?$", rest)
    if not m:
        raise ValueError("cannot read line: " + line)
    owner = re.sub(r"<.*", "", m.group(1))
    params = None
    if m.group(3) is not None:
        params = [p.strip() for p in split_generic(m.group(3)) if p.strip()]
    value = int(m.group(4)) if m.group(4) is not None else None
    return kind, owner, m.group(2), params, value


def split_generic(text):
    parts, depth, cur = [], 0, ""
    for ch in text:
        if ch == "<":
            depth += 1
        elif ch == ">":
            depth -= 1
        if ch == "," and depth == 0:
            parts.append(cur)
            cur = ""
        else:
            cur += ch
    parts.append(cur)
    return parts


def describe_overloads(overloads):
    return "; ".join("(" + ", ".join(o) + ")" for o in overloads if o is not None) or "(no parameters listed)"


def check_member(classes, by_short, kind, owner, member, params, value):
    """None when found, else the reason."""
    cls = find_class(classes, by_short, owner.replace("/", "."))
    if cls is None:
        return "type %s is not in the stubs" % owner
    chain = lineage(classes, by_short, cls)

    def overloads(name):
        for c in chain:
            if name in c.members:
                return c.members[name]
        return None

    if params is None:  # a field or enum value
        for c in chain:
            if member in c.values:
                if value is not None and c.values[member] != value:
                    return "%s.%s is %d in the stubs, %d here" % (owner, member, c.values[member], value)
                return None
        if overloads(member) is not None:
            return None
        return "%s has no field or value %s" % (owner, member)

    args = [p for p in params if not p.startswith("out ")]
    name = member
    if member == ".ctor":
        found = overloads("__init__")
        if found is None:
            return None if not args else "%s has no constructor in the stubs" % owner
        name = "__init__"
    elif member in ("get_Item", "set_Item"):
        if overloads("__getitem__" if member == "get_Item" else "__setitem__") is not None or overloads("Item") is not None:
            return None
        return "%s has no indexer" % owner
    elif member.startswith("get_") or member.startswith("set_"):
        prop = member[4:]
        found = overloads(prop)
        if found is None:
            return "%s has no property %s" % (owner, prop)
        if member.startswith("set_") and not any(prop in c.setters for c in chain) and not any(o is not None and len(o) == 1 for o in found):
            return "%s.%s has no setter in the stubs" % (owner, prop)
        return None
    found = overloads(name)
    if found is None:
        return "%s has no member %s" % (owner, name)
    for o in found:
        if o is not None and len(o) == len(args) and all(cs_type_ok(a, s) for a, s in zip(args, o)):
            return None
    return "no overload %s.%s(%s); the stubs have %s" % (owner, name, ", ".join(args), describe_overloads(found))


def same_use(key, entry):
    """An exception entry covers a use: M and O lines of the same member are the same entry."""
    def norm(text):
        return ("M" + text[1:]) if text[:1] in ("M", "O") else text
    key, entry = norm(key), norm(entry)
    return key == entry or (entry.endswith("*") and key.startswith(entry[:-1]))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--stubs", action="append", required=True, help="a folder holding Rhino/ or Grasshopper/ stubs")
    ap.add_argument("--allow", required=True, help="not-in-stubs.txt")
    ap.add_argument("refs", nargs="+")
    a = ap.parse_args()
    classes, by_short = load_stubs(a.stubs)
    if not any(k.startswith("Rhino.") for k in classes):
        print("check_api: no Rhino stubs found under " + ", ".join(a.stubs), file=sys.stderr)
        return 1
    allow = {}
    with open(a.allow, encoding="utf-8") as fh:
        for line in fh:
            entry = line.split("#", 1)[0].strip()
            if entry:
                allow[entry] = 0
    checked = misses = 0
    for path in a.refs:
        with open(path, encoding="utf-8") as fh:
            for line in fh:
                line = line.rstrip("\n")
                if not line.strip():
                    continue
                kind, owner, member, params, value = parse_ref(line)
                key = line.strip()
                allowed = [e for e in allow if same_use(key, e)]
                if allowed:
                    for e in allowed:
                        allow[e] += 1
                    checked += 1
                    continue
                if kind == "T":
                    reason = None if find_class(classes, by_short, owner.replace("/", ".")) else "type %s is not in the stubs" % owner
                else:
                    reason = check_member(classes, by_short, kind, owner, member, params, value)
                checked += 1
                if reason:
                    misses += 1
                    print("MISS  %s: %s\n      %s" % (os.path.basename(path), key, reason))
    stale = [e for e, n in allow.items() if n == 0]
    for e in stale:
        print("STALE %s: in %s but nothing uses it" % (e, os.path.basename(a.allow)))
    print("API check: %d uses checked against the stubs, %d missing, %d stale exceptions" % (checked, misses, len(stale)))
    return 1 if misses or stale else 0


if __name__ == "__main__":
    sys.exit(main())
