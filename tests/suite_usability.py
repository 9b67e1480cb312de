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


@test("libgmsh is opened only by a run that needs it (src/sys/gmshlib.c): lib/libssstar.so does not link it; a run "
      "that meshes a .geo into an empty cache loads it, the same run again from the cache never does (LD_DEBUG=files)")
def gmsh_only_to_mesh():
    needed = subprocess.run(["ldd", os.path.join(ROOT, "lib", "libssstar.so")], stdout=subprocess.PIPE, text=True).stdout
    expect("libgmsh" not in needed, "lib/libssstar.so links libgmsh", needed)
    cache = fresh_dir("gmsh_only_to_mesh")
    env = dict(os.environ, LD_DEBUG="files")
    for first in (True, False):
        p = subprocess.run(mpiexec(1, PRISM, "-level", "2", "-mesh_cache", cache), cwd=ROOT, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=300)
        expect(p.returncode == 0, "examples/prism -level 2 failed", p.stdout[-4000:])
        loaded = re.search(r"file=\S*libgmsh\.so", p.stdout) is not None
        expect(loaded == first, "libgmsh %s when the mesh %s in the cache" % ("was not loaded" if first else "was loaded", "was not" if first else "was"), p.stdout[-4000:])


@test("the set-up line of a solve says what its set-up did, and only then: on the gap's ten load steps (one K) the "
      "first says K was reduced (the dense route) or taken whole (reduction none), the nine others that it was kept and "
      "only the load changed", full=True)
def setup_line_says_what_was_done():
    for route, built, kept in (("direct", r"set-up: K reduced to \d+ contact dofs by the direct Schur complement, ",
                                r"set-up: K's reduction to \d+ contact dofs \(direct\) kept from the last solve, the new load reduced, "),
                               ("none", r"set-up: the whole body, \d+ dofs, P never formed \(reduction none\), ",
                                r"set-up: the whole body's K \(\d+ dofs\) kept from the last solve, the free dofs in equilibrium with the new load, ")):
        out = run(mpiexec(1, CONTACT, "-options_file", os.path.join(ROOT, "scenes", "gap.opts"), "-snes_ssstar_reduction", route))
        expect(len(re.findall(built, out)) == 1 and len(re.findall(kept, out)) == 9 and len(re.findall("set-up: ", out)) == 10,
               "%s: the set-up lines do not say once that K was %s and nine times that it was kept" % (route, "reduced" if route == "direct" else "taken whole"), out)


@test("check_solution.py compare judges two runs by the agreement the solver guarantees (default --tol 2e-6, "
      "harness.AGREE): the prism (level 4) on 1 and on 2 ranks agree by default, a copy whose contact displacement is off "
      "by 1e-5 of the largest is DIFFERENT; an FCLib solution file (examples/fclib -o) is compared (r, u, v) and checked "
      "(law: FCLib's error, u = W r + q) instead of crashing, and a reaction off by 1 % fails the law")
def check_solution_defaults():
    import h5py
    import numpy as np
    names = []
    for ranks in (1, 2):
        names.append(os.path.join(OUT, "usability_prism_np%d.h5" % ranks))
        run(mpiexec(ranks, PRISM, "-level", "4", "-o", names[-1]))
    out = run(CHECK + ["compare"] + names)
    expect("DIFFERENT" not in out, "1 and 2 ranks are DIFFERENT at compare's default tolerance", out)
    off = os.path.join(OUT, "usability_prism_off.h5")
    shutil.copy(names[0], off)
    with h5py.File(off, "r+") as f:
        u = f["contact/displacement"]
        u[0, 2] += 1e-5 * np.abs(u[:]).max()
    out = run(CHECK + ["compare", names[0], off], expect_rc=1)
    expect("displacement max difference" in out and "DIFFERENT" in out, "a displacement off by 1e-5 passes compare", out)
    problem = os.path.join(ROOT, "tests", "data", "fclib", "LMGC_GFC3D-i00001-1-00000.hdf5")
    sol = [os.path.join(OUT, "usability_fclib_np%d.h5" % ranks) for ranks in (1, 2)]
    for ranks, name in zip((1, 2), sol):
        run(mpiexec(ranks, os.path.join(ROOT, "examples", "fclib"), problem, "-o", name))
    out = run(CHECK + ["compare"] + sol)
    expect(re.search(r"solution/r\s+max difference .* ok", out) is not None and "solution/v" in out, "FCLib files not compared by r, u, v", out)
    out = run(CHECK + ["law", sol[0]])
    expect(re.search(r"FCLib error\s+\S+ .* ok", out) is not None, "the FCLib file's law not checked", out)
    bad = os.path.join(OUT, "usability_fclib_bad.h5")
    shutil.copy(sol[0], bad)
    with h5py.File(bad, "r+") as f:
        f["solution/r"][:] = 1.01 * f["solution/r"][:]
    out = run(CHECK + ["law", bad], expect_rc=1)
    expect("VIOLATED" in out, "a reaction off by 1 % passes the FCLib law", out)


@test("a value PETSc's options parser cannot read is refused naming the option, for every real, integer and logical "
      "option of ours and of PETSc's: -snes_rtol abc, -ksp_max_it 1.5, -E abc, -ssstar_progress maybe, an entry of "
      "-friction_direction_<G> 1,x,0 (one line, PETSc's error code, no file); from Python too (ssstar.Scene(snes_rtol='abc'))")
def bad_values_name_the_option():
    cases = [(["-snes_rtol", "abc"], "Option -snes_rtol abc: abc is not a number"),
             (["-ksp_max_it", "1.5"], "Option -ksp_max_it 1.5: 1.5 is not an integer"),
             (["-E", "abc"], "Option -E abc: abc is not a number"),
             (["-ssstar_progress", "maybe"], "Option -ssstar_progress maybe: maybe is not true or false"),
             (["-friction_law_contact", "orthotropic", "-friction_1_contact", "0.3", "-friction_2_contact", "0.6", "-friction_direction_contact", "1,x,0"],
              "Option -friction_direction_contact 1,x,0: x is not a number")]
    for args, message in cases:
        h5 = os.path.join(OUT, "usability_bad_value.h5")
        if os.path.exists(h5):
            os.remove(h5)
        p = subprocess.run([PRISM, "-level", "2", "-o", h5, *args], cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=120)
        lines = p.stdout.strip().splitlines()
        expect(p.returncode not in (0, NOT_CONVERGED) and lines and lines[0].endswith(": " + message) and len(lines) == 1 and not os.path.exists(h5),
               "%s: not one line '%s' and an error code without a file" % (" ".join(args), message), p.stdout)
    script = "import ssstar\ntry:\n    ssstar.Scene(%r, snes_rtol='abc')\nexcept ssstar.Error as e:\n    print('error:', e)\n" % os.path.join(ROOT, "scenes", "shear.opts")
    p = subprocess.run([PYTHON, "-c", script], cwd=ROOT, env=dict(os.environ, PYTHONPATH=os.path.join(ROOT, "python")), stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=120)
    expect("error: Option -snes_rtol abc: abc is not a number" in p.stdout, "Python's Scene does not name the option", p.stdout)


@test("a per-group direction whose first component is -2 (PETSC_DEFAULT) is a direction like any other: the orthotropic "
      "block (scenes/orthotropic.opts) with -friction_direction_bottom -2,1,0 solves with every node's friction direction "
      "(-2,1,0)/sqrt 5 in the file, as with the solver's -snes_ssstar_friction_direction -2,1,0 (the same file to 2e-6)")
def direction_minus_two_is_given():
    import h5py
    import numpy as np
    a, b = os.path.join(OUT, "usability_direction_group.h5"), os.path.join(OUT, "usability_direction_solver.h5")
    scene = [CONTACT, "-options_file", os.path.join(ROOT, "scenes", "orthotropic.opts")]
    run(mpiexec(1, *scene, "-friction_direction_bottom", "-2,1,0", "-o", a))
    run(mpiexec(1, *scene, "-friction_direction_bottom", "-2,1,0", "-snes_ssstar_friction_direction", "-2,1,0", "-o", b))
    with h5py.File(a, "r") as f:
        d = f["contact/friction_direction"][:]
    expect(np.abs(d - np.array([-2, 1, 0]) / np.sqrt(5)).max() < 1e-12, "the friction direction is not (-2,1,0)/sqrt 5: %s" % d[:3])
    run(CHECK + ["compare", a, b])


@test("a refined mesh is marked as such: prism level 2 with -dm_refine 1 prints the level 2r1 in its summary row, the "
      "scene view (examples/contact) says 'refined 1 time (-dm_refine)', and the file's /scene has refinements = 1")
def refined_mesh_marked():
    import h5py
    out, s = prism(2, extra=["-dm_refine", "1"], h5="usability_refined.h5")
    expect(s["level"] == 2 and s["refined"] == 1 and re.search(r"^\s*2r1\s", out, re.M) is not None, "the summary row does not read 2r1", out)
    with h5py.File(os.path.join(OUT, "usability_refined.h5"), "r") as f:
        expect(int(f["scene"].attrs["refinements"]) == 1, "/scene refinements is not 1")
    out = run(mpiexec(1, CONTACT, "-options_file", os.path.join(ROOT, "scenes", "shear.opts"), "-level", "1", "-dm_refine", "1"))
    expect(re.search(r"Scene: mesh \S+block_L1\.msh refined 1 time \(-dm_refine\), \d+ nodes", out) is not None, "the scene view does not mark the refinement", out)
    out, s = prism(2)
    expect(s["refined"] == 0 and re.search(r"^\s*2\s", out, re.M) is not None, "an unrefined level is marked", out)
