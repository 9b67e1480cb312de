"""What the benches against GetFEM 5.4 share (bench/getfem_prism.py, bench/getfem_ball.py): the environment of the
runs, ssstar's whole run timed, and GetFEM's mesh read from ssstar's mesh cache, so that both codes solve on the same
tetrahedra. Runs with Debian's python3-getfem (/usr/bin/python3)."""
import os
import re
import subprocess
import time

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "bench", "output")
MESH = re.compile(r"^mesh: file (\S+?), \d+ nodes", re.M)


def environment():
    """mpiexec as root in the containers, one BLAS thread per process (both codes alike)"""
    for k, v in (("OMPI_ALLOW_RUN_AS_ROOT", "1"), ("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1"), ("OPENBLAS_NUM_THREADS", "1")):
        os.environ.setdefault(k, v)
    os.makedirs(OUT, exist_ok=True)


def timed(cmd):
    """(output, seconds of the whole process) of a run of ssstar from the project's root; exits on its failure"""
    t0 = time.perf_counter()
    p = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    seconds = time.perf_counter() - t0
    if p.returncode:
        raise SystemExit("ssstar failed (%s):\n%s" % (" ".join(cmd), p.stdout[-3000:]))
    return p.stdout, seconds


def mesh_file(output):
    """the gmsh file of ssstar's mesh cache that a run names on its mesh line"""
    return MESH.search(output).group(1)


def mesh(path):
    """GetFEM's P1 mesh of the tetrahedra of ssstar's cache (the .h5 beside the gmsh file), its vertices in ssstar's
    order: (gf.Mesh, vertices)"""
    import getfem as gf
    with h5py.File(path + ".h5", "r") as f:
        x, cells = f["vertices"][:], f["cells"][:]
    m = gf.Mesh("empty", 3)
    m.add_convex(gf.GeoTrans("GT_PK(3,1)"), np.ascontiguousarray(x[cells].transpose(2, 1, 0)))
    return m, x
