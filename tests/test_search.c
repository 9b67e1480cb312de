static const char help[] = "The search over triangles spread over the ranks (src/geometry/search.c) against brute force.\n";

/* Requirement: on any number of ranks and however the triangles are spread (compact parts of a partition, every
   size-th triangle, all on rank 0), SSStarSearchClosest() gives every rank's points the triangle a loop over all
   triangles gives (the least key among those within tol of the closest distance; tol = 0: among the closest), with
   the same squared distance, closest point, barycentric coordinates and feature bit for bit, and the triangle's data;
   SSStarSearchFindInRegions() gives each region the triangles of a loop over all, in the order of their keys. Cases: a
   soup of random triangles with keys in no spatial order, and a curved grid whose keys are its triangles' sorted
   vertex numbers (as contact pairs have them), with points on its vertices (exact ties) and near them (ties within
   tol); random boxes and oriented regions, unbounded ones too; and a search without any triangle. */
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

/* The same numbers on every rank: a linear congruential generator, uniform in (lo, hi) */
static PetscReal Uniform(unsigned long long *state, PetscReal lo, PetscReal hi)
{
  *state = *state * 6364136223846793005ULL + 1442695040888963407ULL;
  return lo + (PetscReal)(*state >> 11) / 9007199254740992.0 * (hi - lo);
}

typedef struct {
  const char *name;
  PetscInt    n;
  PetscReal  *x;   /* 9 per triangle   */
  PetscInt   *key; /* 3 per triangle   */
  PetscReal   size, tol;
} Set;

static int CompareKeys(const PetscInt a[3], const PetscInt b[3])
{
  for (PetscInt k = 0; k < 3; k++)
    if (a[k] != b[k]) return a[k] < b[k] ? -1 : 1;
  return 0;
}

static PetscReal Distance2(const PetscReal p[3], const PetscReal x[9], PetscReal q[3])
{
  SSStarClosestPointOnTriangle(p, &x[0], &x[3], &x[6], q, NULL, NULL);
  return PetscSqr(p[0] - q[0]) + PetscSqr(p[1] - q[1]) + PetscSqr(p[2] - q[2]);
}

/* The loop over all triangles: the least key among those within tol of the closest distance */
static PetscInt BruteClosest(const Set *s, const PetscReal p[3], PetscReal tol)
{
  PetscReal d2min = PETSC_MAX_REAL, bound2, q[3];
  PetscInt  best  = -1;

  for (PetscInt t = 0; t < s->n; t++) d2min = PetscMin(d2min, Distance2(p, &s->x[9 * t], q));
  bound2 = tol > 0 ? PetscSqr(PetscSqrtReal(d2min) + tol) : d2min;
  for (PetscInt t = 0; t < s->n; t++)
    if (Distance2(p, &s->x[9 * t], q) <= bound2 && (best < 0 || CompareKeys(&s->key[3 * t], &s->key[3 * best]) < 0)) best = t;
  return best;
}

/* The triangles of rank `rank` of `size` when spread by `spread`: "partition", "every size-th", "rank 0" */
static PetscErrorCode Share(const Set *s, const char spread[], PetscMPIInt rank, PetscMPIInt size, PetscInt *n, PetscReal **x, PetscInt **key, PetscReal **data)
{
  PetscMPIInt *part;
  PetscBool    byPartition, byRankZero;

  PetscFunctionBegin;
  PetscCall(PetscStrcmp(spread, "partition", &byPartition));
  PetscCall(PetscStrcmp(spread, "rank 0", &byRankZero));
  PetscCall(PetscMalloc1(s->n + 1, &part));
  if (byPartition) PetscCall(SSStarTrianglesPartition(s->n, s->x, size, part));
  else
    for (PetscInt t = 0; t < s->n; t++) part[t] = byRankZero ? 0 : (PetscMPIInt)(t % size);
  PetscCall(PetscMalloc3(9 * s->n + 1, x, 3 * s->n + 1, key, 2 * s->n + 1, data));
  *n = 0;
  for (PetscInt t = 0; t < s->n; t++) {
    if (part[t] != rank) continue;
    PetscCall(PetscArraycpy(&(*x)[9 * *n], &s->x[9 * t], 9));
    PetscCall(PetscArraycpy(&(*key)[3 * *n], &s->key[3 * t], 3));
    (*data)[2 * *n]     = (PetscReal)t; /* the data: where the triangle is in the whole set */
    (*data)[2 * *n + 1] = -(PetscReal)t;
    (*n)++;
  }
  PetscCall(PetscFree(part));
  PetscFunctionReturn(0);
}

static PetscErrorCode CheckClosest(SSStarSearch search, const Set *s, PetscInt np, const PetscReal p[], PetscReal tol, const char name[])
{
  SSStarSearchHit *hit;
  PetscReal       *data;

  PetscFunctionBegin;
  PetscCall(PetscMalloc2(np + 1, &hit, 2 * np + 1, &data));
  PetscCall(SSStarSearchClosest(search, np, p, tol, hit, data));
  for (PetscInt i = 0; i < np; i++) {
    const PetscInt        t = BruteClosest(s, &p[3 * i], tol);
    PetscReal             q[3], w[3];
    SSStarTriangleFeature f;
    PetscBool             same;

    if (t < 0) {
      Expect((PetscBool)(hit[i].key[0] == -1), "a triangle found where there is none", name);
      continue;
    }
    SSStarClosestPointOnTriangle(&p[3 * i], &s->x[9 * t], &s->x[9 * t + 3], &s->x[9 * t + 6], q, w, &f);
    same = (PetscBool)(!CompareKeys(hit[i].key, &s->key[3 * t]) && hit[i].d2 == Distance2(&p[3 * i], &s->x[9 * t], q) && f == hit[i].feature && data[2 * i] == (PetscReal)t && data[2 * i + 1] == -(PetscReal)t);
    for (PetscInt k = 0; k < 3; k++) same = (PetscBool)(same && q[k] == hit[i].q[k] && w[k] == hit[i].w[k]);
    for (PetscInt k = 0; k < 9; k++) same = (PetscBool)(same && s->x[9 * t + k] == hit[i].x[k]);
    if (!same) PetscCall(PetscPrintf(PETSC_COMM_SELF, "  point %" PetscInt_FMT " (%g, %g, %g): key (%" PetscInt_FMT " %" PetscInt_FMT " %" PetscInt_FMT "), brute force (%" PetscInt_FMT " %" PetscInt_FMT " %" PetscInt_FMT ")\n", i, (double)p[3 * i], (double)p[3 * i + 1], (double)p[3 * i + 2], hit[i].key[0], hit[i].key[1], hit[i].key[2], s->key[3 * t], s->key[3 * t + 1], s->key[3 * t + 2]));
    Expect(same, "the closest triangle is not brute force's", name);
  }
  PetscCall(PetscFree2(hit, data));
  PetscFunctionReturn(0);
}

static PetscErrorCode CheckRegions(SSStarSearch search, const Set *s, PetscInt nr, const SSStarRegion r[], const char name[])
{
  PetscInt        *offset;
  SSStarSearchHit *hit;
  PetscReal       *data;

  PetscFunctionBegin;
  PetscCall(SSStarSearchFindInRegions(search, nr, r, &offset, &hit, &data));
  for (PetscInt i = 0; i < nr; i++) {
    PetscInt  m = 0, last = -1;
    PetscBool same = PETSC_TRUE;

    for (PetscInt e = offset[i]; e < offset[i + 1]; e++) {
      const PetscInt t = (PetscInt)data[2 * e];

      same = (PetscBool)(same && t >= 0 && t < s->n && BruteMeets(&s->x[9 * t], &r[i]) && !CompareKeys(hit[e].key, &s->key[3 * t]) && (last < 0 || CompareKeys(&s->key[3 * last], &s->key[3 * t]) < 0));
      last = t;
    }
    for (PetscInt t = 0; t < s->n; t++) m += BruteMeets(&s->x[9 * t], &r[i]);
    Expect((PetscBool)(same && m == offset[i + 1] - offset[i]), "the triangles of a region are not brute force's, or not in key order", name);
  }
  PetscCall(PetscFree(offset));
  PetscCall(PetscFree(hit));
  PetscCall(PetscFree(data));
  PetscFunctionReturn(0);
}

/* Every rank's own random points and regions, and points on the set's vertices */
static PetscErrorCode CheckSet(const Set *s, const char spread[], PetscMPIInt rank, PetscMPIInt size)
{
  unsigned long long state = 1000 + (unsigned long long)rank;
  SSStarSearch       search;
  PetscInt           n = 0, np = 0, nr = 60;
  PetscReal         *x, *data, *p;
  PetscInt          *key;
  SSStarRegion       r[60];
  char               name[128];

  PetscFunctionBegin;
  PetscCall(PetscSNPrintf(name, sizeof(name), "%s, %s", s->name, spread));
  PetscCall(Share(s, spread, rank, size, &n, &x, &key, &data));
  PetscCall(SSStarSearchCreate(PETSC_COMM_WORLD, n, x, key, 2, data, &search));
  PetscCall(PetscFree3(x, key, data));
  PetscCall(PetscMalloc1(3 * (200 + 3 * s->n), &p));
  for (PetscInt i = 0; i < 200; i++, np++)
    for (PetscInt k = 0; k < 3; k++) p[3 * np + k] = Uniform(&state, -(i < 150 ? 1 : 5) * s->size, (i < 150 ? 1 : 5) * s->size);
  for (PetscInt t = rank; t < s->n; t += size, np++) /* on a vertex; near it */
    for (PetscInt k = 0; k < 3; k++) p[3 * np + k] = s->x[9 * t + k] + (t % 2 ? 0 : Uniform(&state, -1e-4, 1e-4) * s->size);
  PetscCall(CheckClosest(search, s, np, p, 0, name));
  PetscCall(CheckClosest(search, s, np, p, s->tol, name));
  for (PetscInt i = 0; i < nr; i++) {
    PetscReal box[6];

    for (PetscInt k = 0; k < 3; k++) {
      box[k]     = Uniform(&state, -s->size, s->size);
      box[3 + k] = box[k] + Uniform(&state, 0, s->size / 3);
    }
    SSStarRegionBox(box, &r[i]);
    if (i % 2) {
      for (PetscInt k = 0; k < 3; k++) r[i].origin[k] = Uniform(&state, -s->size, s->size);
      for (PetscInt k = 0; k < 9; k++) r[i].axes[k] = Uniform(&state, -1, 1);
      if (i % 3 == 0) {
        r[i].lo[2] = PETSC_NINFINITY;
        r[i].hi[2] = PETSC_INFINITY;
      }
    }
  }
  PetscCall(CheckRegions(search, s, nr, r, name));
  PetscCall(SSStarSearchDestroy(&search));
  PetscCall(PetscFree(p));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  unsigned long long state = 7;
  const PetscInt     m     = 14, nsoup = 700;
  const char        *spreads[] = {"partition", "every size-th", "rank 0"};
  Set                soup = {"random soup", nsoup, NULL, NULL, 1, 0.05}, grid = {"curved grid", 2 * m * m, NULL, NULL, (PetscReal)m, 1e-3}, none = {"no triangle", 0, NULL, NULL, 1, 0};
  PetscMPIInt        rank, size;

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCall(PetscMalloc2(9 * nsoup, &soup.x, 3 * nsoup, &soup.key));
  for (PetscInt t = 0; t < nsoup; t++) {
    for (PetscInt k = 0; k < 9; k++) soup.x[9 * t + k] = k < 3 ? Uniform(&state, -1, 1) : soup.x[9 * t + k % 3] + Uniform(&state, -0.2, 0.2);
    soup.key[3 * t]     = (t * 389) % nsoup; /* keys in no spatial order */
    soup.key[3 * t + 1] = soup.key[3 * t + 2] = 0;
  }
  PetscCall(PetscMalloc2(9 * grid.n, &grid.x, 3 * grid.n, &grid.key));
  for (PetscInt i = 0, t = 0; i < m; i++) /* z = sin(x) cos(y) / 2, two triangles per square, keys: sorted vertex numbers */
    for (PetscInt j = 0; j < m; j++)
      for (PetscInt h = 0; h < 2; h++, t++) {
        const PetscInt corner[2][3] = {{0, 1, 2}, {0, 2, 3}};

        for (PetscInt c = 0; c < 3; c++) {
          const PetscInt v = corner[h][c], vi = i + (v == 1 || v == 2), vj = j + (v >= 2);

          grid.x[9 * t + 3 * c]     = (PetscReal)vi;
          grid.x[9 * t + 3 * c + 1] = (PetscReal)vj;
          grid.x[9 * t + 3 * c + 2] = PetscSinReal((PetscReal)vi) * PetscCosReal((PetscReal)vj) / 2;
          grid.key[3 * t + c]       = vi * (m + 1) + vj;
        }
        PetscCall(PetscSortInt(3, &grid.key[3 * t]));
      }
  for (size_t k = 0; k < PETSC_STATIC_ARRAY_LENGTH(spreads); k++) {
    PetscCall(CheckSet(&soup, spreads[k], rank, size));
    PetscCall(CheckSet(&grid, spreads[k], rank, size));
  }
  PetscCall(CheckSet(&none, "partition", rank, size));
  PetscCall(PetscFree2(soup.x, soup.key));
  PetscCall(PetscFree2(grid.x, grid.key));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &failures, 1, MPI_INT, MPI_SUM, PETSC_COMM_WORLD));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s\n", failures ? "FAILED" : "OK"));
  PetscCall(PetscFinalize());
  return failures ? 1 : 0;
}
