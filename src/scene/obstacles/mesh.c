/*
   A rigid body bounded by the 3-node triangles of a gmsh file (-obstacle_<G> mesh:FILE.msh), oriented counterclockwise
   seen from outside (their normals (b - a) x (c - a) point out of the obstacle, towards the body), as gmsh orients the
   boundary of a volume; an open surface (a square standing for a plane) is oriented with its normals towards the body.
   A node's closest point q on the triangles gives its distance; its sign is that of (x - q) . m, with m the
   pseudo-normal of the feature q lies on (src/geometry/surface.c), which is right on every side of a closed oriented
   surface. The normal is (x - q)/|x - q| for a node off the surface and m for a node on it (distance within round-off).
   Brute force over the triangles, pruned by their bounding boxes.
*/
#include "../obstacleimpl.h"
#include <gmshc.h>
#include <unistd.h>

typedef struct {
  char      file[PETSC_MAX_PATH_LEN];
  PetscInt  nv, nt;
  PetscReal *xv;  /* 3 per vertex                                                                  */
  PetscInt  *tri; /* 3 vertex indices per triangle, counterclockwise seen from outside              */
  PetscReal *pn;  /* pseudo-normals, 7 x 3 per triangle: face, edges 01 12 20, vertices (surface.c) */
  PetscReal *box; /* bounding box per triangle, 6                                                  */
} Mesh;

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

/* The triangles: read on rank 0, broadcast; their pseudo-normals and boxes; refuses a surface that bounds no body */
static PetscErrorCode SetFromString_Mesh(SSStarObstacle ob, MPI_Comm comm, const char option[], const char spec[], const char numbers[])
{
  Mesh              *mesh = (Mesh *)ob->data;
  PetscMPIInt        rank;
  int                failure  = 0;
  PetscInt           sizes[2] = {0, 0};
  SSStarSurfaceCheck check;

  PetscFunctionBegin;
  PetscCheck(numbers[0], comm, PETSC_ERR_ARG_WRONG, "Option %s mesh: needs a file name (mesh:FILE.msh)", option);
  PetscCall(PetscStrncpy(mesh->file, numbers, sizeof(mesh->file)));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) PetscCall(ReadTriangles(mesh->file, &mesh->nv, &mesh->xv, &mesh->nt, &mesh->tri, &failure));
  PetscCallMPI(MPI_Bcast(&failure, 1, MPI_INT, 0, comm));
  PetscCheck(failure != 1, comm, PETSC_ERR_FILE_OPEN, "Option %s mesh:%s: cannot read the file", option, mesh->file);
  PetscCheck(failure != 2, comm, PETSC_ERR_FILE_READ, "Option %s mesh:%s: gmsh cannot read the file as a mesh", option, mesh->file);
  PetscCheck(failure != 3, comm, PETSC_ERR_ARG_WRONG, "Option %s mesh:%s: the file has no triangles (3-node triangles, gmsh element type 2): an obstacle is given by its surface", option, mesh->file);
  sizes[0] = mesh->nv;
  sizes[1] = mesh->nt;
  PetscCallMPI(MPI_Bcast(sizes, 2, MPIU_INT, 0, comm));
  if (rank) {
    mesh->nv = sizes[0];
    mesh->nt = sizes[1];
    PetscCall(PetscMalloc1(3 * mesh->nv, &mesh->xv));
    PetscCall(PetscMalloc1(3 * mesh->nt, &mesh->tri));
  }
  PetscCallMPI(MPI_Bcast(mesh->xv, (PetscMPIInt)(3 * mesh->nv), MPIU_REAL, 0, comm));
  PetscCallMPI(MPI_Bcast(mesh->tri, (PetscMPIInt)(3 * mesh->nt), MPIU_INT, 0, comm));
  PetscCall(PetscMalloc1(21 * mesh->nt, &mesh->pn));
  PetscCall(PetscMalloc1(6 * mesh->nt, &mesh->box));
  PetscCall(SSStarSurfacePseudoNormals(mesh->nv, mesh->xv, mesh->nt, mesh->tri, mesh->pn, &check));
  PetscCheck(check.defect != SSSTAR_SURFACE_ZERO_AREA, comm, PETSC_ERR_ARG_WRONG, "Option %s mesh:%s: triangle %" PetscInt_FMT " (0-based, file order) has zero area", option, mesh->file, check.triangle[0]);
  PetscCheck(check.defect != SSSTAR_SURFACE_NONMANIFOLD, comm, PETSC_ERR_ARG_WRONG, "Option %s mesh:%s: the edge between nodes %" PetscInt_FMT " and %" PetscInt_FMT " (0-based, by node tag) is shared by %" PetscInt_FMT " triangles: not the surface of a body", option, mesh->file, check.vertex[0], check.vertex[1], check.count);
  PetscCheck(check.defect != SSSTAR_SURFACE_MISORIENTED, comm, PETSC_ERR_ARG_WRONG, "Option %s mesh:%s: triangles %" PetscInt_FMT " and %" PetscInt_FMT " (0-based) are oriented differently: orient every triangle counterclockwise seen from outside the obstacle", option, mesh->file, check.triangle[0], check.triangle[1]);
  for (PetscInt t = 0; t < mesh->nt; t++) {
    const PetscInt *v = &mesh->tri[3 * t];

    SSStarTriangleBox(&mesh->xv[3 * v[0]], &mesh->xv[3 * v[1]], &mesh->xv[3 * v[2]], &mesh->box[6 * t]);
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode Gap_Mesh(SSStarObstacle ob, const PetscReal x[3], PetscReal tol, PetscReal *gap, PetscReal n[3])
{
  const Mesh           *mesh = (const Mesh *)ob->data;
  PetscReal             best = PETSC_MAX_REAL, q[3], qbest[3] = {0, 0, 0}, d[3], len, s;
  PetscInt              tbest = -1;
  SSStarTriangleFeature feature, fbest = SSSTAR_TRIANGLE_FACE;
  const PetscReal      *m;

  PetscFunctionBegin;
  for (PetscInt t = 0; t < mesh->nt; t++) {
    const PetscInt *v = &mesh->tri[3 * t];
    PetscReal       d2;

    if (SSStarBoxDistance2(x, &mesh->box[6 * t]) >= best) continue;
    SSStarClosestPointOnTriangle(x, &mesh->xv[3 * v[0]], &mesh->xv[3 * v[1]], &mesh->xv[3 * v[2]], q, NULL, &feature);
    d2 = PetscSqr(x[0] - q[0]) + PetscSqr(x[1] - q[1]) + PetscSqr(x[2] - q[2]);
    if (d2 < best) {
      best  = d2;
      tbest = t;
      fbest = feature;
      for (PetscInt k = 0; k < 3; k++) qbest[k] = q[k];
    }
  }
  m = &mesh->pn[21 * tbest + 3 * (PetscInt)fbest]; /* the features in the order of the pseudo-normals */
  for (PetscInt k = 0; k < 3; k++) d[k] = x[k] - qbest[k];
  len  = PetscSqrtReal(best);
  s    = SSStarDot3(d, m) >= 0 ? 1.0 : -1.0;
  *gap = s * len;
  if (len > tol)
    for (PetscInt k = 0; k < 3; k++) n[k] = s * d[k] / len;
  else
    for (PetscInt k = 0; k < 3; k++) n[k] = m[k];
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
  PetscCall(PetscFree(mesh->xv));
  PetscCall(PetscFree(mesh->tri));
  PetscCall(PetscFree(mesh->pn));
  PetscCall(PetscFree(mesh->box));
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarObstacleCreate_Mesh(SSStarObstacle ob)
{
  PetscFunctionBegin;
  PetscCall(PetscNew((Mesh **)&ob->data));
  ob->ops.setfromstring = SetFromString_Mesh;
  ob->ops.gap           = Gap_Mesh;
  ob->ops.describe      = Describe_Mesh;
  ob->ops.attributes    = Attributes_Mesh;
  ob->ops.destroy       = Destroy_Mesh;
  ob->ops.insideHint    = "are the obstacle's triangles oriented counterclockwise seen from outside it, their normals towards the body?";
  PetscFunctionReturn(0);
}
