/*
   Reduction of K u = F to the contact dofs C (DERIVATION.md section 0):
   P = K_CC - K_CI K_II^-1 K_IC,  f = F_C - K_CI K_II^-1 F_I,  and the recovery u_I = K_II^-1 (F_I - K_IC u_C).

   mumps:    one Cholesky factorization of the whole K with the Schur block C (MUMPS, on rank 0) gives P, and its
             solves give f and u: x = K^-1 F has x_C = P^-1 f, so f = P x_C; K^-1 (F + E_C (P u_C - f)) = u.
   explicit: MATSCHURCOMPLEMENT made explicit, with K_II factored once (MUMPS Cholesky, prefix -interior_).
*/
#include <ssstarreduction.h>
#include <petscmat.h>

const char *const SSStarReductionTypes[] = {"mumps", "explicit", "SSStarReductionType", "SSSTAR_REDUCTION_", NULL};

struct _n_SSStarReduction {
  SSStarReductionType type;
  IS                  isC, isI;
  Mat                 P;
  Mat                 Kii, Kic, Kci; /* explicit: blocks of K                                   */
  KSP                 kspI;          /* explicit: K_II^-1                                       */
  Mat                 Kfactor;       /* mumps: Cholesky of K with the Schur block C, on rank 0  */
  VecScatter          toZero;        /* mumps: K's vectors to and from their copy on rank 0     */
  Vec                 bZero, xZero;
};

static PetscErrorCode CheckFactor(Mat F, const char what[])
{
  MatFactorError err;

  PetscFunctionBegin;
  PetscCall(MatFactorGetError(F, &err));
  PetscCheck(err == MAT_FACTOR_NOERROR, PetscObjectComm((PetscObject)F), PETSC_ERR_LIB, "%s failed (MatFactorError %d): is the body held by the \"dirichlet\" group?", what, (int)err);
  PetscFunctionReturn(0);
}

/* P by MUMPS's own Schur complement of the whole K (gathered on rank 0), then scattered by rows like isC. */
static PetscErrorCode ReduceMUMPS(SSStarReduction red, Mat K)
{
  MPI_Comm             comm = PetscObjectComm((PetscObject)K);
  PetscMPIInt          size, rank;
  PetscInt             N, mC, NC;
  IS                   isAll, isCall;
  Mat                 *Kseq, F, Sseq;
  MatFactorInfo        info;
  MatFactorSchurStatus status;

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
  if (rank == 0) {
    PetscCall(MatSetOption(Kseq[0], MAT_SPD, PETSC_TRUE));
    PetscCall(MatGetFactor(Kseq[0], MATSOLVERMUMPS, MAT_FACTOR_CHOLESKY, &F));
    PetscCall(MatSetOptionsPrefix(F, "schur_"));
    PetscCall(MatSetFromOptions(F));
    PetscCall(MatFactorSetSchurIS(F, isCall));
    PetscCall(MatFactorInfoInitialize(&info));
    PetscCall(MatCholeskyFactorSymbolic(F, Kseq[0], NULL, &info));
    PetscCall(MatCholeskyFactorNumeric(F, Kseq[0], &info));
    PetscCall(CheckFactor(F, "MUMPS Cholesky factorization of K with a Schur complement"));
    PetscCall(MatFactorCreateSchurComplement(F, &Sseq, &status));
    red->Kfactor = F;
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
  PetscFunctionBegin;
  PetscCall(VecScatterBegin(red->toZero, b, red->bZero, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(red->toZero, b, red->bZero, INSERT_VALUES, SCATTER_FORWARD));
  if (red->Kfactor) PetscCall(MatSolve(red->Kfactor, red->bZero, red->xZero));
  PetscCall(VecScatterBegin(red->toZero, red->xZero, x, INSERT_VALUES, SCATTER_REVERSE));
  PetscCall(VecScatterEnd(red->toZero, red->xZero, x, INSERT_VALUES, SCATTER_REVERSE));
  PetscFunctionReturn(0);
}

/* The interior blocks of K and the factorization of K_II (explicit path) */
static PetscErrorCode SetUpInterior(SSStarReduction red, Mat K)
{
  PC pc;

  PetscFunctionBegin;
  PetscCall(MatCreateSubMatrix(K, red->isI, red->isI, MAT_INITIAL_MATRIX, &red->Kii));
  PetscCall(MatCreateSubMatrix(K, red->isI, red->isC, MAT_INITIAL_MATRIX, &red->Kic));
  PetscCall(MatCreateSubMatrix(K, red->isC, red->isI, MAT_INITIAL_MATRIX, &red->Kci));
  PetscCall(MatSetOption(red->Kii, MAT_SPD, PETSC_TRUE));
  PetscCall(KSPCreate(PetscObjectComm((PetscObject)K), &red->kspI));
  PetscCall(KSPSetOptionsPrefix(red->kspI, "interior_"));
  PetscCall(KSPSetOperators(red->kspI, red->Kii, red->Kii));
  PetscCall(KSPSetType(red->kspI, KSPPREONLY));
  PetscCall(KSPGetPC(red->kspI, &pc));
  PetscCall(PCSetType(pc, PCCHOLESKY));
  PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  PetscCall(KSPSetErrorIfNotConverged(red->kspI, PETSC_TRUE));
  PetscCall(KSPSetFromOptions(red->kspI));
  PetscCall(KSPSetUp(red->kspI));
  PetscFunctionReturn(0);
}

/* P by MATSCHURCOMPLEMENT made explicit, sharing the factorization of K_II. */
static PetscErrorCode ReduceExplicit(SSStarReduction red, Mat K)
{
  Mat Kcc, S, Paij;

  PetscFunctionBegin;
  PetscCall(SetUpInterior(red, K));
  PetscCall(MatCreateSubMatrix(K, red->isC, red->isC, MAT_INITIAL_MATRIX, &Kcc));
  PetscCall(MatCreateSchurComplement(red->Kii, red->Kii, red->Kic, red->Kci, Kcc, &S));
  PetscCall(MatSchurComplementSetKSP(S, red->kspI));
  PetscCall(MatSchurComplementComputeExplicitOperator(S, &Paij));
  PetscCall(MatConvert(Paij, MATDENSE, MAT_INITIAL_MATRIX, &red->P));
  PetscCall(MatDestroy(&Paij));
  PetscCall(MatDestroy(&S));
  PetscCall(MatDestroy(&Kcc));
  PetscFunctionReturn(0);
}

/*@C
   SSStarReductionReduceLoad - f = F_C - K_CI K_II^-1 F_I, the load reduced to the contact dofs (a vector like P's)
@*/
PetscErrorCode SSStarReductionReduceLoad(SSStarReduction red, Vec F, Vec f)
{
  Vec FI, FC, x, xC, t;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(SSSTAR_Schur, 0, 0, 0, 0));
  switch (red->type) {
  case SSSTAR_REDUCTION_MUMPS: /* x = K^-1 F has x_C = P^-1 f */
    PetscCall(VecDuplicate(F, &x));
    PetscCall(SolveWholeK(red, F, x));
    PetscCall(VecGetSubVector(x, red->isC, &xC));
    PetscCall(MatMult(red->P, xC, f));
    PetscCall(VecRestoreSubVector(x, red->isC, &xC));
    PetscCall(VecDestroy(&x));
    break;
  case SSSTAR_REDUCTION_EXPLICIT:
    PetscCall(MatCreateVecs(red->Kii, &t, NULL));
    PetscCall(VecGetSubVector(F, red->isI, &FI));
    PetscCall(KSPSolve(red->kspI, FI, t));
    PetscCall(VecRestoreSubVector(F, red->isI, &FI));
    PetscCall(MatMult(red->Kci, t, f));
    PetscCall(VecGetSubVector(F, red->isC, &FC));
    PetscCall(VecAYPX(f, -1.0, FC));
    PetscCall(VecRestoreSubVector(F, red->isC, &FC));
    PetscCall(VecDestroy(&t));
    break;
  }
  PetscCall(PetscLogEventEnd(SSSTAR_Schur, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/*@C
   SSStarReductionCreate - the Schur complement P = K_CC - K_CI K_II^-1 K_IC of K on the dofs isC

   Input Parameters:
+  K    - the (SPD) stiffness
.  isC  - owned global dofs of the contact nodes (3 per node), in the order P is to have
.  isI  - all other owned dofs
-  type - SSSTAR_REDUCTION_MUMPS or SSSTAR_REDUCTION_EXPLICIT

   Notes:
   P is dense and distributed by rows like isC. The factorization that gave P is kept for the recovery.
   Options: -schur_mat_mumps_* (mumps), -interior_ksp_*, -interior_pc_* (explicit).
@*/
PetscErrorCode SSStarReductionCreate(Mat K, IS isC, IS isI, SSStarReductionType type, SSStarReduction *red)
{
  SSStarReduction r;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(SSSTAR_Schur, K, 0, 0, 0));
  PetscCall(PetscNew(&r));
  r->type = type;
  PetscCall(PetscObjectReference((PetscObject)isC));
  PetscCall(PetscObjectReference((PetscObject)isI));
  r->isC = isC;
  r->isI = isI;
  switch (type) {
  case SSSTAR_REDUCTION_MUMPS:
    PetscCall(ReduceMUMPS(r, K));
    {
      Vec F;

      PetscCall(MatCreateVecs(K, NULL, &F));
      PetscCall(VecScatterCreateToZero(F, &r->toZero, &r->bZero));
      PetscCall(VecDestroy(&F));
    }
    PetscCall(VecDuplicate(r->bZero, &r->xZero));
    break;
  case SSSTAR_REDUCTION_EXPLICIT:
    PetscCall(ReduceExplicit(r, K));
    break;
  }
  PetscCall(PetscObjectSetName((PetscObject)r->P, "P"));
  PetscCall(PetscLogEventEnd(SSSTAR_Schur, K, 0, 0, 0));
  *red = r;
  PetscFunctionReturn(0);
}

/*@C
   SSStarReductionGetSchurComplement - P (3p x 3p, dense, rows distributed like isC); owned by the reduction
@*/
PetscErrorCode SSStarReductionGetSchurComplement(SSStarReduction red, Mat *P)
{
  PetscFunctionBegin;
  *P = red->P;
  PetscFunctionReturn(0);
}

/*@C
   SSStarReductionRecover - the full displacement u (a vector of K) of the load F from the contact displacement uC
   and the contact force rC = P uC - f
@*/
PetscErrorCode SSStarReductionRecover(SSStarReduction red, Vec F, Vec uC, Vec rC, Vec u)
{
  Vec FI, rhs, uI, bC;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(SSSTAR_Recovery, 0, 0, 0, 0));
  switch (red->type) {
  case SSSTAR_REDUCTION_MUMPS: /* u = K^-1 (F + E_C (P u_C - f)) */
    PetscCall(VecDuplicate(F, &rhs));
    PetscCall(VecCopy(F, rhs));
    PetscCall(VecGetSubVector(rhs, red->isC, &bC));
    PetscCall(VecAXPY(bC, 1.0, rC));
    PetscCall(VecRestoreSubVector(rhs, red->isC, &bC));
    PetscCall(SolveWholeK(red, rhs, u));
    PetscCall(VecDestroy(&rhs));
    break;
  case SSSTAR_REDUCTION_EXPLICIT: /* u_I = K_II^-1 (F_I - K_IC u_C) */
    PetscCall(MatCreateVecs(red->Kii, &uI, &rhs));
    PetscCall(MatMult(red->Kic, uC, rhs));
    PetscCall(VecGetSubVector(F, red->isI, &FI));
    PetscCall(VecAYPX(rhs, -1.0, FI));
    PetscCall(VecRestoreSubVector(F, red->isI, &FI));
    PetscCall(KSPSolve(red->kspI, rhs, uI));
    PetscCall(VecISCopy(u, red->isI, SCATTER_FORWARD, uI));
    PetscCall(VecDestroy(&uI));
    PetscCall(VecDestroy(&rhs));
    break;
  }
  PetscCall(VecISCopy(u, red->isC, SCATTER_FORWARD, uC)); /* the contact solution itself, not its round-off image */
  PetscCall(PetscLogEventEnd(SSSTAR_Recovery, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/*@C
   SSStarReductionDestroy - frees the reduction (its factorization and P)
@*/
PetscErrorCode SSStarReductionDestroy(SSStarReduction *red)
{
  PetscFunctionBegin;
  if (!*red) PetscFunctionReturn(0);
  PetscCall(ISDestroy(&(*red)->isC));
  PetscCall(ISDestroy(&(*red)->isI));
  PetscCall(MatDestroy(&(*red)->Kii));
  PetscCall(MatDestroy(&(*red)->Kic));
  PetscCall(MatDestroy(&(*red)->Kci));
  PetscCall(MatDestroy(&(*red)->P));
  PetscCall(KSPDestroy(&(*red)->kspI));
  PetscCall(MatDestroy(&(*red)->Kfactor));
  PetscCall(VecScatterDestroy(&(*red)->toZero));
  PetscCall(VecDestroy(&(*red)->bZero));
  PetscCall(VecDestroy(&(*red)->xZero));
  PetscCall(PetscFree(*red));
  PetscFunctionReturn(0);
}
