/*
   What the reductions share: the names of their options, the memory they plan for, checked before any of it is taken
   (MUMPS's factors and the dense matrices of P's size, per rank, against -snes_ssstar_memory_limit or the node's
   MemAvailable; auto asks here too), and MUMPS's failures in words.
*/
#include "reductionimpl.h"
#include "../sys/meminfo.h"

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
    PetscCall(SSStarMemAvailable(&available));
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

PetscErrorCode SSStarReductionOptionName(SSStarReduction red, const char option[], char name[], size_t len)
{
  PetscFunctionBegin;
  PetscCall(PetscSNPrintf(name, len, "-%s%s", red->prefix ? red->prefix : "", option));
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
PetscErrorCode SSStarReductionCheckFactor(MPI_Comm comm, PetscMPIInt root, Mat F, PetscLogDouble estimate, const char what[], const char icntl[])
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
