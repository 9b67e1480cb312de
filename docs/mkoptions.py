#!/usr/bin/env python3
"""Writes docs/options.md: one table of every option of ssstar — the solver's (-snes_ssstar_*), the scenes', the
examples' own — with its default and meaning, from what the programs print for -help (which does no work), so that the
table cannot drift from the code: the sections of -help that ssstar's sources open (PetscOptionsBegin and
PetscOptionsHeadBegin titles in src/ and examples/*.c), the solver's monitors (SNESMonitorSetFromOptions in src/), and
the options a program's own help text lists.

  docs/mkoptions.py           regenerate docs/options.md (make docs; the examples must be built)
  docs/mkoptions.py --check   exit 1 if docs/options.md is not what the programs print today

tests/suite_package.py runs the check; tests/suite_outcomes.py compares the table's solver defaults with -help."""
import glob
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OPTIONS = os.path.join(ROOT, "docs", "options.md")
# the programs and the arguments of their -help run; the first one that prints an option gives its row's default
PROGRAMS = [("contact", []), ("prism", []), ("generic", ["-snes_type", "ssstar"]), ("fclib", [])]
RULE = "-" * 40
# where an option comes from, by the -help section it is printed in (the solver's and the scene's are shared)
SOLVER, SCENE, ERRORS = "solver", "scene", "every example"
REGISTERED = re.compile(r"^\s+(-[\w<>]+):?\s+<(.*?)>:?\s*(.*?)\s*\((\w+)\)\s*$")
FAMILY = re.compile(r"^  (-[\w<>]+) <([^>]*)>:\s*(.*)$")
OWN = re.compile(r"^  (-\w+ <[^>]*>(?: -\w+ <[^>]*>)*)\s+(\S.*)$")
MONITOR = re.compile(r'SNESMonitorSetFromOptions\(\s*\w+,\s*"(-[\w]+)",\s*"([^"]*)"')


def titles():
    """The -help section titles ssstar's sources open (PetscOptionsBegin(comm, prefix, title, ...) and the SNES type's
    PetscOptionsHeadBegin(PetscOptionsObject, title))"""
    found = set()
    for path in glob.glob(os.path.join(ROOT, "src", "**", "*.c"), recursive=True) + glob.glob(os.path.join(ROOT, "examples", "*.c")):
        text = open(path).read()
        found |= set(re.findall(r'PetscOptionsBegin\([^,]+,[^,]+,\s*"([^"]+)"', text))
        found |= {"  " + t for t in re.findall(r'PetscOptionsHeadBegin\(\s*\w+,\s*"([^"]+)"', text)}
    return found


def monitors():
    found = {}
    for path in glob.glob(os.path.join(ROOT, "src", "**", "*.c"), recursive=True):
        found.update(MONITOR.findall(open(path).read()))
    return found


def help_text(program, args):
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    exe = os.path.join(ROOT, "examples", program)
    if not os.path.exists(exe):
        sys.exit("docs/mkoptions.py: %s is not built (make)" % exe)
    p = subprocess.run([exe, "-help"] + args, cwd=ROOT, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if p.returncode != 0:
        sys.exit("docs/mkoptions.py: examples/%s -help failed:\n%s" % (program, p.stdout[-2000:]))
    return p.stdout.replace(ROOT + "/", "")


def value(inner):
    """The default in -help's <...>: "now X : formerly Y" or "X : Y" gives X (the value in use), else the text"""
    m = re.match(r"now (.*?) : formerly .*$", inner) or re.match(r"(.*?) : .*$", inner)
    v = (m.group(1) if m else inner).strip()
    if v in ("TRUE", "FALSE"):
        return v.lower()
    if re.fullmatch(r"-?\d+\.", v):
        return v[:-1]
    return v


def meaning(text, function):
    text = re.sub(r"\s+", " ", text).strip()
    text = re.sub(r"\(choose one of\)|\(one of\)", "; one of", text).replace(" ;", ";")
    return text + (" (`%s`)" % function if function and function != "None" else "")


def parse(program, text, mine, monitor_text):
    """Rows (option, default or form, meaning, origin) of one program's -help, in its order"""
    rows = []
    sections = text.split(RULE)
    # the program's own help text: options it lists that no section of ours registers
    own = []
    for line in sections[0].split("\n"):
        m = OWN.match(line)
        if m:
            names = re.findall(r"(-\w+) <([^>]*)>", m.group(1))
            own.append([names, m.group(2)])
        elif own and re.match(r"^\s{6,}\S", line) and not line.strip().startswith("-"):
            own[-1][1] += " " + line.strip()
        elif not line.startswith("  "):
            own.append([[], ""])  # prose ends a continuation
    for section in sections[1:]:
        lines = section.strip("\n").split("\n")
        title = lines[0].rstrip(":")
        ours = title in mine
        origin = {"Scene: the body, its loads and its contact groups": SCENE, "Error reports": ERRORS}.get(title, program)
        viewer = re.match(r"Viewer \((-\w+)\)", title)
        if viewer and viewer.group(1) in monitor_text:
            name = viewer.group(1)
            rows.append((name, "", monitor_text[name] + "; a PETSc viewer (`%s ascii:file`)" % name, SOLVER))
            continue
        for line in lines[1:]:
            if line.rstrip() in mine:
                ours, origin = True, SOLVER
                continue
            if not ours:
                if re.match(r"^\s+-snes_ssstar_newton_ksp_type ", line):
                    m = REGISTERED.match(line)
                    rows.append((m.group(1), value(m.group(2)), "the Krylov method of a dense Newton step solved on the last LU "
                                 "(`-snes_ssstar_lu_reuse`); every `-snes_ssstar_newton_ksp_*` option of PETSc's applies", SOLVER))
                continue
            m = REGISTERED.match(line)
            if m:
                rows.append((m.group(1), value(m.group(2)), meaning(m.group(3), m.group(4)), origin))
                continue
            m = FAMILY.match(line)
            if m:
                rows.append(("%s <%s>" % (m.group(1), m.group(2)), "", meaning(m.group(3), None), origin))
            elif rows and re.match(r"^\s{6,}\S", line):
                name, default, text, where = rows[-1]
                rows[-1] = (name, default, text + " " + line.strip(), where)
    listed = {r[0].split()[0] for r in rows}
    for names, text in own:
        for name, default in names:
            if name not in listed:
                rows.append((name, value(default), meaning(text, None), program))
                listed.add(name)
    return rows


def table():
    mine, monitor_text = titles(), monitors()
    merged, order = {}, []
    for program, args in PROGRAMS:
        for name, default, text, origin in parse(program, help_text(program, args), mine, monitor_text):
            key = (name, text)
            if key not in merged:
                merged[key] = {"default": default, "origin": origin, "programs": [], "others": []}
                order.append(key)
            row = merged[key]
            row["programs"].append(program)
            if default != row["default"] and (program, default) not in row["others"]:
                row["others"].append((program, default))
    rank = {SOLVER: 0, SCENE: 1, ERRORS: 2}
    order.sort(key=lambda k: (rank.get(merged[k]["origin"], 3), [p for p, _ in PROGRAMS].index(merged[k]["programs"][0]) if merged[k]["origin"] not in rank else 0))
    where = {SOLVER: "solver", SCENE: "scene", ERRORS: "every example"}
    out = ["| option | default | where | meaning |", "|---|---|---|---|"]
    for key in order:
        row = merged[key]
        name, text = key
        default = "`%s`" % row["default"] if row["default"] else ""
        if row["others"]:
            default += "".join(" (`examples/%s`: `%s`)" % (p, d) if d else " (`examples/%s`: none)" % p for p, d in row["others"])
            default = default.strip()
        origin = where.get(row["origin"], "`examples/%s`" % row["origin"])
        if row["origin"] not in where and len(row["programs"]) > 1:
            origin = ", ".join("`examples/%s`" % p for p in row["programs"])
        out.append("| `%s` | %s | %s | %s |" % (name, default, origin, text.replace("|", "\\|")))
    return "\n".join(out) + "\n"


HEADER = """# Options

Every option of ssstar's solver (`-snes_ssstar_*`), of its scenes (`examples/contact`, `examples/prism`, Python's
`ssstar.Scene`: keywords without the dash) and of the example programs, with the default each program runs with and
what it means. **Generated** by `docs/mkoptions.py` (`make docs`) from what the programs print for `-help` — do not edit
by hand; `make test` fails when this page differs from the programs (`tests/suite_package.py`).

Where: *solver*, any program with `-snes_type ssstar` (also `SNESSetFromOptions` in your own); *scene*,
`examples/contact`, `examples/prism` and `ssstar.Scene`; else the example programs that read it. A group option
`-name_<G>` exists for every group G of the mesh; `<...>` after an option's name is the form of its
value as `-help` prints it. PETSc's own options (`-snes_rtol`, `-snes_max_it`, `-ksp_*`, `-pc_*`, `-log_view`, ...)
keep their meaning ([what converged means](guide/converged.md), [large problems](guide/large-problems.md)); the
reduction's solvers read `-schur_direct_mumps_icntl_<i>`, `-schur_direct_mumps_cntl_<i>`, `-schur_mat_mumps_*`,
`-interior_ksp_*`, `-interior_pc_*` ([the prism](guide/prism.md#the-reductions)) and `examples/prism -initial_guess
elastic` reads `-initial_ksp_*`, `-initial_pc_*`.

"""


def main():
    text = HEADER + table()
    if "--check" in sys.argv[1:]:
        if not os.path.exists(OPTIONS) or open(OPTIONS).read() != text:
            sys.exit("docs/options.md is out of date: run make docs (docs/mkoptions.py)")
        return
    with open(OPTIONS, "w") as f:
        f.write(text)


if __name__ == "__main__":
    main()
