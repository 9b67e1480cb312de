"""The Schur reduction (src/reduction): its three paths agree, on any number of ranks; memory is checked before the
factorization; a singular K and MUMPS's failures are reported in words, on every rank."""
import os
import re

from harness import *  # noqa: F401,F403 (run, expect, mpiexec, test, paths)

TEST_REDUCTION = os.path.join(ROOT, "tests", "test_reduction")
SINGULAR = "K is singular: is the body held? (Dirichlet conditions)"


def error_text(out):
    """The error message lines: the driver's one line (program: message), or PETSc's report (-info, test programs)
    without the traceback and the configure line"""
    return " ".join(re.findall(r"(?:PETSC ERROR|^\S+(?:, rank \d+)?): ((?:K is|The |Out of|MUMPS|-schur).*)", out, re.M))


@test("on a hand-assembled K (contact dofs in no particular order), direct, mumps and explicit give the same P, f and recovered u to 1e-10, and u solves the interior equations to 1e-12, on 1, 2 and 3 ranks", full=True)
def schur_paths_agree_lattice():
    for ranks in (1, 2, 3):
        out = run(mpiexec(ranks, TEST_REDUCTION, "-n", "7"))
        for other in ("mumps", "explicit"):
            m = re.search(r"%s vs direct: P (\S+) f (\S+) u (\S+)" % other, out)
            expect(m is not None, "no comparison of %s with direct on %d ranks" % (other, ranks), out)
            for name, value in zip("Pfu", m.groups()):
                expect(float(value) <= 1e-10, "%d ranks: %s of %s differs from direct by %s" % (ranks, name, other, value), out)
        residuals = re.findall(r"(\w+): interior residual (\S+)", out)
        expect(len(residuals) == 3, "missing interior residuals on %d ranks" % ranks, out)
        for path, value in residuals:
            expect(float(value) <= 1e-12, "%d ranks: %s leaves an interior residual %s" % (ranks, path, value), out)


@test("the prism (level 4) solved through the direct reduction on 1, 2 and 3 ranks has the reference iterations and the same solution (contact face and whole mesh) as the mumps and explicit paths to 2e-6 (harness.AGREE)", full=True)
def schur_paths_agree_prism():
    cases = [("direct", 1), ("direct", 2), ("direct", 3), ("mumps", 1), ("explicit", 2)]
    for path, ranks in cases:
        out, s = prism(4, ranks, extra=["-snes_ssstar_reduction", path], h5="schur_%s%d_L4.h5" % (path, ranks))
        expect(s["iters"] == REFERENCE_ITERATIONS[4] and s["sep_sl_st"] == REFERENCE_STATES[4],
               "%s on %d ranks: %d iterations, states %s" % (path, ranks, s["iters"], s["sep_sl_st"]), out)
    for path, ranks in cases[1:]:
        run(CHECK + ["compare", os.path.join(OUT, "schur_direct1_L4.h5"), os.path.join(OUT, "schur_%s%d_L4.h5" % (path, ranks)), "--tol", str(AGREE)])


@test("-log_view shows the phases of the direct reduction (SSStarOrdering, SSStarAnalysis, SSStarFactor, SSStarSchurScat) with MUMPS's flops in SSStarFactor")
def schur_log_events():
    out, _ = prism(3, 2, extra=["-log_view"])
    for name in ("SSStarOrdering", "SSStarAnalysis", "SSStarFactor", "SSStarSchurScat"):
        expect(re.search(r"^%s\s+1 " % name, out, re.M) is not None, "no event " + name, out)
    m = re.search(r"^SSStarFactor\s+\S+\s+\S+\s+\S+\s+\S+\s+(\S+)", out, re.M)
    expect(m is not None and float(m.group(1)) > 1e6, "no flops logged in SSStarFactor", out)


@test("a memory limit too small is refused after the analysis and before the factorization, with the estimate and the limit in the message and a non-zero exit, for each path (2 ranks)")
def schur_memory_refusal():
    for path in ("direct", "mumps", "explicit"):
        # examples/generic: the prism's scene would refuse the mesh itself against so small a limit, before the reduction
        out = run(mpiexec(2, os.path.join(ROOT, "examples", "generic"), "-snes_type", "ssstar", "-snes_ssstar_reduction", path, "-snes_ssstar_memory_limit", "0.001", "-info"), expect_rc=1)
        msg = error_text(out)
        expect(re.search(r"The %s Schur reduction.* needs an estimated [\d.e+-]+ GB on rank \d \(.*\), more than the limit of 0.001 GB per rank \(-snes_ssstar_memory_limit\): refused before the factorization" % path, msg) is not None,
               "%s: no refusal with the estimate and the limit" % path, out)
        expect("MUMPS factorization" not in out, "%s: factored before refusing" % path, out)
        expect(path != "direct" or "MUMPS analysis" in out, "direct: refused before its analysis", out)


@test("a K with a part held nowhere (a floating lattice; a node without stiffness) is refused as singular, with the words of the singular-K message, by every path, on 1 and 2 ranks", full=True)
def schur_singular_k():
    for floating in ("2", "1"):
        for path in ("direct", "mumps", "explicit"):
            for ranks in (1, 2):
                out = run(mpiexec(ranks, TEST_REDUCTION, "-n", "5", "-floating", floating, "-types", path), expect_rc=1, timeout=60)
                expect(SINGULAR in error_text(out), "%s, %d ranks, floating %s: no singular-K message" % (path, ranks, floating), out)


@test("MUMPS running out of memory is reported as memory, with the amount MUMPS missed and its INFOG, for each path (here: its working memory capped by ICNTL(23) = 1 MB)")
def schur_mumps_out_of_memory():
    for path, option in (("direct", "-schur_direct_mumps_icntl_23"), ("mumps", "-schur_mat_mumps_icntl_23"), ("explicit", "-interior_mat_mumps_icntl_23")):
        out = run(mpiexec(2, PRISM, "-level", "4", "-snes_ssstar_reduction", path, option, "1"), expect_rc=1)
        msg = error_text(out)
        expect(re.search(r"Out of memory in .*MUMPS needed [\d.e+-]+ GB more than the working memory it was allowed \(%s\) \(INFOG\(1\) = -19" % option, msg) is not None,
               "%s: no memory message with the amount" % path, out)


@test("an ICNTL the direct reduction relies on (-schur_direct_mumps_icntl_19) is refused, naming the option")
def schur_reserved_icntl():
    out = run([PRISM, "-level", "2", "-schur_direct_mumps_icntl_19", "1"], expect_rc=1)
    expect("-schur_direct_mumps_icntl_19: ICNTL(19) is set by the direct reduction itself" in out, "the option is not named", out)


@test("a memory limit between MUMPS's out-of-core and in-core estimates puts the factors out of core (on disk), with the same solution as in core to 1e-10 (examples/generic, 25 x 25 x 13 nodes: in core 223 MB, out of core 100 MB, with the dense contact matrices 84 MB; limit 0.25 GB)", full=True)
def schur_out_of_core():
    import h5py
    import numpy as np
    generic = [os.path.join(ROOT, "examples", "generic"), "-snes_type", "ssstar", "-da_grid_x", "25", "-da_grid_y", "25", "-da_grid_z", "13", "-snes_converged_reason",
               "-snes_ssstar_reduction", "direct"]  # 24 375 dofs: auto would take the whole body
    out = run(generic + ["-snes_ssstar_memory_limit", "0.25", "-info", ":mat", "-o", os.path.join(OUT, "schur_ooc.h5")])
    expect(re.search(r"MUMPS's factors in core: \d+ MB, out of core: \d+ MB on this rank; out of core", out) is not None, "the factors stayed in core", out)
    expect("CONVERGED_FNORM_RELATIVE" in out, "out of core: not converged", out)
    run(generic + ["-o", os.path.join(OUT, "schur_incore.h5")])
    with h5py.File(os.path.join(OUT, "schur_ooc.h5"), "r") as a, h5py.File(os.path.join(OUT, "schur_incore.h5"), "r") as b:
        ua, ub = a["contact/displacement"][:], b["contact/displacement"][:]
    error = float(np.abs(ua - ub).max() / np.abs(ub).max())
    expect(error <= 1e-10, "out of core differs from in core by %.1e" % error)
