/*
   A P1 displacement carried from one mesh to another by point location (nested iteration's start on the finer mesh):
   each node of the fine mesh takes the value of the coarse tetrahedron that holds it (barycentric weights), or of the
   one it is least outside of. Both meshes are distributed: the bounding box of the coarse mesh is cut into buckets
   spread over the ranks, every coarse cell goes to the ranks of the buckets its box meets (its vertices and values),
   every fine node to the rank of its bucket, which answers with the value. No rank holds either mesh whole.
*/
#include "../sceneimpl.h"

#define CELL_RECORD 24 /* 4 vertices' coordinates, then their 3 values each */

typedef struct {
  PetscReal lo[3], h[3];
  PetscInt  n[3];
} Buckets;

static PetscInt BucketIndex(const Buckets *b, const PetscReal x[3], PetscInt d)
{
  const PetscInt i = (PetscInt)PetscFloorReal((x[d] - b->lo[d]) / b->h[d]);

  return PetscMax(0, PetscMin(b->n[d] - 1, i));
}

static PetscMPIInt BucketOwner(const Buckets *b, PetscInt i, PetscInt j, PetscInt k, PetscMPIInt size)
{
  const PetscInt64 B = (PetscInt64)b->n[0] * b->n[1] * b->n[2], id = i + b->n[0] * ((PetscInt64)j + b->n[1] * (PetscInt64)k);

  return (PetscMPIInt)(id * size / B);
}

/* The buckets i0[d]..i1[d] in each direction d that the box of a cell's 4 vertices (r: x, y, z of each) touches */
static void CellBuckets(const Buckets *b, const PetscReal r[12], PetscInt i0[3], PetscInt i1[3])
{
  PetscReal lo[3], hi[3];

  for (PetscInt d = 0; d < 3; d++) {
    lo[d] = PetscMin(PetscMin(r[d], r[3 + d]), PetscMin(r[6 + d], r[9 + d]));
    hi[d] = PetscMax(PetscMax(r[d], r[3 + d]), PetscMax(r[6 + d], r[9 + d]));
  }
  for (PetscInt d = 0; d < 3; d++) {
    i0[d] = BucketIndex(b, lo, d);
    i1[d] = BucketIndex(b, hi, d);
  }
}

/* det(p1 - p0, p2 - p0, p3 - p0) of the tetrahedron p (12 numbers): 6 times its signed volume */
static PetscReal Determinant(const PetscReal p[12])
{
  PetscReal e[3][3];

  for (PetscInt k = 0; k < 3; k++)
    for (PetscInt d = 0; d < 3; d++) e[k][d] = p[3 * (k + 1) + d] - p[d];
  return e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) - e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) + e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
}

/* Barycentric coordinates of x in the tetrahedron p (12 numbers); the smallest of them */
static PetscReal Barycentric(const PetscReal p[12], const PetscReal x[3], PetscReal l[4])
{
  PetscReal a[3][3], r[3], det, m = PETSC_MAX_REAL;

  for (PetscInt d = 0; d < 3; d++) {
    for (PetscInt k = 0; k < 3; k++) a[d][k] = p[3 * (k + 1) + d] - p[d];
    r[d] = x[d] - p[d];
  }
  det = Determinant(p);
  if (det == 0) return -PETSC_MAX_REAL;
  /* Cramer's rule */
  l[1] = (r[0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (r[1] * a[2][2] - a[1][2] * r[2]) + a[0][2] * (r[1] * a[2][1] - a[1][1] * r[2])) / det;
  l[2] = (a[0][0] * (r[1] * a[2][2] - a[1][2] * r[2]) - r[0] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) + a[0][2] * (a[1][0] * r[2] - r[1] * a[2][0])) / det;
  l[3] = (a[0][0] * (a[1][1] * r[2] - r[1] * a[2][1]) - a[0][1] * (a[1][0] * r[2] - r[1] * a[2][0]) + r[0] * (a[1][0] * a[2][1] - a[1][1] * a[2][0])) / det;
  l[0] = 1 - l[1] - l[2] - l[3];
  for (PetscInt k = 0; k < 4; k++) m = PetscMin(m, l[k]);
  return m;
}

/* Coordinates and values (3 each, 0 where constrained) of a vertex of dm from local vectors */
static PetscErrorCode VertexData(DM dm, PetscSection cs, const PetscScalar *xa, PetscSection s, const PetscScalar *ua, PetscInt v, PetscReal *x, PetscReal *u)
{
  PetscInt off, dof;

  PetscFunctionBegin;
  PetscCall(PetscSectionGetOffset(cs, v, &off));
  for (PetscInt d = 0; d < 3; d++) x[d] = PetscRealPart(xa[off + d]);
  PetscCall(PetscSectionGetDof(s, v, &dof));
  PetscCall(PetscSectionGetOffset(s, v, &off));
  for (PetscInt d = 0; d < 3; d++) u[d] = dof == 3 ? PetscRealPart(ua[off + d]) : 0;
  PetscFunctionReturn(0);
}

/* The coarse cells as records (CELL_RECORD numbers each), the bounding box of the coarse mesh and the bucket size */
static PetscErrorCode CoarseCells(DM dm, Vec u, PetscInt *nc, PetscReal **rec, Buckets *b)
{
  MPI_Comm           comm = PetscObjectComm((PetscObject)dm);
  PetscSection       s, cs;
  Vec                ul, xl;
  const PetscScalar *ua, *xa;
  PetscInt           cStart, cEnd, NC;
  PetscReal          box[6], vol = 0;

  PetscFunctionBegin;
  PetscCall(DMGetLocalSection(dm, &s));
  PetscCall(DMGetCoordinateSection(dm, &cs));
  PetscCall(DMGetCoordinatesLocal(dm, &xl));
  PetscCall(DMGetLocalVector(dm, &ul));
  PetscCall(VecZeroEntries(ul));
  PetscCall(DMGlobalToLocal(dm, u, INSERT_VALUES, ul));
  PetscCall(VecGetArrayRead(ul, &ua));
  PetscCall(VecGetArrayRead(xl, &xa));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  *nc = cEnd - cStart;
  PetscCall(PetscMalloc1(CELL_RECORD * *nc + 1, rec));
  for (PetscInt d = 0; d < 3; d++) {
    box[d]     = PETSC_MAX_REAL;
    box[3 + d] = -PETSC_MAX_REAL;
  }
  for (PetscInt c = cStart; c < cEnd; c++) {
    PetscReal *r = &(*rec)[CELL_RECORD * (c - cStart)];
    PetscInt   v[4];

    PetscCall(SSStarMeshCellVertices(dm, c, v));
    for (PetscInt k = 0; k < 4; k++) PetscCall(VertexData(dm, cs, xa, s, ua, v[k], &r[3 * k], &r[12 + 3 * k]));
    for (PetscInt k = 0; k < 4; k++)
      for (PetscInt d = 0; d < 3; d++) {
        box[d]     = PetscMin(box[d], r[3 * k + d]);
        box[3 + d] = PetscMax(box[3 + d], r[3 * k + d]);
      }
    vol += PetscAbsReal(Determinant(r)) / 6;
  }
  PetscCall(VecRestoreArrayRead(xl, &xa));
  PetscCall(VecRestoreArrayRead(ul, &ua));
  PetscCall(DMRestoreLocalVector(dm, &ul));
  for (PetscInt d = 0; d < 3; d++) box[3 + d] = -box[3 + d];
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, box, 6, MPIU_REAL, MPIU_MIN, comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &vol, 1, MPIU_REAL, MPIU_SUM, comm));
  PetscCall(MPIU_Allreduce(nc, &NC, 1, MPIU_INT, MPI_SUM, comm));
  /* buckets of about 8 cells' volume each */
  for (PetscInt d = 0; d < 3; d++) {
    const PetscReal ext = PetscMax(-box[3 + d] - box[d], PETSC_SMALL), h = PetscCbrtReal(8 * vol / PetscMax(NC, 1));

    b->lo[d] = box[d];
    b->n[d]  = PetscMax(1, PetscMin(1024, (PetscInt)(ext / h)));
    b->h[d]  = ext / b->n[d];
  }
  PetscFunctionReturn(0);
}

/*
   A displacement u of the mesh coarse (P1, 3 dofs per vertex, its constrained dofs 0) at the vertices of the mesh fine:
   v (global vector of fine) takes at each vertex the value of the coarse tetrahedron that holds it, or of the one it is
   least outside of (the weights clipped)
*/
PetscErrorCode SSStarMeshInterpolate(DM coarse, Vec u, DM fine, Vec v)
{
  MPI_Comm           comm = PetscObjectComm((PetscObject)coarse);
  PetscMPIInt        size, *count, *rcount, *fill;
  PetscInt           nc, nrecv = 0, npts = 0, nasked = 0, vStart, vEnd, *cellStart, *cellList, B;
  PetscReal         *rec, *send, *cells, *pts, *asked, *answer, *got;
  PetscSection       gs, cs;
  Vec                xl;
  const PetscScalar *xa;
  PetscScalar       *va;
  Buckets            b;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(CoarseCells(coarse, u, &nc, &rec, &b));
  B = b.n[0] * b.n[1] * b.n[2];
  /* each coarse cell to the owners of the buckets its box meets (once per owner) */
  PetscCall(PetscCalloc3(size, &count, size, &rcount, size + 1, &fill));
  for (PetscInt pass = 0; pass < 2; pass++) {
    if (pass) {
      for (PetscMPIInt r = 0; r < size; r++) fill[r + 1] = fill[r] + count[r];
      PetscCall(PetscMalloc1(CELL_RECORD * fill[size] + 1, &send));
    }
    for (PetscInt c = 0; c < nc; c++) {
      const PetscReal *r = &rec[CELL_RECORD * c];
      PetscInt         i0[3], i1[3];
      PetscMPIInt      last = -1;

      CellBuckets(&b, r, i0, i1);
      /* the owners of a box's buckets, in increasing order for bucket ids increasing with k, j, i */
      for (PetscInt k = i0[2]; k <= i1[2]; k++)
        for (PetscInt j = i0[1]; j <= i1[1]; j++)
          for (PetscInt i = i0[0]; i <= i1[0]; i++) {
            const PetscMPIInt o = BucketOwner(&b, i, j, k, size);

            if (o <= last) continue;
            last = o;
            if (!pass) count[o]++;
            else PetscCall(PetscArraycpy(&send[CELL_RECORD * fill[o]++], r, CELL_RECORD));
          }
    }
  }
  PetscCall(PetscFree(rec));
  PetscCall(SSStarExchange(comm, count, CELL_RECORD * sizeof(PetscReal), send, rcount, (void **)&cells));
  PetscCall(PetscFree(send));
  for (PetscMPIInt r = 0; r < size; r++) nrecv += rcount[r];
  /* the cells of each of this rank's buckets (CSR over the buckets [b0, b1)) */
  {
    PetscMPIInt rank;
    PetscInt    b0, b1;

    PetscCallMPI(MPI_Comm_rank(comm, &rank));
    b0 = (PetscInt)(((PetscInt64)rank * B + size - 1) / size);
    b1 = (PetscInt)(((PetscInt64)(rank + 1) * B + size - 1) / size);
    PetscCall(PetscCalloc1(b1 - b0 + 1, &cellStart));
    for (PetscInt pass = 0; pass < 2; pass++) {
      if (pass) {
        for (PetscInt k = 0; k < b1 - b0; k++) cellStart[k + 1] += cellStart[k];
        PetscCall(PetscMalloc1(cellStart[b1 - b0] + 1, &cellList));
      }
      for (PetscInt c = 0; c < nrecv; c++) {
        PetscInt i0[3], i1[3];

        CellBuckets(&b, &cells[CELL_RECORD * c], i0, i1);
        for (PetscInt k = i0[2]; k <= i1[2]; k++)
          for (PetscInt j = i0[1]; j <= i1[1]; j++)
            for (PetscInt i = i0[0]; i <= i1[0]; i++) {
              const PetscInt id = i + b.n[0] * (j + b.n[1] * k);

              if (id < b0 || id >= b1) continue;
              if (!pass) cellStart[id - b0 + 1]++;
              else cellList[cellStart[id - b0]++] = c;
            }
      }
      if (pass)
        for (PetscInt k = b1 - b0; k > 0; k--) cellStart[k] = cellStart[k - 1];
      if (pass) cellStart[0] = 0;
    }

    /* the fine mesh's owned vertices to the owners of their buckets */
    PetscCall(DMGetGlobalSection(fine, &gs));
    PetscCall(DMGetCoordinateSection(fine, &cs));
    PetscCall(DMGetCoordinatesLocal(fine, &xl));
    PetscCall(VecGetArrayRead(xl, &xa));
    PetscCall(DMPlexGetDepthStratum(fine, 0, &vStart, &vEnd));
    PetscCall(PetscArrayzero(count, size));
    PetscCall(PetscMalloc1(4 * (vEnd - vStart) + 1, &pts));
    for (PetscInt p = vStart; p < vEnd; p++) {
      PetscInt off, dof, coff;

      PetscCall(PetscSectionGetDof(gs, p, &dof));
      PetscCall(PetscSectionGetOffset(gs, p, &off));
      if (dof <= 0 || off < 0) continue; /* not owned, or constrained */
      PetscCall(PetscSectionGetOffset(cs, p, &coff));
      for (PetscInt d = 0; d < 3; d++) pts[4 * npts + d] = PetscRealPart(xa[coff + d]);
      pts[4 * npts++ + 3] = (PetscReal)p;
    }
    PetscCall(VecRestoreArrayRead(xl, &xa));
    for (PetscInt i = 0; i < npts; i++) count[BucketOwner(&b, BucketIndex(&b, &pts[4 * i], 0), BucketIndex(&b, &pts[4 * i], 1), BucketIndex(&b, &pts[4 * i], 2), size)]++;
    fill[0] = 0;
    for (PetscMPIInt r = 0; r < size; r++) fill[r + 1] = fill[r] + count[r];
    PetscCall(PetscMalloc1(4 * npts + 1, &send));
    for (PetscInt i = 0; i < npts; i++) {
      const PetscMPIInt o = BucketOwner(&b, BucketIndex(&b, &pts[4 * i], 0), BucketIndex(&b, &pts[4 * i], 1), BucketIndex(&b, &pts[4 * i], 2), size);

      PetscCall(PetscArraycpy(&send[4 * fill[o]++], &pts[4 * i], 4));
    }
    PetscCall(PetscArraycpy(pts, send, 4 * npts)); /* pts in the order sent: the answers come back so */
    PetscCall(SSStarExchange(comm, count, 4 * sizeof(PetscReal), send, rcount, (void **)&asked));
    PetscCall(PetscFree(send));
    for (PetscMPIInt r = 0; r < size; r++) nasked += rcount[r];
    /* the value at each point asked: the cell of its bucket that holds it, or that it is least outside of */
    PetscCall(PetscMalloc1(3 * nasked + 1, &answer));
    for (PetscInt q = 0; q < nasked; q++) {
      const PetscReal *x  = &asked[4 * q];
      const PetscInt   id = BucketIndex(&b, x, 0) + b.n[0] * (BucketIndex(&b, x, 1) + b.n[1] * BucketIndex(&b, x, 2)) - b0;
      PetscReal        best = -PETSC_MAX_REAL, lbest[4] = {0, 0, 0, 0};
      const PetscReal *rbest = NULL;

      for (PetscInt j = cellStart[id]; j < cellStart[id + 1] && best < 0; j++) {
        const PetscReal *r = &cells[CELL_RECORD * cellList[j]];
        PetscReal        l[4], m = Barycentric(r, x, l);

        if (m > best) {
          best  = m;
          rbest = r;
          PetscCall(PetscArraycpy(lbest, l, 4));
        }
      }
      if (best < 0) { /* outside every cell: the nearest one's weights, clipped */
        PetscReal sum = 0;

        for (PetscInt k = 0; k < 4; k++) sum += (lbest[k] = PetscMax(lbest[k], 0));
        for (PetscInt k = 0; k < 4; k++) lbest[k] = sum > 0 ? lbest[k] / sum : 0.25;
      }
      for (PetscInt d = 0; d < 3; d++) {
        answer[3 * q + d] = 0;
        for (PetscInt k = 0; rbest && k < 4; k++) answer[3 * q + d] += lbest[k] * rbest[12 + 3 * k + d];
      }
    }
    PetscCall(PetscFree(asked));
    PetscCall(PetscFree(cellStart));
    PetscCall(PetscFree(cellList));
    PetscCall(PetscFree(cells));
  }
  PetscCall(SSStarExchange(comm, rcount, 3 * sizeof(PetscReal), answer, count, (void **)&got));
  PetscCall(PetscFree(answer));
  /* into v at the fine vertices' global offsets */
  {
    PetscInt lo;

    PetscCall(VecGetOwnershipRange(v, &lo, NULL));
    PetscCall(VecGetArrayWrite(v, &va));
    for (PetscInt i = 0; i < npts; i++) {
      PetscInt off;

      PetscCall(PetscSectionGetOffset(gs, (PetscInt)pts[4 * i + 3], &off));
      for (PetscInt d = 0; d < 3; d++) va[off - lo + d] = got[3 * i + d];
    }
    PetscCall(VecRestoreArrayWrite(v, &va));
  }
  PetscCall(PetscFree(got));
  PetscCall(PetscFree(pts));
  PetscCall(PetscFree3(count, rcount, fill));
  PetscFunctionReturn(0);
}
