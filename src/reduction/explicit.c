/*
   The explicit reduction: MATSCHURCOMPLEMENT made explicit, with K_II factored once (MUMPS Cholesky, options
   -<prefix>interior_); the same factorization gives f and the recovery.
*/
#include "reductionimpl.h"

typedef struct {
  Mat Kii, Kic, Kci; /* blocks of K  */
  KSP kspI;          /* K_II^-1      */
} Reduction_Explicit;

/* The interior blocks of K and the factorization of K_II (explicit path) */
static PetscErrorCode SetUpInterior(SSStarReduction red, Mat K)
{
  Reduction_Explicit *ex = (Reduction_Explicit *)red->data;
  PC        pc;
  Mat       F;
  PetscReal flops;
  char      icntl[256];

  PetscFunctionBegin;
  PetscCall(MatCreateSubMatrix(K, red->isI, red->isI, MAT_INITIAL_MATRIX, &ex->Kii));
  PetscCall(MatCreateSubMatrix(K, red->isI, red->isC, MAT_INITIAL_MATRIX, &ex->Kic));
  PetscCall(MatCreateSubMatrix(K, red->isC, red->isI, MAT_INITIAL_MATRIX, &ex->Kci));
  PetscCall(MatSetOption(ex->Kii, MAT_SPD, PETSC_TRUE));
  PetscCall(KSPCreate(PetscObjectComm((PetscObject)K), &ex->kspI));
  PetscCall(KSPSetOptionsPrefix(ex->kspI, red->prefix));
  PetscCall(KSPAppendOptionsPrefix(ex->kspI, "interior_"));
  PetscCall(KSPSetOperators(ex->kspI, ex->Kii, ex->Kii));
  PetscCall(KSPSetType(ex->kspI, KSPPREONLY));
  PetscCall(KSPGetPC(ex->kspI, &pc));
  PetscCall(PCSetType(pc, PCCHOLESKY));
  PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  PetscCall(KSPSetFromOptions(ex->kspI));
  PetscCall(KSPSetUp(ex->kspI));
  PetscCall(PCFactorGetMatrix(pc, &F));
  PetscCall(SSStarReductionOptionName(red, "interior_mat_mumps_icntl_", icntl, sizeof(icntl)));
  PetscCall(SSStarReductionCheckFactor(PetscObjectComm((PetscObject)K), -1, F, 0, "the MUMPS Cholesky factorization of K_II (explicit Schur complement)", icntl));
  PetscCall(MatMumpsGetRinfo(F, 3, &flops)); /* PETSc does not log MUMPS's flops */
  PetscCall(PetscLogFlops(flops));
  PetscCall(MatMumpsGetRinfog(F, 3, &flops));
  PetscCall(PetscInfo(K, "MUMPS factorization of K_II: %g flops\n", (double)flops));
  PetscCall(KSPSetErrorIfNotConverged(ex->kspI, PETSC_TRUE)); /* after the set-up: its failures are reported above */
  PetscFunctionReturn(0);
}

/*
   P by MATSCHURCOMPLEMENT made explicit, sharing the factorization of K_II. MatSchurComplementComputeExplicitOperator
   holds K_IC and K_II^-1 K_IC as dense matrices and P as AIJ: checked before (the factor of K_II not counted).
*/
static PetscErrorCode ReduceExplicit(SSStarReduction red, Mat K)
{
  Reduction_Explicit *ex = (Reduction_Explicit *)red->data;
  Mat      Kcc, S, Paij;
  PetscInt nI, mC, NC;

  PetscFunctionBegin;
  PetscCall(ISGetLocalSize(red->isI, &nI));
  PetscCall(ISGetLocalSize(red->isC, &mC));
  PetscCall(ISGetSize(red->isC, &NC));
  PetscCall(SSStarReductionCheckMemory(PetscObjectComm((PetscObject)K), red->memoryLimit, 0, 8.0 * NC * (2.0 * nI + 1.5 * mC + (1 + SSSTAR_DENSE_WORK) * (PetscLogDouble)mC), "The explicit Schur reduction (its dense blocks K_IC and K_II^-1 K_IC; the factor of K_II not counted)"));
  PetscCall(SetUpInterior(red, K));
  PetscCall(MatCreateSubMatrix(K, red->isC, red->isC, MAT_INITIAL_MATRIX, &Kcc));
  PetscCall(MatCreateSchurComplement(ex->Kii, ex->Kii, ex->Kic, ex->Kci, Kcc, &S));
  PetscCall(MatSchurComplementSetKSP(S, ex->kspI));
  PetscCall(MatSchurComplementComputeExplicitOperator(S, &Paij));
  PetscCall(MatConvert(Paij, MATDENSE, MAT_INITIAL_MATRIX, &red->P));
  PetscCall(MatDestroy(&Paij));
  PetscCall(MatDestroy(&S));
  PetscCall(MatDestroy(&Kcc));
  PetscFunctionReturn(0);
}


/* f = F_C - K_CI K_II^-1 F_I */
static PetscErrorCode SSStarReductionReduceLoad_Explicit(SSStarReduction red, Vec F, Vec f)
{
  Reduction_Explicit *ex = (Reduction_Explicit *)red->data;
  Vec                 FI, FC, t;

  PetscFunctionBegin;
  PetscCall(MatCreateVecs(ex->Kii, &t, NULL));
  PetscCall(VecGetSubVector(F, red->isI, &FI));
  PetscCall(KSPSolve(ex->kspI, FI, t));
  PetscCall(VecRestoreSubVector(F, red->isI, &FI));
  PetscCall(MatMult(ex->Kci, t, f));
  PetscCall(VecGetSubVector(F, red->isC, &FC));
  PetscCall(VecAYPX(f, -1.0, FC));
  PetscCall(VecRestoreSubVector(F, red->isC, &FC));
  PetscCall(VecDestroy(&t));
  PetscFunctionReturn(0);
}

/* u_I = K_II^-1 (F_I - K_IC u_C) */
static PetscErrorCode SSStarReductionRecover_Explicit(SSStarReduction red, Vec F, Vec uC, Vec rC, Vec u)
{
  Reduction_Explicit *ex = (Reduction_Explicit *)red->data;
  Vec                 FI, rhs, uI;

  PetscFunctionBegin;
  PetscCall(MatCreateVecs(ex->Kii, &uI, &rhs));
  PetscCall(MatMult(ex->Kic, uC, rhs));
  PetscCall(VecGetSubVector(F, red->isI, &FI));
  PetscCall(VecAYPX(rhs, -1.0, FI));
  PetscCall(VecRestoreSubVector(F, red->isI, &FI));
  PetscCall(KSPSolve(ex->kspI, rhs, uI));
  PetscCall(VecISCopy(u, red->isI, SCATTER_FORWARD, uI));
  PetscCall(VecDestroy(&uI));
  PetscCall(VecDestroy(&rhs));
  PetscFunctionReturn(0);
}

static PetscErrorCode SSStarReductionDestroy_Explicit(SSStarReduction red)
{
  Reduction_Explicit *ex = (Reduction_Explicit *)red->data;

  PetscFunctionBegin;
  PetscCall(MatDestroy(&ex->Kii));
  PetscCall(MatDestroy(&ex->Kic));
  PetscCall(MatDestroy(&ex->Kci));
  PetscCall(KSPDestroy(&ex->kspI));
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarReductionCreate_Explicit(SSStarReduction red, Mat K)
{
  Reduction_Explicit *ex;

  PetscFunctionBegin;
  PetscCall(PetscNew(&ex));
  red->data           = ex;
  red->ops.reduceload = SSStarReductionReduceLoad_Explicit;
  red->ops.recover    = SSStarReductionRecover_Explicit;
  red->ops.destroy    = SSStarReductionDestroy_Explicit;
  PetscCall(ReduceExplicit(red, K));
  PetscFunctionReturn(0);
}
