/*
   The Newton step of ssstar (DERIVATION.md section 5) in the nodes' frames: with v = R u,
     (gamma S R P R^T + T) dv = y,   i.e.   (gamma S' P + T') du = y  with  S' = S R, T' = T R, dv = R du.
   A = gamma S' P + T' is formed (S' and T' block diagonal) and factored by the SNES's KSP (LU by default):
   LAPACK for a dense P on one rank, ScaLAPACK on several, MUMPS for a sparse P.
*/
#include "ssstarimpl.h"

struct _n_SSStarNewton {
  SNES       snes;
  Mat        P;
  PetscReal  gamma;
  Mat        S, T;      /* S' and T', block diagonal with a fixed 3x3 pattern (S' P is recomputed in place) */
  Mat        SP, A;     /* S' P and A                                                                        */
  PetscBool  scalapack; /* A is distributed dense: factor a MATSCALAPACK copy                                 */
  Mat        Ascalapack;
  Vec        yScalapack, duScalapack;
  VecScatter toScalapack;
};

PetscErrorCode SSStarNewtonCreate(SNES snes, SSStarNewton *newton)
{
  PetscFunctionBegin;
  PetscCall(PetscNew(newton));
  (*newton)->snes = snes;
  PetscFunctionReturn(0);
}

static PetscErrorCode SSStarNewtonReset(SSStarNewton nt)
{
  PetscFunctionBegin;
  PetscCall(MatDestroy(&nt->P));
  PetscCall(MatDestroy(&nt->S));
  PetscCall(MatDestroy(&nt->T));
  PetscCall(MatDestroy(&nt->SP));
  PetscCall(MatDestroy(&nt->A));
  PetscCall(MatDestroy(&nt->Ascalapack));
  PetscCall(VecDestroy(&nt->yScalapack));
  PetscCall(VecDestroy(&nt->duScalapack));
  PetscCall(VecScatterDestroy(&nt->toScalapack));
  PetscFunctionReturn(0);
}

/* P (global frame) and gamma; everything built from an earlier P is dropped */
PetscErrorCode SSStarNewtonSetOperator(SSStarNewton nt, Mat P, PetscReal gamma)
{
  SNES          snes = nt->snes;
  PetscInt      n, N;
  PC            pc;
  MatSolverType solver;
  PetscMPIInt   size;
  PetscBool     isdense;

  PetscFunctionBegin;
  nt->gamma = gamma;
  if (P == nt->P) PetscFunctionReturn(0);
  PetscCall(SSStarNewtonReset(nt));
  PetscCall(PetscObjectReference((PetscObject)P));
  nt->P = P;
  PetscCall(MatGetLocalSize(P, &n, NULL));
  PetscCall(MatGetSize(P, &N, NULL));
  PetscCall(MatCreateAIJ(PetscObjectComm((PetscObject)P), n, n, N, N, 3, NULL, 0, NULL, &nt->S));
  PetscCall(MatSetBlockSize(nt->S, 3));
  PetscCall(MatSetOption(nt->S, MAT_IGNORE_ZERO_ENTRIES, PETSC_FALSE));
  PetscCall(MatDuplicate(nt->S, MAT_DO_NOT_COPY_VALUES, &nt->T));

  /* SNESSetFromOptions() gave the KSP the user's Jacobian (K in the whole-body use), and PCSetFromOptions() may have made a factor for it */
  PetscCall(KSPReset(snes->ksp));
  PetscCall(KSPGetPC(snes->ksp, &pc));
  PetscCall(PCFactorGetMatSolverType(pc, &solver));
  PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)P), &size));
  PetscCall(PetscObjectTypeCompareAny((PetscObject)P, &isdense, MATDENSE, MATMPIDENSE, MATSEQDENSE, ""));
  /* parallel dense LU is ScaLAPACK's, on a MATSCALAPACK copy of A; parallel sparse LU is MUMPS's */
  nt->scalapack = (PetscBool)(size > 1 && isdense);
  if (!solver && size > 1 && !isdense) PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  PetscFunctionReturn(0);
}

/*
   Sets up the KSP (the LU factorization of the Newton matrix). Dense LU (LAPACK, ScaLAPACK) raises an error on a
   zero pivot where sparse LU only flags it: catch that error so that a singular Newton matrix ends the solve with
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

static PetscErrorCode AssembleBlocks(SSStarNewton nt, const PetscReal frames[], const PetscReal S[], const PetscReal T[])
{
  PetscInt rstart, rend;

  PetscFunctionBegin;
  PetscCall(MatGetOwnershipRange(nt->S, &rstart, &rend));
  for (PetscInt i = 0; i < (rend - rstart) / 3; i++) {
    const PetscInt idx[3] = {rstart + 3 * i, rstart + 3 * i + 1, rstart + 3 * i + 2};
    const PetscReal *R   = frames ? &frames[9 * i] : NULL;
    PetscReal        SR[9], TR[9];

    RightMultiply(&S[9 * i], R, SR);
    RightMultiply(&T[9 * i], R, TR);
    PetscCall(MatSetValues(nt->S, 3, idx, 3, idx, SR, INSERT_VALUES));
    PetscCall(MatSetValues(nt->T, 3, idx, 3, idx, TR, INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(nt->S, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(nt->S, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyBegin(nt->T, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(nt->T, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

/*
   Solves (gamma S R P + T R) du = y; solved is PETSC_FALSE (on every rank) when the Newton matrix is singular
   or the linear solve failed.
*/
PetscErrorCode SSStarNewtonSolve(SSStarNewton nt, const PetscReal frames[], const PetscReal S[], const PetscReal T[], Vec y, Vec du, PetscBool *solved)
{
  SNES               snes = nt->snes;
  KSPConvergedReason kspreason;

  PetscFunctionBegin;
  PetscCall(AssembleBlocks(nt, frames, S, T));
  PetscCall(MatMatMult(nt->S, nt->P, nt->SP ? MAT_REUSE_MATRIX : MAT_INITIAL_MATRIX, PETSC_DEFAULT, &nt->SP));
  if (!nt->A) {
    PetscCall(MatDuplicate(nt->SP, MAT_COPY_VALUES, &nt->A));
    PetscCall(MatScale(nt->A, nt->gamma));
    PetscCall(MatAXPY(nt->A, 1.0, nt->T, DIFFERENT_NONZERO_PATTERN));
  } else {
    PetscCall(MatCopy(nt->SP, nt->A, SUBSET_NONZERO_PATTERN));
    PetscCall(MatScale(nt->A, nt->gamma));
    PetscCall(MatAXPY(nt->A, 1.0, nt->T, SUBSET_NONZERO_PATTERN));
  }
  if (nt->scalapack) {
    /* MATSCALAPACK chooses its own row layout: move y and du to it and back */
    PetscCall(MatConvert(nt->A, MATSCALAPACK, nt->Ascalapack ? MAT_REUSE_MATRIX : MAT_INITIAL_MATRIX, &nt->Ascalapack));
    if (!nt->toScalapack) {
      PetscInt lo, hi;
      IS       own;

      PetscCall(MatCreateVecs(nt->Ascalapack, &nt->duScalapack, &nt->yScalapack));
      PetscCall(VecGetOwnershipRange(y, &lo, &hi));
      PetscCall(ISCreateStride(PETSC_COMM_SELF, hi - lo, lo, 1, &own));
      PetscCall(VecScatterCreate(y, own, nt->yScalapack, own, &nt->toScalapack));
      PetscCall(ISDestroy(&own));
    }
    PetscCall(KSPSetOperators(snes->ksp, nt->Ascalapack, nt->Ascalapack));
    PetscCall(FactorNewtonMatrix(snes, solved));
    if (!*solved) PetscFunctionReturn(0);
    PetscCall(VecScatterBegin(nt->toScalapack, y, nt->yScalapack, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterEnd(nt->toScalapack, y, nt->yScalapack, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(KSPSolve(snes->ksp, nt->yScalapack, nt->duScalapack));
    PetscCall(VecScatterBegin(nt->toScalapack, nt->duScalapack, du, INSERT_VALUES, SCATTER_REVERSE));
    PetscCall(VecScatterEnd(nt->toScalapack, nt->duScalapack, du, INSERT_VALUES, SCATTER_REVERSE));
  } else {
    PetscCall(KSPSetOperators(snes->ksp, nt->A, nt->A));
    PetscCall(FactorNewtonMatrix(snes, solved));
    if (!*solved) PetscFunctionReturn(0);
    PetscCall(KSPSolve(snes->ksp, y, du));
  }
  PetscCall(KSPGetConvergedReason(snes->ksp, &kspreason));
  *solved = (PetscBool)(kspreason >= 0);
  /* a failed MUMPS factorization cannot be redone (its INFOG(1) stays negative): the next one starts afresh */
  if (!*solved) PetscCall(KSPReset(snes->ksp));
  PetscFunctionReturn(0);
}

/* 1/cond of the last factored Newton matrix (an estimate), or -1 when the factorization gives none */
PetscErrorCode SSStarNewtonGetConditionEstimate(SSStarNewton nt, PetscReal *rcond)
{
  PetscFunctionBegin;
  *rcond = -1;
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarNewtonView(SSStarNewton nt, PetscViewer viewer)
{
  PetscFunctionBegin;
  PetscCall(PetscViewerASCIIPrintf(viewer, "  Newton step: (gamma S P + T) du = (S + T) z formed and factored by the KSP%s\n", nt && nt->scalapack ? " (ScaLAPACK copy)" : ""));
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarNewtonDestroy(SSStarNewton *nt)
{
  PetscFunctionBegin;
  if (!*nt) PetscFunctionReturn(0);
  PetscCall(SSStarNewtonReset(*nt));
  PetscCall(PetscFree(*nt));
  PetscFunctionReturn(0);
}
