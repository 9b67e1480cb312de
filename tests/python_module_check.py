#!/usr/bin/python3
"""The Python module ssstar on a small reduced problem (tests/suite_python.py runs it on 1 and 2 ranks, from the source
tree and from a make install): every setter and getter round-trips, the solve converges with per-node laws (Coulomb
with per-node coefficients, Tresca, frictionless; the laws' names from the library's table), the states and forces come back per local node, and bad input
raises petsc4py.PETSc.Error. Prints "test_module: ok" and the module's library path."""
import sys

import numpy as np
import petsc4py

petsc4py.init(sys.argv)
from petsc4py import PETSc  # noqa: E402

import ssstar  # noqa: E402  (PYTHONPATH decides which: the source tree's python/ or an installed one)


def expect(cond, message):
    if not cond:
        PETSc.Sys.Print("test_module: FAILED: " + message)
        sys.exit(1)


def main():
    comm = PETSc.COMM_WORLD
    rank, size = comm.getRank(), comm.getSize()
    p = 12  # contact nodes in all, split over the ranks
    n = p // size + (rank < p % size)
    first = rank * (p // size) + min(rank, p % size)
    # a reduced problem c(u) = P u - f: a symmetric, diagonally dominant P coupling neighbouring nodes, a load pressing
    # most nodes onto the plane with tangential parts that make some slide and some stick
    P = PETSc.Mat().createAIJ(((3 * n, 3 * p), (3 * n, 3 * p)), nnz=(9, 9), comm=comm)
    P.setUp()
    f = PETSc.Vec().createMPI((3 * n, 3 * p), comm=comm)
    for i in range(first, first + n):
        for a in range(3):
            P.setValue(3 * i + a, 3 * i + a, 4.0)
            if i + 1 < p:
                P.setValue(3 * i + a, 3 * (i + 1) + a, -1.0)
            if i > 0:
                P.setValue(3 * i + a, 3 * (i - 1) + a, -1.0)
        angle = 0.7 * i
        f.setValues([3 * i, 3 * i + 1, 3 * i + 2], [0.5 * (i % 3) * np.cos(angle), 0.5 * (i % 3) * np.sin(angle), -1.0 if i % 5 else 0.5])
    P.assemble()
    f.assemble()

    snes = PETSc.SNES().create(comm=comm)
    snes.setType(ssstar.SNESSSSTAR)
    expect(snes.getType() == "ssstar", "the type is %s" % snes.getType())
    ssstar.set_linear_problem(snes, P, f)
    expect(ssstar.get_contact_nodes(snes)[0] == n, "the node count of a reduced problem with its function vector: %d, not %d" % (ssstar.get_contact_nodes(snes)[0], n))

    # the lists the module reads from the library (none written in the module)
    expect(ssstar.REDUCTION_TYPES == ["direct", "mumps", "explicit", "none", "auto"], "REDUCTION_TYPES %s" % ssstar.REDUCTION_TYPES)
    expect(ssstar.LAW_PARAMETERS == ["slip_bound", "friction", "friction_1", "friction_2", "friction_direction"], "LAW_PARAMETERS %s" % ssstar.LAW_PARAMETERS)
    expect((len(ssstar.STATE_NAMES), len(ssstar.REASONS), len(ssstar.METHODS), len(ssstar.REMEDIES)) == (7, 12, 2, 5) and ssstar.STATE_NAMES[-1] == "LS" and "NO_EQUILIBRIUM" in ssstar.REASONS and ssstar.REASONS[-1] == "NOT_AFFINE", "the enum names")
    source = open(ssstar.__file__).read()
    expect('"direct", "mumps"' not in source and not any(n in source for n in ('Names", 7)', 'Reasons", 11)')), "the module writes a list of the library's names itself")

    # setters and getters
    expect(ssstar.get_affine(snes), "set_linear_problem's F is affine")
    ssstar.set_affine(snes, False)
    expect(not ssstar.get_affine(snes), "set_affine/get_affine")
    ssstar.set_affine(snes, True)
    ssstar.set_friction(snes, 0.4)
    expect(ssstar.get_friction(snes) == 0.4, "set_friction/get_friction")
    ssstar.set_friction_law(snes, "tresca")
    expect(ssstar.get_friction_law(snes) == "tresca", "set_friction_law/get_friction_law")
    ssstar.set_friction_law(snes, "coulomb")
    ssstar.set_method(snes, "fixedpoint")
    expect(ssstar.get_method(snes) == "fixedpoint", "set_method/get_method")
    ssstar.set_method(snes, "newton")
    ssstar.set_scaling(snes, 0.5)
    expect(ssstar.get_scaling(snes) == 0.5, "set_scaling/get_scaling")
    ssstar.set_scaling(snes, 0)
    ssstar.set_reduction_type(snes, "direct")
    expect(ssstar.get_reduction_type(snes) == "direct", "set_reduction_type/get_reduction_type")
    ssstar.set_state_tolerance(snes, 1e-13)
    ssstar.set_globalization(snes, True, damping_min=1 / 64, stagnation_its=20)
    ssstar.set_memory_limit(snes, 0)
    ssstar.set_lu_reuse(snes, -1)
    for bad, what in ((lambda: ssstar.set_friction_law(snes, "sticky"), "an unknown law"), (lambda: ssstar.set_reduction_type(snes, 7), "a reduction code out of range")):
        try:
            bad()
            expect(False, "%s is accepted" % what)
        except ValueError:
            pass
    try:
        ssstar.set_friction(snes, -1.0)
        expect(False, "a negative friction coefficient is accepted")
    except PETSc.Error as e:
        expect(e.ierr == 63, "PETSc error %d, not PETSC_ERR_ARG_OUTOFRANGE" % e.ierr)

    # per-node laws: node i Coulomb with phi 0.2 + 0.05 (i % 3), Tresca (bound 0.3) every fourth node, none every
    # seventh; the laws and bounds are set before the set-up, which fixes the node count
    ids = np.arange(first, first + n)
    laws = ["none" if i % 7 == 6 else ("tresca" if i % 4 == 3 else "coulomb") for i in ids]
    ssstar.set_node_friction_laws(snes, laws)
    ssstar.set_node_law_parameter(snes, "friction", 0.2 + 0.05 * (ids % 3))
    ssstar.set_node_law_parameter(snes, "slip_bound", np.where(ids % 4 == 3, 0.3, 0.0))
    snes.setTolerances(rtol=1e-12)
    snes.setFromOptions()
    u = f.duplicate()
    u.zeroEntries()
    snes.solve(None, u)

    expect(snes.getConvergedReason() > 0, "not converged: %d" % snes.getConvergedReason())
    expect(ssstar.get_reason(snes) in ("CONVERGED_RELATIVE", "CONVERGED_ABSOLUTE"), "sub-reason %s" % ssstar.get_reason(snes))
    expect(0 <= snes.getFunctionNorm() <= ssstar.get_tolerance(snes), "||z|| %g above the tolerance %g" % (snes.getFunctionNorm(), ssstar.get_tolerance(snes)))
    count, dofs, normals, gaps = ssstar.get_contact_nodes(snes)
    expect(count == n and dofs is None and normals is None and gaps is None, "get_contact_nodes: %s" % ((count, dofs, normals, gaps),))
    states, counts = ssstar.get_states(snes)
    expect(len(states) == n and counts.sum() == p, "states: %d local, counts %s" % (len(states), counts))
    expect(set(np.unique(states)) <= set(range(7)), "state codes %s" % np.unique(states))
    law_codes = ssstar.get_node_friction_laws(snes)
    phi, bounds = ssstar.get_node_law_parameter(snes, "friction"), ssstar.get_node_law_parameter(snes, "slip_bound")
    coulomb, tresca = ssstar.FRICTION_LAWS.index("coulomb"), ssstar.FRICTION_LAWS.index("tresca")
    expect(list(law_codes) == [ssstar.FRICTION_LAWS.index(x) for x in laws], "get_node_friction_laws: laws %s" % law_codes)
    expect(np.allclose(phi[law_codes == coulomb], (0.2 + 0.05 * (ids % 3))[law_codes == coulomb]) and np.allclose(bounds[law_codes == tresca], 0.3), "get_node_law_parameter: friction or slip_bound")
    r = ssstar.get_contact_forces(snes).reshape(-1)
    expected = P.createVecLeft()
    P.mult(u, expected)
    expected.axpy(-1.0, f)
    expect(np.allclose(r, expected.getArray(), rtol=0, atol=1e-12), "get_contact_forces is not P u - f")
    # the law at each local node, from the module's outputs alone
    ua = u.getArray().reshape(-1, 3)
    r = r.reshape(-1, 3)
    limit = np.where(law_codes == coulomb, phi * r[:, 2], np.where(law_codes == tresca, bounds, 0.0))
    worst = max(np.max(-ua[:, 2], initial=0), np.max(-r[:, 2], initial=0), np.max(np.abs(ua[:, 2] * r[:, 2]), initial=0),
                np.max(np.linalg.norm(r[:, :2], axis=1) - limit, initial=0))
    expect(worst <= 1e-10, "the friction law is violated by %g" % worst)
    nlaws = len(ssstar.FRICTION_LAWS)
    counted = PETSc.Vec().createMPI((nlaws if rank == 0 else 0, nlaws), comm=comm)
    counted.setValues(list(range(nlaws)), np.bincount(law_codes, minlength=nlaws).astype(float), addv=PETSc.InsertMode.ADD_VALUES)
    counted.assemble()
    global_law_counts = [int(round(x)) for x in counted.getArray()] if rank == 0 else []
    # a load path's next step with the same load (set_contact_offsets, (10.4)): the solution is its own next step,
    # every node in contact keeps its place (the incremental law holds with a zero increment)
    offsets = np.zeros_like(ua)
    offsets[:, :2] = -ua[:, :2]
    ssstar.set_contact_offsets(snes, offsets)
    expect(np.array_equal(ssstar.get_contact_offsets(snes), offsets.reshape(-1)), "get_contact_offsets")
    previous = u.copy()
    ssstar.release_work(snes)  # the next solve builds its preconditioner again
    snes.solve(None, u)
    expect(snes.getConvergedReason() > 0 and np.abs(u.getArray() - previous.getArray()).max() <= 1e-10, "a step with an unchanged load moved the solution (after release_work())")
    ssstar.set_contact_offsets(snes, None)
    expect(ssstar.get_contact_offsets(snes) is None, "set_contact_offsets(None) kept the offsets")
    a, b, c = ssstar.get_newton_step_counts(snes)
    expect(ssstar.get_nonlinear_counts(snes) == (1, 0), "an affine residual's Jacobian evaluated once, no contact update: %s" % (ssstar.get_nonlinear_counts(snes),))
    remedies = ssstar.get_remedy_counts(snes)
    expect(set(remedies) == set(ssstar.REMEDIES) and min(a, b, c) >= 0, "remedy or Newton step counts")
    PETSc.Sys.Print("test_module: ok; %d nodes on %d ranks, %d iterations, states %s, laws %s; library %s"
                    % (p, size, snes.getIterationNumber(), "/".join(str(x) for x in counts), "/".join(str(x) for x in global_law_counts), ssstar.library))


if __name__ == "__main__":
    main()
