/*
   A triangulated surface that bounds a body: the pseudo-normals of its faces, edges and vertices (Baerentzen and Aanaes
   2005), which give the side of the surface a point is on from the feature its closest point lies on, and the checks
   that make the sides well defined (src/geometry, include/ssstargeometry.h).
*/
#include <ssstargeometry.h>

typedef struct {
  PetscInt  lo, hi, t, e; /* the edge's vertices (lo < hi), its triangle and the triangle's edge (0: 01, 1: 12, 2: 20) */
  PetscBool forward;      /* the triangle runs lo -> hi                                                               */
} Edge;

static int CompareEdge(const void *a, const void *b)
{
  const Edge *x = (const Edge *)a, *y = (const Edge *)b;

  if (x->lo != y->lo) return x->lo < y->lo ? -1 : 1;
  if (x->hi != y->hi) return x->hi < y->hi ? -1 : 1;
  return x->t < y->t ? -1 : (x->t > y->t ? 1 : 0);
}

/*@C
   SSStarSurfacePseudoNormals - the unit pseudo-normals of a triangulated surface: of each face, of each edge (the sum
   of its two faces' normals) and of each vertex (the angle-weighted sum of its faces' normals), and whether the
   surface can bound a body

   Not Collective

   Input Parameters:
+  nv  - the number of vertices
.  xv  - their coordinates, 3 per vertex
.  nt  - the number of triangles
-  tri - their vertices, 3 per triangle, counterclockwise seen from the side the normals point to

   Output Parameters:
+  pn    - 21 per triangle (room given by the caller): the face's normal, then its edges' (vertices 0-1, 1-2, 2-0), then
           its vertices' (0, 1, 2); a zero sum (a folded surface) stays zero
-  check - SSSTAR_SURFACE_OK, or the first defect found: a triangle of zero area, an edge of more than two triangles,
           two neighbours that run their common edge the same way (oriented differently); pn is then incomplete

   Notes:
   With such pseudo-normals m, a point x whose closest point on the surface is q lies on the side (x - q) . m points to,
   on every feature of a closed oriented surface (Baerentzen and Aanaes, IEEE TVCG 11(3), 2005).

   Level: developer

.seealso: `SSStarClosestPointOnTriangle()`, `SSStarTriangleNormal()`
@*/
PetscErrorCode SSStarSurfacePseudoNormals(PetscInt nv, const PetscReal xv[], PetscInt nt, const PetscInt tri[], PetscReal pn[], SSStarSurfaceCheck *check)
{
  PetscReal *vn;
  Edge      *edges;

  PetscFunctionBegin;
  PetscCall(PetscMemzero(check, sizeof(*check)));
  PetscCall(PetscCalloc1(3 * nv + 1, &vn));
  PetscCall(PetscMalloc1(3 * nt + 1, &edges));
  for (PetscInt t = 0; t < nt && check->defect == SSSTAR_SURFACE_OK; t++) {
    const PetscInt *v = &tri[3 * t];
    PetscReal       n[3], e[3][3], len;

    for (PetscInt j = 0; j < 3; j++)
      for (PetscInt k = 0; k < 3; k++) e[j][k] = xv[3 * v[(j + 1) % 3] + k] - xv[3 * v[j] + k]; /* e_j: from vertex j to j+1 */
    SSStarCross3(e[0], e[1], n);
    len = PetscSqrtReal(SSStarDot3(n, n));
    if (!(len > 0)) {
      check->defect      = SSSTAR_SURFACE_ZERO_AREA;
      check->triangle[0] = t;
      break;
    }
    for (PetscInt k = 0; k < 3; k++) pn[21 * t + k] = n[k] / len;
    for (PetscInt j = 0; j < 3; j++) { /* the angle-weighted vertex normals */
      const PetscReal *in = e[(j + 2) % 3], *out = e[j]; /* the edges into and out of vertex j */
      const PetscReal  c     = -SSStarDot3(in, out) / PetscSqrtReal(SSStarDot3(in, in) * SSStarDot3(out, out));
      const PetscReal  angle = PetscAcosReal(PetscMax(-1.0, PetscMin(1.0, c)));

      for (PetscInt k = 0; k < 3; k++) vn[3 * v[j] + k] += angle * pn[21 * t + k];
    }
    for (PetscInt j = 0; j < 3; j++) {
      Edge *ed = &edges[3 * t + j];

      ed->lo      = PetscMin(v[j], v[(j + 1) % 3]);
      ed->hi      = PetscMax(v[j], v[(j + 1) % 3]);
      ed->t       = t;
      ed->e       = j;
      ed->forward = (PetscBool)(v[j] < v[(j + 1) % 3]);
    }
  }
  if (check->defect == SSSTAR_SURFACE_OK) qsort(edges, (size_t)(3 * nt), sizeof(Edge), CompareEdge);
  for (PetscInt i = 0; i < 3 * nt && check->defect == SSSTAR_SURFACE_OK;) {
    PetscInt  j = i + 1;
    PetscReal m[3] = {0, 0, 0};

    while (j < 3 * nt && edges[j].lo == edges[i].lo && edges[j].hi == edges[i].hi) j++;
    if (j - i > 2) {
      check->defect    = SSSTAR_SURFACE_NONMANIFOLD;
      check->vertex[0] = edges[i].lo;
      check->vertex[1] = edges[i].hi;
      check->count     = j - i;
    } else if (j - i == 2 && edges[i].forward == edges[i + 1].forward) {
      check->defect      = SSSTAR_SURFACE_MISORIENTED;
      check->triangle[0] = edges[i].t;
      check->triangle[1] = edges[i + 1].t;
    } else {
      for (PetscInt l = i; l < j; l++)
        for (PetscInt k = 0; k < 3; k++) m[k] += pn[21 * edges[l].t + k];
      for (PetscInt l = i; l < j; l++)
        for (PetscInt k = 0; k < 3; k++) pn[21 * edges[l].t + 3 * (1 + edges[l].e) + k] = m[k];
    }
    i = j;
  }
  if (check->defect == SSSTAR_SURFACE_OK) {
    for (PetscInt t = 0; t < nt; t++)
      for (PetscInt j = 0; j < 3; j++)
        for (PetscInt k = 0; k < 3; k++) pn[21 * t + 3 * (4 + j) + k] = vn[3 * tri[3 * t + j] + k];
    for (PetscInt i = 0; i < 7 * nt; i++) {
      const PetscReal len = PetscSqrtReal(SSStarDot3(&pn[3 * i], &pn[3 * i]));

      if (len > 0)
        for (PetscInt k = 0; k < 3; k++) pn[3 * i + k] /= len;
    }
  }
  PetscCall(PetscFree(edges));
  PetscCall(PetscFree(vn));
  PetscFunctionReturn(0);
}
