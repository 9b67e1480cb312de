/*
   The Newton step of ssstar (DERIVATION.md section 5) in the nodes' frames R: with v = R u,
     A dv = y,   A = gamma S R P R^T + T   (S, T block diagonal, 3x3 per node),
   returned as du = R^T dv in the global frame.

   Dense P (a Schur complement): a row r of node i with S_i row r = 0 and T_i row r = e_r reads dv_ir = y_ir (every row
   of a sticking node, the normal row of a node in strong contact). With K these known dofs and R the others, A is block
   triangular, and only
     A_RR dv_R = y_R - A_RK y_K
   is solved. A_RR is assembled column by column from the local rows of P (the rotations applied on the fly) and
   factored by LAPACK on rank 0 (its rows gathered there); the factors are kept. While at most a given fraction of the
   nodes (by default none) changed their known dofs since that factorization, a step solves A_RR by GMRES
   preconditioned by the old A's inverse instead (the dofs that changed status moved over, see ApplyFactoredInverse);
   a fresh LU when more did or GMRES does not converge within about the cost of an LU.

   Sparse P: A R = gamma S R P + T R (the matrix of du) is formed by MatMatMult and factored by the SNES's KSP (LU;
   MUMPS in parallel).
*/
#if !defined(_GNU_SOURCE)
  #define _GNU_SOURCE /* sched_getaffinity */
#endif
#include "ssstarimpl.h"
#include <petscblaslapack.h>
#include <unistd.h>
#include <dlfcn.h>
#if defined(__linux__)
  #include <sched.h>
#endif

/* LAPACK routines PETSc 3.18 does not declare */
#define SSStarLAPACKgecon_ PETSCBLAS(gecon, GECON)
#define SSStarLAPACKlange_ PETSCBLAS(lange, LANGE)
BLAS_EXTERN void      SSStarLAPACKgecon_(const char *, const PetscBLASInt *, const PetscScalar *, const PetscBLASInt *, const PetscReal *, PetscReal *, PetscScalar *, PetscBLASInt *, PetscBLASInt *);
BLAS_EXTERN PetscReal SSStarLAPACKlange_(const char *, const PetscBLASInt *, const PetscBLASInt *, const PetscScalar *, const PetscBLASInt *, PetscReal *);

/* Which dofs a step knows: row r of local node i is known when S_i row r = 0 and T_i row r = e_r */
typedef struct {
  PetscBool  valid;
  PetscInt  *index;       /* per dof of every node (global numbering): its place among the unknowns, or -1 if known */
  PetscInt  *dofs;        /* the global dofs of the unknowns, in order                                              */
  PetscInt   n, N, start; /* unknowns: local, global, first local one                                               */
  PetscReal *S, *T;       /* the blocks of the local nodes (9 each)                                                 */
} Elimination;

/* LU of a dense matrix distributed by rows: the rows are gathered on rank 0 and factored by LAPACK there */
typedef struct {
  PetscInt      N;               /* order; -1 before the first factorization          */
  PetscMPIInt  *counts, *displs; /* rows per rank                                     */
  PetscScalar  *lu, *work;       /* rank 0: the factors (column-major), a vector      */
  size_t        capacity;        /* of lu                                             */
  PetscBLASInt *pivots;
  PetscReal     rcond;           /* LAPACK's estimate of 1/cond_1, or -1               */
  int           threads;         /* rank 0's BLAS threads during the factorization (0: leave them) */
} DenseLU;

struct _n_SSStarNewton {
  SNES      snes;
  Mat       P;
  PetscReal gamma;
  PetscBool dense;    /* the eliminated path */
  PetscReal reuse;    /* reuse the factors while at most this fraction of the nodes changed their known dofs */
  PetscInt  luThreads;/* rank 0's BLAS threads for the LU on several ranks; 0: the cores it may use */
  PetscReal rcond;    /* of the last factored Newton matrix, -1 if unknown */
  PetscInt  nFactor;  /* counts of the current SNESSolve: LU factorizations, */
  PetscInt  nReused;  /* steps solved on old factors,                         */
  PetscInt  nKrylov;  /* their Krylov iterations,                             */
  PetscInt  nFallback;/* reuse steps that fell back to a fresh LU             */

  /* sparse P */
  Mat S, T;  /* S' = S R and T' = T R, block diagonal with a fixed 3x3 pattern */
  Mat SP, A; /* S' P and A                                                     */

  /* dense P */
  PetscInt     nnodes, Nnodes, nodeStart; /* contact nodes: local, global, first local one                  */
  PetscMPIInt *nodeCounts, *nodeStarts;   /* per rank                                                      */
  PetscReal   *frames;                    /* of every node (9 each), or NULL for identities                */
  Elimination  cur, fac;                  /* of this step, of the factored matrix                          */
  Mat          Arr;                       /* A_RR of this step: the local rows of unknowns, every column    */
  Vec          x, rhs;                    /* in the layout of Arr                                           */
  PetscScalar *w, *q;                     /* R^T y_K of every node, P w on the local rows                  */
  DenseLU      lu;
  Vec          xf, bf;                    /* in the layout of the factored matrix                          */
  KSP          ksp;                       /* on Arr, preconditioned by the old factors                     */
  PetscBool    userMaxIt;                 /* its iteration limit was set by the user                       */
  PetscInt     nMoved;                    /* dofs known to the factors and unknown now (C)                  */
  PetscInt    *moved;                     /* their global dofs                                             */
  PetscMPIInt *movedCounts, *movedStarts; /* per rank                                                      */
  PetscScalar *Bmoved, *tMoved, *t;       /* A_fac[R_fac, C] (local rows), values on C, a local dof vector */
};

PetscErrorCode SSStarNewtonCreate(SNES snes, SSStarNewton *newton)
{
  PetscFunctionBegin;
  PetscCall(PetscNew(newton));
  (*newton)->snes  = snes;
  (*newton)->reuse     = 0;
  (*newton)->luThreads = 1;
  (*newton)->rcond = -1;
  (*newton)->lu.N  = -1;
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarNewtonSetReuse(SSStarNewton nt, PetscReal fraction)
{
  PetscFunctionBegin;
  nt->reuse = fraction;
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarNewtonGetReuse(SSStarNewton nt, PetscReal *fraction)
{
  PetscFunctionBegin;
  *fraction = nt->reuse;
  PetscFunctionReturn(0);
}

/* Takes effect with the next P */
PetscErrorCode SSStarNewtonSetLUThreads(SSStarNewton nt, PetscInt threads)
{
  PetscFunctionBegin;
  nt->luThreads = threads;
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarNewtonGetLUThreads(SSStarNewton nt, PetscInt *threads)
{
  PetscFunctionBegin;
  *threads = nt->luThreads;
  PetscFunctionReturn(0);
}

static PetscErrorCode EliminationDestroy(Elimination *e)
{
  PetscFunctionBegin;
  PetscCall(PetscFree2(e->index, e->dofs));
  PetscCall(PetscFree2(e->S, e->T));
  e->valid = PETSC_FALSE;
  PetscFunctionReturn(0);
}

static PetscErrorCode DenseLUDestroy(DenseLU *lu)
{
  PetscFunctionBegin;
  PetscCall(PetscFree2(lu->counts, lu->displs));
  PetscCall(PetscFree(lu->lu));
  PetscCall(PetscFree2(lu->work, lu->pivots));
  lu->capacity = 0;
  lu->N        = -1;
  PetscFunctionReturn(0);
}

/* Drops everything built for a P (the settings stay) */
PetscErrorCode SSStarNewtonReset(SSStarNewton nt)
{
  PetscFunctionBegin;
  if (!nt) PetscFunctionReturn(0);
  PetscCall(MatDestroy(&nt->P));
  PetscCall(MatDestroy(&nt->S));
  PetscCall(MatDestroy(&nt->T));
  PetscCall(MatDestroy(&nt->SP));
  PetscCall(MatDestroy(&nt->A));
  PetscCall(PetscFree2(nt->nodeCounts, nt->nodeStarts));
  PetscCall(PetscFree(nt->frames));
  PetscCall(EliminationDestroy(&nt->cur));
  PetscCall(EliminationDestroy(&nt->fac));
  PetscCall(MatDestroy(&nt->Arr));
  PetscCall(VecDestroy(&nt->x));
  PetscCall(VecDestroy(&nt->rhs));
  PetscCall(PetscFree2(nt->w, nt->q));
  PetscCall(DenseLUDestroy(&nt->lu));
  PetscCall(VecDestroy(&nt->xf));
  PetscCall(VecDestroy(&nt->bf));
  PetscCall(KSPDestroy(&nt->ksp));
  PetscCall(PetscFree(nt->moved));
  PetscCall(PetscFree2(nt->movedCounts, nt->movedStarts));
  PetscCall(PetscFree3(nt->Bmoved, nt->tMoved, nt->t));
  nt->nMoved = 0;
  PetscFunctionReturn(0);
}

static PetscErrorCode ApplyFactoredInverse(PC, Vec, Vec);
static PetscErrorCode LUThreads(MPI_Comm, PetscInt, int *);

static PetscErrorCode SetUpDense(SSStarNewton nt)
{
  MPI_Comm    comm = PetscObjectComm((PetscObject)nt->P);
  PetscMPIInt size, rank, nloc;
  PetscInt    m;
  PC          pc;
  const char *prefix;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(MatGetLocalSize(nt->P, &m, NULL));
  nt->nnodes = m / 3;
  PetscCall(PetscMalloc2(size, &nt->nodeCounts, size + 1, &nt->nodeStarts));
  PetscCall(PetscMPIIntCast(nt->nnodes, &nloc));
  PetscCallMPI(MPI_Allgather(&nloc, 1, MPI_INT, nt->nodeCounts, 1, MPI_INT, comm));
  nt->nodeStarts[0] = 0;
  for (PetscMPIInt r = 0; r < size; r++) nt->nodeStarts[r + 1] = nt->nodeStarts[r] + nt->nodeCounts[r];
  nt->Nnodes = nt->nodeStarts[size];
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  nt->nodeStart = nt->nodeStarts[rank];
  PetscCall(PetscMalloc2(PetscMax(3 * nt->Nnodes, 1), &nt->w, PetscMax(3 * nt->nnodes, 1), &nt->q));
  PetscCall(LUThreads(comm, nt->luThreads, &nt->lu.threads));

  /* the Krylov solver of the steps on old factors: GMRES with the preconditioner on the right, so that its residual
     is the true one */
  PetscCall(KSPCreate(comm, &nt->ksp));
  PetscCall(PetscObjectIncrementTabLevel((PetscObject)nt->ksp, (PetscObject)nt->snes, 1));
  PetscCall(SNESGetOptionsPrefix(nt->snes, &prefix));
  PetscCall(KSPSetOptionsPrefix(nt->ksp, prefix));
  PetscCall(KSPAppendOptionsPrefix(nt->ksp, "snes_ssstar_newton_"));
  PetscCall(KSPSetType(nt->ksp, KSPGMRES));
  PetscCall(KSPSetPCSide(nt->ksp, PC_RIGHT));
  PetscCall(KSPSetTolerances(nt->ksp, 1e-12, 0.0, PETSC_DEFAULT, PETSC_DEFAULT));
  PetscCall(KSPGetPC(nt->ksp, &pc));
  PetscCall(PCSetType(pc, PCSHELL));
  PetscCall(PCShellSetContext(pc, nt));
  PetscCall(PCShellSetApply(pc, ApplyFactoredInverse));
  PetscCall(PCShellSetName(pc, "the factors of an earlier Newton matrix"));
  PetscCall(KSPSetFromOptions(nt->ksp));
  PetscCall(PetscOptionsHasName(((PetscObject)nt->ksp)->options, ((PetscObject)nt->ksp)->prefix, "-ksp_max_it", &nt->userMaxIt));
  PetscFunctionReturn(0);
}

static PetscErrorCode SetUpSparse(SSStarNewton nt)
{
  SNES          snes = nt->snes;
  Mat           P    = nt->P;
  PetscInt      n, N;
  PC            pc;
  MatSolverType solver;
  PetscMPIInt   size;

  PetscFunctionBegin;
  PetscCall(MatGetLocalSize(P, &n, NULL));
  PetscCall(MatGetSize(P, &N, NULL));
  PetscCall(MatCreateAIJ(PetscObjectComm((PetscObject)P), n, n, N, N, 3, NULL, 0, NULL, &nt->S));
  PetscCall(MatSetBlockSize(nt->S, 3));
  PetscCall(MatSetOption(nt->S, MAT_IGNORE_ZERO_ENTRIES, PETSC_FALSE));
  PetscCall(MatDuplicate(nt->S, MAT_DO_NOT_COPY_VALUES, &nt->T));
  PetscCall(KSPGetPC(snes->ksp, &pc));
  PetscCall(PCFactorGetMatSolverType(pc, &solver));
  PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)P), &size));
  if (!solver && size > 1) PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  PetscFunctionReturn(0);
}

/* P (global frame) and gamma, for one SNESSolve; everything built from an earlier P is dropped */
PetscErrorCode SSStarNewtonSetOperator(SSStarNewton nt, Mat P, PetscReal gamma)
{
  PetscFunctionBegin;
  nt->gamma     = gamma;
  nt->rcond     = -1;
  nt->nFactor   = 0;
  nt->nReused   = 0;
  nt->nKrylov   = 0;
  nt->nFallback = 0;
  nt->fac.valid = PETSC_FALSE; /* gamma may have changed */
  if (P == nt->P) PetscFunctionReturn(0);
  PetscCall(SSStarNewtonReset(nt));
  PetscCall(PetscObjectReference((PetscObject)P));
  nt->P = P;
  /* SNESSetFromOptions() gave the KSP the user's Jacobian (K in the whole-body use), and PCSetFromOptions() may have made a factor for it */
  PetscCall(KSPReset(nt->snes->ksp));
  PetscCall(PetscObjectTypeCompareAny((PetscObject)P, &nt->dense, MATDENSE, MATMPIDENSE, MATSEQDENSE, ""));
  if (nt->dense) PetscCall(SetUpDense(nt));
  else PetscCall(SetUpSparse(nt));
  PetscFunctionReturn(0);
}

/* ---------------------------------------------------------------------------------------------------------------- */
/* sparse P */

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

static PetscErrorCode AssembleBlocks(SSStarNewton nt, const PetscReal frames[], const PetscReal S[], const PetscReal T[])
{
  PetscInt rstart, rend;

  PetscFunctionBegin;
  PetscCall(MatGetOwnershipRange(nt->S, &rstart, &rend));
  for (PetscInt i = 0; i < (rend - rstart) / 3; i++) {
    const PetscInt   idx[3] = {rstart + 3 * i, rstart + 3 * i + 1, rstart + 3 * i + 2};
    const PetscReal *R      = frames ? &frames[9 * i] : NULL;
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

/* (gamma S R P + T R) du = y */
static PetscErrorCode SolveSparse(SSStarNewton nt, const PetscReal frames[], const PetscReal S[], const PetscReal T[], Vec y, Vec du, PetscBool *solved)
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
  PetscCall(KSPSetOperators(snes->ksp, nt->A, nt->A));
  PetscCall(FactorNewtonMatrix(snes, solved));
  nt->nFactor++;
  if (!*solved) PetscFunctionReturn(0);
  PetscCall(KSPSolve(snes->ksp, y, du));
  PetscCall(KSPGetConvergedReason(snes->ksp, &kspreason));
  *solved = (PetscBool)(kspreason >= 0);
  /* a failed MUMPS factorization cannot be redone (its INFOG(1) stays negative): the next one starts afresh */
  if (!*solved) PetscCall(KSPReset(snes->ksp));
  PetscFunctionReturn(0);
}

/* ---------------------------------------------------------------------------------------------------------------- */
/* dense P: the eliminated system */

static PetscBool KnownRow(const PetscReal S[9], const PetscReal T[9], PetscInt r)
{
  for (PetscInt k = 0; k < 3; k++)
    if (S[3 * r + k] != 0.0 || T[3 * r + k] != (PetscReal)(k == r)) return PETSC_FALSE;
  return PETSC_TRUE;
}

static PetscErrorCode EliminationAllocate(SSStarNewton nt, Elimination *e)
{
  PetscFunctionBegin;
  if (e->index) PetscFunctionReturn(0);
  PetscCall(PetscMalloc2(3 * nt->Nnodes, &e->index, 3 * nt->Nnodes, &e->dofs));
  PetscCall(PetscMalloc2(9 * nt->nnodes, &e->S, 9 * nt->nnodes, &e->T));
  PetscFunctionReturn(0);
}

/* The known and unknown dofs of every node, from the blocks of the local nodes */
static PetscErrorCode BuildElimination(SSStarNewton nt, const PetscReal S[], const PetscReal T[], Elimination *e)
{
  MPI_Comm       comm = PetscObjectComm((PetscObject)nt->P);
  unsigned char *mask, *allMask;

  PetscFunctionBegin;
  PetscCall(EliminationAllocate(nt, e));
  PetscCall(PetscMalloc2(nt->nnodes, &mask, nt->Nnodes, &allMask));
  for (PetscInt i = 0; i < nt->nnodes; i++) {
    mask[i] = 0;
    for (PetscInt r = 0; r < 3; r++)
      if (!KnownRow(&S[9 * i], &T[9 * i], r)) mask[i] |= (unsigned char)(1 << r);
  }
  PetscCallMPI(MPI_Allgatherv(mask, (PetscMPIInt)nt->nnodes, MPI_UNSIGNED_CHAR, allMask, nt->nodeCounts, nt->nodeStarts, MPI_UNSIGNED_CHAR, comm));
  e->N = 0;
  for (PetscInt j = 0; j < nt->Nnodes; j++) {
    for (PetscInt r = 0; r < 3; r++) {
      if (allMask[j] & (1 << r)) {
        e->index[3 * j + r] = e->N;
        e->dofs[e->N++]     = 3 * j + r;
      } else e->index[3 * j + r] = -1;
    }
  }
  e->start = 0;
  e->n     = 0;
  for (PetscInt g = 0; g < 3 * nt->nodeStart; g++) e->start += e->index[g] >= 0;
  for (PetscInt g = 3 * nt->nodeStart; g < 3 * (nt->nodeStart + nt->nnodes); g++) e->n += e->index[g] >= 0;
  PetscCall(PetscArraycpy(e->S, S, 9 * nt->nnodes));
  PetscCall(PetscArraycpy(e->T, T, 9 * nt->nnodes));
  e->valid = PETSC_TRUE;
  PetscCall(PetscFree2(mask, allMask));
  PetscFunctionReturn(0);
}

static PetscErrorCode EliminationCopy(SSStarNewton nt, const Elimination *from, Elimination *to)
{
  PetscFunctionBegin;
  PetscCall(EliminationAllocate(nt, to));
  PetscCall(PetscArraycpy(to->index, from->index, 3 * nt->Nnodes));
  PetscCall(PetscArraycpy(to->dofs, from->dofs, from->N));
  PetscCall(PetscArraycpy(to->S, from->S, 9 * nt->nnodes));
  PetscCall(PetscArraycpy(to->T, from->T, 9 * nt->nnodes));
  to->n     = from->n;
  to->N     = from->N;
  to->start = from->start;
  to->valid = from->valid;
  PetscFunctionReturn(0);
}

/* Nodes whose known dofs differ between two eliminations (the same on every rank) */
static PetscInt ChangedNodes(SSStarNewton nt, const Elimination *a, const Elimination *b)
{
  PetscInt changed = 0;

  for (PetscInt j = 0; j < nt->Nnodes; j++)
    for (PetscInt r = 0; r < 3; r++)
      if ((a->index[3 * j + r] < 0) != (b->index[3 * j + r] < 0)) {
        changed++;
        break;
      }
  return changed;
}

/* The rows of the local unknowns of e: a row is M_a . (P' column)_{node} + T_i[r][.], M_a = gamma (S_i R_i) row r */
typedef struct {
  PetscInt   n;
  PetscInt  *base;  /* 3 i: the first row of the node in the local rows of P */
  PetscInt  *first; /* per local node: its first row among the unknowns       */
  PetscReal *M;     /* 3 per row                                              */
} RowMaps;

static PetscErrorCode RowMapsCreate(SSStarNewton nt, const Elimination *e, RowMaps *rm)
{
  const PetscReal *R = nt->frames;
  PetscInt         a = 0;

  PetscFunctionBegin;
  rm->n = e->n;
  PetscCall(PetscMalloc3(e->n, &rm->base, nt->nnodes + 1, &rm->first, 3 * e->n, &rm->M));
  for (PetscInt i = 0; i < nt->nnodes; i++) {
    const PetscReal *S  = &e->S[9 * i];
    const PetscReal *Ri = R ? &R[9 * (nt->nodeStart + i)] : NULL;

    rm->first[i] = a;
    for (PetscInt r = 0; r < 3; r++) {
      if (e->index[3 * (nt->nodeStart + i) + r] < 0) continue;
      rm->base[a] = 3 * i;
      for (PetscInt k = 0; k < 3; k++) {
        PetscReal sr = 0;

        for (PetscInt m = 0; m < 3; m++) sr += S[3 * r + m] * (Ri ? Ri[3 * m + k] : (PetscReal)(m == k));
        rm->M[3 * a + k] = nt->gamma * sr;
      }
      a++;
    }
  }
  rm->first[nt->nnodes] = a;
  PetscFunctionReturn(0);
}

static PetscErrorCode RowMapsDestroy(RowMaps *rm)
{
  PetscFunctionBegin;
  PetscCall(PetscFree3(rm->base, rm->first, rm->M));
  PetscFunctionReturn(0);
}

/*
   out[:, c] = A[R_e local rows, cols[c]] for the global dofs cols[], A = gamma S R P R^T + T with the blocks of e:
   column g = 3 j + l of P R^T is P[:, 3j..3j+2] R_j[l][.], and row a = (i, r) of A is M_a . (that column)[3i..3i+2].
*/
static PetscErrorCode AssembleColumns(SSStarNewton nt, const Elimination *e, PetscInt ncols, const PetscInt cols[], PetscScalar *out, PetscInt ldout)
{
  const PetscScalar *pa;
  PetscScalar       *buf = NULL;
  PetscInt           lda, m;
  RowMaps            rm;

  PetscFunctionBegin;
  PetscCall(RowMapsCreate(nt, e, &rm));
  PetscCall(MatDenseGetLDA(nt->P, &lda));
  PetscCall(MatDenseGetArrayRead(nt->P, &pa));
  m = 3 * nt->nnodes;
  if (nt->frames) PetscCall(PetscMalloc1(m, &buf));
  for (PetscInt c = 0; c < ncols; c++) {
    const PetscInt     g = cols[c], j = g / 3, l = g % 3, jl = j - nt->nodeStart;
    const PetscScalar *col;
    PetscScalar       *o = out + c * ldout;

    if (nt->frames) {
      const PetscReal   *Rj = &nt->frames[9 * j];
      const PetscScalar *p0 = pa + (3 * j) * lda, *p1 = p0 + lda, *p2 = p1 + lda;

      for (PetscInt k = 0; k < m; k++) buf[k] = p0[k] * Rj[3 * l] + p1[k] * Rj[3 * l + 1] + p2[k] * Rj[3 * l + 2];
      col = buf;
    } else col = pa + g * lda;
    for (PetscInt a = 0; a < rm.n; a++) {
      const PetscScalar *cb = col + rm.base[a];
      const PetscReal   *Ma = &rm.M[3 * a];

      o[a] = Ma[0] * cb[0] + Ma[1] * cb[1] + Ma[2] * cb[2];
    }
    if (jl >= 0 && jl < nt->nnodes) { /* the diagonal block: + T_j[r][l] */
      PetscInt a = rm.first[jl];

      for (PetscInt r = 0; r < 3; r++)
        if (e->index[g - l + r] >= 0) o[a++] += e->T[9 * jl + 3 * r + l];
    }
  }
  PetscCall(MatDenseRestoreArrayRead(nt->P, &pa));
  PetscCall(PetscFree(buf));
  PetscCall(RowMapsDestroy(&rm));
  PetscFunctionReturn(0);
}

/* A_RR of the current step */
static PetscErrorCode AssembleReducedMatrix(SSStarNewton nt)
{
  const Elimination *e = &nt->cur;
  PetscScalar       *aa;
  PetscInt           n = -1, N = -1;

  PetscFunctionBegin;
  if (nt->Arr) PetscCall(MatGetLocalSize(nt->Arr, &n, NULL));
  if (nt->Arr) PetscCall(MatGetSize(nt->Arr, &N, NULL));
  if (n != e->n || N != e->N) {
    PetscCall(MatDestroy(&nt->Arr));
    PetscCall(VecDestroy(&nt->x));
    PetscCall(VecDestroy(&nt->rhs));
    PetscCall(MatCreateDense(PetscObjectComm((PetscObject)nt->P), e->n, e->n, e->N, e->N, NULL, &nt->Arr));
    PetscCall(MatCreateVecs(nt->Arr, &nt->x, &nt->rhs));
  }
  PetscCall(MatDenseGetArrayWrite(nt->Arr, &aa));
  PetscCall(AssembleColumns(nt, e, e->N, e->dofs, aa, PetscMax(e->n, 1)));
  PetscCall(MatDenseRestoreArrayWrite(nt->Arr, &aa));
  PetscCall(MatAssemblyBegin(nt->Arr, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(nt->Arr, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

/*
   rhs = y_R - A_RK y_K. With w = R^T y_K (global frame, every node), A_RK y_K = gamma S R P w + T_RK y_K: P w on the
   local rows needs only the columns of P of known dofs.
*/
static PetscErrorCode BuildRightHandSide(SSStarNewton nt, Vec y)
{
  MPI_Comm           comm = PetscObjectComm((PetscObject)nt->P);
  const Elimination *e    = &nt->cur;
  const PetscScalar *ya, *pa;
  PetscScalar       *ra, *w = nt->w, *q = nt->q;
  PetscInt           lda, m = 3 * nt->nnodes;
  PetscMPIInt        size;
  PetscMPIInt       *counts, *starts;
  RowMaps            rm;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(PetscMalloc2(size, &counts, size, &starts));
  for (PetscMPIInt r = 0; r < size; r++) {
    counts[r] = 3 * nt->nodeCounts[r];
    starts[r] = 3 * nt->nodeStarts[r];
  }
  PetscCall(VecGetArrayRead(y, &ya));
  PetscCallMPI(MPI_Allgatherv(ya, (PetscMPIInt)m, MPIU_SCALAR, w, counts, starts, MPIU_SCALAR, comm));
  PetscCall(PetscFree2(counts, starts));
  for (PetscInt j = 0; j < nt->Nnodes; j++) {
    const PetscReal *R = nt->frames ? &nt->frames[9 * j] : NULL;
    PetscScalar      yk[3];

    for (PetscInt r = 0; r < 3; r++) yk[r] = e->index[3 * j + r] < 0 ? w[3 * j + r] : 0.0;
    for (PetscInt k = 0; k < 3; k++) w[3 * j + k] = R ? R[k] * yk[0] + R[3 + k] * yk[1] + R[6 + k] * yk[2] : yk[k];
  }
  PetscCall(PetscArrayzero(q, m));
  PetscCall(MatDenseGetLDA(nt->P, &lda));
  PetscCall(MatDenseGetArrayRead(nt->P, &pa));
  for (PetscInt g = 0; g < 3 * nt->Nnodes; g++) {
    const PetscScalar *col = pa + g * lda;

    if (w[g] == 0.0) continue;
    for (PetscInt k = 0; k < m; k++) q[k] += col[k] * w[g];
  }
  PetscCall(MatDenseRestoreArrayRead(nt->P, &pa));

  PetscCall(RowMapsCreate(nt, e, &rm));
  PetscCall(VecGetArrayWrite(nt->rhs, &ra));
  for (PetscInt i = 0; i < nt->nnodes; i++) {
    const PetscInt   g = 3 * (nt->nodeStart + i);
    const PetscReal *T = &e->T[9 * i];
    PetscInt         a = rm.first[i];

    for (PetscInt r = 0; r < 3; r++) {
      PetscScalar v;

      if (e->index[g + r] < 0) continue;
      v = ya[3 * i + r] - (rm.M[3 * a] * q[3 * i] + rm.M[3 * a + 1] * q[3 * i + 1] + rm.M[3 * a + 2] * q[3 * i + 2]);
      for (PetscInt c = 0; c < 3; c++)
        if (e->index[g + c] < 0) v -= T[3 * r + c] * ya[3 * i + c];
      ra[a++] = v;
    }
  }
  PetscCall(VecRestoreArrayWrite(nt->rhs, &ra));
  PetscCall(VecRestoreArrayRead(y, &ya));
  PetscCall(RowMapsDestroy(&rm));
  PetscFunctionReturn(0);
}

/* du = R^T dv with dv = y on the known dofs, x on the others */
static PetscErrorCode Expand(SSStarNewton nt, Vec y, Vec du)
{
  const Elimination *e = &nt->cur;
  const PetscScalar *ya, *xa;
  PetscScalar       *da;

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(y, &ya));
  PetscCall(VecGetArrayRead(nt->x, &xa));
  PetscCall(VecGetArrayWrite(du, &da));
  for (PetscInt i = 0; i < nt->nnodes; i++) {
    const PetscReal *R = nt->frames ? &nt->frames[9 * (nt->nodeStart + i)] : NULL;
    PetscScalar      dv[3];

    for (PetscInt r = 0; r < 3; r++) {
      const PetscInt idx = e->index[3 * (nt->nodeStart + i) + r];

      dv[r] = idx < 0 ? ya[3 * i + r] : xa[idx - e->start];
    }
    for (PetscInt k = 0; k < 3; k++) da[3 * i + k] = R ? R[k] * dv[0] + R[3 + k] * dv[1] + R[6 + k] * dv[2] : dv[k];
  }
  PetscCall(VecRestoreArrayWrite(du, &da));
  PetscCall(VecRestoreArrayRead(nt->x, &xa));
  PetscCall(VecRestoreArrayRead(y, &ya));
  PetscFunctionReturn(0);
}

/*
   On several ranks, the other ranks of rank 0's node sleep while it factors: its BLAS (OpenBLAS) may use their cores.
   The threads asked for (0: as many cores as rank 0 may run on, mpiexec --bind-to none, at most the ranks of its
   node); 0 = leave the BLAS as it is: on one rank, with 1 asked for, or without OpenBLAS.
*/
static PetscErrorCode LUThreads(MPI_Comm comm, PetscInt requested, int *threads)
{
  PetscMPIInt size, nodeSize;
  MPI_Comm    node;
  int         cpus = 1;

  PetscFunctionBegin;
  *threads = 0;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  if (size == 1 || requested == 1 || !dlsym(RTLD_DEFAULT, "openblas_set_num_threads")) PetscFunctionReturn(0);
  if (requested > 1) {
    *threads = (int)requested;
    PetscFunctionReturn(0);
  }
  PetscCallMPI(MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node));
  PetscCallMPI(MPI_Comm_size(node, &nodeSize));
  PetscCallMPI(MPI_Comm_free(&node));
#if defined(__linux__)
  {
    cpu_set_t set;

    if (!sched_getaffinity(0, sizeof(set), &set)) cpus = CPU_COUNT(&set);
  }
#endif
  *threads = PetscMin(cpus, nodeSize);
  PetscFunctionReturn(0);
}

/* Sets OpenBLAS's thread count and returns the previous one (0: nothing done) */
static int SetBLASThreads(int threads)
{
  void (*set)(int) = (void (*)(int))dlsym(RTLD_DEFAULT, "openblas_set_num_threads");
  int (*get)(void) = (int (*)(void))dlsym(RTLD_DEFAULT, "openblas_get_num_threads");
  int previous;

  if (!threads || !set || !get) return 0;
  previous = get();
  set(threads);
  return previous;
}

/*
   The other ranks wait for rank 0 without spinning in MPI, so that rank 0 (and its BLAS threads) may use their cores:
   they sleep, 10 us at first and up to 1 ms (waking often takes the core from rank 0 on a loaded machine)
*/
static PetscErrorCode WaitForRankZero(MPI_Comm comm)
{
  MPI_Request req;
  PetscMPIInt rank;
  int         done = 0;
  useconds_t  nap  = 10;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Ibarrier(comm, &req));
  if (rank == 0) {
    PetscCallMPI(MPI_Wait(&req, MPI_STATUS_IGNORE));
    done = 1;
  }
  while (!done) {
    PetscCallMPI(MPI_Test(&req, &done, MPI_STATUS_IGNORE));
    if (!done) usleep(nap);
    nap = PetscMin(2 * nap, 1000);
  }
  PetscFunctionReturn(0);
}

/* Gathers the rows of A (dense, local rows) on rank 0 and factors them there; ok on every rank */
static PetscErrorCode DenseLUFactor(Mat A, DenseLU *lu, PetscBool *ok)
{
  MPI_Comm           comm = PetscObjectComm((PetscObject)A);
  PetscMPIInt        rank, size, nloc;
  PetscInt           N, n, lda;
  const PetscScalar *aa;
  PetscReal          result[2] = {0, -1}; /* info, rcond */

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(MatGetSize(A, &N, NULL));
  PetscCall(MatGetLocalSize(A, &n, NULL));
  PetscCall(MatDenseGetLDA(A, &lda));
  PetscCheck(lda == n || n == 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Newton matrix with leading dimension %" PetscInt_FMT " != %" PetscInt_FMT " rows", lda, n);
  if (!lu->counts) PetscCall(PetscMalloc2(size, &lu->counts, size + 1, &lu->displs));
  PetscCall(PetscMPIIntCast(n, &nloc));
  PetscCallMPI(MPI_Allgather(&nloc, 1, MPI_INT, lu->counts, 1, MPI_INT, comm));
  lu->displs[0] = 0;
  for (PetscMPIInt r = 0; r < size; r++) lu->displs[r + 1] = lu->displs[r] + lu->counts[r];
  if (rank == 0 && (size_t)N * N > lu->capacity) {
    PetscCall(PetscFree(lu->lu));
    PetscCall(PetscMalloc1((size_t)N * N, &lu->lu));
    lu->capacity = (size_t)N * N;
  }
  if (rank == 0 && N != lu->N) {
    PetscCall(PetscFree2(lu->work, lu->pivots));
    PetscCall(PetscMalloc2(PetscMax(4 * N, 1), &lu->work, PetscMax(N, 1), &lu->pivots));
  }
  lu->N = N;
  PetscCall(MatDenseGetArrayRead(A, &aa));
  if (rank == 0) {
    MPI_Request *reqs;
    MPI_Datatype *types;
    PetscBLASInt  bn, info, *iwork;
    PetscReal     anorm;

    PetscCall(PetscMalloc2(size, &reqs, size, &types));
    for (PetscMPIInt r = 1; r < size; r++) {
      reqs[r] = MPI_REQUEST_NULL;
      if (!lu->counts[r]) continue;
      PetscCallMPI(MPI_Type_vector((PetscMPIInt)N, lu->counts[r], (PetscMPIInt)N, MPIU_SCALAR, &types[r]));
      PetscCallMPI(MPI_Type_commit(&types[r]));
      PetscCallMPI(MPI_Irecv(lu->lu + lu->displs[r], 1, types[r], r, 0, comm, &reqs[r]));
    }
    for (PetscInt c = 0; c < N; c++) PetscCall(PetscArraycpy(lu->lu + c * N, aa + c * n, n));
    if (size > 1) PetscCallMPI(MPI_Waitall(size - 1, reqs + 1, MPI_STATUSES_IGNORE));
    for (PetscMPIInt r = 1; r < size; r++)
      if (lu->counts[r]) PetscCallMPI(MPI_Type_free(&types[r]));
    PetscCall(PetscFree2(reqs, types));

    PetscCall(PetscBLASIntCast(N, &bn));
    if (N > 0) {
      PetscCall(PetscMalloc1(N, &iwork));
      anorm = SSStarLAPACKlange_("1", &bn, &bn, lu->lu, &bn, (PetscReal *)lu->work);
      const int previous = SetBLASThreads(lu->threads);

      PetscCallBLAS("LAPACKgetrf", LAPACKgetrf_(&bn, &bn, lu->lu, &bn, lu->pivots, &info));
      SetBLASThreads(previous);
      result[0] = info;
      if (!info) {
        PetscCallBLAS("LAPACKgecon", SSStarLAPACKgecon_("1", &bn, lu->lu, &bn, &anorm, &result[1], lu->work, iwork, &info));
        PetscCall(PetscLogFlops(2.0 / 3.0 * N * (double)N * N));
      }
      PetscCall(PetscFree(iwork));
    } else result[1] = 1;
  } else if (nloc) PetscCallMPI(MPI_Send(aa, nloc * (PetscMPIInt)N, MPIU_SCALAR, 0, 0, comm));
  PetscCall(MatDenseRestoreArrayRead(A, &aa));
  if (size > 1) PetscCall(WaitForRankZero(comm));
  PetscCallMPI(MPI_Bcast(result, 2, MPIU_REAL, 0, comm));
  *ok       = (PetscBool)(result[0] == 0);
  lu->rcond = result[1];
  PetscFunctionReturn(0);
}

/* x = A^-1 b by the factors of DenseLUFactor; b and x in the row layout of the factored A */
static PetscErrorCode DenseLUSolve(MPI_Comm comm, DenseLU *lu, Vec b, Vec x)
{
  PetscMPIInt        rank, nloc;
  PetscInt           n;
  const PetscScalar *ba;
  PetscScalar       *xa;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(VecGetLocalSize(b, &n));
  PetscCall(PetscMPIIntCast(n, &nloc));
  PetscCall(VecGetArrayRead(b, &ba));
  PetscCallMPI(MPI_Gatherv(ba, nloc, MPIU_SCALAR, lu->work, lu->counts, lu->displs, MPIU_SCALAR, 0, comm));
  PetscCall(VecRestoreArrayRead(b, &ba));
  if (rank == 0 && lu->N > 0) {
    PetscBLASInt bn, one = 1, info;

    PetscCall(PetscBLASIntCast(lu->N, &bn));
    PetscCallBLAS("LAPACKgetrs", LAPACKgetrs_("N", &bn, &one, lu->lu, &bn, lu->pivots, lu->work, &bn, &info));
    PetscCall(PetscLogFlops(2.0 * lu->N * (double)lu->N));
  }
  PetscCall(VecGetArrayWrite(x, &xa));
  PetscCallMPI(MPI_Scatterv(lu->work, lu->counts, lu->displs, MPIU_SCALAR, xa, nloc, MPIU_SCALAR, 0, comm));
  PetscCall(VecRestoreArrayWrite(x, &xa));
  PetscFunctionReturn(0);
}

/* A fresh LU of the current A_RR; it becomes the factored matrix */
static PetscErrorCode FactorReducedMatrix(SSStarNewton nt, PetscBool *ok)
{
  PetscFunctionBegin;
  PetscCall(DenseLUFactor(nt->Arr, &nt->lu, ok));
  nt->nFactor++;
  nt->rcond = nt->lu.rcond;
  PetscCall(EliminationCopy(nt, &nt->cur, &nt->fac));
  if (!*ok) nt->fac.valid = PETSC_FALSE;
  PetscCall(VecDestroy(&nt->xf));
  PetscCall(VecDestroy(&nt->bf));
  PetscCall(VecDuplicate(nt->x, &nt->xf));
  PetscCall(VecDuplicate(nt->x, &nt->bf));
  PetscFunctionReturn(0);
}

/*
   The preconditioner of a step on old factors: with F the factored matrix (A of an earlier step, block triangular
   in its own known dofs K_F, A_F = [A_FF A_FK; 0 I]) and C the dofs known to F and unknown now, r on the current
   unknowns R is extended by 0 on the current known dofs and F^-1 is applied:
     x_C = r_C,   x_RF = A_FF^-1 (r_RF - A_F[R_F, C] r_C),
   then restricted to R. Exact when A did not change; A - F is zero outside the rows of nodes whose blocks changed.
*/
static PetscErrorCode ApplyFactoredInverse(PC pc, Vec r, Vec x)
{
  SSStarNewton       nt;
  MPI_Comm           comm;
  const Elimination *cur, *fac;
  const PetscScalar *ra, *xfa;
  PetscScalar       *xa, *ba, *t;
  PetscMPIInt        rank;
  PetscInt           a;

  PetscFunctionBegin;
  PetscCall(PCShellGetContext(pc, &nt));
  PetscCall(PetscObjectGetComm((PetscObject)pc, &comm));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  cur = &nt->cur;
  fac = &nt->fac;
  t   = nt->t;
  /* r extended by 0 to every local dof, and its values on C gathered from every rank */
  PetscCall(VecGetArrayRead(r, &ra));
  for (PetscInt d = 0; d < 3 * nt->nnodes; d++) {
    const PetscInt g = 3 * nt->nodeStart + d;

    t[d] = cur->index[g] >= 0 ? ra[cur->index[g] - cur->start] : 0.0;
  }
  PetscCall(VecRestoreArrayRead(r, &ra));
  for (PetscInt c = nt->movedStarts[rank]; c < nt->movedStarts[rank + 1]; c++) nt->tMoved[c] = t[nt->moved[c] - 3 * nt->nodeStart];
  if (nt->nMoved) PetscCallMPI(MPI_Allgatherv(MPI_IN_PLACE, 0, MPIU_SCALAR, nt->tMoved, nt->movedCounts, nt->movedStarts, MPIU_SCALAR, comm));
  /* b = r_RF - A_F[R_F, C] r_C */
  PetscCall(VecGetArrayWrite(nt->bf, &ba));
  a = 0;
  for (PetscInt d = 0; d < 3 * nt->nnodes; d++)
    if (fac->index[3 * nt->nodeStart + d] >= 0) ba[a++] = t[d];
  if (nt->nMoved && fac->n) {
    PetscBLASInt m, nc, one = 1;
    PetscScalar  mone = -1.0, pone = 1.0;

    PetscCall(PetscBLASIntCast(fac->n, &m));
    PetscCall(PetscBLASIntCast(nt->nMoved, &nc));
    PetscCallBLAS("BLASgemv", BLASgemv_("N", &m, &nc, &mone, nt->Bmoved, &m, nt->tMoved, &one, &pone, ba, &one));
    PetscCall(PetscLogFlops(2.0 * fac->n * nt->nMoved));
  }
  PetscCall(VecRestoreArrayWrite(nt->bf, &ba));
  PetscCall(DenseLUSolve(comm, &nt->lu, nt->bf, nt->xf));
  /* restricted to R: x_RF where F had the dof unknown, r on C */
  PetscCall(VecGetArrayRead(nt->xf, &xfa));
  PetscCall(VecGetArrayWrite(x, &xa));
  a = 0;
  for (PetscInt d = 0; d < 3 * nt->nnodes; d++) {
    const PetscInt g = 3 * nt->nodeStart + d;

    if (cur->index[g] < 0) continue;
    xa[a++] = fac->index[g] >= 0 ? xfa[fac->index[g] - fac->start] : t[d];
  }
  PetscCall(VecRestoreArrayWrite(x, &xa));
  PetscCall(VecRestoreArrayRead(nt->xf, &xfa));
  PetscFunctionReturn(0);
}

/* C (known to the factors, unknown now) and A_F[R_F local rows, C] for ApplyFactoredInverse */
static PetscErrorCode SetUpReuse(SSStarNewton nt)
{
  MPI_Comm    comm = PetscObjectComm((PetscObject)nt->P);
  PetscMPIInt size;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  if (!nt->movedCounts) PetscCall(PetscMalloc2(size, &nt->movedCounts, size + 1, &nt->movedStarts));
  PetscCall(PetscFree(nt->moved));
  PetscCall(PetscFree3(nt->Bmoved, nt->tMoved, nt->t));
  nt->nMoved = 0;
  for (PetscInt g = 0; g < 3 * nt->Nnodes; g++) nt->nMoved += (nt->fac.index[g] < 0 && nt->cur.index[g] >= 0);
  PetscCall(PetscMalloc1(nt->nMoved, &nt->moved));
  nt->nMoved         = 0;
  nt->movedStarts[0] = 0;
  for (PetscMPIInt r = 0; r < size; r++) {
    for (PetscInt g = 3 * nt->nodeStarts[r]; g < 3 * nt->nodeStarts[r + 1]; g++)
      if (nt->fac.index[g] < 0 && nt->cur.index[g] >= 0) nt->moved[nt->nMoved++] = g;
    nt->movedStarts[r + 1] = (PetscMPIInt)nt->nMoved;
    nt->movedCounts[r]     = nt->movedStarts[r + 1] - nt->movedStarts[r];
  }
  PetscCall(PetscMalloc3(PetscMax(nt->fac.n * nt->nMoved, 1), &nt->Bmoved, PetscMax(nt->nMoved, 1), &nt->tMoved, PetscMax(3 * nt->nnodes, 1), &nt->t));
  PetscCall(AssembleColumns(nt, &nt->fac, nt->nMoved, nt->moved, nt->Bmoved, PetscMax(nt->fac.n, 1)));
  PetscFunctionReturn(0);
}

static PetscErrorCode GatherFrames(SSStarNewton nt, const PetscReal frames[])
{
  MPI_Comm     comm = PetscObjectComm((PetscObject)nt->P);
  PetscBool    has  = (PetscBool)(frames != NULL);
  PetscMPIInt  size, n9;
  PetscMPIInt *counts, *starts;

  PetscFunctionBegin;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &has, 1, MPIU_BOOL, MPI_LOR, comm));
  if (!has) {
    PetscCall(PetscFree(nt->frames));
    PetscFunctionReturn(0);
  }
  PetscCallMPI(MPI_Comm_size(comm, &size));
  if (!nt->frames) PetscCall(PetscMalloc1(9 * nt->Nnodes, &nt->frames));
  PetscCall(PetscMalloc2(size, &counts, size, &starts));
  for (PetscMPIInt r = 0; r < size; r++) {
    counts[r] = 9 * nt->nodeCounts[r];
    starts[r] = 9 * nt->nodeStarts[r];
  }
  n9 = 9 * (PetscMPIInt)nt->nnodes;
  PetscCallMPI(MPI_Allgatherv(frames, n9, MPIU_REAL, nt->frames, counts, starts, MPIU_REAL, comm));
  PetscCall(PetscFree2(counts, starts));
  PetscFunctionReturn(0);
}

static PetscErrorCode SolveDense(SSStarNewton nt, const PetscReal frames[], const PetscReal S[], const PetscReal T[], Vec y, Vec du, PetscBool *solved)
{
  PetscBool reuse;

  PetscFunctionBegin;
  PetscCall(GatherFrames(nt, frames));
  PetscCall(BuildElimination(nt, S, T, &nt->cur));
  reuse = (PetscBool)(nt->fac.valid && nt->reuse >= 0 && ChangedNodes(nt, &nt->cur, &nt->fac) <= nt->reuse * nt->Nnodes);
  PetscCall(PetscLogEventBegin(SSSTAR_NewtonAssemble, nt->snes, 0, 0, 0));
  PetscCall(AssembleReducedMatrix(nt));
  PetscCall(BuildRightHandSide(nt, y));
  PetscCall(PetscLogEventEnd(SSSTAR_NewtonAssemble, nt->snes, 0, 0, 0));
  *solved = PETSC_TRUE;
  if (reuse) {
    KSPConvergedReason reason;
    PetscInt           its;

    PetscCall(PetscLogEventBegin(SSSTAR_NewtonKrylov, nt->snes, 0, 0, 0));
    PetscCall(SetUpReuse(nt));
    PetscCall(KSPReset(nt->ksp)); /* the order of A_RR changes from step to step */
    if (!nt->userMaxIt) { /* GMRES may cost about one LU: an iteration reads A_RR and the factors, ~ N_R/100 of an LU here */
      const PetscInt maxit = PetscMax(10, nt->cur.N / 100);

      PetscCall(KSPSetTolerances(nt->ksp, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT, maxit));
      PetscCall(KSPGMRESSetRestart(nt->ksp, maxit));
    }
    PetscCall(KSPSetOperators(nt->ksp, nt->Arr, nt->Arr));
    PetscCall(KSPSolve(nt->ksp, nt->rhs, nt->x));
    PetscCall(PetscLogEventEnd(SSSTAR_NewtonKrylov, nt->snes, 0, 0, 0));
    PetscCall(KSPGetConvergedReason(nt->ksp, &reason));
    PetscCall(KSPGetIterationNumber(nt->ksp, &its));
    nt->nKrylov += its;
    nt->snes->linear_its += its;
    if (reason > 0) nt->nReused++;
    else {
      nt->nFallback++;
      reuse = PETSC_FALSE;
    }
  }
  if (!reuse) {
    PetscCall(PetscLogEventBegin(SSSTAR_NewtonFactor, nt->snes, 0, 0, 0));
    PetscCall(FactorReducedMatrix(nt, solved));
    if (*solved) PetscCall(DenseLUSolve(PetscObjectComm((PetscObject)nt->P), &nt->lu, nt->rhs, nt->x));
    PetscCall(PetscLogEventEnd(SSSTAR_NewtonFactor, nt->snes, 0, 0, 0));
    if (!*solved) PetscFunctionReturn(0);
  }
  PetscCall(Expand(nt, y, du));
  PetscFunctionReturn(0);
}

/*
   Solves (gamma S R P R^T + T) R du = y for du (global frame); solved is PETSC_FALSE (on every rank) when the Newton
   matrix is singular or the linear solve failed.
*/
PetscErrorCode SSStarNewtonSolve(SSStarNewton nt, const PetscReal frames[], const PetscReal S[], const PetscReal T[], Vec y, Vec du, PetscBool *solved)
{
  PetscFunctionBegin;
  if (nt->dense) PetscCall(SolveDense(nt, frames, S, T, y, du, solved));
  else PetscCall(SolveSparse(nt, frames, S, T, y, du, solved));
  PetscFunctionReturn(0);
}

/* 1/cond_1 of the last factored Newton matrix (LAPACK's estimate), or -1 when the factorization gives none */
PetscErrorCode SSStarNewtonGetConditionEstimate(SSStarNewton nt, PetscReal *rcond)
{
  PetscFunctionBegin;
  *rcond = nt->rcond;
  PetscFunctionReturn(0);
}

/* LU factorizations, steps solved on old factors and their Krylov iterations, in the current SNESSolve */
PetscErrorCode SSStarNewtonGetCounts(SSStarNewton nt, PetscInt *factorizations, PetscInt *reused, PetscInt *krylov)
{
  PetscFunctionBegin;
  if (factorizations) *factorizations = nt->nFactor;
  if (reused) *reused = nt->nReused;
  if (krylov) *krylov = nt->nKrylov;
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarNewtonView(SSStarNewton nt, PetscViewer viewer)
{
  PetscFunctionBegin;
  if (nt->P && !nt->dense) PetscCall(PetscViewerASCIIPrintf(viewer, "  Newton step (sparse P): (gamma S P + T) du = (S + T) z formed and factored by the KSP\n"));
  else {
    char threads[64] = "";

    if (nt->lu.threads > 1) PetscCall(PetscSNPrintf(threads, sizeof(threads), " (%d BLAS threads)", nt->lu.threads));
    PetscCall(PetscViewerASCIIPrintf(viewer, "  Newton step (dense P): the dofs of sticking nodes and the normals of nodes in contact eliminated, LU of the others by LAPACK on rank 0%s\n", threads));
    if (nt->reuse < 0) PetscCall(PetscViewerASCIIPrintf(viewer, "    a fresh LU at every step\n"));
    else if (nt->reuse == 0) PetscCall(PetscViewerASCIIPrintf(viewer, "    a step is solved by GMRES on the last LU when no node changed its known rows since it\n"));
    else PetscCall(PetscViewerASCIIPrintf(viewer, "    a step is solved by GMRES on the last LU when at most %g%% of the nodes changed their known rows since it\n", (double)(100 * nt->reuse)));
  }
  if (nt->P) PetscCall(PetscViewerASCIIPrintf(viewer, "    last solve: %" PetscInt_FMT " LU factorizations (last 1/cond %g), %" PetscInt_FMT " steps on an old LU (%" PetscInt_FMT " Krylov iterations), %" PetscInt_FMT " fallbacks to a fresh LU\n", nt->nFactor, (double)nt->rcond, nt->nReused, nt->nKrylov, nt->nFallback));
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
