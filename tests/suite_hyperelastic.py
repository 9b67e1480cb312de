"""Hyperelastic bodies (docs/guide/large-deformation.md, docs/derivation.md section 18): the material models' kernels
and their numerical check, homogeneous compressions against the closed forms of uniaxial stress, a rigid rotation of
90 degrees (no stress; the linear model's spurious one beside it), Newton's convergence, the small-strain limit, the
file's fields, bad input refused by name."""
import os
import re
import subprocess

import h5py
import numpy as np

from harness import *  # noqa: F401,F403 (run, expect, mpiexec, test, paths)

CONTACT = os.path.join(ROOT, "examples", "contact")
E, NU = 1000.0, 0.3
LAM, MU = E * NU / ((1 + NU) * (1 - 2 * NU)), E / (2 * (1 + NU))
CUBE = ["-geo", os.path.join(ROOT, "meshes", "cube.geo"), "-E", "1000", "-nu", "0.3"]
# the unit cube held on three planes of symmetry (x = 0, y = 0, z = 0: each in its normal only), its top moved down:
# a homogeneous uniaxial stress
SYMMETRY = ["-displacement_bottom", "free,free,0", "-displacement_left", "0,free,free", "-displacement_front", "free,0,free"]
STRAINS = (0.1, 0.3, 0.5)
TIGHT = ["-snes_rtol", "1e-12", "-snes_atol", "1e-9"]


def uniaxial(model, l3):
    """The closed form of a uniaxial stress (sigma_xx = sigma_yy = 0) at the stretch l3 along z: the lateral stretch s
    and the nominal stress P_33 (the force per reference area) of each model (docs/derivation.md (18.6))"""
    if model == "linear":
        return 1 - NU * (l3 - 1), E * (l3 - 1)
    if model == "saint_venant_kirchhoff":
        E33 = 0.5 * (l3 * l3 - 1)
        return np.sqrt(1 - 2 * NU * E33), l3 * E * E33
    lo, hi = 0.5, 2.0  # neo-Hookean: mu (s^2 - 1) + lambda ln(s^2 l3) = 0
    for _ in range(200):
        s = 0.5 * (lo + hi)
        if MU * (s * s - 1) + LAM * np.log(s * s * l3) > 0:
            hi = s
        else:
            lo = s
    s = 0.5 * (lo + hi)
    return s, MU * (l3 - 1 / l3) + LAM * np.log(s * s * l3) / l3


def contact(args, h5, ranks=1, expect_rc=0):
    out = run(mpiexec(ranks, CONTACT, *args, "-o", os.path.join(OUT, h5)), expect_rc=expect_rc)
    return out, h5py.File(os.path.join(OUT, h5), "r")


def law(h5):
    out = run(CHECK + ["law", os.path.join(OUT, h5), "--steps"])
    expect("VIOLATED" not in out and "WRONG" not in out, "check_solution.py law %s" % h5, out)


def steps(f):
    return sorted((k for k in f.get("steps", {}) if k.isdigit()), key=int)


@test("docs/derivation.md section 18 holds (tests/hyperelastic_check.py, numpy, independent of the C code): each model's P = dW/dF and A = dP/dF (central differences), Hooke's at F = I; a P1 cell's force balances, has no moment about any point of the current configuration and is the gradient of V W; its tangent is the force's derivative and symmetric; the closed forms of uniaxial stress at stretches 0.9, 0.7, 0.5; no stress from a rotation, the linear model's at 90 degrees; the small-strain limit falls as the strain; neo-Hookean's Cauchy stress; the predictor of prescribed displacements")
def hyperelastic_derivation():
    out = run([PYTHON, os.path.join(ROOT, "tests", "hyperelastic_check.py")])
    expect("all checks passed" in out and "FAIL" not in out, "tests/hyperelastic_check.py", out)


@test("the material models' kernels give hand-computed values and their own derivatives (tests/test_hyperelastic.c): P = dW/dF and A = dP/dF by central differences to 1e-7 for the linear, Saint Venant-Kirchhoff and neo-Hookean models, A's major symmetry, Hooke's at F = I; a rotation of 90 degrees stresses neither hyperelastic model and gives the linear one the spurious stress of eps = diag(-1, -1, 0); the uniaxial stretch by hand; the Cauchy stress objective; det F <= 0 refused by neo-Hookean; a cell's force the gradient of V W and its tangent the force's derivative")
def hyperelastic_kernels():
    out = run([os.path.join(ROOT, "tests", "test_hyperelastic")])
    expect("passed: 0 failures" in out, "tests/test_hyperelastic", out)


@test("a homogeneous compression of the unit cube (meshes/cube.geo, E = 1000, nu = 0.3) held on three planes of symmetry, its top moved down by 10 %, 30 %, 50 % with x and y free (a load path, no contact: Newton's method): for saint_venant_kirchhoff, neo_hookean and linear the top's reaction /steps/groups/top/reaction is the closed form P_33 A of uniaxial stress to 1e-8 relative at every step, u_x = (s - 1) x with the lateral stretch s of the closed form, every cell's J = s^2 lambda_3, Cauchy stress (0, 0, P_33 lambda_3 / J) and (hyperelastic) Green-Lagrange strain to 1e-8; check_solution.py law --steps accepts the file; 1 rank, and 2 for neo_hookean")
def hyperelastic_compression():
    history = "0:free,free,0;" + ";".join("%d:free,free,%g" % (k + 1, -d) for k, d in enumerate(STRAINS))
    for model in ("saint_venant_kirchhoff", "neo_hookean", "linear"):
        for ranks in (1, 2) if model == "neo_hookean" else (1,):
            h5 = "hyperelastic_compression_%s_%d.h5" % (model, ranks)
            out, f = contact(CUBE + ["-level", "1", "-material_model", model, "-displacement_top", history] + SYMMETRY + TIGHT, h5, ranks)
            what = "%s, %d ranks" % (model, ranks)
            reactions = f["steps/groups/top/reaction"][:]
            for k, delta in enumerate((0.0,) + STRAINS):
                l3 = 1 - delta
                s, P33 = uniaxial(model, l3)
                expect(np.abs(reactions[k] - [0, 0, P33]).max() <= 1e-8 * max(abs(P33), 1.0), "%s, %g %%: the top's reaction %s, not the closed form (0, 0, %.10g)" % (what, 100 * delta, reactions[k], P33), out)
                prefix = "steps/%d/" % k
                x, u = f["geometry/vertices"][:], f[prefix + "fields/displacement"][:]
                expect(np.abs(u[:, 0] - (s - 1) * x[:, 0]).max() <= 1e-8 and np.abs(u[:, 2] + delta * x[:, 2]).max() <= 1e-8, "%s, %g %%: the displacement is not the homogeneous (s - 1) x, -delta z" % (what, 100 * delta))
                stress = f[prefix + "fields/stress"][:]
                if model == "linear":
                    sigma = [0, 0, P33]
                    expect("steps/0/fields/J" not in f, "%s: a linear scene's file has J" % what)
                else:
                    J = s * s * l3
                    sigma = [0, 0, P33 * l3 / J]
                    strain = 0.5 * np.array([s * s - 1, s * s - 1, l3 * l3 - 1, 0, 0, 0])
                    expect(np.abs(f[prefix + "fields/J"][:] - J).max() <= 1e-8, "%s, %g %%: J is not s^2 lambda_3 = %g" % (what, 100 * delta, J))
                    expect(np.abs(f[prefix + "fields/strain"][:] - strain).max() <= 1e-8, "%s, %g %%: the Green-Lagrange strain is not the closed form's" % (what, 100 * delta))
                expect(np.abs(stress - np.array(sigma + [0, 0, 0])).max() <= 1e-8 * max(abs(P33), 1.0), "%s, %g %%: the Cauchy stress is off the closed form (0, 0, %g) by %g" % (what, 100 * delta, sigma[2], np.abs(stress - np.array(sigma + [0, 0, 0])).max()))
            law(h5)


@test("the same compression with the cube's bottom in contact with the rigid plane z = 0 (-contact bottom, frictionless; the planes x = 0, y = 0 of symmetry; the top's z prescribed to 10 %, 30 %, 50 %; ssstar on the nonlinear residual, the whole body; Saint Venant-Kirchhoff to 50 % past its limit point with -pc_type lu, to 30 % with the defaults): for saint_venant_kirchhoff and neo_hookean the top's reaction and the contact's normal force are both the closed form P_33 A of uniaxial stress to 1e-8 relative at every step, every contact node touches with no gap, every cell's J = s^2 lambda_3; check_solution.py law --steps accepts the file; 1 rank, and 2 for neo_hookean")
def hyperelastic_compression_contact():
    # Saint Venant-Kirchhoff's tangent is indefinite past its limit point lambda_3 = 1/sqrt(3) (0.577): the whole body's
    # default Krylov solver (conjugate gradients) stops there; a direct solver (-pc_type lu, MUMPS) takes it to 50 %
    lu = ["-pc_type", "lu", "-pc_factor_mat_solver_type", "mumps"]
    for model, strains, extra in (("neo_hookean", STRAINS, []), ("saint_venant_kirchhoff", STRAINS[:2], []), ("saint_venant_kirchhoff", STRAINS, lu)):
        history = "0:free,free,0;" + ";".join("%d:free,free,%g" % (k + 1, -d) for k, d in enumerate(strains))
        for ranks in (1, 2) if model == "neo_hookean" else (1,):
            h5 = "hyperelastic_contact_%s_%d%s.h5" % (model, ranks, "_lu" if extra else "")
            out, f = contact(CUBE + ["-level", "1", "-material_model", model, "-displacement_top", history, "-contact", "bottom", "-friction_law_bottom", "none"] + SYMMETRY[2:] + TIGHT + extra, h5, ranks)
            what = "%s, %d ranks%s" % (model, ranks, " " + " ".join(extra) if extra else "")
            for k, delta in enumerate(strains, start=1):
                l3 = 1 - delta
                s, P33 = uniaxial(model, l3)
                top = f["steps/groups/top/reaction"][k]
                normal = f["steps/%d/contact/reaction" % k][:, 2].sum()
                expect(abs(top[2] - P33) <= 1e-8 * abs(P33) and abs(normal + P33) <= 1e-8 * abs(P33), "%s, %g %%: the top's reaction %g and the contact's normal force %g, not the closed form %.10g" % (what, 100 * delta, top[2], normal, -P33), out)
                expect(np.abs(f["steps/%d/contact/final_gap" % k][:]).max() <= 1e-9, "%s, %g %%: a contact node off the plane" % (what, 100 * delta), out)
                expect(np.abs(f["steps/%d/fields/J" % k][:] - s * s * l3).max() <= 1e-8, "%s, %g %%: J is not s^2 lambda_3" % (what, 100 * delta))
            law(h5)


def pressed_ball(ranks):
    args = ["-geo", os.path.join(ROOT, "meshes", "indent.geo"), "-level", "1", "-E", "1000", "-nu", "0.3", "-material_model", "neo_hookean", "-contact", "top", "-obstacle_top", "sphere:0,0,10,10", "-friction_law_top", "none", "-displacement_bottom", "0:0,0,0;1:0,0,0.5;2:0,0,1"]
    h5 = "hyperelastic_ball_%d.h5" % ranks
    out, f = contact(args, h5, ranks)
    what = "%d ranks" % ranks
    expect(out.count("set-up:") == len(re.findall(r"^step \d+/\d+ ", out, re.M)), "%s: a step solved more than once (the contact not measured at the iterates)" % what, out)
    x, c = f["geometry/vertices"][:], f["contact/coordinates"][:]
    nodes = np.argmin(((c[:, None, :] - x[None, :, :]) ** 2).sum(axis=-1), axis=1)
    for k in (1, 2):
        gap = np.linalg.norm(f["steps/%d/fields/position" % k][:][nodes] - [0, 0, 10], axis=1) - 10
        touching = f["steps/%d/contact/state" % k][:] > 0
        expect(touching.sum() > 100 and np.abs(gap[touching]).max() <= 1e-8 and gap.min() >= -1e-8, "%s, step %d: %d touching nodes, off the sphere by up to %g, the deepest %g" % (what, k, touching.sum(), np.abs(gap[touching]).max(), gap.min()), out)
        forces = f["steps/%d/contact/reaction" % k][:].sum(axis=0)
        expect(np.abs(f["steps/groups/bottom/reaction"][k] + forces).max() <= 1e-8 * np.abs(forces).max(), "%s, step %d: the bottom's reaction %s does not balance the contact forces %s" % (what, k, f["steps/groups/bottom/reaction"][k], forces), out)
    law(h5)


BALL = "a neo-Hookean block (meshes/indent.geo level 1, E = 1000) pushed by its bottom 0.5 and 1.0 into the rigid ball of radius 10 (frictionless, a load path): the contact is measured at every iterate (large sliding within the Newton loop, SNESSSStarSetContactUpdate), so every touching node's current position lies on the sphere to 1e-8 (the loop between solves left 1e-4) with no node inside it, every step (or halved step) is solved once, the bottom's reaction balances the contact forces to 1e-8 of them, and check_solution.py law --steps accepts the file"


@test(BALL + "; 1 rank")
def hyperelastic_ball():
    pressed_ball(1)


@test(BALL + "; 2 ranks (slow: about a minute on the shared machine)", full=True)
def hyperelastic_ball_parallel():
    pressed_ball(2)


@test("Coulomb friction on a load path with a hyperelastic body: the neo-Hookean unit cube on the rigid plane with phi = 0.3 (-friction_bottom), its top pressed down 20 % then moved sideways by 0.2 and 0.5 (x), the slip incremental: check_solution.py law --steps accepts every step, the top's reaction balances the contact forces to 1e-8 of them at every step, the first sideways step leaves nodes sticking, at the last every contact node slides and the tangential resultant is within 1 % below phi times the normal force (the nodes' slips nearly parallel); 1 and 2 ranks")
def hyperelastic_friction():
    args = CUBE + ["-level", "1", "-material_model", "neo_hookean", "-contact", "bottom", "-friction_bottom", "0.3", "-displacement_top", "0:0,0,0;1:0,0,-0.2;2:0.2,0,-0.2;3:0.5,0,-0.2"]
    for ranks in (1, 2):
        h5 = "hyperelastic_friction_%d.h5" % ranks
        out, f = contact(args, h5, ranks)
        what = "%d ranks" % ranks
        for k in (1, 2, 3):
            forces = f["steps/%d/contact/reaction" % k][:].sum(axis=0)
            expect(np.abs(f["steps/groups/top/reaction"][k] + forces).max() <= 1e-8 * np.abs(forces).max(), "%s, step %d: the top's reaction %s does not balance the contact forces %s" % (what, k, f["steps/groups/top/reaction"][k], forces), out)
        states = [f["steps/%d/contact/state" % k][:] for k in (2, 3)]
        expect((states[0] == 1).sum() < len(states[0]) and (states[1] == 1).all(), "%s: the sliding nodes %d, %d of %d, not some then all" % (what, (states[0] == 1).sum(), (states[1] == 1).sum(), len(states[1])), out)
        forces = f["steps/3/contact/reaction"][:].sum(axis=0)
        ratio = np.hypot(forces[0], forces[1]) / (0.3 * abs(forces[2]))
        expect(0.99 <= ratio <= 1 + 1e-9, "%s: the tangential resultant is %g of phi N" % (what, ratio), out)
        law(h5)


@test("a rigid rotation of 90 degrees about z (-rotation_bottom, through the cube's axis x = y = 0.5, in three steps of 30 degrees) prescribed on the bottom of the unit cube, nothing else holding or loading it: a hyperelastic body (saint_venant_kirchhoff, neo_hookean) turns rigidly, every cell's Cauchy stress zero to 1e-9 E and the displacement the rigid rotation's to 1e-9, J = 1; the linear model's answer to the same prescription is strained (its von Mises stress reaches more than 0.1 E): the small-strain model's spurious stress; 1 and 2 ranks")
def hyperelastic_rotation():
    args = CUBE + ["-level", "1", "-rotation_bottom", "0:0,0,0;1:0,0,30;2:0,0,60;3:0,0,90", "-rotation_center_bottom", "0.5,0.5,0"] + TIGHT
    for model in ("saint_venant_kirchhoff", "neo_hookean"):
        for ranks in (1, 2):
            h5 = "hyperelastic_rotation_%s_%d.h5" % (model, ranks)
            out, f = contact(args + ["-material_model", model], h5, ranks)
            x, u = f["geometry/vertices"][:], f["fields/displacement"][:]
            rigid = np.column_stack([1 - x[:, 1], x[:, 0], x[:, 2]]) - x  # 90 degrees about (0.5, 0.5, z)
            what = "%s, %d ranks" % (model, ranks)
            expect(np.abs(u - rigid).max() <= 1e-9, "%s: the displacement is off the rigid rotation by %g" % (what, np.abs(u - rigid).max()), out)
            expect(np.abs(f["fields/stress"][:]).max() <= 1e-9 * E and np.abs(f["fields/J"][:] - 1).max() <= 1e-9, "%s: the rotated body is stressed (%g) or its volume changed" % (what, np.abs(f["fields/stress"][:]).max()), out)
            law(h5)
    out, f = contact(args, "hyperelastic_rotation_linear.h5")
    vm = f["fields/von_mises"][:].max()
    expect(vm > 0.1 * E, "the linear model's answer to a rotation of 90 degrees is not strained (max von Mises %g)" % vm, out)


def monitor_norms(out):
    """the -snes_monitor norms of each solve: a list per solve"""
    solves, current = [], []
    for line in out.splitlines():
        m = re.match(r"\s*(\d+) SNES Function norm ([0-9.eE+-]+)", line)
        if m:
            if int(m.group(1)) == 0 and current:
                solves.append(current)
                current = []
            current.append(float(m.group(2)))
    return solves + [current] if current else solves


@test("Newton's method on a hyperelastic body converges quadratically: a cantilever (meshes/cantilever.geo level 1, 10 x 1 x 1, E = 1000, clamped root) bent by a tip traction of 0.1 (a tip deflection of 4 % of its length: its rotation makes the problem nonlinear; the homogeneous compressions converge in one Newton step after the predictor) converges in at most 6 iterations for saint_venant_kirchhoff and neo_hookean, and the observed order log(r_k+1/r_k)/log(r_k/r_k-1) of its last three residuals above 1e-9 r_0 is at least 1.8")
def hyperelastic_newton_order():
    args = ["-geo", os.path.join(ROOT, "meshes", "cantilever.geo"), "-level", "1", "-E", "1000", "-nu", "0.3", "-dirichlet", "root", "-traction_tip", "0,0,-0.1", "-snes_monitor", "-snes_rtol", "1e-14", "-snes_atol", "1e-13"]
    for model in ("saint_venant_kirchhoff", "neo_hookean"):
        out, f = contact(args + ["-material_model", model], "hyperelastic_newton_%s.h5" % model)
        r = monitor_norms(out)[-1]
        expect(len(r) - 1 <= 6, "%s: %d iterations" % (model, len(r) - 1), out)
        above = [x for x in r if x > 1e-9 * r[0]]  # above round-off
        expect(len(above) >= 3, "%s: too few iterations to measure an order: %s" % (model, r), out)
        order = np.log(above[-1] / above[-2]) / np.log(above[-2] / above[-3])
        expect(order >= 1.8, "%s: observed order %.2f of %s" % (model, order, r), out)


@test("the small-strain limit: a cantilever (meshes/cantilever.geo level 1, clamped root) under a tip traction of 1e-4 (strains about 1e-4): the hyperelastic models' displacements equal the linear model's to 1e-3 relative (the strain's order) but not to 1e-7 (they are not the linear model); the root's reactions balance the load")
def hyperelastic_small_strain():
    args = ["-geo", os.path.join(ROOT, "meshes", "cantilever.geo"), "-level", "1", "-E", "1000", "-nu", "0.3", "-dirichlet", "root", "-traction_tip", "0,0,-1e-4"] + TIGHT
    _, lin = contact(args, "hyperelastic_small_linear.h5")
    ul = lin["fields/displacement"][:]
    for model in ("saint_venant_kirchhoff", "neo_hookean"):
        out, f = contact(args + ["-material_model", model], "hyperelastic_small_%s.h5" % model)
        d = np.abs(f["fields/displacement"][:] - ul).max() / np.abs(ul).max()
        expect(1e-7 < d < 1e-3, "%s: its displacement differs from the linear model's by %g relative" % (model, d), out)
        expect(abs(f["groups/root/reaction"][2] - 1e-4) <= 1e-10, "%s: the root's reaction %s does not balance the load" % (model, f["groups/root/reaction"][:]))


@test("bad input is refused by name, before any work: an unknown -material_model or -material_model_<G> value, a -material_model_<G> of a surface group or a group the mesh lacks, a -rotation_center_<G> without -rotation_<G>, a rotation and a displacement on the same nodes; exit with an error, no file")
def hyperelastic_refused():
    cases = [
        (["-material_model", "rubber"], "rubber"),
        (["-material_model_cube", "rubber"], "-material_model_cube rubber: unknown material model"),
        (["-material_model_top", "neo_hookean"], "not a volume group"),
        (["-material_model_block", "neo_hookean"], "no physical group named \"block\""),
        (["-rotation_center_top", "0,0,0"], "-rotation_center_top needs -rotation_top"),
        (["-rotation_top", "0,0,10", "-displacement_top", "0,0,-0.1"], "prescribed twice"),
    ]
    for extra, message in cases:
        h5 = os.path.join(OUT, "hyperelastic_refused.h5")
        if os.path.exists(h5):
            os.remove(h5)
        out = run([CONTACT] + CUBE + ["-level", "1", "-dirichlet", "bottom"] + extra + ["-o", h5], expect_rc=1)
        expect(message in out, "%s: no error naming it (%s)" % (" ".join(extra), message), out)
        expect(not os.path.exists(h5), "%s: a file was written" % " ".join(extra))


# the unit cube held by contact alone: its bottom on the frictionless plane z = 0, a dead traction on its top
FLOATING = ["-level", "1", "-contact", "bottom", "-friction_law_bottom", "none", "-snes_rtol", "1e-13", "-snes_atol", "1e-13"]


def stretch(model, load):
    """The stretch l3 of uniaxial stress whose nominal stress P_33 is -load (bisection on (18.6))"""
    lo, hi = 0.3 if model == "neo_hookean" else 1 / np.sqrt(3), 1.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if uniaxial(model, mid)[1] < -load:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def floating_cube(model, load, h5, ranks=1):
    out, f = contact(CUBE + FLOATING + ["-material_model", model, "-traction_top", "0,0,%.17g" % -load], h5, ranks)
    force = f["contact/reaction"][:].sum(axis=0)
    expect(np.abs(force - [0, 0, load]).max() <= 1e-8 * load, "%s %g on %d ranks: the plane carries %s, not the load (0, 0, %g)" % (model, load, ranks, force, load), out)
    return out, f


@test("a hyperelastic body held by contact alone (docs/derivation.md section 18b): the unit cube on the frictionless plane z = 0 (nothing else holds it: its sliding and turning about z are free), a dead traction on its top (neo_hookean 300 = a compression of 24 %, saint_venant_kirchhoff 100, below its limit point): the contact forces balance the load to 1e-8 relative, the top's u_z is the closed form lambda_3 - 1 of uniaxial stress (18.6) and every cell's J = s^2 lambda_3 to 1e-8, in at most 8 iterations; check_solution.py law --steps accepts the file; neo_hookean on 1 and 2 ranks")
def hyperelastic_floating():
    for model, load, ranks in (("neo_hookean", 300.0, 1), ("neo_hookean", 300.0, 2), ("saint_venant_kirchhoff", 100.0, 1)):
        h5 = "hyperelastic_floating_%s_%d.h5" % (model, ranks)
        out, f = floating_cube(model, load, h5, ranks)
        l3 = stretch(model, load)
        s = uniaxial(model, l3)[0]
        x, u = f["geometry/vertices"][:], f["fields/displacement"][:]
        top = np.abs(x[:, 2] - 1) < 1e-12
        expect(np.abs(u[top, 2] - (l3 - 1)).max() <= 1e-8, "%s %d: top u_z %s, closed form %.10f" % (model, ranks, u[top, 2][:3], l3 - 1), out)
        expect(np.abs(f["fields/J"][:] - s * s * l3).max() <= 1e-8, "%s %d: J from %.10f to %.10f, closed form %.10f" % (model, ranks, f["fields/J"][:].min(), f["fields/J"][:].max(), s * s * l3))
        its = [int(k) for k in re.findall(r"^\s*(\d+) SSStar \|\|z\|\|", out, re.M)]
        expect("CONVERGED" in out and its and max(its) <= 8, "%s %d: %s iterations" % (model, ranks, max(its) if its else "no"), out)
        law(h5)


@test("the small-strain limit of a body held by contact alone: the floating cube of hyperelastic_floating under a traction of 0.1 (strains of 1e-4, the loads x 1e-3 of 100): neo_hookean's and saint_venant_kirchhoff's u_z equal the linear model's to 1e-3 relative (the strain's order) and not to 1e-7; the contact forces balance the load to 1e-8; and the stack of scenes/stack.opts (two floating blocks, phi = 0.5 and frictionless) with neo_hookean: the plane carries both weights (0, 0, 9810) and the pair the lid's (0, 0, 4905) to 1e-8 relative, on 1 and 2 ranks, check_solution.py law accepts the files")
def hyperelastic_floating_small_strain():
    ref = floating_cube("linear", 0.1, "hyperelastic_floating_linear.h5")[1]["fields/displacement"][:, 2]
    for model in ("neo_hookean", "saint_venant_kirchhoff"):
        uz = floating_cube(model, 0.1, "hyperelastic_floating_small_%s.h5" % model)[1]["fields/displacement"][:, 2]
        d = np.abs(uz - ref).max() / np.abs(ref).max()
        expect(1e-7 < d <= 1e-3, "%s: u_z differs from the linear model's by %.2e relative" % (model, d))
    stack = ["-options_file", os.path.join(ROOT, "scenes", "stack.opts"), "-level", "1", "-material_model", "neo_hookean"] + TIGHT
    for phi, ranks in (("0.5", 1), ("0.5", 2), ("0", 1)):
        h5 = "hyperelastic_floating_stack_%s_%d.h5" % (phi, ranks)
        out, f = contact(stack + ["-snes_ssstar_friction", phi], h5, ranks)
        names = f["contact/group"].attrs["names"]
        names = [n.split("->")[0] for n in (names.decode() if isinstance(names, bytes) else str(names)).split(",")]
        for g, w in (("bottom", 9810.0), ("lid_bottom", 4905.0)):
            force = f["contact/reaction"][:][f["contact/group"][:] == names.index(g)].sum(0)
            expect(np.abs(force - [0, 0, w]).max() <= 1e-8 * w, "stack phi %s %d: %s carries %s, not (0, 0, %g)" % (phi, ranks, g, force, w), out)
        law(h5)


def squeezed_ball(ranks, motion, model, h5):
    """scenes/squeeze.opts (the ball held by the two plates alone) with Coulomb phi = 0.3 on both caps, the top plate
    moved down by motion: the two plates' contact forces (they are the only loads: their sum vanishes)"""
    args = ["-options_file", os.path.join(ROOT, "scenes", "squeeze.opts"), "-material_model", model, "-friction_law_bottom_cap", "coulomb", "-friction_law_top_cap", "coulomb",
            "-snes_ssstar_friction", "0.3", "-obstacle_top_cap_motion", "0:0,0,0;1:0,0,%.17g" % -motion]
    out, f = contact(args, h5, ranks)
    names = f["contact/group"].attrs["names"]
    names = [n.split("->")[0] for n in (names.decode() if isinstance(names, bytes) else str(names)).split(",")]
    r, g = f["contact/reaction"][:], f["contact/group"][:]
    bottom, top = r[g == names.index("bottom_cap")].sum(0), r[g == names.index("top_cap")].sum(0)
    expect(bottom[2] > 0 and np.abs(bottom + top).max() <= 1e-8 * bottom[2], "%s %g on %d ranks: the plates' forces %s and %s do not balance" % (model, motion, ranks, bottom, top), out)
    expect("CONVERGED" in out, "%s %g on %d ranks: not converged" % (model, motion, ranks), out)
    law(h5)
    return bottom[2]


SQUEEZE = "the neo-Hookean ball of scenes/squeeze.opts held by the two plates alone (a floating body, docs/derivation.md 18b), with Coulomb phi = 0.3 on both caps, the top plate moved down by 0.2: converges, the plates' contact forces balance (their sum 0 to 1e-8 of the normal force), check_solution.py law --steps accepts the file"


@test(SQUEEZE + "; 1 rank")
def hyperelastic_floating_squeeze():
    squeezed_ball(1, 0.2, "neo_hookean", "hyperelastic_squeeze_1.h5")


@test(SQUEEZE + "; 2 ranks; and at loads x 1e-3 (the plate moved by 2e-4) the normal force equals the linear model's to 1e-2 relative (the strain's order, about 1e-3 at the contact) (slow)", full=True)
def hyperelastic_floating_squeeze_parallel():
    squeezed_ball(2, 0.2, "neo_hookean", "hyperelastic_squeeze_2.h5")
    small = squeezed_ball(1, 2e-4, "neo_hookean", "hyperelastic_squeeze_small.h5")
    linear = squeezed_ball(1, 2e-4, "linear", "hyperelastic_squeeze_linear.h5")
    expect(abs(small - linear) <= 1e-2 * linear, "the normal force at 2e-4: neo_hookean %.6g, linear %.6g" % (small, linear))


@test("the Python module solves a hyperelastic scene as examples/contact does: ssstar.Scene(material_model=\"neo_hookean\") of the cube compressed on the frictionless plane by 10 % and 30 % (ssstar, nonlinear residual) and of the cube held on its planes of symmetry (Newton's method, no contact): the top's reactions are the closed form P_33 A to 1e-8, the displacements of every step agree with examples/contact's to 2e-6 (and the contact's: check_solution.py compare) and pass check_solution.py law --steps")
def hyperelastic_python():
    history = "0:free,free,0;1:free,free,-0.1;2:free,free,-0.3"
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "python"))
    cases = {"contact": ["-contact", "bottom", "-friction_law_bottom", "none"] + SYMMETRY[2:], "symmetry": SYMMETRY}
    for name, extra in cases.items():
        options = CUBE + ["-level", "1", "-material_model", "neo_hookean", "-displacement_top", history] + extra
        keywords = ", ".join("%s=%r" % (options[k][1:], options[k + 1]) for k in range(0, len(options), 2))
        h5 = os.path.join(OUT, "hyperelastic_python_%s.h5" % name)
        script = "import ssstar\nscene = ssstar.Scene(%s, o=%r)\nscene.solve()\nscene.close()\n" % (keywords, h5)
        p = subprocess.run([PYTHON, "-c", script], cwd=ROOT, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=300)
        expect(p.returncode == 0, "%s: the Python scene failed" % name, p.stdout)
        f = h5py.File(h5, "r")
        for k, delta in enumerate((0.1, 0.3), start=1):
            P33 = uniaxial("neo_hookean", 1 - delta)[1]
            r = f["steps/groups/top/reaction"][k][2]
            expect(abs(r - P33) <= 1e-8 * abs(P33), "%s, %g %%: the top's reaction %g, not %.10g" % (name, 100 * delta, r, P33), p.stdout)
        law(os.path.basename(h5))
        c = "hyperelastic_python_%s_c.h5" % name
        _, g = contact(options, c)
        for k in steps(g):
            a, b = g["steps/%s/fields/displacement" % k][:], f["steps/%s/fields/displacement" % k][:]
            expect(np.abs(a - b).max() <= AGREE * max(np.abs(a).max(), 1e-300), "%s, step %s: the Python scene's displacement is not examples/contact's" % (name, k))
        if "contact" in g:
            run(CHECK + ["compare", os.path.join(OUT, c), h5, "--steps", "--tol", str(AGREE)])


GETFEM_BALL = os.path.join(ROOT, "tests", "data", "getfem_ball_L1.csv")


def getfem_ball(phi, ranks):
    """scenes/hemisphere.opts at level 1 (the neo-Hookean half ball, its top moved down to 0.3 R in 6 steps) with the
    friction phi, against GetFEM 5.4's curve of the same scene on the same mesh (tests/data/getfem_ball_L1.csv, written by
    bench/getfem_ball.py --reference: its command in the file's first line)"""
    rows = [line.split(",") for line in open(GETFEM_BALL) if not line.startswith(("#", "phi"))]
    known = {round(float(r[1]), 9): (float(r[2]), float(r[3])) for r in rows if float(r[0]) == phi}
    expect(len(known) == 6, "%s: no GetFEM curve of phi = %g" % (GETFEM_BALL, phi))
    h5 = "hyperelastic_getfem_ball_%g_%d.h5" % (phi, ranks)
    out, f = contact(["-options_file", os.path.join(ROOT, "scenes", "hemisphere.opts"), "-level", "1", "-friction_sphere", "%g" % phi], h5, ranks)
    what = "phi %g, %d ranks" % (phi, ranks)
    x, c = f["geometry/vertices"][:], f["contact/coordinates"][:]
    nodes = np.argmin(((c[:, None, :] - x[None, :, :]) ** 2).sum(axis=-1), axis=1)
    for k in range(1, 7):
        delta = round(0.5 * k, 9)
        force = f["steps/%d/contact/reaction" % k][:]
        normal = force[:, 2].sum()
        getfem_force, getfem_radius = known[delta]
        expect(abs(normal - getfem_force) <= AGREE * getfem_force, "%s, delta %g: the normal force %.10g, GetFEM's %.10g (%.1e apart)" % (what, delta, normal, getfem_force, abs(normal / getfem_force - 1)), out)
        carrying = force[:, 2] > 1e-6 * force[:, 2].max()
        position = f["steps/%d/fields/position" % k][:][nodes]
        radius = np.hypot(position[carrying, 0], position[carrying, 1]).max()
        expect(abs(radius - getfem_radius) <= 1e-5 * getfem_radius, "%s, delta %g: the contact radius %.6g, GetFEM's %.6g" % (what, delta, radius, getfem_radius), out)
        expect(np.abs(f["steps/groups/top/reaction"][k] + force.sum(axis=0)).max() <= 1e-8 * normal, "%s, delta %g: the top's reaction does not balance the contact forces" % (what, delta), out)
    law(h5)


BALL_GETFEM = "the neo-Hookean half ball of scenes/hemisphere.opts (meshes/hemisphere.geo level 1, R = 10, E = 1000, nu = 0.3, the whole sphere in contact with the rigid plane) pressed by its top to delta = 0.3 R in 6 steps gives at every step the normal force of GetFEM 5.4 on the same mesh (its finite-strain brick with the same W, its nodal contact brick with the plane: the same discrete problem; tests/data/getfem_ball_L1.csv, measured at most 7e-10 apart) to 2e-6 relative, the same contact radius (the outermost node carrying a normal force, current configuration) to 1e-5, the top's reaction balancing the contact forces; check_solution.py law --steps accepts the file"


@test(BALL_GETFEM + "; Coulomb friction phi = 0.3 on the path (incremental), 1 rank")
def hyperelastic_getfem_ball():
    getfem_ball(0.3, 1)


@test(BALL_GETFEM + "; frictionless on 1 rank and phi = 0.3 on 2 ranks", full=True)
def hyperelastic_getfem_ball_full():
    getfem_ball(0.0, 1)
    getfem_ball(0.3, 2)
