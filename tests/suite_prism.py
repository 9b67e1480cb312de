"""The seed's prism through examples/prism: reference iterations and states, the law, ranks, Schur paths, errors."""
import os
import re

from harness import *  # noqa: F401,F403 (run, expect, mpiexec, test, paths)

CONTACT = os.path.join(ROOT, "examples", "contact")


def prism_level_run(level, extra, slack):
    out, s = prism(level, extra=["-snes_view"] + extra)
    expect(s["reason"] == "CONVERGED_FNORM_RELATIVE", "level %d: %s" % (level, s["reason"]), out)
    expect(re.search(r"remedies: damped steps 0, full steps after a failed line search 0, rescalings of gamma 0, regularized Newton steps 0, fixed-point rounds 0; cycles detected 0", out),
           "level %d: the globalization intervened in a healthy iteration" % level, out)
    expect(last_znorm(out) <= 1e-12, "level %d: final |z| %g > 1e-12" % (level, last_znorm(out)), out)
    ref = REFERENCE_ITERATIONS[level]
    expect(abs(s["iters"] - ref) <= slack, "level %d: %d iterations, reference %d" % (level, s["iters"], ref), out)
    expect(s["contact"] == 4 * level * (2 * level + 1), "level %d: %d contact nodes" % (level, s["contact"]), out)
    expect(s["nodes"] == (4 * level + 1) * (2 * level + 1) ** 2, "level %d: %d nodes" % (level, s["nodes"]), out)
    if level in REFERENCE_STATES:
        expect(s["sep_sl_st"] == REFERENCE_STATES[level], "level %d: states %s, reference %s" % (level, s["sep_sl_st"], REFERENCE_STATES[level]), out)
    return out, s


def prism_level(level):
    """The default (auto): the dense route up to level 7 (auto's cost model, src/reduction/auto.c), the reference iterations +- 1;
    the whole body above, whose inexact steps may take up to two more (docs/guide/large-problems.md), and there the dense
    route named (-snes_ssstar_reduction direct) for the reference iterations +- 1; above 50 000 dofs auto starts from
    the coarser level's solution (nested iteration: fewer iterations), and from u = 0 with -nested_levels 0"""
    dofs = 3 * (4 * level + 1) * (2 * level + 1) ** 2
    dense, nested = dofs <= 20000, dofs > 50000
    out, s = prism_level_run(level, ["-nested_levels", "0"] if nested else [], 1 if dense else 2)
    route = r"set-up: K reduced to \d+ contact dofs by the direct Schur complement \(chosen by auto\)" if dense else r"set-up: the whole body, \d+ dofs, P never formed \(reduction none, chosen by auto\)"
    expect(re.search(route, out) is not None, "level %d: not the route of auto (%s)" % (level, "dense" if dense else "whole body"), out)
    if not dense:
        prism_level_run(level, ["-snes_ssstar_reduction", "direct"], 1)
    if nested:
        out, s = prism(level, extra=["-snes_view"])
        expect(s["reason"] == "CONVERGED_FNORM_RELATIVE" and re.search(r"^nested: 1 coarser mesh, the finest of \d+ nodes", out, re.M) is not None, "level %d: auto did not start from the coarser level" % level, out)
        expect(s["iters"] < REFERENCE_ITERATIONS[level], "level %d: %d iterations from the coarser level's solution, %d from zero" % (level, s["iters"], REFERENCE_ITERATIONS[level]), out)


for _L in sorted(REFERENCE_ITERATIONS):
    test("prism level %d converges from u = 0 (relative rule, rtol 1e-10) to |z| <= 1e-12 in %d +- 1 iterations on the dense route (+- 2 on the whole body, auto's choice from level 8) without any remedy of the globalization, with the reference node counts%s; above 50 000 dofs auto starts from the coarser level's solution and takes fewer"
         % (_L, REFERENCE_ITERATIONS[_L], " and states " + REFERENCE_STATES[_L] if _L in REFERENCE_STATES else ""), full=_L > 5)(
        (lambda L: (lambda: prism_level(L)))(_L))
    TESTS[-1] = ("prism_level_%d" % _L,) + TESTS[-1][1:]


@test("the prism solution (level 4) satisfies the Coulomb law at every contact node to 1e-7 relative, checked from the HDF5 file; the XDMF file matches it; plot_contact.py draws it")
def prism_coulomb_law():
    prism(4, h5="coulomb_L4.h5")
    out = run(CHECK + ["coulomb", os.path.join(OUT, "coulomb_L4.h5"), "--tol", "1e-7"])
    expect("VIOLATED" not in out, "law violated", out)
    png = os.path.join(OUT, "coulomb_L4.png")
    if os.path.exists(png):
        os.remove(png)
    run([PYTHON, os.path.join(ROOT, "examples", "plot_contact.py"), os.path.join(OUT, "coulomb_L4.h5")])
    expect(os.path.getsize(png) > 10000, "examples/plot_contact.py wrote no picture")


@test("a non-default friction (-snes_ssstar_friction 0.5) reaches the solver and the law holds with it")
def prism_friction_option():
    prism(3, extra=["-snes_ssstar_friction", "0.5"], h5="friction05_L3.h5")
    run(CHECK + ["coulomb", os.path.join(OUT, "friction05_L3.h5")])


@test("1 rank and 2 ranks give the same iterates (|z| to 1e-8 relative while above 1e-10) and the same solution (level 5, contact face and whole mesh) to 2e-6 relative (harness.AGREE)", full=True)
def prism_ranks_agree():
    out1, s1 = prism(5, 1, h5="ranks1_L5.h5")
    out2, s2 = prism(5, 2, h5="ranks2_L5.h5")
    z1 = [float(z) for z in re.findall(r"SNES Function norm ([0-9.eE+-]+)", out1)]
    z2 = [float(z) for z in re.findall(r"SNES Function norm ([0-9.eE+-]+)", out2)]
    expect(len(z1) == len(z2), "%d iterations on 1 rank, %d on 2" % (len(z1) - 1, len(z2) - 1), out1 + out2)
    for k, (a, b) in enumerate(zip(z1, z2)):
        expect(a < 1e-10 or abs(a - b) <= 1e-8 * a, "iterate %d: |z| %.12e on 1 rank, %.12e on 2" % (k, a, b), out1 + out2)
    run(CHECK + ["compare", os.path.join(OUT, "ranks1_L5.h5"), os.path.join(OUT, "ranks2_L5.h5"), "--tol", str(AGREE)])


@test("the two Schur paths (MUMPS's own, MatSchurComplement explicit) give the same solution, on the contact face and on the whole mesh (recovery), to 2e-6 (harness.AGREE), on 1 and 2 ranks", full=True)
def prism_schur_paths_agree():
    prism(4, 1, extra=["-snes_ssstar_reduction", "mumps"], h5="mumps_L4.h5")
    prism(4, 1, extra=["-snes_ssstar_reduction", "explicit"], h5="explicit_L4.h5")
    prism(4, 2, extra=["-snes_ssstar_reduction", "explicit"], h5="explicit2_L4.h5")
    run(CHECK + ["compare", os.path.join(OUT, "mumps_L4.h5"), os.path.join(OUT, "explicit_L4.h5"), "--tol", str(AGREE)])
    run(CHECK + ["compare", os.path.join(OUT, "mumps_L4.h5"), os.path.join(OUT, "explicit2_L4.h5"), "--tol", str(AGREE)])


@test("-snes_view prints the ssstar settings and -log_view shows the assembly, Schur, AS and NS events")
def prism_view_and_log():
    out, _ = prism(3, extra=["-snes_view", "-log_view", "-snes_ssstar_monitor_states"])
    for pattern in [r"type: ssstar", r"friction coefficient phi = 0.3", r"stopping rule \|\|z\|\| <= max\(atol, rtol max\(\|\|u\|\|, \|\|gamma f\|\|\)\), atol = 1e-50, rtol = 1e-10",
                    r"SSStarAssembly", r"SSStarSchur", r"SSStarAS", r"SSStarNS", r"SSStar states L 14 M1 55 M2 0 M3\+ 15 M3- 0 M4 0"]:
        expect(re.search(pattern, out) is not None, "missing in output: " + pattern, out)


@test("meshes/prism.geo gives the node counts of Table 2 for L = 3..16 and 4L(2L+1) contact nodes")
def mesh_node_counts():
    table2 = [637, 1377, 2541, 4225, 6525, 9537, 13357, 18081, 23805, 30625, 38637, 47937, 58621, 70785]
    for level, nodes in zip(range(3, 17), table2):
        msh = os.path.join(OUT, "count_L%d.msh" % level)
        run(["gmsh", "-3", "-setnumber", "L", str(level), "-format", "msh22", os.path.join(ROOT, "meshes", "prism.geo"), "-o", msh])
        with open(msh) as f:
            lines = f.read().split("\n")
        got = int(lines[lines.index("$Nodes") + 1])
        expect(got == nodes, "level %d: %d nodes, Table 2 has %d" % (level, got, nodes))
        os.remove(msh)


@test("-mesh runs a gmsh file given by the user (here msh 4.1 written by the gmsh command) and finds the same solution as -level")
def prism_user_mesh():
    msh = os.path.join(OUT, "user_L3.msh")
    run(["gmsh", "-3", "-setnumber", "L", "3", "-format", "msh41", os.path.join(ROOT, "meshes", "prism.geo"), "-o", msh])
    out = run(mpiexec(2, PRISM, "-mesh", msh, "-snes_converged_reason"))
    m = SUMMARY.search(out)
    expect(m is not None and m.group(8) == REFERENCE_STATES[3] and m.group(9) == "CONVERGED_FNORM_RELATIVE", "different result from -mesh", out)


@test("bad input is refused with an error naming it: a missing mesh file, a mesh without a physical group, a negative friction, an output file that cannot be written")
def errors_name_the_problem():
    out = run([PRISM, "-mesh", "no/such.msh"], expect_rc=1)
    expect("no/such.msh" in out, "the missing file is not named", out)
    geo = os.path.join(OUT, "no_right.geo")
    with open(os.path.join(ROOT, "meshes", "prism.geo")) as f:
        text = f.read().replace('Physical Surface("right") = {4};', "")
    with open(geo, "w") as f:
        f.write(text)
    out = run([PRISM, "-geo", geo, "-level", "2"], expect_rc=1)
    expect('no physical group named "right"' in out, "the missing group is not named", out)
    out = run([PRISM, "-level", "2", "-snes_ssstar_friction", "-1"], expect_rc=1)
    expect("-snes_ssstar_friction -1" in out, "the bad option is not named", out)
    out = run([PRISM, "-level", "2", "-o", "no/such/folder/x.h5"], expect_rc=1)
    expect("Cannot write no/such/folder/x.h5" in out, "the output file is not named", out)


@test("-snes_ssstar_method fixedpoint (u <- u + z, the first-order baseline of make accuracy) converges on level 3 with rtol 1e-12 to the Newton solution (1e-8 relative) with the same states, in over 100 times the iterations; -snes_view names it")
def prism_fixedpoint_baseline():
    out, s = prism(3, extra=["-snes_ssstar_method", "fixedpoint", "-snes_max_it", "100000", "-snes_rtol", "1e-12", "-snes_view"], h5="fixedpoint_L3.h5")
    expect(s["reason"] == "CONVERGED_FNORM_RELATIVE" and s["iters"] > 100 * REFERENCE_ITERATIONS[3], "%s after %d iterations" % (s["reason"], s["iters"]), out)
    expect("method: fixedpoint" in out and "gamma = 1/(largest contact row sum of K)" in out, "-snes_view does not name the method and its gamma", out)
    newton, t = prism(3, h5="newton_L3.h5")
    expect(t["states"] == s["states"], "states %s, Newton %s" % (s["states"], t["states"]), out)
    run(CHECK + ["compare", os.path.join(OUT, "newton_L3.h5"), os.path.join(OUT, "fixedpoint_L3.h5"), "--tol", str(AGREE)])


PROGRESS_PHASES = [r"mesh: file \S+prism_L4\.msh, 1377 nodes", r"mesh: read and distributed over 2 ranks, \d+ cells", r"contact: 144 contact nodes in 1 group",
                   r"assembly: K of \d+ dofs and b", r"set-up: K reduced to 432 contact dofs by the direct Schur complement \(chosen by auto\)"]
SECONDS_MEMORY = r", ([0-9.]+) s, ([0-9.]+) GB per rank$"


@test("examples/prism prints a line as each phase ends, flushed, in order (mesh file, mesh distributed, contact nodes, assembly, "
      "the solver's set-up by auto, one line per iterate whose ||z|| is -snes_monitor's, the summary row with the peak memory "
      "per rank, the output file), with sane seconds and memory; level 4 on 2 ranks")
def prism_progress_lines():
    out, s = prism(4, 2, h5="progress_L4.h5")
    lines = out.splitlines()
    at = []
    for phase in PROGRESS_PHASES + [r"^\s+0 SSStar \|\|z\|\|", r"^level ranks", r"output: wrote \S+progress_L4\.h5 and \S+progress_L4\.xmf"]:
        i = next((k for k, line in enumerate(lines) if re.search(phase, line)), None)
        expect(i is not None, "no line " + phase, out)
        at.append(i)
    expect(at == sorted(at), "the phases are not in order: %s" % at, out)
    memories = []
    for phase in PROGRESS_PHASES + [r"output: wrote"]:
        m = re.search(phase + ".*" + SECONDS_MEMORY, out, re.M)
        expect(m is not None, "no seconds and memory on the line " + phase, out)
        expect(0 <= float(m.group(1)) < 60 and 0.01 < float(m.group(2)) < 4, "%s: %s s, %s GB" % (phase, m.group(1), m.group(2)), out)
        memories.append(float(m.group(2)))
    znorms = re.findall(r"^\s*\d+ SSStar \|\|z\|\| ([0-9.e+-]+)", out, re.M)
    monitor = re.findall(r"SNES Function norm ([0-9.e+-]+)", out)
    expect(len(znorms) == s["iters"] + 1 and znorms == monitor, "the iterate lines' ||z|| %s are not -snes_monitor's %s" % (znorms, monitor), out)
    steps = re.findall(r"^\s*(\d+) SSStar \|\|z\|\| \S+, (\d+) nodes? changed state; step ([0-9.]+) s, (\d+) Krylov its(, new LU \(([0-9.]+) s\))?, ([0-9.]+) GB per rank$", out, re.M)
    expect([int(k) for k, *_ in steps] == list(range(1, s["iters"] + 1)), "not one step line per Newton iteration", out)
    expect(int(steps[0][1]) > 0 and int(steps[-1][1]) == 0, "the changed states do not go from some to none", out)
    expect(all(float(t) < 60 for _, _, t, *_ in steps), "a step's seconds are not sane", out)
    expect(any(fresh for _, _, _, _, fresh, _, _ in steps) and all(0 < float(lu) <= float(t) for _, _, t, _, fresh, lu, _ in steps if fresh), "no step line says new LU with its seconds (within the step's)", out)
    expect(s["peak_gb"] >= max(memories) - 0.002 and s["peak_gb"] < 4, "peak %.3f GB per rank below a phase's memory %s" % (s["peak_gb"], memories), out)


@test("-ssstar_progress 0 turns the progress lines off: with -summary_header 0 the output is the summary row alone (the scripted use); "
      "-snes_ssstar_monitor_progress brings the solver's lines back alone; with the progress on too, the option adds nothing (it crashed: "
      "the duplicate monitor's context destroyed twice)")
def prism_progress_off():
    out = run(mpiexec(1, PRISM, "-level", "3", "-ssstar_progress", "0", "-summary_header", "0"))
    expect(len(out.strip().splitlines()) == 1 and SUMMARY.search(out) is not None, "more than the summary row", out)
    out = run(mpiexec(1, PRISM, "-level", "3", "-ssstar_progress", "0", "-summary_header", "0", "-snes_ssstar_monitor_progress"))
    expect("mesh:" not in out and "set-up:" in out and len(re.findall(r"SSStar \|\|z\|\|", out)) == 8, "not the solver's lines alone", out)
    out = run(mpiexec(1, PRISM, "-level", "3", "-snes_ssstar_monitor_progress"))
    expect("mesh:" in out and len(re.findall(r"SSStar \|\|z\|\|", out)) == 8, "not each progress line once", out)


@test("-save_reduced names the dense route itself (P is what it writes): the set-up line says direct, not chosen by auto")
def prism_save_reduced_direct():
    out = run(mpiexec(1, PRISM, "-level", "3", "-save_reduced", os.path.join(OUT, "progress_L3.bin")))
    expect(re.search(r"set-up: K reduced to \d+ contact dofs by the direct Schur complement, ", out) is not None, "not the direct route named", out)


@test("examples/contact prints the phase lines too and its summary the peak memory per rank; -ssstar_progress 0 leaves them out")
def contact_progress_lines():
    args = [CONTACT, "-options_file", os.path.join(ROOT, "scenes", "incline.opts")]
    out = run(mpiexec(1, *args))
    for phase in [r"^mesh: file", r"^contact: \d+ contact nodes", r"^assembly: K of", r"set-up: ", r"^\s+1 SSStar \|\|z\|\|", r"summary: .* peak [0-9.]+ GB per rank$"]:
        expect(re.search(phase, out, re.M) is not None, "no line " + phase, out)
    out = run(mpiexec(1, *args, "-ssstar_progress", "0"))
    expect("mesh:" not in out and "SSStar ||z||" not in out and "summary:" in out, "progress lines with -ssstar_progress 0", out)


PROCESS_PEAK = re.compile(r"Maximum \(over computational time\) process memory:\s+total \S+ max (\S+)")


@test("the output adds little to the process's peak (docs/guide/scale.md, the output's memory): prism level 12 on 2 ranks "
      "(the whole body, a nested start) written with -o: the process's peak (-memory_view's maximum, the largest rank) "
      "exceeds the solve's (the summary row) by at most 8 % of it (measured 4.3-5.1 %, the output's own 10-12 MB, since the "
      "solve holds one multigrid set-up fewer and its peak fell from 0.274 to 0.234 GB (h36b): 2.5 % before, where the "
      "output reused what the first set-up had freed; 12 % before the output computed its cell fields one at a time and "
      "the Newton steps' work was freed first); the file passes check_solution.py")
def prism_output_memory():
    out = run(mpiexec(2, PRISM, "-level", "12", "-memory_view", "-o", os.path.join(OUT, "output_memory_L12.h5")), check_memory=False)
    s = SUMMARY.search(out)
    process = PROCESS_PEAK.search(out)
    expect(s and process, "no summary row or -memory_view maximum", out)
    solve, peak = float(s.group(10)), float(process.group(1)) / 1e9
    expect(peak - solve <= 0.08 * solve, "the output raised the peak from %.3f to %.3f GB per rank" % (solve, peak), out)
    run(CHECK + ["law", os.path.join(OUT, "output_memory_L12.h5")])
