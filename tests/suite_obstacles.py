"""Rigid obstacles of any shape (-obstacle_<G> plane:, sphere:, cylinder:, mesh:): the known answers (Hertz's ball,
the line contact of a cylinder, a plane given as a mesh or as a huge ball), on both paths (the direct reduction and
the whole body), each node's gap and normal from the geometry, and bad input refused naming the option."""
import os
import re

import h5py
import numpy as np

from harness import *  # noqa: F401,F403 (run, expect, mpiexec, test, paths)
import scene_answers
from suite_scenes import CONTACT, contact_run, plot, refused, scene

PATHS = ("direct", "none")
SQUARE = os.path.join(ROOT, "meshes", "square_obstacle.msh")


def h5path(name):
    return os.path.join(OUT, name)


def contact_data(h5):
    c = h5py.File(h5path(h5), "r")["contact"]
    return c["coordinates"][:], c["normal"][:], c["gap"][:]


def compare(a, b, tol):
    """The largest difference of displacement and reaction of two solution files, relative to their largest entries"""
    da, db = scene_answers.contact(h5path(a)), scene_answers.contact(h5path(b))
    expect(np.array_equal(da["coordinates"], db["coordinates"]), "%s and %s: not the same contact nodes" % (a, b))
    err = max(np.abs(da[k] - db[k]).max() / np.abs(da[k]).max() for k in ("displacement", "reaction"))
    expect(err <= tol and np.array_equal(da["state"], db["state"]), "%s against %s: %g (tolerance %g), states equal: %s" % (a, b, err, tol, np.array_equal(da["state"], db["state"])))
    return err


def prism_mesh(level):
    """The prism's mesh of a level as the programs make it (in the mesh cache), made by a short run if it is not there"""
    msh = mesh_of("meshes/prism.geo", level)
    if not os.path.exists(msh):
        run(mpiexec(1, PRISM, "-level", str(level), "-snes_max_it", "1"), expect_rc=None)
    return msh


def square_msh(name, z, flip=(), reverse=False):
    """The two-triangle square (-10, 10)^2 at height z, its triangles oriented up (towards +z) unless reversed; the
    triangles in flip reversed alone"""
    tri = [[1, 2, 3], [1, 3, 4]]
    for t in range(2):
        if reverse or t in flip:
            tri[t] = tri[t][::-1]
    text = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n"
    text += "".join("%d %g %g %g\n" % (i + 1, x, y, z) for i, (x, y) in enumerate([(-10, -10), (10, -10), (10, 10), (-10, 10)]))
    text += "$EndNodes\n$Elements\n2\n" + "".join("%d 2 2 1 1 %d %d %d\n" % (t + 1, *tri[t]) for t in range(2)) + "$EndElements\n"
    path = h5path(name)
    with open(path, "w") as f:
        f.write(text)
    return path


def sphere_msh():
    """The ball of radius 10 centred at (0, 0, 10) as gmsh triangles (OpenCASCADE: oriented outwards), size 0.5"""
    geo, msh = h5path("sphere_obstacle.geo"), h5path("sphere_obstacle.msh")
    with open(geo, "w") as f:
        f.write('SetFactory("OpenCASCADE");\nSphere(1) = {0, 0, 10, 10};\nMesh.MeshSizeMax = 0.5;\n'
                'Physical Surface("ball") = {Boundary{Volume{1};}};\n')
    run(["gmsh", "-2", "-format", "msh41", geo, "-o", msh])
    return msh


# ---- the known answers ----------------------------------------------------------------------------------------------

@test("ball (level 1, frictionless, a rigid ball R = 10 on a block pushed up by a pressure): Hertz's contact radius within 5 % (measured +3.3 %) and peak pressure within 4 % (+2.2 %), the contact bracketed; every node's gap |x - c| - R and normal (x - c)/|x - c| to 1e-12; the direct reduction and the whole body agree to 1e-8; picture written")
def obstacle_ball():
    # frictionless, the block is held sideways by its soft spring alone (k A = 100 against E = 2.1e5): its rigid
    # sliding is ~1e4 times less stiff than the rest (at the defaults the paths differed by 7e-7 there before the law
    # residual joined the stopping rule, docs/derivation.md section 12)
    for path in PATHS:
        out, s = contact_run(scene("ball") + ["-snes_ssstar_reduction", path, "-snes_view"], h5="ball_%s.h5" % path)
        expect("rigid ball of radius 10. centred at (0., 0., 10.)" in out, "the scene view does not name the ball", out)
        h = scene_answers.hertz(h5path("ball_%s.h5" % path))
        expect(abs(h["a_error"]) < 0.05 and abs(h["p0_error"]) < 0.04 and h["a_outside"] < 1.05 * h["a_hertz"] and h["a_inside"] > 0.95 * h["a_hertz"],
               "%s: Hertz %s" % (path, h))
    x, n, g = contact_data("ball_direct.h5")
    d = x - [0, 0, 10]
    r = np.linalg.norm(d, axis=1)
    expect(np.abs(g - (r - 10)).max() < 1e-12 and np.abs(n - d / r[:, None]).max() < 1e-12, "ball: gaps or normals are not the sphere's")
    compare("ball_direct.h5", "ball_none.h5", 1e-8)
    plot("ball_direct.h5")


@test("roller (level 1, frictionless, a rigid cylinder R = 10 along y on a block extruded along it): the line contact in the section y = 0, half-width within 3 % (measured +1.8 %, the same at level 2: the finite block) and peak pressure within 3 % (-1.5 %); every node's gap and normal from the axis to 1e-12; both paths agree to 1e-8; picture written")
def obstacle_roller():
    for path in PATHS:
        out, _ = contact_run(scene("roller") + ["-snes_ssstar_reduction", path, "-snes_view"], h5="roller_%s.h5" % path)
        expect("rigid cylinder of radius 10., axis through (0., 0., 10.) along (0., 1., 0.)" in out, "the scene view does not name the cylinder", out)
        h = scene_answers.line(h5path("roller_%s.h5" % path))
        expect(abs(h["b_error"]) < 0.03 and abs(h["p0_error"]) < 0.03 and h["b_inside"] < h["b_hertz"] < h["b_outside"], "%s: line contact %s" % (path, h))
    x, n, g = contact_data("roller_direct.h5")
    d = x - [0, 0, 10]
    d[:, 1] = 0
    r = np.linalg.norm(d, axis=1)
    expect(np.abs(g - (r - 10)).max() < 1e-12 and np.abs(n - d / r[:, None]).max() < 1e-12, "roller: gaps or normals are not the cylinder's")
    compare("roller_direct.h5", "roller_none.h5", 1e-8)
    plot("roller_direct.h5")


@test("a plane given as mesh: (a two-triangle square) gives the plane's solution on the prism at level 3 to 1e-12 (measured: identical) on both paths; as a ball of radius R below it, the plane's solution to the geometric error, falling as 1/R (measured 2.2e-3 at R = 1e6, 2.0e-5 at R = 1e8)")
def obstacle_plane_as_mesh_or_ball():
    base = scene("prism") + ["-level", "3"]
    for path in PATHS:
        p = ["-snes_ssstar_reduction", path]
        contact_run(base + p, h5="prism_plane_%s.h5" % path)
        contact_run(base + p + ["-obstacle_contact", "mesh:" + SQUARE], h5="prism_mesh_%s.h5" % path)
        contact_run(base + p + ["-obstacle_contact", "plane:0,0,0,0,0,1"], h5="prism_planeform_%s.h5" % path)
        compare("prism_plane_%s.h5" % path, "prism_mesh_%s.h5" % path, 1e-12)
        compare("prism_plane_%s.h5" % path, "prism_planeform_%s.h5" % path, 0)
    errs = {}
    for R in (1e6, 1e8):
        contact_run(base + ["-obstacle_contact", "sphere:0,0,%g,%g" % (-R, R)], h5="prism_ball_%g.h5" % R)
        da, db = scene_answers.contact(h5path("prism_plane_direct.h5")), scene_answers.contact(h5path("prism_ball_%g.h5" % R))
        errs[R] = np.abs(da["displacement"] - db["displacement"]).max() / np.abs(da["displacement"]).max()
    expect(all(400 / R < e < 4000 / R for R, e in errs.items()), "huge ball against the plane: %s" % errs)


@test("a closed mesh obstacle (a ball of radius 10 as 12000 gmsh triangles, oriented outwards): each node's gap within the chordal error (h^2/(8R) ~ 0.006 for h = 0.5) and its normal within h/R of the exact ball's, and Hertz's answer as for the exact ball (states equal, contact force to 1e-3)")
def obstacle_mesh_ball():
    msh = sphere_msh()
    out, s = contact_run(scene("ball") + ["-obstacle_top", "mesh:" + msh, "-snes_view"], h5="ball_mesh.h5")
    expect(re.search(r"rigid body of mesh .*sphere_obstacle.msh \(\d+ triangles\)", out), "the scene view does not name the mesh", out)
    x, n, g = contact_data("ball_mesh.h5")
    d = x - [0, 0, 10]
    r = np.linalg.norm(d, axis=1)
    expect(np.abs(g - (r - 10)).max() < 0.01 and np.abs(n - d / r[:, None]).max() < 0.05 and g.min() >= 0,
           "mesh ball: gaps %g, normals %g from the ball's" % (np.abs(g - (r - 10)).max(), np.abs(n - d / r[:, None]).max()))
    contact_run(scene("ball"), h5="ball_exact.h5")
    a, b = scene_answers.hertz(h5path("ball_exact.h5")), scene_answers.hertz(h5path("ball_mesh.h5"))
    expect(abs(a["force"] / b["force"] - 1) < 1e-3 and abs(a["nodes_in_contact"] - b["nodes_in_contact"]) <= 3, "exact ball %s, mesh %s" % (a, b))


@test("obstacles on 2 ranks give the 1-rank solution (mesh obstacle read on rank 0 and spread over the ranks; ball): to 2e-6 (harness.AGREE)")
def obstacle_ranks():
    for ranks in (1, 2):
        contact_run(scene("prism") + ["-level", "3", "-obstacle_contact", "mesh:" + SQUARE], h5="prism_mesh_r%d.h5" % ranks, ranks=ranks)
    run(CHECK + ["compare", h5path("prism_mesh_r1.h5"), h5path("prism_mesh_r2.h5"), "--tol", str(AGREE)])
    contact_run(scene("ball"), h5="ball_r1.h5")
    contact_run(scene("ball"), h5="ball_r2.h5", ranks=2)
    run(CHECK + ["compare", h5path("ball_r1.h5"), h5path("ball_r2.h5"), "--tol", str(AGREE)])


@test("-help lists the obstacle forms; examples/contact does not leak with a mesh obstacle (-malloc_dump)")
def obstacle_help_and_memory():
    out = run([CONTACT, "-help"] + scene("prism") + ["-level", "1"], expect_rc=None)
    for form in ("sphere:cx,cy,cz,R", "cylinder:px,py,pz,ax,ay,az,R", "mesh:FILE.msh", "plane:px,py,pz,nx,ny,nz"):
        expect(form in out, "-help does not list %s" % form, out)
    out = run([CONTACT, "-malloc_dump", "-malloc_debug"] + scene("prism") + ["-level", "2", "-obstacle_contact", "mesh:" + SQUARE])
    expect(not LEAK.findall(out), "leaks with a mesh obstacle", out)


# ---- bad input --------------------------------------------------------------------------------------------------------

BAD_OBSTACLES = [
    # name, the value of -obstacle_contact on the prism (level 1) or a function giving it, message(s)
    ("negative_radius", "sphere:0,0,-1,-1", "Option -obstacle_contact sphere:0,0,-1,-1: the radius -1. must be positive"),
    ("zero_radius", "cylinder:0,0,-1,0,1,0,0", "the radius 0. must be positive"),
    ("zero_axis", "cylinder:0,0,-1,0,0,0,1", "Option -obstacle_contact cylinder:0,0,-1,0,0,0,1: the axis (0., 0., 0.) is zero"),
    ("zero_normal", "plane:0,0,-1,0,0,0", "the normal (0., 0., 0.) is zero"),
    ("too_few_values", "sphere:0,0,1", "Option -obstacle_contact sphere:0,0,1 needs 4 comma-separated values cx,cy,cz,R (got 3)"),
    ("not_a_number", "cylinder:0,0,x,0,1,0,1", "is not a list of numbers px,py,pz,ax,ay,az,R"),
    ("nan", "sphere:0,0,nan,1", "value 3 is not a finite number"),
    ("unknown_shape", "cube:0,0,0,1", ["Option -obstacle_contact cube:0,0,0,1: unknown obstacle", "mesh:FILE.msh"]),
    ("missing_file", "mesh:no/such.msh", "Option -obstacle_contact mesh:no/such.msh: cannot read the file"),
    ("not_a_mesh", lambda: "mesh:" + os.path.join(ROOT, "README.md"), "gmsh cannot read the file as a mesh"),
    ("no_triangles", lambda: "mesh:" + prism_mesh(1), "the file has no triangles"),
    ("inconsistent_orientation", lambda: "mesh:" + square_msh("flipped.msh", 0, flip=(1,)), "are oriented differently"),
    ("node_inside_ball", "sphere:0.5,0.5,0,0.2", ["starts 0.2 inside the obstacle of -obstacle_contact", "the body touches the ball from outside"]),
    ("node_inside_cylinder", "cylinder:1,0,-0.5,0,1,0,0.6", ["inside the obstacle of -obstacle_contact", "the body touches the cylinder from outside"]),
    ("node_inside_mesh", lambda: "mesh:" + square_msh("reversed.msh", -0.1, reverse=True), ["starts 0.1 inside the obstacle", "oriented counterclockwise seen from outside"]),
]


def bad_obstacle_test(name, value, message):
    def check():
        if name == "no_triangles":  # a volume mesh whose file holds tetrahedra only (msh 4.1 of the prism, no surfaces saved)
            msh = h5path("tets_only.msh")
            geo = h5path("tets_only.geo")
            with open(geo, "w") as f:
                f.write(open(os.path.join(ROOT, "meshes", "prism.geo")).read().split("Physical Surface")[0] + 'Physical Volume("v") = {1};\n')
            run(["gmsh", "-3", "-setnumber", "L", "1", "-format", "msh41", geo, "-o", msh])
            v = "mesh:" + msh
        else:
            v = value() if callable(value) else value
        refused(CONTACT, scene("prism") + ["-level", "1", "-obstacle_contact", v], message, "obstacle_" + name)
    return check


for _name, _value, _message in BAD_OBSTACLES:
    test("examples/contact refuses a bad obstacle before any work, naming the option: %s" % _name.replace("_", " "))(
        bad_obstacle_test(_name, _value, _message))
    TESTS[-1] = ("bad_obstacle_" + _name,) + TESTS[-1][1:]
