/*
   The mesh in file order: vertex v of the file is row v of /geometry/vertices and /fields/displacement, on any number
   of ranks. Each rank writes the rows [start_r, start_r + n_r) of an even split of the N vertices; a vertex goes from
   the rank that owns it (the root of DMPlex's point SF) to the rank of its row. Per-node fields (the contact nodes, the
   contact faces' vertices: few) are gathered on rank 0 in file order.
*/
#include "outputimpl.h"
#include <petscsf.h>

/* ghost[p - pStart]: point p is a leaf of the point SF (another rank owns it) */
PetscErrorCode SSStarGhostPoints(DM dm, PetscBool **ghost)
{
  PetscSF         sf;
  PetscInt        pStart, pEnd, nleaves;
  const PetscInt *ilocal;

  PetscFunctionBegin;
  PetscCall(DMPlexGetChart(dm, &pStart, &pEnd));
  PetscCall(PetscCalloc1(pEnd - pStart + 1, ghost));
  PetscCall(DMGetPointSF(dm, &sf));
  PetscCall(PetscSFGetGraph(sf, NULL, &nleaves, &ilocal, NULL));
  for (PetscInt i = 0; i < (nleaves > 0 ? nleaves : 0); i++) (*ghost)[(ilocal ? ilocal[i] : i) - pStart] = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* The even split of N rows over the ranks: rank r has rows [ranges[r], ranges[r + 1]) */
static PetscErrorCode EvenRanges(MPI_Comm comm, PetscInt N, PetscInt **ranges)
{
  PetscMPIInt size;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(PetscMalloc1(size + 1, ranges));
  for (PetscMPIInt r = 0; r <= size; r++) (*ranges)[r] = r * (N / size) + PetscMin(r, N % size);
  PetscFunctionReturn(0);
}

/*
   A field of bs values per mesh vertex in file order: vertex v's values at la[off] with off its offset in sec (NULL: bs
   per vertex from vStart); nat holds this rank's rows of the even split
*/
static PetscErrorCode VertexFieldInFileOrder(SSStarScene scene, const PetscBool ghost[], PetscInt bs, const PetscScalar la[], PetscSection sec, Vec *nat)
{
  PetscInt           pStart, vStart, vEnd, *ranges;
  PetscMPIInt        rank;
  const PetscScalar *ta;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(scene->comm, &rank));
  PetscCall(EvenRanges(scene->comm, scene->nodesGlobal, &ranges));
  PetscCall(VecCreateMPI(scene->comm, bs * (ranges[rank + 1] - ranges[rank]), bs * scene->nodesGlobal, nat));
  PetscCall(VecSetBlockSize(*nat, bs));
  PetscCall(PetscFree(ranges));
  PetscCall(DMPlexGetChart(scene->dm, &pStart, NULL));
  PetscCall(DMPlexGetDepthStratum(scene->dm, 0, &vStart, &vEnd));
  PetscCall(VecGetArrayRead(scene->tags, &ta));
  for (PetscInt v = vStart; v < vEnd; v++) {
    PetscInt off = bs * (v - vStart), row = (PetscInt)PetscRealPart(ta[v - vStart]);

    if (ghost[v - pStart]) continue;
    if (sec) PetscCall(PetscSectionGetOffset(sec, v, &off));
    PetscCall(VecSetValuesBlocked(*nat, 1, &row, &la[off], INSERT_VALUES));
  }
  PetscCall(VecRestoreArrayRead(scene->tags, &ta));
  PetscCall(VecAssemblyBegin(*nat));
  PetscCall(VecAssemblyEnd(*nat));
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarWriteVec(hid_t file, const char path[], PetscInt cols, Vec v)
{
  const PetscScalar *a;
  PetscReal         *w;
  PetscInt           n;

  PetscFunctionBegin;
  PetscCall(VecGetLocalSize(v, &n));
  PetscCall(PetscMalloc1(n + 1, &w));
  PetscCall(VecGetArrayRead(v, &a));
  for (PetscInt i = 0; i < n; i++) w[i] = PetscRealPart(a[i]);
  PetscCall(VecRestoreArrayRead(v, &a));
  PetscCall(SSStarH5WriteRows(PetscObjectComm((PetscObject)v), file, path, n / (cols ? cols : 1), cols, w, NULL));
  PetscCall(PetscFree(w));
  PetscFunctionReturn(0);
}

/* The vertices of a tetrahedron, reordered by an even permutation (orientation kept) so that the smallest comes first
   and the smallest of the other three second: the same cell gives the same row whatever the mesh's numbering */
static void CanonicalTetrahedron(PetscInt c[4])
{
  PetscInt m = 0, t[4], k = 1;

  for (PetscInt i = 1; i < 4; i++)
    if (c[i] < c[m]) m = i;
  switch (m) { /* double transpositions bring the smallest to the front */
  case 0:
    t[0] = c[0], t[1] = c[1], t[2] = c[2], t[3] = c[3];
    break;
  case 1:
    t[0] = c[1], t[1] = c[0], t[2] = c[3], t[3] = c[2];
    break;
  case 2:
    t[0] = c[2], t[1] = c[3], t[2] = c[0], t[3] = c[1];
    break;
  default:
    t[0] = c[3], t[1] = c[2], t[2] = c[1], t[3] = c[0];
  }
  for (PetscInt i = 2; i < 4; i++)
    if (t[i] < t[k]) k = i;
  c[0] = t[0]; /* a rotation of the last three brings the smallest of them second */
  c[1] = t[k];
  c[2] = t[k == 3 ? 1 : k + 1];
  c[3] = t[k == 1 ? 3 : k - 1];
}

/* Rows of cols vertex numbers, compared by their sorted entries */
int SSStarCompareRows(const void *a, const void *b, void *ctx)
{
  const PetscInt cols = *(const PetscInt *)ctx;
  PetscInt       x[4], y[4];

  for (PetscInt k = 0; k < cols; k++) {
    x[k] = ((const PetscInt *)a)[k];
    y[k] = ((const PetscInt *)b)[k];
  }
  PetscSortInt(cols, x);
  PetscSortInt(cols, y);
  for (PetscInt k = 0; k < cols; k++)
    if (x[k] != y[k]) return x[k] < y[k] ? -1 : 1;
  return 0;
}

/*
   The order of canonical rows of 4 vertex numbers (ctx; CanonicalTetrahedron(): the smallest first, the smallest of the
   other three second), for PetscTimSort() of their indices: the order of SSStarCompareRows() (by the sorted entries),
   whose sorted entries of a canonical row are r[0], r[1], min(r[2], r[3]), max(r[2], r[3]) -- no sort per comparison
   (those sorts were a quarter of the output's time)
*/
static int CompareRowIndices(const void *a, const void *b, void *ctx)
{
  const PetscInt *rows = (const PetscInt *)ctx, *x = &rows[4 * *(const PetscInt *)a], *y = &rows[4 * *(const PetscInt *)b];
  PetscInt        xs[4] = {x[0], x[1], PetscMin(x[2], x[3]), PetscMax(x[2], x[3])}, ys[4] = {y[0], y[1], PetscMin(y[2], y[3]), PetscMax(y[2], y[3])};

  for (PetscInt k = 0; k < 4; k++)
    if (xs[k] != ys[k]) return xs[k] < ys[k] ? -1 : 1;
  return 0;
}

/*
   The order of the tetrahedra in the file (SSStarCellOrder, outputimpl.h): each local cell's row of 4 file vertex
   numbers, canonical, goes to the rank whose even-split vertex range holds its smallest vertex, which sorts the rows
   it receives; the ranks' rows in rank order are sorted. The plan keeps where each cell goes and where each received
   row lands, so that a field of the cells travels the same way later, one field at a time (SSStarCellOrderApply()).
   With cells, this rank's rows in file order too.
*/
PetscErrorCode SSStarCellOrderCreate(SSStarScene scene, SSStarCellOrder *plan, PetscInt **cells)
{
  MPI_Comm           comm = scene->comm;
  PetscMPIInt        size;
  PetscBool         *ghost;
  PetscInt           pStart, cStart, cEnd, vStart, ncells = 0, *rows, *ranges, *sorted, nrecv;
  const PetscScalar *ta, *xa;
  DM                 cdm;
  PetscSection       csec;
  Vec                coordinates;

  PetscFunctionBegin;
  PetscCall(PetscMemzero(plan, sizeof(*plan)));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(SSStarGhostPoints(scene->dm, &ghost));
  PetscCall(EvenRanges(comm, scene->nodesGlobal, &ranges));
  PetscCall(DMPlexGetChart(scene->dm, &pStart, NULL));
  PetscCall(DMPlexGetHeightStratum(scene->dm, 0, &cStart, &cEnd));
  PetscCall(DMPlexGetDepthStratum(scene->dm, 0, &vStart, NULL));
  PetscCall(PetscMalloc1(4 * (cEnd - cStart) + 1, &rows));
  PetscCall(PetscMalloc1(cEnd - cStart + 1, &plan->send));
  PetscCall(DMGetCoordinatesLocal(scene->dm, &coordinates));
  PetscCall(DMGetCoordinateDM(scene->dm, &cdm));
  PetscCall(DMGetLocalSection(cdm, &csec));
  PetscCall(VecGetArrayRead(coordinates, &xa));
  PetscCall(VecGetArrayRead(scene->tags, &ta));
  for (PetscInt c = cStart; c < cEnd; c++) {
    PetscInt  v[4], *row = &rows[4 * ncells];
    PetscReal x[4][3], e[3][3], volume;

    if (ghost[c - pStart]) continue;
    PetscCall(SSStarMeshCellVertices(scene->dm, c, v));
    for (PetscInt i = 0; i < 4; i++) {
      PetscInt off;

      PetscCall(PetscSectionGetOffset(csec, v[i], &off));
      for (PetscInt k = 0; k < 3; k++) x[i][k] = PetscRealPart(xa[off + k]);
      row[i] = (PetscInt)PetscRealPart(ta[v[i] - vStart]);
    }
    /* VTK's (and XDMF's) orientation: (x1 - x0) x (x2 - x0) . (x3 - x0) > 0 */
    for (PetscInt i = 0; i < 3; i++)
      for (PetscInt k = 0; k < 3; k++) e[i][k] = x[i + 1][k] - x[0][k];
    volume = (e[0][1] * e[1][2] - e[0][2] * e[1][1]) * e[2][0] + (e[0][2] * e[1][0] - e[0][0] * e[1][2]) * e[2][1] + (e[0][0] * e[1][1] - e[0][1] * e[1][0]) * e[2][2];
    if (volume < 0) {
      const PetscInt t = row[2];

      row[2] = row[3];
      row[3] = t;
    }
    CanonicalTetrahedron(row);
    plan->send[ncells++] = c - cStart;
  }
  PetscCall(VecRestoreArrayRead(scene->tags, &ta));
  PetscCall(VecRestoreArrayRead(coordinates, &xa));
  PetscCall(PetscFree(ghost));
  plan->nsend = ncells;
  /* rows to the rank of their smallest vertex (rows[4 i]): the send order sorts them by destination */
  PetscCall(PetscCalloc4(size, &plan->scount, size + 1, &plan->sdispl, size, &plan->rcount, size + 1, &plan->rdispl));
  {
    PetscInt *dest, *perm, *tmp;

    PetscCall(PetscMalloc3(ncells + 1, &dest, ncells + 1, &perm, 4 * ncells + 1, &tmp));
    for (PetscInt i = 0; i < ncells; i++) {
      PetscInt r = 0;

      while (r + 1 < size && ranges[r + 1] <= rows[4 * i]) r++; /* the range [ranges[r], ranges[r + 1]) holding it */
      dest[i] = r;
      perm[i] = i;
      plan->scount[r]++;
    }
    PetscCall(PetscSortIntWithArray(ncells, dest, perm));
    for (PetscInt i = 0; i < ncells; i++) {
      for (PetscInt k = 0; k < 4; k++) tmp[4 * i + k] = rows[4 * perm[i] + k];
      dest[i] = plan->send[perm[i]];
    }
    PetscCall(PetscArraycpy(rows, tmp, 4 * ncells));
    PetscCall(PetscArraycpy(plan->send, dest, ncells));
    PetscCall(PetscFree3(dest, perm, tmp));
  }
  PetscCall(PetscFree(ranges));
  PetscCallMPI(MPI_Alltoall(plan->scount, 1, MPI_INT, plan->rcount, 1, MPI_INT, comm));
  for (PetscMPIInt r = 0; r < size; r++) {
    plan->sdispl[r + 1] = plan->sdispl[r] + plan->scount[r];
    plan->rdispl[r + 1] = plan->rdispl[r] + plan->rcount[r];
  }
  nrecv = plan->rdispl[size];
  PetscCall(PetscMalloc1(4 * nrecv + 1, &sorted));
  {
    MPI_Datatype row;

    PetscCallMPI(MPI_Type_contiguous(4, MPIU_INT, &row));
    PetscCallMPI(MPI_Type_commit(&row));
    PetscCallMPI(MPI_Alltoallv(rows, plan->scount, plan->sdispl, row, sorted, plan->rcount, plan->rdispl, row, comm));
    PetscCallMPI(MPI_Type_free(&row));
  }
  PetscCall(PetscFree(rows)); /* sent: not held beside the received copy */
  plan->nrows = nrecv;
  PetscCall(PetscMalloc1(nrecv + 1, &plan->order));
  for (PetscInt i = 0; i < nrecv; i++) plan->order[i] = i;
  if (nrecv > 1) PetscCall(PetscTimSort(nrecv, plan->order, sizeof(PetscInt), CompareRowIndices, sorted));
  if (cells) {
    PetscCall(PetscMalloc1(4 * nrecv + 1, cells));
    for (PetscInt i = 0; i < nrecv; i++)
      for (PetscInt k = 0; k < 4; k++) (*cells)[4 * i + k] = sorted[4 * plan->order[i] + k];
  }
  PetscCall(PetscFree(sorted));
  PetscFunctionReturn(0);
}

/*
   A field of ndata values per cell in file order: send holds the values of the cells plan->send[0], plan->send[1], ...
   (ndata each, in that order); rows gets this rank's plan->nrows rows of the file. Holds two copies of the field at most.
*/
PetscErrorCode SSStarCellOrderApply(MPI_Comm comm, const SSStarCellOrder *plan, PetscInt ndata, const PetscReal send[], PetscReal **rows)
{
  PetscReal   *received;
  MPI_Datatype unit;

  PetscFunctionBegin;
  PetscCall(PetscMalloc1(ndata * plan->nrows + 1, &received));
  PetscCallMPI(MPI_Type_contiguous((PetscMPIInt)ndata, MPIU_REAL, &unit));
  PetscCallMPI(MPI_Type_commit(&unit));
  PetscCallMPI(MPI_Alltoallv(send, plan->scount, plan->sdispl, unit, received, plan->rcount, plan->rdispl, unit, comm));
  PetscCallMPI(MPI_Type_free(&unit));
  PetscCall(PetscMalloc1(ndata * plan->nrows + 1, rows));
  for (PetscInt i = 0; i < plan->nrows; i++)
    for (PetscInt k = 0; k < ndata; k++) (*rows)[ndata * i + k] = received[ndata * plan->order[i] + k];
  PetscCall(PetscFree(received));
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarCellOrderDestroy(SSStarCellOrder *plan)
{
  PetscFunctionBegin;
  PetscCall(PetscFree(plan->send));
  PetscCall(PetscFree(plan->order));
  PetscCall(PetscFree4(plan->scount, plan->sdispl, plan->rcount, plan->rdispl));
  PetscFunctionReturn(0);
}

/*
   The vertices' coordinates (u NULL) or the displacement u with the held dofs (0: DMGlobalToLocal leaves the
   constrained dofs as they are) in file order, 3 per vertex: nat holds this rank's rows of the even split
*/
PetscErrorCode SSStarVertexFieldInFileOrder(SSStarScene scene, Vec u, Vec *nat)
{
  PetscSection sec;
  PetscBool   *ghost;
  Vec          local;

  PetscFunctionBegin;
  PetscCall(SSStarGhostPoints(scene->dm, &ghost));
  if (u) {
    PetscCall(DMGetLocalSection(scene->dm, &sec));
    PetscCall(DMGetLocalVector(scene->dm, &local));
    PetscCall(VecZeroEntries(local));
    PetscCall(DMGlobalToLocal(scene->dm, u, INSERT_VALUES, local));
  } else {
    DM cdm;

    PetscCall(DMGetCoordinatesLocal(scene->dm, &local));
    PetscCall(DMGetCoordinateDM(scene->dm, &cdm));
    PetscCall(DMGetLocalSection(cdm, &sec));
  }
  {
    const PetscScalar *la;

    PetscCall(VecGetArrayRead(local, &la));
    PetscCall(VertexFieldInFileOrder(scene, ghost, 3, la, sec, nat));
    PetscCall(VecRestoreArrayRead(local, &la));
  }
  if (u) PetscCall(DMRestoreLocalVector(scene->dm, &local));
  PetscCall(PetscFree(ghost));
  PetscFunctionReturn(0);
}

/* The bs values of every local vertex (by vertex from vStart) in file order: nat holds this rank's rows */
PetscErrorCode SSStarVertexValuesInFileOrder(SSStarScene scene, PetscInt bs, const PetscScalar values[], Vec *nat)
{
  PetscBool *ghost;

  PetscFunctionBegin;
  PetscCall(SSStarGhostPoints(scene->dm, &ghost));
  PetscCall(VertexFieldInFileOrder(scene, ghost, bs, values, NULL, nat));
  PetscCall(PetscFree(ghost));
  PetscFunctionReturn(0);
}

/* <prefix>/fields/<name>: a field of 3 values per vertex (a global vector of the scene's DM; held vertices 0) */
PetscErrorCode SSStarWriteVertexField(SSStarScene scene, hid_t file, const char prefix[], const char name[], Vec u)
{
  Vec   nat;
  hid_t group;
  char  path[PETSC_MAX_PATH_LEN];

  PetscFunctionBegin;
  PetscCall(PetscSNPrintf(path, sizeof(path), "%s/fields", prefix));
  PetscCall(SSStarH5GroupOpen(file, path, &group));
  PetscCallH5(H5Gclose(group));
  PetscCall(SSStarVertexFieldInFileOrder(scene, u, &nat));
  PetscCall(PetscSNPrintf(path, sizeof(path), "%s/fields/%s", prefix, name));
  PetscCall(SSStarWriteVec(file, path, 3, nat));
  PetscCall(VecDestroy(&nat));
  PetscFunctionReturn(0);
}

/* <prefix>/fields/displacement; of a hyperelastic scene <prefix>/fields/position too, X + u: the current configuration;
   with -dynamics <prefix>/fields/velocity */
PetscErrorCode SSStarWriteDisplacement(SSStarScene scene, hid_t file, const char prefix[], Vec u)
{
  Vec v;

  PetscFunctionBegin;
  PetscCall(SSStarWriteVertexField(scene, file, prefix, "displacement", u));
  if (!scene->affine) {
    Vec  nat, x;
    char path[PETSC_MAX_PATH_LEN];

    PetscCall(SSStarVertexFieldInFileOrder(scene, u, &nat));
    PetscCall(SSStarVertexFieldInFileOrder(scene, NULL, &x));
    PetscCall(VecAXPY(nat, 1.0, x));
    PetscCall(PetscSNPrintf(path, sizeof(path), "%s/fields/position", prefix));
    PetscCall(SSStarWriteVec(file, path, 3, nat));
    PetscCall(VecDestroy(&x));
    PetscCall(VecDestroy(&nat));
  }
  PetscCall(SSStarDynamicsGetVelocity(scene, &v));
  if (v) PetscCall(SSStarWriteVertexField(scene, file, prefix, "velocity", v));
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarWriteMesh(SSStarScene scene, hid_t file, Vec u)
{
  Vec             nat;
  PetscInt       *cells;
  SSStarCellOrder plan;
  hid_t           group;

  PetscFunctionBegin;
  PetscCall(SSStarH5GroupOpen(file, "/geometry", &group));
  PetscCallH5(H5Gclose(group));
  PetscCall(SSStarVertexFieldInFileOrder(scene, NULL, &nat));
  PetscCall(SSStarWriteVec(file, "/geometry/vertices", 3, nat));
  PetscCall(VecDestroy(&nat));

  PetscCall(SSStarWriteDisplacement(scene, file, "", u));

  PetscCall(SSStarCellOrderCreate(scene, &plan, &cells));
  PetscCall(SSStarH5GroupOpen(file, "/viz/topology", &group));
  PetscCallH5(H5Gclose(group));
  PetscCall(SSStarH5WriteRows(scene->comm, file, "/viz/topology/cells", plan.nrows, 4, NULL, cells));
  {
    hid_t set = H5Dopen2(file, "/viz/topology/cells", H5P_DEFAULT);

    PetscCall(SSStarH5AttrInt(set, "cell_dim", 3)); /* what PETSc's petsc_gen_xdmf.py reads */
    PetscCall(SSStarH5AttrInt(set, "cell_corners", 4));
    PetscCallH5(H5Dclose(set));
  }
  PetscCall(PetscFree(cells));
  PetscCall(SSStarCellOrderDestroy(&plan));
  PetscFunctionReturn(0);
}

/* ------------------------------------------------------------------------------------------------------------------
   Per-node fields gathered on rank 0 in file order (the contact nodes, the contact faces' vertices: few)
   ------------------------------------------------------------------------------------------------------------------ */

/* Position of each of the n local keys (file vertex numbers) among the sorted keys of all ranks; *p: their number */
PetscErrorCode SSStarFileOrder(MPI_Comm comm, PetscInt n, const PetscInt key[], PetscInt *p, PetscInt **all, PetscInt pos[])
{
  IS              local, gathered;
  const PetscInt *keys;

  PetscFunctionBegin;
  PetscCall(ISCreateGeneral(comm, n, key, PETSC_USE_POINTER, &local));
  PetscCall(ISAllGather(local, &gathered));
  PetscCall(ISGetLocalSize(gathered, p));
  PetscCall(ISGetIndices(gathered, &keys));
  PetscCall(PetscMalloc1(*p + 1, all));
  PetscCall(PetscArraycpy(*all, keys, *p));
  PetscCall(ISRestoreIndices(gathered, &keys));
  PetscCall(PetscSortInt(*p, *all));
  for (PetscInt i = 0; i < n; i++) PetscCall(PetscFindInt(key[i], *p, *all, &pos[i]));
  PetscCall(ISDestroy(&gathered));
  PetscCall(ISDestroy(&local));
  PetscFunctionReturn(0);
}

/* The dataset path (p rows of bs values, bs = 1: 1-d) from the n local nodes at positions pos; integers if asInt */
PetscErrorCode SSStarWriteNodeField(MPI_Comm comm, hid_t file, const char path[], PetscInt p, PetscInt n, const PetscInt pos[], PetscInt bs, const PetscReal values[], PetscBool asInt)
{
  PetscMPIInt        rank;
  Vec                v;
  const PetscScalar *a;
  PetscReal         *w;
  PetscInt          *iw;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(VecCreateMPI(comm, rank ? 0 : p * bs, p * bs, &v));
  for (PetscInt i = 0; i < n; i++)
    for (PetscInt k = 0; k < bs; k++) PetscCall(VecSetValue(v, pos[i] * bs + k, values[i * bs + k], INSERT_VALUES));
  PetscCall(VecAssemblyBegin(v));
  PetscCall(VecAssemblyEnd(v));
  PetscCall(PetscMalloc2(rank ? 1 : p * bs + 1, &w, rank ? 1 : p * bs + 1, &iw));
  PetscCall(VecGetArrayRead(v, &a));
  for (PetscInt i = 0; i < (rank ? 0 : p * bs); i++) {
    w[i]  = PetscRealPart(a[i]);
    iw[i] = (PetscInt)PetscRealPart(a[i]);
  }
  PetscCall(VecRestoreArrayRead(v, &a));
  PetscCall(SSStarH5WriteRows(comm, file, path, rank ? 0 : p, bs > 1 ? bs : 0, asInt ? NULL : w, asInt ? iw : NULL));
  PetscCall(PetscFree2(w, iw));
  PetscCall(VecDestroy(&v));
  PetscFunctionReturn(0);
}
