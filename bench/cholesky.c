static const char help[] = "The yardstick of the Schur reduction (bench/schur.py): one plain Cholesky factorization of the whole\n\
stiffness K of the prism, by PETSc's MUMPS with its own ordering (-mat_mumps_icntl_7 to choose another), timed.\n\
  -level <6>     mesh level of meshes/prism.geo (the prism scene's K: run with -options_file scenes/prism.opts)\n\
Prints: cholesky level <L> ranks <R> dofs <N> time <s> flops <MUMPS RINFOG(3)>\n";

#include <ssstar.h>
#include <ssstarcontact.h>

int main(int argc, char **argv)
{
  SSStarScene    scene;
  PetscInt       level = 6, N, infog1;
  PetscReal      flops;
  PetscLogDouble t0, t1;
  Vec            b;
  Mat            K, F;
  KSP            ksp;
  PC             pc;
  PetscMPIInt    size;

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(SSStarInitializePackage());
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-level", &level, NULL));
  PetscCall(SSStarSceneCreate(PETSC_COMM_WORLD, &scene));
  PetscCall(SSStarSceneSetFromOptions(scene));
  PetscCall(SSStarSceneSetUp(scene));
  PetscCall(SSStarSceneAssemble(scene, &K, &b));
  PetscCall(MatGetSize(K, &N, NULL));
  PetscCall(MatSetOption(K, MAT_SPD, PETSC_TRUE));

  PetscCall(KSPCreate(PETSC_COMM_WORLD, &ksp));
  PetscCall(KSPSetOperators(ksp, K, K));
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCCHOLESKY));
  PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  PetscCall(KSPSetFromOptions(ksp));
  PetscCallMPI(MPI_Barrier(PETSC_COMM_WORLD));
  PetscCall(PetscTime(&t0));
  PetscCall(KSPSetUp(ksp));
  PetscCall(PetscTime(&t1));
  PetscCall(PCFactorGetMatrix(pc, &F));
  PetscCall(MatMumpsGetInfog(F, 1, &infog1));
  PetscCheck(infog1 >= 0, PETSC_COMM_WORLD, PETSC_ERR_LIB, "The MUMPS Cholesky factorization of K failed: INFOG(1) = %" PetscInt_FMT, infog1);
  PetscCall(MatMumpsGetRinfog(F, 3, &flops));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "cholesky level %" PetscInt_FMT " ranks %d dofs %" PetscInt_FMT " time %.3f flops %.4e\n", level, size, N, t1 - t0, (double)flops));

  PetscCall(KSPDestroy(&ksp));
  PetscCall(MatDestroy(&K));
  PetscCall(VecDestroy(&b));
  PetscCall(SSStarSceneDestroy(&scene));
  PetscCall(PetscFinalize());
  return 0;
}
