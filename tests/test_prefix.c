static const char help[] = "An ssstar SNES with an options prefix (tests/suite_solver.py): the options of its reduction's solvers take\n\
the SNES's prefix (-foo_schur_direct_mumps_icntl_<i>, -foo_schur_mat_mumps_*, -foo_interior_ksp_*).\n\
  -prefix <foo_>   the SNES's prefix\n";

/*
   Requirement: a SNES with the prefix foo_ reads -foo_snes_ssstar_reduction and passes its prefix to the reduction, whose
   solvers read -foo_schur_... and -foo_interior_...; the unprefixed names are not read. A chain of 8 nodes per rank
   tied by springs to the ground and to their neighbours, half of them contact nodes pressed onto the plane z = 0.
*/
#include <ssstar.h>

#define NODES 8 /* per rank */

int main(int argc, char **argv)
{
  char                prefix[64] = "foo_";
  PetscInt            lo, hi, dofs[3 * NODES], n = 0;
  Mat                 K;
  Vec                 b, u;
  IS                  is;
  SNES                snes;
  SNESConvergedReason reason;
  SSStarReductionType type;

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(SSStarInitializePackage());
  PetscCall(PetscOptionsGetString(NULL, NULL, "-prefix", prefix, sizeof(prefix), NULL));
  PetscCall(MatCreateAIJ(PETSC_COMM_WORLD, 3 * NODES, 3 * NODES, PETSC_DETERMINE, PETSC_DETERMINE, 3, NULL, 3, NULL, &K));
  PetscCall(MatGetOwnershipRange(K, &lo, &hi));
  for (PetscInt r = lo; r < hi; r++) {
    PetscInt N;

    PetscCall(MatGetSize(K, &N, NULL));
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
  for (PetscInt i = 0; i < NODES; i += 2)
    for (PetscInt k = 0; k < 3; k++) dofs[n++] = lo + 3 * i + k;
  PetscCall(ISCreateGeneral(PETSC_COMM_WORLD, n, dofs, PETSC_COPY_VALUES, &is));

  PetscCall(SNESCreate(PETSC_COMM_WORLD, &snes));
  PetscCall(SNESSetOptionsPrefix(snes, prefix));
  PetscCall(SNESSetType(snes, SNESSSSTAR));
  PetscCall(SNESSSStarSetLinearProblem(snes, K, b));
  PetscCall(SNESSSStarSetContactNodes(snes, is, NULL, NULL));
  PetscCall(SNESSetFromOptions(snes));
  PetscCall(SNESSolve(snes, NULL, u));
  PetscCall(SNESGetConvergedReason(snes, &reason));
  PetscCall(SNESSSStarGetReductionType(snes, &type));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s with the reduction %s\n", SNESConvergedReasons[reason], type));
  PetscCall(SNESDestroy(&snes));
  PetscCall(MatDestroy(&K));
  PetscCall(VecDestroy(&b));
  PetscCall(VecDestroy(&u));
  PetscCall(ISDestroy(&is));
  PetscCall(PetscFinalize());
  return reason > 0 ? 0 : SSSTAR_EXIT_NOT_CONVERGED;
}
