static const char help[] = "The Newton phase of ssstar on the prism's reduced problem, without the Schur step: P and f of a level are\n\
computed once (whole-body solve through examples/prism's path) and kept in a PETSc binary file; every run then\n\
loads them and solves the reduced problem from u = 0, repeatedly, timing the event SSStarNS.\n\
  -level <10>             prism level\n\
  -data <bench/output/data> folder of the files P_L<level>.bin\n\
  -repeat <3>             solves; one line per solve and the medians\n\
  -csv_header <true>      print the header of the CSV lines\n\
Any -snes_ssstar_* option applies (-snes_ssstar_lu_reuse, -snes_ssstar_newton_ksp_*).\n";

#include <ssstar.h>
#include <ssstarcontact.h>

#ifndef SSSTAR_MESH_DIR
  #define SSSTAR_MESH_DIR "meshes"
#endif

PETSC_EXTERN PetscLogEvent SSSTAR_NewtonStep;

typedef struct {
  Mat K;
  Vec b;
} Body;

static PetscErrorCode FormFunction(SNES snes, Vec u, Vec r, void *ctx)
{
  Body *body = (Body *)ctx;

  PetscFunctionBeginUser;
  PetscCall(MatMult(body->K, u, r));
  PetscCall(VecAXPY(r, -1.0, body->b));
  PetscFunctionReturn(0);
}

static PetscErrorCode FormJacobian(SNES snes, Vec u, Mat J, Mat Jpre, void *ctx)
{
  PetscFunctionBeginUser;
  PetscFunctionReturn(0); /* K, assembled once (without a routine SNESSetUp() would install finite differences) */
}

/* P, f of the prism at this level (the default scene), as the whole-body solve computes them, written to file */
static PetscErrorCode WriteReducedProblem(PetscInt level, const char file[])
{
  SSStarScene        scene = {2.1e5, 0.3, {0, 0, -500}, {-200, 30, 200}};
  char               msh[PETSC_MAX_PATH_LEN];
  DM                 dm;
  Vec                tags, u, f;
  Mat                P;
  Body               body;
  SSStarContactNodes cn;
  SNES               snes;
  PetscViewer        viewer;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(msh, sizeof(msh), "%s/prism_L%" PetscInt_FMT ".msh", SSSTAR_MESH_DIR, level));
  PetscCall(SSStarMeshGeneratePrism(PETSC_COMM_WORLD, SSSTAR_MESH_DIR "/prism.geo", level, msh));
  PetscCall(SSStarMeshLoad(PETSC_COMM_WORLD, msh, &dm, &tags));
  PetscCall(SSStarAssembleElasticity(dm, &scene, &body.K, &body.b));
  PetscCall(SSStarContactNodesCreate(dm, tags, &cn));
  PetscCall(SNESCreate(PETSC_COMM_WORLD, &snes));
  PetscCall(SNESSetType(snes, SNESSSSTAR));
  PetscCall(SNESSetFunction(snes, NULL, FormFunction, &body));
  PetscCall(SNESSetJacobian(snes, body.K, body.K, FormJacobian, NULL));
  PetscCall(SNESSSStarSetContactNodes(snes, cn.isC, NULL, NULL));
  PetscCall(SNESSetFromOptions(snes));
  PetscCall(SNESSetTolerances(snes, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT, 0, PETSC_DEFAULT));
  PetscCall(DMCreateGlobalVector(dm, &u));
  PetscCall(VecZeroEntries(u));
  PetscCall(SNESSolve(snes, NULL, u));
  PetscCall(SNESSSStarGetReducedProblem(snes, &P, &f));
  PetscCall(PetscViewerBinaryOpen(PETSC_COMM_WORLD, file, FILE_MODE_WRITE, &viewer));
  PetscCall(VecView(f, viewer));
  PetscCall(MatView(P, viewer));
  PetscCall(PetscViewerDestroy(&viewer));
  PetscCall(SNESDestroy(&snes));
  PetscCall(VecDestroy(&u));
  PetscCall(SSStarContactNodesDestroy(&cn));
  PetscCall(MatDestroy(&body.K));
  PetscCall(VecDestroy(&body.b));
  PetscCall(VecDestroy(&tags));
  PetscCall(DMDestroy(&dm));
  PetscFunctionReturn(0);
}

/* P dense and f, rows split by whole nodes */
static PetscErrorCode ReadReducedProblem(const char file[], Mat *P, Vec *f)
{
  PetscViewer viewer;
  PetscInt    N, nodes = PETSC_DECIDE, Nnodes;

  PetscFunctionBeginUser;
  PetscCall(PetscViewerBinaryOpen(PETSC_COMM_WORLD, file, FILE_MODE_READ, &viewer));
  PetscCall(VecCreate(PETSC_COMM_WORLD, f));
  PetscCall(VecLoad(*f, viewer)); /* for the size; then again with whole nodes on each rank */
  PetscCall(VecGetSize(*f, &N));
  PetscCall(VecDestroy(f));
  PetscCall(PetscViewerDestroy(&viewer));
  Nnodes = N / 3;
  PetscCall(PetscSplitOwnership(PETSC_COMM_WORLD, &nodes, &Nnodes));
  PetscCall(PetscViewerBinaryOpen(PETSC_COMM_WORLD, file, FILE_MODE_READ, &viewer));
  PetscCall(VecCreate(PETSC_COMM_WORLD, f));
  PetscCall(VecSetSizes(*f, 3 * nodes, N));
  PetscCall(VecLoad(*f, viewer));
  PetscCall(MatCreate(PETSC_COMM_WORLD, P));
  PetscCall(MatSetSizes(*P, 3 * nodes, 3 * nodes, N, N));
  PetscCall(MatSetType(*P, MATDENSE));
  PetscCall(MatLoad(*P, viewer));
  PetscCall(PetscViewerDestroy(&viewer));
  PetscFunctionReturn(0);
}

static int CompareReal(const void *a, const void *b)
{
  const PetscReal x = *(const PetscReal *)a, y = *(const PetscReal *)b;
  return x < y ? -1 : x > y;
}

int main(int argc, char **argv)
{
  PetscInt    level = 10, repeat = 3;
  char        dir[PETSC_MAX_PATH_LEN] = "bench/output/data", file[PETSC_MAX_PATH_LEN];
  PetscBool   header = PETSC_TRUE, exists;
  Mat         P;
  Vec         f, u;
  SNES        snes;
  PetscMPIInt size;
  PetscReal   times[64], reuse = 0;

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(SSStarInitializePackage());
  PetscCall(PetscLogDefaultBegin());
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-level", &level, NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-repeat", &repeat, NULL));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-data", dir, sizeof(dir), NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-csv_header", &header, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-snes_ssstar_lu_reuse", &reuse, NULL));
  PetscCheck(repeat >= 1 && repeat <= 64, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-repeat %" PetscInt_FMT ": 1 to 64", repeat);
  PetscCall(PetscSNPrintf(file, sizeof(file), "%s/P_L%" PetscInt_FMT ".bin", dir, level));
  PetscCall(PetscTestFile(file, 'r', &exists));
  if (!exists) {
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "# computing P, f of level %" PetscInt_FMT " into %s\n", level, file));
    PetscCall(PetscMkdir(dir));
    PetscCall(WriteReducedProblem(level, file));
  }
  PetscCall(ReadReducedProblem(file, &P, &f));
  PetscCall(VecDuplicate(f, &u));

  PetscCall(SNESCreate(PETSC_COMM_WORLD, &snes));
  PetscCall(SNESSetType(snes, SNESSSSTAR));
  PetscCall(SNESSSStarSetContactProblem(snes, P, f));
  PetscCall(SNESSetFromOptions(snes));
  if (header) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "level,ranks,dofs,lu_reuse,run,iterations,newton_seconds,lu,reused,krylov_its,reason\n"));
  for (PetscInt r = 0; r < repeat; r++) {
    PetscEventPerfInfo before, after;
    PetscInt           its, nlu, nreused, nkrylov, dofs;
    SNESConvergedReason reason;
    PetscReal          t;

    PetscCall(VecZeroEntries(u));
    PetscCall(PetscLogEventGetPerfInfo(PETSC_DETERMINE, SSSTAR_NewtonStep, &before));
    PetscCall(SNESSolve(snes, NULL, u));
    PetscCall(PetscLogEventGetPerfInfo(PETSC_DETERMINE, SSSTAR_NewtonStep, &after));
    t = after.time - before.time;
    PetscCall(MPIU_Allreduce(&t, &times[r], 1, MPIU_REAL, MPIU_MAX, PETSC_COMM_WORLD));
    PetscCall(SNESGetIterationNumber(snes, &its));
    PetscCall(VecGetSize(f, &dofs));
    PetscCall(SNESGetConvergedReason(snes, &reason));
    PetscCall(SNESSSStarGetNewtonStepCounts(snes, &nlu, &nreused, &nkrylov));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%" PetscInt_FMT ",%d,%" PetscInt_FMT ",%g,%" PetscInt_FMT ",%" PetscInt_FMT ",%.4f,%" PetscInt_FMT ",%" PetscInt_FMT ",%" PetscInt_FMT ",%s\n", level, size, dofs, (double)reuse, r, its, (double)times[r], nlu, nreused, nkrylov, SNESConvergedReasons[reason]));
  }
  qsort(times, repeat, sizeof(PetscReal), CompareReal);
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "# median Newton phase %.4f s over %" PetscInt_FMT " solves\n", (double)times[repeat / 2], repeat));
  PetscCall(SNESDestroy(&snes));
  PetscCall(VecDestroy(&u));
  PetscCall(VecDestroy(&f));
  PetscCall(MatDestroy(&P));
  PetscCall(PetscFinalize());
  return 0;
}
