static const char help[] = "The yardstick of the Schur reduction (bench/schur.py): one plain Cholesky factorization of the whole\n\
stiffness K of the prism, by PETSc's MUMPS with its own ordering (-mat_mumps_icntl_7 to choose another), timed.\n\
  -level <6>     mesh level of meshes/prism.geo\n\
Prints: cholesky level <L> ranks <R> dofs <N> time <s> flops <MUMPS RINFOG(3)>\n";

#include <ssstar.h>
#include <ssstarcontact.h>

#ifndef SSSTAR_MESH_DIR
  #define SSSTAR_MESH_DIR "meshes"
#endif

int main(int argc, char **argv)
{
  SSStarScene    scene = {2.1e5, 0.3, {0, 0, -500}, {-200, 30, 200}};
  PetscInt       level = 6, N, infog1;
  PetscReal      flops;
  PetscLogDouble t0, t1;
  char           mesh[PETSC_MAX_PATH_LEN];
  DM             dm;
  Vec            tags, b;
  Mat            K, F;
  KSP            ksp;
  PC             pc;
  PetscMPIInt    size;

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(SSStarInitializePackage());
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-level", &level, NULL));
  PetscCall(PetscSNPrintf(mesh, sizeof(mesh), "%s/prism_L%" PetscInt_FMT ".msh", SSSTAR_MESH_DIR, level));
  PetscCall(SSStarMeshGeneratePrism(PETSC_COMM_WORLD, SSSTAR_MESH_DIR "/prism.geo", level, mesh));
  PetscCall(SSStarMeshLoad(PETSC_COMM_WORLD, mesh, &dm, &tags));
  PetscCall(SSStarAssembleElasticity(dm, &scene, &K, &b));
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
  PetscCall(VecDestroy(&tags));
  PetscCall(DMDestroy(&dm));
  PetscCall(PetscFinalize());
  return 0;
}
