"""The Python module's prescribed displacements (tests/suite_displacement.py runs it): the compression of
suite_displacement as a Scene with displacement={"top": history} (None: a free component), its steps' rows with
groups/top/reaction, a file; then Scene.set(displacement=...) moves the lid on, and a new pattern of free components is
refused. Prints one line per step and the outcome; argv[1]: the output file."""
import sys

import petsc4py

petsc4py.init(sys.argv)
import ssstar  # noqa: E402

with ssstar.Scene(geo="meshes/block.geo", level=1, E=1000, nu=0.3, contact=["bottom"], friction_law={"bottom": "none"},
                  displacement={"top": [(0, (None, None, 0)), (1, (None, None, -0.005)), (2, ("free", None, -0.01))]}, o=sys.argv[1]) as scene:
    for step in scene.steps():
        print("t %g reaction %r normal_force %r" % (step.time, list(step.row["groups/top/reaction"]), step.row["normal_force"]))
    scene.set(displacement={"top": [(2, (None, None, -0.01)), (3, (None, None, -0.02))]})
    step = scene.step(3)
    print("t %g reaction %r normal_force %r" % (step.time, list(step.row["groups/top/reaction"]), step.row["normal_force"]))
    try:
        scene.set(displacement={"top": (0, None, -0.02)})
        print("not refused")
    except ssstar.Error as e:
        print("refused: %s" % str(e).splitlines()[0])
