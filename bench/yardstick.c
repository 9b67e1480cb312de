static const char help[] = "The yardsticks of the benchmarks: one plain Cholesky factorization of the whole stiffness K of a scene\n\
(PETSc's MUMPS with its own ordering; -mat_mumps_icntl_7 to choose another), and one solve of K u = b by CG with\n\
algebraic multigrid (PCGAMG with K's near-null space, the rigid-body modes; rtol 1e-8), each timed.\n\
  -level <6>                  mesh level of the scene (run with -options_file scenes/prism.opts)\n\
  -yardstick <cholesky,amg>   which of them\n\
  -amg_w_levels <n>           amg: W-cycles on the n finest levels of the multigrid, V below (as ssstar's, n = 2)\n\
  -amg_overcorrection <alpha> amg: the coarse corrections into the W-cycled levels times alpha (ssstar's\n\
                              -snes_ssstar_mg_overcorrection; the levers on K alone, docs/guide/scale.md)\n\
Prints: cholesky level <L> ranks <R> dofs <N> time <s> flops <MUMPS RINFOG(3)>\n\
        amg level <L> ranks <R> dofs <N> setup <s> solve <s> its <n>\n\
        peak <GB> GB per rank (the largest rank's VmHWM: mesh, K and the yardsticks)\n";

#include <ssstar.h>
#include <ssstarscene.h>

static PetscErrorCode Cholesky(Mat K, PetscInt level)
{
  PetscInt       N, infog1;
  PetscReal      flops;
  PetscLogDouble t0, t1;
  Mat            F;
  KSP            ksp;
  PC             pc;
  PetscMPIInt    size;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCall(MatGetSize(K, &N, NULL));
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
  PetscFunctionReturn(0);
}

/* ssstar's cycle on the multigrid set up: W-cycles on the wLevels finest levels, their coarse corrections times alpha */
static PetscErrorCode CycleLevers(PC pc)
{
  PetscInt  wLevels = 0, nlevels;
  PetscReal alpha   = 1;
  PetscBool set;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-amg_w_levels", &wLevels, &set));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-amg_overcorrection", &alpha, NULL));
  if (!set) PetscFunctionReturn(0);
  PetscCall(PCMGGetLevels(pc, &nlevels));
  for (PetscInt l = 1; l < nlevels; l++) {
    PetscCall(PCMGSetCycleTypeOnLevel(pc, l, l >= nlevels - wLevels ? PC_MG_CYCLE_W : PC_MG_CYCLE_V));
    if (l >= nlevels - wLevels && alpha != 1) {
      Mat P;

      PetscCall(PCMGGetInterpolation(pc, l, &P));
      PetscCall(MatScale(P, PetscSqrtReal(alpha)));
    }
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode AMG(Mat K, Vec b, PetscInt level)
{
  PetscInt           N, its;
  PetscLogDouble     t0, t1, t2;
  KSP                ksp;
  PC                 pc;
  Vec                u;
  PetscMPIInt        size;
  KSPConvergedReason reason;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCall(MatGetSize(K, &N, NULL));
  PetscCall(VecDuplicate(b, &u));
  PetscCall(KSPCreate(PETSC_COMM_WORLD, &ksp));
  PetscCall(KSPSetOptionsPrefix(ksp, "amg_"));
  PetscCall(KSPSetOperators(ksp, K, K));
  PetscCall(KSPSetType(ksp, KSPCG));
  PetscCall(KSPSetTolerances(ksp, 1e-8, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCGAMG));
  PetscCall(KSPSetFromOptions(ksp));
  PetscCallMPI(MPI_Barrier(PETSC_COMM_WORLD));
  PetscCall(PetscTime(&t0));
  PetscCall(KSPSetUp(ksp));
  PetscCall(CycleLevers(pc));
  PetscCall(PetscTime(&t1));
  PetscCall(KSPSolve(ksp, b, u));
  PetscCall(PetscTime(&t2));
  PetscCall(KSPGetConvergedReason(ksp, &reason));
  PetscCheck(reason > 0, PETSC_COMM_WORLD, PETSC_ERR_NOT_CONVERGED, "The AMG solve of K did not converge: %s", KSPConvergedReasons[reason]);
  PetscCall(KSPGetIterationNumber(ksp, &its));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "amg level %" PetscInt_FMT " ranks %d dofs %" PetscInt_FMT " setup %.3f solve %.3f its %" PetscInt_FMT "\n", level, size, N, t1 - t0, t2 - t1, its));
  PetscCall(KSPDestroy(&ksp));
  PetscCall(VecDestroy(&u));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  SSStarScene scene;
  PetscInt    level = 6, n = 2;
  char       *which[2] = {NULL, NULL};
  PetscBool   given;
  Vec         b;
  Mat         K;

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(SSStarInitializePackage());
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-level", &level, NULL));
  PetscCall(PetscOptionsGetStringArray(NULL, NULL, "-yardstick", which, &n, NULL));
  PetscCall(SSStarSceneCreate(PETSC_COMM_WORLD, &scene));
  PetscCall(SSStarSceneSetFromOptions(scene));
  PetscCall(SSStarSceneSetUp(scene));
  PetscCall(SSStarSceneAssemble(scene, &K, &b));
  PetscCall(MatSetOption(K, MAT_SPD, PETSC_TRUE));
  given = (PetscBool)(which[0] != NULL); /* before the loop frees the names */
  if (!given) n = 2;
  for (PetscInt k = 0; k < n; k++) {
    const char *name = given ? which[k] : (k ? "amg" : "cholesky");
    PetscBool   cholesky, amg;

    PetscCall(PetscStrcmp(name, "cholesky", &cholesky));
    PetscCall(PetscStrcmp(name, "amg", &amg));
    PetscCheck(cholesky || amg, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-yardstick %s: not cholesky or amg", name);
    if (cholesky) PetscCall(Cholesky(K, level));
    else PetscCall(AMG(K, b, level));
    PetscCall(PetscFree(which[k]));
  }
  {
    PetscLogDouble peak;

    PetscCall(SSStarMemoryGetUsage(PETSC_COMM_WORLD, NULL, &peak));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "peak %.3f GB per rank\n", peak / 1e9));
  }
  PetscCall(MatDestroy(&K));
  PetscCall(VecDestroy(&b));
  PetscCall(SSStarSceneDestroy(&scene));
  PetscCall(PetscFinalize());
  return 0;
}
