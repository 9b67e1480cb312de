/*
   The whole body's Newton matrix without a copy of K (newton_wholebody.c): it differs from K only in the entries of the
   contact rows and the contact columns (the "cross"), so it is formed in K's own storage for each linear solve and
   K's entries are put back after it, bit for bit. With Q the rotation into the nodes' frames at the contact dofs
   (identity elsewhere),

     M = Shat Q K Q^T + That / gamma,   Shat = blockdiag(S_i, 1),   That = blockdiag(T_i, 0),

   so the cross is all that changes: a column triple (the 3 columns of a contact node b in one row) turns into
   K_rb R_b^T, a row triple (the 3 rows of a contact node a in one column) into S_a R_a times them, and T_a / gamma
   adds to the node's diagonal block. The known dofs are then eliminated by MatZeroRowsColumns() (rows and columns of
   contact dofs: the cross again). K must be AIJ with each contact node's rows and columns complete 3 x 3 blocks (the
   scenes assemble it so); any other K is copied once into an AIJ matrix with those blocks completed by zeros.

   The matrix's state tells PCSetUp() whether the Newton matrix changed: every Newton matrix gets a state of its own, and
   K gets its own state back with its entries, so that the solver does not take the restored K for a new one.
*/
#include "newtonimpl.h"

#define CROSS_INFO 5 /* per dof, to the ranks that hold it as a ghost column: node key, component, R row */

struct _n_SSStarWholeBodyMatrix {
  Mat              A;         /* the stiffness K (a reference)                                                   */
  Mat              K;         /* where the Newton matrix is formed: A, or an AIJ copy of it                   */
  PetscBool        inPlace;   /* K is A: its entries are put back after every solve                           */
  Mat              block[2];  /* K's diagonal and off-diagonal blocks (block[1] NULL on one rank)             */
  PetscInt         nz0;       /* entries of block[0]                                                          */
  PetscInt         ncross;    /* entries in a contact row or a contact column                                 */
  PetscInt        *pos;       /* their positions: < nz0 in block[0]'s values, else nz0 + the one in block[1]'s */
  PetscScalar     *valK, *valM; /* their values in K and in the Newton matrix                                 */
  PetscInt         ncol, *col; /* column triples: 3 cross entries and the node (frames) each                   */
  PetscInt         nrow, *row; /* row triples: 3 cross entries and the node each                              */
  PetscInt        *diag;      /* 9 cross entries per local contact node: its diagonal block                  */
  PetscInt         nnodes;    /* local contact nodes; the ghost ones follow in frames                         */
  PetscBool        hasFrames; /* some rank has frames (a rank without contact nodes has none of its own)      */
  PetscReal       *frames;    /* 9 per node, local then ghost, with hasFrames                                 */
  PetscObjectState stateK;    /* A's state with its own entries                                               */
  PetscObjectState stateM;    /* of the last Newton matrix formed                                            */
  PetscBool        holdsM;    /* K holds a Newton matrix now                                                  */
  MatNullSpace     nullK;     /* K's null space (floating bodies), detached while K holds a Newton matrix:    */
                              /* the Newton matrix is regular and a KSP would project its residual on it     */
};

/* R_b of a column node n (NULL: identity) */
static inline const PetscReal *Frame(SSStarWholeBodyMatrix wm, PetscInt n)
{
  return wm->hasFrames ? &wm->frames[9 * n] : NULL;
}

/*
   Per ghost column of K (block[1]): its contact node (>= nnodes: numbered after the local ones) and component, or -1;
   the ghost nodes' frames into wm->frames. Each rank sends, per dof it owns, the key of its node (the global index
   of the node's first dof), the component and the row of R.
*/
static PetscErrorCode GhostColumns(SSStarWholeBodyMatrix wm, const SSStarContactLayout *L, PetscInt **node, PetscInt **comp, PetscInt *nghost)
{
  MPI_Comm           comm = PetscObjectComm((PetscObject)wm->K);
  const PetscInt    *garray;
  PetscInt           m, rstart, nB = 0, *keys, nkeys = 0;
  Vec                info, ghost;
  IS                 is;
  VecScatter         scatter;
  PetscScalar       *a;
  const PetscScalar *g;

  PetscFunctionBegin;
  *nghost = 0;
  PetscCall(MatMPIAIJGetSeqAIJ(wm->K, NULL, NULL, &garray));
  PetscCall(MatGetLocalSize(wm->block[1], NULL, &nB));
  PetscCall(MatGetLocalSize(wm->K, &m, NULL));
  PetscCall(MatGetOwnershipRange(wm->K, &rstart, NULL));
  PetscCall(VecCreateMPI(comm, CROSS_INFO * m, PETSC_DETERMINE, &info));
  PetscCall(VecSet(info, -1.0));
  PetscCall(VecGetArray(info, &a));
  for (PetscInt i = 0; i < L->nnodes; i++)
    for (PetscInt k = 0; k < 3; k++) {
      PetscScalar *e = &a[CROSS_INFO * L->dofs[3 * i + k]];

      e[0] = (PetscScalar)(rstart + L->dofs[3 * i]);
      e[1] = (PetscScalar)k;
      for (PetscInt c = 0; c < 3; c++) e[2 + c] = L->frames ? L->frames[9 * i + 3 * k + c] : (PetscReal)(c == k);
    }
  PetscCall(VecRestoreArray(info, &a));
  PetscCall(ISCreateBlock(PETSC_COMM_SELF, CROSS_INFO, nB, garray, PETSC_COPY_VALUES, &is));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, CROSS_INFO * nB, &ghost));
  PetscCall(VecScatterCreate(info, is, ghost, NULL, &scatter));
  PetscCall(VecScatterBegin(scatter, info, ghost, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(scatter, info, ghost, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterDestroy(&scatter));
  PetscCall(ISDestroy(&is));
  PetscCall(VecDestroy(&info));

  PetscCall(PetscMalloc2(nB, node, nB, comp));
  PetscCall(PetscMalloc1(nB, &keys));
  PetscCall(VecGetArrayRead(ghost, &g));
  for (PetscInt j = 0; j < nB; j++)
    if (PetscRealPart(g[CROSS_INFO * j]) >= 0) keys[nkeys++] = (PetscInt)PetscRealPart(g[CROSS_INFO * j]);
  PetscCall(PetscSortRemoveDupsInt(&nkeys, keys));
  *nghost = nkeys;
  if (wm->hasFrames) PetscCall(PetscRealloc(sizeof(PetscReal) * (9 * (wm->nnodes + nkeys) + 1), &wm->frames));
  for (PetscInt j = 0; j < nB; j++) {
    const PetscScalar *e = &g[CROSS_INFO * j];
    PetscInt           at;

    (*node)[j] = (*comp)[j] = -1;
    if (PetscRealPart(e[0]) < 0) continue;
    PetscCall(PetscFindInt((PetscInt)PetscRealPart(e[0]), nkeys, keys, &at));
    (*node)[j] = wm->nnodes + at;
    (*comp)[j] = (PetscInt)PetscRealPart(e[1]);
    if (wm->hasFrames)
      for (PetscInt c = 0; c < 3; c++) wm->frames[9 * (wm->nnodes + at) + 3 * (*comp)[j] + c] = PetscRealPart(e[2 + c]);
  }
  PetscCall(VecRestoreArrayRead(ghost, &g));
  PetscCall(VecDestroy(&ghost));
  PetscCall(PetscFree(keys));
  PetscFunctionReturn(0);
}

typedef struct {
  PetscInt node, comp, entry;
} ColumnEntry;

static int CompareColumnEntry(const void *x, const void *y)
{
  const ColumnEntry *a = (const ColumnEntry *)x, *b = (const ColumnEntry *)y;

  return a->node != b->node ? (a->node < b->node ? -1 : 1) : (a->comp > b->comp) - (a->comp < b->comp);
}

/*
   The cross of K: its positions and values, the column triples, the row triples and the diagonal blocks.
   complete: every contact node's rows have the same columns and every row has all 3 columns of a contact node or none.
*/
static PetscErrorCode BuildCross(SSStarWholeBodyMatrix wm, const SSStarContactLayout *L, PetscBool *complete)
{
  const PetscInt    *ia[2] = {NULL, NULL}, *ja[2] = {NULL, NULL};
  const PetscScalar *va[2] = {NULL, NULL};
  PetscInt           m, nb, *rowNode, *rowComp, *ghostNode = NULL, *ghostComp = NULL, nghost = 0, *rowStart, maxRow = 0;
  PetscInt           ncross = 0, ncol = 0, nrow = 0;
  ColumnEntry       *list;
  PetscBool          done, ok = PETSC_TRUE;

  PetscFunctionBegin;
  PetscCall(MatGetLocalSize(wm->K, &m, NULL));
  wm->nnodes    = L->nnodes;
  wm->hasFrames = (PetscBool)(L->frames != NULL);
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &wm->hasFrames, 1, MPIU_BOOL, MPI_LOR, PetscObjectComm((PetscObject)wm->K)));
  if (wm->hasFrames) {
    PetscCall(PetscMalloc1(9 * L->nnodes + 1, &wm->frames));
    if (L->frames) PetscCall(PetscArraycpy(wm->frames, L->frames, 9 * L->nnodes));
    else
      for (PetscInt k = 0; k < 9 * L->nnodes; k++) wm->frames[k] = (PetscReal)(k % 4 == 0);
  }
  nb = wm->block[1] ? 2 : 1;
  if (wm->block[1]) PetscCall(GhostColumns(wm, L, &ghostNode, &ghostComp, &nghost));
  for (PetscInt b = 0; b < nb; b++) {
    PetscCall(MatGetRowIJ(wm->block[b], 0, PETSC_FALSE, PETSC_FALSE, NULL, &ia[b], &ja[b], &done));
    PetscCheck(done, PETSC_COMM_SELF, PETSC_ERR_SUP, "Cannot read the rows of K");
    PetscCall(MatSeqAIJGetArrayRead(wm->block[b], &va[b]));
  }
  wm->nz0 = ia[0][m];
  PetscCall(PetscMalloc3(m, &rowNode, m, &rowComp, 3 * L->nnodes, &rowStart));
  for (PetscInt j = 0; j < m; j++) rowNode[j] = rowComp[j] = -1;
  for (PetscInt i = 0; i < L->nnodes; i++)
    for (PetscInt k = 0; k < 3; k++) {
      rowNode[L->dofs[3 * i + k]] = i;
      rowComp[L->dofs[3 * i + k]] = k;
    }
  for (PetscInt r = 0; r < m; r++) maxRow = PetscMax(maxRow, ia[0][r + 1] - ia[0][r] + (nb > 1 ? ia[1][r + 1] - ia[1][r] : 0));
  PetscCall(PetscMalloc1(maxRow, &list));

  /* two passes over the rows: count, then fill */
  for (PetscInt pass = 0; pass < 2; pass++) {
    ncross = ncol = 0;
    for (PetscInt r = 0; r < m; r++) {
      const PetscBool contactRow = (PetscBool)(rowNode[r] >= 0);
      PetscInt        nlist      = 0;

      if (contactRow && pass) rowStart[3 * rowNode[r] + rowComp[r]] = ncross;
      for (PetscInt b = 0; b < nb; b++)
        for (PetscInt j = ia[b][r]; j < ia[b][r + 1]; j++) {
          const PetscInt node = b ? ghostNode[ja[b][j]] : rowNode[ja[b][j]], comp = b ? ghostComp[ja[b][j]] : rowComp[ja[b][j]];

          if (!contactRow && node < 0) continue;
          if (pass) {
            wm->pos[ncross]  = b ? wm->nz0 + j : j;
            wm->valK[ncross] = va[b][j];
          }
          if (node >= 0) {
            list[nlist].node    = node;
            list[nlist].comp    = comp;
            list[nlist++].entry = ncross;
          }
          ncross++;
        }
      qsort(list, nlist, sizeof(ColumnEntry), CompareColumnEntry);
      for (PetscInt t = 0; t < nlist; t += 3) {
        if (t + 2 >= nlist || list[t].node != list[t + 2].node || list[t].comp != 0 || list[t + 1].comp != 1 || list[t + 2].comp != 2) {
          ok = PETSC_FALSE;
          break;
        }
        if (pass) {
          for (PetscInt k = 0; k < 3; k++) wm->col[4 * ncol + k] = list[t + k].entry;
          wm->col[4 * ncol + 3] = list[t].node;
        }
        ncol++;
      }
    }
    if (!ok) break;
    if (!pass) {
      wm->ncross = ncross;
      wm->ncol   = ncol;
      PetscCall(PetscMalloc3(ncross, &wm->pos, ncross, &wm->valK, ncross, &wm->valM));
      PetscCall(PetscMalloc1(4 * ncol, &wm->col));
    }
  }

  /* row triples: the 3 rows of a contact node with the same columns; the node's diagonal block among them */
  for (PetscInt i = 0; ok && i < L->nnodes; i++) {
    PetscInt len[3];

    for (PetscInt k = 0; k < 3; k++) {
      const PetscInt r = L->dofs[3 * i + k];

      len[k] = ia[0][r + 1] - ia[0][r] + (nb > 1 ? ia[1][r + 1] - ia[1][r] : 0);
    }
    if (len[0] != len[1] || len[0] != len[2]) ok = PETSC_FALSE;
    for (PetscInt b = 0; ok && b < nb; b++)
      for (PetscInt k = 1; ok && k < 3; k++) {
        const PetscInt r0 = L->dofs[3 * i], rk = L->dofs[3 * i + k];

        if (ia[b][rk + 1] - ia[b][rk] != ia[b][r0 + 1] - ia[b][r0]) ok = PETSC_FALSE;
        for (PetscInt j = 0; ok && j < ia[b][r0 + 1] - ia[b][r0]; j++) ok = (PetscBool)(ja[b][ia[b][r0] + j] == ja[b][ia[b][rk] + j]);
      }
    nrow += len[0];
  }
  if (ok) {
    wm->nrow = nrow;
    PetscCall(PetscMalloc2(4 * nrow, &wm->row, 9 * L->nnodes, &wm->diag));
    nrow = 0;
    for (PetscInt i = 0; i < L->nnodes; i++) {
      const PetscInt r0 = L->dofs[3 * i], len = ia[0][r0 + 1] - ia[0][r0] + (nb > 1 ? ia[1][r0 + 1] - ia[1][r0] : 0);

      for (PetscInt j = 0; j < len; j++, nrow++) {
        for (PetscInt k = 0; k < 3; k++) wm->row[4 * nrow + k] = rowStart[3 * i + k] + j;
        wm->row[4 * nrow + 3] = i;
      }
      for (PetscInt l = 0; l < 9; l++) wm->diag[9 * i + l] = -1;
      for (PetscInt j = ia[0][r0]; j < ia[0][r0 + 1]; j++)
        if (rowNode[ja[0][j]] == i)
          for (PetscInt k = 0; k < 3; k++) wm->diag[9 * i + 3 * k + rowComp[ja[0][j]]] = rowStart[3 * i + k] + j - ia[0][r0];
      for (PetscInt l = 0; l < 9; l++)
        if (wm->diag[9 * i + l] < 0) ok = PETSC_FALSE;
    }
  }
  for (PetscInt b = 0; b < nb; b++) {
    PetscCall(MatSeqAIJRestoreArrayRead(wm->block[b], &va[b]));
    PetscCall(MatRestoreRowIJ(wm->block[b], 0, PETSC_FALSE, PETSC_FALSE, NULL, &ia[b], &ja[b], &done));
  }
  PetscCall(PetscFree(list));
  PetscCall(PetscFree3(rowNode, rowComp, rowStart));
  PetscCall(PetscFree2(ghostNode, ghostComp));
  PetscCall(MPIU_Allreduce(&ok, complete, 1, MPIU_BOOL, MPI_LAND, PetscObjectComm((PetscObject)wm->K)));
  PetscFunctionReturn(0);
}

/* Writes one value per cross entry into K's storage */
static PetscErrorCode WriteCross(SSStarWholeBodyMatrix wm, const PetscScalar v[])
{
  PetscScalar *a[2] = {NULL, NULL};

  PetscFunctionBegin;
  PetscCall(MatSeqAIJGetArray(wm->block[0], &a[0]));
  if (wm->block[1]) PetscCall(MatSeqAIJGetArray(wm->block[1], &a[1]));
  for (PetscInt e = 0; e < wm->ncross; e++) {
    const PetscInt p = wm->pos[e];

    if (p < wm->nz0) a[0][p] = v[e];
    else a[1][p - wm->nz0] = v[e];
  }
  if (wm->block[1]) PetscCall(MatSeqAIJRestoreArray(wm->block[1], &a[1]));
  PetscCall(MatSeqAIJRestoreArray(wm->block[0], &a[0]));
  PetscFunctionReturn(0);
}

/* K's diagonal and off-diagonal blocks */
static PetscErrorCode GetBlocks(SSStarWholeBodyMatrix wm)
{
  PetscBool mpi;

  PetscFunctionBegin;
  PetscCall(PetscObjectBaseTypeCompare((PetscObject)wm->K, MATMPIAIJ, &mpi));
  if (mpi) PetscCall(MatMPIAIJGetSeqAIJ(wm->K, &wm->block[0], &wm->block[1], NULL));
  else {
    wm->block[0] = wm->K;
    wm->block[1] = NULL;
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode FreeCross(SSStarWholeBodyMatrix wm)
{
  PetscFunctionBegin;
  PetscCall(PetscFree3(wm->pos, wm->valK, wm->valM));
  PetscCall(PetscFree(wm->col));
  PetscCall(PetscFree2(wm->row, wm->diag));
  PetscCall(PetscFree(wm->frames));
  wm->ncross = wm->ncol = wm->nrow = 0;
  PetscFunctionReturn(0);
}

/*
   An AIJ copy of A whose contact nodes' rows and columns are complete 3 x 3 blocks: Ihat^T A Ihat with Ihat the
   identity stored with a full 3 x 3 block (zeros off the diagonal) at every contact node
*/
static PetscErrorCode CompletedCopy(Mat A, const SSStarContactLayout *L, Mat *K)
{
  Mat            Aaij, Ihat;
  PetscInt       m, rstart, *nnz;
  PetscBool      isaij;
  const PetscScalar I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};

  PetscFunctionBegin;
  PetscCall(PetscObjectBaseTypeCompareAny((PetscObject)A, &isaij, MATSEQAIJ, MATMPIAIJ, ""));
  if (isaij) {
    PetscCall(PetscObjectReference((PetscObject)A));
    Aaij = A;
  } else PetscCall(MatConvert(A, MATAIJ, MAT_INITIAL_MATRIX, &Aaij));
  PetscCall(MatGetLocalSize(A, &m, NULL));
  PetscCall(MatGetOwnershipRange(A, &rstart, NULL));
  PetscCall(PetscMalloc1(m, &nnz));
  for (PetscInt j = 0; j < m; j++) nnz[j] = 1;
  for (PetscInt k = 0; k < 3 * L->nnodes; k++) nnz[L->dofs[k]] = 3;
  PetscCall(MatCreateAIJ(PetscObjectComm((PetscObject)A), m, m, PETSC_DETERMINE, PETSC_DETERMINE, 0, nnz, 0, NULL, &Ihat));
  PetscCall(PetscFree(nnz));
  for (PetscInt j = 0; j < m; j++) PetscCall(MatSetValue(Ihat, rstart + j, rstart + j, 1.0, INSERT_VALUES));
  for (PetscInt i = 0; i < L->nnodes; i++) {
    PetscInt rows[3];

    for (PetscInt k = 0; k < 3; k++) rows[k] = rstart + L->dofs[3 * i + k];
    PetscCall(MatSetValues(Ihat, 3, rows, 3, rows, I3, INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(Ihat, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(Ihat, MAT_FINAL_ASSEMBLY));
  PetscCall(MatPtAP(Aaij, Ihat, MAT_INITIAL_MATRIX, PETSC_DEFAULT, K));
  PetscCall(MatProductClear(*K));
  PetscCall(MatDestroy(&Ihat));
  PetscCall(MatDestroy(&Aaij));
  PetscFunctionReturn(0);
}

/*
   The Newton matrix of A (K) for the contact nodes of the layout, formed in A's storage when A is AIJ with complete
   3 x 3 blocks at the contact nodes, else in a copy (CompletedCopy)
*/
PetscErrorCode SSStarWholeBodyMatrixCreate(Mat A, const SSStarContactLayout *L, SSStarWholeBodyMatrix *wholem)
{
  SSStarWholeBodyMatrix wm;
  PetscBool        isaij, complete = PETSC_FALSE;

  PetscFunctionBegin;
  PetscCall(PetscNew(&wm));
  PetscCall(PetscObjectReference((PetscObject)A));
  wm->A = A;
  PetscCall(PetscObjectBaseTypeCompareAny((PetscObject)A, &isaij, MATSEQAIJ, MATMPIAIJ, ""));
  if (isaij) {
    PetscCall(PetscObjectReference((PetscObject)A));
    wm->K       = A;
    wm->inPlace = PETSC_TRUE;
    PetscCall(GetBlocks(wm));
    PetscCall(BuildCross(wm, L, &complete));
  }
  if (!complete) {
    PetscCall(FreeCross(wm));
    PetscCall(MatDestroy(&wm->K));
    PetscCall(CompletedCopy(A, L, &wm->K));
    wm->inPlace = PETSC_FALSE;
    PetscCall(GetBlocks(wm));
    PetscCall(BuildCross(wm, L, &complete));
    PetscCheck(complete, PetscObjectComm((PetscObject)A), PETSC_ERR_PLIB, "The Newton matrix's contact blocks are not complete after completion");
  }
  PetscCall(PetscObjectStateGet((PetscObject)wm->K, &wm->stateK));
  wm->stateM = wm->stateK;
  *wholem     = wm;
  PetscFunctionReturn(0);
}

/* Whether the Newton matrix is formed in K's own storage (no copy of K) */
PetscErrorCode SSStarWholeBodyMatrixInPlace(SSStarWholeBodyMatrix wm, PetscBool *inPlace)
{
  PetscFunctionBegin;
  *inPlace = wm->inPlace;
  PetscFunctionReturn(0);
}

/*
   M = Shat Q K Q^T + That / gamma (ig = 1 / gamma) in K's storage, the known rows and columns then eliminated with
   unit rows scaled by ig: with y and rhs the right-hand side rhs is updated as MatZeroRowsColumns() does; without
   them (the same step's matrix formed again) M keeps the state of that step's, so that its multigrid stays.
*/
PetscErrorCode SSStarWholeBodyMatrixForm(SSStarWholeBodyMatrix wm, const PetscReal S[], const PetscReal T[], PetscReal ig, PetscInt nknown, const PetscInt known[], Vec y, Vec rhs, Mat *M)
{
  PetscScalar *v = wm->valM;
  PetscReal    SR[9];

  PetscFunctionBegin;
  PetscCall(PetscArraycpy(v, wm->valK, wm->ncross));
  for (PetscInt t = 0; t < wm->ncol; t++) { /* K Q^T */
    const PetscInt  *e = &wm->col[4 * t];
    const PetscReal *R = Frame(wm, e[3]);
    PetscScalar      x[3];

    if (!R) continue;
    for (PetscInt k = 0; k < 3; k++) x[k] = v[e[k]];
    for (PetscInt l = 0; l < 3; l++) v[e[l]] = R[3 * l] * x[0] + R[3 * l + 1] * x[1] + R[3 * l + 2] * x[2];
  }
  for (PetscInt t = 0, node = -1; t < wm->nrow; t++) { /* Shat Q (K Q^T) */
    const PetscInt *e = &wm->row[4 * t];
    PetscScalar     x[3];

    if (e[3] != node) {
      const PetscReal *Si = &S[9 * e[3]], *R = Frame(wm, e[3]);

      node = e[3];
      for (PetscInt k = 0; k < 3; k++)
        for (PetscInt j = 0; j < 3; j++) SR[3 * k + j] = R ? Si[3 * k] * R[j] + Si[3 * k + 1] * R[3 + j] + Si[3 * k + 2] * R[6 + j] : Si[3 * k + j];
    }
    for (PetscInt k = 0; k < 3; k++) x[k] = v[e[k]];
    for (PetscInt k = 0; k < 3; k++) v[e[k]] = SR[3 * k] * x[0] + SR[3 * k + 1] * x[1] + SR[3 * k + 2] * x[2];
  }
  for (PetscInt i = 0; i < wm->nnodes; i++) /* + That / gamma */
    for (PetscInt l = 0; l < 9; l++) v[wm->diag[9 * i + l]] += ig * T[9 * i + l];
  PetscCall(WriteCross(wm, v));
  if (!wm->holdsM) {
    PetscCall(MatGetNullSpace(wm->K, &wm->nullK));
    PetscCall(PetscObjectReference((PetscObject)wm->nullK));
    PetscCall(MatSetNullSpace(wm->K, NULL));
  }
  PetscCall(MatZeroRowsColumns(wm->K, nknown, known, ig, y, rhs));
  if (rhs) wm->stateM = PetscMax(wm->stateM, wm->stateK) + 1;
  PetscCall(PetscObjectStateSet((PetscObject)wm->K, wm->stateM));
  wm->holdsM = PETSC_TRUE;
  *M         = wm->K;
  PetscFunctionReturn(0);
}

/* K's own entries and state back in its storage, after a linear solve with M */
PetscErrorCode SSStarWholeBodyMatrixRestore(SSStarWholeBodyMatrix wm)
{
  PetscFunctionBegin;
  if (!wm->holdsM) PetscFunctionReturn(0);
  if (wm->inPlace) {
    PetscCall(WriteCross(wm, wm->valK));
    PetscCall(PetscObjectStateSet((PetscObject)wm->K, wm->stateK));
  }
  PetscCall(MatSetNullSpace(wm->K, wm->nullK));
  PetscCall(MatNullSpaceDestroy(&wm->nullK));
  wm->holdsM = PETSC_FALSE;
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarWholeBodyMatrixDestroy(SSStarWholeBodyMatrix *wm)
{
  PetscFunctionBegin;
  if (!*wm) PetscFunctionReturn(0);
  PetscCall(SSStarWholeBodyMatrixRestore(*wm));
  PetscCall(FreeCross(*wm));
  PetscCall(MatDestroy(&(*wm)->K));
  PetscCall(MatDestroy(&(*wm)->A));
  PetscCall(PetscFree(*wm));
  PetscFunctionReturn(0);
}
