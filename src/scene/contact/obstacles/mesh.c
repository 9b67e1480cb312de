/*
   A rigid body bounded by the 3-node triangles of a gmsh file (-obstacle_<G> mesh:FILE.msh), oriented counterclockwise
   seen from outside (their normals (b - a) x (c - a) point out of the obstacle, towards the body), as gmsh orients the
   boundary of a volume; an open surface (a square standing for a plane) is oriented with its normals towards the body.
   A node's closest point q on the triangles gives its distance; its sign is that of (x - q) . m, with m the
   pseudo-normal of the feature q lies on (src/geometry/surface.c), which is right on every side of a closed oriented
   surface. The normal is (x - q)/|x - q| for a node off the surface and m for a node on it (distance within round-off).
   Rank 0 reads the file and checks the surface; the triangles are then spread over the ranks in compact parts
   (SSStarTrianglesPartition()), each rank's in a search tree, and the closest triangle of a node is found by the
   ranks whose triangles can hold it (SSStarSearchClosest(): the first in file order among the closest, as a loop over
   all would find): no rank keeps every triangle.
*/
#include "obstacleimpl.h"
#include "../../../sys/gmshlib.h"
#include <unistd.h>

#define PSEUDO_NORMALS 21 /* 7 x 3 per triangle: face, edges 01 12 20, vertices (surface.c) */

typedef struct {
  char         file[PETSC_MAX_PATH_LEN];
  PetscInt     nt;     /* triangles in the file                                                                */
  SSStarSearch search; /* this rank's share of them; key: the file index; data: its pseudo-normals             */
} Mesh;

/* A triangle as rank 0 sends it: its vertices (9), file index, pseudo-normals */
#define PACKED (9 + 1 + PSEUDO_NORMALS)

/*
   Rank 0's triangles (the file's nv vertices xv, nt triangles tri, their pseudo-normals pn) spread over the ranks of
   comm in compact parts, each rank's in file order; the search over them
*/
static PetscErrorCode SpreadTriangles(MPI_Comm comm, PetscInt nv, const PetscReal xv[], PetscInt nt, const PetscInt tri[], const PetscReal pn[], SSStarSearch *search)
{
  PetscMPIInt  rank, size, *part = NULL, *counts = NULL, *displs = NULL, mine;
  PetscReal   *packed = NULL, *x = NULL, *local, *data, *xl;
  PetscInt    *key, n;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(SSSTAR_Search, 0, 0, 0, 0));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  if (rank == 0) {
    PetscCall(PetscMalloc4(9 * nt + 1, &x, nt + 1, &part, size, &counts, size, &displs));
    for (PetscInt t = 0; t < nt; t++)
      for (PetscInt j = 0; j < 3; j++)
        for (PetscInt k = 0; k < 3; k++) x[9 * t + 3 * j + k] = xv[3 * tri[3 * t + j] + k];
    PetscCall(SSStarTrianglesPartition(nt, x, size, part));
    PetscCall(PetscArrayzero(counts, size));
    for (PetscInt t = 0; t < nt; t++) counts[part[t]] += PACKED;
    displs[0] = 0;
    for (PetscMPIInt r = 1; r < size; r++) displs[r] = displs[r - 1] + counts[r - 1];
    PetscCall(PetscMalloc1(PACKED * nt + 1, &packed));
    for (PetscInt t = 0; t < nt; t++) { /* in file order within each rank's share */
      PetscReal *a = &packed[displs[part[t]]];

      PetscCall(PetscArraycpy(a, &x[9 * t], 9));
      a[9] = (PetscReal)t;
      PetscCall(PetscArraycpy(&a[10], &pn[PSEUDO_NORMALS * t], PSEUDO_NORMALS));
      displs[part[t]] += PACKED;
    }
    for (PetscMPIInt r = 0; r < size; r++) displs[r] -= counts[r];
  }
  PetscCallMPI(MPI_Scatter(counts, 1, MPI_INT, &mine, 1, MPI_INT, 0, comm));
  PetscCall(PetscMalloc1(mine + 1, &local));
  PetscCallMPI(MPI_Scatterv(packed, counts, displs, MPIU_REAL, local, mine, MPIU_REAL, 0, comm));
  if (rank == 0) {
    PetscCall(PetscFree(packed));
    PetscCall(PetscFree4(x, part, counts, displs));
  }
  n = mine / PACKED;
  PetscCall(PetscMalloc3(9 * n + 1, &xl, 3 * n + 1, &key, PSEUDO_NORMALS * n + 1, &data));
  for (PetscInt t = 0; t < n; t++) {
    const PetscReal *a = &local[PACKED * t];

    PetscCall(PetscArraycpy(&xl[9 * t], a, 9));
    key[3 * t]     = (PetscInt)a[9];
    key[3 * t + 1] = key[3 * t + 2] = 0;
    PetscCall(PetscArraycpy(&data[PSEUDO_NORMALS * t], &a[10], PSEUDO_NORMALS));
  }
  PetscCall(PetscFree(local));
  PetscCall(PetscLogEventEnd(SSSTAR_Search, 0, 0, 0, 0));
  PetscCall(SSStarSearchCreate(comm, n, xl, key, PSEUDO_NORMALS, data, search));
  PetscCall(PetscFree3(xl, key, data));
  PetscFunctionReturn(0);
}

/*
   Rank 0 reads the triangles of file with gmsh (3-node triangles, element type 2, of every entity) into xv, tri;
   *failure: 0, 1 (no such file), 2 (gmsh cannot read it), 3 (no triangle)
*/
static PetscErrorCode ReadTriangles(const char file[], PetscInt *nv, PetscReal **xv, PetscInt *nt, PetscInt **tri, int *failure)
{
  size_t   *nodeTags = NULL, nn = 0, nc = 0, np = 0, *etags = NULL, ne = 0, *enodes = NULL, nen = 0;
  double   *coord = NULL, *param = NULL;
  int       ierr = 0;
  PetscInt *tags, *order;

  PetscFunctionBegin;
  *failure = 0;
  *nv = *nt = 0;
  *xv       = NULL;
  *tri      = NULL;
  if (access(file, R_OK)) {
    *failure = 1;
    PetscFunctionReturn(0);
  }
  if (SSStarGmshLoad()) {
    *failure = 2;
    PetscFunctionReturn(0);
  }
  gmshInitialize(0, NULL, 0, &ierr);
  if (!ierr) gmshOptionSetNumber("General.Verbosity", 0, &ierr);
  if (!ierr) gmshOpen(file, &ierr);
  if (!ierr) gmshModelMeshGetNodes(&nodeTags, &nn, &coord, &nc, &param, &np, -1, -1, 0, 0, &ierr);
  if (!ierr) gmshModelMeshGetElementsByType(2, &etags, &ne, &enodes, &nen, -1, 0, 1, &ierr);
  if (ierr) *failure = 2;
  else if (!ne) *failure = 3;
  if (!*failure) {
    PetscCall(PetscMalloc2(nn, &tags, nn, &order));
    for (size_t i = 0; i < nn; i++) {
      tags[i]  = (PetscInt)nodeTags[i];
      order[i] = (PetscInt)i;
    }
    PetscCall(PetscSortIntWithArray((PetscInt)nn, tags, order));
    PetscCall(PetscMalloc1(3 * nn, xv));
    PetscCall(PetscMalloc1(3 * ne, tri));
    for (size_t i = 0; i < nn; i++)
      for (PetscInt k = 0; k < 3; k++) (*xv)[3 * i + k] = (PetscReal)coord[3 * order[i] + k];
    for (size_t i = 0; i < 3 * ne && !*failure; i++) {
      PetscInt loc;

      PetscCall(PetscFindInt((PetscInt)enodes[i], (PetscInt)nn, tags, &loc));
      if (loc < 0) *failure = 2;
      else (*tri)[i] = loc;
    }
    PetscCall(PetscFree2(tags, order));
    *nv = (PetscInt)nn;
    *nt = (PetscInt)ne;
    if (*failure) {
      PetscCall(PetscFree(*xv));
      PetscCall(PetscFree(*tri));
      *nv = *nt = 0;
    }
  }
  gmshFree(nodeTags);
  gmshFree(coord);
  gmshFree(param);
  gmshFree(etags);
  gmshFree(enodes);
  gmshFinalize(&ierr);
  PetscFunctionReturn(0);
}

/* The triangles: read on rank 0, checked there, spread over the ranks; refuses a surface that bounds no body */
static PetscErrorCode SetFromString_Mesh(SSStarObstacle ob, MPI_Comm comm, const char option[], const char spec[], const char numbers[])
{
  Mesh              *mesh = (Mesh *)ob->data;
  PetscMPIInt        rank;
  int                failure = 0;
  PetscInt           nv = 0, *tri = NULL, defect[6];
  PetscReal         *xv = NULL, *pn = NULL;
  SSStarSurfaceCheck check;

  PetscFunctionBegin;
  PetscCheck(numbers[0], comm, PETSC_ERR_ARG_WRONG, "Option %s mesh: needs a file name (mesh:FILE.msh)", option);
  PetscCall(PetscStrncpy(mesh->file, numbers, sizeof(mesh->file)));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) PetscCall(ReadTriangles(mesh->file, &nv, &xv, &mesh->nt, &tri, &failure));
  PetscCallMPI(MPI_Bcast(&failure, 1, MPI_INT, 0, comm));
  PetscCheck(failure != 1, comm, PETSC_ERR_FILE_OPEN, "Option %s mesh:%s: cannot read the file", option, mesh->file);
  PetscCheck(failure != 2, comm, PETSC_ERR_FILE_READ, "Option %s mesh:%s: gmsh cannot read the file as a mesh", option, mesh->file);
  PetscCheck(failure != 3, comm, PETSC_ERR_ARG_WRONG, "Option %s mesh:%s: the file has no triangles (3-node triangles, gmsh element type 2): an obstacle is given by its surface", option, mesh->file);
  if (rank == 0) {
    for (PetscInt v = 0; v < nv; v++) /* the reference point: the mean of the vertices */
      for (PetscInt k = 0; k < 3; k++) ob->reference[k] += xv[3 * v + k] / nv;
    PetscCall(PetscMalloc1(PSEUDO_NORMALS * mesh->nt, &pn));
    PetscCall(SSStarSurfacePseudoNormals(nv, xv, mesh->nt, tri, pn, &check));
    defect[0] = (PetscInt)check.defect;
    defect[1] = check.triangle[0];
    defect[2] = check.triangle[1];
    defect[3] = check.vertex[0];
    defect[4] = check.vertex[1];
    defect[5] = check.count;
  }
  PetscCallMPI(MPI_Bcast(defect, 6, MPIU_INT, 0, comm));
  PetscCallMPI(MPI_Bcast(&mesh->nt, 1, MPIU_INT, 0, comm));
  PetscCallMPI(MPI_Bcast(ob->reference, 3, MPIU_REAL, 0, comm));
  if (defect[0] == (PetscInt)SSSTAR_SURFACE_OK) PetscCall(SpreadTriangles(comm, nv, xv, mesh->nt, tri, pn, &mesh->search));
  PetscCall(PetscFree(xv));
  PetscCall(PetscFree(tri));
  PetscCall(PetscFree(pn));
  PetscCheck(defect[0] != (PetscInt)SSSTAR_SURFACE_ZERO_AREA, comm, PETSC_ERR_ARG_WRONG, "Option %s mesh:%s: triangle %" PetscInt_FMT " (0-based, file order) has zero area", option, mesh->file, defect[1]);
  PetscCheck(defect[0] != (PetscInt)SSSTAR_SURFACE_NONMANIFOLD, comm, PETSC_ERR_ARG_WRONG, "Option %s mesh:%s: the edge between nodes %" PetscInt_FMT " and %" PetscInt_FMT " (0-based, by node tag) is shared by %" PetscInt_FMT " triangles: not the surface of a body", option, mesh->file, defect[3], defect[4], defect[5]);
  PetscCheck(defect[0] != (PetscInt)SSSTAR_SURFACE_MISORIENTED, comm, PETSC_ERR_ARG_WRONG, "Option %s mesh:%s: triangles %" PetscInt_FMT " and %" PetscInt_FMT " (0-based) are oriented differently: orient every triangle counterclockwise seen from outside the obstacle", option, mesh->file, defect[1], defect[2]);
  PetscFunctionReturn(0);
}

/* Each point's closest triangle over the ranks; the sign of the distance from the pseudo-normal of its feature */
static PetscErrorCode Gaps_Mesh(SSStarObstacle ob, PetscInt n, const PetscReal x[], PetscReal tol, PetscReal gap[], PetscReal normal[])
{
  const Mesh      *mesh = (const Mesh *)ob->data;
  SSStarSearchHit *hit;
  PetscReal       *pn;

  PetscFunctionBegin;
  PetscCall(PetscMalloc2(n + 1, &hit, PSEUDO_NORMALS * n + 1, &pn));
  PetscCall(SSStarSearchClosest(mesh->search, n, x, 0, hit, pn));
  for (PetscInt i = 0; i < n; i++) {
    const PetscReal *m = &pn[PSEUDO_NORMALS * i + 3 * (PetscInt)hit[i].feature]; /* the features in the order of the pseudo-normals */
    PetscReal        d[3], len = PetscSqrtReal(hit[i].d2), s;

    for (PetscInt k = 0; k < 3; k++) d[k] = x[3 * i + k] - hit[i].q[k];
    s      = SSStarDot3(d, m) >= 0 ? 1.0 : -1.0;
    gap[i] = s * len;
    if (len > tol)
      for (PetscInt k = 0; k < 3; k++) normal[3 * i + k] = s * d[k] / len;
    else
      for (PetscInt k = 0; k < 3; k++) normal[3 * i + k] = m[k];
  }
  PetscCall(PetscFree2(hit, pn));
  PetscFunctionReturn(0);
}

static PetscErrorCode Describe_Mesh(SSStarObstacle ob, char text[], size_t len)
{
  const Mesh *mesh = (const Mesh *)ob->data;

  PetscFunctionBegin;
  PetscCall(PetscSNPrintf(text, len, "rigid body of mesh %s (%" PetscInt_FMT " triangles)", mesh->file, mesh->nt));
  PetscFunctionReturn(0);
}

static PetscErrorCode Attributes_Mesh(SSStarObstacle ob, SSStarAttributeWriter *w)
{
  const Mesh *mesh = (const Mesh *)ob->data;

  PetscFunctionBegin;
  PetscCall((*w->string)(w->ctx, "file", mesh->file));
  PetscCall((*w->integer)(w->ctx, "triangles", mesh->nt));
  PetscFunctionReturn(0);
}

static PetscErrorCode Destroy_Mesh(SSStarObstacle ob)
{
  Mesh *mesh = (Mesh *)ob->data;

  PetscFunctionBegin;
  PetscCall(SSStarSearchDestroy(&mesh->search));
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarObstacleCreate_Mesh(SSStarObstacle ob)
{
  PetscFunctionBegin;
  PetscCall(PetscNew((Mesh **)&ob->data));
  ob->ops.setfromstring = SetFromString_Mesh;
  ob->ops.gaps          = Gaps_Mesh;
  ob->ops.describe      = Describe_Mesh;
  ob->ops.attributes    = Attributes_Mesh;
  ob->ops.destroy       = Destroy_Mesh;
  ob->ops.insideHint    = "are the obstacle's triangles oriented counterclockwise seen from outside it, their normals towards the body?";
  PetscFunctionReturn(0);
}
