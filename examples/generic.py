#!/usr/bin/python3
"""examples/generic.c in Python (petsc4py + the ssstar module): a block on a structured grid (DMDA, trilinear
elements) whose top face is pushed down and sideways, its bottom face above a rigid plane. The program assembles K and
b, solves F(u) = K u - b with a SNES and declares the bottom nodes as contact nodes through the module.

  examples/generic.py [-snes_type ssstar] [-o file.h5] [options of examples/generic]
  mpiexec -n 2 /usr/bin/python3 examples/generic.py -snes_converged_reason

Options (as examples/generic): -da_grid_x <9> -da_grid_y <9> -da_grid_z <5>, -size <1,1,0.5>, -E <2.1e5> -nu <0.3>,
-push <0.005,0,-0.01>, -obstacle_point <0,0,-0.002>, -obstacle_normal <0,0,1>, -o <file.h5> (the contact nodes'
coordinates, displacement, reaction, normal, gap and friction, as examples/generic writes them); and, to exercise the
per-node friction of the module:
  -phi_left <phi>      the bottom nodes with x < a/2 get this Coulomb coefficient (set_node_law_parameter
                       "friction")
  -tresca_right <s>    the bottom nodes with x > a/2 get Tresca friction with bound s (set_node_friction_laws,
                       set_node_law_parameter "slip_bound")
It prints the reason, ssstar's sub-reason, the iterations, the state counts, the smallest distance to the plane and
the normal force and the number of nodes of each law of the library's table, as one line starting "generic.py:"."""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "python"))
import petsc4py  # noqa: E402

petsc4py.init(sys.argv)
from petsc4py import PETSc  # noqa: E402

import ssstar  # noqa: E402  (the source tree's python/ssstar, or the installed one)


def vector_option(name, default):
    if not PETSc.Options().hasName(name[1:]):
        return np.array(default, dtype=float)
    value = PETSc.Options().getString(name[1:])
    v = np.array([float(x) for x in value.split(",")])
    if v.size != 3 or not np.isfinite(v).all():
        sys.exit("Option %s needs three comma-separated numbers x,y,z" % name)
    return v


def brick_stiffness(h, lam, mu):
    """The 24 x 24 stiffness of a trilinear brick h[0] x h[1] x h[2] (2 x 2 x 2 Gauss points); node a = di + 2 dj + 4 dk"""
    g, det = 1 / np.sqrt(3), h[0] * h[1] * h[2] / 8
    Ke = np.zeros((24, 24))
    signs = np.array([[1 if a & 1 else -1, 1 if a & 2 else -1, 1 if a & 4 else -1] for a in range(8)], dtype=float)
    for q in range(8):
        xi = np.array([g if q & 1 else -g, g if q & 2 else -g, g if q & 4 else -g])
        f = 1 + signs * xi
        dN = np.stack([signs[:, 0] * f[:, 1] * f[:, 2] / 8 * 2 / h[0], f[:, 0] * signs[:, 1] * f[:, 2] / 8 * 2 / h[1],
                       f[:, 0] * f[:, 1] * signs[:, 2] / 8 * 2 / h[2]], axis=1)
        for a in range(8):
            for b in range(8):
                block = lam * np.outer(dN[a], dN[b]) + mu * np.outer(dN[b], dN[a]) + mu * dN[a].dot(dN[b]) * np.eye(3)
                Ke[3 * a:3 * a + 3, 3 * b:3 * b + 3] += det * block
    return Ke


def main():
    opts = PETSc.Options()
    size = vector_option("-size", [1, 1, 0.5])
    push = vector_option("-push", [0.005, 0, -0.01])
    point = vector_option("-obstacle_point", [0, 0, -0.002])
    normal = vector_option("-obstacle_normal", [0, 0, 1])
    E, nu = opts.getReal("E", 2.1e5), opts.getReal("nu", 0.3)
    out = opts.getString("o", "")
    phi_left = opts.getReal("phi_left", -1.0)
    tresca_right = opts.getReal("tresca_right", -1.0)
    if not (E > 0 and -1 < nu < 0.5):
        sys.exit("-E %g -nu %g: need E > 0 and -1 < nu < 0.5" % (E, nu))
    normal = normal / np.linalg.norm(normal)
    comm = PETSc.COMM_WORLD

    da = PETSc.DMDA().create(dim=3, dof=3, sizes=(9, 9, 5), stencil_type=PETSc.DMDA.StencilType.BOX, stencil_width=1, comm=comm)
    da.setFromOptions()
    da.setUp()
    M, N, P = da.getSizes()
    (xs, xe), (ys, ye), (zs, ze) = da.getRanges()
    (gxs, gxe), (gys, gye), (gzs, gze) = da.getGhostRanges()
    h = size / (np.array([M, N, P]) - 1)
    lam, mu = E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))
    Ke = brick_stiffness(h, lam, mu)

    # K: each element added by the rank that owns its lowest corner, in the ghosted local numbering of the DMDA
    K = da.createMatrix()
    gx, gy = gxe - gxs, gye - gys
    for k in range(zs, min(ze, P - 1)):
        for j in range(ys, min(ye, N - 1)):
            for i in range(xs, min(xe, M - 1)):
                nodes = [((k + (a >> 2 & 1) - gzs) * gy + (j + (a >> 1 & 1) - gys)) * gx + (i + (a & 1) - gxs) for a in range(8)]
                idx = np.array([3 * n + c for n in nodes for c in range(3)], dtype=PETSc.IntType)
                K.setValuesLocal(idx, idx, Ke, addv=PETSc.InsertMode.ADD_VALUES)
    K.assemble()

    # the top face moves by push: identity rows and columns (K stays SPD), b carries the imposed values
    b, x = da.createGlobalVec(), da.createGlobalVec()
    rstart = x.getOwnershipRange()[0]
    xm, ym = xe - xs, ye - ys
    owned = lambda i, j, k: rstart + 3 * (((k - zs) * ym + (j - ys)) * xm + (i - xs))  # noqa: E731 (owned nodes, i fastest)
    rows = []
    if ze == P:
        for j in range(ys, ye):
            for i in range(xs, xe):
                for c in range(3):
                    rows.append(owned(i, j, P - 1) + c)
                    x.setValue(owned(i, j, P - 1) + c, push[c])
    x.assemble()
    b.zeroEntries()
    K.zeroRowsColumns(np.array(rows, dtype=PETSc.IntType), 1.0, x, b)

    # the bottom nodes (declared j fastest, as examples/generic.c): dofs, normals, gaps, coordinates
    n = xm * ym if zs == 0 else 0
    dofs = np.zeros(3 * n, dtype=PETSc.IntType)
    X = np.zeros((n, 3))
    for q in range(n):
        i, j = xs + q // ym, ys + q % ym
        X[q] = [size[0] * i / (M - 1), size[1] * j / (N - 1), 0.0]
        dofs[3 * q:3 * q + 3] = owned(i, j, 0) + np.arange(3)
    gaps = (X - point).dot(normal)
    if (gaps < 0).any():
        sys.exit("A bottom node starts inside the obstacle: move -obstacle_point")
    normals = np.tile(normal, (n, 1))

    snes = PETSc.SNES().create(comm=comm)
    ssstar.set_linear_problem(snes, K, b)  # F(u) = K u - b, Jacobian K
    snes.setType(ssstar.SNESSSSTAR)
    snes.setFromOptions()
    ssstar.set_contact_nodes(snes, dofs, normals, gaps)
    left, right = X[:, 0] < size[0] / 2, X[:, 0] > size[0] / 2
    if phi_left >= 0:
        phi = np.where(left, phi_left, ssstar.get_friction(snes))
        ssstar.set_node_law_parameter(snes, "friction", phi)
    if tresca_right >= 0:
        ssstar.set_node_friction_laws(snes, ["tresca" if right[q] else ssstar.get_friction_law(snes) for q in range(n)])
        ssstar.set_node_law_parameter(snes, "slip_bound", np.where(right, tresca_right, 0.0))
    u = da.createGlobalVec()
    u.zeroEntries()
    snes.solve(None, u)

    reason = snes.getConvergedReason()
    names = {getattr(PETSc.SNES.ConvergedReason, k): k for k in dir(PETSc.SNES.ConvergedReason) if not k.startswith("_")}
    states, counts = ssstar.get_states(snes)
    forces = ssstar.get_contact_forces(snes)
    laws = ssstar.get_node_friction_laws(snes)
    ua = u.getArray(readonly=True)[dofs - rstart].reshape(n, 3) if n else np.zeros((0, 3))
    worst = minimum(comm, float((ua.dot(normal) + gaps).min()) if n else np.inf)
    force = total(comm, [forces.dot(normal).sum()])[0]
    lawcounts = total(comm, np.bincount(laws, minlength=len(ssstar.FRICTION_LAWS))).astype(int)
    PETSc.Sys.Print("generic.py: %s %s after %d iterations; states %s; smallest distance to the plane %.6e; normal force %.6e; laws %s"
                    % (names.get(reason, reason), ssstar.get_reason(snes), snes.getIterationNumber(),
                       "/".join(str(c) for c in counts), worst, force, "/".join(str(c) for c in lawcounts)), comm=comm)
    if out:
        write(out, snes, X, ua, forces, normals, gaps)


def minimum(comm, value):
    """The smallest value over the ranks (through a Vec: no mpi4py needed)"""
    v = PETSc.Vec().createMPI((1, PETSc.DECIDE), comm=comm)
    v.setArray([value])
    return v.min()[1]


def total(comm, values):
    """The sums over the ranks of the entries of values, on every rank"""
    values = np.atleast_1d(np.asarray(values, dtype=float))
    k = len(values)
    v = PETSc.Vec().createMPI((k if comm.getRank() == 0 else 0, k), comm=comm)
    v.setValues(np.arange(k, dtype=PETSc.IntType), values, addv=PETSc.InsertMode.ADD_VALUES)
    v.assemble()
    scatter, w = PETSc.Scatter.toAll(v)
    scatter.scatter(v, w)
    return w.getArray().copy()


def write(path, snes, X, u, r, normals, gaps):
    """The layout of examples/generic.c's -o file: /contact/{coordinates, displacement, reaction, normal, gap}, each
    rank's nodes after those of the lower ranks, and the friction of each node as the library writes it
    (write_node_friction: friction_law and the parameters of the laws in use)"""
    comm = snes.getComm()
    viewer = PETSc.ViewerHDF5().createHDF5(path, "w", comm=comm)
    viewer.pushGroup("/contact")
    for name, values, bs in (("coordinates", X, 3), ("displacement", u, 3), ("reaction", r, 3), ("normal", normals, 3), ("gap", gaps, 1)):
        a = np.ascontiguousarray(np.asarray(values, dtype=PETSc.ScalarType).reshape(-1))
        v = PETSc.Vec().createMPI((a.size, PETSc.DECIDE), bsize=bs, comm=comm)
        v.setArray(a)
        v.setName(name)
        v.view(viewer)
        v.destroy()
    viewer.popGroup()
    ssstar.write_node_friction(snes, viewer, "/contact")
    viewer.destroy()


if __name__ == "__main__":
    main()
