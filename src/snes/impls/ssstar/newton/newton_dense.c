/*
   The Newton step with a dense P (a Schur complement), in the nodes' frames R: with v = R u,
     A dv = y,   A = gamma S R P R^T + T   (S, T block diagonal, 3x3 per node),
   returned as du = R^T dv in the global frame.

   A row r of node i with S_i row r = 0 and T_i row r = e_r reads dv_ir = y_ir (every row of a sticking node, the
   normal row of a node in strong contact). With K these known dofs and R the others, A is block triangular, and only
     A_RR dv_R = y_R - A_RK y_K
   is solved. A_RR is assembled column by column from the local rows of P (the rotations applied on the fly) and
   LU-factored (denselu.c); the factors are kept. While at most a given fraction of the nodes (by default none)
   changed their known dofs since that factorization, a step solves A_RR by GMRES preconditioned by the old A's
   inverse instead (the dofs that changed status moved over, see ApplyFactoredInverse); a fresh LU when more did or
   GMRES does not converge within about the cost of an LU.
*/
#include "newtonimpl.h"
#include <petscblaslapack.h>

/* Which dofs a step knows: row r of local node i is known when S_i row r = 0 and T_i row r = e_r */
typedef struct {
  PetscBool  valid;
  PetscInt  *index;       /* per dof of every node (global numbering): its place among the unknowns, or -1 if known */
  PetscInt  *dofs;        /* the global dofs of the unknowns, in order                                              */
  PetscInt   n, N, start; /* unknowns: local, global, first local one                                               */
  PetscReal *S, *T;       /* the blocks of the local nodes (9 each)                                                 */
} Elimination;

typedef struct {
  PetscInt      nnodes, Nnodes, nodeStart; /* contact nodes: local, global, first local one                  */
  PetscMPIInt  *nodeCounts, *nodeStarts;   /* per rank                                                      */
  PetscReal    *allFrames;                 /* of every node (9 each), or NULL for identities                */
  Elimination   cur, fac;                  /* of this step, of the factored matrix                          */
  Mat           Arr;                       /* A_RR of this step: the local rows of unknowns, every column    */
  Vec           x, rhs;                    /* in the layout of Arr                                           */
  PetscScalar  *w, *q;                     /* R^T y_K of every node, P w on the local rows                  */
  SSStarDenseLU lu;
  Vec           xf, bf;                    /* in the layout of the factored matrix                          */
  KSP           ksp;                       /* on Arr, preconditioned by the old factors                     */
  PetscBool     userMaxIt;                 /* its iteration limit was set by the user                       */
  PetscInt      nMoved;                    /* dofs known to the factors and unknown now (C)                  */
  PetscInt     *moved;                     /* their global dofs                                             */
  PetscMPIInt  *movedCounts, *movedStarts; /* per rank                                                      */
  PetscScalar  *Bmoved, *tMoved, *t;       /* A_fac[R_fac, C] (local rows), values on C, a local dof vector */
  PetscInt      nfree;                     /* floating bodies: the step's free motions (newtonimpl.h)       */
  PetscReal    *freeAll;                   /* of every node in its frame: freeAll[g nfree + f]               */
} Newton_Dense;

static PetscErrorCode ApplyFactoredInverse(PC, Vec, Vec);

static PetscErrorCode EliminationDestroy(Elimination *e)
{
  PetscFunctionBegin;
  PetscCall(PetscFree2(e->index, e->dofs));
  PetscCall(PetscFree2(e->S, e->T));
  e->valid = PETSC_FALSE;
  PetscFunctionReturn(0);
}

static PetscErrorCode SSStarNewtonSetUp_Dense(SSStarNewton nt)
{
  Newton_Dense *dn = (Newton_Dense *)nt->data;
  MPI_Comm    comm = PetscObjectComm((PetscObject)nt->A);
  PetscMPIInt size, rank, nloc;
  PetscInt    m;
  PC          pc;
  const char *prefix;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(MatGetLocalSize(nt->A, &m, NULL));
  dn->nnodes = m / 3;
  PetscCall(PetscMalloc2(size, &dn->nodeCounts, size + 1, &dn->nodeStarts));
  PetscCall(PetscMPIIntCast(dn->nnodes, &nloc));
  PetscCallMPI(MPI_Allgather(&nloc, 1, MPI_INT, dn->nodeCounts, 1, MPI_INT, comm));
  dn->nodeStarts[0] = 0;
  for (PetscMPIInt r = 0; r < size; r++) dn->nodeStarts[r + 1] = dn->nodeStarts[r] + dn->nodeCounts[r];
  dn->Nnodes = dn->nodeStarts[size];
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  dn->nodeStart = dn->nodeStarts[rank];
  PetscCall(PetscMalloc2(PetscMax(3 * dn->Nnodes, 1), &dn->w, PetscMax(3 * dn->nnodes, 1), &dn->q));
  PetscCall(SSStarDenseLUSetThreads(comm, nt->luThreads, &dn->lu));

  /* the Krylov solver of the steps on old factors: GMRES with the preconditioner on the right, so that its residual
     is the true one */
  PetscCall(KSPCreate(comm, &dn->ksp));
  PetscCall(PetscObjectIncrementTabLevel((PetscObject)dn->ksp, (PetscObject)nt->snes, 1));
  PetscCall(SNESGetOptionsPrefix(nt->snes, &prefix));
  PetscCall(KSPSetOptionsPrefix(dn->ksp, prefix));
  PetscCall(KSPAppendOptionsPrefix(dn->ksp, "snes_ssstar_newton_"));
  PetscCall(KSPSetType(dn->ksp, KSPGMRES));
  PetscCall(KSPSetPCSide(dn->ksp, PC_RIGHT));
  PetscCall(KSPSetTolerances(dn->ksp, 1e-12, 0.0, PETSC_DEFAULT, PETSC_DEFAULT));
  PetscCall(KSPGetPC(dn->ksp, &pc));
  PetscCall(PCSetType(pc, PCSHELL));
  PetscCall(PCShellSetContext(pc, nt));
  PetscCall(PCShellSetApply(pc, ApplyFactoredInverse));
  PetscCall(PCShellSetName(pc, "the factors of an earlier Newton matrix"));
  PetscCall(KSPSetFromOptions(dn->ksp));
  PetscCall(PetscOptionsHasName(((PetscObject)dn->ksp)->options, ((PetscObject)dn->ksp)->prefix, "-ksp_max_it", &dn->userMaxIt));
  PetscFunctionReturn(0);
}

static PetscErrorCode EliminationAllocate(SSStarNewton nt, Elimination *e)
{
  Newton_Dense *dn = (Newton_Dense *)nt->data;

  PetscFunctionBegin;
  if (e->index) PetscFunctionReturn(0);
  PetscCall(PetscMalloc2(3 * dn->Nnodes, &e->index, 3 * dn->Nnodes, &e->dofs));
  PetscCall(PetscMalloc2(9 * dn->nnodes, &e->S, 9 * dn->nnodes, &e->T));
  PetscFunctionReturn(0);
}

/* The known and unknown dofs of every node, from the blocks of the local nodes */
static PetscErrorCode BuildElimination(SSStarNewton nt, const PetscReal S[], const PetscReal T[], Elimination *e)
{
  Newton_Dense *dn = (Newton_Dense *)nt->data;
  MPI_Comm       comm = PetscObjectComm((PetscObject)nt->A);
  unsigned char *mask, *allMask;

  PetscFunctionBegin;
  PetscCall(EliminationAllocate(nt, e));
  PetscCall(PetscMalloc2(dn->nnodes, &mask, dn->Nnodes, &allMask));
  for (PetscInt i = 0; i < dn->nnodes; i++) {
    mask[i] = 0;
    for (PetscInt r = 0; r < 3; r++)
      if (!SSStarKnownRow(&S[9 * i], &T[9 * i], r)) mask[i] |= (unsigned char)(1 << r);
  }
  PetscCallMPI(MPI_Allgatherv(mask, (PetscMPIInt)dn->nnodes, MPI_UNSIGNED_CHAR, allMask, dn->nodeCounts, dn->nodeStarts, MPI_UNSIGNED_CHAR, comm));
  e->N = 0;
  for (PetscInt j = 0; j < dn->Nnodes; j++) {
    for (PetscInt r = 0; r < 3; r++) {
      if (allMask[j] & (1 << r)) {
        e->index[3 * j + r] = e->N;
        e->dofs[e->N++]     = 3 * j + r;
      } else e->index[3 * j + r] = -1;
    }
  }
  e->start = 0;
  e->n     = 0;
  for (PetscInt g = 0; g < 3 * dn->nodeStart; g++) e->start += e->index[g] >= 0;
  for (PetscInt g = 3 * dn->nodeStart; g < 3 * (dn->nodeStart + dn->nnodes); g++) e->n += e->index[g] >= 0;
  PetscCall(PetscArraycpy(e->S, S, 9 * dn->nnodes));
  PetscCall(PetscArraycpy(e->T, T, 9 * dn->nnodes));
  e->valid = PETSC_TRUE;
  PetscCall(PetscFree2(mask, allMask));
  PetscFunctionReturn(0);
}

static PetscErrorCode EliminationCopy(SSStarNewton nt, const Elimination *from, Elimination *to)
{
  Newton_Dense *dn = (Newton_Dense *)nt->data;

  PetscFunctionBegin;
  PetscCall(EliminationAllocate(nt, to));
  PetscCall(PetscArraycpy(to->index, from->index, 3 * dn->Nnodes));
  PetscCall(PetscArraycpy(to->dofs, from->dofs, from->N));
  PetscCall(PetscArraycpy(to->S, from->S, 9 * dn->nnodes));
  PetscCall(PetscArraycpy(to->T, from->T, 9 * dn->nnodes));
  to->n     = from->n;
  to->N     = from->N;
  to->start = from->start;
  to->valid = from->valid;
  PetscFunctionReturn(0);
}

/* Nodes whose known dofs differ between two eliminations (the same on every rank) */
static PetscInt ChangedNodes(SSStarNewton nt, const Elimination *a, const Elimination *b)
{
  Newton_Dense *dn = (Newton_Dense *)nt->data;
  PetscInt changed = 0;

  for (PetscInt j = 0; j < dn->Nnodes; j++)
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
  Newton_Dense *dn = (Newton_Dense *)nt->data;
  const PetscReal *R = dn->allFrames;
  PetscInt         a = 0;

  PetscFunctionBegin;
  rm->n = e->n;
  PetscCall(PetscMalloc3(e->n, &rm->base, dn->nnodes + 1, &rm->first, 3 * e->n, &rm->M));
  for (PetscInt i = 0; i < dn->nnodes; i++) {
    const PetscReal *S  = &e->S[9 * i];
    const PetscReal *Ri = R ? &R[9 * (dn->nodeStart + i)] : NULL;

    rm->first[i] = a;
    for (PetscInt r = 0; r < 3; r++) {
      if (e->index[3 * (dn->nodeStart + i) + r] < 0) continue;
      rm->base[a] = 3 * i;
      for (PetscInt k = 0; k < 3; k++) {
        PetscReal sr = 0;

        for (PetscInt m = 0; m < 3; m++) sr += S[3 * r + m] * (Ri ? Ri[3 * m + k] : (PetscReal)(m == k));
        rm->M[3 * a + k] = nt->gamma * sr;
      }
      a++;
    }
  }
  rm->first[dn->nnodes] = a;
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
   With free motions U of floating bodies, P + (SSSTAR_FREE_STIFFNESS / gamma) U U^T: column g gains U (R U)[g, .]^T.
   (They vanish at the known dofs, so the right-hand side's A_RK y_K does not see them.)
*/
static PetscErrorCode AssembleColumns(SSStarNewton nt, const Elimination *e, PetscInt ncols, const PetscInt cols[], PetscScalar *out, PetscInt ldout)
{
  Newton_Dense *dn = (Newton_Dense *)nt->data;
  const PetscScalar *pa;
  PetscScalar       *buf = NULL;
  PetscInt           lda, m;
  RowMaps            rm;

  PetscFunctionBegin;
  PetscCall(RowMapsCreate(nt, e, &rm));
  PetscCall(MatDenseGetLDA(nt->A, &lda));
  PetscCall(MatDenseGetArrayRead(nt->A, &pa));
  m = 3 * dn->nnodes;
  if (dn->allFrames || dn->nfree) PetscCall(PetscMalloc1(m, &buf));
  for (PetscInt c = 0; c < ncols; c++) {
    const PetscInt     g = cols[c], j = g / 3, l = g % 3, jl = j - dn->nodeStart;
    const PetscScalar *col;
    PetscScalar       *o = out + c * ldout;

    if (dn->allFrames) {
      const PetscReal   *Rj = &dn->allFrames[9 * j];
      const PetscScalar *p0 = pa + (3 * j) * lda, *p1 = p0 + lda, *p2 = p1 + lda;

      for (PetscInt k = 0; k < m; k++) buf[k] = p0[k] * Rj[3 * l] + p1[k] * Rj[3 * l + 1] + p2[k] * Rj[3 * l + 2];
      col = buf;
    } else col = pa + g * lda;
    if (dn->nfree) {
      const PetscReal  coef = SSSTAR_FREE_STIFFNESS / nt->gamma;
      const PetscReal *ug = nt->layout.floating->freeGlobal, *uf = &dn->freeAll[g * dn->nfree];

      if (col != buf) PetscCall(PetscArraycpy(buf, col, m));
      for (PetscInt f = 0; f < dn->nfree; f++)
        for (PetscInt k = 0; k < m; k++) buf[k] += coef * ug[f * m + k] * uf[f];
      col = buf;
    }
    for (PetscInt a = 0; a < rm.n; a++) {
      const PetscScalar *cb = col + rm.base[a];
      const PetscReal   *Ma = &rm.M[3 * a];

      o[a] = Ma[0] * cb[0] + Ma[1] * cb[1] + Ma[2] * cb[2];
    }
    if (jl >= 0 && jl < dn->nnodes) { /* the diagonal block: + T_j[r][l] */
      PetscInt a = rm.first[jl];

      for (PetscInt r = 0; r < 3; r++)
        if (e->index[g - l + r] >= 0) o[a++] += e->T[9 * jl + 3 * r + l];
    }
  }
  PetscCall(MatDenseRestoreArrayRead(nt->A, &pa));
  PetscCall(PetscFree(buf));
  PetscCall(RowMapsDestroy(&rm));
  PetscFunctionReturn(0);
}

/* A_RR of the current step */
static PetscErrorCode AssembleReducedMatrix(SSStarNewton nt)
{
  Newton_Dense *dn = (Newton_Dense *)nt->data;
  const Elimination *e = &dn->cur;
  PetscScalar       *aa;
  PetscInt           n = -1, N = -1;
  PetscBool          resize;

  PetscFunctionBegin;
  if (dn->Arr) PetscCall(MatGetLocalSize(dn->Arr, &n, NULL));
  if (dn->Arr) PetscCall(MatGetSize(dn->Arr, &N, NULL));
  /* decided together: the unknown dofs may move between ranks and leave their number N as it was */
  resize = (PetscBool)(n != e->n || N != e->N);
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &resize, 1, MPIU_BOOL, MPI_LOR, PetscObjectComm((PetscObject)nt->A)));
  if (resize) {
    PetscCall(MatDestroy(&dn->Arr));
    PetscCall(VecDestroy(&dn->x));
    PetscCall(VecDestroy(&dn->rhs));
    PetscCall(MatCreateDense(PetscObjectComm((PetscObject)nt->A), e->n, e->n, e->N, e->N, NULL, &dn->Arr));
    PetscCall(MatCreateVecs(dn->Arr, &dn->x, &dn->rhs));
  }
  PetscCall(MatDenseGetArrayWrite(dn->Arr, &aa));
  PetscCall(AssembleColumns(nt, e, e->N, e->dofs, aa, PetscMax(e->n, 1)));
  PetscCall(MatDenseRestoreArrayWrite(dn->Arr, &aa));
  PetscCall(MatAssemblyBegin(dn->Arr, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(dn->Arr, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

/*
   rhs = y_R - A_RK y_K. With w = R^T y_K (global frame, every node), A_RK y_K = gamma S R P w + T_RK y_K: P w on the
   local rows needs only the columns of P of known dofs.
*/
static PetscErrorCode BuildRightHandSide(SSStarNewton nt, Vec y)
{
  Newton_Dense *dn = (Newton_Dense *)nt->data;
  MPI_Comm           comm = PetscObjectComm((PetscObject)nt->A);
  const Elimination *e    = &dn->cur;
  const PetscScalar *ya, *pa;
  PetscScalar       *ra, *w = dn->w, *q = dn->q;
  PetscInt           lda, m = 3 * dn->nnodes;
  PetscMPIInt        size;
  PetscMPIInt       *counts, *starts;
  RowMaps            rm;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(PetscMalloc2(size, &counts, size, &starts));
  for (PetscMPIInt r = 0; r < size; r++) {
    counts[r] = 3 * dn->nodeCounts[r];
    starts[r] = 3 * dn->nodeStarts[r];
  }
  PetscCall(VecGetArrayRead(y, &ya));
  PetscCallMPI(MPI_Allgatherv(ya, (PetscMPIInt)m, MPIU_SCALAR, w, counts, starts, MPIU_SCALAR, comm));
  PetscCall(PetscFree2(counts, starts));
  for (PetscInt j = 0; j < dn->Nnodes; j++) {
    const PetscReal *R = dn->allFrames ? &dn->allFrames[9 * j] : NULL;
    PetscScalar      yk[3];

    for (PetscInt r = 0; r < 3; r++) yk[r] = e->index[3 * j + r] < 0 ? w[3 * j + r] : 0.0;
    for (PetscInt k = 0; k < 3; k++) w[3 * j + k] = R ? R[k] * yk[0] + R[3 + k] * yk[1] + R[6 + k] * yk[2] : yk[k];
  }
  PetscCall(PetscArrayzero(q, m));
  PetscCall(MatDenseGetLDA(nt->A, &lda));
  PetscCall(MatDenseGetArrayRead(nt->A, &pa));
  for (PetscInt g = 0; g < 3 * dn->Nnodes; g++) {
    const PetscScalar *col = pa + g * lda;

    if (w[g] == 0.0) continue;
    for (PetscInt k = 0; k < m; k++) q[k] += col[k] * w[g];
  }
  PetscCall(MatDenseRestoreArrayRead(nt->A, &pa));

  PetscCall(RowMapsCreate(nt, e, &rm));
  PetscCall(VecGetArrayWrite(dn->rhs, &ra));
  for (PetscInt i = 0; i < dn->nnodes; i++) {
    const PetscInt   g = 3 * (dn->nodeStart + i);
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
  PetscCall(VecRestoreArrayWrite(dn->rhs, &ra));
  PetscCall(VecRestoreArrayRead(y, &ya));
  PetscCall(RowMapsDestroy(&rm));
  PetscFunctionReturn(0);
}

/* du = R^T dv with dv = y on the known dofs, x on the others */
static PetscErrorCode Expand(SSStarNewton nt, Vec y, Vec du)
{
  Newton_Dense *dn = (Newton_Dense *)nt->data;
  const Elimination *e = &dn->cur;
  const PetscScalar *ya, *xa;
  PetscScalar       *da;

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(y, &ya));
  PetscCall(VecGetArrayRead(dn->x, &xa));
  PetscCall(VecGetArrayWrite(du, &da));
  for (PetscInt i = 0; i < dn->nnodes; i++) {
    const PetscReal *R = dn->allFrames ? &dn->allFrames[9 * (dn->nodeStart + i)] : NULL;
    PetscScalar      dv[3];

    for (PetscInt r = 0; r < 3; r++) {
      const PetscInt idx = e->index[3 * (dn->nodeStart + i) + r];

      dv[r] = idx < 0 ? ya[3 * i + r] : xa[idx - e->start];
    }
    for (PetscInt k = 0; k < 3; k++) da[3 * i + k] = R ? R[k] * dv[0] + R[3 + k] * dv[1] + R[6 + k] * dv[2] : dv[k];
  }
  PetscCall(VecRestoreArrayWrite(du, &da));
  PetscCall(VecRestoreArrayRead(dn->x, &xa));
  PetscCall(VecRestoreArrayRead(y, &ya));
  PetscFunctionReturn(0);
}


/* A fresh LU of the current A_RR; it becomes the factored matrix */
static PetscErrorCode FactorReducedMatrix(SSStarNewton nt, PetscBool *ok)
{
  Newton_Dense *dn = (Newton_Dense *)nt->data;

  PetscLogDouble t0, t1;

  PetscFunctionBegin;
  PetscCall(PetscTime(&t0));
  PetscCall(SSStarDenseLUFactor(dn->Arr, &dn->lu, ok));
  PetscCall(PetscTime(&t1));
  nt->factorSeconds += t1 - t0;
  nt->nFactor++;
  nt->rcond = dn->lu.rcond;
  PetscCall(EliminationCopy(nt, &dn->cur, &dn->fac));
  if (!*ok) dn->fac.valid = PETSC_FALSE;
  PetscCall(VecDestroy(&dn->xf));
  PetscCall(VecDestroy(&dn->bf));
  PetscCall(VecDuplicate(dn->x, &dn->xf));
  PetscCall(VecDuplicate(dn->x, &dn->bf));
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
  Newton_Dense      *dn;
  MPI_Comm           comm;
  const Elimination *cur, *fac;
  const PetscScalar *ra, *xfa;
  PetscScalar       *xa, *ba, *t;
  PetscMPIInt        rank;
  PetscInt           a;

  PetscFunctionBegin;
  PetscCall(PCShellGetContext(pc, &nt));
  dn = (Newton_Dense *)nt->data;
  PetscCall(PetscObjectGetComm((PetscObject)pc, &comm));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  cur = &dn->cur;
  fac = &dn->fac;
  t   = dn->t;
  /* r extended by 0 to every local dof, and its values on C gathered from every rank */
  PetscCall(VecGetArrayRead(r, &ra));
  for (PetscInt d = 0; d < 3 * dn->nnodes; d++) {
    const PetscInt g = 3 * dn->nodeStart + d;

    t[d] = cur->index[g] >= 0 ? ra[cur->index[g] - cur->start] : 0.0;
  }
  PetscCall(VecRestoreArrayRead(r, &ra));
  for (PetscInt c = dn->movedStarts[rank]; c < dn->movedStarts[rank + 1]; c++) dn->tMoved[c] = t[dn->moved[c] - 3 * dn->nodeStart];
  if (dn->nMoved) PetscCallMPI(MPI_Allgatherv(MPI_IN_PLACE, 0, MPIU_SCALAR, dn->tMoved, dn->movedCounts, dn->movedStarts, MPIU_SCALAR, comm));
  /* b = r_RF - A_F[R_F, C] r_C */
  PetscCall(VecGetArrayWrite(dn->bf, &ba));
  a = 0;
  for (PetscInt d = 0; d < 3 * dn->nnodes; d++)
    if (fac->index[3 * dn->nodeStart + d] >= 0) ba[a++] = t[d];
  if (dn->nMoved && fac->n) {
    PetscBLASInt m, nc, one = 1;
    PetscScalar  mone = -1.0, pone = 1.0;

    PetscCall(PetscBLASIntCast(fac->n, &m));
    PetscCall(PetscBLASIntCast(dn->nMoved, &nc));
    PetscCallBLAS("BLASgemv", BLASgemv_("N", &m, &nc, &mone, dn->Bmoved, &m, dn->tMoved, &one, &pone, ba, &one));
    PetscCall(PetscLogFlops(2.0 * fac->n * dn->nMoved));
  }
  PetscCall(VecRestoreArrayWrite(dn->bf, &ba));
  PetscCall(SSStarDenseLUSolve(comm, &dn->lu, dn->bf, dn->xf));
  /* restricted to R: x_RF where F had the dof unknown, r on C */
  PetscCall(VecGetArrayRead(dn->xf, &xfa));
  PetscCall(VecGetArrayWrite(x, &xa));
  a = 0;
  for (PetscInt d = 0; d < 3 * dn->nnodes; d++) {
    const PetscInt g = 3 * dn->nodeStart + d;

    if (cur->index[g] < 0) continue;
    xa[a++] = fac->index[g] >= 0 ? xfa[fac->index[g] - fac->start] : t[d];
  }
  PetscCall(VecRestoreArrayWrite(x, &xa));
  PetscCall(VecRestoreArrayRead(dn->xf, &xfa));
  PetscFunctionReturn(0);
}

/* C (known to the factors, unknown now) and A_F[R_F local rows, C] for ApplyFactoredInverse */
static PetscErrorCode SetUpReuse(SSStarNewton nt)
{
  Newton_Dense *dn = (Newton_Dense *)nt->data;
  MPI_Comm    comm = PetscObjectComm((PetscObject)nt->A);
  PetscMPIInt size;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  if (!dn->movedCounts) PetscCall(PetscMalloc2(size, &dn->movedCounts, size + 1, &dn->movedStarts));
  PetscCall(PetscFree(dn->moved));
  PetscCall(PetscFree3(dn->Bmoved, dn->tMoved, dn->t));
  dn->nMoved = 0;
  for (PetscInt g = 0; g < 3 * dn->Nnodes; g++) dn->nMoved += (dn->fac.index[g] < 0 && dn->cur.index[g] >= 0);
  PetscCall(PetscMalloc1(dn->nMoved, &dn->moved));
  dn->nMoved         = 0;
  dn->movedStarts[0] = 0;
  for (PetscMPIInt r = 0; r < size; r++) {
    for (PetscInt g = 3 * dn->nodeStarts[r]; g < 3 * dn->nodeStarts[r + 1]; g++)
      if (dn->fac.index[g] < 0 && dn->cur.index[g] >= 0) dn->moved[dn->nMoved++] = g;
    dn->movedStarts[r + 1] = (PetscMPIInt)dn->nMoved;
    dn->movedCounts[r]     = dn->movedStarts[r + 1] - dn->movedStarts[r];
  }
  PetscCall(PetscMalloc3(PetscMax(dn->fac.n * dn->nMoved, 1), &dn->Bmoved, PetscMax(dn->nMoved, 1), &dn->tMoved, PetscMax(3 * dn->nnodes, 1), &dn->t));
  PetscCall(AssembleColumns(nt, &dn->fac, dn->nMoved, dn->moved, dn->Bmoved, PetscMax(dn->fac.n, 1)));
  PetscFunctionReturn(0);
}

static PetscErrorCode GatherFrames(SSStarNewton nt)
{
  Newton_Dense    *dn     = (Newton_Dense *)nt->data;
  const PetscReal *frames = nt->layout.frames;
  MPI_Comm     comm = PetscObjectComm((PetscObject)nt->A);
  PetscBool    has  = (PetscBool)(frames != NULL);
  PetscMPIInt  size, n9;
  PetscMPIInt *counts, *starts;

  PetscFunctionBegin;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &has, 1, MPIU_BOOL, MPI_LOR, comm));
  if (!has) {
    PetscCall(PetscFree(dn->allFrames));
    PetscFunctionReturn(0);
  }
  PetscCallMPI(MPI_Comm_size(comm, &size));
  if (!dn->allFrames) PetscCall(PetscMalloc1(9 * dn->Nnodes, &dn->allFrames));
  PetscCall(PetscMalloc2(size, &counts, size, &starts));
  for (PetscMPIInt r = 0; r < size; r++) {
    counts[r] = 9 * dn->nodeCounts[r];
    starts[r] = 9 * dn->nodeStarts[r];
  }
  n9 = 9 * (PetscMPIInt)dn->nnodes;
  PetscCallMPI(MPI_Allgatherv(frames, n9, MPIU_REAL, dn->allFrames, counts, starts, MPIU_REAL, comm));
  PetscCall(PetscFree2(counts, starts));
  PetscFunctionReturn(0);
}

/* The free motions of floating bodies of this step (in the nodes' frames) of every node, for the columns */
static PetscErrorCode GatherFreeMotions(SSStarNewton nt)
{
  Newton_Dense *dn = (Newton_Dense *)nt->data;
  SSStarFloating *fb = nt->layout.floating;
  MPI_Comm      comm = PetscObjectComm((PetscObject)nt->A);
  PetscMPIInt   size, *counts, *starts;
  PetscReal    *mine;

  PetscFunctionBegin;
  PetscCall(PetscFree(dn->freeAll));
  dn->nfree = fb ? fb->nfree : 0; /* the same on every rank */
  if (!dn->nfree) PetscFunctionReturn(0);
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(PetscMalloc1(3 * dn->Nnodes * dn->nfree, &dn->freeAll));
  PetscCall(PetscMalloc3(3 * dn->nnodes * dn->nfree + 1, &mine, size, &counts, size, &starts));
  for (PetscInt d = 0; d < 3 * dn->nnodes; d++)
    for (PetscInt f = 0; f < dn->nfree; f++) mine[d * dn->nfree + f] = fb->free[f * 3 * dn->nnodes + d];
  for (PetscMPIInt r = 0; r < size; r++) {
    counts[r] = (PetscMPIInt)(3 * dn->nodeCounts[r] * dn->nfree);
    starts[r] = (PetscMPIInt)(3 * dn->nodeStarts[r] * dn->nfree);
  }
  PetscCallMPI(MPI_Allgatherv(mine, (PetscMPIInt)(3 * dn->nnodes * dn->nfree), MPIU_REAL, dn->freeAll, counts, starts, MPIU_REAL, comm));
  PetscCall(PetscFree3(mine, counts, starts));
  PetscFunctionReturn(0);
}

static PetscErrorCode SSStarNewtonSolve_Dense(SSStarNewton nt, const PetscReal S[], const PetscReal T[], Vec y, Vec du, PetscBool *solved)
{
  Newton_Dense *dn = (Newton_Dense *)nt->data;
  PetscBool reuse;

  PetscFunctionBegin;
  PetscCall(GatherFrames(nt));
  PetscCall(GatherFreeMotions(nt));
  PetscCall(BuildElimination(nt, S, T, &dn->cur));
  reuse = (PetscBool)(dn->fac.valid && nt->reuse >= 0 && ChangedNodes(nt, &dn->cur, &dn->fac) <= nt->reuse * dn->Nnodes);
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
    PetscCall(KSPReset(dn->ksp)); /* the order of A_RR changes from step to step */
    if (!dn->userMaxIt) { /* GMRES may cost about one LU: an iteration reads A_RR and the factors, ~ N_R/100 of an LU here */
      const PetscInt maxit = PetscMax(10, dn->cur.N / 100);

      PetscCall(KSPSetTolerances(dn->ksp, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT, maxit));
      PetscCall(KSPGMRESSetRestart(dn->ksp, maxit));
    }
    PetscCall(KSPSetOperators(dn->ksp, dn->Arr, dn->Arr));
    PetscCall(KSPSolve(dn->ksp, dn->rhs, dn->x));
    PetscCall(PetscLogEventEnd(SSSTAR_NewtonKrylov, nt->snes, 0, 0, 0));
    PetscCall(KSPGetConvergedReason(dn->ksp, &reason));
    PetscCall(KSPGetIterationNumber(dn->ksp, &its));
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
    if (*solved) PetscCall(SSStarDenseLUSolve(PetscObjectComm((PetscObject)nt->A), &dn->lu, dn->rhs, dn->x));
    PetscCall(PetscLogEventEnd(SSSTAR_NewtonFactor, nt->snes, 0, 0, 0));
    if (!*solved) PetscFunctionReturn(0);
  }
  PetscCall(Expand(nt, y, du));
  PetscFunctionReturn(0);
}


/* A new gamma: the factors of the old Newton matrix do not apply */
static PetscErrorCode SSStarNewtonSetScaling_Dense(SSStarNewton nt)
{
  Newton_Dense *dn = (Newton_Dense *)nt->data;

  PetscFunctionBegin;
  dn->fac.valid = PETSC_FALSE;
  PetscFunctionReturn(0);
}

static PetscErrorCode SSStarNewtonView_Dense(SSStarNewton nt, PetscViewer viewer)
{
  Newton_Dense *dn          = (Newton_Dense *)nt->data;
  char          threads[64] = "";

  PetscFunctionBegin;
  if (dn->lu.threads > 1) PetscCall(PetscSNPrintf(threads, sizeof(threads), " (%d BLAS threads)", dn->lu.threads));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  Newton step (dense P): the dofs of sticking nodes and the normals of nodes in contact eliminated, LU of the others by LAPACK on rank 0%s\n", threads));
  if (nt->reuse < 0) PetscCall(PetscViewerASCIIPrintf(viewer, "    a fresh LU at every step\n"));
  else if (nt->reuse == 0) PetscCall(PetscViewerASCIIPrintf(viewer, "    a step is solved by GMRES on the last LU when no node changed its known rows since it\n"));
  else PetscCall(PetscViewerASCIIPrintf(viewer, "    a step is solved by GMRES on the last LU when at most %g%% of the nodes changed their known rows since it\n", (double)(100 * nt->reuse)));
  PetscCall(PetscViewerASCIIPrintf(viewer, "    last solve: %" PetscInt_FMT " LU factorizations (last 1/cond %g), %" PetscInt_FMT " steps on an old LU (%" PetscInt_FMT " Krylov iterations), %" PetscInt_FMT " fallbacks to a fresh LU\n", nt->nFactor, (double)nt->rcond, nt->nReused, nt->nKrylov, nt->nFallback));
  PetscFunctionReturn(0);
}

static PetscErrorCode SSStarNewtonReset_Dense(SSStarNewton nt)
{
  Newton_Dense *dn = (Newton_Dense *)nt->data;

  PetscFunctionBegin;
  PetscCall(PetscFree2(dn->nodeCounts, dn->nodeStarts));
  PetscCall(PetscFree(dn->allFrames));
  PetscCall(EliminationDestroy(&dn->cur));
  PetscCall(EliminationDestroy(&dn->fac));
  PetscCall(MatDestroy(&dn->Arr));
  PetscCall(VecDestroy(&dn->x));
  PetscCall(VecDestroy(&dn->rhs));
  PetscCall(PetscFree2(dn->w, dn->q));
  PetscCall(SSStarDenseLUDestroy(&dn->lu));
  PetscCall(VecDestroy(&dn->xf));
  PetscCall(VecDestroy(&dn->bf));
  PetscCall(KSPDestroy(&dn->ksp));
  PetscCall(PetscFree(dn->moved));
  PetscCall(PetscFree2(dn->movedCounts, dn->movedStarts));
  PetscCall(PetscFree3(dn->Bmoved, dn->tMoved, dn->t));
  PetscCall(PetscFree(dn->freeAll));
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarNewtonCreate_Dense(SSStarNewton nt)
{
  Newton_Dense *dn;

  PetscFunctionBegin;
  nt->snes->usesksp = PETSC_FALSE; /* the Newton systems are solved by dense LU and its own GMRES */
  PetscCall(PetscNew(&dn));
  dn->lu.N            = -1;
  nt->data            = dn;
  nt->ops.setup       = SSStarNewtonSetUp_Dense;
  nt->ops.setscaling  = SSStarNewtonSetScaling_Dense;
  nt->ops.solve       = SSStarNewtonSolve_Dense;
  nt->ops.view        = SSStarNewtonView_Dense;
  nt->ops.reset       = SSStarNewtonReset_Dense;
  PetscFunctionReturn(0);
}
