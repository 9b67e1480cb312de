"""Prescribed displacements, reaction forces, stresses and strains (docs/guide/displacements-and-stresses.md,
docs/derivation.md section 15): a block compressed on a frictionless plane by its lid moved down with x, y free (the
reaction E A delta/h and the stress exact at every step), a clamped lid on a frictional base (the reaction balances
the contact force), a plane of symmetry through contact nodes (the half model is the mirrored full model's half), the
bad input refused by name, Hertz's subsurface stress, a cantilever against beam theory, the Python module."""
import json
import os
import re
import subprocess

import h5py
import numpy as np
import scene_answers

from harness import *  # noqa: F401,F403 (run, expect, mpiexec, test, paths)

CONTACT = os.path.join(ROOT, "examples", "contact")
BLOCK = ["-geo", os.path.join(ROOT, "meshes", "block.geo"), "-level", "1", "-E", "1000", "-nu", "0.3"]
E, NU, AREA, HEIGHT = 1000.0, 0.3, 1.0, 0.5
STUCK = 24.6  # -reaction z of the clamped lid on a base with phi = 100 (every node sticks): 24.56 at level 1
PATHS = [(red, ranks) for red in ("direct", "none") for ranks in (1, 2)]
CROSS = [("direct", 1), ("none", 2)]  # both paths and both rank counts, in two runs


@test("docs/derivation.md section 15 holds (tests/displacement_check.py, numpy, independent of the C code): the identity rows give u_D = g and the lifted free equations, the reaction is the constraint's multiplier, the reduction of K' is that of K_FF with the lifted load (to 1e-12); a P1 cube held in z on its top keeps 3 rigid motions; a contact node held in x on a plane of symmetry (Coulomb) has u_x = 0 and no force along x; the P1 strain of a linear field is exact; Hertz's on-axis von Mises maximum is 0.62 p0 at 0.48 a")
def displacement_derivation():
    out = run([PYTHON, os.path.join(ROOT, "tests", "displacement_check.py")])
    expect(out.count("PASS") == 6 and "FAIL" not in out, "tests/displacement_check.py", out)


@test("the P1 tetrahedron's kernels give hand-computed values (tests/test_stress.c): the strain of u = A x + c is sym(A) on a unit and a distorted tetrahedron, whatever the vertices' order, zero for a small rotation; Hooke's stress of (1, -nu, -nu) is (E, 0, 0) and of a shear 2 mu eps; von Mises |s|, sqrt(3) |tau|, 0 for a hydrostatic stress, sqrt(234) for (1, ..., 6)")
def displacement_kernels():
    out = run([os.path.join(ROOT, "tests", "test_stress")])
    expect("passed: 0 failures" in out, "tests/test_stress", out)


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


@test("a lid clamped (-displacement_top 0,0,-0.01, every component) on a block on a frictional base (phi = 0.3): the lid's reaction /groups/top/reaction and the contact force balance (their sum zero to 1e-8 of the reaction), the reaction's z is between the frictionless E A delta/h = 20 and the fully stuck base's (24.56 at phi = 100); the lid's nodes are no contact nodes; direct on 1 rank and none on 2 agree to 2e-6 (harness.AGREE); the law holds")
def displacement_clamped_balance():
    first = None
    for red, ranks in CROSS:
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


@test("a plane of symmetry through contact nodes (docs/derivation.md section 15): half a block (meshes/halfblock.geo, level 1) held in x on its face x = 0 (-displacement_sym 0,free,free), its lid clamped and moved down by 0.01, on a base with Coulomb friction phi = 0.3, and the full block (the half mirrored about x = 0, exact mirror images): the contact nodes on the plane stay contact nodes, their u_x and contact force's x are 0 (1e-12), and the half's displacements, contact forces and reactions are the full block's halves to 2e-6 (harness.AGREE; the reactions and forces twice the half's); the law holds on both; direct on 1 rank, none on 2", full=True)
def displacement_symmetry_plane():
    half, full = os.path.join(OUT, "halfblock_L1.msh"), os.path.join(OUT, "fullblock_L1.msh")
    run(["gmsh", "-3", "-setnumber", "L", "1", "-format", "msh22", os.path.join(ROOT, "meshes", "halfblock.geo"), "-o", half])
    mirror_msh22(half, full, "sym")
    common = ["-E", "1000", "-nu", "0.3", "-contact", "bottom", "-friction_bottom", "0.3", "-displacement_top", "0,0,-0.01"]
    for red, ranks in CROSS:
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


@test("bad prescribed displacements are refused with one line naming the option, group or node, and no file: every component free; a value that is not a number; a history whose times do not increase; a node prescribed twice with different values (naming the node and both groups); a group both -dirichlet and -displacement_<G>; a contact node with a prescribed component that is no plane of symmetry (a value other than 0, a normal along it, a contact pair's slave: naming the node, its contact group and the prescribing group); a prescribed node on a pair's master surface; an unknown group; a body held by prescribed displacements in some directions only, without contact")
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
    # contact pairs: a prescribed master node; a slave node with a prescribed component
    hertz2 = ["-options_file", os.path.join(ROOT, "scenes", "hertz2.opts")]
    for extra, message in ((["-displacement_block_top", "0,0,0"], r"Mesh node \d+ \(0-based, file order\) of the master surface block_top of contact pair cap has a displacement prescribed by -displacement_block_top: a pair's master nodes may not be prescribed"),
                           (["-displacement_cap", "free,free,0"], r"of contact group \"cap\" has its z displacement prescribed by -displacement_cap: .*; here its group's contact is a contact pair")):
        out = run([CONTACT] + hertz2 + extra, expect_rc=1)
        expect(re.search(message, out) is not None, "%s: not refused with %r" % (extra, message), out)
    # no contact: the lid held in z alone leaves rigid motions free
    out = run([CONTACT, "-mesh", half, "-E", "1000", "-nu", "0.3", "-displacement_top", "free,free,-0.01"], expect_rc=1)
    expect(re.search(r"The body of volume group \"block\" .* is held in some directions only: its prescribed displacements .* leave 3 of its rigid-body motions free, and there is no contact to hold them", out) is not None, "a partly held body without contact is not refused by name", out)


@test("the stresses in the XDMF file: VTK's vtkXdmfReader (what ParaView uses) reads the compression's file (a load path) with the cell arrays strain, stress (full symmetric tensors, 9 components, built from the file's xx, yy, zz, yz, xz, xy) and von_mises and the point array stress_nodal at every time, their means the HDF5 file's")
def displacement_xdmf():
    from suite_loadpath import vtk_python
    h5 = os.path.join(OUT, "displacement_compression_none_2.h5")
    if not os.path.exists(h5):
        contact(BLOCK + ["-contact", "bottom", "-friction_law_bottom", "none", "-displacement_top", "0:free,free,0;1:free,free,-0.005;2:free,free,-0.01", "-snes_ssstar_reduction", "none"], os.path.basename(h5), 2)
    py = vtk_python()
    expect(py is not None, "no Python with VTK's vtkXdmfReader: pip install vtk (or set SSSTAR_VTK_PYTHON)")
    steps = json.loads(run([py, os.path.join(ROOT, "tests", "xdmf_check.py"), h5.replace(".h5", ".xmf")]))
    f = h5py.File(h5, "r")
    full = lambda s: s[:, [0, 5, 4, 5, 1, 3, 4, 3, 2]]  # noqa: E731 (xx, yy, zz, yz, xz, xy as VTK's 3 x 3 rows)
    for k, s in enumerate(steps):
        mesh = s["grids"]["mesh"]
        for name in ("strain", "stress", "von_mises"):
            data = f["steps/%d/fields/%s" % (k, name)][:]
            mean = (full(data) if data.ndim == 2 else data[:, None]).mean(axis=0)
            got = np.array(mesh["cell_means"].get(name, []))
            expect(got.shape == mean.shape and np.allclose(got, mean, rtol=1e-12, atol=1e-15 * max(1, np.abs(mean).max())), "step %d: the XDMF's cell array %s has the means %s, the file %s" % (k, name, got, mean))
        mean = full(f["steps/%d/fields/stress_nodal" % k][:]).mean(axis=0)
        got = np.array(mesh["means"].get("stress_nodal", []))
        expect(got.shape == mean.shape and np.allclose(got, mean, rtol=1e-12, atol=1e-12 * max(1, np.abs(mean).max())), "step %d: the XDMF's point array stress_nodal has the means %s, the file %s" % (k, got, mean))


@test("Hertz's subsurface stress (scenes/hertz.opts at level 1, nu = 0.3, mesh size h = 0.2 near the pole): the largest von Mises stress of the cells on the axis (centroid within h/2) is 0.62 p0 at the depth 0.48 a, within what cells of size h resolve: the value within 0.62 p0 - min(vm(0.48 a - h), vm(0.48 a + h)) = 0.056 p0 and the depth within h, with a and p0 Hertz's for the measured normal force; the law holds")
def displacement_hertz_stress():
    out, f = contact(["-options_file", os.path.join(ROOT, "scenes", "hertz.opts"), "-level", "1"], "displacement_hertz_L1.h5")
    law("displacement_hertz_L1.h5")
    nu, E, R, h = 0.3, 2.1e5, 10.0, 0.2
    F = f["contact/reaction"][:, 2].sum()
    a = (3 * F * R / (4 * E / (1 - nu ** 2))) ** (1 / 3)
    p0 = 3 * F / (2 * np.pi * a ** 2)
    zz = np.linspace(0.01, 3, 30000)
    theory = scene_answers.hertz_on_axis(zz, nu)
    zmax, vmax = zz[theory.argmax()], theory.max()
    expect(abs(vmax - 0.62) < 0.005 and abs(zmax - 0.48) < 0.005, "Hertz's on-axis maximum %.4f p0 at %.4f a, not 0.62 at 0.48" % (vmax, zmax))
    tol = vmax - min(scene_answers.hertz_on_axis(np.array([zmax - h / a, zmax + h / a]), nu))
    x, cells, vm = f["geometry/vertices"][:], f["viz/topology/cells"][:], f["fields/von_mises"][:]
    centre = x[cells].mean(axis=1)
    axis = (np.hypot(centre[:, 0], centre[:, 1]) < h / 2) & (centre[:, 2] < 2 * a)
    j = np.argmax(vm[axis])
    value, depth = vm[axis][j] / p0, centre[axis][j, 2] / a
    expect(abs(value - vmax) <= tol and abs(depth - zmax) <= h / a, "the largest von Mises stress on the axis is %.4f p0 at %.3f a (Hertz %.4f at %.3f; tolerances %.3f p0, %.3f a)" % (value, depth, vmax, zmax, tol, h / a), out)


@test("a cantilever beam 10 x 1 x 1 (meshes/cantilever.geo, E = 1000, nu = 0.3) clamped at its root (-dirichlet root), a tip load P = 1 (-traction_tip 0,0,-1): away from the ends (x = 2.5, 5, 7.5) the shear force of the cells' stresses over a section is P to 1e-6 and their bending moment is beam theory's P (L - x), short by P1 tetrahedra's bending error, which falls as h^2: 15-25 % at level 2, 4-9 % at level 4, 3x or more from one to the other (1.8 % at level 8); the root's reaction /groups/root/reaction balances the load (0, 0, P) to 1e-8")
def displacement_cantilever():
    errors = {}
    for level in (2, 4):
        out, f = contact(["-geo", os.path.join(ROOT, "meshes", "cantilever.geo"), "-level", str(level), "-E", "1000", "-nu", "0.3", "-dirichlet", "root", "-traction_tip", "0,0,-1"], "displacement_cantilever_L%d.h5" % level)
        law("displacement_cantilever_L%d.h5" % level)
        x, cells, s = f["geometry/vertices"][:], f["viz/topology/cells"][:], f["fields/stress"][:]
        X = x[cells]
        centre, e = X.mean(axis=1), X[:, 1:] - X[:, :1]
        vol = np.abs(np.einsum("ij,ij->i", np.cross(e[:, 0], e[:, 1]), e[:, 2])) / 6
        h = 10.0 / (20 * level)
        reaction = f["groups/root/reaction"][:]
        expect(np.abs(reaction - [0, 0, 1]).max() <= 1e-8, "level %d: the root's reaction %s does not balance the load" % (level, reaction))
        for xs in (2.5, 5.0, 7.5):
            slab = np.abs(centre[:, 0] - xs) < h  # the cells between the node planes xs - h and xs + h
            V = (vol[slab] * s[slab, 4]).sum() / (2 * h)
            M = (vol[slab] * s[slab, 0] * centre[slab, 2]).sum() / (2 * h)
            expect(abs(V + 1) <= 1e-6, "level %d, x = %g: the section's shear force %g, not -P" % (level, xs, V))
            errors.setdefault(level, []).append(M / (10 - xs) - 1)
    e2, e4 = np.array(errors[2]), np.array(errors[4])
    expect((-0.25 < e2).all() and (e2 < -0.15).all() and (-0.09 < e4).all() and (e4 < -0.04).all() and (e2 / e4 > 3).all(), "the bending moments' errors %s (level 2), %s (level 4) do not fall as h^2" % (e2, e4))


@test("the Python module: ssstar.Scene(displacement={\"top\": [(t, (None, None, -delta)), ...]}) (None or \"free\": a free component) solves the compression's steps with Step.row[\"groups/top/reaction\"] = (0, 0, -E A delta/h) to 1e-8; Scene.set(displacement=...) moves the lid on (t = 3: delta 0.02, reaction -40); a new pattern of free components is refused naming the option; the file it writes is examples/contact's (the same steps to 2e-6) and passes check_solution.py law --steps; no memory left (-malloc_dump)")
def displacement_python():
    h5 = os.path.join(OUT, "displacement_python.h5")
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "python"))
    p = subprocess.run([PYTHON, os.path.join(ROOT, "tests", "displacement_python.py"), h5, "-malloc_dump"], cwd=ROOT, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=300)
    expect(p.returncode == 0 and not LEAK.findall(p.stdout), "tests/displacement_python.py failed or leaked", p.stdout)
    rows = {float(t): (json.loads(r), float(n)) for t, r, n in re.findall(r"^t (\S+) reaction (\[.*?\]) normal_force (\S+)$", p.stdout, re.M)}
    expect(sorted(rows) == [0, 1, 2, 3], "the steps %s, not 0, 1, 2, 3" % sorted(rows), p.stdout)
    for t, (reaction, normal) in rows.items():
        delta = 0.005 * t if t <= 2 else 0.02
        expect(np.abs(np.array(reaction) - [0, 0, -E * AREA * delta / HEIGHT]).max() <= 1e-8 * max(1, E * delta / HEIGHT) and abs(normal - E * AREA * delta / HEIGHT) <= 1e-8 * max(1, E * delta / HEIGHT), "t %g: reaction %s, normal force %g" % (t, reaction, normal), p.stdout)
    expect(re.search(r"^refused: Option -displacement_top 0,free,-0\.02: the free components of a prescribed displacement are fixed", p.stdout, re.M) is not None, "a new pattern of free components is not refused", p.stdout)
    law("displacement_python.h5")
    c = "displacement_python_c.h5"
    contact(BLOCK + ["-contact", "bottom", "-friction_law_bottom", "none", "-displacement_top", "0:free,free,0;1:free,free,-0.005;2:free,free,-0.01;3:free,free,-0.02"], c)
    run(CHECK + ["compare", os.path.join(OUT, c), h5, "--steps", "--tol", str(AGREE)])


@test("the force-displacement picture (examples/plot_contact.py on the compression's load path): FILE_reaction.png is drawn, one panel per prescribed group, its line the file's /steps/groups/<G>/displacement and /steps/groups/<G>/reaction in the prescribed component that moves most (z), labelled with the group, the component and the units; the other pictures are drawn too, also for a load path with a -dirichlet group (its /steps/groups/<G> has a reaction and no displacement: a lid held fixed, the base pushed up by a moving plane, held in x on its plane of symmetry)")
def displacement_plot():
    import importlib.util
    h5 = "displacement_plot.h5"
    _, f = contact(BLOCK + ["-contact", "bottom", "-friction_law_bottom", "none", "-displacement_top", "0:free,free,0;1:free,free,-0.005;2:free,free,-0.01"], h5)
    half = os.path.join(OUT, "halfblock_L1.msh")
    run(["gmsh", "-3", "-setnumber", "L", "1", "-format", "msh22", os.path.join(ROOT, "meshes", "halfblock.geo"), "-o", half])
    contact(["-mesh", half, "-E", "1000", "-nu", "0.3", "-dirichlet", "top", "-contact", "bottom", "-obstacle_bottom_motion", "0:0,0,0;1:0,0,0.01", "-displacement_sym", "0,free,free"], "displacement_plot_held.h5")
    for name in ("displacement_plot", "displacement_plot_held"):
        out = run([PYTHON, os.path.join(ROOT, "examples", "plot_contact.py"), os.path.join(OUT, name + ".h5")])
        for png in (name + ".png", name + "_history.png", name + "_reaction.png"):
            expect(os.path.exists(os.path.join(OUT, png)) and "wrote " + os.path.join(OUT, png) in out, "%s is not drawn" % png, out)
    spec = importlib.util.spec_from_file_location("plot_contact", os.path.join(ROOT, "examples", "plot_contact.py"))
    plot = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(plot)
    fig = plot.draw_reactions(os.path.join(OUT, h5))
    expect(fig is not None and len(fig.axes) == 1, "draw_reactions(): not one panel for the one prescribed group")
    ax = fig.axes[0]
    x, y = ax.lines[0].get_xdata(), ax.lines[0].get_ydata()
    expect(np.array_equal(x, f["steps/groups/top/displacement"][:, 2]) and np.array_equal(y, f["steps/groups/top/reaction"][:, 2]), "the line is not the file's z displacement and reaction of top")
    expect("$u_z$ of top" in ax.get_xlabel() and "$R_z$ at top" in ax.get_ylabel() and "length" in ax.get_xlabel() and "E unit" in ax.get_ylabel(), "labels %r, %r" % (ax.get_xlabel(), ax.get_ylabel()))
    expect(abs(y[-1] + 20) < 1e-8 * 20, "the last reaction %g is not -E A delta/h" % y[-1])
