/*
   The contact operator B (docs/contact-operator.md): the map from the whole displacement u to each contact point's
   relative displacement in its frame (t1, t2, n), w = B u + g, with w_n >= 0 and the friction law on w_t. A point i
   owns three dofs s_i of u (its slave node), where B has a positive multiple of a rotation,

     B_i = d_i R_i (E_{s_i} - M_i),   d_i > 0, R_i a rotation (rows t1, t2, n), M_i on dofs that are no point's own,

   so that w_i / d_i = R_i (u_{s_i} - M_i u) + g_i / d_i: a rigid obstacle is M_i = 0 (SNESSSStarSetContactNodes),
   a point against another body's surface has M_i = the weights of the master dofs it is compared with. The change of
   variables u = T v, T = I + E_S^T M (v: the slave dofs replaced by u_s - M u, the other dofs kept) turns every point
   into a node against a rigid obstacle: K becomes T^T K T (SPD), b becomes T^T b, and the rest of the solver (the
   kernels, the reductions, the Newton steps) does not change. T is unit triangular: invertible, v = u - E_S^T M u.
   Without master dofs (every point against a rigid obstacle, SNESSSStarSetContactNodes()) there is no T.
*/
#include "ssstarimpl.h"
#include <petscblaslapack.h>

/* det of a 3x3 row-major matrix */
static PetscReal Det3(const PetscReal A[9])
{
  return A[0] * (A[4] * A[8] - A[5] * A[7]) - A[1] * (A[3] * A[8] - A[5] * A[6]) + A[2] * (A[3] * A[7] - A[4] * A[6]);
}

/* max |R R^T - I| */
static PetscReal OrthogonalityDefect(const PetscReal R[9])
{
  PetscReal defect = 0;

  for (PetscInt r = 0; r < 3; r++)
    for (PetscInt c = 0; c < 3; c++) {
      PetscReal dot = R[3 * r] * R[3 * c] + R[3 * r + 1] * R[3 * c + 1] + R[3 * r + 2] * R[3 * c + 2];

      defect = PetscMax(defect, PetscAbsReal(dot - (PetscReal)(r == c)));
    }
  return defect;
}

/* A rotation within round-off: the block of a point at its own dofs, divided by d */
#define SSSTAR_ROTATION_TOL 1e-8

/*
   From B: the frame R_i and the scale d_i of every point (solver's order), and T = I + E_S^T M with
   M_i = -(1/d_i) R_i^T (B_i without the point's own columns). Refuses what makes B rank-deficient or T singular,
   naming the points, on every rank: a block at a point's own dofs that is not an invertible multiple of a rotation,
   and a point's own dofs among the dofs another point is compared with.
*/
PetscErrorCode SSStarContactOperatorSetUp(MPI_Comm comm, SSStarContact *ct, Mat B, Vec x)
{
  PetscInt        rB, n = ct->nnodes, m, xstart, nmaster = 0, *dnz, *onz, xend;
  const PetscInt *idx;
  PetscInt      **cols;
  PetscScalar   **vals;
  PetscInt       *ncols;
  PetscBool       tilted = PETSC_FALSE;
  Vec             mark;
  PetscScalar    *ma;
  char            msg[512] = "";

  PetscFunctionBegin;
  PetscCall(MatGetOwnershipRange(B, &rB, NULL));
  PetscCall(VecGetOwnershipRange(x, &xstart, &xend));
  PetscCall(VecGetLocalSize(x, &m));
  PetscCall(ISGetIndices(ct->dofs, &idx));
  PetscCall(PetscMalloc1(9 * n, &ct->frames));
  PetscCall(PetscMalloc1(n, &ct->pointScale));
  PetscCall(PetscMalloc3(3 * n, &ncols, 3 * n, &cols, 3 * n, &vals));
  /* mark: 1 at every point's own dofs, to find those a point is compared with */
  PetscCall(VecDuplicate(x, &mark));
  PetscCall(VecZeroEntries(mark));
  PetscCall(VecGetArray(mark, &ma));
  for (PetscInt k = 0; k < 3 * n; k++) ma[idx[k] - xstart] = 1;
  PetscCall(VecRestoreArray(mark, &ma));

  for (PetscInt i = 0; i < n; i++) {
    const PetscInt   j = ct->order[i], *own = &idx[3 * j];
    PetscReal        S[9] = {0}, d, *R = &ct->frames[9 * i];
    PetscInt         nc;
    const PetscInt  *rc;
    const PetscScalar *rv;

    for (PetscInt c = 0; c < 3; c++) {
      const PetscInt row = 3 * i + c;

      PetscCall(MatGetRow(B, rB + 3 * j + c, &nc, &rc, &rv));
      PetscCall(PetscMalloc2(nc, &cols[row], nc, &vals[row]));
      ncols[row] = 0;
      for (PetscInt e = 0; e < nc; e++) {
        PetscInt k;

        for (k = 0; k < 3 && rc[e] != own[k]; k++) continue;
        if (k < 3) S[3 * c + k] = PetscRealPart(rv[e]);
        else if (rv[e] != 0.0) {
          cols[row][ncols[row]]   = rc[e];
          vals[row][ncols[row]++] = rv[e];
        }
      }
      PetscCall(MatRestoreRow(B, rB + 3 * j + c, &nc, &rc, &rv));
    }
    d = Det3(S);
    if (!(d > 0) && !msg[0]) PetscCall(PetscSNPrintf(msg, sizeof(msg), "SNESSSStarSetContactOperator: contact point %" PetscInt_FMT " (dofs %" PetscInt_FMT ", %" PetscInt_FMT ", %" PetscInt_FMT "): B's block at the point's own dofs has determinant %g, not positive: B is rank-deficient there (or its rows are not t1, t2, n)", j, own[0], own[1], own[2], (double)d));
    d = d > 0 ? PetscCbrtReal(d) : 1;
    for (PetscInt k = 0; k < 9; k++) R[k] = S[k] / d;
    if (!(OrthogonalityDefect(R) <= SSSTAR_ROTATION_TOL) && !msg[0]) PetscCall(PetscSNPrintf(msg, sizeof(msg), "SNESSSStarSetContactOperator: contact point %" PetscInt_FMT " (dofs %" PetscInt_FMT ", %" PetscInt_FMT ", %" PetscInt_FMT "): B's block at the point's own dofs is not a positive multiple of a rotation (rows t1, t2, n; defect %g)", j, own[0], own[1], own[2], (double)OrthogonalityDefect(R)));
    ct->pointScale[i] = d;
    if (R[0] != 1.0 || R[4] != 1.0 || R[8] != 1.0) tilted = PETSC_TRUE;
    for (PetscInt c = 0; c < 3; c++) nmaster += ncols[3 * i + c];
  }
  PetscCall(ISRestoreIndices(ct->dofs, &idx));
  PetscCall(SSStarCheckAllRanks(comm, PETSC_ERR_ARG_WRONG, msg));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &tilted, 1, MPIU_BOOL, MPI_LOR, comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &nmaster, 1, MPIU_INT, MPI_SUM, comm));
  if (!tilted) PetscCall(PetscFree(ct->frames));

  /* T = I + E_S^T M, rows of point i's own dofs: x_s = v_s + M_i v, M_i = -(1/d_i) R_i^T B_i(masters) */
  PetscCall(MatDestroy(&ct->T));
  if (nmaster > 0) {
    IS          isMaster;
    Vec         seen;
    VecScatter  toSeen;
    PetscInt   *all, nall = 0;
    const PetscScalar *sa;

    /* no master dof may be a point's own dof */
    for (PetscInt r = 0; r < 3 * n; r++) nall += ncols[r];
    PetscCall(PetscMalloc1(nall, &all));
    nall = 0;
    for (PetscInt r = 0; r < 3 * n; r++)
      for (PetscInt e = 0; e < ncols[r]; e++) all[nall++] = cols[r][e];
    PetscCall(ISCreateGeneral(PETSC_COMM_SELF, nall, all, PETSC_COPY_VALUES, &isMaster));
    PetscCall(VecCreateSeq(PETSC_COMM_SELF, nall, &seen));
    PetscCall(VecScatterCreate(mark, isMaster, seen, NULL, &toSeen));
    PetscCall(VecScatterBegin(toSeen, mark, seen, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterEnd(toSeen, mark, seen, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecGetArrayRead(seen, &sa));
    nall = 0;
    for (PetscInt i = 0; i < n; i++)
      for (PetscInt c = 0; c < 3; c++)
        for (PetscInt e = 0; e < ncols[3 * i + c]; e++, nall++)
          if (sa[nall] != 0.0 && !msg[0]) PetscCall(PetscSNPrintf(msg, sizeof(msg), "SNESSSStarSetContactOperator: contact point %" PetscInt_FMT " is compared with dof %" PetscInt_FMT ", which is another contact point's own dof: a node may be a slave or a master, not both", ct->order[i], cols[3 * i + c][e]));
    PetscCall(VecRestoreArrayRead(seen, &sa));
    PetscCall(VecScatterDestroy(&toSeen));
    PetscCall(VecDestroy(&seen));
    PetscCall(ISDestroy(&isMaster));
    PetscCall(PetscFree(all));
    PetscCall(SSStarCheckAllRanks(comm, PETSC_ERR_ARG_WRONG, msg));

    PetscCall(PetscCalloc2(m, &dnz, m, &onz));
    for (PetscInt r = 0; r < m; r++) dnz[r] = 1;
    PetscCall(ISGetIndices(ct->isC, &idx)); /* the solver's order: point i's dofs at 3 i */
    for (PetscInt i = 0; i < n; i++)
      for (PetscInt k = 0; k < 3; k++) {
        const PetscInt row = idx[3 * i + k] - xstart;

        for (PetscInt c = 0; c < 3; c++) /* row k of R^T B_m: every column of the point's three rows */
          for (PetscInt e = 0; e < ncols[3 * i + c]; e++) {
            if (cols[3 * i + c][e] >= xstart && cols[3 * i + c][e] < xend) dnz[row]++;
            else onz[row]++;
          }
      }
    PetscCall(MatCreateAIJ(comm, m, m, PETSC_DETERMINE, PETSC_DETERMINE, 0, dnz, 0, onz, &ct->T));
    PetscCall(PetscFree2(dnz, onz));
    PetscCall(MatSetOption(ct->T, MAT_NO_OFF_PROC_ENTRIES, PETSC_TRUE));
    for (PetscInt r = xstart; r < xend; r++) PetscCall(MatSetValue(ct->T, r, r, 1.0, ADD_VALUES));
    for (PetscInt i = 0; i < n; i++) {
      const PetscReal *R = ct->frames ? &ct->frames[9 * i] : NULL;
      const PetscReal  d = ct->pointScale[i];

      for (PetscInt k = 0; k < 3; k++)
        for (PetscInt c = 0; c < 3; c++) {
          const PetscReal Rck = R ? R[3 * c + k] : (PetscReal)(c == k);

          if (Rck == 0.0) continue;
          for (PetscInt e = 0; e < ncols[3 * i + c]; e++) PetscCall(MatSetValue(ct->T, idx[3 * i + k], cols[3 * i + c][e], -Rck * vals[3 * i + c][e] / d, ADD_VALUES));
        }
    }
    PetscCall(ISRestoreIndices(ct->isC, &idx));
    PetscCall(MatAssemblyBegin(ct->T, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(ct->T, MAT_FINAL_ASSEMBLY));
  }
  for (PetscInt r = 0; r < 3 * n; r++) PetscCall(PetscFree2(cols[r], vals[r]));
  PetscCall(PetscFree3(ncols, cols, vals));
  PetscCall(VecDestroy(&mark));
  PetscFunctionReturn(0);
}

/* K in the points' variables, T^T K T (its near-null space too: T^-1 z), or K itself */
PetscErrorCode SSStarContactTransformStiffness(SSStarContact *ct, Mat K, Mat *Kw)
{
  MatNullSpace nsp;

  PetscFunctionBegin;
  if (!ct->T) {
    PetscCall(PetscObjectReference((PetscObject)K));
    *Kw = K;
    PetscFunctionReturn(0);
  }
  PetscCall(MatPtAP(K, ct->T, MAT_INITIAL_MATRIX, PETSC_DEFAULT, Kw));
  PetscCall(MatGetNearNullSpace(K, &nsp));
  if (nsp) {
    PetscBool  hasConstant;
    PetscInt   nv;
    const Vec *vecs;
    Vec       *w;
    MatNullSpace wsp;

    PetscCall(MatNullSpaceGetVecs(nsp, &hasConstant, &nv, &vecs));
    PetscCall(PetscMalloc1(nv, &w));
    for (PetscInt k = 0; k < nv; k++) {
      PetscCall(VecDuplicate(vecs[k], &w[k]));
      PetscCall(SSStarContactToPointVariables(ct, vecs[k], w[k]));
    }
    PetscCall(MatNullSpaceCreate(PetscObjectComm((PetscObject)K), hasConstant, nv, w, &wsp));
    PetscCall(MatSetNearNullSpace(*Kw, wsp));
    PetscCall(MatNullSpaceDestroy(&wsp));
    for (PetscInt k = 0; k < nv; k++) PetscCall(VecDestroy(&w[k]));
    PetscCall(PetscFree(w));
  }
  PetscFunctionReturn(0);
}

/* v = T^-1 u = u - (T - I) u = 2 u - T u */
PetscErrorCode SSStarContactToPointVariables(SSStarContact *ct, Vec u, Vec v)
{
  PetscFunctionBegin;
  if (!ct->T) {
    PetscCall(VecCopy(u, v));
    PetscFunctionReturn(0);
  }
  PetscCall(MatMult(ct->T, u, v));
  PetscCall(VecAXPBY(v, 2.0, -1.0, u));
  PetscFunctionReturn(0);
}
