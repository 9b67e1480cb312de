static const char help[] = "The geometry module (src/geometry) against hand-computed cases.\n";

/* Requirement: the closest point of a triangle, its barycentric coordinates and feature are the hand-computed ones for
   a point over the face, beyond each edge and each vertex and in the plane, and the right point (no NaN) for degenerate
   triangles (two vertices equal, three on a line, a point); on random triangles it is never farther than the closest
   point found by brute force (the face's projection and the three edges). A triangle's normal and area, its bounding
   box and a point's distance to a box are the hand-computed ones. The pseudo-normals of a tetrahedron are its faces'
   outward normals, the sums of two for its edges, the angle-weighted sums for its vertices; a triangle of zero area,
   an edge of three triangles and two neighbours oriented differently are each named. Tolerance 1e-14 (O(1) data). */
#include <ssstargeometry.h>

static int failures = 0;

static void Expect(PetscBool ok, const char what[], const char name[])
{
  if (!ok) {
    failures++;
    PetscPrintf(PETSC_COMM_SELF, "FAIL %s: %s\n", name, what);
  }
}

static PetscBool Close(PetscInt n, const PetscReal a[], const PetscReal b[], PetscReal tol)
{
  for (PetscInt i = 0; i < n; i++)
    if (!(PetscAbsReal(a[i] - b[i]) <= tol)) return PETSC_FALSE; /* NaN fails */
  return PETSC_TRUE;
}

typedef struct {
  const char           *name;
  PetscReal             p[3], a[3], b[3], c[3];
  PetscReal             q[3], w[3]; /* expected */
  SSStarTriangleFeature feature;
  PetscBool             degenerate; /* w and the feature are not unique */
} Case;

static void CheckCase(const Case *k)
{
  PetscReal             q[3], w[3], qw[3], sum;
  SSStarTriangleFeature f;

  SSStarClosestPointOnTriangle(k->p, k->a, k->b, k->c, q, w, &f);
  Expect(Close(3, q, k->q, 1e-14), "closest point", k->name);
  for (PetscInt j = 0; j < 3; j++) qw[j] = w[0] * k->a[j] + w[1] * k->b[j] + w[2] * k->c[j];
  sum = w[0] + w[1] + w[2];
  Expect((PetscBool)(Close(3, qw, q, 1e-14) && PetscAbsReal(sum - 1) <= 1e-14 && w[0] >= 0 && w[1] >= 0 && w[2] >= 0), "barycentric coordinates", k->name);
  if (k->degenerate) return;
  Expect(Close(3, w, k->w, 1e-14), "barycentric coordinates, hand-computed", k->name);
  Expect((PetscBool)(f == k->feature), "feature", k->name);
}

/* The closest point of segment a b to p */
static void ClosestOnSegment(const PetscReal p[3], const PetscReal a[3], const PetscReal b[3], PetscReal q[3])
{
  PetscReal ab[3], ap[3], t = 0, len2;

  for (PetscInt k = 0; k < 3; k++) {
    ab[k] = b[k] - a[k];
    ap[k] = p[k] - a[k];
  }
  len2 = SSStarDot3(ab, ab);
  if (len2 > 0) t = PetscMax(0, PetscMin(1, SSStarDot3(ap, ab) / len2));
  for (PetscInt k = 0; k < 3; k++) q[k] = a[k] + t * ab[k];
}

static PetscReal Distance(const PetscReal x[3], const PetscReal y[3])
{
  return PetscSqrtReal(PetscSqr(x[0] - y[0]) + PetscSqr(x[1] - y[1]) + PetscSqr(x[2] - y[2]));
}

/* Random triangles and points: the closest point is on the triangle and no farther than brute force finds */
static void CheckRandom(PetscRandom rnd)
{
  for (PetscInt trial = 0; trial < 2000; trial++) {
    PetscReal x[12], q[3], w[3], n[3], best, s[3], proj[3], d, lam[3];

    for (PetscInt k = 0; k < 12; k++) PetscRandomGetValueReal(rnd, &x[k]);
    SSStarClosestPointOnTriangle(x, &x[3], &x[6], &x[9], q, w, NULL);
    /* brute force: the edges, and the projection onto the plane when it falls inside */
    ClosestOnSegment(x, &x[3], &x[6], s);
    best = Distance(x, s);
    ClosestOnSegment(x, &x[6], &x[9], s);
    best = PetscMin(best, Distance(x, s));
    ClosestOnSegment(x, &x[9], &x[3], s);
    best = PetscMin(best, Distance(x, s));
    (void)SSStarTriangleNormal(&x[3], &x[6], &x[9], n);
    d = (x[0] - x[3]) * n[0] + (x[1] - x[4]) * n[1] + (x[2] - x[5]) * n[2];
    for (PetscInt k = 0; k < 3; k++) proj[k] = x[k] - d * n[k];
    { /* barycentric coordinates of the projection by areas */
      PetscReal t0[3], t1[3], t2[3], full = SSStarTriangleNormal(&x[3], &x[6], &x[9], t0);

      lam[0] = SSStarTriangleNormal(proj, &x[6], &x[9], t0);
      lam[1] = SSStarTriangleNormal(&x[3], proj, &x[9], t1);
      lam[2] = SSStarTriangleNormal(&x[3], &x[6], proj, t2);
      if (PetscAbsReal(lam[0] + lam[1] + lam[2] - full) <= 1e-12 * full) best = PetscMin(best, PetscAbsReal(d));
    }
    if (!(Distance(x, q) <= best + 1e-12) || !(w[0] >= 0 && w[1] >= 0 && w[2] >= 0 && PetscAbsReal(w[0] + w[1] + w[2] - 1) <= 1e-14)) {
      Expect(PETSC_FALSE, "farther than brute force, or outside the triangle", "random triangle");
      break;
    }
  }
}

/* A tetrahedron with outward faces; a defect: flip (misoriented), fin (a third triangle on an edge), flat (zero area) */
static void CheckSurface(const char defect[])
{
  PetscReal          xv[15] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1}, pn[21 * 5];
  PetscInt           tri[15] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3, 0, 1, 4}, nt = 4;
  SSStarSurfaceCheck check;
  const PetscReal    r2 = PetscSqrtReal(2.0), r3 = PetscSqrtReal(3.0);

  if (!strcmp(defect, "flip")) {
    tri[1] = 1;
    tri[2] = 2;
  }
  if (!strcmp(defect, "fin")) nt = 5;
  if (!strcmp(defect, "flat")) {
    tri[3 * 3 + 0] = 1;
    tri[3 * 3 + 1] = 1;
  }
  PetscCallAbort(PETSC_COMM_SELF, SSStarSurfacePseudoNormals(5, xv, nt, tri, pn, &check));
  if (!strcmp(defect, "flip")) Expect((PetscBool)(check.defect == SSSTAR_SURFACE_MISORIENTED && check.triangle[0] == 0 && check.triangle[1] == 1), "a flipped face is named with its neighbour (triangles 0 and 1)", "surface");
  else if (!strcmp(defect, "fin")) Expect((PetscBool)(check.defect == SSSTAR_SURFACE_NONMANIFOLD && check.vertex[0] == 0 && check.vertex[1] == 1 && check.count == 3), "the edge 0-1 of three triangles", "surface");
  else if (!strcmp(defect, "flat")) Expect((PetscBool)(check.defect == SSSTAR_SURFACE_ZERO_AREA && check.triangle[0] == 3), "triangle 3 of zero area", "surface");
  else {
    const PetscReal face[4][3] = {{0, 0, -1}, {0, -1, 0}, {-1, 0, 0}, {1 / r3, 1 / r3, 1 / r3}};
    const PetscReal edge01[3] = {0, -1 / r2, -1 / r2}, vertex0[3] = {-1 / r3, -1 / r3, -1 / r3};

    Expect((PetscBool)(check.defect == SSSTAR_SURFACE_OK), "a closed oriented surface", "surface");
    for (PetscInt t = 0; t < 4; t++) Expect(Close(3, &pn[21 * t], face[t], 1e-14), "face normal", "surface");
    Expect(Close(3, &pn[21 * 0 + 3 * 3], edge01, 1e-14), "edge 0-1 (edge 2-0 of triangle 0): the mean of two faces", "surface"); /* triangle 0 = (0 2 1): edge 1-0 is its third */
    Expect(Close(3, &pn[21 * 1 + 3 * 1], edge01, 1e-14), "edge 0-1 of triangle 1", "surface");
    Expect(Close(3, &pn[21 * 0 + 3 * 4], vertex0, 1e-14), "vertex 0: three right angles", "surface");
  }
}

int main(int argc, char **argv)
{
  const Case cases[] = {
    {"over the face", {0.5, 0.5, 3}, {0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0.5, 0.5, 0}, {0.5, 0.25, 0.25}, SSSTAR_TRIANGLE_FACE, PETSC_FALSE},
    {"in the face", {0.5, 0.5, 0}, {0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0.5, 0.5, 0}, {0.5, 0.25, 0.25}, SSSTAR_TRIANGLE_FACE, PETSC_FALSE},
    {"beyond edge ab", {1, -1, 1}, {0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {1, 0, 0}, {0.5, 0.5, 0}, SSSTAR_TRIANGLE_EDGE_AB, PETSC_FALSE},
    {"beyond edge bc", {2, 2, -1}, {0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {1, 1, 0}, {0, 0.5, 0.5}, SSSTAR_TRIANGLE_EDGE_BC, PETSC_FALSE},
    {"beyond edge ca", {-1, 1, 0.5}, {0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 1, 0}, {0.5, 0, 0.5}, SSSTAR_TRIANGLE_EDGE_CA, PETSC_FALSE},
    {"beyond vertex a", {-1, -1, 0}, {0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 0}, {1, 0, 0}, SSSTAR_TRIANGLE_VERTEX_A, PETSC_FALSE},
    {"beyond vertex b", {3, -1, 0}, {0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {2, 0, 0}, {0, 1, 0}, SSSTAR_TRIANGLE_VERTEX_B, PETSC_FALSE},
    {"beyond vertex c", {-1, 3, 2}, {0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 2, 0}, {0, 0, 1}, SSSTAR_TRIANGLE_VERTEX_C, PETSC_FALSE},
    {"three on a line", {1.5, 1, 0}, {0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {1.5, 0, 0}, {0, 0, 0}, SSSTAR_TRIANGLE_FACE, PETSC_TRUE},
    {"a = b", {1, 1, 0}, {0, 0, 0}, {0, 0, 0}, {2, 0, 0}, {1, 0, 0}, {0, 0, 0}, SSSTAR_TRIANGLE_FACE, PETSC_TRUE},
    {"b = c", {1, 1, 0}, {0, 0, 0}, {2, 0, 0}, {2, 0, 0}, {1, 0, 0}, {0, 0, 0}, SSSTAR_TRIANGLE_FACE, PETSC_TRUE},
    {"c = a", {1, -1, 0}, {0, 0, 0}, {2, 0, 0}, {0, 0, 0}, {1, 0, 0}, {0, 0, 0}, SSSTAR_TRIANGLE_FACE, PETSC_TRUE},
    {"a point", {0, 0, 0}, {1, 1, 1}, {1, 1, 1}, {1, 1, 1}, {1, 1, 1}, {0, 0, 0}, SSSTAR_TRIANGLE_FACE, PETSC_TRUE},
  };
  PetscRandom rnd;
  PetscReal   n[3], area, box[6];
  const PetscReal a[3] = {0, 0, 0}, b[3] = {2, 0, 0}, c[3] = {0, 2, 0}, up[3] = {0, 0, 1}, far[3] = {3, 0.5, -1}, in[3] = {1, 0.5, 0}, lohi[6] = {0, 0, 0, 2, 2, 0};

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  for (size_t k = 0; k < PETSC_STATIC_ARRAY_LENGTH(cases); k++) CheckCase(&cases[k]);
  PetscCall(PetscRandomCreate(PETSC_COMM_SELF, &rnd));
  PetscCall(PetscRandomSetInterval(rnd, -1, 1));
  CheckRandom(rnd);
  PetscCall(PetscRandomDestroy(&rnd));
  area = SSStarTriangleNormal(a, b, c, n);
  Expect((PetscBool)(Close(3, n, up, 1e-14) && PetscAbsReal(area - 2) <= 1e-14), "normal (0, 0, 1) and area 2", "triangle normal");
  area = SSStarTriangleNormal(a, c, b, n);
  Expect((PetscBool)(n[2] == -1 && area == 2), "the other orientation: normal (0, 0, -1)", "triangle normal");
  SSStarTriangleBox(c, a, b, box);
  Expect(Close(6, box, lohi, 0), "bounding box", "triangle box");
  Expect((PetscBool)(PetscAbsReal(SSStarBoxDistance2(far, box) - 2) <= 1e-14), "squared distance 1 + 1 to the box", "box distance");
  Expect((PetscBool)(SSStarBoxDistance2(in, box) == 0), "inside the box: 0", "box distance");
  CheckSurface("none");
  CheckSurface("flip");
  CheckSurface("fin");
  CheckSurface("flat");
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "%s\n", failures ? "FAILED" : "OK"));
  PetscCall(PetscFinalize());
  return failures ? 1 : 0;
}
