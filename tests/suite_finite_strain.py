"""Hyperelastic bodies on 3 and 4 ranks and the hard cases of bench/robust.py's finite_strain family
(docs/guide/large-deformation.md, docs/derivation.md section 18): a first step deep into an obstacle (a trial point with
an inverted cell halves the step), a body on a soft spring under a dead load and Saint Venant-Kirchhoff past its limit
point (an indefinite tangent: GMRES after CG), a pair under a large dead pressure."""
import os

import numpy as np

from harness import *  # noqa: F401,F403 (run, expect, mpiexec, test, paths)
from suite_hyperelastic import CUBE, contact, law, uniaxial

# the unit cube on the frictionless plane, held on its planes of symmetry x = 0, y = 0, its top's z prescribed
PLANE = CUBE + ["-level", "1", "-contact", "bottom", "-friction_law_bottom", "none", "-displacement_left", "0,free,free", "-displacement_front", "free,0,free"]
INDENT = ["-geo", os.path.join(ROOT, "meshes", "indent.geo"), "-level", "1", "-E", "1000", "-nu", "0.3", "-material_model", "neo_hookean", "-contact", "top",
          "-obstacle_top", "sphere:0,0,10,10", "-friction_law_top", "none"]


def compressed(model, strains):
    return PLANE + ["-material_model", model, "-displacement_top", "0:free,free,0;" + ";".join("%d:free,free,%g" % (k + 1, -d) for k, d in enumerate(strains))]


def closed_form(f, model, strains, what, out, tol=1e-8):
    for k, delta in enumerate(strains, start=1):
        P33 = uniaxial(model, 1 - delta)[1]
        top = f["steps/groups/top/reaction"][k][2]
        normal = f["steps/%d/contact/reaction" % k][:, 2].sum()
        expect(abs(top - P33) <= tol * abs(P33) and abs(normal + P33) <= tol * abs(P33), "%s, %g %%: the top's reaction %g and the contact's normal force %g, not the closed form %.10g" % (what, 100 * delta, top, normal, P33), out)


@test("docs/derivation.md section 18a holds (tests/finite_strain_check.py, numpy): a P1 cell's tangent along an infinitesimal rotation w = Omega x of its current configuration is -f . (Omega^2 x), f its internal force (central differences, both hyperelastic models, unstressed, compressed and sheared cells), zero unstressed and negative for the rotation of a compressed cell about a transverse axis; Saint Venant-Kirchhoff's uniaxial force has its maximum at lambda_3 = 1/sqrt(3)")
def finite_strain_derivation():
    out = run([PYTHON, os.path.join(ROOT, "tests", "finite_strain_check.py")])
    expect("all checks passed" in out and "FAIL" not in out, "tests/finite_strain_check.py", out)


@test("a neo-Hookean body on 3 and 4 ranks: the unit cube on the frictionless plane compressed by 10 %, 30 %, 50 % (its top's z prescribed, the planes of symmetry held; ssstar on the whole body) gives the top's reaction and the contact's normal force of the closed form of uniaxial stress to 1e-8 at every step on 3 and 4 ranks, and check_solution.py law --steps accepts the files")
def finite_strain_ranks():
    for ranks in (3, 4):
        h5 = "finite_strain_ranks_%d.h5" % ranks
        out, f = contact(compressed("neo_hookean", (0.1, 0.3, 0.5)) + ["-snes_rtol", "1e-12", "-snes_atol", "1e-9"], h5, ranks)
        closed_form(f, "neo_hookean", (0.1, 0.3, 0.5), "%d ranks" % ranks, out)
        law(h5)


def pushed(depth, ranks):
    h5 = "finite_strain_deep_%g_%d.h5" % (depth, ranks)
    out, f = contact(INDENT + ["-displacement_bottom", "0:0,0,0;1:0,0,%g" % depth, "-steps_max_cuts", "0"], h5, ranks)
    x, c = f["geometry/vertices"][:], f["contact/coordinates"][:]
    nodes = np.argmin(((c[:, None, :] - x[None, :, :]) ** 2).sum(axis=-1), axis=1)
    gap = np.linalg.norm(f["steps/1/fields/position"][:][nodes] - [0, 0, 10], axis=1) - 10
    touching = f["steps/1/contact/state"][:] > 0
    what = "pushed %g in one step, %d ranks" % (depth, ranks)
    expect(touching.sum() > 100 and np.abs(gap[touching]).max() <= 1e-8 and gap.min() >= -1e-8, "%s: %d touching nodes, off the sphere by up to %g" % (what, touching.sum(), np.abs(gap[touching]).max()), out)
    expect(f["steps/1/fields/J"][:].min() > 0, "%s: an inverted cell in the answer" % what, out)
    law(h5)
    return out


@test("a first step deep into an obstacle: the neo-Hookean block of meshes/indent.geo (level 1, E = 1000) pushed by its bottom 0.25 and 1.0 into the rigid ball of radius 10 in one step with no step halving (-steps_max_cuts 0) converges on 1 rank (0.25 stopped with DIVERGED_FNORM_NAN at iteration 0: the step's first trial point turned cells inside out, F undefined there; the trial is now refused and a Newton step to such a point halved until F is defined, as PETSc's line searches treat SNESSetFunctionDomainError), every touching node on the sphere to 1e-8, no cell inverted, the law holds")
def finite_strain_deep_step():
    for depth in (0.25, 1.0):
        pushed(depth, 1)


@test("the first deep step on 3 and 4 ranks: the block pushed 0.25 into the ball in one step converges as on one rank, every touching node on the sphere to 1e-8, no cell inverted, the law holds", full=True)
def finite_strain_deep_step_ranks():
    for ranks in (3, 4):
        pushed(0.25, ranks)


@test("a neo-Hookean half ball on a soft spring (scenes/hertz.opts at level 1: k = 1 per unit area against E = 2.1e5, the dead pressure 100 on its top, frictionless on the plane) converges at the defaults (it stopped at DIVERGED_MAX_IT: the dead load's geometric stiffness makes the tangent indefinite in the nearly free rotations, CG stopped with DIVERGED_INDEFINITE_MAT and the Newton step failed; GMRES now solves it on the same multigrid): the contact's normal force balances the load minus the spring's share to 1 % and the law holds", full=True)
def finite_strain_soft_spring():
    h5 = "finite_strain_soft_spring.h5"
    out, f = contact(["-options_file", os.path.join(ROOT, "scenes", "hertz.opts"), "-level", "1", "-material_model", "neo_hookean", "-info", ":snes"], h5)
    expect("DIVERGED_INDEFINITE_MAT" in out and "solved again by GMRES" in out, "the soft spring's tangent was not found indefinite (the case does not test the fallback)", out)
    normal = f["contact/reaction"][:, 2].sum()
    expect(abs(normal - 100 * np.pi * 100) <= 0.01 * 100 * np.pi * 100, "the normal force %g is not the load 31416 to 1 %%" % normal, out)
    law(h5)


@test("Saint Venant-Kirchhoff past its limit point at the defaults: the unit cube on the frictionless plane compressed by 10 %, 30 %, 50 % converges with the default Krylov solver at the defaults and at -snes_rtol 1e-13 (there it stopped with DIVERGED_LINEAR_SOLVE: its tangent is indefinite past 42 %, CG stops with DIVERGED_INDEFINITE_MAT, GMRES now solves the step); the steps before the limit point give the closed form to 1e-6, the 50 % step an equilibrium (its equilibria are not unique there) whose every cell has J > 0 and the law holds", full=True)
def finite_strain_svk_limit():
    for extra in ([], ["-snes_rtol", "1e-13"]):
        h5 = "finite_strain_svk_limit%s.h5" % ("_tight" if extra else "")
        out, f = contact(compressed("saint_venant_kirchhoff", (0.1, 0.3, 0.5)) + extra, h5)
        closed_form(f, "saint_venant_kirchhoff", (0.1, 0.3), "Saint Venant-Kirchhoff %s" % (" ".join(extra) or "at the defaults"), out, tol=1e-6)
        expect(f["steps/3/fields/J"][:].min() > 0, "an inverted cell at 50 %", out)
        law(h5)


@test("a hyperelastic tangent is not declared positive definite: the Saint Venant-Kirchhoff cube on the frictionless plane compressed 40 % in one step (the tangent indefinite at the first iterates, the limit point at 42 %) converges at the defaults on the whole body with no failed multigrid, the contact's normal force balancing the top's reaction to 1e-8 (in one step it may find an equilibrium other than uniaxial stress: Saint Venant-Kirchhoff's compressed equilibria are not unique) (since 7d91dc6 every Jacobian of a scene with a body held by contact and prescribed displacements was declared MAT_SPD: GAMG then estimated its smoother's eigenvalues by CG, which stopped with DIVERGED_INDEFINITE_MAT and failed the multigrid, DIVERGED_PC_FAILED, and the step ended DIVERGED_LINEAR_SOLVE); the law holds")
def finite_strain_svk_indefinite_tangent():
    h5 = "finite_strain_svk_indefinite_tangent.h5"
    out, f = contact(compressed("saint_venant_kirchhoff", (0.4,)) + ["-ksp_converged_reason"], h5)
    expect("DIVERGED_PC_FAILED" not in out, "the multigrid failed", out)
    top, normal = f["steps/groups/top/reaction"][1][2], f["steps/1/contact/reaction"][:, 2].sum()
    expect(abs(top + normal) <= 1e-8 * abs(top), "the top's reaction %g and the contact's normal force %g do not balance" % (top, normal), out)
    law(h5)


@test("a pair of neo-Hookean bodies under a large dead pressure: scenes/patch.opts (the lid E = 1, nu = 0 on the base, node-to-surface, phi = 0.3) with -material_model neo_hookean and the pressure 0.5 E on the lid's top converges at the defaults (0.2 E and more stopped with DIVERGED_LINEAR_SOLVE: CG on an indefinite tangent); the contact's normal force balances the load less the spring's share to 1 % and the law holds", full=True)
def finite_strain_pair():
    h5 = "finite_strain_pair.h5"
    out, f = contact(["-options_file", os.path.join(ROOT, "scenes", "patch.opts"), "-material_model", "neo_hookean", "-traction_top", "0,0,-0.5"], h5)
    normal = f["contact/reaction"][:, 2].sum()
    expect(abs(abs(normal) - 0.5) <= 0.01 * 0.5, "the normal force %g is not the load 0.5 to 1 %%" % normal, out)
    law(h5)


@test("hyperelastic bodies on 3 and 4 ranks agree with one rank: the neo-Hookean cube pressed 20 % onto the plane with phi = 0.3 and dragged sideways by 0.2 and 0.5 (the contact measured at the iterates, incremental friction) gives every step's displacement and contact of the one-rank run to 2e-6 (check_solution.py compare --steps) and the law; a rotation of 90 degrees prescribed on the top of the cube standing on the frictionless plane (Saint Venant-Kirchhoff) leaves every cell unstressed to 1e-6 E on 3 and 4 ranks", full=True)
def finite_strain_ranks_full():
    drag = CUBE + ["-level", "1", "-material_model", "neo_hookean", "-contact", "bottom", "-friction_bottom", "0.3", "-displacement_top", "0:0,0,0;1:0,0,-0.2;2:0.2,0,-0.2;3:0.5,0,-0.2"]
    contact(drag, "finite_strain_drag_1.h5")
    rotated = CUBE + ["-level", "1", "-material_model", "saint_venant_kirchhoff", "-contact", "bottom", "-friction_law_bottom", "none", "-rotation_center_top", "0.5,0.5,1",
                      "-rotation_top", "0:0,0,0;1:0,0,30;2:0,0,60;3:0,0,90"]
    for ranks in (3, 4):
        h5 = "finite_strain_drag_%d.h5" % ranks
        contact(drag, h5, ranks)
        law(h5)
        run(CHECK + ["compare", os.path.join(OUT, "finite_strain_drag_1.h5"), os.path.join(OUT, h5), "--steps", "--tol", str(AGREE)])
        h5 = "finite_strain_rotated_%d.h5" % ranks
        out, f = contact(rotated, h5, ranks)
        stress = max(np.abs(f["steps/%s/fields/stress" % k][:]).max() for k in f["steps"] if k.isdigit())
        expect(stress <= 1e-6 * 1000, "%d ranks: the rotated body is stressed (%g)" % (ranks, stress), out)
        law(h5)
