/*
   Rigid obstacles of the scenes (-obstacle_<G>): a plane, a ball, an infinite cylinder or a gmsh surface mesh of
   triangles, and for each contact node its initial gap and the unit normal of its frame (pointing out of the
   obstacle, into the body). Small deformation: both at the reference configuration.

   A mesh obstacle is a rigid body bounded by triangles oriented counterclockwise seen from outside (their normals
   (b - a) x (c - a) point out of the obstacle, towards the body), as gmsh orients the boundary of a volume; an open
   surface (a square standing for a plane) is oriented with its normals towards the body. A node's closest point q on
   the triangles gives its distance; its sign is that of (x - q) . m, with m the pseudo-normal of the feature q lies on
   (the face's normal, the sum of the two faces' normals on an edge, the angle-weighted sum of the faces' normals at a
   vertex: Baerentzen and Aanaes 2005), which is right on every side of a closed oriented surface. The normal is
   (x - q)/|x - q| for a node off the surface and m/|m| for a node on it (distance within round-off).
*/
#include "obstacle.h"
#include <gmshc.h>
#include <unistd.h>

static PetscReal Dot3(const PetscReal a[3], const PetscReal b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void Cross3(const PetscReal a[3], const PetscReal b[3], PetscReal c[3])
{
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

/* The comma-separated numbers of a spec: exactly n finite values */
static PetscErrorCode ParseNumbers(MPI_Comm comm, const char option[], const char spec[], const char numbers[], PetscInt n, const char form[], PetscReal v[])
{
  const char *s = numbers;
  PetscInt    got = 0;

  PetscFunctionBegin;
  while (*s) {
    char     *end;
    PetscReal value = (PetscReal)strtod(s, &end);

    PetscCheck(end != s && (*end == ',' || !*end), comm, PETSC_ERR_ARG_WRONG, "Option %s %s: \"%s\" is not a list of numbers %s", option, spec, numbers, form);
    PetscCheck(got < n, comm, PETSC_ERR_ARG_WRONG, "Option %s %s needs %" PetscInt_FMT " comma-separated values %s (got more)", option, spec, n, form);
    PetscCheck(!PetscIsInfOrNanReal(value), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option %s %s: value %" PetscInt_FMT " is not a finite number (%g)", option, spec, got + 1, (double)value);
    v[got++] = value;
    s        = *end ? end + 1 : end;
  }
  PetscCheck(got == n, comm, PETSC_ERR_ARG_WRONG, "Option %s %s needs %" PetscInt_FMT " comma-separated values %s (got %" PetscInt_FMT ")", option, spec, n, form, got);
  PetscFunctionReturn(0);
}

/* A unit vector from v, refused when zero */
static PetscErrorCode Normalize(MPI_Comm comm, const char option[], const char spec[], const char what[], const PetscReal v[3], PetscReal u[3])
{
  const PetscReal len = PetscSqrtReal(Dot3(v, v));

  PetscFunctionBegin;
  PetscCheck(len > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option %s %s: the %s (%g, %g, %g) is zero", option, spec, what, (double)v[0], (double)v[1], (double)v[2]);
  for (PetscInt k = 0; k < 3; k++) u[k] = v[k] / len;
  PetscFunctionReturn(0);
}

typedef struct {
  PetscInt lo, hi, t, e; /* the edge's vertices (lo < hi), its triangle and the triangle's edge (0: 01, 1: 12, 2: 20) */
  PetscBool forward;     /* the triangle runs lo -> hi                                                               */
} Edge;

static int CompareEdge(const void *a, const void *b)
{
  const Edge *x = (const Edge *)a, *y = (const Edge *)b;

  if (x->lo != y->lo) return x->lo < y->lo ? -1 : 1;
  if (x->hi != y->hi) return x->hi < y->hi ? -1 : 1;
  return x->t < y->t ? -1 : (x->t > y->t ? 1 : 0);
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

/* The pseudo-normals of every triangle's face, edges and vertices; refuses degenerate, non-manifold and inconsistently oriented meshes */
static PetscErrorCode MeshPseudoNormals(MPI_Comm comm, const char option[], SSStarObstacle *ob)
{
  const PetscInt nt = ob->nt;
  PetscReal     *vn;
  Edge          *edges;

  PetscFunctionBegin;
  PetscCall(PetscCalloc1(21 * nt, &ob->pn));
  PetscCall(PetscMalloc1(6 * nt, &ob->box));
  PetscCall(PetscCalloc1(3 * ob->nv, &vn));
  PetscCall(PetscMalloc1(3 * nt, &edges));
  for (PetscInt t = 0; t < nt; t++) {
    const PetscInt *v = &ob->tri[3 * t];
    PetscReal       n[3], e[3][3], len;

    for (PetscInt j = 0; j < 3; j++)
      for (PetscInt k = 0; k < 3; k++) e[j][k] = ob->xv[3 * v[(j + 1) % 3] + k] - ob->xv[3 * v[j] + k]; /* e_j: from vertex j to j+1 */
    Cross3(e[0], e[1], n);
    len = PetscSqrtReal(Dot3(n, n));
    PetscCheck(len > 0, comm, PETSC_ERR_ARG_WRONG, "Option %s mesh:%s: triangle %" PetscInt_FMT " (0-based, file order) has zero area", option, ob->file, t);
    for (PetscInt k = 0; k < 3; k++) ob->pn[21 * t + k] = n[k] / len;
    /* the angle-weighted vertex normals */
    for (PetscInt j = 0; j < 3; j++) {
      const PetscReal *in = e[(j + 2) % 3], *out = e[j]; /* the edges into and out of vertex j */
      PetscReal        c  = -Dot3(in, out) / PetscSqrtReal(Dot3(in, in) * Dot3(out, out));
      const PetscReal  angle = PetscAcosReal(PetscMax(-1.0, PetscMin(1.0, c)));

      for (PetscInt k = 0; k < 3; k++) vn[3 * v[j] + k] += angle * ob->pn[21 * t + k];
    }
    for (PetscInt j = 0; j < 3; j++) {
      Edge *ed = &edges[3 * t + j];

      ed->lo      = PetscMin(v[j], v[(j + 1) % 3]);
      ed->hi      = PetscMax(v[j], v[(j + 1) % 3]);
      ed->t       = t;
      ed->e       = j;
      ed->forward = (PetscBool)(v[j] < v[(j + 1) % 3]);
    }
    for (PetscInt k = 0; k < 3; k++) {
      ob->box[6 * t + k]     = PetscMin(ob->xv[3 * v[0] + k], PetscMin(ob->xv[3 * v[1] + k], ob->xv[3 * v[2] + k]));
      ob->box[6 * t + 3 + k] = PetscMax(ob->xv[3 * v[0] + k], PetscMax(ob->xv[3 * v[1] + k], ob->xv[3 * v[2] + k]));
    }
  }
  qsort(edges, (size_t)(3 * nt), sizeof(Edge), CompareEdge);
  for (PetscInt i = 0; i < 3 * nt;) {
    PetscInt  j = i + 1;
    PetscReal m[3];

    while (j < 3 * nt && edges[j].lo == edges[i].lo && edges[j].hi == edges[i].hi) j++;
    PetscCheck(j - i <= 2, comm, PETSC_ERR_ARG_WRONG, "Option %s mesh:%s: the edge between nodes %" PetscInt_FMT " and %" PetscInt_FMT " (0-based, by node tag) is shared by %" PetscInt_FMT " triangles: not the surface of a body", option, ob->file, edges[i].lo, edges[i].hi, j - i);
    PetscCheck(j - i == 1 || edges[i].forward != edges[i + 1].forward, comm, PETSC_ERR_ARG_WRONG, "Option %s mesh:%s: triangles %" PetscInt_FMT " and %" PetscInt_FMT " (0-based) are oriented differently: orient every triangle counterclockwise seen from outside the obstacle", option, ob->file, edges[i].t, edges[i + 1].t);
    for (PetscInt k = 0; k < 3; k++) m[k] = 0;
    for (PetscInt l = i; l < j; l++)
      for (PetscInt k = 0; k < 3; k++) m[k] += ob->pn[21 * edges[l].t + k];
    for (PetscInt l = i; l < j; l++)
      for (PetscInt k = 0; k < 3; k++) ob->pn[21 * edges[l].t + 3 * (1 + edges[l].e) + k] = m[k];
    i = j;
  }
  for (PetscInt t = 0; t < nt; t++)
    for (PetscInt j = 0; j < 3; j++)
      for (PetscInt k = 0; k < 3; k++) ob->pn[21 * t + 3 * (4 + j) + k] = vn[3 * ob->tri[3 * t + j] + k];
  /* unit pseudo-normals (a zero one, on a folded surface, stays zero: such a node takes the direction to its closest point) */
  for (PetscInt i = 0; i < 7 * nt; i++) {
    const PetscReal len = PetscSqrtReal(Dot3(&ob->pn[3 * i], &ob->pn[3 * i]));

    if (len > 0)
      for (PetscInt k = 0; k < 3; k++) ob->pn[3 * i + k] /= len;
  }
  PetscCall(PetscFree(edges));
  PetscCall(PetscFree(vn));
  PetscFunctionReturn(0);
}

/* The triangles of a mesh obstacle: read on rank 0, broadcast */
static PetscErrorCode MeshObstacle(MPI_Comm comm, const char option[], SSStarObstacle *ob)
{
  PetscMPIInt rank;
  int         failure = 0;
  PetscInt    sizes[2] = {0, 0};

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) PetscCall(ReadTriangles(ob->file, &ob->nv, &ob->xv, &ob->nt, &ob->tri, &failure));
  PetscCallMPI(MPI_Bcast(&failure, 1, MPI_INT, 0, comm));
  PetscCheck(failure != 1, comm, PETSC_ERR_FILE_OPEN, "Option %s mesh:%s: cannot read the file", option, ob->file);
  PetscCheck(failure != 2, comm, PETSC_ERR_FILE_READ, "Option %s mesh:%s: gmsh cannot read the file as a mesh", option, ob->file);
  PetscCheck(failure != 3, comm, PETSC_ERR_ARG_WRONG, "Option %s mesh:%s: the file has no triangles (3-node triangles, gmsh element type 2): an obstacle is given by its surface", option, ob->file);
  sizes[0] = ob->nv;
  sizes[1] = ob->nt;
  PetscCallMPI(MPI_Bcast(sizes, 2, MPIU_INT, 0, comm));
  if (rank) {
    ob->nv = sizes[0];
    ob->nt = sizes[1];
    PetscCall(PetscMalloc1(3 * ob->nv, &ob->xv));
    PetscCall(PetscMalloc1(3 * ob->nt, &ob->tri));
  }
  PetscCallMPI(MPI_Bcast(ob->xv, (PetscMPIInt)(3 * ob->nv), MPIU_REAL, 0, comm));
  PetscCallMPI(MPI_Bcast(ob->tri, (PetscMPIInt)(3 * ob->nt), MPIU_INT, 0, comm));
  PetscCall(MeshPseudoNormals(comm, option, ob));
  PetscFunctionReturn(0);
}

/*
   SSStarObstacleSetFromString - the obstacle of an option's value: plane:px,py,pz,nx,ny,nz (or the six numbers
   alone), sphere:cx,cy,cz,R, cylinder:px,py,pz,ax,ay,az,R, mesh:FILE.msh; errors name the option
*/
PetscErrorCode SSStarObstacleSetFromString(MPI_Comm comm, const char option[], const char value[], SSStarObstacle *ob)
{
  PetscReal v[7];
  PetscBool match;

  PetscFunctionBegin;
  PetscCall(SSStarObstacleReset(ob));
  PetscCall(PetscStrncmp(value, "mesh:", 5, &match));
  if (match) {
    PetscCheck(value[5], comm, PETSC_ERR_ARG_WRONG, "Option %s mesh: needs a file name (mesh:FILE.msh)", option);
    ob->type = SSSTAR_OBSTACLE_MESH;
    PetscCall(PetscStrncpy(ob->file, value + 5, sizeof(ob->file)));
    PetscCall(MeshObstacle(comm, option, ob));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscStrncmp(value, "sphere:", 7, &match));
  if (match) {
    ob->type = SSSTAR_OBSTACLE_SPHERE;
    PetscCall(ParseNumbers(comm, option, value, value + 7, 4, "cx,cy,cz,R", v));
    PetscCheck(v[3] > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option %s %s: the radius %g must be positive", option, value, (double)v[3]);
    for (PetscInt k = 0; k < 3; k++) ob->point[k] = v[k];
    ob->radius = v[3];
    PetscFunctionReturn(0);
  }
  PetscCall(PetscStrncmp(value, "cylinder:", 9, &match));
  if (match) {
    ob->type = SSSTAR_OBSTACLE_CYLINDER;
    PetscCall(ParseNumbers(comm, option, value, value + 9, 7, "px,py,pz,ax,ay,az,R", v));
    PetscCall(Normalize(comm, option, value, "axis", &v[3], ob->dir));
    PetscCheck(v[6] > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option %s %s: the radius %g must be positive", option, value, (double)v[6]);
    for (PetscInt k = 0; k < 3; k++) ob->point[k] = v[k];
    ob->radius = v[6];
    PetscFunctionReturn(0);
  }
  PetscCall(PetscStrncmp(value, "plane:", 6, &match));
  ob->type = SSSTAR_OBSTACLE_PLANE;
  PetscCheck(match || !value[0] || (value[0] >= '0' && value[0] <= '9') || value[0] == '-' || value[0] == '+' || value[0] == '.', comm, PETSC_ERR_ARG_WRONG, "Option %s %s: unknown obstacle; give plane:px,py,pz,nx,ny,nz (or the six numbers), sphere:cx,cy,cz,R, cylinder:px,py,pz,ax,ay,az,R or mesh:FILE.msh", option, value);
  PetscCall(ParseNumbers(comm, option, value, match ? value + 6 : value, 6, "px,py,pz,nx,ny,nz", v));
  PetscCall(Normalize(comm, option, value, "normal", &v[3], ob->dir));
  for (PetscInt k = 0; k < 3; k++) ob->point[k] = v[k];
  PetscFunctionReturn(0);
}

/* SSStarObstacleReset - frees a mesh obstacle's triangles; the obstacle becomes the default, the plane z = 0 with normal +z */
PetscErrorCode SSStarObstacleReset(SSStarObstacle *ob)
{
  PetscFunctionBegin;
  PetscCall(PetscFree(ob->xv));
  PetscCall(PetscFree(ob->tri));
  PetscCall(PetscFree(ob->pn));
  PetscCall(PetscFree(ob->box));
  PetscCall(PetscMemzero(ob, sizeof(*ob)));
  ob->type   = SSSTAR_OBSTACLE_PLANE;
  ob->dir[2] = 1.0;
  PetscFunctionReturn(0);
}

/*
   The closest point q of triangle abc to p (Ericson, Real-Time Collision Detection 5.1.5) and the feature it lies on:
   0 the face, 1 edge ab, 2 edge bc, 3 edge ca, 4 vertex a, 5 vertex b, 6 vertex c
*/
static void ClosestOnTriangle(const PetscReal p[3], const PetscReal a[3], const PetscReal b[3], const PetscReal c[3], PetscReal q[3], PetscInt *feature)
{
  PetscReal ab[3], ac[3], ap[3], bp[3], cp[3], d1, d2, d3, d4, d5, d6, va, vb, vc, v, w;

  for (PetscInt k = 0; k < 3; k++) {
    ab[k] = b[k] - a[k];
    ac[k] = c[k] - a[k];
    ap[k] = p[k] - a[k];
    bp[k] = p[k] - b[k];
    cp[k] = p[k] - c[k];
  }
  d1 = Dot3(ab, ap);
  d2 = Dot3(ac, ap);
  if (d1 <= 0 && d2 <= 0) {
    for (PetscInt k = 0; k < 3; k++) q[k] = a[k];
    *feature = 4;
    return;
  }
  d3 = Dot3(ab, bp);
  d4 = Dot3(ac, bp);
  if (d3 >= 0 && d4 <= d3) {
    for (PetscInt k = 0; k < 3; k++) q[k] = b[k];
    *feature = 5;
    return;
  }
  vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    v = d1 / (d1 - d3);
    for (PetscInt k = 0; k < 3; k++) q[k] = a[k] + v * ab[k];
    *feature = 1;
    return;
  }
  d5 = Dot3(ab, cp);
  d6 = Dot3(ac, cp);
  if (d6 >= 0 && d5 <= d6) {
    for (PetscInt k = 0; k < 3; k++) q[k] = c[k];
    *feature = 6;
    return;
  }
  vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    w = d2 / (d2 - d6);
    for (PetscInt k = 0; k < 3; k++) q[k] = a[k] + w * ac[k];
    *feature = 3;
    return;
  }
  va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
    w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    for (PetscInt k = 0; k < 3; k++) q[k] = b[k] + w * (c[k] - b[k]);
    *feature = 2;
    return;
  }
  v = vb / (va + vb + vc);
  w = vc / (va + vb + vc);
  for (PetscInt k = 0; k < 3; k++) q[k] = a[k] + v * ab[k] + w * ac[k];
  *feature = 0;
}

/* The squared distance from p to a box (lo[3], hi[3]) */
static PetscReal BoxDistance2(const PetscReal p[3], const PetscReal box[6])
{
  PetscReal d2 = 0;

  for (PetscInt k = 0; k < 3; k++) {
    const PetscReal d = p[k] < box[k] ? box[k] - p[k] : (p[k] > box[3 + k] ? p[k] - box[3 + k] : 0);

    d2 += d * d;
  }
  return d2;
}

/*
   SSStarObstacleGap - the signed distance of x to the obstacle (positive outside it) and the unit normal of its frame
   (out of the obstacle, into the body); tol: the distance within which x lies on the obstacle's surface
*/
PetscErrorCode SSStarObstacleGap(const SSStarObstacle *ob, const PetscReal x[3], PetscReal tol, PetscReal *gap, PetscReal n[3])
{
  PetscReal d[3], len;

  PetscFunctionBegin;
  for (PetscInt k = 0; k < 3; k++) d[k] = x[k] - ob->point[k];
  switch (ob->type) {
  case SSSTAR_OBSTACLE_PLANE:
    *gap = Dot3(d, ob->dir);
    for (PetscInt k = 0; k < 3; k++) n[k] = ob->dir[k];
    break;
  case SSSTAR_OBSTACLE_CYLINDER:
  case SSSTAR_OBSTACLE_SPHERE:
    if (ob->type == SSSTAR_OBSTACLE_CYLINDER) {
      const PetscReal along = Dot3(d, ob->dir);

      for (PetscInt k = 0; k < 3; k++) d[k] -= along * ob->dir[k];
    }
    len  = PetscSqrtReal(Dot3(d, d));
    *gap = len - ob->radius;
    for (PetscInt k = 0; k < 3; k++) n[k] = len > 0 ? d[k] / len : (k == 2 ? 1.0 : 0.0); /* on the centre or the axis: deep inside, refused */
    break;
  case SSSTAR_OBSTACLE_MESH: {
    PetscReal best = PETSC_MAX_REAL, q[3], qbest[3] = {0, 0, 0}, s;
    PetscInt  tbest = -1, fbest = 0;

    for (PetscInt t = 0; t < ob->nt; t++) {
      const PetscInt *v = &ob->tri[3 * t];
      PetscInt        feature;
      PetscReal       d2;

      if (BoxDistance2(x, &ob->box[6 * t]) >= best) continue;
      ClosestOnTriangle(x, &ob->xv[3 * v[0]], &ob->xv[3 * v[1]], &ob->xv[3 * v[2]], q, &feature);
      d2 = PetscSqr(x[0] - q[0]) + PetscSqr(x[1] - q[1]) + PetscSqr(x[2] - q[2]);
      if (d2 < best) {
        best  = d2;
        tbest = t;
        fbest = feature;
        for (PetscInt k = 0; k < 3; k++) qbest[k] = q[k];
      }
    }
    {
      const PetscReal *m = &ob->pn[21 * tbest + 3 * fbest];

      for (PetscInt k = 0; k < 3; k++) d[k] = x[k] - qbest[k];
      len  = PetscSqrtReal(best);
      s    = Dot3(d, m) >= 0 ? 1.0 : -1.0;
      *gap = s * len;
      if (len > tol)
        for (PetscInt k = 0; k < 3; k++) n[k] = s * d[k] / len;
      else
        for (PetscInt k = 0; k < 3; k++) n[k] = m[k];
    }
  } break;
  }
  PetscFunctionReturn(0);
}

/* SSStarObstacleDescribe - the obstacle in words, for the scene's view */
PetscErrorCode SSStarObstacleDescribe(const SSStarObstacle *ob, char text[], size_t len)
{
  const PetscReal *p = ob->point, *a = ob->dir;

  PetscFunctionBegin;
  switch (ob->type) {
  case SSSTAR_OBSTACLE_PLANE:
    PetscCall(PetscSNPrintf(text, len, "plane through (%g, %g, %g) with normal (%g, %g, %g)", (double)p[0], (double)p[1], (double)p[2], (double)a[0], (double)a[1], (double)a[2]));
    break;
  case SSSTAR_OBSTACLE_SPHERE:
    PetscCall(PetscSNPrintf(text, len, "rigid ball of radius %g centred at (%g, %g, %g)", (double)ob->radius, (double)p[0], (double)p[1], (double)p[2]));
    break;
  case SSSTAR_OBSTACLE_CYLINDER:
    PetscCall(PetscSNPrintf(text, len, "rigid cylinder of radius %g, axis through (%g, %g, %g) along (%g, %g, %g)", (double)ob->radius, (double)p[0], (double)p[1], (double)p[2], (double)a[0], (double)a[1], (double)a[2]));
    break;
  case SSSTAR_OBSTACLE_MESH:
    PetscCall(PetscSNPrintf(text, len, "rigid body of mesh %s (%" PetscInt_FMT " triangles)", ob->file, ob->nt));
    break;
  }
  PetscFunctionReturn(0);
}

/* SSStarObstacleInsideHint - what to check when a node starts inside the obstacle */
const char *SSStarObstacleInsideHint(const SSStarObstacle *ob)
{
  switch (ob->type) {
  case SSSTAR_OBSTACLE_PLANE:
    return "does the normal point into the body?";
  case SSSTAR_OBSTACLE_SPHERE:
    return "the body touches the ball from outside: is the centre or the radius wrong?";
  case SSSTAR_OBSTACLE_CYLINDER:
    return "the body touches the cylinder from outside: is the axis or the radius wrong?";
  default:
    return "are the obstacle's triangles oriented counterclockwise seen from outside it, their normals towards the body?";
  }
}
