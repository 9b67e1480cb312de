"""ssstar as a package: make install + pkg-config, documentation of every public function, -help of every option."""
import glob
import os
import re
import shlex
import shutil
import subprocess

from harness import *  # noqa: F401,F403 (run, expect, mpiexec, test, paths)

OPTION = re.compile(r'(?:PetscOptions\w*|SNESMonitorSetFromOptions)\(\s*(?:[^,()]*,\s*){0,2}"(-[A-Za-z][A-Za-z0-9_]*)"')
LITERAL = re.compile(r'[(,]\s*"(-[A-Za-z][A-Za-z0-9_]*)"')  # an option name passed to any function


@test("make install PREFIX=<tmp> installs the library, the headers and ssstar.pc; a program (examples/generic.c) builds with mpicc and pkg-config alone and solves its contact problem")
def install_and_build_downstream():
    prefix = os.path.join(OUT, "prefix")
    build = os.path.join(OUT, "downstream")
    shutil.rmtree(prefix, ignore_errors=True)
    shutil.rmtree(build, ignore_errors=True)
    os.makedirs(build)
    run(["make", "-s", "install", "PREFIX=" + prefix])
    for path in ("lib/libssstar.so", "lib/pkgconfig/ssstar.pc", "include/ssstar.h", "include/ssstarreduction.h", "include/ssstarscene.h", "include/ssstargeometry.h"):
        expect(os.path.exists(os.path.join(prefix, path)), "make install did not install " + path)
    shutil.copy(os.path.join(ROOT, "examples", "generic.c"), build)
    env = dict(os.environ, PKG_CONFIG_PATH=os.path.join(prefix, "lib", "pkgconfig"))
    flags = subprocess.run(["pkg-config", "--cflags", "--libs", "ssstar"], env=env, stdout=subprocess.PIPE, text=True, check=True).stdout.split()
    expect(any(f.startswith("-I") and "petsc" in f for f in flags), "ssstar.pc does not carry PETSc's include flags: %s" % flags)
    p = subprocess.run(["mpicc", "generic.c", "-o", "generic"] + flags, cwd=build, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    expect(p.returncode == 0, "the downstream program does not build with pkg-config alone", p.stdout)
    out = run(mpiexec(2, os.path.join(build, "generic"), "-snes_type", "ssstar", "-snes_converged_reason"))
    expect("CONVERGED_FNORM_RELATIVE" in out, "the downstream program did not solve", out)
    ldd = subprocess.run(["ldd", os.path.join(build, "generic")], stdout=subprocess.PIPE, text=True).stdout
    expect(os.path.join(prefix, "lib", "libssstar.so") in ldd, "the downstream program does not use the installed library", ldd)


@test("every public function (PETSC_EXTERN in include/*.h) has a manual page block in the sources, and docs/manual.md is regenerated from them (docs/mkmanual.py --check)")
def manual_pages_complete():
    run([PYTHON, os.path.join(ROOT, "docs", "mkmanual.py"), "--check"])


def options_in(paths, pattern=OPTION):
    names = set()
    for path in paths:
        names |= set(pattern.findall(open(path).read()))
    return names


def help_of(program, *args):
    return run(mpiexec(1, os.path.join(ROOT, "examples", program), "-help", *args))


@test("-help lists every option with its default: each -snes_ssstar_* option of the library in examples/prism -help, each scene option of src/scene in examples/prism and examples/contact -help, and each option an example reads in that example's -help")
def help_lists_every_option():
    sources = glob.glob(os.path.join(ROOT, "src", "**", "*.c"), recursive=True)
    library = {o for o in options_in(sources) if o.startswith("-snes_ssstar")}
    scene = {o for o in options_in(glob.glob(os.path.join(ROOT, "src", "scene", "**", "*.c"), recursive=True), LITERAL) if not o.startswith("-dm_")}
    expect(len(library) >= 5 and len(scene) >= 10, "found only %s and %s in src/" % (sorted(library), sorted(scene)))
    args = {"prism": ["-level", "2"], "contact": ["-options_file", os.path.join(ROOT, "scenes", "prism.opts"), "-level", "2"]}
    for source in sorted(glob.glob(os.path.join(ROOT, "examples", "*.c"))):
        program = os.path.splitext(os.path.basename(source))[0]
        if not os.path.exists(os.path.join(ROOT, "examples", program)):
            continue
        # an option an example reads and hands to the scene library (-steps: SSStarSceneGetPathTimes() names it in its
        # errors) is that example's, listed in its -help alone
        handed = options_in([os.path.join(ROOT, "examples", "contact.c")], LITERAL) if program == "prism" else set()
        wanted = options_in([source], LITERAL) | (library if program == "prism" else set()) | ((scene - handed) if program in args else set())
        text = help_of(program, *args.get(program, []))
        for name in sorted(wanted):
            # "-name <default>" ("-name: <default>" for a PetscBool), "-name_<G> <default>" for a family of options, or
            # for a monitor "-name ascii[:...]"
            pattern = re.escape(name) + (r"<G>\s+<" if name.endswith("_") else r":?\s+(<|ascii\[)")
            expect(re.search(pattern, text) is not None, "examples/%s -help does not list %s with its default" % (program, name), text)


@test("docs/options.md, the one table of every option, is what docs/mkoptions.py makes from the examples' -help today (make docs; --check), and it has a row for every option the library, the scenes and each example read: each -snes_ssstar_* option of src/ (with its default), each scene option of src/scene, each option an example reads")
def options_table_fresh():
    run([PYTHON, os.path.join(ROOT, "docs", "mkoptions.py"), "--check"])
    table = open(os.path.join(ROOT, "docs", "options.md")).read()
    rows = set(re.findall(r"^\| `(-[\w<>]+)[^`]*` \|", table, re.M))
    sources = glob.glob(os.path.join(ROOT, "src", "**", "*.c"), recursive=True)
    library = {o for o in options_in(sources) if o.startswith("-snes_ssstar")}
    scene = {o for o in options_in(glob.glob(os.path.join(ROOT, "src", "scene", "**", "*.c"), recursive=True), LITERAL) if not o.startswith(("-dm_", "-pc_", "-ksp_")) or o == "-dm_refine"}  # PETSc's own are PETSc's to document
    examples = set()
    for source in glob.glob(os.path.join(ROOT, "examples", "*.c")):
        examples |= {o for o in options_in([source], LITERAL) if not o.startswith(("-snes_type", "-pc_", "-ksp_", "-da_"))}
    expect(len(library) >= 15 and len(scene) >= 10 and len(examples) >= 10, "found only %s, %s and %s" % (sorted(library), sorted(scene), sorted(examples)))
    missing = sorted(o for o in library | scene | examples if o not in rows and (o + "<G>") not in rows and not any(r.startswith(o + "<G>") for r in rows))
    expect(not missing, "docs/options.md has no row for %s" % missing)
    for name in library:
        if name in rows and not name.startswith(("-snes_ssstar_monitor", "-snes_ssstar_newton")):
            expect(re.search(r"^\| `%s` \| `[^`]+`" % re.escape(name), table, re.M) is not None, "docs/options.md gives no default for %s" % name)


@test("README.md, docs/guide/*.md and docs/options.md link only to files that exist and to headings those pages have (tests/doc_commands.py), and the README links the guide's index and every page of docs/guide/")
def guide_links_resolve():
    import doc_commands
    broken = doc_commands.broken_links()
    expect(not broken, "broken links: %s" % broken)
    readme = open(os.path.join(ROOT, "README.md")).read()
    unlinked = [os.path.basename(p) for p in glob.glob(os.path.join(ROOT, "docs", "guide", "*.md")) if "docs/guide/" + os.path.basename(p) not in readme]
    expect(not unlinked, "the README does not link these guide pages: %s" % unlinked)
    index = open(os.path.join(ROOT, "docs", "guide", "README.md")).read()
    missing = [os.path.basename(p) for p in glob.glob(os.path.join(ROOT, "docs", "guide", "*.md")) if os.path.basename(p) != "README.md" and "(%s)" % os.path.basename(p) not in index]
    expect(not missing, "docs/guide/README.md does not list these pages: %s" % missing)


PY_LINE = re.compile(r"petsc4py \+ ssstar: (\S+) after (\d+) iterations; (\d+) contact nodes; Coulomb law violation (\S+); \|u - u_C\|/\|u_C\| = (\S+)")


@test("examples/prism.py (petsc4py, ssstar loaded by -dll_append only) solves the reduced prism problem saved by examples/prism -save_reduced: same iterations, the same u to 1e-8 (the reduced use scales by diag P, the whole body by diag K_CC: both stop at rtol 1e-10), the Coulomb law to 1e-7, on 1 and 2 ranks")
def petsc4py_reduced_prism():
    binary = os.path.join(OUT, "reduced_L4.bin")
    out = run(mpiexec(1, PRISM, "-level", "4", "-save_reduced", binary))
    its = int(re.search(r"^\s+4\s+1\s+\d+\s+[\d.]+\s+[\d.]+\s+\d+\s+[\d.]+\s+(\d+)", out, re.M).group(1))
    for ranks in (1, 2):
        py = run(mpiexec(ranks, PYTHON, os.path.join(ROOT, "examples", "prism.py"), binary))
        m = PY_LINE.search(py)
        expect(m is not None, "%d ranks: no summary from prism.py" % ranks, py)
        expect(m.group(1) == "CONVERGED_FNORM_RELATIVE" and int(m.group(2)) == its and int(m.group(3)) == 144,
               "%d ranks: %s after %s iterations (prism: %d)" % (ranks, m.group(1), m.group(2), its), py)
        expect(float(m.group(4)) <= 1e-7 and float(m.group(5)) <= 1e-8, "%d ranks: law %s, difference %s" % (ranks, m.group(4), m.group(5)), py)


SYNOPSIS = re.compile(r"^### (\w+)\n\nSynopsis:\n\n```c\n#include <(\w+\.h)>\n([^\n]*);\n```", re.M)


def compile_synopses(synopses, name):
    """Compiles a C file that assigns each public function to a pointer of its manual's synopsis type, with the
    project's compiler and flags and -Werror (an incompatible pointer is an error); returns (ok, compiler output)"""
    source = os.path.join(OUT, name + ".c")
    lines = ["#include <%s>" % os.path.basename(h) for h in sorted(glob.glob(os.path.join(ROOT, "include", "*.h")))] + [""]
    for k, (function, header, signature) in enumerate(synopses):
        lines.append("%s = %s;" % (signature.replace(" %s(" % function, " (*manual_%d)(" % k, 1), function))
    open(source, "w").write("\n".join(lines) + "\n")
    # a make of its own: under make test the jobserver's flags in the environment would add make's own messages
    env = {k: v for k, v in os.environ.items() if k not in ("MAKEFLAGS", "MFLAGS", "MAKELEVEL")}
    flags = shlex.split(subprocess.run(["make", "-s", "--no-print-directory", "print-cflags"], cwd=ROOT, env=env, stdout=subprocess.PIPE, text=True, check=True).stdout.strip())
    p = subprocess.run(flags + ["-Werror", "-c", source, "-o", os.path.join(OUT, name + ".o")], cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    return p.returncode == 0, p.stdout


@test("the manual's synopses are the C signatures: docs/manual.md has one synopsis per public function of include/*.h, each compiles as the type of a pointer assigned from the real function (the project's mpicc and flags, -Werror), and a synopsis whose parameter type drifts (SNES -> Mat) does not compile")
def manual_synopses_compile():
    synopses = SYNOPSIS.findall(open(os.path.join(ROOT, "docs", "manual.md")).read())
    public = set()
    for header in glob.glob(os.path.join(ROOT, "include", "*.h")):
        public |= set(re.findall(r"PETSC_EXTERN\s+[\w ]+?\s\**(\w+)\s*\(", open(header).read()))
    expect({s[0] for s in synopses} == public, "synopses for %s, public functions %s" % (sorted({s[0] for s in synopses} ^ public), "differ"))
    ok, out = compile_synopses(synopses, "manual_synopses")
    expect(ok, "the manual's synopses do not compile against the headers", out)
    drifted = [(f, h, s.replace("(SNES snes", "(Mat snes", 1)) for f, h, s in synopses]
    expect(any(d != s for d, s in zip(drifted, synopses)), "no SNES parameter to alter")
    ok, out = compile_synopses(drifted, "manual_synopses_drifted")
    expect(not ok and "incompatible" in out, "a drifted synopsis compiles", out)


@test("the derivation lives in the project (docs/derivation.md, cited by the README and the code) and its checks hold: tests/derivation_check.py on a random 16-node problem gives (d, b) in gph Q, the 6p and 3p Newton steps equal to 1e-12, T G = S H, quadratic convergence with omega = +d_t/|d_t| and at least twice the iterations with the slides' sign, and the library's kernels equal to the page's blocks")
def derivation_checks():
    page = open(os.path.join(ROOT, "docs", "derivation.md")).read()
    for equation in ("(1.1)", "(3.2)", "(4.1)", "(5.1)", "(5.2)", "(6.1)"):
        expect(equation in page, "docs/derivation.md has no equation %s" % equation)
    expect("docs/derivation.md" in open(os.path.join(ROOT, "README.md")).read() and "DERIVATION.md" not in open(os.path.join(ROOT, "README.md")).read(), "README does not cite docs/derivation.md")
    cited = [p for p in glob.glob(os.path.join(ROOT, "src", "**", "*.[ch]"), recursive=True) if "docs/derivation.md" in open(p).read()]
    expect(len(cited) >= 5, "the code cites docs/derivation.md in %d files" % len(cited))
    out = run([PYTHON, os.path.join(ROOT, "tests", "derivation_check.py")])
    expect("FAILED" not in out and "quadratic" in out, "derivation checks", out)


@test("the layout holds (issue 17): tests/layout_check.py finds no call circle between the C files of src/ (from their function definitions and calls), no include circle and no file over 800 lines in src/, include/, examples/, python/; and it does find them in a small tree made with a call circle through three files, an include circle and a long file")
def layout_no_circles():
    out = run([PYTHON, os.path.join(ROOT, "tests", "layout_check.py")])
    expect(re.search(r": 0 call circles, 0 include circles, 0 files over 800 lines$", out.strip()) is not None and int(out.split()[0]) >= 50, "the layout check", out)
    tree = os.path.join(OUT, "layout_tree")
    shutil.rmtree(tree, ignore_errors=True)
    os.makedirs(os.path.join(tree, "src", "x"))
    os.makedirs(os.path.join(tree, "include"))
    files = {"src/a.c": '#include "a.h"\nint A(void)\n{\n  return B() + Helper(); /* C() in a comment */\n}\nstatic int Helper(void)\n{\n  return 1;\n}\n',
             "src/x/b.c": "int B(void)\n{\n  return C(1);\n}\n",
             "src/x/c.c": 'int C(int k)\n{\n  if (k) return A();\n  return printf("B()");\n}\n',
             "src/d.c": "int D(void)\n{\n  return A();\n}\n" + "/* a long file */\n" * 801,
             "src/a.h": '#include "b.h"\n', "src/b.h": '#include "a.h"\n'}
    for name, text in files.items():
        with open(os.path.join(tree, name), "w") as f:
            f.write(text)
    out = run([PYTHON, os.path.join(ROOT, "tests", "layout_check.py"), "--root", tree], expect_rc=1)
    expect("call circle: src/a.c (A calls B) -> src/x/b.c (B calls C) -> src/x/c.c (C calls A) -> src/a.c" in out, "the made call circle is not found", out)
    expect("include circle: src/a.h -> src/b.h -> src/a.h" in out and "over 800 lines: src/d.c (805)" in out and ": 1 call circles, 1 include circles, 1 files over 800 lines" in out, "the made include circle or long file is not found", out)
