/*
   The mumps reduction: one Cholesky factorization of the whole K with the Schur block C (PETSc's MUMPS, on rank 0)
   gives P, and its solves give f and u: x = K^-1 F has x_C = P^-1 f, so f = P x_C; K^-1 (F + E_C (P u_C - f)) = u.
*/
#include "reductionimpl.h"

typedef struct {
  Mat        Kfactor;      /* Cholesky of K with the Schur block C, on rank 0 */
  VecScatter toZero;       /* K's vectors to and from their copy on rank 0    */
  Vec        bZero, xZero;
} Reduction_MUMPS;

/*
   P by MUMPS's own Schur complement of the whole K (gathered on rank 0), then scattered by rows like isC. Rank 0
   holds two dense copies of P beside MUMPS (MUMPS's Schur block and the one created from it) and its scatter buffer.
*/
static PetscErrorCode ReduceMUMPS(SSStarReduction red, Mat K)
{
  Reduction_MUMPS     *mu   = (Reduction_MUMPS *)red->data;
  MPI_Comm             comm = PetscObjectComm((PetscObject)K);
  PetscMPIInt          size, rank;
  PetscInt             N, mC, NC, estimateMB = 0;
  PetscLogDouble       dense;
  IS                   isAll, isCall;
  Mat                 *Kseq, F = NULL, Sseq = NULL;
  MatFactorInfo        info;
  MatFactorSchurStatus status;
  const char          *what = "the MUMPS Cholesky factorization of K with a Schur complement (PETSc, rank 0)";
  char                 prefix[256], icntl[256];

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(MatGetSize(K, &N, NULL));
  PetscCall(ISGetLocalSize(red->isC, &mC));
  PetscCall(ISGetSize(red->isC, &NC));
  PetscCall(ISCreateStride(PETSC_COMM_SELF, rank ? 0 : N, 0, 1, &isAll));
  PetscCall(MatCreateSubMatrices(K, 1, &isAll, &isAll, MAT_INITIAL_MATRIX, &Kseq));
  PetscCall(ISDestroy(&isAll));
  PetscCall(ISAllGather(red->isC, &isCall));
  PetscCall(MatFactorInfoInitialize(&info));
  PetscCall(PetscSNPrintf(prefix, sizeof(prefix), "%sschur_", red->prefix ? red->prefix : ""));
  PetscCall(SSStarReductionOptionName(red, "schur_mat_mumps_icntl_", icntl, sizeof(icntl)));
  if (rank == 0) {
    PetscCall(MatSetOption(Kseq[0], MAT_SPD, PETSC_TRUE));
    PetscCall(MatGetFactor(Kseq[0], MATSOLVERMUMPS, MAT_FACTOR_CHOLESKY, &F));
    PetscCall(MatSetOptionsPrefix(F, prefix));
    PetscCall(MatSetFromOptions(F));
    PetscCall(MatFactorSetSchurIS(F, isCall));
    PetscCall(MatCholeskyFactorSymbolic(F, Kseq[0], NULL, &info));
  }
  PetscCall(SSStarReductionCheckFactor(comm, 0, F, 0, what, icntl));
  if (rank == 0) PetscCall(MatMumpsGetInfo(F, 15, &estimateMB));
  dense = 8.0 * NC * ((rank == 0 ? 2.0 * NC : 0) + (size > 1 ? 2.0 * mC : 0) + SSSTAR_DENSE_WORK * (PetscLogDouble)mC);
  PetscCall(SSStarReductionCheckMemory(comm, red->memoryLimit, 1e6 * (PetscLogDouble)estimateMB, dense, "The mumps Schur reduction"));
  if (rank == 0) PetscCall(MatCholeskyFactorNumeric(F, Kseq[0], &info));
  PetscCall(SSStarReductionCheckFactor(comm, 0, F, 1e6 * (PetscLogDouble)estimateMB, what, icntl));
  if (rank == 0) {
    PetscReal flops;

    PetscCall(MatMumpsGetRinfo(F, 3, &flops)); /* PETSc does not log MUMPS's flops */
    PetscCall(PetscLogFlops(flops));
    PetscCall(PetscInfo(K, "MUMPS factorization (PETSc, rank 0): %g flops\n", (double)flops));
    PetscCall(MatFactorCreateSchurComplement(F, &Sseq, &status));
    mu->Kfactor = F;
  }
  PetscCall(ISDestroy(&isCall));
  PetscCall(MatDestroyMatrices(1, &Kseq));

  if (size == 1) {
    red->P = Sseq;
  } else {
    /* P is symmetric: rows owned by rank r are the (contiguous) columns r0..r0+mC of the column-major Sseq */
    PetscMPIInt       *counts = NULL, *displs = NULL, cnt;
    const PetscScalar *sa     = NULL;
    PetscScalar       *buf, *pa;
    PetscInt           lda;

    PetscCall(MatCreateDense(comm, mC, mC, NC, NC, NULL, &red->P));
    PetscCall(PetscMPIIntCast(mC * NC, &cnt));
    if (rank == 0) PetscCall(PetscMalloc2(size, &counts, size, &displs));
    PetscCallMPI(MPI_Gather(&cnt, 1, MPI_INT, counts, 1, MPI_INT, 0, comm));
    if (rank == 0) {
      displs[0] = 0;
      for (PetscMPIInt r = 1; r < size; r++) displs[r] = displs[r - 1] + counts[r - 1];
      PetscCall(MatDenseGetArrayRead(Sseq, &sa));
    }
    PetscCall(PetscMalloc1(mC * NC, &buf));
    PetscCallMPI(MPI_Scatterv(sa, counts, displs, MPIU_SCALAR, buf, cnt, MPIU_SCALAR, 0, comm));
    if (rank == 0) {
      PetscCall(MatDenseRestoreArrayRead(Sseq, &sa));
      PetscCall(MatDestroy(&Sseq));
      PetscCall(PetscFree2(counts, displs));
    }
    PetscCall(MatDenseGetLDA(red->P, &lda));
    PetscCall(MatDenseGetArrayWrite(red->P, &pa));
    for (PetscInt i = 0; i < mC; i++)
      for (PetscInt j = 0; j < NC; j++) pa[j * lda + i] = buf[i * NC + j];
    PetscCall(MatDenseRestoreArrayWrite(red->P, &pa));
    PetscCall(PetscFree(buf));
    PetscCall(MatAssemblyBegin(red->P, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(red->P, MAT_FINAL_ASSEMBLY));
  }
  PetscFunctionReturn(0);
}

/* x = K^-1 b by the factor on rank 0 (mumps path) */
static PetscErrorCode SolveWholeK(SSStarReduction red, Vec b, Vec x)
{
  Reduction_MUMPS *mu = (Reduction_MUMPS *)red->data;

  PetscFunctionBegin;
  PetscCall(VecScatterBegin(mu->toZero, b, mu->bZero, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(mu->toZero, b, mu->bZero, INSERT_VALUES, SCATTER_FORWARD));
  if (mu->Kfactor) PetscCall(MatSolve(mu->Kfactor, mu->bZero, mu->xZero));
  PetscCall(VecScatterBegin(mu->toZero, mu->xZero, x, INSERT_VALUES, SCATTER_REVERSE));
  PetscCall(VecScatterEnd(mu->toZero, mu->xZero, x, INSERT_VALUES, SCATTER_REVERSE));
  PetscFunctionReturn(0);
}


/* f = P x_C with x = K^-1 F */
static PetscErrorCode SSStarReductionReduceLoad_MUMPS(SSStarReduction red, Vec F, Vec f)
{
  Vec x, xC;

  PetscFunctionBegin;
  PetscCall(VecDuplicate(F, &x));
  PetscCall(SolveWholeK(red, F, x));
  PetscCall(VecGetSubVector(x, red->isC, &xC));
  PetscCall(MatMult(red->P, xC, f));
  PetscCall(VecRestoreSubVector(x, red->isC, &xC));
  PetscCall(VecDestroy(&x));
  PetscFunctionReturn(0);
}

/* u = K^-1 (F + E_C (P u_C - f)) */
static PetscErrorCode SSStarReductionRecover_MUMPS(SSStarReduction red, Vec F, Vec uC, Vec rC, Vec u)
{
  Vec rhs, bC;

  PetscFunctionBegin;
  PetscCall(VecDuplicate(F, &rhs));
  PetscCall(VecCopy(F, rhs));
  PetscCall(VecGetSubVector(rhs, red->isC, &bC));
  PetscCall(VecAXPY(bC, 1.0, rC));
  PetscCall(VecRestoreSubVector(rhs, red->isC, &bC));
  PetscCall(SolveWholeK(red, rhs, u));
  PetscCall(VecDestroy(&rhs));
  PetscFunctionReturn(0);
}

static PetscErrorCode SSStarReductionDestroy_MUMPS(SSStarReduction red)
{
  Reduction_MUMPS *mu = (Reduction_MUMPS *)red->data;

  PetscFunctionBegin;
  PetscCall(MatDestroy(&mu->Kfactor));
  PetscCall(VecScatterDestroy(&mu->toZero));
  PetscCall(VecDestroy(&mu->bZero));
  PetscCall(VecDestroy(&mu->xZero));
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarReductionCreate_MUMPS(SSStarReduction red, Mat K)
{
  Reduction_MUMPS *mu;
  Vec              F;

  PetscFunctionBegin;
  PetscCall(PetscNew(&mu));
  red->data            = mu;
  red->ops.reduceload  = SSStarReductionReduceLoad_MUMPS;
  red->ops.recover     = SSStarReductionRecover_MUMPS;
  red->ops.destroy     = SSStarReductionDestroy_MUMPS;
  PetscCall(ReduceMUMPS(red, K));
  PetscCall(MatCreateVecs(K, NULL, &F));
  PetscCall(VecScatterCreateToZero(F, &mu->toZero, &mu->bZero));
  PetscCall(VecDestroy(&F));
  PetscCall(VecDuplicate(mu->bZero, &mu->xZero));
  PetscFunctionReturn(0);
}
