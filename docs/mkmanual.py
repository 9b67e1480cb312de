#!/usr/bin/env python3
"""Writes docs/manual.md: one man page per public function of ssstar (every PETSC_EXTERN function of include/*.h), as
PETSc's are: the synopsis (the C signature, its types from the header, its parameter names from the definition in
src/), then the function's /*@ ... @*/ block (what it does, Collective or not, Input and Output Parameters, Options
Database Keys, Notes, Level, .seealso); and the SNES type's page (its /*MC ... M*/ block).

  docs/mkmanual.py           regenerate docs/manual.md
  docs/mkmanual.py --check   exit 1 if a public function has no block, a block lacks its Level or its .seealso or
                             leaves a parameter undocumented, a definition is not found, or docs/manual.md is out of date

tests/suite_package.py compiles every synopsis of docs/manual.md against the headers."""
import glob
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MANUAL = os.path.join(ROOT, "docs", "manual.md")
DECL = re.compile(r"PETSC_EXTERN\s+((?:const\s+)?\w+\s*\**)\s*(\w+)\s*\(([^;]*)\)\s*;")
BLOCK = re.compile(r"/\*@C?\s*\n(.*?)@\*/", re.S)
TYPE = re.compile(r"/\*MC\s*\n(.*?)M\*/", re.S)
HEADERS = {"ssstar.h": "The SNES type", "ssstarreduction.h": "The reduction to the contact dofs", "ssstarscene.h": "Scenes: meshes, FEM, contact groups and output", "ssstargeometry.h": "Geometry the scenes share",
           "ssstarhistory.h": "Load histories"}


def dedent(text):
    lines = text.rstrip().split("\n")
    indent = min((len(line) - len(line.lstrip()) for line in lines if line.strip()), default=0)
    return "\n".join(line[indent:] for line in lines)


def sources():
    return sorted(glob.glob(os.path.join(ROOT, "src", "**", "*.c"), recursive=True))


def blocks():
    """name -> (text, file) of every documentation block in src/"""
    found = {}
    for path in sources():
        for m in BLOCK.finditer(open(path).read()):
            text = dedent(m.group(1))
            found[text.split()[0]] = (text, os.path.relpath(path, ROOT))
    return found


def definitions():
    """name -> parameter list (text) of every function defined at file level in src/"""
    found = {}
    for path in sources():
        for m in re.finditer(r"^(?:static\s+)?(?:const\s+)?\w+\s*\**\s*(\w+)\s*\(([^;{]*?)\)\s*\{", open(path).read(), re.M | re.S):
            found.setdefault(m.group(1), " ".join(m.group(2).split()))
    return found


def split_params(text):
    """The parameters of a C parameter list, split at the commas outside parentheses and brackets"""
    params, depth, cur = [], 0, ""
    for ch in text:
        if ch in "([":
            depth += 1
        elif ch in ")]":
            depth -= 1
        if ch == "," and depth == 0:
            params.append(cur.strip())
            cur = ""
        else:
            cur += ch
    if cur.strip():
        params.append(cur.strip())
    return params


def param_name(param):
    """The declared name of a parameter with one (int n, PetscErrorCode (*f)(void), const PetscReal *x[])"""
    m = re.search(r"\(\s*\*\s*(\w+)\s*\)", param)
    if m:
        return m.group(1)
    m = re.search(r"(\w+)\s*(\[[^\]]*\]\s*)*$", param)
    return m.group(1) if m else None


def named(header_param, name):
    """The header's parameter type with the definition's name put in (PetscInt[3] + c -> PetscInt c[3])"""
    if "(*)" in header_param:
        return header_param.replace("(*)", "(*%s)" % name, 1)
    if param_name(header_param) == name:
        return header_param
    bracket = header_param.find("[")
    base, dims = (header_param, "") if bracket < 0 else (header_param[:bracket].rstrip(), header_param[bracket:])
    return base + ("" if base.endswith("*") else " ") + name + dims


def synopsis(ret, name, header_params, definition):
    """(the C signature, the parameter names), or (None, problem)"""
    hp = split_params(header_params)
    if hp == ["void"]:
        return "%s %s(void);" % (" ".join(ret.split()), name), []
    if definition is None:
        return None, "no definition of %s in src/" % name
    dp = split_params(definition)
    if len(dp) != len(hp):
        return None, "%s: %d parameters in the header, %d in the definition" % (name, len(hp), len(dp))
    names = [param_name(p) for p in dp]
    return "%s %s(%s);" % (" ".join(ret.split()).replace(" *", " *"), name, ", ".join(named(h, n) for h, n in zip(hp, names))), names


SECTION_LINE = re.compile(r"^\s*[+.-]\s+(\w+)\s+-", re.M)


def problems_of(name, text, params):
    """What the man page of name lacks"""
    lacks = []
    if not re.search(r"^\s*Level:\s*\w+", text, re.M):
        lacks.append("a Level")
    if not re.search(r"^\s*\.seealso:", text, re.M):
        lacks.append("a .seealso")
    documented = set(SECTION_LINE.findall(text))
    for p in params:
        if p not in documented:
            lacks.append("the parameter %s" % p)
    if params and not re.search(r"^\s*(Input|Output) Parameters?:", text, re.M):
        lacks.append("Input/Output Parameters")
    return ["%s: no %s" % (name, what) for what in lacks]


def manual():
    docs, defs, missing = blocks(), definitions(), []
    out = ["# ssstar manual pages", "",
           "Generated by `docs/mkmanual.py` from the headers and the documentation blocks of the sources; do not edit by hand.",
           "Each page: the synopsis (types from the header, names from the definition), then the block: what the function",
           "does, whether it is collective, its input and output parameters, options, notes, level and related functions.", ""]
    text, where = type_page()
    out += ["## SNESSSSTAR (the type)", "", "```", text, "```", "", "Source: `%s`" % where, ""]
    for header, title in HEADERS.items():
        seen = []
        out += ["## %s (`#include <%s>`)" % (title, header), ""]
        for m in DECL.finditer(open(os.path.join(ROOT, "include", header)).read()):
            ret, name, params = m.group(1), m.group(2), m.group(3)
            if name in seen:
                continue
            seen.append(name)
            if name not in docs:
                missing.append("%s (include/%s): no documentation block" % (name, header))
                continue
            signature, names = synopsis(ret, name, params, defs.get(name))
            if signature is None:
                missing.append(names)
                continue
            text, where = docs[name]
            missing += problems_of(name, text, names)
            out += ["### %s" % name, "", "Synopsis:", "", "```c", "#include <%s>" % header, signature, "```", "",
                    "```", text, "```", "", "Source: `%s`" % where, ""]
    return "\n".join(out), missing


def type_page():
    for path in sources():
        m = TYPE.search(open(path).read())
        if m:
            return dedent(m.group(1)), os.path.relpath(path, ROOT)
    return None, None


def main():
    text, missing = manual()
    if "--check" in sys.argv:
        ok = not missing and os.path.exists(MANUAL) and open(MANUAL).read() == text
        for problem in missing:
            print(problem)
        if not missing and not ok:
            print("docs/manual.md is out of date: run docs/mkmanual.py")
        sys.exit(0 if ok else 1)
    if missing:
        sys.exit("incomplete manual pages:\n  " + "\n  ".join(missing))
    open(MANUAL, "w").write(text)


if __name__ == "__main__":
    main()
