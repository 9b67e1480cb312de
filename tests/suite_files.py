"""The result files: what a scripted user and a ParaView user read. The HDF5 file describes its run and its scene, is the
same on any number of ranks (the mesh file's node order), and its XDMF file opens the mesh and the contact faces with
their point fields; tests/check_solution.py takes the friction law of each node from the file."""
import os
import re
import shutil
import xml.etree.ElementTree as ET

import h5py
import numpy as np

from harness import *  # noqa: F401,F403 (run, expect, mpiexec, test, paths)

CONTACT = os.path.join(ROOT, "examples", "contact")
STATE_NAMES = ["L", "M1", "M2", "M3+", "M3-", "M4", "LS"]  # SSStarStateNames, in the order of their codes
# the prism at level 2 with two contact groups: the bottom (Coulomb 0.45) and, above the top, a plane 0.001 away
# pressed by nothing (Tresca, bound 0.5); a material group, tractions and a spring
TWO_GROUPS = ["-geo", os.path.join(ROOT, "meshes", "prism.geo"), "-level", "2", "-E", "1e5", "-nu", "0.25",
              "-material_body", "2.1e5,0.3", "-dirichlet", "dirichlet", "-traction_top", "0,0,-500",
              "-traction_right", "-200,30,200", "-spring_right", "10", "-contact", "contact,top",
              "-obstacle_top", "0,0,1.001,0,0,-1", "-friction_law_top", "tresca", "-slip_bound_top", "0.5",
              "-friction_contact", "0.45"]


def text(value):
    return value.decode() if isinstance(value, bytes) else str(value)


def makefile_version():
    return re.search(r"^VERSION\s*:=\s*(\S+)", open(os.path.join(ROOT, "Makefile")).read(), re.M).group(1)


def msh41_nodes(path):
    """The node coordinates of an msh 4.1 file (ASCII or binary), by ascending node tag"""
    data = open(path, "rb").read()
    if data.split(b"\n")[1].split()[1] == b"1":  # binary: size_t and int in this machine's order
        i = data.index(b"$Nodes\n") + 7
        blocks = int(np.frombuffer(data, np.uint64, 1, i)[0])
        i += 32
        tags, xyz = [], []
        for _ in range(blocks):
            parametric = int(np.frombuffer(data, np.int32, 3, i)[2])
            k = int(np.frombuffer(data, np.uint64, 1, i + 12)[0])
            expect(parametric == 0, "parametric nodes in %s" % path)
            i += 20
            tags.append(np.frombuffer(data, np.uint64, k, i))
            xyz.append(np.frombuffer(data, np.float64, 3 * k, i + 8 * k).reshape(k, 3))
            i += 32 * k
        return np.concatenate(xyz)[np.argsort(np.concatenate(tags))]
    lines = data.decode().split("\n")
    i = lines.index("$Nodes")
    blocks = int(lines[i + 1].split()[0])
    i += 2
    tags, xyz = [], []
    for _ in range(blocks):
        k = int(lines[i].split()[3])
        tags += [int(t) for t in lines[i + 1:i + 1 + k]]
        xyz += [[float(v) for v in line.split()] for line in lines[i + 1 + k:i + 1 + 2 * k]]
        i += 1 + 2 * k
    return np.array(xyz)[np.argsort(tags)]


@test("the result file describes itself: versions (ssstar = the Makefile's, PETSc 3.18), the command line, the ranks, the converged reason and ssstar's sub-reason, iterations, ||z|| <= the tolerance, rtol, state names beside their codes and counts; the scene (mesh, E and nu, the material group, tractions, spring, each contact group's law, friction or slip bound, plane); the friction law, coefficient and bound of every contact node (two groups: Coulomb 0.45 and Tresca 0.5)")
def file_metadata():
    h5 = os.path.join(OUT, "files_two_groups.h5")
    out = run(mpiexec(2, CONTACT, *TWO_GROUPS, "-snes_converged_reason", "-o", h5))
    its = int(re.search(r"iterations (\d+) states", out).group(1))
    with h5py.File(h5, "r") as f:
        a = f.attrs
        expect(text(a["ssstar_version"]) == makefile_version(), "ssstar_version %s, Makefile %s" % (a["ssstar_version"], makefile_version()))
        expect(text(a["petsc_version"]).startswith("3.18."), "petsc_version %s" % a["petsc_version"])
        cmd = text(a["command_line"])
        expect(cmd.split()[0].endswith("examples/contact") and "-friction_law_top tresca" in cmd and h5 in cmd, "command_line: %s" % cmd)
        expect(int(a["ranks"]) == 2 and text(a["snes_type"]) == "ssstar", "ranks %s, snes_type %s" % (a["ranks"], a["snes_type"]))
        expect(text(a["converged_reason"]) == "CONVERGED_FNORM_RELATIVE" and int(a["converged_reason_code"]) == 3, "reason %s (%s)" % (a["converged_reason"], a["converged_reason_code"]))
        expect(text(a["sub_reason"]) == "CONVERGED_RELATIVE", "sub_reason %s" % a["sub_reason"])
        expect(int(a["iterations"]) == its, "iterations %s, the run printed %d" % (a["iterations"], its))
        expect(0 <= float(a["residual_norm"]) <= float(a["tolerance"]) and float(a["rtol"]) == 1e-10, "||z|| %s, tolerance %s, rtol %s" % (a["residual_norm"], a["tolerance"], a["rtol"]))
        expect(text(a["state_names"]).split(",") == STATE_NAMES, "state_names %s" % a["state_names"])
        c = f["contact"]
        state, group, law = c["state"][:], c["group"][:], c["friction_law"][:]
        expect(text(c["state"].attrs["names"]).split(",") == STATE_NAMES, "/contact/state names %s" % c["state"].attrs["names"])
        expect(list(a["state_counts"]) == [int((state == s).sum()) for s in range(7)], "state_counts %s, /contact/state %s" % (a["state_counts"], np.bincount(state, minlength=7)))
        expect(text(c["group"].attrs["names"]) == "contact,top" and text(c["friction_law"].attrs["names"]) == "none,tresca,coulomb,orthotropic", "names of groups/laws")
        bottom, top = group == 0, group == 1
        expect(bottom.any() and top.any(), "nodes per group %d, %d" % (bottom.sum(), top.sum()))
        expect((law[bottom] == 2).all() and np.allclose(c["friction"][:][bottom], 0.45) and (c["slip_bound"][:][bottom] == 0).all(), "bottom: Coulomb 0.45 per node")
        expect((law[top] == 1).all() and np.allclose(c["slip_bound"][:][top], 0.5) and (c["friction"][:][top] == 0).all(), "top: Tresca 0.5 per node")
        expect(np.isin(state[top], (0, 6)).all(), "the top plane is never touched: every top node L or LS, got %s" % np.bincount(state[top], minlength=7))
        s = f["scene"]
        expect(text(s.attrs["mesh"]).endswith("prism_L2.msh") and int(s.attrs["nodes"]) == len(f["geometry/vertices"]) and int(s.attrs["cells"]) == len(f["viz/topology/cells"]), "scene mesh %s" % dict(s.attrs))
        expect(float(s.attrs["E"]) == 1e5 and float(s.attrs["nu"]) == 0.25, "scene E, nu %s %s" % (s.attrs["E"], s.attrs["nu"]))
        expect(float(s["material/body"].attrs["E"]) == 2.1e5 and float(s["material/body"].attrs["nu"]) == 0.3, "material body")
        expect(list(s["traction/top"].attrs["traction"]) == [0, 0, -500] and list(s["traction/right"].attrs["traction"]) == [-200, 30, 200], "tractions")
        expect(float(s["spring/right"].attrs["k"]) == 10 and text(s.attrs["dirichlet"]) == "dirichlet", "spring, dirichlet")
        g0, g1 = s["contact/contact"].attrs, s["contact/top"].attrs
        expect(text(g0["law"]) == "coulomb" and float(g0["friction"]) == 0.45 and int(g0["nodes"]) == bottom.sum(), "group contact: %s" % dict(g0))
        expect(text(g1["law"]) == "tresca" and float(g1["slip_bound"]) == 0.5 and list(g1["normal"]) == [0, 0, -1] and abs(float(g1["gap_min"]) - 0.001) < 1e-12, "group top: %s" % dict(g1))
    law = run(CHECK + ["coulomb", h5])
    expect("VIOLATED" not in law and "Tresca (s 0.5)" in law and "Coulomb (phi 0.45)" in law, "check_solution.py with the file's laws", law)


@test("tests/check_solution.py needs no --phi: it reads each node's coefficient from the file (prism -snes_ssstar_friction 0.45 passes; the same file with /contact/friction set to 0.1 fails, and so does --phi 0.3 against it); a run that stops early (-snes_max_it 2) writes a file that says so: DIVERGED_MAX_IT, MAX_IT, 2 iterations, ||z|| above the tolerance")
def file_friction_and_reason():
    h5 = os.path.join(OUT, "files_phi045.h5")
    prism(3, extra=["-snes_ssstar_friction", "0.45"], h5="files_phi045.h5")
    law = run(CHECK + ["coulomb", h5])
    expect("VIOLATED" not in law and "phi 0.45" in law, "the law with the file's phi", law)
    run(CHECK + ["coulomb", h5, "--phi", "0.3"], expect_rc=1)
    wrong = os.path.join(OUT, "files_phi_wrong.h5")
    shutil.copy(h5, wrong)
    with h5py.File(wrong, "r+") as f:
        f["contact/friction"][...] = 0.1
    out = run(CHECK + ["coulomb", wrong], expect_rc=1)
    expect("VIOLATED" in out, "a wrong coefficient in the file is not noticed", out)

    stopped = os.path.join(OUT, "files_max_it.h5")
    if os.path.exists(stopped):
        os.remove(stopped)
    run(mpiexec(1, PRISM, "-level", "4", "-snes_max_it", "2", "-o", stopped), expect_rc=NOT_CONVERGED)
    expect(os.path.exists(stopped), "no file from the run stopped by -snes_max_it")
    with h5py.File(stopped, "r") as f:
        a = f.attrs
        expect(text(a["converged_reason"]) == "DIVERGED_MAX_IT" and text(a["sub_reason"]) == "MAX_IT" and int(a["iterations"]) == 2, "reason %s/%s after %s iterations" % (a["converged_reason"], a["sub_reason"], a["iterations"]))
        expect(float(a["residual_norm"]) > float(a["tolerance"]), "||z|| %s not above the tolerance %s" % (a["residual_norm"], a["tolerance"]))


def datasets(f):
    names = []
    f.visititems(lambda name, obj: names.append(name) if isinstance(obj, h5py.Dataset) else None)
    return sorted(names)


@test("1, 2 and 3 ranks write the same file (prism level 3, and the two-group scene on 1 and 2 ranks): the same datasets, vertices and tetrahedra identical, every real field to 2e-6 of its largest entry (harness.AGREE), every integer field identical; the vertices are the mesh file's nodes in node-tag order, the tetrahedra positively oriented (VTK) and filling the prism's volume")
def file_same_on_any_ranks():
    files = []
    for ranks in (1, 2, 3):
        name = "files_prism_L3_np%d.h5" % ranks
        prism(3, ranks=ranks, h5=name)
        files.append(os.path.join(OUT, name))
    for ranks in (1, 2):
        name = os.path.join(OUT, "files_two_groups_np%d.h5" % ranks)
        run(mpiexec(ranks, CONTACT, *TWO_GROUPS, "-o", name))
        files.append(name)
    for first, other in ((files[0], files[1]), (files[0], files[2]), (files[3], files[4])):
        with h5py.File(first, "r") as a, h5py.File(other, "r") as b:
            expect(datasets(a) == datasets(b), "%s and %s hold other datasets: %s / %s" % (first, other, datasets(a), datasets(b)))
            for name in datasets(a):
                x, y = a[name][:], b[name][:]
                expect(x.shape == y.shape and x.dtype.kind == y.dtype.kind, "%s: %s %s against %s %s" % (name, x.shape, x.dtype, y.shape, y.dtype))
                if name in ("geometry/vertices", "viz/topology/cells", "contact_faces/triangles", "contact_faces/vertices") or x.dtype.kind != "f":
                    expect(np.array_equal(x, y), "%s differs between %s and %s" % (name, first, other))
                else:
                    scale = max(np.abs(x).max(), 1e-300)
                    expect(np.abs(x - y).max() <= AGREE * scale, "%s differs by %.1e relative between %s and %s" % (name, np.abs(x - y).max() / scale, first, other))
    with h5py.File(files[1], "r") as f:
        x, cells = f["geometry/vertices"][:], f["viz/topology/cells"][:]
        nodes = msh41_nodes(mesh_of("meshes/prism.geo", 3))
        expect(np.array_equal(x, nodes), "the vertices are not the mesh file's nodes in node-tag order")
        e = x[cells[:, 1:]] - x[cells[:, :1]]
        volume = np.einsum("ij,ij->i", np.cross(e[:, 0], e[:, 1]), e[:, 2]) / 6
        expect((volume > 0).all() and abs(volume.sum() - 2.0) < 1e-12, "tetrahedra: %d not positively oriented, volume %g (prism: 2)" % ((volume <= 0).sum(), volume.sum()))


def xdmf_items(xmf):
    """(grid name, element tag, item name, file, path, dims, number type) of every DataItem of the XDMF file that reads
    the HDF5 file (a tensor's columns are such items inside a JOIN of hyperslabs)"""
    items = []
    for grid in ET.parse(xmf).getroot().iter("Grid"):
        for element in grid:
            for item in element.iter("DataItem"):
                if item.get("Format") != "HDF":
                    continue
                file, path = item.text.strip().split(":")
                items.append((grid.get("Name"), element.tag, element.get("Name"), file, path,
                              tuple(int(d) for d in item.get("Dimensions").split()), item.get("NumberType"), element))
    return items


@test("the XDMF file (parsed with xml.etree) opens two grids: the mesh (tetrahedra, displacement) and the contact faces (triangles; point fields state, pressure, tangential_traction, slip, gap, displacement); every DataItem of the HDF format names a dataset of the .h5 beside it with its dims and number type; the contact grid's fields agree with /contact (states; pressure = r.n/area; slip and traction tangential; gap = initial gap + u.n); a scene without contact has the mesh grid only")
def file_xdmf_contact_fields():
    h5 = os.path.join(OUT, "files_prism_L3_np2.h5")
    if not os.path.exists(h5):
        prism(3, ranks=2, h5="files_prism_L3_np2.h5")
    xmf = h5[:-3] + ".xmf"
    items = xdmf_items(xmf)
    with h5py.File(h5, "r") as f:
        for grid, tag, name, file, path, dims, kind, element in items:
            expect(file == os.path.basename(h5), "%s: the DataItem names the file %s" % (path, file))
            expect(path in f and f[path].shape == dims, "%s %s: the HDF5 file has %s" % (path, dims, f[path].shape if path in f else "nothing"))
            expect((kind == "Int") == (f[path].dtype.kind == "i"), "%s: NumberType %s, dtype %s" % (path, kind, f[path].dtype))
            if tag == "Topology":
                expect(int(element.get("NumberOfElements")) == dims[0], "%s: NumberOfElements %s" % (path, element.get("NumberOfElements")))
        grids = {}
        for grid, tag, name, file, path, dims, kind, element in items:
            grids.setdefault(grid, {})[name or tag] = (path, element)
        expect(set(grids) == {"mesh", "contact"}, "grids %s" % sorted(grids))
        expect(grids["mesh"]["Topology"][1].get("TopologyType") == "Tetrahedron" and "displacement" in grids["mesh"], "mesh grid %s" % sorted(grids["mesh"]))
        fields = {"state", "pressure", "tangential_traction", "slip", "gap", "displacement"}
        expect(fields <= set(grids["contact"]) and grids["contact"]["Topology"][1].get("TopologyType") == "Triangle", "contact grid %s" % sorted(grids["contact"]))
        for name in fields:
            expect(grids["contact"][name][1].get("Center") == "Node", "%s is not a point field" % name)
        cf, c = f["contact_faces"], f["contact"]
        y, tri = cf["vertices"][:], cf["triangles"][:]
        expect(tri.min() >= 0 and tri.max() < len(y) and len(np.unique(tri)) == len(y), "triangles do not index every face vertex")
        # each contact node among the face vertices (by coordinates, both in file order)
        x = c["coordinates"][:]
        at = np.array([np.flatnonzero((y == xi).all(axis=1))[0] for xi in x])
        n, u, r, area, gap0 = c["normal"][:], c["displacement"][:], c["reaction"][:], c["area"][:], c["gap"][:]
        rn, un = np.einsum("ij,ij->i", r, n), np.einsum("ij,ij->i", u, n)
        scale_r, scale_u = np.abs(r / area[:, None]).max(), np.abs(u).max()
        expect(np.array_equal(cf["state"][:][at], c["state"][:]), "states of the contact grid differ from /contact/state")
        expect(np.abs(cf["pressure"][:][at] - rn / area).max() <= 1e-12 * scale_r, "pressure is not r.n/area")
        expect(np.abs(cf["tangential_traction"][:][at] - (r - rn[:, None] * n) / area[:, None]).max() <= 1e-12 * scale_r, "tangential traction")
        expect(np.abs(cf["slip"][:][at] - (u - un[:, None] * n)).max() <= 1e-12 * scale_u and np.abs(cf["gap"][:][at] - (gap0 + un)).max() <= 1e-12 * scale_u, "slip or gap")
        held = np.setdiff1d(np.arange(len(y)), at)
        expect(len(held) > 0 and (cf["state"][:][held] == -1).all() and not cf["displacement"][:][held].any(), "the held vertices of the contact face (x = 0): state -1, u = 0")
        nrm = np.cross(y[tri[:, 1]] - y[tri[:, 0]], y[tri[:, 2]] - y[tri[:, 0]])
        expect((nrm[:, 2] < 0).all(), "contact triangles not oriented out of the body (towards the plane)")
    plain = os.path.join(OUT, "files_no_contact.h5")
    run(mpiexec(1, CONTACT, "-geo", os.path.join(ROOT, "meshes", "prism.geo"), "-level", "2", "-E", "1e5", "-nu", "0.3", "-dirichlet", "dirichlet", "-traction_top", "0,0,-500", "-o", plain))
    names = {grid for grid, *_ in xdmf_items(plain[:-3] + ".xmf")}
    expect(names == {"mesh"}, "a scene without contact: grids %s" % sorted(names))
    with h5py.File(plain, "r") as f:
        expect(text(f.attrs["converged_reason"]) == "CONVERGED_ITS" and "contact" not in f and "sub_reason" not in f.attrs, "no contact: %s, %s" % (dict(f.attrs), list(f)))
