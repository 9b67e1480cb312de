"""What costs a new user an hour (issue 31): where meshes go, what the checker calls agreement, errors that name the
option, values that are not "not given", the mark of a refined mesh, progress lines that say what was done."""
import os
import re
import shutil
import subprocess

from harness import *  # noqa: F401,F403 (run, expect, mpiexec, test, paths)

CONTACT = os.path.join(ROOT, "examples", "contact")


def fresh_dir(name):
    path = os.path.join(OUT, name)
    shutil.rmtree(path, ignore_errors=True)
    os.makedirs(path)
    return path


@test("a mesh made from a .geo goes into the mesh cache, never beside the .geo (the source tree): run from another "
      "directory, examples/prism -geo G -level 2 makes $XDG_CACHE_HOME/ssstar/<folder>-<hash>/<name>_L2.msh and its "
      "parallel cache beside it and writes nothing beside G; -mesh_cache D puts it in D; two runs meshing the same level "
      "into an empty cache at once both succeed (the files are written to temporary names and renamed); a -mesh_cache "
      "that cannot be made is refused naming it")
def mesh_cache():
    source = fresh_dir("cache_geo")
    geo = os.path.join(source, "prism.geo")
    shutil.copy(os.path.join(ROOT, "meshes", "prism.geo"), geo)
    xdg, elsewhere = fresh_dir("cache_xdg"), fresh_dir("cache_cwd")
    env = dict(os.environ, XDG_CACHE_HOME=xdg)
    p = subprocess.run(mpiexec(1, PRISM, "-geo", geo, "-level", "2"), cwd=elsewhere, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=300)
    expect(p.returncode == 0, "examples/prism run from another directory failed", p.stdout)
    msh = mesh_of(geo, 2, cache=os.path.join(xdg, "ssstar"))
    expect(os.path.exists(msh) and os.path.exists(msh + ".h5"), "no mesh %s (and its .h5 cache) in the cache" % msh, p.stdout)
    expect("mesh: file %s," % msh in p.stdout, "the mesh line does not name the cached file %s" % msh, p.stdout)
    expect(os.listdir(source) == ["prism.geo"] and not os.listdir(elsewhere), "files were written beside the .geo or in the working directory: %s %s" % (os.listdir(source), os.listdir(elsewhere)))
    cache = fresh_dir("cache_given")
    procs = [subprocess.Popen(mpiexec(1, PRISM, "-geo", geo, "-level", "3", "-mesh_cache", cache), cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True) for _ in range(2)]
    outs = [q.communicate(timeout=300)[0] for q in procs]
    for q, o in zip(procs, outs):
        expect(q.returncode == 0, "one of two runs meshing into the same empty cache at once failed", o)
    msh = mesh_of(geo, 3, cache=cache)
    expect(os.path.exists(msh) and [f for f in os.listdir(os.path.dirname(msh)) if not f.startswith("prism_L3.msh")] == [],
           "-mesh_cache: not the one mesh and its cache in %s: %s" % (os.path.dirname(msh), os.listdir(os.path.dirname(msh))))
    out = run(mpiexec(1, PRISM, "-level", "2", "-mesh_cache", "/proc/no_such_folder"), expect_rc=-1)
    expect("-mesh_cache /proc/no_such_folder: cannot make the folder or write to it" in out, "an impossible -mesh_cache is not refused by name", out)


@test("the set-up line of a solve says what its set-up did, and only then: on the gap's ten load steps (one K) the "
      "first says K was reduced (the dense route) or taken whole (reduction none), the nine others that it was kept and "
      "only the load changed")
def setup_line_says_what_was_done():
    for route, built, kept in (("direct", r"set-up: K reduced to \d+ contact dofs by the direct Schur complement, ",
                                r"set-up: K's reduction to \d+ contact dofs \(direct\) kept from the last solve, the new load reduced, "),
                               ("none", r"set-up: the whole body, \d+ dofs, P never formed \(reduction none\), ",
                                r"set-up: the whole body's K \(\d+ dofs\) kept from the last solve, the free dofs in equilibrium with the new load, ")):
        out = run(mpiexec(1, CONTACT, "-options_file", os.path.join(ROOT, "scenes", "gap.opts"), "-snes_ssstar_reduction", route))
        expect(len(re.findall(built, out)) == 1 and len(re.findall(kept, out)) == 9 and len(re.findall("set-up: ", out)) == 10,
               "%s: the set-up lines do not say once that K was %s and nine times that it was kept" % (route, "reduced" if route == "direct" else "taken whole"), out)
