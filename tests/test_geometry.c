static const char help[] = "The geometry module (src/geometry) against hand-computed cases.\n";

/* Requirement: the closest point of a triangle, its barycentric coordinates and feature are the hand-computed ones for
   a point over the face, beyond each edge and each vertex and in the plane, and the right point (no NaN) for degenerate
   triangles (two vertices equal, three on a line, a point); on random triangles it is never farther than the closest
   point found by brute force (the face's projection and the three edges). A triangle's normal and area, its bounding
   box and a point's distance to a box are the hand-computed ones. The pseudo-normals of a tetrahedron are its faces'
   outward normals, the sums of two for its edges, the angle-weighted sums for its vertices; a triangle of zero area,
   an edge of three triangles and two neighbours oriented differently are each named. Tolerance 1e-14 (O(1) data).
   The search tree (tree.c) answers as a loop over all triangles, bit for bit: the closest triangle (the least squared
   distance, the lowest number among equal ones) of random points near and far, of points on the vertices of a curved
   grid (exact ties between the triangles around a vertex), for random soups, identical triangles, triangles of zero
   area (segments, points), one triangle and none; the triangles meeting random boxes and random oriented regions
   (infinite bounds too); the top boxes hold every triangle; a partition of the triangles has parts of equal size. */
#include <ssstargeometry.h>
#include "brute_region.h"

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

/* ---- the search tree against brute force ---- */

/* The least (d2, t) over all triangles, as SSStarTreeClosest() promises */
static void BruteClosest(PetscInt n, const PetscReal x[], const PetscReal p[3], PetscInt *t, PetscReal *d2)
{
  *t  = -1;
  *d2 = PETSC_MAX_REAL;
  for (PetscInt i = 0; i < n; i++) {
    PetscReal q[3], e2;

    SSStarClosestPointOnTriangle(p, &x[9 * i], &x[9 * i + 3], &x[9 * i + 6], q, NULL, NULL);
    e2 = PetscSqr(p[0] - q[0]) + PetscSqr(p[1] - q[1]) + PetscSqr(p[2] - q[2]);
    if (e2 < *d2) {
      *d2 = e2;
      *t  = i;
    }
  }
}

static void CheckTreeClosest(SSStarTree tree, PetscInt n, const PetscReal x[], const PetscReal p[3], const char name[])
{
  PetscInt  t, tb;
  PetscReal d2, db;

  PetscCallAbort(PETSC_COMM_SELF, SSStarTreeClosest(tree, p, &t, &d2));
  BruteClosest(n, x, p, &tb, &db);
  if (t != tb || d2 != db) {
    PetscPrintf(PETSC_COMM_SELF, "  point (%g, %g, %g): tree %" PetscInt_FMT " at %.17g, brute force %" PetscInt_FMT " at %.17g\n", (double)p[0], (double)p[1], (double)p[2], t, (double)d2, tb, (double)db);
    Expect(PETSC_FALSE, "the closest triangle is not brute force's", name);
  }
}

static void CheckTreeRegion(SSStarTree tree, PetscInt n, const PetscReal x[], const SSStarRegion *r, const char name[])
{
  PetscInt        nf, m = 0;
  const PetscInt *found;
  PetscBool       same = PETSC_TRUE;

  PetscCallAbort(PETSC_COMM_SELF, SSStarTreeFindInRegion(tree, r, &nf, &found));
  for (PetscInt i = 0; i < n; i++)
    if (BruteMeets(&x[9 * i], r)) {
      if (m >= nf || found[m] != i) same = PETSC_FALSE;
      m++;
    }
  Expect((PetscBool)(same && m == nf), "the triangles of a region are not brute force's", name);
}

static PetscReal Uniform(PetscRandom rnd, PetscReal lo, PetscReal hi)
{
  PetscReal v;

  PetscRandomGetValueReal(rnd, &v); /* in (-1, 1) */
  return lo + (v + 1) / 2 * (hi - lo);
}

/* Random points near and far, random boxes and random oriented regions (some of infinite extent) */
static void CheckTreeQueries(PetscRandom rnd, PetscInt n, const PetscReal x[], PetscReal size, const char name[])
{
  SSStarTree tree;

  PetscCallAbort(PETSC_COMM_SELF, SSStarTreeCreate(n, x, &tree));
  for (PetscInt j = 0; j < 300; j++) {
    PetscReal p[3], reach = j < 200 ? size : 10 * size;

    for (PetscInt k = 0; k < 3; k++) p[k] = Uniform(rnd, -reach, reach);
    CheckTreeClosest(tree, n, x, p, name);
  }
  for (PetscInt j = 0; j < 100; j++) {
    SSStarRegion r;
    PetscReal    box[6];

    for (PetscInt k = 0; k < 3; k++) {
      box[k]     = Uniform(rnd, -size, size);
      box[3 + k] = box[k] + Uniform(rnd, 0, size / 2);
    }
    SSStarRegionBox(box, &r);
    CheckTreeRegion(tree, n, x, &r, name);
    for (PetscInt k = 0; k < 3; k++) r.origin[k] = Uniform(rnd, -size, size);
    for (PetscInt k = 0; k < 9; k++) r.axes[k] = Uniform(rnd, -1, 1);
    for (PetscInt k = 0; k < 3; k++) {
      r.lo[k] = Uniform(rnd, -size, size);
      r.hi[k] = r.lo[k] + Uniform(rnd, 0, size);
    }
    if (j % 3 == 0) { /* a prism: unbounded along its third axis */
      r.lo[2] = PETSC_NINFINITY;
      r.hi[2] = PETSC_INFINITY;
    }
    CheckTreeRegion(tree, n, x, &r, name);
  }
  { /* the top boxes hold every triangle */
    PetscReal boxes[6 * 16];
    PetscInt  nb;
    PetscBool held = PETSC_TRUE;

    PetscCallAbort(PETSC_COMM_SELF, SSStarTreeGetBoxes(tree, 16, &nb, boxes));
    for (PetscInt i = 0; i < n; i++) {
      PetscReal tb[6];
      PetscBool in = PETSC_FALSE;

      SSStarTriangleBox(&x[9 * i], &x[9 * i + 3], &x[9 * i + 6], tb);
      for (PetscInt b = 0; b < nb && !in; b++) in = (PetscBool)(tb[0] >= boxes[6 * b] && tb[1] >= boxes[6 * b + 1] && tb[2] >= boxes[6 * b + 2] && tb[3] <= boxes[6 * b + 3] && tb[4] <= boxes[6 * b + 4] && tb[5] <= boxes[6 * b + 5]);
      held = (PetscBool)(held && in);
    }
    Expect((PetscBool)(held && nb <= 16 && (n == 0 ? nb == 0 : nb >= 1)), "the top boxes do not hold every triangle", name);
  }
  PetscCallAbort(PETSC_COMM_SELF, SSStarTreeDestroy(&tree));
}

/* The grid z = sin(x) cos(y) / 2 over (0, m)^2, two triangles per square: points on its vertices (exact ties) */
static void CheckTreeGrid(PetscRandom rnd)
{
  const PetscInt m = 12;
  PetscReal     *x, v[4][3];
  PetscInt       n = 0;
  SSStarTree     tree;

  PetscCallAbort(PETSC_COMM_SELF, PetscMalloc1(18 * m * m, &x));
  for (PetscInt i = 0; i < m; i++)
    for (PetscInt j = 0; j < m; j++) {
      for (PetscInt c = 0; c < 4; c++) {
        v[c][0] = i + (c == 1 || c == 2);
        v[c][1] = j + (c >= 2);
        v[c][2] = PetscSinReal(v[c][0]) * PetscCosReal(v[c][1]) / 2;
      }
      for (PetscInt k = 0; k < 3; k++) {
        x[9 * n + k]     = v[0][k];
        x[9 * n + 3 + k] = v[1][k];
        x[9 * n + 6 + k] = v[2][k];
        x[9 * n + 9 + k] = v[0][k];
        x[9 * n + 12 + k] = v[2][k];
        x[9 * n + 15 + k] = v[3][k];
      }
      n += 2;
    }
  PetscCallAbort(PETSC_COMM_SELF, SSStarTreeCreate(n, x, &tree));
  for (PetscInt i = 0; i <= m; i++)
    for (PetscInt j = 0; j <= m; j++) {
      PetscReal p[3] = {(PetscReal)i, (PetscReal)j, PetscSinReal((PetscReal)i) * PetscCosReal((PetscReal)j) / 2}, lifted[3] = {p[0], p[1], p[2] + 0.25};

      CheckTreeClosest(tree, n, x, p, "grid vertices");
      CheckTreeClosest(tree, n, x, lifted, "above the grid vertices");
    }
  PetscCallAbort(PETSC_COMM_SELF, SSStarTreeDestroy(&tree));
  CheckTreeQueries(rnd, n, x, m, "curved grid");
  PetscCallAbort(PETSC_COMM_SELF, PetscFree(x));
}

static void CheckTree(PetscRandom rnd)
{
  const PetscInt n = 600;
  PetscReal     *x;
  PetscMPIInt    part[600], size[5] = {0, 0, 0, 0, 0};

  PetscCallAbort(PETSC_COMM_SELF, PetscMalloc1(9 * n, &x));
  for (PetscInt i = 0; i < 9 * n; i++) x[i] = Uniform(rnd, -1, 1); /* a soup of random triangles */
  CheckTreeQueries(rnd, n, x, 1, "random soup");
  for (PetscInt i = 0; i < n; i++) /* small ones, spread */
    for (PetscInt k = 0; k < 9; k++) x[9 * i + k] = x[9 * i + k % 3] + 0.05 * x[9 * i + k];
  CheckTreeQueries(rnd, n, x, 1, "small random triangles");
  for (PetscInt i = 1; i < 50; i++) PetscCallAbort(PETSC_COMM_SELF, PetscArraycpy(&x[9 * i], x, 9)); /* 50 identical triangles: ties everywhere */
  CheckTreeQueries(rnd, 50, x, 1, "identical triangles");
  for (PetscInt i = 0; i < 50; i++) /* zero area: on a line, or a point */
    for (PetscInt k = 0; k < 3; k++) {
      x[9 * i + 3 + k] = i % 2 ? x[9 * i + k] : 2 * x[9 * i + 6 + k] - x[9 * i + k];
      if (i % 5 == 0) x[9 * i + 6 + k] = x[9 * i + 3 + k] = x[9 * i + k];
    }
  CheckTreeQueries(rnd, 50, x, 1, "triangles of zero area");
  CheckTreeQueries(rnd, 1, x, 1, "one triangle");
  CheckTreeQueries(rnd, 0, x, 1, "no triangle");
  CheckTreeGrid(rnd);
  for (PetscInt i = 0; i < 9 * n; i++) x[i] = Uniform(rnd, -1, 1);
  PetscCallAbort(PETSC_COMM_SELF, SSStarTrianglesPartition(n, x, 5, part));
  for (PetscInt i = 0; i < n; i++)
    if (part[i] >= 0 && part[i] < 5) size[part[i]]++;
  Expect((PetscBool)(size[0] == 120 && size[1] == 120 && size[2] == 120 && size[3] == 120 && size[4] == 120), "5 parts of 120 triangles", "partition");
  PetscCallAbort(PETSC_COMM_SELF, PetscFree(x));
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
  CheckTree(rnd);
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
