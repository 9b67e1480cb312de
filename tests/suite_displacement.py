"""Prescribed displacements, reaction forces, stresses and strains (docs/guide/displacements-and-stresses.md,
docs/derivation.md section 15): a block compressed on a frictionless plane by its lid moved down with x, y free (the
reaction E A delta/h and the stress exact at every step), a clamped lid on a frictional base (the reaction balances
the contact force), a plane of symmetry through contact nodes (the half model is the mirrored full model's half), the
bad input refused by name, Hertz's subsurface stress, a cantilever against beam theory, the Python module."""
import json
import os
import re

import h5py
import numpy as np

from harness import *  # noqa: F401,F403 (run, expect, mpiexec, test, paths)

CONTACT = os.path.join(ROOT, "examples", "contact")
BLOCK = ["-geo", os.path.join(ROOT, "meshes", "block.geo"), "-level", "1", "-E", "1000", "-nu", "0.3"]
E, NU, AREA, HEIGHT = 1000.0, 0.3, 1.0, 0.5
STUCK = 24.6  # -reaction z of the clamped lid on a base with phi = 100 (every node sticks): 24.56 at level 1
PATHS = [(red, ranks) for red in ("direct", "none") for ranks in (1, 2)]


def contact(args, h5, ranks=1, expect_rc=0):
    out = run(mpiexec(ranks, CONTACT, *args, "-o", os.path.join(OUT, h5)), expect_rc=expect_rc)
    return out, h5py.File(os.path.join(OUT, h5), "r")


def law(h5):
    out = run(CHECK + ["law", os.path.join(OUT, h5), "--steps"])
    expect("VIOLATED" not in out and "WRONG" not in out, "check_solution.py law %s" % h5, out)


def states(f):
    """The top level and every step of a file: (prefix, time) pairs"""
    steps = sorted((k for k in f.get("steps", {}) if k.isdigit()), key=int)
    return [("steps/%s/" % k, f["steps/time"][int(k)]) for k in steps] if steps else [("", 0.0)]


@test("a block 1 x 1 x 0.5 (E = 1000, nu = 0.3) on a frictionless plane, its lid moved down by delta = 0, 0.005, 0.01 with x and y free (-displacement_top \"0:free,free,0;...\"), the rigid motions in the plane left to the kernel: at every step the lid's reaction /steps/groups/top/reaction is (0, 0, -E A delta/h) and the contact force its opposite to 1e-8, every cell's stress (0, 0, -E delta/h, 0, 0, 0), strain (nu, nu, -1, 0, 0, 0) delta/h and von Mises stress E delta/h to 1e-8 (also the nodal recovery), the displacement u_z = -delta z/h exact; the step line prints the reaction; the law holds at every step (check_solution.py law --steps); direct and none, 1 and 2 ranks")
def displacement_compression():
    for red, ranks in PATHS:
        h5 = "displacement_compression_%s_%d.h5" % (red, ranks)
        out, f = contact(BLOCK + ["-contact", "bottom", "-friction_law_bottom", "none", "-displacement_top", "0:free,free,0;1:free,free,-0.005;2:free,free,-0.01", "-snes_ssstar_reduction", red], h5, ranks)
        what = "%s %d ranks" % (red, ranks)
        expect(re.search(r"^step 3/3 t 2\.?: .* reaction of top \(0, 0, -20\)$", out, re.M) is not None, what + ": the step line does not print the lid's reaction", out)
        st = f["steps"]
        expect(len(st["time"]) == 3 and st["groups/top/reaction"].shape == (3, 3), what + ": no /steps/groups/top/reaction")
        for k, (prefix, t) in enumerate(states(f)):
            delta = 0.005 * t
            scale = E * delta / HEIGHT if delta else 1.0
            reaction = st["groups/top/reaction"][k]
            force = f[prefix + "contact/reaction"][:].sum(0)
            expect(np.abs(reaction - [0, 0, -E * AREA * delta / HEIGHT]).max() <= 1e-8 * scale, "%s t %g: the lid's reaction %s, not (0, 0, %g)" % (what, t, reaction, -E * AREA * delta / HEIGHT))
            expect(np.abs(reaction + force + st["load"][k]).max() <= 1e-8 * scale, "%s t %g: reaction %s + contact force %s + load do not balance" % (what, t, reaction, force))
            stress, strain, vm = f[prefix + "fields/stress"][:], f[prefix + "fields/strain"][:], f[prefix + "fields/von_mises"][:]
            exact = np.array([0, 0, -E * delta / HEIGHT, 0, 0, 0])
            expect(np.abs(stress - exact).max() <= 1e-8 * scale and np.abs(f[prefix + "fields/stress_nodal"][:] - exact).max() <= 1e-8 * scale, "%s t %g: stress off by %g" % (what, t, np.abs(stress - exact).max()))
            expect(np.abs(strain - np.array([NU, NU, -1, 0, 0, 0]) * delta / HEIGHT).max() <= 1e-8 * scale / E, "%s t %g: strain off by %g" % (what, t, np.abs(strain - np.array([NU, NU, -1, 0, 0, 0]) * delta / HEIGHT).max()))
            expect(np.abs(vm - E * delta / HEIGHT).max() <= 1e-8 * scale, "%s t %g: von Mises off" % (what, t))
            x, u = f["geometry/vertices"][:], f[prefix + "fields/displacement"][:]
            expect(np.abs(u[:, 2] + delta * x[:, 2] / HEIGHT).max() <= 1e-8 * max(delta, 1e-300), "%s t %g: u_z is not -delta z/h" % (what, t))
        law(h5)


@test("a lid clamped (-displacement_top 0,0,-0.01, every component) on a block on a frictional base (phi = 0.3): the lid's reaction /groups/top/reaction and the contact force balance (their sum zero to 1e-8 of the reaction), the reaction's z is between the frictionless E A delta/h = 20 and the fully stuck base's (24.56 at phi = 100); the lid's nodes are no contact nodes; direct and none, 1 and 2 ranks agree to 2e-6 (harness.AGREE); the law holds")
def displacement_clamped_balance():
    first = None
    for red, ranks in PATHS:
        h5 = "displacement_clamped_%s_%d.h5" % (red, ranks)
        out, f = contact(BLOCK + ["-contact", "bottom", "-friction_bottom", "0.3", "-displacement_top", "0,0,-0.01", "-snes_ssstar_reduction", red], h5, ranks)
        what = "%s %d ranks" % (red, ranks)
        reaction, force = f["groups/top/reaction"][:], f["contact/reaction"][:].sum(0)
        expect(np.abs(reaction + force).max() <= 1e-8 * np.abs(reaction).max(), "%s: the lid's reaction %s and the contact force %s do not balance" % (what, reaction, force), out)
        expect(0.01 * E * AREA / HEIGHT * 1.01 < -reaction[2] < STUCK, "%s: the reaction %s is not between the frictionless block's and the stuck one's" % (what, reaction))
        law(h5)
        if first is None:
            first = h5
        else:
            run(CHECK + ["compare", os.path.join(OUT, first), os.path.join(OUT, h5), "--tol", str(AGREE)])


def read_msh22(path):
    """The nodes {id: xyz}, elements [(type, tags, nodes)] and physical names lines of a gmsh 2.2 ASCII file"""
    lines = open(path).read().split("\n")
    i = lines.index("$PhysicalNames")
    names = lines[i + 1:i + 2 + int(lines[i + 1])]
    i = lines.index("$Nodes")
    nodes = {int(l.split()[0]): np.array([float(v) for v in l.split()[1:4]]) for l in lines[i + 2:i + 2 + int(lines[i + 1])]}
    i = lines.index("$Elements")
    elements = []
    for l in lines[i + 2:i + 2 + int(lines[i + 1])]:
        w = [int(v) for v in l.split()]
        elements.append((w[1], w[3:3 + w[2]], w[3 + w[2]:]))
    return nodes, elements, names


def mirror_msh22(half, full, plane_group):
    """The mesh of half mirrored about x = 0 and joined to it (the nodes on x = 0 shared): a full mesh whose halves are
    exact mirror images, without the faces of plane_group (inside the full body); written as gmsh 2.2"""
    nodes, elements, names = read_msh22(half)
    tag = int([l.split()[1] for l in names[1:] if l.split()[2].strip('"') == plane_group][0])
    n = max(nodes)
    image = {k: (k if abs(x[0]) < 1e-12 else k + n) for k, x in nodes.items()}
    allnodes = dict(nodes)
    allnodes.update({image[k]: x * [-1, 1, 1] for k, x in nodes.items() if image[k] != k})
    out = []
    for etype, tags, vs in elements:
        if tags[0] == tag:
            continue
        out.append((etype, tags, vs))
        mirrored = [image[v] for v in vs]
        mirrored[0], mirrored[1] = mirrored[1], mirrored[0]  # a mirror image turns the orientation: turn it back
        out.append((etype, tags, mirrored))
    with open(full, "w") as fp:
        fp.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n")
        kept = [l for l in names[1:] if int(l.split()[1]) != tag]
        fp.write("%d\n%s\n$EndPhysicalNames\n$Nodes\n%d\n" % (len(kept), "\n".join(kept), len(allnodes)))
        for k in sorted(allnodes):
            fp.write("%d %.17g %.17g %.17g\n" % ((k,) + tuple(allnodes[k])))
        fp.write("$EndNodes\n$Elements\n%d\n" % len(out))
        for j, (etype, tags, vs) in enumerate(out):
            fp.write("%d %d %d %s %s\n" % (j + 1, etype, len(tags), " ".join(map(str, tags)), " ".join(map(str, vs))))
        fp.write("$EndElements\n")


@test("a plane of symmetry through contact nodes (docs/derivation.md section 15): half a block (meshes/halfblock.geo, level 1) held in x on its face x = 0 (-displacement_sym 0,free,free), its lid clamped and moved down by 0.01, on a base with Coulomb friction phi = 0.3, and the full block (the half mirrored about x = 0, exact mirror images): the contact nodes on the plane stay contact nodes, their u_x and contact force's x are 0 (1e-12), and the half's displacements, contact forces and reactions are the full block's halves to 2e-6 (harness.AGREE; the reactions and forces twice the half's); the law holds on both; direct and none, 1 and 2 ranks")
def displacement_symmetry_plane():
    half, full = os.path.join(OUT, "halfblock_L1.msh"), os.path.join(OUT, "fullblock_L1.msh")
    run(["gmsh", "-3", "-setnumber", "L", "1", "-format", "msh22", os.path.join(ROOT, "meshes", "halfblock.geo"), "-o", half])
    mirror_msh22(half, full, "sym")
    common = ["-E", "1000", "-nu", "0.3", "-contact", "bottom", "-friction_bottom", "0.3", "-displacement_top", "0,0,-0.01"]
    for red, ranks in PATHS:
        what = "%s %d ranks" % (red, ranks)
        _, h = contact(["-mesh", half, "-displacement_sym", "0,free,free", "-snes_ssstar_reduction", red] + common, "displacement_half_%s_%d.h5" % (red, ranks), ranks)
        _, f = contact(["-mesh", full, "-snes_ssstar_reduction", red] + common, "displacement_full_%s_%d.h5" % (red, ranks), ranks)
        for name in ("half", "full"):
            law("displacement_%s_%s_%d.h5" % (name, red, ranks))
        xh, uh = h["geometry/vertices"][:], h["fields/displacement"][:]
        xf, uf = f["geometry/vertices"][:], f["fields/displacement"][:]
        cx, cu, cr = h["contact/coordinates"][:], h["contact/displacement"][:], h["contact/reaction"][:]
        plane = np.abs(cx[:, 0]) < 1e-12
        expect(plane.sum() == 5 and np.abs(cu[plane, 0]).max() <= 1e-12 and np.abs(cr[plane, 0]).max() <= 1e-12 * np.abs(cr).max(), "%s: the contact nodes on the plane (%d) move in x or are pushed in x: %s, %s" % (what, plane.sum(), cu[plane, 0], cr[plane, 0]))
        where = {tuple(np.round(x, 9)): k for k, x in enumerate(xf)}
        match = np.array([where[tuple(np.round(x, 9))] for x in xh])
        scale = np.abs(uf).max()
        expect(np.abs(uh - uf[match]).max() <= AGREE * scale, "%s: the half's displacement differs from the full block's by %g of its largest" % (what, np.abs(uh - uf[match]).max() / scale))
        rh, rf = h["groups/top/reaction"][:], f["groups/top/reaction"][:]
        expect(abs(2 * rh[2] - rf[2]) <= AGREE * abs(rf[2]) and abs(rf[0]) <= AGREE * abs(rf[2]) and abs(rh[1] * 2 - rf[1]) <= AGREE * abs(rf[2]), "%s: the half's reaction %s is not half the full block's %s" % (what, rh, rf))
        expect(np.abs(h["groups/sym/reaction"][:][[1, 2]]).max() == 0, "%s: the plane's reaction has a y or z component: %s" % (what, h["groups/sym/reaction"][:]))


@test("bad prescribed displacements are refused with one line naming the option, group or node, and no file: every component free; a value that is not a number; a history whose times do not increase; a node prescribed twice with different values (naming the node and both groups); a group both -dirichlet and -displacement_<G>; a contact node with a prescribed component that is no plane of symmetry (a value other than 0, naming the node, its contact group and the prescribing group); an unknown group; a body held by prescribed displacements in some directions only, without contact")
def displacement_refused():
    half = os.path.join(OUT, "halfblock_L1.msh")
    run(["gmsh", "-3", "-setnumber", "L", "1", "-format", "msh22", os.path.join(ROOT, "meshes", "halfblock.geo"), "-o", half])
    base = ["-mesh", half, "-E", "1000", "-nu", "0.3", "-contact", "bottom"]
    cases = [
        (["-displacement_top", "free,free,free"], r"Option -displacement_top free,free,free: every component is free, nothing is prescribed"),
        (["-displacement_top", "free,free,abc"], r"Option -displacement_top: value 3 \"abc\" is not a number"),
        (["-displacement_top", "1:0,0,0;0:0,0,-1"], r"Option -displacement_top: the times of the knots must increase"),
        (["-displacement_top", "0,0,-0.01", "-displacement_sym", "0.001,free,free"], r"Mesh node \d+ \(0-based, file order\) at \(0\.?, -?0\.\d+, 0\.5\) is prescribed twice with different values: its x displacement by -displacement_\w+ and by -displacement_\w+"),
        (["-dirichlet", "top", "-displacement_top", "0,0,-0.01"], r"Options -displacement_top and -dirichlet contradict each other: the group \"top\" is held fixed"),
        (["-displacement_sym", "0.001,free,free"], r"Mesh node \d+ \(0-based, file order\) at \(0\.?, -?0\.\d+, 0\.?\) of contact group \"bottom\" has its x displacement prescribed by -displacement_sym: a contact node may have some components prescribed only as on a plane of symmetry .*; here its prescribed value is not 0 at every time"),
        (["-displacement_sym", "0,free,free", "-obstacle_bottom", "plane:0,0,0,0.1,0,1"], r"of contact group \"bottom\" has its x displacement prescribed by -displacement_sym: .*; here the contact normal at the node has a component along it"),
        (["-displacement_lid", "0,0,-0.01"], r"has no physical group named \"lid\" \(option -displacement_lid\)"),
        (["-displacement_top", "free,free,-0.01", "-contact", "nothing"], r"nothing"),
    ]
    for k, (extra, message) in enumerate(cases):
        h5 = os.path.join(OUT, "displacement_refused_%d.h5" % k)
        if os.path.exists(h5):
            os.remove(h5)
        out = run([CONTACT] + base + extra + ["-o", h5], expect_rc=1)
        expect(re.search(message, out) is not None, "case %d %s: not refused with %r" % (k, extra, message), out)
        expect(not os.path.exists(h5), "case %d: a refused run wrote %s" % (k, h5))
    # no contact: the lid held in z alone leaves rigid motions free
    out = run([CONTACT, "-mesh", half, "-E", "1000", "-nu", "0.3", "-displacement_top", "free,free,-0.01"], expect_rc=1)
    expect(re.search(r"The body of volume group \"block\" .* is held in some directions only: its prescribed displacements .* leave 3 of its rigid-body motions free, and there is no contact to hold them", out) is not None, "a partly held body without contact is not refused by name", out)
