"""The contact search at scene level (src/geometry/search.c through contact/obstacles/mesh.c, contact/pairs/): the gaps and
normals of a mesh obstacle and of contact pairs equal those of a brute-force search over every triangle (NumPy, from
the mesh files), and are the same on 1, 2, 3 and 4 ranks."""
import os

import h5py
import numpy as np

from harness import *  # noqa: F401,F403 (run, expect, mpiexec, test, paths)
from suite_obstacles import sphere_msh
from suite_scenes import contact_run, scene

RANKS = (1, 2, 3, 4)


def read_msh41(path):
    """The nodes of a msh 4.1 file in file order (ascending tag), the triangles of each physical surface and the
    tetrahedra, by node index (a binary file, as ssstar meshes a .geo, read from gmsh's ASCII copy of it)"""
    with open(path, "rb") as f:
        binary = f.read(64).split(b"\n")[1].split()[1] == b"1"
    if binary:
        ascii_copy = os.path.join(OUT, os.path.basename(path) + ".ascii.msh")
        run(["gmsh", path, "-0", "-o", ascii_copy, "-format", "msh41", "-setnumber", "Mesh.Binary", "0"])
        path = ascii_copy
    lines = iter(open(path).read().split("\n"))
    names, entity_groups, tags, coords, triangles, tets = {}, {}, [], [], {}, []
    for line in lines:
        if line == "$PhysicalNames":
            for _ in range(int(next(lines))):
                dim, tag, name = next(lines).split(maxsplit=2)
                names[(int(dim), int(tag))] = name.strip('"')
        elif line == "$Entities":
            counts = [int(c) for c in next(lines).split()]
            for dim, count in enumerate(counts):
                for _ in range(count):
                    f = next(lines).split()
                    at = 4 if dim == 0 else 7
                    entity_groups[(dim, int(f[0]))] = [int(t) for t in f[at + 1:at + 1 + int(f[at])]]
        elif line == "$Nodes":
            nblocks = int(next(lines).split()[0])
            for _ in range(nblocks):
                n = int(next(lines).split()[3])
                block = [int(next(lines)) for _ in range(n)]
                tags += block
                coords += [[float(v) for v in next(lines).split()[:3]] for _ in range(n)]
        elif line == "$Elements":
            nblocks = int(next(lines).split()[0])
            for _ in range(nblocks):
                dim, entity, etype, n = (int(v) for v in next(lines).split())
                rows = [[int(v) for v in next(lines).split()[1:]] for _ in range(n)]
                if etype == 2:
                    for g in entity_groups.get((2, entity), []):
                        triangles.setdefault(names[(2, g)], []).extend(rows)
                elif etype == 4:
                    tets += rows
    order = np.argsort(tags)
    index = {t: i for i, t in enumerate(np.asarray(tags)[order])}
    x = np.asarray(coords)[order]
    tri = {name: np.array([[index[t] for t in row] for row in rows]) for name, rows in triangles.items()}
    return x, tri, np.array([[index[t] for t in row] for row in tets])


def closest_points(p, a, b, c):
    """The closest points of the triangles (a, b, c: T x 3) to the point p: the projection where it falls inside, else
    the closest point of the three edges"""
    n = np.cross(b - a, c - a)
    n /= np.linalg.norm(n, axis=1)[:, None]
    proj = p - ((p - a) * n).sum(1)[:, None] * n
    inside = np.ones(len(a), bool)
    for u, v in ((a, b), (b, c), (c, a)):
        inside &= (np.cross(v - u, proj - u) * n).sum(1) >= 0
    best, q = np.full(len(a), np.inf), np.zeros_like(a)
    for u, v in ((a, b), (b, c), (c, a)):
        t = np.clip(((p - u) * (v - u)).sum(1) / ((v - u) ** 2).sum(1), 0, 1)
        e = u + t[:, None] * (v - u)
        d = np.linalg.norm(p - e, axis=1)
        nearer = d < best
        q[nearer], best[nearer] = e[nearer], d[nearer]
    q[inside] = proj[inside]
    return q, np.linalg.norm(p - q, axis=1)


def contact_of(h5):
    c = h5py.File(os.path.join(OUT, h5), "r")["contact"]
    return {k: c[k][:] for k in ("coordinates", "gap", "normal", "group")}


def same_on_ranks(name, args, expect_rc=0):
    """Runs the scene on 1-4 ranks; every rank count's gaps and normals bit for bit those of 1 rank; the 1-rank data"""
    files = []
    for ranks in RANKS:
        files.append("search_%s_%d.h5" % (name, ranks))
        contact_run(args, h5=files[-1], ranks=ranks, expect_rc=expect_rc)
    one = contact_of(files[0])
    for ranks, h5 in zip(RANKS[1:], files[1:]):
        other = contact_of(h5)
        for key in ("gap", "normal"):
            d = np.abs(one[key] - other[key]).max()
            expect(d <= 1e-14, "%s: %s on %d ranks differs from 1 rank by %.2e" % (name, key, ranks, d))
    return one


@test("a mesh obstacle (a ball of radius 10 as 12000 triangles, the ball scene, level 1): every node's gap is its "
      "distance to the closest of all triangles found by brute force (NumPy) to 1e-12, its normal (x - q)/|x - q| "
      "to 1e-9 off the surface; the gaps and normals on 2, 3 and 4 ranks (the triangles spread over the ranks, no rank "
      "holding all) are those of 1 rank to 1e-14", full=True)
def search_mesh_obstacle():
    msh = sphere_msh()
    c = same_on_ranks("mesh_ball", scene("ball") + ["-obstacle_top", "mesh:" + msh])
    xv, tri, _ = read_msh41(msh)
    t = np.concatenate(list(tri.values()))
    a, b, cc = xv[t[:, 0]], xv[t[:, 1]], xv[t[:, 2]]
    worst_gap = worst_normal = 0.0
    for x, gap, n in zip(c["coordinates"], c["gap"], c["normal"]):
        q, d = closest_points(x, a, b, cc)
        k = np.argmin(d)
        worst_gap = max(worst_gap, abs(gap - d[k]))  # every node is outside the ball
        if d[k] > 1e-6:
            worst_normal = max(worst_normal, np.abs(n - (x - q[k]) / d[k]).max())
    expect(worst_gap <= 1e-12 and worst_normal <= 1e-9, "mesh ball against brute force: gaps %.2e, normals %.2e" % (worst_gap, worst_normal))


def pair_brute_force(msh, slave_x, master, tol):
    """Node-to-surface by brute force: of the master triangles within tol of the closest distance the least by sorted
    node indices; the gap and normal of pairs.c (the face's normal inside it or on its rim, the direction from the
    closest point beyond the rim, outside)"""
    xv, tri, tets = read_msh41(msh)
    t = tri[master]
    a, b, c = xv[t[:, 0]], xv[t[:, 1]], xv[t[:, 2]]
    cells = {tuple(sorted(f)): cell for cell in tets for f in ((cell[0], cell[1], cell[2]), (cell[0], cell[1], cell[3]), (cell[0], cell[2], cell[3]), (cell[1], cell[2], cell[3]))}
    n = np.cross(b - a, c - a)
    n /= np.linalg.norm(n, axis=1)[:, None]
    for k, f in enumerate(t):  # out of the master body: away from its cell's centroid
        if np.dot(n[k], (a[k] + b[k] + c[k]) / 3 - xv[list(cells[tuple(sorted(f))])].mean(0)) < 0:
            n[k] = -n[k]
    keys = np.sort(t, axis=1)
    gaps, normals = [], []
    for x in slave_x:
        q, d = closest_points(x, a, b, c)
        near = np.flatnonzero(d <= d.min() + tol)
        k = near[np.lexsort(keys[near].T[::-1])[0]]
        dc = x - q[k]
        length, gap = np.linalg.norm(dc), np.dot(dc, n[k])
        if abs(abs(gap) - length) <= tol * 1e2 + 1e-8 * length or length <= tol or gap <= 0:
            normal = n[k]
        else:
            normal, gap = dc / length, length
        gaps.append(0.0 if abs(gap) <= tol else gap)
        normals.append(normal)
    return np.array(gaps), np.array(normals)


PAIR_CASES = [
    # name, arguments, master group, expected exit status
    ("hertz2", scene("hertz2"), "block_top", 0),
    # the block's top meets the curved cap: ties between the cap's triangles matter, most nodes lie beyond its rim
    ("cap_master", ["-geo", "meshes/hertz2.geo", "-level", "1", "-E", "2.1e5", "-nu", "0.3", "-dirichlet", "block_bottom",
                    "-traction_top", "0,0,-100", "-spring_top", "1", "-contact", "block_top", "-contact_pair_block_top", "cap",
                    "-friction_law_block_top", "none", "-snes_max_it", "2"], "cap", NOT_CONVERGED),
]


@test("contact pairs, node-to-surface (hertz2 level 1; and the block's top as slave of the curved cap, most of its "
      "nodes beyond the cap's rim): every slave node's gap and normal equal those of a brute-force search over all "
      "master triangles (NumPy: the least sorted node indices among the triangles within the contact tolerance of the "
      "closest; triangles tied at a shared vertex or edge give the same gap, normal and weights) to 1e-12, and on 2, 3 "
      "and 4 ranks those of 1 rank to 1e-14", full=True)
def search_pairs_node_to_surface():
    for name, args, master, rc in PAIR_CASES:
        c = same_on_ranks(name, args, expect_rc=rc)
        msh = mesh_of("meshes/hertz2.geo", 1)  # in the mesh cache, where the runs above made it
        xv, _, _ = read_msh41(msh)
        tol = 1e-10 * np.linalg.norm(xv.max(0) - xv.min(0))
        gaps, normals = pair_brute_force(msh, c["coordinates"], master, tol)
        dg, dn = np.abs(gaps - c["gap"]).max(), np.abs(normals - c["normal"]).max()
        expect(dg <= 1e-12 and dn <= 1e-12, "%s against brute force: gaps %.2e, normals %.2e" % (name, dg, dn))


@test("contact pairs, dual mortar (hertz2 level 1; the block's top under the curved cap): the gaps and normals on 2, 3 "
      "and 4 ranks (each slave face's master triangles found on the ranks that hold them) are those of 1 rank to 1e-14", full=True)
def search_pairs_mortar():
    for name, args, _, rc in PAIR_CASES:
        same_on_ranks(name + "_mortar", args + ["-pair_discretization", "dual_mortar"], expect_rc=rc)
