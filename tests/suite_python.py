"""The Python module ssstar (python/ssstar: ctypes over libssstar.so, petsc4py objects): the whole-body API from a
Python program (examples/generic.py, examples/generic.c rewritten) on 1 and 2 ranks against the C program, every
setter and getter on a reduced problem, and the module as make install puts it."""
import os
import re
import shutil
import subprocess

import numpy as np

from harness import *  # noqa: F401,F403 (run, expect, mpiexec, test, paths)
from suite_generic import GENERIC, TILTED, by_coordinates

GENERIC_PY = os.path.join(ROOT, "examples", "generic.py")
MODULE_CHECK = os.path.join(ROOT, "tests", "python_module_check.py")
PY_LINE = re.compile(r"generic\.py: (\S+) (\S+) after (\d+) iterations; states ([\d/]+); smallest distance to the plane (\S+); normal force (\S+); laws ([\d/]+)")
C_LINE = re.compile(r"(\S+) after (\d+) iterations")


@test("examples/generic.py (petsc4py + the module: set_contact_nodes with normals and gaps, get_states, get_reason, get_contact_forces, get_node_friction_laws) solves examples/generic.c's tilted problem on 1 and 2 ranks: the same iterations and reason as the C program, the same displacement and reaction at every contact node to 1e-9, no penetration, and the file it writes passes tests/check_solution.py with the laws it records")
def python_generic_equals_c():
    c_out = run(mpiexec(1, GENERIC, "-snes_type", "ssstar", *TILTED, "-o", os.path.join(OUT, "py_generic_c.h5")))
    m = C_LINE.search(c_out)
    expect(m is not None, "no line from examples/generic", c_out)
    reference = by_coordinates("py_generic_c.h5")
    for ranks in (1, 2):
        name = "py_generic_np%d.h5" % ranks
        out = run(mpiexec(ranks, PYTHON, GENERIC_PY, *TILTED, "-o", os.path.join(OUT, name)))
        py = PY_LINE.search(out)
        expect(py is not None, "%d ranks: no summary from examples/generic.py" % ranks, out)
        expect(py.group(1) == m.group(1) and int(py.group(3)) == int(m.group(2)) and py.group(2) == "CONVERGED_RELATIVE",
               "%d ranks: %s (%s) after %s iterations, C: %s after %s" % (ranks, py.group(1), py.group(2), py.group(3), m.group(1), m.group(2)), out)
        expect(float(py.group(5)) >= -1e-12 and py.group(7) == "0/0/81/0", "%d ranks: distance %s, laws %s" % (ranks, py.group(5), py.group(7)), out)
        mine = by_coordinates(name)
        for field in ("displacement", "reaction", "gap"):
            d = np.abs(mine[field] - reference[field]).max() / np.abs(reference[field]).max()
            expect(d <= 1e-9, "%d ranks: %s differs from examples/generic by %.1e relative" % (ranks, field, d))
        law = run(CHECK + ["coulomb", os.path.join(OUT, name)])
        expect("VIOLATED" not in law and "81 Coulomb (phi 0.3)" in law, "%d ranks: the law" % ranks, law)


@test("per-node friction from Python on 2 ranks (examples/generic.py -phi_left 0.2 -tresca_right 30: set_node_law_parameter, set_node_friction_laws): the solver reports the laws back (get_node_friction_laws: 36 Tresca, 45 Coulomb), separated, sliding and sticking nodes, the law of each node holds (tests/check_solution.py with the file's laws), and 1 rank gives the same solution to 1e-9")
def python_node_friction():
    options = ["-phi_left", "0.2", "-tresca_right", "30", *TILTED]
    files = []
    for ranks in (2, 1):
        name = "py_mixed_np%d.h5" % ranks
        out = run(mpiexec(ranks, PYTHON, GENERIC_PY, *options, "-o", os.path.join(OUT, name)))
        py = PY_LINE.search(out)
        expect(py is not None and py.group(1) == "CONVERGED_FNORM_RELATIVE" and py.group(7) == "0/36/45/0", "%d ranks: %s" % (ranks, py.group(0) if py else "no summary"), out)
        law = run(CHECK + ["coulomb", os.path.join(OUT, name)])
        counts = re.search(r"separated (\d+), sliding (\d+), sticking (\d+)", law)
        expect("VIOLATED" not in law and "36 Tresca (s 30)" in law and "Coulomb (phi 0.2..0.3)" in law, "%d ranks: the law" % ranks, law)
        expect(counts is not None and all(int(c) > 0 for c in counts.groups()), "%d ranks: not every kind of node" % ranks, law)
        files.append(by_coordinates(name))
    for field in ("displacement", "reaction"):
        d = np.abs(files[0][field] - files[1][field]).max() / np.abs(files[1][field]).max()
        expect(d <= 1e-9, "%s: 2 ranks differ from 1 by %.1e relative" % (field, d))


@test("every function of the module on a reduced problem (set_linear_problem; per-node laws none/Tresca/Coulomb with per-node coefficients), 1 and 2 ranks: setters and getters round-trip, unknown names raise ValueError and a negative coefficient PETSc.Error (PETSC_ERR_ARG_OUTOFRANGE), the solve converges with ||z|| <= get_tolerance, get_states, get_node_friction_laws and get_node_law_parameter per local node, get_contact_forces = P u - f, and the friction law holds at every node")
def python_module_api():
    for ranks in (1, 2):
        out = run_python(mpiexec(ranks, PYTHON, MODULE_CHECK), os.path.join(ROOT, "python"))
        expect("test_module: ok" in out and os.path.join(ROOT, "lib", "libssstar.so") in out, "%d ranks: not ok, or not the source tree's library" % ranks, out)


@test("make install PREFIX=<tmp> installs the module in PREFIX/lib/python3/dist-packages/ssstar with the path of the installed library: from another folder, with that PYTHONPATH alone, tests/python_module_check.py imports it, loads PREFIX/lib/libssstar.so and passes on 2 ranks")
def python_module_installed():
    prefix = os.path.join(OUT, "prefix_python")
    shutil.rmtree(prefix, ignore_errors=True)
    out = run(["make", "-s", "install", "PREFIX=" + prefix])
    site = os.path.join(prefix, "lib", "python3", "dist-packages")
    expect(os.path.exists(os.path.join(site, "ssstar", "__init__.py")) and os.path.exists(os.path.join(site, "ssstar", "_config.py")), "make install did not install the module in %s" % site, out)
    expect(site in out, "make install does not say where the module is", out)
    elsewhere = os.path.join(OUT, "elsewhere")
    os.makedirs(elsewhere, exist_ok=True)
    shutil.copy(MODULE_CHECK, elsewhere)
    out = run_python(mpiexec(2, PYTHON, os.path.join(elsewhere, "python_module_check.py")), site, cwd=elsewhere)
    expect("test_module: ok" in out and os.path.join(prefix, "lib", "libssstar.so") in out, "the installed module does not load the installed library", out)


def run_python(cmd, path, cwd=ROOT):
    """Runs a Python program with PYTHONPATH = path (and nothing of the source tree on it)"""
    env = dict(os.environ, PYTHONPATH=path)
    env.pop("SSSTAR_LIB", None)
    p = subprocess.run(cmd, cwd=cwd, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=300)
    expect(p.returncode == 0, "exit status %d from %s" % (p.returncode, " ".join(cmd)), p.stdout)
    return p.stdout
