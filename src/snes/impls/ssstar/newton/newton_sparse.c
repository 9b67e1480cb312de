/*
   The Newton step with a sparse P (a reduced problem given by the user): A R = gamma S R P + T R, the matrix of du
   (global frame), is formed by MatMatMult and factored by the SNES's KSP (default LU; MUMPS on several ranks).
*/
#include "newtonimpl.h"

typedef struct {
  Mat S, T;  /* S' = S R and T' = T R, block diagonal with a fixed 3x3 pattern */
  Mat SP, M; /* S' P and the Newton matrix                                   */
} Newton_Sparse;

static PetscErrorCode SSStarNewtonSetUp_Sparse(SSStarNewton nt)
{
  Newton_Sparse *sp = (Newton_Sparse *)nt->data;
  Mat            P  = nt->A;
  PetscInt       n, N;
  PC             pc;
  MatSolverType  solver;
  PetscMPIInt    size;

  PetscFunctionBegin;
  PetscCall(MatGetLocalSize(P, &n, NULL));
  PetscCall(MatGetSize(P, &N, NULL));
  PetscCall(MatCreateAIJ(PetscObjectComm((PetscObject)P), n, n, N, N, 3, NULL, 0, NULL, &sp->S));
  PetscCall(MatSetBlockSize(sp->S, 3));
  PetscCall(MatSetOption(sp->S, MAT_IGNORE_ZERO_ENTRIES, PETSC_FALSE));
  PetscCall(MatDuplicate(sp->S, MAT_DO_NOT_COPY_VALUES, &sp->T));
  PetscCall(SSStarNewtonSetKSPDefaults(nt, KSPPREONLY, PCLU));
  PetscCall(KSPGetPC(nt->snes->ksp, &pc));
  PetscCall(PCFactorGetMatSolverType(pc, &solver));
  PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)P), &size));
  if (!solver && size > 1) PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  PetscFunctionReturn(0);
}

/*
   Sets up the KSP (the LU factorization of the Newton matrix). Some LU factorizations raise an error on a zero pivot
   where others only flag it: catch that error so that a singular Newton matrix ends the solve with
   SNES_DIVERGED_LINEAR_SOLVE instead of aborting the program.
*/
static PetscErrorCode FactorNewtonMatrix(SNES snes, PetscBool *factored)
{
  PetscErrorCode ierr;
  PetscBool      ok;

  PetscFunctionBegin;
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  ierr = KSPSetUp(snes->ksp);
  PetscCall(PetscPopErrorHandler());
  if (ierr != PETSC_ERR_MAT_LU_ZRPVT && ierr != PETSC_ERR_LIB) PetscCall(ierr);
  ok = (PetscBool)(ierr == 0);
  PetscCall(MPIU_Allreduce(&ok, factored, 1, MPIU_BOOL, MPI_LAND, PetscObjectComm((PetscObject)snes)));
  if (!*factored) PetscCall(KSPReset(snes->ksp)); /* the next Newton matrix gets a fresh factorization */
  PetscFunctionReturn(0);
}

/* M' = M R per node (R NULL: identity) */
static void RightMultiply(const PetscReal M[9], const PetscReal *R, PetscReal out[9])
{
  for (PetscInt r = 0; r < 3; r++)
    for (PetscInt c = 0; c < 3; c++) {
      out[3 * r + c] = 0;
      for (PetscInt k = 0; k < 3; k++) out[3 * r + c] += M[3 * r + k] * (R ? R[3 * k + c] : (PetscReal)(k == c));
    }
}

static PetscErrorCode AssembleBlocks(SSStarNewton nt, const PetscReal S[], const PetscReal T[])
{
  Newton_Sparse   *sp     = (Newton_Sparse *)nt->data;
  const PetscReal *frames = nt->layout.frames;
  PetscInt         rstart, rend;

  PetscFunctionBegin;
  PetscCall(MatGetOwnershipRange(sp->S, &rstart, &rend));
  for (PetscInt i = 0; i < (rend - rstart) / 3; i++) {
    const PetscInt   idx[3] = {rstart + 3 * i, rstart + 3 * i + 1, rstart + 3 * i + 2};
    const PetscReal *R      = frames ? &frames[9 * i] : NULL;
    PetscReal        SR[9], TR[9];

    RightMultiply(&S[9 * i], R, SR);
    RightMultiply(&T[9 * i], R, TR);
    PetscCall(MatSetValues(sp->S, 3, idx, 3, idx, SR, INSERT_VALUES));
    PetscCall(MatSetValues(sp->T, 3, idx, 3, idx, TR, INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(sp->S, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(sp->S, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyBegin(sp->T, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(sp->T, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

/* (gamma S R P + T R) du = y */
static PetscErrorCode SSStarNewtonSolve_Sparse(SSStarNewton nt, const PetscReal S[], const PetscReal T[], Vec y, Vec du, PetscBool *solved)
{
  Newton_Sparse     *sp   = (Newton_Sparse *)nt->data;
  SNES               snes = nt->snes;
  KSPConvergedReason kspreason;
  PetscLogDouble     t0, t1;

  PetscFunctionBegin;
  PetscCall(AssembleBlocks(nt, S, T));
  PetscCall(MatMatMult(sp->S, nt->A, sp->SP ? MAT_REUSE_MATRIX : MAT_INITIAL_MATRIX, PETSC_DEFAULT, &sp->SP));
  if (!sp->M) {
    PetscCall(MatDuplicate(sp->SP, MAT_COPY_VALUES, &sp->M));
    PetscCall(MatScale(sp->M, nt->gamma));
    PetscCall(MatAXPY(sp->M, 1.0, sp->T, DIFFERENT_NONZERO_PATTERN));
  } else {
    PetscCall(MatCopy(sp->SP, sp->M, SUBSET_NONZERO_PATTERN));
    PetscCall(MatScale(sp->M, nt->gamma));
    PetscCall(MatAXPY(sp->M, 1.0, sp->T, SUBSET_NONZERO_PATTERN));
  }
  PetscCall(KSPSetOperators(snes->ksp, sp->M, sp->M));
  PetscCall(PetscTime(&t0));
  PetscCall(FactorNewtonMatrix(snes, solved));
  PetscCall(PetscTime(&t1));
  nt->factorSeconds += t1 - t0;
  nt->nFactor++;
  if (!*solved) PetscFunctionReturn(0);
  PetscCall(KSPSolve(snes->ksp, y, du));
  PetscCall(KSPGetConvergedReason(snes->ksp, &kspreason));
  *solved = (PetscBool)(kspreason >= 0);
  /* a failed MUMPS factorization cannot be redone (its INFOG(1) stays negative): the next one starts afresh */
  if (!*solved) PetscCall(KSPReset(snes->ksp));
  PetscFunctionReturn(0);
}

static PetscErrorCode SSStarNewtonView_Sparse(SSStarNewton nt, PetscViewer viewer)
{
  PetscFunctionBegin;
  PetscCall(PetscViewerASCIIPrintf(viewer, "  Newton step (sparse P): (gamma S P + T) du = (S + T) z formed and solved by the KSP below\n"));
  PetscCall(PetscViewerASCIIPrintf(viewer, "    last solve: %" PetscInt_FMT " factorizations\n", nt->nFactor));
  PetscFunctionReturn(0);
}

static PetscErrorCode SSStarNewtonReset_Sparse(SSStarNewton nt)
{
  Newton_Sparse *sp = (Newton_Sparse *)nt->data;

  PetscFunctionBegin;
  PetscCall(MatDestroy(&sp->S));
  PetscCall(MatDestroy(&sp->T));
  PetscCall(MatDestroy(&sp->SP));
  PetscCall(MatDestroy(&sp->M));
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarNewtonCreate_Sparse(SSStarNewton nt)
{
  Newton_Sparse *sp;

  PetscFunctionBegin;
  nt->snes->usesksp = PETSC_TRUE; /* the SNES's KSP solves the Newton systems */
  PetscCall(PetscNew(&sp));
  nt->data      = sp;
  nt->ops.setup = SSStarNewtonSetUp_Sparse;
  nt->ops.solve = SSStarNewtonSolve_Sparse;
  nt->ops.view  = SSStarNewtonView_Sparse;
  nt->ops.reset = SSStarNewtonReset_Sparse;
  PetscFunctionReturn(0);
}
