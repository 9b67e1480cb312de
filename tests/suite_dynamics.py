"""Elastodynamics with contact and Coulomb friction (issue 32, docs/derivation.md section 16): -dynamics, each time step
the solver ssstar's affine problem (16.6) with incremental friction, the stabilized scheme's energy balance, against
the known answers -- a rod on a rigid wall, a block sliding down a slope or staying, a block on a moving belt, a ball
dropped on a plane against Hertz's impact, the quasi-static limit -- on both paths and 1 and 2 ranks, from C and
Python; the file's velocity and energy columns; the refusals."""
import os
import re

import h5py
import numpy as np

from harness import *  # noqa: F401,F403 (run, expect, mpiexec, test, paths)

CONTACT = os.path.join(ROOT, "examples", "contact")
LAW = CHECK + ["law", "--steps"]
# both paths, 1 and 2 ranks: make test runs a known answer on the dense route on 1 rank and the whole body on 2; make test-full the other two
QUICK, OTHERS = [("direct", 1), ("none", 2)], [("none", 1), ("direct", 2)]
# a rod 0.1 x 0.1 x 1 (meshes/rod.geo, 40 elements along it) at rest on the wall z = 0 moving at -v0 = -0.01:
# E = rho = 1 (c = 1), nu = 0 (1D waves), one element per step (tau = 0.025), to t = 3
ROD = ["-geo", "meshes/rod.geo", "-level", "2", "-E", "1", "-nu", "0", "-density", "1", "-dynamics", "-initial_velocity", "0,0,-0.01",
       "-contact", "tip", "-friction_law_tip", "none", "-end_time", "3", "-steps", "120", "-ssstar_progress", "0"]
# a block 2 x 1 x 0.5 (E = 10 MPa, 1000 kg/m^3) released on a slope of 20 degrees (scenes/slope.opts at level 2),
# Rayleigh damping of its stiffness (its compression under its own weight rings otherwise), 100 steps of 0.01 s
SLOPE = ["-geo", "meshes/incline.geo", "-level", "2", "-E", "1e7", "-nu", "0.3", "-density", "1000", "-gravity", "0,0,-9.81",
         "-contact", "bottom", "-obstacle_bottom", "0,0,0,0.3420201433256687,0,0.9396926207859084", "-dynamics", "-damping", "0,0.003",
         "-end_time", "1", "-steps", "100", "-ssstar_progress", "0"]
# scenes/belt.opts: the block of suite_loadpath (E = 2e8, k = 1000 on its top, pressed by P = 10 over 0.1 s, phi = 0.5)
# on a belt, the plane z = 0 moving at V = 0.01 along x; m = 0.5 (rho = 1), omega = sqrt(k/m) = 44.7; 100 steps of 0.02 s
BELT = ["-options_file", "scenes/belt.opts", "-ssstar_progress", "0"]
# the half ball of scenes/hertz.opts (R = 10, level 1) at rest on the plane with the velocity -v0 = -0.3, E = 1e4,
# nu = 0.3, rho = 1, frictionless; 24 steps of 0.075 to t = 1.8 (Hertz's contact time 1.19)
BALL = ["-geo", "meshes/hertz.geo", "-level", "1", "-E", "1e4", "-nu", "0.3", "-density", "1", "-dynamics", "-initial_velocity", "0,0,-0.3",
        "-contact", "cap", "-friction_law_cap", "none", "-end_time", "1.8", "-steps", "24", "-ssstar_progress", "0"]


def dynamics_run(args, name, red="direct", ranks=1, expect_rc=0):
    path = os.path.join(OUT, name)
    out = run(mpiexec(ranks, CONTACT, *args, "-snes_ssstar_reduction", red, "-o", path, "-malloc_dump"), expect_rc=expect_rc)
    return out, path


def balance(f, where):
    """The file's energy columns: energy_error + impact_dissipation = 0 to round-off (16.8), nothing gained"""
    st = f["steps"]
    scale = max(np.abs(st["kinetic_energy"][:]).max(), np.abs(st["external_work"][:]).max(), 1e-300)
    identity = np.abs(st["energy_error"][:] + st["impact_dissipation"][:]).max() / scale
    expect(identity <= 1e-9, "%s: energy_error + impact_dissipation = %.1e of the energy, not 0" % (where, identity))
    return st["energy_error"][:] / scale


def lumped_weights(f):
    """Each mesh node's share of the mass for a uniform structured rod: the momentum velocity of /fields/velocity"""
    z = f["geometry/vertices"][:, 2]
    return np.where((np.abs(z) < 1e-9) | (np.abs(z - 1) < 1e-9), 0.5, 1.0)


@test("docs/derivation.md section 16 holds (tests/dynamics_check.py, numpy, independent of the C code): the placement (16.1) and the rolling cylinder's no-slip to first order (16.3); the energy identity (16.8) of the scheme (16.5)-(16.7) to 1e-10 on a random body with three Coulomb contact points, damping and a load, never gaining energy at contact; the rod on a wall (contact 2L/c, force E A v0/c, leaving at -v0, energy never above the initial) where plain Newmark gains energy at the release and the scheme without the projection chatters; a rigid block on a slope sliding with g(sin a - phi cos a) or staying")
def dynamics_derivation():
    page = open(os.path.join(ROOT, "docs", "derivation.md")).read()
    for equation in ("(16.1)", "(16.2)", "(16.3)", "(16.4)", "(16.5)", "(16.6)", "(16.7)", "(16.8)"):
        expect(equation in page, "docs/derivation.md has no equation %s" % equation)
    out = run([PYTHON, os.path.join(ROOT, "tests", "dynamics_check.py")])
    expect(out.count("PASS") == 4 and "FAIL" not in out, "tests/dynamics_check.py", out)


def rod(paths):
    fields = []
    for red, ranks in paths:
        out, path = dynamics_run(ROD, "dynamics_rod_%s_%d.h5" % (red, ranks), red, ranks)
        f = h5py.File(path, "r")
        st = f["steps"]
        t, N = st["time"][:], st["normal_force"][:]
        where = "%s %d" % (red, ranks)
        expect(abs(t[N > 1e-12][-1] - 2.025) < 1e-9, "%s: the contact ends at %g, not 2 L/c" % (where, t[N > 1e-12][-1]))
        plateau = N[(t > 0.5) & (t < 1.5)] / 1e-4
        expect(abs(plateau.mean() - 1) < 1e-3 and np.abs(plateau - 1).max() < 0.01, "%s: the force plateau %.6f E A v0/c, off by %.2e at most" % (where, plateau.mean(), np.abs(plateau - 1).max()))
        v = f["steps/%d/fields/velocity" % (len(t) - 1)][:]
        w = lumped_weights(f)
        leaving = (w * v[:, 2]).sum() / w.sum() / 0.01
        expect(v.shape == f["steps/0/fields/displacement"].shape and 0.97 <= leaving <= 1.0, "%s: the rod leaves at %.4f v0" % (where, leaving))
        E0 = 0.5 * 0.01 * 0.01 ** 2  # m v0^2 / 2, m = rho A L
        energy = st["kinetic_energy"][:] + st["strain_energy"][:]
        expect(energy.max() <= E0 * (1 + 1e-9) and st["impact_dissipation"][-1] < 0.01 * E0, "%s: the energy reaches %.8f E0, the impact dissipation %.2e E0" % (where, energy.max() / E0, st["impact_dissipation"][-1] / E0))
        error = balance(f, where)
        expect(error.max() <= 1e-9, "%s: the scheme gained energy: energy_error %.1e" % (where, error.max()))
        run(LAW + [path])
        fields.append(np.concatenate([f["steps/%d/fields/displacement" % k][:].ravel() for k in range(len(t))]))
    for other in fields[1:]:
        diff = np.abs(other - fields[0]).max() / np.abs(fields[0]).max()
        expect(diff <= AGREE, "the paths and rank counts differ by %.1e in the displacements" % diff)


@test("a rod on a rigid wall (meshes/rod.geo: nu = 0, E = rho = 1, L = 1, 40 elements, one per step, v0 = 0.01): the contact lasts 2 L/c (its last touching step at t = 2.025), the wall's force is the plateau E A v0 / c = 1e-4 within 0.1 % on the mean and 1 % at every step of 0.5 < t < 1.5 (measured 4e-6 and 0.2 %), the rod leaves at 0.97-1.0 v0 (momentum; measured 0.974: the rest rings), the energy never rises above the initial, the scheme's impact dissipation is below 1 % of it (measured 0.67 %: the tip's approach) and energy_error + impact_dissipation = 0 to 1e-9; the file's /steps/<k>/fields/velocity are n x 3 and its law holds at every step; both paths on 1 rank (make test-full: on 2; the other known answers run the whole body on 2 ranks in make test) give the same displacements to 2e-6")
def dynamics_rod():
    rod([("direct", 1), ("none", 1)])


@test("the rod on a wall of dynamics_rod on 2 ranks, both paths: the same known answers, the same displacements to 2e-6", full=True)
def dynamics_rod_two_ranks():
    rod([("direct", 2), ("none", 2)])


@test("the rod without the projection (-dynamics_scheme newmark): its contact force chatters about the plateau (off by more than 30 % at some step of 0.5 < t < 1.5; measured 54 %) where the stabilized scheme's stays within 1 %; it gains no energy either (energy_error <= 0); a time step longer than the contact (-steps 3 to t = 6) is said: 'does not resolve the impact'")
def dynamics_rod_schemes():
    _, path = dynamics_run(ROD + ["-dynamics_scheme", "newmark"], "dynamics_rod_newmark.h5")
    f = h5py.File(path, "r")
    t, N = f["steps/time"][:], f["steps/normal_force"][:]
    chatter = np.abs(N[(t > 0.5) & (t < 1.5)] / 1e-4 - 1).max()
    expect(chatter > 0.3, "newmark: the force stays within %.2f of the plateau" % chatter)
    expect(balance(f, "newmark").max() <= 1e-9, "newmark gained energy")
    out, _ = dynamics_run(ROD[:-4] + ["-end_time", "6", "-steps", "3"], "dynamics_rod_coarse.h5")
    expect("does not resolve the impact" in out, "a contact of one step is not said", out)


def slope(paths, stays):
    a, g = np.radians(20), 9.81
    down = np.array([np.cos(a), 0, -np.sin(a)])
    travels = []
    for red, ranks in paths:
        _, path = dynamics_run(SLOPE + ["-friction_bottom", "0.3"], "dynamics_slope_%s_%d.h5" % (red, ranks), red, ranks)
        f = h5py.File(path, "r")
        st = f["steps"]
        t = st["time"][:]
        s = st["groups/bottom/displacement"][:] @ down
        fit = 2 * np.polyfit(t[t >= 0.3], s[t >= 0.3], 2)[0]
        exact = g * (np.sin(a) - 0.3 * np.cos(a))
        where = "%s %d" % (red, ranks)
        expect(abs(fit / exact - 1) < 1e-4, "%s: the block slides with %.6f, not g(sin a - phi cos a) = %.6f" % (where, fit, exact))
        late = t > 0.1
        expect(np.all(st["sticking"][:][late] == 0), "%s: nodes stick while the block slides" % where)
        ratio = np.linalg.norm(st["tangential_force"][:], axis=1)[late] / st["normal_force"][:][late]
        expect(np.abs(ratio - 0.3).max() < 1e-6, "%s: T/N = %s" % (where, ratio))
        error = balance(f, where)
        expect(np.abs(error).max() < 1e-6, "%s: the energy balance is off by %.1e of the work of gravity" % (where, np.abs(error).max()))
        run(LAW + [path])
        travels.append(s)
    diff = max(np.abs(x - travels[0]).max() for x in travels) / np.abs(travels[0]).max()
    expect(diff <= AGREE, "the paths differ by %.1e in the travel" % diff)
    for red, ranks in stays:
        _, path = dynamics_run(SLOPE + ["-friction_bottom", "0.5"], "dynamics_slope_stays_%s_%d.h5" % (red, ranks), red, ranks)
        st = h5py.File(path, "r")["steps"]
        s = st["groups/bottom/displacement"][:] @ down
        ratio = np.linalg.norm(st["tangential_force"][:], axis=1) / st["normal_force"][:]
        expect(np.abs(s).max() < 1e-4 and ratio[5:].max() < 0.5, "%s %d: the block on phi = 0.5 moves by %.2e, T/N up to %.3f" % (red, ranks, np.abs(s).max(), ratio[5:].max()))


@test("the rod on a wall with the lumped mass (-dynamics_mass lumped): the contact lasts 2 L/c, the force plateau E A v0/c within 1 %, the energy never above the initial, and the scheme's impact dissipation is the tip layer's kinetic energy: its lumped mass is 1/80 of the rod's (half an element of 40), so 1/80 of E0 within 1e-3 of it (measured 0.01250); the density and initial velocity of a volume group (-material_rod 1,0,1 -initial_velocity_rod 0,0,-0.01, no -density, no -initial_velocity) give the rod of -density 1 -initial_velocity 0,0,-0.01 to 2e-6")
def dynamics_rod_options():
    E0 = 0.5 * 0.01 * 0.01 ** 2
    _, path = dynamics_run(ROD + ["-dynamics_mass", "lumped"], "dynamics_rod_lumped.h5")
    st = h5py.File(path, "r")["steps"]
    t, N = st["time"][:], st["normal_force"][:]
    plateau = N[(t > 0.5) & (t < 1.5)] / 1e-4
    energy = st["kinetic_energy"][:] + st["strain_energy"][:]
    expect(abs(t[N > 1e-12][-1] - 2.025) < 1e-9 and np.abs(plateau - 1).max() < 0.01, "lumped: contact until %g, plateau off by %.2e" % (t[N > 1e-12][-1], np.abs(plateau - 1).max()))
    expect(energy.max() <= E0 * (1 + 1e-9) and abs(st["impact_dissipation"][-1] / E0 * 80 - 1) < 1e-3, "lumped: energy up to %.6f E0, impact dissipation %.6f E0, not 1/80" % (energy.max() / E0, st["impact_dissipation"][-1] / E0))
    expect(balance(h5py.File(path, "r"), "lumped").max() <= 1e-9, "lumped: energy gained")
    run(LAW + [path])
    drop = {"-density", "1", "-initial_velocity", "0,0,-0.01"}
    group = [a for i, a in enumerate(ROD) if not (a in ("-density", "-initial_velocity") or (i > 0 and ROD[i - 1] in ("-density", "-initial_velocity")))]
    expect(len(group) == len(ROD) - len(drop), "the rod's options without -density and -initial_velocity")
    _, by_group = dynamics_run(group + ["-material_rod", "1,0,1", "-initial_velocity_rod", "0,0,-0.01"], "dynamics_rod_group.h5")
    _, ref = dynamics_run(ROD, "dynamics_rod_reference.h5")
    a, b = h5py.File(by_group, "r"), h5py.File(ref, "r")
    diff = max(np.abs(a["steps/%d/fields/displacement" % k][:] - b["steps/%d/fields/displacement" % k][:]).max() for k in range(len(t)))
    expect(diff <= AGREE * np.abs(b["steps/%d/fields/displacement" % (len(t) - 1)][:]).max(), "per-group density and velocity differ by %.1e" % diff)


@test("a block released on a slope of 20 degrees (E = 10 MPa, 1000 kg/m^3, Rayleigh damping 0.003 K): with phi = 0.3 < tan 20 it slides with the acceleration g (sin a - phi cos a) = 0.5897 (a parabola fitted to its bottom's travel for t >= 0.3: within 1e-4; measured 1e-8), every touching node slides, the tangential force is phi N to 1e-6, and kinetic + strain + friction + damping = the work of gravity to 1e-6 of it (energy_error; measured 6e-13); with phi = 0.5 > tan 20 it stays: its travel below 1e-4 (the elastic shear of its settling) and the friction below phi N; the dense route on 1 rank (make test-full: the whole body on 1 and 2 ranks, the dense route on 2, the travels agreeing to 2e-6)")
def dynamics_slope():
    slope([("direct", 1)], [("direct", 1)])


@test("the block on the slope of dynamics_slope on the other paths and rank counts (the whole body on 1 and 2 ranks, the dense route on 2; the block that stays: the whole body on 2 ranks): the same known answers, the travels agreeing to 2e-6", full=True)
def dynamics_slope_other_paths():
    slope(OTHERS + [("none", 2)], [("none", 2)])


def belt(paths, damped):
    springs = []
    for red, ranks in paths:
        _, path = dynamics_run(BELT, "dynamics_belt_%s_%d.h5" % (red, ranks), red, ranks)
        f = h5py.File(path, "r")
        st = f["steps"]
        t = st["time"][:]
        spring = 1000 * st["groups/top/displacement"][:, 0]
        where = "%s %d" % (red, ranks)
        late = t > 0.6
        ratio = np.abs(st["tangential_force"][:, 0]) / st["normal_force"][:]
        expect(np.abs(ratio[late] - 0.5).max() < 1e-4 and np.all(st["sticking"][:][late] == 0), "%s: T/N off phi by %.1e, sticking %s" % (where, np.abs(ratio[late] - 0.5).max(), st["sticking"][:][late].max()))
        last = t > 1.0
        expect(abs(spring[last].mean() / 5 - 1) < 0.01 and np.abs(spring[last] - 5).max() <= 1000 * 0.01 / np.sqrt(1000 / 0.5), "%s: the spring force %.4f +- %.4f about phi N = 5" % (where, spring[last].mean(), np.abs(spring[last] - 5).max()))
        error = balance(f, where)
        expect(np.abs(error).max() < 1e-5, "%s: the energy balance is off by %.1e of the belt's work" % (where, np.abs(error).max()))
        run(LAW + [path])
        springs.append(spring)
    if springs:
        diff = max(np.abs(x - springs[0]).max() for x in springs) / np.abs(springs[0]).max()
        expect(diff <= AGREE, "the paths differ by %.1e in the spring force" % diff)
    if not damped:
        return
    _, path = dynamics_run(BELT + ["-damping", "20,1e-3"], "dynamics_belt_damped.h5")  # the last option counts
    st = h5py.File(path, "r")["steps"]
    spring = 1000 * st["groups/top/displacement"][:, 0]
    expect(abs(spring[-1] / 5 - 1) < 1e-3, "mass-damped: the spring force %.6f, not phi N = 5" % spring[-1])


@test("a block on a spring dragged by a moving belt (scenes/belt.opts: the plane z = 0 at V = 0.01 along x, P = 10, phi = 0.5, k = 1000, m = 0.5): it rides the belt until the spring holds phi N = 5, then slides for good: T = phi N to 1e-4 at every step after t = 0.6, no node sticks; undamped (Rayleigh 1e-3 K against the block's own ringing) the spring force oscillates about phi N (its mean over the last second within 1 %; measured 0.08 %) with the amplitude k V / omega = 0.22 at most (measured 0.14; pure Coulomb friction, phi_s = phi_k: no stick-slip, the relative velocity only touches zero) (make test-full: with mass damping, 20 M, it settles to the steady sliding state, the spring force phi N within 1e-3); the belt's work is friction + damping + kinetic + spring energy (energy_error within 1e-5 of the work); the dense route on 1 rank and the whole body on 2 agree to 2e-6", full=True)
def dynamics_belt():
    belt(QUICK, False)


@test("the belt of dynamics_belt with mass damping (-damping 20,1e-3): it settles to the steady sliding state, the spring force phi N within 1e-3", full=True)
def dynamics_belt_damped():
    belt([], True)


def ball(paths):
    E, nu, rho, R, v0 = 1e4, 0.3, 1.0, 10.0, 0.3
    Es = E / (1 - nu ** 2)
    forces = []
    for red, ranks in paths:
        _, path = dynamics_run(BALL, "dynamics_ball_%s_%d.h5" % (red, ranks), red, ranks)
        f = h5py.File(path, "r")
        st = f["steps"]
        t, N = st["time"][:], st["normal_force"][:]
        # the initial energy from the balance of the first step, and the discrete mass from it (the polyhedral ball)
        E0 = st["kinetic_energy"][0] + st["strain_energy"][0] + st["dissipation"][0] + st["damping_dissipation"][0] - st["external_work"][0] - st["energy_error"][0]
        m = 2 * E0 / v0 ** 2
        tc = 2.87 * (m ** 2 / (R * Es ** 2 * v0)) ** 0.2
        Fmax = 4 / 3 * Es * R ** 0.5 * (15 * m * v0 ** 2 / (16 * Es * R ** 0.5)) ** 0.6
        on = np.where(N > 1e-9 * N.max())[0]
        ends = t[on[-1]] + (t[1] - t[0]) / 2
        where = "%s %d" % (red, ranks)
        expect(abs(ends / tc - 1) < 0.1 and abs(N.max() / Fmax - 1) < 0.1, "%s: contact time %.4f against Hertz's %.4f, peak force %.1f against %.1f" % (where, ends, tc, N.max(), Fmax))
        rebound = (N * np.diff(np.r_[0, t])).sum() / m - v0
        expect(0.95 <= rebound / v0 <= 1.0, "%s: rebound %.4f v0" % (where, rebound / v0))
        expect(balance(f, where).max() <= 1e-9, "%s: the drop gained energy" % where)
        run(LAW + [path])
        forces.append(N)
    for other in forces[1:]:
        diff = np.abs(other - forces[0]).max() / np.abs(forces[0]).max()
        expect(diff <= AGREE, "the paths differ by %.1e in the force" % diff)


@test("a ball dropped on a plane (the half ball of scenes/hertz.opts, R = 10, E = 1e4, nu = 0.3, rho = 1, v0 = 0.3, frictionless, 24 steps): the contact lasts Hertz's impact time t_c = 2.87 (m^2 / (R E*^2 v0))^(1/5) = 1.18 within 10 % (measured -1.6 %), the peak force Hertz's (4/3) E* R^(1/2) delta^(3/2) within 10 % (measured +7 %: the half ball is not rigid, its cap meshed 5 elements across the contact), it rebounds at 0.95-1.0 v0 (the impulse of the plane over m v0; measured 0.992), and what it lost is the scheme's stated impact dissipation (energy_error + impact_dissipation = 0 to 1e-9, energy never gained); the dense route on 1 rank (make test-full: the whole body on 1 and 2 ranks and the dense route on 2, agreeing to 2e-6)", full=True)
def dynamics_ball():
    ball([("direct", 1)])


@test("the ball dropped on a plane of dynamics_ball on the other paths and rank counts (the whole body on 1 and 2 ranks, the dense route on 2): the same known answers, the forces agreeing to 2e-6", full=True)
def dynamics_ball_other_paths():
    ball(OTHERS + [("none", 2)])


@test("the quasi-static limit: the block on a spring pressed (P = 10), sheared beyond phi P (Q = 7.5) and released over 3 T with -dynamics (rho = 1, damping 20 M + 1e-3 K, 300 steps) follows the load path without -dynamics to the inertia's order: the largest difference of its top's u_x is below 10 % of the path's largest u_x at T = 1 and falls with T (T = 4: by more than 2.5 times; measured 7.6 % and 2.2 %), at the end within 2 % (T = 1) and 0.1 % (T = 4) of (Q - phi P)/k", full=True)
def dynamics_quasistatic():
    diffs = []
    for T in (1, 4):
        hist = "0:0,0,0;%d:0,0,-10;%d:7.5,0,-10;%d:0,0,-10" % (T, 2 * T, 3 * T)
        args = ["-geo", "meshes/block.geo", "-level", "1", "-E", "2e8", "-nu", "0.3", "-spring_top", "1000", "-contact", "bottom",
                "-friction_bottom", "0.5", "-traction_top", hist, "-steps", "300", "-ssstar_progress", "0"]
        _, dyn = dynamics_run(args + ["-density", "1", "-dynamics", "-damping", "20,1e-3"], "dynamics_qs_%d.h5" % T)
        _, qs = dynamics_run(args, "dynamics_qs_path_%d.h5" % T)
        a, b = h5py.File(dyn, "r")["steps"], h5py.File(qs, "r")["steps"]
        ta, tb = a["time"][:], b["time"][:]
        ua, ub = a["groups/top/displacement"][:, 0], b["groups/top/displacement"][:, 0]
        d = ua[np.isin(ta, tb)] - ub[np.isin(tb, ta)]
        diffs.append(np.abs(d).max() / np.abs(ub).max())
        expect(abs(ua[-1] / 2.5e-3 - 1) < (0.02 if T == 1 else 1e-3), "T = %d: u_x ends at %.6e, not (Q - phi P)/k = 2.5e-3" % (T, ua[-1]))
    expect(diffs[0] < 0.1 and diffs[0] > 2.5 * diffs[1], "the dynamic path is off the quasi-static one by %.3f (T = 1) and %.3f (T = 4)" % tuple(diffs))


def floating(paths, slope):
    for red, ranks in paths:
        out, path = dynamics_run(["-options_file", os.path.join(ROOT, "scenes", "stack.opts"), "-level", "1", "-dynamics", "-damping", "0,1e-3",
                                  "-end_time", "0.2", "-steps", "20", "-ssstar_progress", "0"], "dynamics_stack_%s_%d.h5" % (red, ranks), red, ranks)
        f = h5py.File(path, "r")
        expect(np.all(f["steps/reason"][:] > 0) and "no equilibrium" not in out, "%s %d: a step of the stack did not converge" % (red, ranks), out)
        expect(balance(f, "stack %s %d" % (red, ranks)).max() <= 1e-9, "%s %d: the stack gained energy" % (red, ranks))
        run(LAW + [path])
    if not slope:
        return
    out, _ = dynamics_run(["-options_file", os.path.join(ROOT, "scenes", "slope.opts"), "-level", "2", "-friction_bottom", "0.3", "-dynamics", "-damping", "0,0.003",
                           "-end_time", "0.2", "-steps", "20", "-ssstar_progress", "0"], "dynamics_slope_floating.h5")
    expect("no equilibrium" not in out and "sliding" in out, "the released block does not slide", out)


@test("bodies held by contact alone in dynamics (scenes/stack.opts: two blocks, the lower on the plane, the upper on it through a contact pair, no spring, no Dirichlet condition) run without the kernel's refusal -- the mass holds their rigid motions -- on the dense route on 1 rank and the whole body on 2 (make test-full: the other two): every step converges, the energy balance holds (energy_error + impact_dissipation = 0), nothing is gained, the law holds at every step; a single block on the slope with phi = 0.3, whose static problem has no equilibrium, slides instead of stopping")
def dynamics_floating():
    floating(QUICK, True)


@test("the stack of dynamics_floating on the other paths and rank counts (the whole body on 1 rank, the dense route on 2): every step converges, the energy balance holds, nothing is gained, the law holds", full=True)
def dynamics_floating_other_paths():
    floating(OTHERS, False)


@test("Python: ssstar.Scene(dynamics=True, ...) with steps() as for load paths gives examples/contact's file (the rod: the same rows and fields to 2e-6), each Step's velocity (n x 3) and energy columns those of the file; refused at construction: dynamics without steps, steps before t = 0; step() refuses a time not after the last accepted step's")
def dynamics_python():
    ref = os.path.join(OUT, "dynamics_rod_direct_1.h5")
    if not os.path.exists(ref):
        dynamics_run(ROD, "dynamics_rod_direct_1.h5")
    script = os.path.join(OUT, "dynamics_python.py")
    open(script, "w").write('''import sys
sys.path.insert(0, %r)
import h5py, numpy as np
import ssstar
opts = dict(geo="meshes/rod.geo", level=2, E=1, nu=0, density=1, dynamics=True, initial_velocity=(0, 0, -0.01), contact=["tip"],
            friction_law={"tip": "none"}, end_time=3, steps=120, snes_ssstar_reduction="direct")
with ssstar.Scene(o=sys.argv[1], **opts) as scene:
    steps = list(scene.steps())
f = h5py.File(sys.argv[1], "r")
assert all(np.array_equal(s.velocity, f["steps/%%d/fields/velocity" %% k][:]) for k, s in enumerate(steps))
assert all(s.row["kinetic_energy"] == f["steps/kinetic_energy"][k] and s.row["energy_error"] == f["steps/energy_error"][k] for k, s in enumerate(steps))
print("steps", len(steps))
for bad, words in ((dict(opts, steps=None), "needs -steps"), (dict(opts, steps="-1,1"), "before t = 0")):
    try:
        ssstar.Scene(**{k: v for k, v in bad.items() if v is not None})
        print("not refused:", words)
    except ssstar.Error as e:
        print("refused:", words in str(e), e)
with ssstar.Scene(**opts) as scene:
    scene.step(0.1)
    try:
        scene.step(0.1)
        print("not refused: the same time")
    except ssstar.Error as e:
        print("refused:", "is not after" in str(e), e)
''' % os.path.join(ROOT, "python"))
    path = os.path.join(OUT, "dynamics_python.h5")
    out = run([PYTHON, script, path])
    expect("steps 120" in out and "not refused" not in out and "refused: False" not in out, "the Python dynamics", out)
    out = run(CHECK + ["compare", path, ref, "--steps", "--tol", str(AGREE)])
    expect("DIFFERENT" not in out.split("full field")[1].split("\n")[0], "Python's rod differs from examples/contact's", out)


@test("refusals of -dynamics and its options, each one line naming the option, before any work: -initial_velocity, -damping, -dynamics_scheme, -dynamics_mass, -initial_velocity_<G> without -dynamics; -dynamics without -steps; a time before t = 0; -dynamics with -load_steps; a negative damping; an unknown scheme; cells without density (-dynamics without -density); -density alone without -gravity or -dynamics; -material_<G> with a density <= 0; -dynamics with a prescribed displacement -displacement_<G> or a hyperelastic body -material_model (not supported)")
def dynamics_refusals():
    base = ROD[:ROD.index("-dynamics")] + ["-contact", "tip", "-friction_law_tip", "none"]
    cases = [
        (["-initial_velocity", "0,0,1", "-steps", "3", "-end_time", "1"], "-initial_velocity needs -dynamics"),
        (["-damping", "1,0", "-steps", "3", "-end_time", "1"], "-damping needs -dynamics"),
        (["-dynamics_scheme", "newmark", "-steps", "3", "-end_time", "1"], "-dynamics_scheme needs -dynamics"),
        (["-dynamics_mass", "lumped", "-steps", "3", "-end_time", "1"], "-dynamics_mass needs -dynamics"),
        (["-initial_velocity_rod", "0,0,1", "-steps", "3", "-end_time", "1"], "-initial_velocity_rod needs -dynamics"),
        (["-dynamics"], "needs -steps"),
        (["-dynamics", "-steps", "-1,1"], "before t = 0"),
        (["-dynamics", "-load_steps", "3"], "-load_steps"),
        (["-dynamics", "-steps", "3", "-end_time", "1", "-damping", "-1,0"], "-damping"),
        (["-dynamics", "-steps", "3", "-end_time", "1", "-dynamics_scheme", "leapfrog"], "-dynamics_scheme"),
        (["-dynamics", "-steps", "3", "-end_time", "1", "-displacement_top", "0,0,-0.01"], "-dynamics and -displacement_top"),
        (["-dynamics", "-steps", "3", "-end_time", "1", "-material_model", "neo_hookean"], "-dynamics and -material_model"),
    ]
    for extra, words in cases:
        out = run([CONTACT] + base + extra, expect_rc=1)
        expect(words in out, "%s: not refused with '%s'" % (" ".join(extra), words), out)
    nodensity = [a for i, a in enumerate(base) if not (a == "-density" or (i > 0 and base[i - 1] == "-density"))]
    out = run([CONTACT] + nodensity + ["-dynamics", "-steps", "3", "-end_time", "1"], expect_rc=1)
    expect("no positive density" in out, "-dynamics without a density", out)
    out = run([CONTACT] + base + ["-steps", "3", "-end_time", "1"], expect_rc=1)
    expect("-density needs -gravity (or -dynamics)" in out, "-density alone", out)
    out = run([CONTACT] + nodensity + ["-dynamics", "-steps", "3", "-end_time", "1", "-material_rod", "1,0,0"], expect_rc=1)
    expect("-material_rod" in out and "density" in out, "-material_<G> with a density 0", out)
