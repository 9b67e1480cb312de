#!/usr/bin/python3
"""ssstar.Scene's contract, checked on a small block (tests/suite_pyscene.py runs it on 1 and 2 ranks): the arrays of
every step equal the datasets of the file written with them, bit for bit; keywords override the options file; a
misspelt keyword and a bad value raise ssstar.Error with the library's message; two scenes with other options live
side by side and leave petsc4py's database as it was; set(), write(), accept() refuse what they cannot do; a scene on
PETSC_COMM_SELF solves alone on each rank. Prints "test_scene: ok" and the module's library path. Usage:
python_scene_check.py OUTPUT_FOLDER [PETSc options]"""
import os
import sys

import h5py
import numpy as np
import petsc4py

petsc4py.init(sys.argv[:1] + sys.argv[2:])
from petsc4py import PETSc  # noqa: E402

import ssstar  # noqa: E402  (PYTHONPATH decides which: the source tree's python/ or an installed one)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import AGREE  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = sys.argv[1]
BLOCK = dict(geo=os.path.join(ROOT, "meshes", "block.geo"), level=1, E=2e8, nu=0.3, spring={"top": 1000},
             contact=["bottom"], friction={"bottom": 0.5})
PATH = [(0, (0, 0, 0)), (1, (0, 0, -10)), (2, (7.5, 0, -10)), (3, (0, 0, -10))]


def expect(cond, message):
    if not cond:
        PETSc.Sys.Print("test_scene: FAILED: " + message)
        sys.exit(1)


def agrees(a, b):
    """Two solves of one problem (another scene between them, another process): within harness.AGREE of the largest,
    not bit for bit (a parallel factorization's round-off may differ from one run to the next)"""
    a, b = np.asarray(a), np.asarray(b)
    return a.shape == b.shape and np.abs(a - b).max() <= AGREE * max(np.abs(b).max(), 1e-300)


def raises(kind, fn, *words):
    """fn() raises kind, with each of words in its message; returns the exception"""
    try:
        fn()
    except kind as e:
        expect(all(w in str(e) for w in words), "%s: %r lacks %s" % (kind.__name__, str(e), words))
        return e
    expect(False, "no %s (expected %s)" % (kind.__name__, words))


def steps_equal_file():
    """The Step arrays and rows are the file's /steps/<k> datasets and /steps rows, bit for bit"""
    h5 = os.path.join(OUT, "pyscene_check_path.h5")
    with ssstar.Scene(traction={"top": PATH}, **BLOCK) as scene:
        scene.write(h5)
        steps = list(scene.steps())
        vertices, nodes = scene.vertices, scene.contact_nodes
    expect([s.time for s in steps] == [0, 1, 2, 3] and all(s.converged for s in steps), "the knots as steps, converged")
    f = h5py.File(h5, "r")
    expect(np.array_equal(vertices, f["geometry/vertices"][()]), "vertices")
    for name in ("coordinates", "normal", "gap", "area", "group"):
        expect(np.array_equal(nodes[name], f["contact"][name][()]), "contact_nodes %s" % name)
    for k, step in enumerate(steps):
        g = f["steps/%d" % k]
        expect(np.array_equal(step.displacement, g["fields/displacement"][()]), "step %d: displacement" % k)
        for name, values in step.contact.items():
            expect(np.array_equal(values, g["contact"][name][()]), "step %d: contact/%s" % (k, name))
        expect(set(step.contact) == set(g["contact"]), "step %d: the fields %s, the file's %s" % (k, sorted(step.contact), sorted(g["contact"])))
        for name, value in step.row.items():
            expect(np.array_equal(np.asarray(value), f["steps"][name][k]), "step %d: row %s %s, file %s" % (k, name, value, f["steps"][name][k]))
        expect(step.sliding().sum() == step.row["sliding"] and step.sticking().sum() == step.row["sticking"]
               and step.separated().sum() == step.row["separated"], "step %d: the masks count as the row" % k)
    expect(steps[2].sliding().all() is not True and steps[2].row["sliding"] > 0, "sliding at the shear")


def keywords_and_file():
    """A keyword overrides the file's option; a misspelt one is refused naming the nearest (also when the database has it
    already); bad values by the library"""
    shear = os.path.join(ROOT, "scenes", "shear.opts")
    with ssstar.Scene(shear, level=1, geo=BLOCK["geo"]) as scene:
        expect(scene.nodes == 75 and scene.contact_size == 25, "level 1 of the file's block: %d nodes" % scene.nodes)  # (4+1)(4+1)(2+1)
    e = raises(ssstar.Error, lambda: ssstar.Scene(shear, geo=BLOCK["geo"], level=1, frction={"bottom": 0.5}), "Unknown option -frction_bottom", "nearest known option: -friction_bottom")
    expect(e.ierr == 95 and isinstance(e, PETSc.Error), "an unknown option: PETSc's code 95 (PETSC_ERR_USER_INPUT), a PETSc.Error")
    raises(ssstar.Error, lambda: ssstar.Scene(shear, geo=BLOCK["geo"], level=1, E=-1), "-E -1.: Young's modulus must be a positive number")
    raises(ssstar.Error, lambda: ssstar.Scene(shear, geo=BLOCK["geo"], level=1, steps_max_cutz=2), "-steps_max_cutz", "nearest known option: -steps_max_cuts")
    raises(ssstar.Error, lambda: ssstar.Scene(os.path.join(OUT, "no_such.opts")), "no_such.opts")
    db = PETSc.Options()  # the same misspelt option already in the database (the command line), read there: refused too
    db.setValue("levle", "1")
    db.hasName("levle")
    raises(ssstar.Error, lambda: ssstar.Scene(shear, geo=BLOCK["geo"], levle=1), "Unknown option -levle", "nearest known option: -level")
    expect(db.getString("levle", None) == "1", "the database's value is back")
    db.delValue("levle")
    raises(ssstar.Error, lambda: ssstar.Scene(traction={"top": "0:0,0,0;1:0,0"}, **BLOCK), "-traction_top")


def side_by_side():
    """Two scenes with other options, used in turn, give what each gives alone, and leave the database as it was"""
    before = PETSc.Options().getAll()
    a = ssstar.Scene(traction={"top": (4, 0, -10)}, **BLOCK)
    b = ssstar.Scene(traction={"top": (4, 0, -10)}, **dict(BLOCK, friction={"bottom": 0.3}))
    sa, sb = a.solve(), b.solve()
    sa2 = a.solve()
    a.close()
    b.close()
    expect(agrees(sa.displacement, sa2.displacement), "scene a solved again after b")
    expect(abs(sb.row["tangential_force"][0] + 0.3 * sb.row["normal_force"]) < 1e-6 and abs(sa.row["tangential_force"][0] + 4) < 1e-4,
           "phi 0.3 slides (T = 0.3 N), phi 0.5 holds 4: %s, %s" % (sb.row["tangential_force"], sa.row["tangential_force"]))
    with ssstar.Scene(traction={"top": (4, 0, -10)}, **dict(BLOCK, friction={"bottom": 0.3})) as alone:
        expect(agrees(alone.solve().displacement, sb.displacement), "b alone")
    expect(PETSc.Options().getAll() == before, "the database changed: %s" % (set(PETSc.Options().getAll().items()) ^ set(before.items())))


def refusals():
    with ssstar.Scene(traction={"top": PATH}, **BLOCK) as scene:
        raises(RuntimeError, scene.accept, "no converged step waits")
        raises(ssstar.Error, lambda: scene.set(traction={"bottom": (1, 0, 0)}), "no traction on bottom")
        raises(ssstar.Error, lambda: scene.set(gravity=(0, 0, -9.81)), "the scene has no gravity")
        raises(ssstar.Error, lambda: scene.set(obstacle_motion={"bottom": (0, 0, 0)}), "has no motion")
        raises(ValueError, lambda: scene.set(friction={"bottom": 0.1}), "set() changes the histories")
        scene.step(1)
        raises(RuntimeError, lambda: scene.write(os.path.join(OUT, "late.h5")), "before its first step")
        raises(ValueError, lambda: scene.step(float("nan")), "not a finite number")
        raises(ssstar.Error, lambda: scene.step(0.5), "The time 0.5 of a step is before the last accepted step's, 1")  # issue 31
    for steps, words in ((-3, ("-steps", "-3")), (0, ("-steps", "0")), ("1,0.5", ("-steps", "increas"))):  # issue 31: at construction
        raises(ssstar.Error, lambda: ssstar.Scene(traction={"top": PATH}, steps=steps, **BLOCK), *words)
    with ssstar.Scene(traction={"top": (1, 0, -10)}, **BLOCK) as scene:
        scene.write(os.path.join(OUT, "pyscene_early.h5"))  # before the solve: the file of what comes
        raises(ssstar.Error, lambda: scene.write(os.path.join(OUT, "missing", "f.h5")), "Cannot write")
        scene.solve()
    expect(os.path.exists(os.path.join(OUT, "pyscene_early.h5")), "solve() writes the file of write()")
    raises(ssstar.Error, lambda: ssstar.Scene(traction={"top": (1, 0, -10)}, o=os.path.join(OUT, "missing", "f.h5"), **BLOCK), "Cannot write")


def tentative_steps():
    """step(t, accept=False) changes nothing until accept(); set() changes the load of the next step"""
    with ssstar.Scene(traction={"top": (0, 0, -10)}, **BLOCK) as scene:
        first = scene.step(0)
        scene.set(traction={"top": (9, 0, -10)})
        far = scene.step(1, accept=False)  # slides: refused
        scene.set(traction={"top": (2, 0, -10)})
        near = scene.step(1)
    with ssstar.Scene(traction={"top": (0, 0, -10)}, **BLOCK) as scene:
        scene.step(0)
        scene.set(traction={"top": (2, 0, -10)})
        direct = scene.step(1)
    expect(first.converged and far.row["groups/top/displacement"][0] > 1e-3, "the tentative step slides: %s" % far.row["groups/top/displacement"])
    expect(agrees(near.displacement, direct.displacement), "a refused step leaves no trace")
    expect("slip_path" in near.contact and agrees(near.contact["slip_path"], direct.contact["slip_path"]), "the path's fields of the accepted step")


def own_communicator():
    """Each rank its own scene on PETSC_COMM_SELF (a parameter sweep split over the ranks)"""
    rank = PETSc.COMM_WORLD.getRank()
    with ssstar.Scene(traction={"top": (1 + rank, 0, -10)}, comm=PETSc.COMM_SELF, **BLOCK) as scene:
        step = scene.solve()
    expect(step.converged and abs(step.row["tangential_force"][0] + 1 + rank) < 1e-4, "rank %d alone: %s" % (rank, step.row["tangential_force"]))


def documented():
    text = ssstar.Scene.__doc__ + ssstar.Step.__doc__
    for word in ("solve()", "steps(times=None)", "step(t, accept=True)", "set(traction", "write(file)", "close()", "obstacle_motion", "ssstar.Error", "contact_nodes"):
        expect(word in text, "help(ssstar.Scene) does not say %s" % word)
    expect(ssstar.__version__.count(".") == 2, "a version")


def main():
    steps_equal_file()
    keywords_and_file()
    side_by_side()
    refusals()
    tentative_steps()
    own_communicator()
    documented()
    PETSc.Sys.Print("test_scene: ok, %s %s" % (ssstar.__version__, ssstar.library))


if __name__ == "__main__":
    main()
