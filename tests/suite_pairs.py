"""Two deformable bodies (-contact_pair_<G> H, node-to-surface through the contact operator B): the contact patch
test, a block sliding on a block, the output per pair, bad input refused naming the option; both paths
(-snes_ssstar_reduction direct and none), 1 and 2 ranks."""
import os
import re

import h5py
import numpy as np
import scene_answers

from harness import *  # noqa: F401,F403 (run, expect, mpiexec, test, paths)

CONTACT = os.path.join(ROOT, "examples", "contact")
PLOT = [PYTHON, os.path.join(ROOT, "examples", "plot_contact.py")]
SUMMARY = re.compile(r"summary: nodes (\d+) contact (\d+) .* iterations (\d+) states L/M1/M2/M3\+/M3-/M4/LS ([\d/]+) (\S+)")
PATHS = [(red, ranks) for red in ("direct", "none") for ranks in (1, 2)]


def scene(name):
    return ["-options_file", os.path.join(ROOT, "scenes", name + ".opts")]


def contact(args, h5, ranks=1):
    out = run(mpiexec(ranks, CONTACT, *args, "-o", os.path.join(OUT, h5)))
    m = SUMMARY.search(out)
    expect(m is not None and m.group(5).startswith("CONVERGED"), "no converged summary", out)
    return out, [int(s) for s in m.group(4).split("/")], h5py.File(os.path.join(OUT, h5), "r")["contact"]


def forces(c):
    """normal force sum r.n, tangential force sum (global axes) of the slave nodes"""
    r, n = c["reaction"][:], c["normal"][:]
    rn = (r * n).sum(1)
    return rn, r - rn[:, None] * n


# The contact patch test at level 2: the lid (h = 0.175) on the base (h = 0.125), nu = 0, pressure 1, a spring of
# 0.01 on the lid's top: the exact interface pressure is uniform, 1/1.01. Node-to-surface transmits the slave's forces
# to the master nodes by the projection weights, not by the master's own consistent loads: the pressure at the slave
# nodes deviates from uniform by 11.6 % (measured); the displacement jump (w = 0) is exact, the total force to 9e-7.
# The dual mortar coupling (Wohlmuth) transmits the forces consistently and passes: uniform to round-off.
PATCH_DEVIATION = 0.12


@test("contact patch test (scenes/patch.opts, two stacked blocks, non-matching meshes), node-to-surface: total normal force 1/1.01 to 1e-5 (measured 9e-7: the spring sees the inexact lid top), every slave node sticking with final gap 0 and no slip, the pressure uniform within 12 % (measured 11.6 % from 1/1.01), the same pressures on direct and none, 1 and 2 ranks, to 1e-8")
def pairs_patch_test():
    patch_test("node_to_surface", 1e-5, (0.01, PATCH_DEVIATION))


@test("contact patch test, dual mortar (-pair_discretization dual_mortar): the pressure uniform, 1/1.01 at every slave node to 1e-10 (measured 1.4e-14 direct, 5.6e-12 none), total force to 1e-10, final gap 0; direct and none, 1 and 2 ranks")
def pairs_patch_test_mortar():
    patch_test("dual_mortar", 1e-10, (0, 1e-10))


def patch_test(method, force_tol, window):
    ref = None
    for red, ranks in PATHS:
        out, states, c = contact(scene("patch") + ["-snes_ssstar_reduction", red, "-pair_discretization", method], "pairs_patch_%s_%s_%d.h5" % (method, red, ranks), ranks)
        rn, rt = forces(c)
        expect(abs(rn.sum() - 1 / 1.01) <= force_tol, "%s %d: normal force %.12g, not 1/1.01" % (red, ranks, rn.sum()), out)
        expect(states[3] == len(rn), "%s %d: not every slave node sticks: %s" % (red, ranks, states), out)
        expect(np.abs(c["final_gap"][:]).max() <= 1e-10 and np.abs(c["slip"][:]).max() <= 1e-10, "%s %d: gap or slip at the interface" % (red, ranks))
        p = c["pressure"][:]
        dev = np.abs(p / (1 / 1.01) - 1).max()
        expect(window[0] <= dev <= window[1], "%s %d: pressure deviates by %.3g from uniform (expected in [%g, %g])" % (red, ranks, dev, window[0], window[1]))
        expect(abs((p * c["area"][:]).sum() - rn.sum()) <= 1e-12, "%s %d: pressure times area does not sum to the normal force" % (red, ranks))
        if ref is None:
            ref = p
        expect(np.abs(p - ref).max() <= 1e-8, "%s %d: pressures differ from direct on 1 rank by %.1e" % (red, ranks, np.abs(p - ref).max()))
        expect(c["group"].attrs["names"] in (b"lid_bottom->base_top", "lid_bottom->base_top"), "the pair is not named in /contact/group: %s" % c["group"].attrs["names"])


@test("a block sliding on a block (scenes/slider.opts, phi = 0.5, the push along x larger than phi times the pressure): every touching slave node slides, the tangential force of the contact equals phi times its normal force to 1e-4 (measured 8e-6), opposite to the slip; direct and none, 1 and 2 ranks agree to 1e-7; the same with the dual mortar coupling")
def pairs_sliding_block():
    ref = None
    for red, ranks in PATHS + [("mortar", 1), ("mortar", 2)]:
        extra = ["-pair_discretization", "dual_mortar"] if red == "mortar" else ["-snes_ssstar_reduction", red]
        out, states, c = contact(scene("slider") + extra, "pairs_slider_%s_%d.h5" % (red, ranks), ranks)
        rn, rt = forces(c)
        expect(states[3] + states[4] + states[5] == 0 and states[1] > 0, "%s %d: states %s, expected every touching node sliding" % (red, ranks, states), out)
        ratio = np.linalg.norm(rt.sum(0)) / rn.sum()
        expect(abs(ratio - 0.5) <= 1e-4 * 0.5, "%s %d: tangential / normal force %.8f, not phi = 0.5" % (red, ranks, ratio), out)
        slip = c["slip"][:]
        touching = ~np.isin(c["state"][:], (0, 6))
        expect((slip[touching, 0] > 0).all() and (rt[touching, 0] < 0).all(), "%s %d: friction not against the slip along +x" % (red, ranks))
        expect(np.abs(c["final_gap"][:][touching]).max() <= 1e-9, "%s %d: touching nodes with a gap" % (red, ranks))
        if ref is None:
            ref = rn
        if red != "mortar":
            expect(np.abs(rn - ref).max() <= 1e-7 * np.abs(ref).max(), "%s %d: normal forces differ from direct on 1 rank" % (red, ranks))


@test("examples/plot_contact.py draws each pair's slave face (titled slave->master) from the HDF5 of a pair scene")
def pairs_plot():
    h5 = os.path.join(OUT, "pairs_slider_direct_1.h5")
    if not os.path.exists(h5):
        contact(scene("slider"), "pairs_slider_direct_1.h5")
    png = os.path.join(OUT, "pairs_slider.png")
    if os.path.exists(png):
        os.remove(png)
    out = run(PLOT + [h5, "-o", png])
    expect(os.path.getsize(png) > 10000, "no picture", out)
    expect("slider_bottom->base_top" in out, "the pair is not named", out)


SLIDER = ["-geo", "meshes/slider.geo", "-level", "1", "-E", "1", "-nu", "0.3", "-dirichlet", "bottom", "-traction_slider_top", "0.008,0,-0.01",
          "-contact", "slider_bottom", "-friction_slider_bottom", "0.5"]
HELD = ["-spring_slider_top", "0.01"]
REFUSED = [
    ("same body", HELD + ["-contact_pair_slider_bottom", "slider_top"],
     'Option -contact_pair_slider_bottom slider_top: the groups "slider_bottom" and "slider_top" are on the same body'),
    ("master not a surface", HELD + ["-contact_pair_slider_bottom", "slider"],
     'Physical group "slider" of mesh %s is not a surface group, as option -contact_pair_slider_bottom needs' % mesh_of("meshes/slider.geo", 1)),
    ("unknown master", HELD + ["-contact_pair_slider_bottom", "nothing"],
     'Mesh %s has no physical group named "nothing" (option -contact_pair_slider_bottom)' % mesh_of("meshes/slider.geo", 1)),
    ("slave not a contact group", HELD + ["-contact_pair_base_top", "slider_bottom"],
     'Option -contact_pair_base_top: "base_top" is not a contact group (not in -contact; the nearest contact group is "slider_bottom")'),
    ("no master", HELD + ["-contact_pair_slider_bottom"], "Option -contact_pair_slider_bottom needs the name of the master surface group H"),
    ("obstacle and master", HELD + ["-contact_pair_slider_bottom", "base_top", "-obstacle_slider_bottom", "0,0,0,0,0,1"],
     "Options -contact_pair_slider_bottom and -obstacle_slider_bottom contradict each other"),
    ("master held fixed", HELD + ["-contact_pair_slider_bottom", "bottom"], 'the master "bottom" is held fixed'),
]


@test("bad pairs refused naming the option (groups of one body, a master that is a volume or unknown or held fixed, a slave not in -contact, no master, an obstacle too); the check that gathers over the ranks on 1 and 2 ranks (bodies nothing holds: suite_floating.py)", full=True)
def pairs_refused():
    for what, extra, message in REFUSED:
        for ranks in ((1, 2) if what == "same body" else (1,)):
            out = run(mpiexec(ranks, CONTACT, *SLIDER, *extra), expect_rc=1)
            expect(message in out, "%s (%d ranks): not refused with '%s'" % (what, ranks, message), out)


@test("Hertz between two elastic bodies (scenes/hertz2.opts, level 1: a half ball R = 10 on a block of the same material, frictionless, E* = E / (2 (1 - nu^2))): the fitted contact radius and peak pressure within 3 % of Hertz's (measured node-to-surface +1.8 %, +1.8 % on both paths; dual mortar +1.2 %, +1.5 %; level 2 node-to-surface +0.8 %, +0.3 %)", full=True)
def pairs_hertz():
    for extra, ranks, h5 in ((["-snes_ssstar_reduction", "direct"], 1, "pairs_hertz2_direct.h5"),
                             (["-snes_ssstar_reduction", "none"], 2, "pairs_hertz2_none.h5"),
                             (["-pair_discretization", "dual_mortar"], 1, "pairs_hertz2_mortar.h5")):
        out, states, c = contact(scene("hertz2") + extra, h5, ranks)
        h = scene_answers.hertz(os.path.join(OUT, h5), E=1.05e5)
        expect(abs(h["a_error"]) <= 0.03 and abs(h["p0_error"]) <= 0.03, "%s: a %+.3f, p0 %+.3f against Hertz" % (" ".join(extra), h["a_error"], h["p0_error"]), out)
        expect(abs(h["force"] / 31415.9 - 1) <= 0.02, "%s: contact force %g, not the load" % (" ".join(extra), h["force"]), out)


@test("Cattaneo-Mindlin (scenes/mindlin.opts, level 1: the half ball on the block, phi = 0.3, P then Q at the contact's height): for Q/(phi P) = 0.25, 0.5, 0.75 the outermost sticking node lies within 0.1 (half the mesh size at the pole) of c = a (1 - Q/(phi P))^(1/3) (measured node-to-surface -0.007 at 0.25, -0.083 at 0.5; dual mortar -0.001 at 0.5, -0.061 at 0.75); the whole body on 2 ranks gives the same states", full=True)
def pairs_cattaneo_mindlin():
    for q, ratio, method in (("5.89", 0.25, "node_to_surface"), ("11.78", 0.5, "node_to_surface"), ("11.78", 0.5, "dual_mortar"), ("17.67", 0.75, "dual_mortar")):
        if True:
            h5 = "pairs_mindlin_%s_%s.h5" % (q, method)
            out, states, c = contact(scene("mindlin") + ["-traction_block_top", "-%s,0,0" % q, "-pair_discretization", method], h5)
            m = scene_answers.stick_radius(os.path.join(OUT, h5), 0.3, 2.1e5)
            qp, cm, stick = m["ratio"], m["c"], m["stick_outer"]
            expect(abs(qp - ratio) <= 0.005, "%s %s: Q/(phi P) = %.4f, not %g" % (q, method, qp, ratio), out)
            expect(abs(stick - cm) <= 0.1, "%s %s: outermost sticking node at r = %.3f, Cattaneo-Mindlin c = %.3f" % (q, method, stick, cm), out)
    out, states2, c = contact(scene("mindlin") + ["-snes_ssstar_reduction", "none"], "pairs_mindlin_none_2.h5", 2)
    out, states1, c = contact(scene("mindlin"), "pairs_mindlin_direct_1.h5", 1)
    expect(states1 == states2, "the whole body on 2 ranks: states %s, direct on 1 rank %s" % (states2, states1), out)


def corrupted(src, name, change):
    """A copy of the solution file src with change(contact group) applied"""
    import shutil
    dst = os.path.join(OUT, name)
    shutil.copy(src, dst)
    with h5py.File(dst, "r+") as f:
        change(f["contact"])
    return dst


@test("tests/check_solution.py judges two bodies by the relative gap and slip the file records (/contact/final_gap, "
      "/contact/slip): the slider, the patch test and hertz2 pass 'coulomb FILE' (the law at every slave node against "
      "the master surface); a copy with the slip reversed at the sliding nodes, and one with a slave node 1 % of the "
      "largest displacement into the master, fail naming the law they break")
def pairs_check_solution():
    for name in ("slider", "patch", "hertz2"):
        h5 = os.path.join(OUT, "check_%s.h5" % name)
        contact(scene(name), "check_%s.h5" % name)
        law = run(CHECK + ["coulomb", h5])
        expect("VIOLATED" not in law and "final_gap and /contact/slip" in law, "%s: the law against the master surface" % name, law)
    src = os.path.join(OUT, "check_slider.h5")

    def reverse(c):
        slip = c["slip"][:]
        c["slip"][...] = -slip

    def penetrate(c):
        gap, scale = c["final_gap"][:], np.abs(c["displacement"][:]).max()
        touching = np.argmax(np.einsum("ij,ij->i", c["reaction"][:], c["normal"][:]))
        gap[touching] = -0.01 * scale
        c["final_gap"][...] = gap

    out = run(CHECK + ["coulomb", corrupted(src, "check_slider_reversed.h5", reverse)], expect_rc=1)
    expect(re.search(r"r_t = -bound w_t/\|w_t\|\s+\S+ VIOLATED", out) is not None, "a reversed slip passes", out)
    out = run(CHECK + ["coulomb", corrupted(src, "check_slider_penetrating.h5", penetrate)], expect_rc=1)
    expect(re.search(r"w_n >= 0\s+\S+ VIOLATED", out) is not None and re.search(r"w_n r_n = 0\s+\S+ VIOLATED", out) is not None,
           "a penetrating slave node passes", out)
