/*
   One triangle: its closest point to a point, its normal, its bounding box (src/geometry, include/ssstargeometry.h).
   Rigid mesh obstacles (src/scene/contact/obstacles/mesh.c) and contact pairs (src/scene/contact/pairs/) find their
   contact points with it.
*/
#include <ssstargeometry.h>

/*@C
   SSStarClosestPointOnTriangle - the point of the triangle a, b, c closest to p, its barycentric coordinates and the
   feature (face, edge or vertex) it lies on

   Not Collective

   Input Parameters:
+  p - the point
.  a - the first vertex
.  b - the second vertex
-  c - the third vertex

   Output Parameters:
+  q       - the closest point, or pass NULL
.  w       - its barycentric coordinates (q = w0 a + w1 b + w2 c, w >= 0, sum 1), or pass NULL
-  feature - the face, the edge or the vertex q lies on, or pass NULL

   Notes:
   Ericson, Real-Time Collision Detection, section 5.1.5: the Voronoi regions of the vertices, the edges and the face,
   tested in that order. A degenerate triangle (two vertices equal, or all three on a line) is the segment or the point
   it spans: an edge of zero length is never the answer.

   Level: developer

.seealso: `SSStarTriangleNormal()`, `SSStarSurfacePseudoNormals()`
@*/
void SSStarClosestPointOnTriangle(const PetscReal p[3], const PetscReal a[3], const PetscReal b[3], const PetscReal c[3], PetscReal q[3], PetscReal w[3], SSStarTriangleFeature *feature)
{
  PetscReal             ab[3], ac[3], ap[3], bp[3], cp[3], d1, d2, d3, d4, d5, d6, va, vb, vc, v = 0, t = 0, x[3];
  SSStarTriangleFeature f;

  for (PetscInt k = 0; k < 3; k++) {
    ab[k] = b[k] - a[k];
    ac[k] = c[k] - a[k];
    ap[k] = p[k] - a[k];
    bp[k] = p[k] - b[k];
    cp[k] = p[k] - c[k];
  }
  d1 = SSStarDot3(ab, ap);
  d2 = SSStarDot3(ac, ap);
  d3 = SSStarDot3(ab, bp);
  d4 = SSStarDot3(ac, bp);
  d5 = SSStarDot3(ab, cp);
  d6 = SSStarDot3(ac, cp);
  vc = d1 * d4 - d3 * d2;
  vb = d5 * d2 - d1 * d6;
  va = d3 * d6 - d5 * d4;
  /* v, t: q = a + v ab + t ac for the face and the edges from a; q = b + t (c - b) for the edge bc */
  if (d1 <= 0 && d2 <= 0) f = SSSTAR_TRIANGLE_VERTEX_A;
  else if (d3 >= 0 && d4 <= d3) f = SSSTAR_TRIANGLE_VERTEX_B;
  else if (vc <= 0 && d1 >= 0 && d3 <= 0 && d1 - d3 > 0) { /* d1 - d3 = |ab|^2 */
    f = SSSTAR_TRIANGLE_EDGE_AB;
    v = d1 / (d1 - d3);
  } else if (d6 >= 0 && d5 <= d6) f = SSSTAR_TRIANGLE_VERTEX_C;
  else if (vb <= 0 && d2 >= 0 && d6 <= 0 && d2 - d6 > 0) { /* d2 - d6 = |ac|^2 */
    f = SSSTAR_TRIANGLE_EDGE_CA;
    t = d2 / (d2 - d6);
  } else if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0 && (d4 - d3) + (d5 - d6) > 0) { /* the sum is |bc|^2 */
    f = SSSTAR_TRIANGLE_EDGE_BC;
    t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
  } else {
    f = SSSTAR_TRIANGLE_FACE;
    v = vb / (va + vb + vc);
    t = vc / (va + vb + vc);
  }
  switch (f) {
  case SSSTAR_TRIANGLE_VERTEX_A:
    for (PetscInt k = 0; k < 3; k++) x[k] = a[k];
    break;
  case SSSTAR_TRIANGLE_VERTEX_B:
    for (PetscInt k = 0; k < 3; k++) x[k] = b[k];
    break;
  case SSSTAR_TRIANGLE_VERTEX_C:
    for (PetscInt k = 0; k < 3; k++) x[k] = c[k];
    break;
  case SSSTAR_TRIANGLE_EDGE_BC:
    for (PetscInt k = 0; k < 3; k++) x[k] = b[k] + t * (c[k] - b[k]);
    break;
  default:
    for (PetscInt k = 0; k < 3; k++) x[k] = a[k] + v * ab[k] + t * ac[k];
  }
  if (q)
    for (PetscInt k = 0; k < 3; k++) q[k] = x[k];
  if (w) {
    switch (f) {
    case SSSTAR_TRIANGLE_VERTEX_A:
      w[0] = 1, w[1] = 0, w[2] = 0;
      break;
    case SSSTAR_TRIANGLE_VERTEX_B:
      w[0] = 0, w[1] = 1, w[2] = 0;
      break;
    case SSSTAR_TRIANGLE_VERTEX_C:
      w[0] = 0, w[1] = 0, w[2] = 1;
      break;
    case SSSTAR_TRIANGLE_EDGE_BC:
      w[0] = 0, w[1] = 1 - t, w[2] = t;
      break;
    default:
      w[1] = v, w[2] = t, w[0] = 1 - v - t;
    }
  }
  if (feature) *feature = f;
}

/*@C
   SSStarTriangleNormal - the unit normal (b - a) x (c - a) / |(b - a) x (c - a)| of the triangle a, b, c and its area

   Not Collective

   Input Parameters:
+  a - the first vertex
.  b - the second vertex
-  c - the third vertex

   Output Parameter:
.  n - the unit normal (counterclockwise seen from where it points); zero for a triangle of zero area

   Returns:
   the area

   Level: developer

.seealso: `SSStarClosestPointOnTriangle()`, `SSStarSurfacePseudoNormals()`
@*/
PetscReal SSStarTriangleNormal(const PetscReal a[3], const PetscReal b[3], const PetscReal c[3], PetscReal n[3])
{
  PetscReal e1[3], e2[3], len;

  for (PetscInt k = 0; k < 3; k++) {
    e1[k] = b[k] - a[k];
    e2[k] = c[k] - a[k];
  }
  SSStarCross3(e1, e2, n);
  len = PetscSqrtReal(SSStarDot3(n, n));
  for (PetscInt k = 0; k < 3; k++) n[k] = len > 0 ? n[k] / len : 0;
  return len / 2;
}

/*@C
   SSStarTriangleBox - the bounding box of the triangle a, b, c

   Not Collective

   Input Parameters:
+  a - the first vertex
.  b - the second vertex
-  c - the third vertex

   Output Parameter:
.  box - its lower corner (3) and upper corner (3)

   Level: developer

.seealso: `SSStarBoxDistance2()`
@*/
void SSStarTriangleBox(const PetscReal a[3], const PetscReal b[3], const PetscReal c[3], PetscReal box[6])
{
  for (PetscInt k = 0; k < 3; k++) {
    box[k]     = PetscMin(a[k], PetscMin(b[k], c[k]));
    box[3 + k] = PetscMax(a[k], PetscMax(b[k], c[k]));
  }
}

/*@C
   SSStarBoxDistance2 - the squared distance from a point to a box (0 inside it): a lower bound of the squared
   distance to anything in the box

   Not Collective

   Input Parameters:
+  p   - the point
-  box - the lower corner (3) and upper corner (3)

   Returns:
   the squared distance

   Level: developer

.seealso: `SSStarTriangleBox()`
@*/
PetscReal SSStarBoxDistance2(const PetscReal p[3], const PetscReal box[6])
{
  PetscReal d2 = 0;

  for (PetscInt k = 0; k < 3; k++) {
    const PetscReal d = p[k] < box[k] ? box[k] - p[k] : (p[k] > box[3 + k] ? p[k] - box[3 + k] : 0);

    d2 += d * d;
  }
  return d2;
}
