static const char help[] = "The entries of ssstar on two ranks (tests/suite_solver.py): bad input on one rank ends every rank with the\n\
same error, and an options prefix reaches the reduction's solvers.\n\
  -case straddle   rank 0 declares a contact node whose last dof rank 1 owns\n\
  -case normals    rank 1 passes a normals vector of the wrong size\n\
  -case friction   rank 1 gives one node a negative friction coefficient (SNESSSStarSetNodeLawParameter)\n\
  -case law        rank 1 gives one node a law that is not in the table (SNESSSStarSetNodeFrictionLaws)\n\
  -case operator   rank 1 has a contact point whose block of B is not a rotation (SNESSSStarSetContactOperator)\n\
  -case none       nothing wrong: the solve converges (the default)\n\
  -catch           return the error instead of aborting: each rank prints its error code and message\n\
  -prefix <p>      the SNES's options prefix\n";

/*
   Requirement: an entry of the solver that finds its input wrong on one rank raises the error on every rank, with the
   message of the rank that found it (naming the node and the dof), so that no rank waits forever in a collective call:
   the program ends (non-zero) within seconds on every rank. A SNES with an options prefix gives it to its reduction.
   The problem: a chain of 8 nodes per rank held by springs, every other one a contact node pressed onto the plane
   z = 0 (so that the reductions have interior dofs to eliminate).
*/
#include <ssstar.h>

#define NODES 8 /* per rank, half of them contact nodes */

int main(int argc, char **argv)
{
  char                kind[32] = "none", prefix[64] = "";
  PetscBool           catchErrors = PETSC_FALSE, isStraddle, isNormals, isFriction, isLaw, isOperator;
  PetscMPIInt         rank, size;
  const PetscInt      n = NODES / 2;
  PetscInt            lo, hi, N, dofs[3 * NODES / 2], laws[NODES / 2], coulomb;
  Mat                 K, B = NULL;
  Vec                 b, u, normals, friction;
  IS                  is;
  SNES                snes;
  PetscErrorCode      ierr;

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(SSStarInitializePackage());
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCheck(size == 2, PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "run it on 2 ranks");
  PetscCall(PetscOptionsGetString(NULL, NULL, "-case", kind, sizeof(kind), NULL));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-prefix", prefix, sizeof(prefix), NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-catch", &catchErrors, NULL));
  PetscCall(PetscStrcmp(kind, "straddle", &isStraddle));
  PetscCall(PetscStrcmp(kind, "normals", &isNormals));
  PetscCall(PetscStrcmp(kind, "friction", &isFriction));
  PetscCall(PetscStrcmp(kind, "law", &isLaw));
  PetscCall(PetscStrcmp(kind, "operator", &isOperator));

  /* K: a spring of 1.2e3 from each dof to the ground less 1e2 to each neighbour's; b presses every node down */
  PetscCall(MatCreateAIJ(PETSC_COMM_WORLD, 3 * NODES, 3 * NODES, PETSC_DETERMINE, PETSC_DETERMINE, 3, NULL, 3, NULL, &K));
  PetscCall(MatGetOwnershipRange(K, &lo, &hi));
  PetscCall(MatGetSize(K, &N, NULL));
  for (PetscInt r = lo; r < hi; r++) {
    PetscCall(MatSetValue(K, r, r, 1.2e3, ADD_VALUES));
    if (r + 3 < N) {
      PetscCall(MatSetValue(K, r, r + 3, -1e2, ADD_VALUES));
      PetscCall(MatSetValue(K, r + 3, r, -1e2, ADD_VALUES));
    }
  }
  PetscCall(MatAssemblyBegin(K, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(K, MAT_FINAL_ASSEMBLY));
  PetscCall(MatCreateVecs(K, &u, &b));
  for (PetscInt r = lo; r < hi; r++) PetscCall(VecSetValue(b, r, r % 3 == 2 ? -10.0 : 2.0, INSERT_VALUES));
  PetscCall(VecAssemblyBegin(b));
  PetscCall(VecAssemblyEnd(b));
  PetscCall(VecZeroEntries(u));

  /* the contact nodes: the even nodes of the rank (rank 0's last one straddles: its last dof is rank 1's first) */
  for (PetscInt i = 0; i < n; i++)
    for (PetscInt k = 0; k < 3; k++) dofs[3 * i + k] = lo + 6 * i + k;
  if (isStraddle && rank == 0) dofs[3 * n - 1] = hi;
  PetscCall(ISCreateGeneral(PETSC_COMM_WORLD, 3 * n, dofs, PETSC_COPY_VALUES, &is));
  PetscCall(VecCreateMPI(PETSC_COMM_WORLD, isNormals && rank == 1 ? 3 * n - 1 : 3 * n, PETSC_DETERMINE, &normals));
  {
    PetscScalar *a;
    PetscInt     m;

    PetscCall(VecGetLocalSize(normals, &m));
    PetscCall(VecGetArrayWrite(normals, &a));
    for (PetscInt k = 0; k < m; k++) a[k] = k % 3 == 2 ? 1.0 : 0.0; /* (0, 0, 1) */
    PetscCall(VecRestoreArrayWrite(normals, &a));
  }
  PetscCall(VecCreateMPI(PETSC_COMM_WORLD, n, PETSC_DETERMINE, &friction));
  PetscCall(VecSet(friction, 0.3));
  if (isFriction && rank == 1) {
    PetscScalar *a;

    PetscCall(VecGetArray(friction, &a));
    a[2] = -0.5;
    PetscCall(VecRestoreArray(friction, &a));
  }
  PetscCall(SSStarLawGetIndex(SSSTARLAWCOULOMB, &coulomb));
  for (PetscInt i = 0; i < n; i++) laws[i] = isLaw && rank == 1 && i == 1 ? 99 : coulomb;
  if (isOperator) { /* B = the identity at each point's own dofs, but twice the first row at rank 1's point 2 */
    PetscInt start;

    PetscCall(MatCreateAIJ(PETSC_COMM_WORLD, 3 * n, 3 * NODES, PETSC_DETERMINE, PETSC_DETERMINE, 1, NULL, 0, NULL, &B));
    PetscCall(MatGetOwnershipRange(B, &start, NULL));
    for (PetscInt k = 0; k < 3 * n; k++) PetscCall(MatSetValue(B, start + k, dofs[k], rank == 1 && k == 6 ? 2.0 : 1.0, INSERT_VALUES));
    PetscCall(MatAssemblyBegin(B, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(B, MAT_FINAL_ASSEMBLY));
  }

  PetscCall(SNESCreate(PETSC_COMM_WORLD, &snes));
  PetscCall(SNESSetOptionsPrefix(snes, prefix));
  PetscCall(SNESSetType(snes, SNESSSSTAR));
  PetscCall(SNESSSStarSetLinearProblem(snes, K, b));
  PetscCall(SNESSetFromOptions(snes));
  if (catchErrors) PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  ierr = B ? SNESSSStarSetContactOperator(snes, is, B, NULL) : SNESSSStarSetContactNodes(snes, is, normals, NULL);
  if (!ierr) ierr = SNESSSStarSetNodeLawParameter(snes, "friction", friction);
  if (!ierr) ierr = SNESSSStarSetNodeFrictionLaws(snes, n, laws);
  if (!ierr) ierr = SNESSolve(snes, NULL, u);
  if (catchErrors) {
    const char *text, *specific = NULL;

    PetscCall(PetscPopErrorHandler());
    PetscCall(PetscErrorMessage(ierr, &text, (char **)&specific));
    PetscCall(PetscSynchronizedPrintf(PETSC_COMM_WORLD, "rank %d: error %d: %s\n", rank, (int)ierr, ierr ? specific : "none"));
    PetscCall(PetscSynchronizedFlush(PETSC_COMM_WORLD, PETSC_STDOUT));
  } else PetscCall(ierr);
  if (!ierr) {
    SNESConvergedReason reason;
    SSStarReductionType type;

    PetscCall(SNESGetConvergedReason(snes, &reason));
    PetscCall(SNESSSStarGetReductionType(snes, &type));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s with the reduction %s\n", SNESConvergedReasons[reason], type));
  }
  PetscCall(SNESDestroy(&snes));
  PetscCall(MatDestroy(&B));
  PetscCall(MatDestroy(&K));
  PetscCall(VecDestroy(&b));
  PetscCall(VecDestroy(&u));
  PetscCall(VecDestroy(&normals));
  PetscCall(VecDestroy(&friction));
  PetscCall(ISDestroy(&is));
  PetscCall(PetscFinalize());
  return ierr ? 1 : 0;
}
