/*
   Adding the cells' 12x12 matrices to K, once K holds its pattern: straight into the rows' value arrays, a binary
   search per 3x3 block of a cell (16 per cell) instead of MatSetValues()'s search per entry (144 per cell), which
   was half the assembly's CPU time at level 16 (docs/guide/scale.md, "Outside the solve"). The rows of vertices another rank owns go through MatSetValuesBlocked()
   (its stash). K is AIJ with 3x3 blocks: the three rows of a vertex have the same columns, and a block column's three
   columns are adjacent.
*/
#include "../sceneimpl.h"

/*
   SSStarBlockAddBegin - ready to add blocks to K (AIJ, block size 3, its pattern assembled: every 3x3 block the cells
   will add is there); blocks: the global block index of every local vertex (-1: no dofs)
*/
PetscErrorCode SSStarBlockAddBegin(Mat K, PetscInt nv, const PetscInt blocks[], SSStarBlockAdd *add)
{
  PetscBool       mpi, done;
  const PetscInt *garray = NULL;
  PetscInt        rstart, rend, nB = 0;

  PetscFunctionBegin;
  PetscCall(PetscMemzero(add, sizeof(*add)));
  add->K = K;
  PetscCall(PetscObjectTypeCompare((PetscObject)K, MATMPIAIJ, &mpi));
  if (mpi) PetscCall(MatMPIAIJGetSeqAIJ(K, &add->part[0], &add->part[1], &garray));
  else add->part[0] = K;
  PetscCall(MatGetOwnershipRange(K, &rstart, &rend));
  add->bstart = rstart / 3;
  add->bend   = rend / 3;
  if (add->part[1]) PetscCall(MatGetLocalSize(add->part[1], NULL, &nB));
  /* each local vertex's first column in the diagonal part (its local block) or in the off-diagonal part (garray) */
  PetscCall(PetscMalloc2(nv + 1, &add->col, nv + 1, &add->inB));
  for (PetscInt v = 0; v < nv; v++) {
    const PetscInt b = blocks[v];

    add->col[v] = -1;
    add->inB[v] = PETSC_FALSE;
    if (b < 0) continue;
    if (b >= add->bstart && b < add->bend) add->col[v] = 3 * (b - add->bstart);
    else if (nB) {
      PetscInt j;

      PetscCall(PetscFindInt(3 * b, nB, garray, &j));
      add->col[v] = j; /* -1 when no owned row couples to it: only the rank's ghost rows do, through the stash */
      add->inB[v] = PETSC_TRUE;
    }
  }
  for (PetscInt p = 0; p < (add->part[1] ? 2 : 1); p++) {
    PetscCall(MatGetRowIJ(add->part[p], 0, PETSC_FALSE, PETSC_FALSE, NULL, &add->ia[p], &add->ja[p], &done));
    PetscCheck(done, PETSC_COMM_SELF, PETSC_ERR_SUP, "Cannot read the rows of K");
    PetscCall(MatSeqAIJGetArray(add->part[p], &add->va[p]));
  }
  PetscFunctionReturn(0);
}

/* Adds a cell's matrix Ke (12x12, row-major, vertex-major) at the local vertices v[4] of global blocks b[4] */
PetscErrorCode SSStarBlockAddCell(SSStarBlockAdd *add, const PetscInt v[4], const PetscInt b[4], const PetscScalar Ke[144])
{
  PetscFunctionBegin;
  for (PetscInt i = 0; i < 4; i++) {
    PetscInt row;

    if (b[i] < 0) continue;
    if (b[i] < add->bstart || b[i] >= add->bend) { /* another rank's row: its 3 x 12 values through the stash */
      PetscCall(MatSetValuesBlocked(add->K, 1, &b[i], 4, b, &Ke[36 * i], ADD_VALUES));
      continue;
    }
    row = 3 * (b[i] - add->bstart);
    for (PetscInt j = 0; j < 4; j++) {
      const PetscInt  p = add->inB[v[j]] ? 1 : 0, c = add->col[v[j]], lo = add->ia[p][row], n = add->ia[p][row + 1] - lo;
      PetscInt        at;

      if (b[j] < 0) continue;
      PetscCheck(c >= 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Block column %" PetscInt_FMT " is not in K's pattern", b[j]);
      PetscCall(PetscFindInt(c, n, add->ja[p] + lo, &at));
      PetscCheck(at >= 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Block (%" PetscInt_FMT ", %" PetscInt_FMT ") is not in K's pattern", b[i], b[j]);
      for (PetscInt k = 0; k < 3; k++) {
        PetscScalar *a = add->va[p] + add->ia[p][row + k] + at;

        for (PetscInt l = 0; l < 3; l++) a[l] += Ke[12 * (3 * i + k) + 3 * j + l];
      }
    }
  }
  PetscFunctionReturn(0);
}

/* Gives K its arrays back (the caller assembles it) */
PetscErrorCode SSStarBlockAddEnd(SSStarBlockAdd *add)
{
  PetscBool done;

  PetscFunctionBegin;
  for (PetscInt p = 0; p < (add->part[1] ? 2 : 1); p++) {
    PetscCall(MatSeqAIJRestoreArray(add->part[p], &add->va[p]));
    PetscCall(MatRestoreRowIJ(add->part[p], 0, PETSC_FALSE, PETSC_FALSE, NULL, &add->ia[p], &add->ja[p], &done));
  }
  PetscCall(PetscFree2(add->col, add->inB));
  PetscFunctionReturn(0);
}
