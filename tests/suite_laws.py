"""The friction laws as the table gives them to the scenes and the output: the orthotropic scene's known answers (both
paths, 1 and 2 ranks), tests/check_solution.py on every law of a file (a correct orthotropic result passes, corrupted
copies fail), the options -<parameter>_<G> read, checked and refused from the table (the longest prefix first), and
one dataset per parameter of the laws in use."""
import os
import re
import shutil

import h5py
import numpy as np

from harness import *  # noqa: F401,F403 (run, expect, mpiexec, test, paths)
import scene_answers

CONTACT = os.path.join(ROOT, "examples", "contact")
ORTHOTROPIC = ["-options_file", os.path.join(ROOT, "scenes", "orthotropic.opts")]
# the push of scenes/orthotropic.opts (pressure 10 on the top, phi_1 = 0.3 along x, phi_2 = 0.6 across), the axis it
# acts along, and what the block does
PUSHES = [("4,0,-10", 0, "slides", 0.3), ("0,4,-10", 1, "holds", None), ("0,7,-10", 1, "slides", 0.6)]


def contact(ranks, args, h5=None, expect_rc=0):
    cmd = mpiexec(ranks, CONTACT, *args) + (["-o", os.path.join(OUT, h5)] if h5 else [])
    return run(cmd, expect_rc=expect_rc)


def forces(h5):
    """The contact force (normal N, the tangential vector F_t) and the slip of every node, from the file"""
    c = h5py.File(os.path.join(OUT, h5), "r")["contact"]
    r, n = c["reaction"][:], c["normal"][:]
    N = (r * n).sum()
    return N, r.sum(axis=0) - N * n[0], c["slip"][:], c["state"][:]


@test("scenes/orthotropic.opts (a block pressed by 10 and pushed, phi_1 = 0.3 along the friction direction x, phi_2 = 0.6 across, nu = 0): pushed along x by 4 every touching node slides along x and the tangential force is phi_1 times the normal force (1e-8); pushed across by 4 it holds (phi_1 N < F_t < phi_2 N, no slip above 1e-5); pushed across by 7 it slides with phi_2 (1e-8); no force across the push (1e-5 of N); the orthotropic law at every node (check_solution.py); direct and none, 1 and 2 ranks")
def laws_orthotropic_scene():
    for push, axis, kind, phi in PUSHES:
        for red in ("direct", "none"):
            for ranks in (1, 2):
                h5 = "ortho_scene_%s_%s_%d.h5" % (push.replace(",", "_"), red, ranks)
                out = contact(ranks, ORTHOTROPIC + ["-traction_top", push, "-snes_ssstar_reduction", red], h5=h5)
                N, Ft, slip, state = forces(h5)
                touching = np.isin(state, (1, 2, 3, 4, 5))
                what = "push %s, %s, %d ranks: F_t/N = %.9f along, %.2g across, slip along %.3g..%.3g" % (
                    push, red, ranks, -Ft[axis] / N, Ft[1 - axis], slip[touching, axis].min(), slip[touching, axis].max())
                expect("CONVERGED_FNORM" in out and N > 9, what + ": not converged or no contact", out)
                expect(abs(Ft[1 - axis]) <= 1e-5 * N and abs(Ft[2]) <= 1e-9 * N, what + ": a force across the push", out)
                if kind == "slides":
                    expect(abs(-Ft[axis] / N - phi) <= 1e-8 * phi and (slip[touching, axis] > 1e-4).all(), what + ": not sliding with %g" % phi, out)
                else:
                    expect(0.3 * 1.05 < -Ft[axis] / N < 0.6 and np.abs(slip[:, axis]).max() <= 1e-5, what + ": does not hold", out)
                law = run(CHECK + ["law", os.path.join(OUT, h5)])
                expect("VIOLATED" not in law and "orthotropic (phi_1 0.3, phi_2 0.6)" in law, what + ": the law of the file", law)
    with h5py.File(os.path.join(OUT, "ortho_scene_4_0_-10_direct_2.h5"), "r") as f:
        c, g = f["contact"], f["scene/contact/bottom"].attrs
        expect("friction" not in c and "slip_bound" not in c and np.all(c["friction_law"][:] == 3), "datasets of laws not in use, or the law: %s" % list(c))
        expect(np.all(c["friction_1"][:] == 0.3) and np.all(c["friction_2"][:] == 0.6) and np.allclose(c["friction_direction"][:], [1, 0, 0], atol=0, rtol=0),
               "the parameters per node: %s %s" % (np.unique(c["friction_1"][:]), np.unique(c["friction_direction"][:], axis=0)))
        expect(g["law"] == "orthotropic" and g["friction_1"] == 0.3 and g["friction_2"] == 0.6 and list(g["friction_direction"]) == [1, 0, 0], "/scene/contact/bottom: %s" % dict(g))


def corrupted(source, name, change):
    """A copy of a solution file (with its XDMF file) changed by change(h5py file)"""
    for ext in (".h5", ".xmf"):
        shutil.copy(os.path.join(OUT, source + ext), os.path.join(OUT, name + ext))
    with h5py.File(os.path.join(OUT, name + ".h5"), "r+") as f:
        change(f)
    return os.path.join(OUT, name + ".h5")


@test("tests/check_solution.py knows the orthotropic law (the ellipse |M^-1/2 r_t| <= r_n, sliding by maximum dissipation) from the file's /contact/friction_law names and parameters: the orthotropic scene's results pass; a copy with friction_2 = 0.3 (the block pushed across by 7 then exceeds its ellipse), one with the friction direction turned to y (pushed along x: the sliding force is the wrong one), and one whose law the check does not know fail", full=True)
def laws_check_solution_orthotropic():
    along, across = "ortho_scene_4_0_-10_direct_1", "ortho_scene_0_7_-10_direct_1"
    for name in (along, across):
        if not os.path.exists(os.path.join(OUT, name + ".h5")):
            laws_orthotropic_scene()
        out = run(CHECK + ["coulomb", os.path.join(OUT, name + ".h5")])
        expect("VIOLATED" not in out, name + ": the correct result fails", out)

    def set_dataset(path, value):
        return lambda f: f[path].__setitem__(Ellipsis, value)
    bad = {"narrow": (across, set_dataset("contact/friction_2", 0.3), r"\|r_t\| <= bound\s+\S+ VIOLATED"),
           "turned": (along, set_dataset("contact/friction_direction", np.array([0.0, 1.0, 0.0])), r"r_t = -bound w_t/\|w_t\|\s+\S+ VIOLATED"),
           "unknown": (along, lambda f: f["contact/friction_law"].attrs.__setitem__("names", "none,tresca,coulomb,sticky"), "not one this check knows")}
    for name, (source, change, message) in bad.items():
        out = run(CHECK + ["law", corrupted(source, "ortho_" + name, change)], expect_rc=1)
        expect(re.search(message, out) is not None, "a corrupted copy (%s) passes" % name, out)


@test("each parameter of the table of laws is the option -<parameter>_<G> of a contact group, checked by its kind and refused naming the options: -friction_1_bottom with the law coulomb (a parameter of orthotropic), orthotropic without -friction_2_bottom (required: no default), a zero or two-component direction, a negative coefficient; -friction_1_bottom is friction_1 of bottom, and the friction of a group 1_bottom when bottom is no contact group; -help lists them all")
def laws_group_options():
    base = ORTHOTROPIC + ["-level", "1"]
    plain = ["-geo", os.path.join(ROOT, "meshes", "block.geo"), "-level", "1", "-E", "2.1e5", "-nu", "0", "-traction_top", "1,0,-10", "-spring_top", "1000"]
    refusals = [(plain + ["-contact", "bottom", "-friction_1_bottom", "0.3"], "Options -friction_1_bottom and -friction_law_bottom coulomb contradict each other: the friction coefficient along the friction direction is a parameter of the law orthotropic"),
                (plain + ["-contact", "bottom", "-friction_law_bottom", "orthotropic", "-friction_1_bottom", "0.3", "-friction_direction_bottom", "1,0,0"], "Option -friction_law_bottom orthotropic needs -friction_2_bottom"),
                (base + ["-friction_direction_bottom", "0,0,0"], "Option -friction_direction_bottom 0,0,0: the friction direction must be a nonzero vector"),
                (base + ["-friction_direction_bottom", "1,0"], "Option -friction_direction_bottom needs 3 comma-separated values x,y,z (got 2)"),
                (base + ["-friction_2_bottom", "-0.6"], "Option -friction_2_bottom -0.6: the friction coefficient across the friction direction must be a number >= 0"),
                (plain + ["-contact", "bottom", "-friction_law_bottom", "tresca"], "Option -friction_law_bottom tresca needs -slip_bound_bottom (the slip bound)")]
    for args, message in refusals:
        out = contact(1, args, expect_rc=1)
        expect(message in out, "not refused with %r" % message, out)
    geo = os.path.join(OUT, "block_1_bottom.geo")
    with open(geo, "w") as f:  # the block with its bottom named 1_bottom
        f.write(open(os.path.join(ROOT, "meshes", "block.geo")).read().replace('Physical Surface("bottom")', 'Physical Surface("1_bottom")'))
    renamed = ["-geo", geo] + plain[2:] + ["-contact", "1_bottom"]
    out = contact(1, renamed + ["-friction_1_bottom", "0.45"])
    expect(re.search(r"contact group 1_bottom: .*friction coulomb, phi = 0.45\n", out) is not None, "-friction_1_bottom is not the friction of 1_bottom", out)
    out = contact(1, renamed + ["-friction_law_1_bottom", "orthotropic", "-friction_1_1_bottom", "0.3", "-friction_2_1_bottom", "0.6", "-friction_direction_1_bottom", "0,1,0"])
    expect(re.search(r"contact group 1_bottom: .*friction orthotropic, phi_1 = 0.3, phi_2 = 0.6, a = \(0., 1., 0.\)\n", out) is not None, "the orthotropic options of 1_bottom", out)
    text = run(mpiexec(1, CONTACT, "-help"))
    for name in ("friction", "slip_bound", "friction_1", "friction_2", "friction_direction"):
        expect(re.search(r"-%s_<G> <" % name, text) is not None, "-help does not list -%s_<G>" % name, text)
    expect("-friction_law_<G> <coulomb>: the friction law of G: none, tresca, coulomb or orthotropic" in text, "-help does not list the laws", text)


@test("the output has one dataset per parameter of the laws in use, 0 where a node's law lacks it: a Coulomb group (0.45) and an orthotropic group on the prism give /contact/friction, friction_1, friction_2, friction_direction (n x 3) and no slip_bound, each group's values at its nodes and 0 at the other's; /scene/contact/<G> carries its law's parameters; the same file on 1 and 2 ranks; check_solution.py passes it")
def laws_output_datasets():
    two = ["-geo", os.path.join(ROOT, "meshes", "prism.geo"), "-level", "2", "-E", "2.1e5", "-nu", "0.3", "-dirichlet", "dirichlet",
           "-traction_top", "0,0,-500", "-traction_right", "-200,30,200", "-contact", "contact,top", "-obstacle_top", "0,0,1.001,0,0,-1",
           "-friction_contact", "0.45", "-friction_law_top", "orthotropic", "-friction_1_top", "0.2", "-friction_2_top", "0.4",
           "-friction_direction_top", "1,1,0"]
    files = []
    for ranks in (1, 2):
        files.append(os.path.join(OUT, "laws_two_%d.h5" % ranks))
        contact(ranks, two, h5=os.path.basename(files[-1]))
    a, b = h5py.File(files[0], "r"), h5py.File(files[1], "r")
    c = a["contact"]
    law, group = c["friction_law"][:], c["group"][:]
    expect(sorted(k for k in c if k.startswith("friction") or k == "slip_bound") == ["friction", "friction_1", "friction_2", "friction_direction", "friction_law"], "datasets %s" % list(c))
    expect(c["friction_direction"].shape == (len(law), 3) and np.all(law[group == 0] == 2) and np.all(law[group == 1] == 3), "shapes or laws")
    expect(np.all(c["friction"][:][group == 0] == 0.45) and np.all(c["friction"][:][group == 1] == 0), "friction per node")
    expect(np.all(c["friction_1"][:][group == 1] == 0.2) and np.all(c["friction_1"][:][group == 0] == 0) and np.all(c["friction_direction"][:][group == 0] == 0), "orthotropic parameters per node")
    expect(np.allclose(c["friction_direction"][:][group == 1], [2 ** -0.5, 2 ** -0.5, 0], atol=1e-15), "the direction in use (unit): %s" % c["friction_direction"][:][group == 1][0])
    top = a["scene/contact/top"].attrs
    expect(top["law"] == "orthotropic" and top["friction_1"] == 0.2 and top["friction_2"] == 0.4 and "friction" not in top and a["scene/contact/contact"].attrs["friction"] == 0.45, "/scene/contact: %s" % dict(top))
    for name in ("friction_law", "friction", "friction_1", "friction_2", "friction_direction"):
        expect(np.array_equal(a["contact/" + name][:], b["contact/" + name][:]), "/contact/%s differs on 1 and 2 ranks" % name)
    out = run(CHECK + ["law", files[1]])
    expect("VIOLATED" not in out and "Coulomb (phi 0.45)" in out and "orthotropic (phi_1 0.2, phi_2 0.4)" in out, "check_solution.py on two laws", out)
