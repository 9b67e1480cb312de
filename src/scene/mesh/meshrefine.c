/*
   Meshes refined in parallel (-dm_refine k): the slices of the mesh cache (meshcache.c) refined k times before the
   DMPlex is built, so that no rank ever holds the fine mesh and the DMPlex is built once, without edges.

   Each tetrahedron splits 1:8 (four corner tetrahedra and the inner octahedron cut along its shortest diagonal), each
   triangle of a surface group 1:4, and a cell keeps its volume groups. A new vertex is the midpoint of an edge (a, b),
   a < b: it is numbered after the old vertices, the edges in lexicographic order, whatever the number of ranks (the
   output's node order). The edge (a, b) is numbered on the rank that holds vertex a's slice; the ranks that hold cells
   or triangles with that edge ask it for the number.
*/
#include "../sceneimpl.h"

/* Rank of the slice that holds entry v of N spread over size ranks (rank r: [r N/p, (r + 1) N/p), the first N % p one more) */
PetscMPIInt SSStarSliceOwner(PetscInt v, PetscInt N, PetscMPIInt size)
{
  const PetscInt q = N / size, r = N % size;

  return (PetscMPIInt)(v < r * (q + 1) ? v / (q + 1) : r + (v - r * (q + 1)) / q);
}

PetscInt SSStarSliceStart(PetscMPIInt rank, PetscInt N, PetscMPIInt size)
{
  return rank * (N / size) + PetscMin(rank, N % size);
}

/*
   Records of recbytes bytes grouped by destination (count[r] of them to rank r, in rank order): this rank receives
   rcount[r] records from rank r, grouped by source in rank order, into *recv (PetscFree() it)
*/
PetscErrorCode SSStarExchange(MPI_Comm comm, const PetscMPIInt count[], size_t recbytes, const void *send, PetscMPIInt rcount[], void **recv)
{
  PetscMPIInt size, *sc, *sd, *rc, *rd;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Alltoall((void *)count, 1, MPI_INT, rcount, 1, MPI_INT, comm));
  PetscCall(PetscMalloc4(size, &sc, size + 1, &sd, size, &rc, size + 1, &rd));
  sd[0] = rd[0] = 0;
  for (PetscMPIInt r = 0; r < size; r++) {
    PetscCheck((double)count[r] * recbytes < PETSC_MPI_INT_MAX && (double)rcount[r] * recbytes < PETSC_MPI_INT_MAX, PETSC_COMM_SELF, PETSC_ERR_SUP, "More than 2 GB between two ranks: use more ranks");
    sc[r]     = (PetscMPIInt)(count[r] * recbytes);
    rc[r]     = (PetscMPIInt)(rcount[r] * recbytes);
    sd[r + 1] = sd[r] + sc[r];
    rd[r + 1] = rd[r] + rc[r];
  }
  PetscCall(PetscMalloc((size_t)rd[size] + 1, recv));
  PetscCallMPI(MPI_Alltoallv((void *)send, sc, sd, MPI_BYTE, *recv, rc, rd, MPI_BYTE, comm));
  PetscCall(PetscFree4(sc, sd, rc, rd));
  PetscFunctionReturn(0);
}

static int ComparePair(const void *a, const void *b)
{
  const PetscInt *x = (const PetscInt *)a, *y = (const PetscInt *)b;

  return x[0] != y[0] ? (x[0] < y[0] ? -1 : 1) : (x[1] > y[1]) - (x[1] < y[1]);
}

/* The position of pair (a, b) among n sorted pairs, or -1 */
static PetscInt FindPair(const PetscInt pairs[], PetscInt n, PetscInt a, PetscInt b)
{
  PetscInt lo = 0, hi = n;

  while (lo < hi) {
    const PetscInt mid = (lo + hi) / 2;

    if (pairs[2 * mid] < a || (pairs[2 * mid] == a && pairs[2 * mid + 1] < b)) lo = mid + 1;
    else hi = mid;
  }
  return lo < n && pairs[2 * lo] == a && pairs[2 * lo + 1] == b ? lo : -1;
}

/* Sorted distinct entries of v (n of them), in place; their number */
static PetscInt SortUnique(PetscInt n, PetscInt v[])
{
  PetscInt m = n;

  PetscCallAbort(PETSC_COMM_SELF, PetscSortRemoveDupsInt(&m, v));
  return m;
}

/*
   The coordinates of the vertices ids[0..n) (sorted, distinct) from the ranks whose slices hold them: each asks the
   owners (ids sorted: grouped by owner already), which answer in the order asked
*/
static PetscErrorCode FetchCoordinates(MPI_Comm comm, const SSStarMeshSlices *m, PetscInt n, const PetscInt ids[], PetscReal xyz[])
{
  PetscMPIInt size, rank, *count, *rcount;
  PetscInt   *asked, nasked = 0;
  PetscReal  *answer, *got;
  const PetscInt v0 = m->v0;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(PetscCalloc2(size, &count, size, &rcount));
  for (PetscInt i = 0; i < n; i++) count[SSStarSliceOwner(ids[i], m->NV, size)]++;
  PetscCall(SSStarExchange(comm, count, sizeof(PetscInt), ids, rcount, (void **)&asked));
  for (PetscMPIInt r = 0; r < size; r++) nasked += rcount[r];
  PetscCall(PetscMalloc1(3 * nasked + 1, &answer));
  for (PetscInt i = 0; i < nasked; i++)
    for (PetscInt d = 0; d < 3; d++) answer[3 * i + d] = m->coords[3 * (asked[i] - v0) + d];
  PetscCall(SSStarExchange(comm, rcount, 3 * sizeof(PetscReal), answer, count, (void **)&got));
  PetscCall(PetscArraycpy(xyz, got, 3 * n));
  PetscCall(PetscFree(got));
  PetscCall(PetscFree(answer));
  PetscCall(PetscFree(asked));
  PetscCall(PetscFree2(count, rcount));
  PetscFunctionReturn(0);
}

typedef struct {
  PetscInt  a, b;
  PetscReal x[3];
} EdgeRecord;

static int CompareEdgeRecord(const void *p, const void *q)
{
  const EdgeRecord *x = (const EdgeRecord *)p, *y = (const EdgeRecord *)q;

  return x->a != y->a ? (x->a < y->a ? -1 : 1) : (x->b > y->b) - (x->b < y->b);
}

/*
   The numbers of the edges pairs[0..n) (sorted, distinct), their midpoints mid[]: the ranks of the edges' first
   vertices number the edges they hold (in order, after the N vertices and the edges of the ranks before) and keep
   their midpoints (*nmine of them, numbered from *first) for the new vertex slices
*/
static PetscErrorCode NumberEdges(MPI_Comm comm, PetscInt NV, PetscInt n, const PetscInt pairs[], const PetscReal mid[], PetscInt number[], PetscInt *nedges, PetscInt *first, PetscInt *nmine, PetscReal **mine)
{
  PetscMPIInt size, *count, *rcount;
  EdgeRecord *send, *recv;
  PetscInt    nrecv = 0, nu = 0, *keys, *answer, *got;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(PetscCalloc2(size, &count, size, &rcount));
  PetscCall(PetscMalloc1(n + 1, &send));
  for (PetscInt i = 0; i < n; i++) {
    send[i].a = pairs[2 * i];
    send[i].b = pairs[2 * i + 1];
    for (PetscInt d = 0; d < 3; d++) send[i].x[d] = mid[3 * i + d];
    count[SSStarSliceOwner(send[i].a, NV, size)]++;
  }
  PetscCall(SSStarExchange(comm, count, sizeof(EdgeRecord), send, rcount, (void **)&recv));
  PetscCall(PetscFree(send));
  for (PetscMPIInt r = 0; r < size; r++) nrecv += rcount[r];
  /* the distinct edges of this rank, sorted, and their numbers */
  PetscCall(PetscMalloc1(nrecv + 1, &send));
  PetscCall(PetscArraycpy(send, recv, nrecv));
  qsort(send, nrecv, sizeof(EdgeRecord), CompareEdgeRecord);
  for (PetscInt i = 0; i < nrecv; i++)
    if (!nu || CompareEdgeRecord(&send[nu - 1], &send[i])) send[nu++] = send[i];
  PetscCallMPI(MPI_Scan(&nu, first, 1, MPIU_INT, MPI_SUM, comm));
  *first -= nu;
  PetscCall(MPIU_Allreduce(&nu, nedges, 1, MPIU_INT, MPI_SUM, comm));
  PetscCall(PetscMalloc1(2 * nu + 1, &keys));
  PetscCall(PetscMalloc1(3 * nu + 1, mine));
  for (PetscInt i = 0; i < nu; i++) {
    keys[2 * i]     = send[i].a;
    keys[2 * i + 1] = send[i].b;
    for (PetscInt d = 0; d < 3; d++) (*mine)[3 * i + d] = send[i].x[d];
  }
  *nmine = nu;
  PetscCall(PetscFree(send));
  PetscCall(PetscMalloc1(nrecv + 1, &answer));
  for (PetscInt i = 0; i < nrecv; i++) answer[i] = NV + *first + FindPair(keys, nu, recv[i].a, recv[i].b);
  PetscCall(PetscFree(recv));
  PetscCall(SSStarExchange(comm, rcount, sizeof(PetscInt), answer, count, (void **)&got));
  PetscCall(PetscArraycpy(number, got, n));
  PetscCall(PetscFree(got));
  PetscCall(PetscFree(answer));
  PetscCall(PetscFree(keys));
  PetscCall(PetscFree2(count, rcount));
  PetscFunctionReturn(0);
}

/* The edges of a tetrahedron by its vertices; a child's 4 slots among the 10 (4 vertices, then the 6 edges' midpoints) */
static const int TetEdges[6][2] = {
  {0, 1},
  {0, 2},
  {0, 3},
  {1, 2},
  {1, 3},
  {2, 3}
};
static const int Corners[4][4] = {
  {0, 4, 5, 6},
  {4, 1, 7, 8},
  {5, 7, 2, 9},
  {6, 8, 9, 3}
};
/* the inner octahedron's three diagonals (opposite edges' midpoints) */
static const int Diagonals[3][2] = {
  {4, 9},
  {5, 8},
  {6, 7}
};

static PetscReal SignedVolume(const PetscReal *a, const PetscReal *b, const PetscReal *c, const PetscReal *d)
{
  const PetscReal u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]}, w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};

  return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]);
}

static PetscReal Distance2(const PetscReal *a, const PetscReal *b)
{
  return (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]);
}

/* child k (0..7) of a cell with the 10 slots' ids and points, oriented as its parent (sign of the volume) */
static void Child(PetscInt k, PetscInt diag, const PetscInt id[10], PetscReal *const pt[10], PetscReal sign, PetscInt out[4])
{
  int slot[4];

  if (k < 4)
    for (int j = 0; j < 4; j++) slot[j] = Corners[k][j];
  else {
    const int p = Diagonals[diag][0], q = Diagonals[diag][1];
    const int a = Diagonals[(diag + 1) % 3][0], a2 = Diagonals[(diag + 1) % 3][1], b = Diagonals[(diag + 2) % 3][0], b2 = Diagonals[(diag + 2) % 3][1];
    const int ring[4] = {a, b, a2, b2};

    slot[0] = p;
    slot[1] = q;
    slot[2] = ring[k - 4];
    slot[3] = ring[(k - 3) % 4];
  }
  if (SignedVolume(pt[slot[0]], pt[slot[1]], pt[slot[2]], pt[slot[3]]) * sign < 0) {
    const int t = slot[0];

    slot[0] = slot[1];
    slot[1] = t;
  }
  for (int j = 0; j < 4; j++) out[j] = id[slot[j]];
}

typedef struct {
  PetscInt  id;
  PetscReal x[3];
} VertexRecord;

/* The vertex slices of the refined mesh (NV new vertices in all): the old slice's and the new edges' coordinates sent to their new owners */
static PetscErrorCode Reslice(MPI_Comm comm, SSStarMeshSlices *m, PetscInt NV, PetscInt first, PetscInt nmine, const PetscReal mine[])
{
  PetscMPIInt   size, rank, *count, *rcount, *fill;
  VertexRecord *send, *recv;
  PetscInt      n = m->nv + nmine, nrecv = 0;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(PetscCalloc3(size, &count, size, &rcount, size + 1, &fill));
  PetscCall(PetscMalloc1(n + 1, &send));
  for (PetscInt i = 0; i < n; i++) count[SSStarSliceOwner(i < m->nv ? m->v0 + i : m->NV + first + i - m->nv, NV, size)]++;
  for (PetscMPIInt r = 0; r < size; r++) fill[r + 1] = fill[r] + count[r];
  for (PetscInt i = 0; i < n; i++) {
    const PetscInt   id = i < m->nv ? m->v0 + i : m->NV + first + i - m->nv;
    const PetscReal *x  = i < m->nv ? &m->coords[3 * i] : &mine[3 * (i - m->nv)];
    VertexRecord    *rec = &send[fill[SSStarSliceOwner(id, NV, size)]++];

    rec->id = id;
    for (PetscInt d = 0; d < 3; d++) rec->x[d] = x[d];
  }
  PetscCall(SSStarExchange(comm, count, sizeof(VertexRecord), send, rcount, (void **)&recv));
  PetscCall(PetscFree(send));
  for (PetscMPIInt r = 0; r < size; r++) nrecv += rcount[r];
  PetscCall(PetscFree(m->coords));
  m->NV = NV;
  m->v0 = SSStarSliceStart(rank, NV, size);
  m->nv = SSStarSliceStart(rank + 1, NV, size) - m->v0;
  PetscCheck(nrecv == m->nv, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Refinement: %" PetscInt_FMT " vertices received for a slice of %" PetscInt_FMT, nrecv, m->nv);
  PetscCall(PetscMalloc1(3 * m->nv + 1, &m->coords));
  for (PetscInt i = 0; i < nrecv; i++)
    for (PetscInt d = 0; d < 3; d++) m->coords[3 * (recv[i].id - m->v0) + d] = recv[i].x[d];
  PetscCall(PetscFree(recv));
  PetscCall(PetscFree3(count, rcount, fill));
  PetscFunctionReturn(0);
}

/* One refinement of the slices: cells 1:8, surface triangles 1:4, the new vertices at the edges' midpoints */
PetscErrorCode SSStarMeshRefine(MPI_Comm comm, SSStarMeshSlices *m)
{
  PetscInt   nids = 0, *ids, npairs = 0, *pairs, *number, NE = 0, first = 0, nmine = 0, *cells, *tri;
  PetscReal *xyz, *mid, *mine;
  long long *groups;

  PetscFunctionBegin;
  /* the vertices of this rank's cells and triangles, and their coordinates */
  PetscCall(PetscMalloc1(4 * m->nc + 3 * m->ntri + 1, &ids));
  for (PetscInt k = 0; k < 4 * m->nc; k++) ids[nids++] = m->cells[k];
  for (PetscInt t = 0; t < m->ntri; t++)
    for (PetscInt k = 0; k < 3; k++) ids[nids++] = m->tri[4 * t + k];
  nids = SortUnique(nids, ids);
  PetscCall(PetscMalloc1(3 * nids + 1, &xyz));
  PetscCall(FetchCoordinates(comm, m, nids, ids, xyz));
  /* their edges, numbered, and the midpoints */
  PetscCall(PetscMalloc1(12 * m->nc + 6 * m->ntri + 1, &pairs));
  for (PetscInt c = 0; c < m->nc; c++)
    for (PetscInt e = 0; e < 6; e++) {
      const PetscInt a = m->cells[4 * c + TetEdges[e][0]], b = m->cells[4 * c + TetEdges[e][1]];

      pairs[2 * npairs]     = PetscMin(a, b);
      pairs[2 * npairs++ + 1] = PetscMax(a, b);
    }
  for (PetscInt t = 0; t < m->ntri; t++)
    for (PetscInt e = 0; e < 3; e++) {
      const PetscInt a = m->tri[4 * t + e], b = m->tri[4 * t + (e + 1) % 3];

      pairs[2 * npairs]     = PetscMin(a, b);
      pairs[2 * npairs++ + 1] = PetscMax(a, b);
    }
  qsort(pairs, npairs, 2 * sizeof(PetscInt), ComparePair);
  {
    PetscInt nu = 0;

    for (PetscInt i = 0; i < npairs; i++)
      if (!nu || ComparePair(&pairs[2 * (nu - 1)], &pairs[2 * i])) {
        pairs[2 * nu]     = pairs[2 * i];
        pairs[2 * nu++ + 1] = pairs[2 * i + 1];
      }
    npairs = nu;
  }
  PetscCall(PetscMalloc2(3 * npairs + 1, &mid, npairs + 1, &number));
  for (PetscInt i = 0; i < npairs; i++) {
    PetscInt ia, ib;

    PetscCall(PetscFindInt(pairs[2 * i], nids, ids, &ia));
    PetscCall(PetscFindInt(pairs[2 * i + 1], nids, ids, &ib));
    for (PetscInt d = 0; d < 3; d++) mid[3 * i + d] = 0.5 * (xyz[3 * ia + d] + xyz[3 * ib + d]);
  }
  PetscCall(NumberEdges(comm, m->NV, npairs, pairs, mid, number, &NE, &first, &nmine, &mine));

  /* the children */
  PetscCall(PetscMalloc2(32 * m->nc + 1, &cells, 8 * m->nc + 1, &groups));
  for (PetscInt c = 0; c < m->nc; c++) {
    PetscInt   id[10], diag = 0;
    PetscReal  pts[10][3], *pt[10], sign, len[3];

    for (PetscInt k = 0; k < 4; k++) {
      PetscInt at;

      id[k] = m->cells[4 * c + k];
      PetscCall(PetscFindInt(id[k], nids, ids, &at));
      for (PetscInt d = 0; d < 3; d++) pts[k][d] = xyz[3 * at + d];
    }
    for (PetscInt e = 0; e < 6; e++) {
      const PetscInt a = id[TetEdges[e][0]], b = id[TetEdges[e][1]];

      id[4 + e] = number[FindPair(pairs, npairs, PetscMin(a, b), PetscMax(a, b))];
      for (PetscInt d = 0; d < 3; d++) pts[4 + e][d] = 0.5 * (pts[TetEdges[e][0]][d] + pts[TetEdges[e][1]][d]);
    }
    for (PetscInt k = 0; k < 10; k++) pt[k] = pts[k];
    sign = SignedVolume(pt[0], pt[1], pt[2], pt[3]) < 0 ? -1.0 : 1.0;
    for (PetscInt g = 0; g < 3; g++) len[g] = Distance2(pt[Diagonals[g][0]], pt[Diagonals[g][1]]);
    for (PetscInt g = 1; g < 3; g++)
      if (len[g] < len[diag]) diag = g;
    for (PetscInt k = 0; k < 8; k++) {
      Child(k, diag, id, pt, sign, &cells[32 * c + 4 * k]);
      groups[8 * c + k] = m->cellGroups[c];
    }
  }
  PetscCall(PetscMalloc1(16 * m->ntri + 1, &tri));
  for (PetscInt t = 0; t < m->ntri; t++) {
    const PetscInt *v = &m->tri[4 * t];
    PetscInt        e[3];

    for (PetscInt k = 0; k < 3; k++) e[k] = number[FindPair(pairs, npairs, PetscMin(v[k], v[(k + 1) % 3]), PetscMax(v[k], v[(k + 1) % 3]))];
    {
      const PetscInt child[4][3] = {
        {v[0], e[0], e[2]},
        {v[1], e[0], e[1]},
        {v[2], e[1], e[2]},
        {e[0], e[1], e[2]}
      };

      for (PetscInt k = 0; k < 4; k++) {
        for (PetscInt j = 0; j < 3; j++) tri[16 * t + 4 * k + j] = child[k][j];
        SSStarTripleSort(&tri[16 * t + 4 * k]);
        tri[16 * t + 4 * k + 3] = v[3];
      }
    }
  }
  PetscCall(Reslice(comm, m, m->NV + NE, first, nmine, mine));
  PetscCall(PetscFree(mine));
  PetscCall(PetscFree2(mid, number));
  PetscCall(PetscFree(pairs));
  PetscCall(PetscFree(xyz));
  PetscCall(PetscFree(ids));
  PetscCall(PetscFree2(m->cells, m->cellGroups));
  PetscCall(PetscFree(m->tri));
  m->cells      = cells;
  m->cellGroups = groups;
  m->nc *= 8;
  m->tri = tri;
  m->ntri *= 4;
  PetscFunctionReturn(0);
}
