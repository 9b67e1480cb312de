static const char help[] = "Bad input on one rank of two: every rank ends with the same error (tests/suite_solver.py).\n\
  -case straddle   rank 0 declares a contact node whose last dof rank 1 owns\n\
  -case normals    rank 1 passes a normals vector of the wrong size\n\
  -case friction   rank 1 gives one node a negative friction coefficient (SNESSSStarSetNodeLawParameter)\n\
  -case law        rank 1 gives one node a law that is not in the table (SNESSSStarSetNodeFrictionLaws)\n\
  -case operator   rank 1 has a contact point whose block of B is not a rotation (SNESSSStarSetContactOperator)\n\
  -case none       nothing wrong: the solve converges\n\
  -catch           return the error instead of aborting: each rank prints its error code and message\n";

/*
   Requirement: an entry of the solver that finds its input wrong on one rank raises the error on every rank, with the
   message of the rank that found it (naming the node and the dof), so that no rank waits forever in a collective call:
   the program ends (non-zero) within seconds on every rank. A problem of 4 nodes per rank, each held by springs, with
   every node a contact node against the plane z = 0.
*/
#include <ssstar.h>

#define NODES 4 /* per rank */

int main(int argc, char **argv)
{
  char            kind[32] = "straddle";
  PetscBool       catchErrors = PETSC_FALSE, isStraddle, isNormals, isFriction, isLaw, isOperator;
  PetscMPIInt     rank, size;
  PetscInt        lo, hi, dofs[3 * NODES], laws[NODES], coulomb;
  Mat             K, B = NULL;
  Vec             b, u, normals, friction;
  IS              is;
  SNES            snes;
  PetscErrorCode  ierr;

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(SSStarInitializePackage());
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCheck(size == 2, PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "run it on 2 ranks");
  PetscCall(PetscOptionsGetString(NULL, NULL, "-case", kind, sizeof(kind), NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-catch", &catchErrors, NULL));
  PetscCall(PetscStrcmp(kind, "straddle", &isStraddle));
  PetscCall(PetscStrcmp(kind, "normals", &isNormals));
  PetscCall(PetscStrcmp(kind, "friction", &isFriction));
  PetscCall(PetscStrcmp(kind, "law", &isLaw));
  PetscCall(PetscStrcmp(kind, "operator", &isOperator));

  /* K: a spring of 1e3 from each dof to the ground, 1e2 between the dofs of neighbouring nodes; b presses every node */
  PetscCall(MatCreateAIJ(PETSC_COMM_WORLD, 3 * NODES, 3 * NODES, PETSC_DETERMINE, PETSC_DETERMINE, 3, NULL, 3, NULL, &K));
  PetscCall(MatGetOwnershipRange(K, &lo, &hi));
  for (PetscInt r = lo; r < hi; r++) {
    PetscCall(MatSetValue(K, r, r, 1.2e3, ADD_VALUES));
    if (r + 3 < 6 * NODES) {
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

  /* the contact nodes: every node of the rank (rank 0's last one straddles: its last dof is rank 1's first) */
  for (PetscInt k = 0; k < 3 * NODES; k++) dofs[k] = lo + k;
  if (isStraddle && rank == 0) dofs[3 * NODES - 1] = hi;
  PetscCall(ISCreateGeneral(PETSC_COMM_WORLD, 3 * NODES, dofs, PETSC_COPY_VALUES, &is));
  PetscCall(VecCreateMPI(PETSC_COMM_WORLD, isNormals && rank == 1 ? 3 * NODES - 1 : 3 * NODES, PETSC_DETERMINE, &normals));
  {
    PetscScalar *a;
    PetscInt     n;

    PetscCall(VecGetLocalSize(normals, &n));
    PetscCall(VecGetArrayWrite(normals, &a));
    for (PetscInt k = 0; k < n; k++) a[k] = k % 3 == 2 ? 1.0 : 0.0; /* (0, 0, 1) */
    PetscCall(VecRestoreArrayWrite(normals, &a));
  }
  PetscCall(VecCreateMPI(PETSC_COMM_WORLD, NODES, PETSC_DETERMINE, &friction));
  PetscCall(VecSet(friction, 0.3));
  if (isFriction && rank == 1) {
    PetscScalar *a;

    PetscCall(VecGetArray(friction, &a));
    a[2] = -0.5;
    PetscCall(VecRestoreArray(friction, &a));
  }
  PetscCall(SSStarLawGetIndex(SSSTARLAWCOULOMB, &coulomb));
  for (PetscInt i = 0; i < NODES; i++) laws[i] = isLaw && rank == 1 && i == 1 ? 99 : coulomb;
  if (isOperator) { /* B = the identity at each point's own dofs, but twice the identity's first row at rank 1's node 2 */
    PetscInt start;

    PetscCall(MatCreateAIJ(PETSC_COMM_WORLD, 3 * NODES, 3 * NODES, PETSC_DETERMINE, PETSC_DETERMINE, 1, NULL, 0, NULL, &B));
    PetscCall(MatGetOwnershipRange(B, &start, NULL));
    for (PetscInt k = 0; k < 3 * NODES; k++) PetscCall(MatSetValue(B, start + k, dofs[k], rank == 1 && k == 6 ? 2.0 : 1.0, INSERT_VALUES));
    PetscCall(MatAssemblyBegin(B, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(B, MAT_FINAL_ASSEMBLY));
  }

  PetscCall(SNESCreate(PETSC_COMM_WORLD, &snes));
  PetscCall(SNESSetType(snes, SNESSSSTAR));
  PetscCall(SNESSSStarSetLinearProblem(snes, K, b));
  PetscCall(SNESSetFromOptions(snes));
  if (catchErrors) PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  ierr = B ? SNESSSStarSetContactOperator(snes, is, B, NULL) : SNESSSStarSetContactNodes(snes, is, normals, NULL);
  if (!ierr) ierr = SNESSSStarSetNodeLawParameter(snes, "friction", friction);
  if (!ierr) ierr = SNESSSStarSetNodeFrictionLaws(snes, NODES, laws);
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

    PetscCall(SNESGetConvergedReason(snes, &reason));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s\n", SNESConvergedReasons[reason]));
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
