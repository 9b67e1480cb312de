/*
   Reduction of K u = F to the contact dofs C (DERIVATION.md section 0):
   P = K_CC - K_CI K_II^-1 K_IC,  f = F_C - K_CI K_II^-1 F_I,  and the recovery u_I = K_II^-1 (F_I - K_IC u_C).

   direct:   MUMPS through its C API (direct.c): one Cholesky factorization of K with the Schur block C, METIS
             ordering, on every rank; its condensation gives f and its expansion u.
   mumps:    one Cholesky factorization of the whole K with the Schur block C (PETSc's MUMPS, on rank 0) gives P, and
             its solves give f and u: x = K^-1 F has x_C = P^-1 f, so f = P x_C; K^-1 (F + E_C (P u_C - f)) = u.
   explicit: MATSCHURCOMPLEMENT made explicit, with K_II factored once (MUMPS Cholesky, prefix -interior_).

   Every path checks its memory estimate before the factorization and reports MUMPS's failures on every rank.
*/
#include "reductionimpl.h"
#include <petscmat.h>
#include <stdio.h>

const char *const SSStarReductionTypes[] = {"direct", "mumps", "explicit", "SSStarReductionType", "SSSTAR_REDUCTION_", NULL};

/* MemAvailable of this node (bytes) from /proc/meminfo; 0 when unknown */
static PetscErrorCode GetMemAvailable(PetscLogDouble *bytes)
{
  FILE *file = fopen("/proc/meminfo", "r");
  char  line[256];
  long  kb;

  PetscFunctionBegin;
  *bytes = 0;
  if (!file) PetscFunctionReturn(0);
  while (fgets(line, sizeof(line), file))
    if (sscanf(line, "MemAvailable: %ld kB", &kb) == 1) *bytes = 1024.0 * (PetscLogDouble)kb;
  fclose(file);
  PetscFunctionReturn(0);
}

/*
   Whether the estimate (sparse factors + dense matrices, bytes per rank) fits, the same answer on every rank: each
   rank's estimate within limitGB, or (limitGB = 0) the estimates of a node's ranks together within its MemAvailable.
   When it does not and what is given, raises the error with the figures of the rank that fits worst.
*/
static PetscErrorCode CompareMemory(MPI_Comm comm, PetscReal limitGB, PetscLogDouble sparse, PetscLogDouble dense, const char what[], PetscBool *fits)
{
  MPI_Comm       node;
  PetscMPIInt    rank, nodeSize;
  PetscLogDouble need = sparse + dense, nodeNeed = need, available = 1e9 * limitGB, worst[5];
  char           parts[160];
  struct {
    double ratio;
    int    rank;
  } mine, max;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node));
  PetscCallMPI(MPI_Comm_size(node, &nodeSize));
  if (limitGB <= 0) {
    PetscCall(GetMemAvailable(&available));
    PetscCallMPI(MPI_Allreduce(&need, &nodeNeed, 1, MPI_DOUBLE, MPI_SUM, node));
  }
  PetscCallMPI(MPI_Comm_free(&node));
  mine.ratio = available > 0 ? nodeNeed / available : 0; /* no /proc/meminfo: nothing to compare with */
  mine.rank  = rank;
  PetscCallMPI(MPI_Allreduce(&mine, &max, 1, MPI_DOUBLE_INT, MPI_MAXLOC, comm));
  PetscCall(PetscInfo(NULL, "Memory estimate %g GB on rank %d (sparse %g, dense %g), %g GB on its node, limit %g GB\n", need / 1e9, rank, sparse / 1e9, dense / 1e9, nodeNeed / 1e9, available / 1e9));
  *fits = (PetscBool)(max.ratio <= 1);
  if (*fits || !what) PetscFunctionReturn(0);
  worst[0] = sparse;
  worst[1] = dense;
  worst[2] = nodeNeed;
  worst[3] = available;
  worst[4] = nodeSize;
  PetscCallMPI(MPI_Bcast(worst, 5, MPI_DOUBLE, max.rank, comm));
  if (worst[0] > 0) PetscCall(PetscSNPrintf(parts, sizeof(parts), "%.3g GB on rank %d (MUMPS's factors %.3g GB, P and the dense work %.3g GB)", (worst[0] + worst[1]) / 1e9, max.rank, worst[0] / 1e9, worst[1] / 1e9));
  else PetscCall(PetscSNPrintf(parts, sizeof(parts), "%.3g GB on rank %d (P and the dense work)", worst[1] / 1e9, max.rank));
  if (limitGB > 0) SETERRQ(comm, PETSC_ERR_MEM, "%s needs an estimated %s, more than the limit of %.3g GB per rank (-snes_ssstar_memory_limit): refused before the factorization", what, parts, worst[3] / 1e9);
  SETERRQ(comm, PETSC_ERR_MEM, "%s needs an estimated %.3g GB on the node of rank %d, its %d ranks together (%s), more than the node's %.3g GB of MemAvailable: refused before the factorization (more nodes, or -snes_ssstar_memory_limit to plan for another amount)", what, worst[2] / 1e9, max.rank, (int)worst[4], parts, worst[3] / 1e9);
}

/* Whether the estimate fits (collective; see CompareMemory) */
PetscErrorCode SSStarReductionFitsMemory(MPI_Comm comm, PetscReal limitGB, PetscLogDouble sparse, PetscLogDouble dense, PetscBool *fits)
{
  PetscFunctionBegin;
  PetscCall(CompareMemory(comm, limitGB, sparse, dense, NULL, fits));
  PetscFunctionReturn(0);
}

/* Refuses, on every rank, when the estimate does not fit, with the figures in the message (see CompareMemory) */
PetscErrorCode SSStarReductionCheckMemory(MPI_Comm comm, PetscReal limitGB, PetscLogDouble sparse, PetscLogDouble dense, const char what[])
{
  PetscBool fits;

  PetscFunctionBegin;
  PetscCall(CompareMemory(comm, limitGB, sparse, dense, what, &fits));
  PetscFunctionReturn(0);
}

/* MUMPS's "INFO(2) entries" (negative: millions of entries) in bytes of an entry of the given size */
static PetscLogDouble MUMPSEntries(PetscInt info2, size_t entry)
{
  return (info2 < 0 ? -1e6 * (PetscLogDouble)info2 : (PetscLogDouble)info2) * (PetscLogDouble)entry;
}

/*
   Raises MUMPS's failure (INFOG(1) < 0) on every rank of comm, in words: a singular K, memory (with the amount MUMPS
   reports), or the codes. root: the rank that holds INFOG (-1: every rank does). estimate: MUMPS's memory estimate for
   the factorization (bytes per rank, 0 if unknown). icntl: the prefix of the options of MUMPS's ICNTL (for 14 and 23).
*/
PetscErrorCode SSStarReductionCheckMUMPS(MPI_Comm comm, PetscMPIInt root, PetscInt infog1, PetscInt infog2, PetscLogDouble estimate, const char what[], const char icntl[])
{
  PetscInt       infog[2] = {infog1, infog2};
  PetscLogDouble est      = estimate;
  char           estimated[128] = "";

  PetscFunctionBegin;
  if (root >= 0) {
    PetscCallMPI(MPI_Bcast(infog, 2, MPIU_INT, root, comm));
    PetscCallMPI(MPI_Bcast(&est, 1, MPI_DOUBLE, root, comm));
  }
  if (infog[0] >= 0) PetscFunctionReturn(0);
  if (est > 0) PetscCall(PetscSNPrintf(estimated, sizeof(estimated), "; MUMPS's estimate after its analysis was %.3g GB per rank", est / 1e9));
  switch (infog[0]) {
  case -6:  /* structurally singular */
  case -10: /* numerically singular (INFOG(2): pivots eliminated) */
  case -40: /* SYM = 1 but a negative or zero pivot */
    SETERRQ(comm, PETSC_ERR_MAT_CH_ZRPVT, "K is singular: is the body held? (Dirichlet conditions) [MUMPS met a zero pivot in %s: INFOG(1) = %" PetscInt_FMT ", INFOG(2) = %" PetscInt_FMT "]", what, infog[0], infog[1]);
  case -9: /* real workspace too small by INFOG(2) entries */
  case -11:
  case -12:
    SETERRQ(comm, PETSC_ERR_MEM, "Out of memory in %s: MUMPS's workspace lacked %.3g GB (INFOG(1) = %" PetscInt_FMT ", INFOG(2) = %" PetscInt_FMT ")%s. Give it more memory (more ranks or nodes) or a larger margin %s14", what, MUMPSEntries(infog[1], sizeof(PetscScalar)) / 1e9, infog[0], infog[1], estimated, icntl);
  case -19: /* the working memory allowed by ICNTL(23) too small by INFOG(2) entries */
    SETERRQ(comm, PETSC_ERR_MEM, "Out of memory in %s: MUMPS needed %.3g GB more than the working memory it was allowed (%s23) (INFOG(1) = %" PetscInt_FMT ", INFOG(2) = %" PetscInt_FMT ")%s", what, MUMPSEntries(infog[1], sizeof(PetscScalar)) / 1e9, icntl, infog[0], infog[1], estimated);
  case -13: /* an allocation of INFOG(2) entries failed */
  case -5:
    SETERRQ(comm, PETSC_ERR_MEM, "Out of memory in %s: MUMPS could not allocate %.3g GB (INFOG(1) = %" PetscInt_FMT ", INFOG(2) = %" PetscInt_FMT ")%s. Give it more memory (more ranks or nodes)", what, MUMPSEntries(infog[1], sizeof(PetscScalar)) / 1e9, infog[0], infog[1], estimated);
  case -7: /* an integer allocation of INFOG(2) entries failed */
    SETERRQ(comm, PETSC_ERR_MEM, "Out of memory in %s: MUMPS could not allocate %.3g GB of integers (INFOG(1) = %" PetscInt_FMT ", INFOG(2) = %" PetscInt_FMT ")%s. Give it more memory (more ranks or nodes)", what, MUMPSEntries(infog[1], 4) / 1e9, infog[0], infog[1], estimated);
  case -8: /* integer workspace too small */
  case -14:
  case -15:
  case -17: /* send buffer too small */
  case -20: /* receive buffer too small */
    SETERRQ(comm, PETSC_ERR_MEM, "Out of memory in %s: a workspace or buffer of MUMPS was too small (INFOG(1) = %" PetscInt_FMT ", INFOG(2) = %" PetscInt_FMT ")%s. Raise its margin %s14", what, infog[0], infog[1], estimated, icntl);
  default:
    SETERRQ(comm, PETSC_ERR_LIB, "MUMPS failed in %s: INFOG(1) = %" PetscInt_FMT ", INFOG(2) = %" PetscInt_FMT " (see the error codes in the MUMPS users' guide)", what, infog[0], infog[1]);
  }
}

/* A PETSc MUMPS factor's failure, reported on every rank of comm (root: the rank holding F, -1: all) */
static PetscErrorCode CheckFactor(MPI_Comm comm, PetscMPIInt root, Mat F, PetscLogDouble estimate, const char what[], const char icntl[])
{
  PetscInt infog1 = 0, infog2 = 0;

  PetscFunctionBegin;
  if (F) {
    MatFactorError err;

    PetscCall(MatFactorGetError(F, &err));
    if (err != MAT_FACTOR_NOERROR) {
      PetscCall(MatMumpsGetInfog(F, 1, &infog1));
      PetscCall(MatMumpsGetInfog(F, 2, &infog2));
      if (infog1 >= 0) infog1 = -999; /* PETSc saw a failure MUMPS did not report */
    }
  }
  PetscCall(SSStarReductionCheckMUMPS(comm, root, infog1, infog2, estimate, what, icntl));
  PetscFunctionReturn(0);
}

/*
   P by MUMPS's own Schur complement of the whole K (gathered on rank 0), then scattered by rows like isC. Rank 0
   holds two dense copies of P beside MUMPS (MUMPS's Schur block and the one created from it) and its scatter buffer.
*/
static PetscErrorCode ReduceMUMPS(SSStarReduction red, Mat K)
{
  MPI_Comm             comm = PetscObjectComm((PetscObject)K);
  PetscMPIInt          size, rank;
  PetscInt             N, mC, NC, estimateMB = 0;
  PetscLogDouble       dense;
  IS                   isAll, isCall;
  Mat                 *Kseq, F = NULL, Sseq = NULL;
  MatFactorInfo        info;
  MatFactorSchurStatus status;
  const char          *what = "the MUMPS Cholesky factorization of K with a Schur complement (PETSc, rank 0)";

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
  if (rank == 0) {
    PetscCall(MatSetOption(Kseq[0], MAT_SPD, PETSC_TRUE));
    PetscCall(MatGetFactor(Kseq[0], MATSOLVERMUMPS, MAT_FACTOR_CHOLESKY, &F));
    PetscCall(MatSetOptionsPrefix(F, "schur_"));
    PetscCall(MatSetFromOptions(F));
    PetscCall(MatFactorSetSchurIS(F, isCall));
    PetscCall(MatCholeskyFactorSymbolic(F, Kseq[0], NULL, &info));
  }
  PetscCall(CheckFactor(comm, 0, F, 0, what, "-schur_mat_mumps_icntl_"));
  if (rank == 0) PetscCall(MatMumpsGetInfo(F, 15, &estimateMB));
  dense = 8.0 * NC * ((rank == 0 ? 2.0 * NC : 0) + (size > 1 ? 2.0 * mC : 0) + SSSTAR_DENSE_WORK * (PetscLogDouble)mC);
  PetscCall(SSStarReductionCheckMemory(comm, red->memoryLimit, 1e6 * (PetscLogDouble)estimateMB, dense, "The mumps Schur reduction"));
  if (rank == 0) PetscCall(MatCholeskyFactorNumeric(F, Kseq[0], &info));
  PetscCall(CheckFactor(comm, 0, F, 1e6 * (PetscLogDouble)estimateMB, what, "-schur_mat_mumps_icntl_"));
  if (rank == 0) {
    PetscReal flops;

    PetscCall(MatMumpsGetRinfo(F, 3, &flops)); /* PETSc does not log MUMPS's flops */
    PetscCall(PetscLogFlops(flops));
    PetscCall(PetscInfo(K, "MUMPS factorization (PETSc, rank 0): %g flops\n", (double)flops));
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
  PC        pc;
  Mat       F;
  PetscReal flops;

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
  PetscCall(KSPSetFromOptions(red->kspI));
  PetscCall(KSPSetUp(red->kspI));
  PetscCall(PCFactorGetMatrix(pc, &F));
  PetscCall(CheckFactor(PetscObjectComm((PetscObject)K), -1, F, 0, "the MUMPS Cholesky factorization of K_II (explicit Schur complement)", "-interior_mat_mumps_icntl_"));
  PetscCall(MatMumpsGetRinfo(F, 3, &flops)); /* PETSc does not log MUMPS's flops */
  PetscCall(PetscLogFlops(flops));
  PetscCall(MatMumpsGetRinfog(F, 3, &flops));
  PetscCall(PetscInfo(K, "MUMPS factorization of K_II: %g flops\n", (double)flops));
  PetscCall(KSPSetErrorIfNotConverged(red->kspI, PETSC_TRUE)); /* after the set-up: its failures are reported above */
  PetscFunctionReturn(0);
}

/*
   P by MATSCHURCOMPLEMENT made explicit, sharing the factorization of K_II. MatSchurComplementComputeExplicitOperator
   holds K_IC and K_II^-1 K_IC as dense matrices and P as AIJ: checked before (the factor of K_II not counted).
*/
static PetscErrorCode ReduceExplicit(SSStarReduction red, Mat K)
{
  Mat      Kcc, S, Paij;
  PetscInt nI, mC, NC;

  PetscFunctionBegin;
  PetscCall(ISGetLocalSize(red->isI, &nI));
  PetscCall(ISGetLocalSize(red->isC, &mC));
  PetscCall(ISGetSize(red->isC, &NC));
  PetscCall(SSStarReductionCheckMemory(PetscObjectComm((PetscObject)K), red->memoryLimit, 0, 8.0 * NC * (2.0 * nI + 1.5 * mC + (1 + SSSTAR_DENSE_WORK) * (PetscLogDouble)mC), "The explicit Schur reduction (its dense blocks K_IC and K_II^-1 K_IC; the factor of K_II not counted)"));
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

/* f = F_C - K_CI K_II^-1 F_I */
static PetscErrorCode ReduceLoad(SSStarReduction red, Vec F, Vec f)
{
  Vec FI, FC, x, xC, t;

  PetscFunctionBegin;
  switch (red->type) {
  case SSSTAR_REDUCTION_DIRECT:
    PetscCall(SSStarDirectReduceLoad(red->direct, F, f));
    break;
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
  PetscFunctionReturn(0);
}

/* u with u_C = uC and u_I = K_II^-1 (F_I - K_IC u_C); rC = P uC - f */
static PetscErrorCode Recover(SSStarReduction red, Vec F, Vec uC, Vec rC, Vec u)
{
  Vec FI, rhs, uI, bC;

  PetscFunctionBegin;
  switch (red->type) {
  case SSSTAR_REDUCTION_DIRECT: /* u_I = K_II^-1 (F_I - K_IC u_C) */
    PetscCall(SSStarDirectRecover(red->direct, F, uC, u));
    break;
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
  PetscFunctionReturn(0);
}

/*
   The Cholesky factorizations of K (K_II) do not pivot, and MUMPS does not look for zero pivots there: a singular K_II
   factors into garbage. Solving K_II x = b for a b of positive, irregular entries tells: the relative residual is
   round-off for a K_II of any reasonable condition, and of the order of b itself for a singular one.
*/
static PetscErrorCode CheckInteriorSolve(SSStarReduction red, Mat K)
{
  Vec          b, f, zero, x, r, rI, bI;
  PetscInt     lo, hi;
  PetscScalar *ba;
  PetscReal    rnorm, bnorm;

  PetscFunctionBegin;
  PetscCall(MatCreateVecs(K, &x, &b));
  PetscCall(VecDuplicate(b, &r));
  PetscCall(VecGetOwnershipRange(b, &lo, &hi));
  PetscCall(VecGetArrayWrite(b, &ba));
  for (PetscInt i = lo; i < hi; i++) ba[i - lo] = 1.0 + 0.5 * PetscSinReal((PetscReal)i);
  PetscCall(VecRestoreArrayWrite(b, &ba));
  PetscCall(MatCreateVecs(red->P, &f, &zero));
  PetscCall(VecZeroEntries(zero));
  if (red->type == SSSTAR_REDUCTION_MUMPS) { /* its recovery takes the contact force of u_C = 0, -f */
    PetscCall(ReduceLoad(red, b, f));
    PetscCall(VecScale(f, -1.0));
  }
  PetscCall(Recover(red, b, zero, f, x));
  PetscCall(MatMult(K, x, r));
  PetscCall(VecAXPY(r, -1.0, b));
  PetscCall(VecGetSubVector(r, red->isI, &rI));
  PetscCall(VecGetSubVector(b, red->isI, &bI));
  PetscCall(VecNorm(rI, NORM_INFINITY, &rnorm));
  PetscCall(VecNorm(bI, NORM_INFINITY, &bnorm));
  PetscCall(VecRestoreSubVector(b, red->isI, &bI));
  PetscCall(VecRestoreSubVector(r, red->isI, &rI));
  PetscCall(PetscInfo(K, "K_II x = b solved to a relative residual %g\n", (double)(rnorm / bnorm)));
  PetscCheck(rnorm <= SSSTAR_SINGULAR_RESIDUAL * bnorm, PetscObjectComm((PetscObject)K), PETSC_ERR_MAT_CH_ZRPVT,
             "K is singular: is the body held? (Dirichlet conditions). K_II, K without the contact dofs, is singular or nearly so: a solve with it leaves a relative residual of %.1e, so some part of the body is held neither by Dirichlet conditions nor through the contact dofs", (double)(rnorm / bnorm));
  PetscCall(VecDestroy(&b));
  PetscCall(VecDestroy(&x));
  PetscCall(VecDestroy(&r));
  PetscCall(VecDestroy(&f));
  PetscCall(VecDestroy(&zero));
  PetscFunctionReturn(0);
}

/*@C
   SSStarReductionReduceLoad - f = F_C - K_CI K_II^-1 F_I, the load reduced to the contact dofs (a vector like P's)
@*/
PetscErrorCode SSStarReductionReduceLoad(SSStarReduction red, Vec F, Vec f)
{
  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(SSSTAR_Schur, 0, 0, 0, 0));
  PetscCall(ReduceLoad(red, F, f));
  PetscCall(PetscLogEventEnd(SSSTAR_Schur, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/*@C
   SSStarReductionCreate - the Schur complement P = K_CC - K_CI K_II^-1 K_IC of K on the dofs isC

   Input Parameters:
+  K           - the (SPD) stiffness
.  isC         - owned global dofs of the contact nodes (3 per node), in the order P is to have
.  isI         - all other owned dofs
.  type        - SSSTAR_REDUCTION_DIRECT, SSSTAR_REDUCTION_MUMPS or SSSTAR_REDUCTION_EXPLICIT
-  memoryLimit - GB (1e9 bytes) per rank the reduction may plan for; 0: MemAvailable of each node split over its ranks

   Notes:
   P is dense and distributed by rows like isC. The factorization that gave P is kept for the recovery.
   Before factorizing, the memory each rank needs (MUMPS's estimate after its analysis, P, and SSSTAR_DENSE_WORK
   more dense matrices of P's size for the caller) is compared with memoryLimit: the reduction refuses, on every rank,
   with the estimate and the limit in the message. MUMPS's failures (a singular K, memory) are raised on every rank.
   Options: -schur_direct_mumps_icntl_<i>, -schur_direct_mumps_cntl_<i> (direct), -schur_mat_mumps_* (mumps),
   -interior_ksp_*, -interior_pc_* (explicit).
@*/
PetscErrorCode SSStarReductionCreate(Mat K, IS isC, IS isI, SSStarReductionType type, PetscReal memoryLimit, SSStarReduction *red)
{
  SSStarReduction r;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(SSSTAR_Schur, K, 0, 0, 0));
  PetscCall(PetscNew(&r));
  r->type        = type;
  r->memoryLimit = memoryLimit;
  PetscCall(PetscObjectReference((PetscObject)isC));
  PetscCall(PetscObjectReference((PetscObject)isI));
  r->isC = isC;
  r->isI = isI;
  switch (type) {
  case SSSTAR_REDUCTION_DIRECT:
    PetscCall(SSStarDirectCreate(K, isC, memoryLimit, &r->direct, &r->P));
    break;
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
  PetscCall(CheckInteriorSolve(r, K));
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
  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(SSSTAR_Recovery, 0, 0, 0, 0));
  PetscCall(Recover(red, F, uC, rC, u));
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
  PetscCall(SSStarDirectDestroy(&(*red)->direct));
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
