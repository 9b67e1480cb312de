static const char help[] = "The Newton phase of ssstar without the Schur step: loads P and f from a file written by\n\
examples/prism -save_reduced and solves the reduced problem from u = 0, repeatedly, timing the event SSStarNS.\n\
  -file <P.bin>           the file of examples/prism -save_reduced (P, then f)\n\
  -level <0>              the level it was written for (printed only)\n\
  -repeat <3>             solves; one CSV line per solve and the median\n\
  -csv_header <true>      print the header of the CSV lines\n\
Any -snes_ssstar_* option applies (-snes_ssstar_lu_reuse, -snes_ssstar_lu_threads, -snes_ssstar_newton_ksp_*).\n";

#include <ssstar.h>

PETSC_EXTERN PetscLogEvent SSSTAR_NewtonStep;

/* P dense and f, the rows split by whole nodes */
static PetscErrorCode ReadReducedProblem(const char file[], Mat *P, Vec *f)
{
  PetscViewer viewer;
  PetscInt    header[4], N, nodes = PETSC_DECIDE, Nnodes;

  PetscFunctionBeginUser;
  PetscCall(PetscViewerBinaryOpen(PETSC_COMM_WORLD, file, FILE_MODE_READ, &viewer));
  PetscCall(PetscViewerBinaryRead(viewer, header, 4, NULL, PETSC_INT)); /* MAT_FILE_CLASSID, rows, columns, nonzeros */
  PetscCall(PetscViewerDestroy(&viewer));
  PetscCheck(header[0] == MAT_FILE_CLASSID && header[1] == header[2] && header[1] % 3 == 0, PETSC_COMM_WORLD, PETSC_ERR_FILE_UNEXPECTED, "%s does not start with a square matrix of 3 dofs per node", file);
  N      = header[1];
  Nnodes = N / 3;
  PetscCall(PetscSplitOwnership(PETSC_COMM_WORLD, &nodes, &Nnodes));
  PetscCall(PetscViewerBinaryOpen(PETSC_COMM_WORLD, file, FILE_MODE_READ, &viewer));
  PetscCall(MatCreate(PETSC_COMM_WORLD, P));
  PetscCall(MatSetSizes(*P, 3 * nodes, 3 * nodes, N, N));
  PetscCall(MatSetType(*P, MATDENSE));
  PetscCall(MatLoad(*P, viewer));
  PetscCall(VecCreate(PETSC_COMM_WORLD, f));
  PetscCall(VecSetSizes(*f, 3 * nodes, N));
  PetscCall(VecLoad(*f, viewer));
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
  PetscInt    level = 0, repeat = 3;
  char        file[PETSC_MAX_PATH_LEN] = "P.bin";
  PetscBool   header = PETSC_TRUE;
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
  PetscCall(PetscOptionsGetString(NULL, NULL, "-file", file, sizeof(file), NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-csv_header", &header, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-snes_ssstar_lu_reuse", &reuse, NULL));
  PetscCheck(repeat >= 1 && repeat <= 64, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-repeat %" PetscInt_FMT ": 1 to 64", repeat);
  PetscCall(ReadReducedProblem(file, &P, &f));
  PetscCall(VecDuplicate(f, &u));

  PetscCall(SNESCreate(PETSC_COMM_WORLD, &snes));
  PetscCall(SNESSetType(snes, SNESSSSTAR));
  PetscCall(SNESSSStarSetLinearProblem(snes, P, f));
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
