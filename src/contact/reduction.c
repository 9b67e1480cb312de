/*
   Reduction of K u = F to the contact dofs C (DERIVATION.md section 0):
   P = K_CC - K_CI K_II^-1 K_IC,  f = F_C - K_CI K_II^-1 F_I,  and the recovery u_I = K_II^-1 (F_I - K_IC u_C).
*/
#include <ssstarcontact.h>
#include <petscmat.h>

const char *const SSStarReductionTypes[] = {"mumps", "explicit", "SSStarReductionType", "SSSTAR_REDUCTION_", NULL};

struct _n_SSStarReduction {
  SSStarReductionType type;
  IS                  isC, isI;
  Mat                 Kii, Kic, Kci, P;
  KSP                 kspI; /* K_II^-1: MUMPS Cholesky, options prefix -interior_ */
  Vec                 F, f;
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
    PetscCall(MatDestroy(&F));
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

/* P by MATSCHURCOMPLEMENT made explicit, sharing the factorization of K_II. */
static PetscErrorCode ReduceExplicit(SSStarReduction red, Mat K)
{
  Mat Kcc, S, Paij;

  PetscFunctionBegin;
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
   SSStarReductionCreate - eliminates every dof but those of isC from K u = F

   Input Parameters:
+  K    - the (SPD) stiffness
.  F    - the load
.  isC  - owned global dofs of the contact nodes (3 per node)
.  isI  - all other owned dofs
-  type - SSSTAR_REDUCTION_MUMPS or SSSTAR_REDUCTION_EXPLICIT

   Notes:
   P is dense and distributed by rows like isC. K_II is factored by a KSP with prefix -interior_
   (MUMPS Cholesky), used for f and for the recovery of the interior displacement.
@*/
PetscErrorCode SSStarReductionCreate(Mat K, Vec F, IS isC, IS isI, SSStarReductionType type, SSStarReduction *red)
{
  SSStarReduction r;
  PC              pc;
  Vec             FI, FC, t, s;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(SSSTAR_Schur, K, 0, 0, 0));
  PetscCall(PetscNew(&r));
  r->type = type;
  PetscCall(PetscObjectReference((PetscObject)isC));
  PetscCall(PetscObjectReference((PetscObject)isI));
  PetscCall(PetscObjectReference((PetscObject)F));
  r->isC = isC;
  r->isI = isI;
  r->F   = F;
  PetscCall(MatCreateSubMatrix(K, isI, isI, MAT_INITIAL_MATRIX, &r->Kii));
  PetscCall(MatCreateSubMatrix(K, isI, isC, MAT_INITIAL_MATRIX, &r->Kic));
  PetscCall(MatCreateSubMatrix(K, isC, isI, MAT_INITIAL_MATRIX, &r->Kci));
  PetscCall(MatSetOption(r->Kii, MAT_SPD, PETSC_TRUE));

  PetscCall(KSPCreate(PetscObjectComm((PetscObject)K), &r->kspI));
  PetscCall(KSPSetOptionsPrefix(r->kspI, "interior_"));
  PetscCall(KSPSetOperators(r->kspI, r->Kii, r->Kii));
  PetscCall(KSPSetType(r->kspI, KSPPREONLY));
  PetscCall(KSPGetPC(r->kspI, &pc));
  PetscCall(PCSetType(pc, PCCHOLESKY));
  PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  PetscCall(KSPSetErrorIfNotConverged(r->kspI, PETSC_TRUE));
  PetscCall(KSPSetFromOptions(r->kspI));
  PetscCall(KSPSetUp(r->kspI));

  switch (type) {
  case SSSTAR_REDUCTION_MUMPS:
    PetscCall(ReduceMUMPS(r, K));
    break;
  case SSSTAR_REDUCTION_EXPLICIT:
    PetscCall(ReduceExplicit(r, K));
    break;
  }
  PetscCall(PetscObjectSetName((PetscObject)r->P, "P"));

  /* f = F_C - K_CI K_II^-1 F_I */
  PetscCall(MatCreateVecs(r->P, NULL, &r->f));
  PetscCall(PetscObjectSetName((PetscObject)r->f, "f"));
  PetscCall(MatCreateVecs(r->Kii, &t, &s));
  PetscCall(VecGetSubVector(F, isI, &FI));
  PetscCall(KSPSolve(r->kspI, FI, t));
  PetscCall(VecRestoreSubVector(F, isI, &FI));
  PetscCall(MatMult(r->Kci, t, r->f));
  PetscCall(VecGetSubVector(F, isC, &FC));
  PetscCall(VecAYPX(r->f, -1.0, FC));
  PetscCall(VecRestoreSubVector(F, isC, &FC));
  PetscCall(VecDestroy(&t));
  PetscCall(VecDestroy(&s));
  PetscCall(PetscLogEventEnd(SSSTAR_Schur, K, 0, 0, 0));
  *red = r;
  PetscFunctionReturn(0);
}

/*@C
   SSStarReductionGetProblem - the reduced P (3p x 3p, dense) and f; owned by the reduction
@*/
PetscErrorCode SSStarReductionGetProblem(SSStarReduction red, Mat *P, Vec *f)
{
  PetscFunctionBegin;
  if (P) *P = red->P;
  if (f) *f = red->f;
  PetscFunctionReturn(0);
}

/*@C
   SSStarReductionRecover - the full displacement u (a global vector of K) from the contact displacement uC
@*/
PetscErrorCode SSStarReductionRecover(SSStarReduction red, Vec uC, Vec u)
{
  Vec FI, rhs, uI;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(SSSTAR_Recovery, 0, 0, 0, 0));
  PetscCall(MatCreateVecs(red->Kii, &uI, &rhs));
  PetscCall(MatMult(red->Kic, uC, rhs));
  PetscCall(VecGetSubVector(red->F, red->isI, &FI));
  PetscCall(VecAYPX(rhs, -1.0, FI));
  PetscCall(VecRestoreSubVector(red->F, red->isI, &FI));
  PetscCall(KSPSolve(red->kspI, rhs, uI));
  PetscCall(VecISCopy(u, red->isI, SCATTER_FORWARD, uI));
  PetscCall(VecISCopy(u, red->isC, SCATTER_FORWARD, uC));
  PetscCall(VecDestroy(&uI));
  PetscCall(VecDestroy(&rhs));
  PetscCall(PetscLogEventEnd(SSSTAR_Recovery, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

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
  PetscCall(VecDestroy(&(*red)->F));
  PetscCall(VecDestroy(&(*red)->f));
  PetscCall(PetscFree(*red));
  PetscFunctionReturn(0);
}
