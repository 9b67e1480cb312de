/*
   The faces of the mesh cache's tetrahedra without edges (meshcache.c reads the cells): each cell's four faces found by
   their vertices, and the faces on rank boundaries matched through a hash of their vertex triples (the rank a triple
   hashes to meets both copies), which also matches the surface groups' triangles to their faces.
*/
#include "../sceneimpl.h"
#include <petscsf.h>

/* The rank a vertex triple (sorted) is matched on */
PetscMPIInt SSStarTripleHomeRank(const PetscInt v[3], PetscMPIInt size)
{
  unsigned long long h = 1469598103934665603ULL;

  for (int k = 0; k < 3; k++) h = (h ^ (unsigned long long)v[k]) * 1099511628211ULL;
  return (PetscMPIInt)(h % (unsigned long long)size);
}

int SSStarTripleCompare(const void *a, const void *b)
{
  const PetscInt *x = (const PetscInt *)a, *y = (const PetscInt *)b;

  for (int k = 0; k < 3; k++)
    if (x[k] != y[k]) return x[k] < y[k] ? -1 : 1;
  return 0;
}

void SSStarTripleSort(PetscInt v[3])
{
  PetscInt t;

  if (v[0] > v[1]) { t = v[0]; v[0] = v[1]; v[1] = t; }
  if (v[1] > v[2]) { t = v[1]; v[1] = v[2]; v[2] = t; }
  if (v[0] > v[1]) { t = v[0]; v[0] = v[1]; v[1] = t; }
}

/* Sends records of 4 PetscInt to the ranks dest[] (sorted by nothing), returns what this rank receives */
PetscErrorCode SSStarTripleExchange(MPI_Comm comm, PetscInt n, const PetscMPIInt dest[], const PetscInt rec[], PetscInt *nrecv, PetscInt **recv)
{
  PetscMPIInt size, *scount, *sdispl, *rcount, *rdispl, *fill;
  PetscInt   *sbuf;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(PetscCalloc5(size, &scount, size + 1, &sdispl, size, &rcount, size + 1, &rdispl, size, &fill));
  for (PetscInt i = 0; i < n; i++) scount[dest[i]] += 4;
  for (PetscMPIInt r = 0; r < size; r++) sdispl[r + 1] = sdispl[r] + scount[r];
  PetscCall(PetscMalloc1(4 * n + 1, &sbuf));
  for (PetscInt i = 0; i < n; i++) {
    PetscCall(PetscArraycpy(sbuf + sdispl[dest[i]] + fill[dest[i]], rec + 4 * i, 4));
    fill[dest[i]] += 4;
  }
  PetscCallMPI(MPI_Alltoall(scount, 1, MPI_INT, rcount, 1, MPI_INT, comm));
  for (PetscMPIInt r = 0; r < size; r++) rdispl[r + 1] = rdispl[r] + rcount[r];
  PetscCall(PetscMalloc1(rdispl[size] + 1, recv));
  PetscCallMPI(MPI_Alltoallv(sbuf, scount, sdispl, MPIU_INT, *recv, rcount, rdispl, MPIU_INT, comm));
  *nrecv = rdispl[size] / 4;
  PetscCall(PetscFree(sbuf));
  PetscCall(PetscFree5(scount, sdispl, rcount, rdispl, fill));
  PetscFunctionReturn(0);
}

/* The four faces of a tetrahedron (local vertex indices), opposite its vertices 0, 1, 2, 3 */
static const int TetFaces[4][3] = {
  {1, 2, 3},
  {0, 2, 3},
  {0, 1, 3},
  {0, 1, 2}
};

/*
   Faces shared with other ranks: each face of local support 1 meets its twin (same global vertex triple) on the rank
   the triple hashes to; the lower rank owns it, the other gets a leaf. Appends the leaves (local face, owner's face)
   to the n vertex leaves in ilocal, iremote (allocated for every face of support 1 beyond them).
*/
static PetscErrorCode ShareFaces(MPI_Comm comm, DM dm, const PetscInt gvertex[], PetscInt *n, PetscInt ilocal[], PetscSFNode iremote[])
{
  PetscMPIInt size, rank, *dest;
  PetscInt    fStart, fEnd, vStart, nface = 0, *rec, nrecv, *recv, nback = 0, *back, nret, *ret;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (size == 1) PetscFunctionReturn(0);
  PetscCall(DMPlexGetHeightStratum(dm, 1, &fStart, &fEnd));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, NULL));
  PetscCall(PetscMalloc2(fEnd - fStart + 1, &dest, 4 * (fEnd - fStart) + 1, &rec));
  for (PetscInt f = fStart; f < fEnd; f++) {
    const PetscInt *cone;
    PetscInt        support;

    PetscCall(DMPlexGetSupportSize(dm, f, &support));
    if (support != 1) continue;
    PetscCall(DMPlexGetCone(dm, f, &cone));
    for (int k = 0; k < 3; k++) rec[4 * nface + k] = gvertex[cone[k] - vStart];
    SSStarTripleSort(&rec[4 * nface]);
    rec[4 * nface + 3] = rank + (PetscInt)size * f;
    dest[nface]        = SSStarTripleHomeRank(&rec[4 * nface], size);
    nface++;
  }
  PetscCall(SSStarTripleExchange(comm, nface, dest, rec, &nrecv, &recv));
  PetscCall(PetscFree2(dest, rec));
  /* at home: twins are neighbours once sorted; the higher rank's face becomes a leaf of the lower rank's */
  qsort(recv, nrecv, 4 * sizeof(PetscInt), SSStarTripleCompare);
  PetscCall(PetscMalloc2(nrecv / 2 + 1, &dest, 4 * (nrecv / 2) + 1, &back));
  for (PetscInt i = 0; i + 1 < nrecv; i++) {
    const PetscInt *a = &recv[4 * i], *b = &recv[4 * i + 4];
    PetscInt        ra = a[3] % size, rb = b[3] % size;

    if (SSStarTripleCompare(a, b)) continue;
    if (ra > rb) {
      const PetscInt *t = a;

      a  = b;
      b  = t;
      ra = rb;
      rb = b[3] % size;
    }
    dest[nback]         = (PetscMPIInt)rb;
    back[4 * nback]     = b[3] / size;
    back[4 * nback + 1] = ra;
    back[4 * nback + 2] = a[3] / size;
    back[4 * nback + 3] = 0;
    nback++;
    i++;
  }
  PetscCall(PetscFree(recv));
  PetscCall(SSStarTripleExchange(comm, nback, dest, back, &nret, &ret));
  PetscCall(PetscFree2(dest, back));
  for (PetscInt i = 0; i < nret; i++) {
    ilocal[*n]        = ret[4 * i];
    iremote[*n].rank  = ret[4 * i + 1];
    iremote[*n].index = ret[4 * i + 2];
    (*n)++;
  }
  PetscCall(PetscFree(ret));
  PetscFunctionReturn(0);
}

/*
   The mesh with its faces but without edges (nothing here uses edges; DMPlex's interpolation makes both, most of the
   read's time at scale): from the uninterpolated dm0 (cells [0, nc), vertices [nc, nc + nv)), cells -> 4 faces -> 3
   vertices with the faces numbered after the vertices, dm0's coordinates, and dm0's vertex SF with the faces shared
   with other ranks. The faces are found by their smallest vertex, then the other two.
*/
PetscErrorCode SSStarMeshAddFaces(DM dm0, const PetscInt gvertex[], DM *dm)
{
  MPI_Comm        comm = PetscObjectComm((PetscObject)dm0);
  PetscInt        cStart, cEnd, vStart, vEnd, nc, nv, nf = 0, *start, *fill, *slot, *faceOf, *faceCone, *first, nleaves, nroots, n = 0, *ilocal;
  const PetscInt *leaves;
  const PetscSFNode *remotes;
  PetscSFNode    *iremote;
  PetscSF         sf0, sf;
  PetscSection    csec;
  Vec             coordinates;

  PetscFunctionBegin;
  PetscCall(DMPlexGetHeightStratum(dm0, 0, &cStart, &cEnd));
  PetscCall(DMPlexGetDepthStratum(dm0, 0, &vStart, &vEnd));
  PetscCheck(cStart == 0 && vStart == cEnd, comm, PETSC_ERR_PLIB, "Unexpected point numbering of the uninterpolated mesh");
  nc = cEnd;
  nv = vEnd - vStart;
  /* the (cell, face) slots in buckets by their smallest vertex */
  PetscCall(PetscCalloc2(nv + 1, &start, nv, &fill));
  PetscCall(PetscMalloc4(4 * nc, &slot, 4 * nc, &faceOf, 12 * nc, &faceCone, 4 * nc, &first));
  for (PetscInt c = 0; c < nc; c++) {
    const PetscInt *cone;

    PetscCall(DMPlexGetCone(dm0, c, &cone));
    for (int k = 0; k < 4; k++) {
      PetscInt *t = &faceCone[3 * (4 * c + k)];

      for (int j = 0; j < 3; j++) t[j] = cone[TetFaces[k][j]] - vStart;
      SSStarTripleSort(t);
      start[t[0] + 1]++;
    }
  }
  for (PetscInt v = 0; v < nv; v++) start[v + 1] += start[v];
  for (PetscInt s = 0; s < 4 * nc; s++) {
    const PetscInt v = faceCone[3 * s];

    slot[start[v] + fill[v]++] = s;
  }
  /* in each bucket, a slot whose other two vertices match an earlier slot's is the same face */
  for (PetscInt v = 0; v < nv; v++)
    for (PetscInt i = start[v]; i < start[v + 1]; i++) {
      const PetscInt *t = &faceCone[3 * slot[i]];
      PetscInt        j;

      for (j = start[v]; j < i; j++) {
        const PetscInt *u = &faceCone[3 * slot[j]];

        if (u[1] == t[1] && u[2] == t[2]) break;
      }
      if (j < i) faceOf[slot[i]] = faceOf[slot[j]];
      else {
        first[nf]       = slot[i];
        faceOf[slot[i]] = nf++;
      }
    }
  PetscCall(DMPlexCreate(comm, dm));
  PetscCall(DMSetDimension(*dm, 3));
  PetscCall(DMPlexSetChart(*dm, 0, nc + nv + nf));
  for (PetscInt c = 0; c < nc; c++) PetscCall(DMPlexSetConeSize(*dm, c, 4));
  for (PetscInt f = 0; f < nf; f++) PetscCall(DMPlexSetConeSize(*dm, nc + nv + f, 3));
  PetscCall(DMSetUp(*dm));
  for (PetscInt c = 0; c < nc; c++) {
    PetscInt cone[4];

    for (int k = 0; k < 4; k++) cone[k] = nc + nv + faceOf[4 * c + k];
    PetscCall(DMPlexSetCone(*dm, c, cone));
  }
  for (PetscInt f = 0; f < nf; f++) {
    PetscInt cone[3];

    for (int j = 0; j < 3; j++) cone[j] = vStart + faceCone[3 * first[f] + j];
    PetscCall(DMPlexSetCone(*dm, nc + nv + f, cone));
  }
  PetscCall(PetscFree4(slot, faceOf, faceCone, first));
  PetscCall(PetscFree2(start, fill));
  PetscCall(DMPlexSymmetrize(*dm));
  PetscCall(DMPlexStratify(*dm));

  /* the point SF: dm0's vertex leaves (same point numbers) and the shared faces; then the coordinates */
  PetscCall(DMGetPointSF(dm0, &sf0));
  PetscCall(PetscSFGetGraph(sf0, NULL, &nleaves, &leaves, &remotes));
  nleaves = PetscMax(nleaves, 0);
  PetscCall(PetscMalloc1(nleaves + nf, &ilocal));
  PetscCall(PetscMalloc1(nleaves + nf, &iremote));
  for (PetscInt l = 0; l < nleaves; l++) {
    ilocal[n]    = leaves ? leaves[l] : l;
    iremote[n++] = remotes[l];
  }
  PetscCall(ShareFaces(comm, *dm, gvertex, &n, ilocal, iremote));
  nroots = nc + nv + nf;
  PetscCall(PetscSFCreate(comm, &sf));
  PetscCall(PetscSFSetGraph(sf, nroots, n, ilocal, PETSC_OWN_POINTER, iremote, PETSC_OWN_POINTER));
  PetscCall(DMSetPointSF(*dm, sf));
  PetscCall(PetscSFDestroy(&sf));
  PetscCall(DMSetCoordinateDim(*dm, 3));
  PetscCall(DMGetCoordinateSection(dm0, &csec));
  PetscCall(DMSetCoordinateSection(*dm, 3, csec));
  PetscCall(DMGetCoordinatesLocal(dm0, &coordinates));
  PetscCall(DMSetCoordinatesLocal(*dm, coordinates));
  PetscFunctionReturn(0);
}

