/*
   The search over triangles spread over the ranks of a communicator (include/ssstargeometry.h): each rank holds some
   triangles in a tree (tree.c) and tells every rank where they are by the boxes of its tree's top nodes. A rank's
   question (the closest triangle to each of its points, the triangles that meet each of its regions) goes to the
   ranks whose boxes can hold an answer, and their answers come back: the triangles travel only as answers, so no rank
   holds them all. The answers are those of a loop over every triangle of every rank (exactly: same triangles, same
   distances), whatever the number of ranks and however the triangles are spread.

   Closest triangle to a point p: a triangle farther than the farthest point of some box holding a triangle cannot be
   the closest, nor can one farther than this rank's own closest; so p goes to each rank with a box within that reach
   (plus the tolerance of ties and round-off), each answers with its candidates, and the asking rank picks.
*/
#include "geometryimpl.h"
#include <ssstar.h> /* SSStarInitializePackage() registers SSSTAR_Search */

#define SEARCH_BOXES 16 /* top boxes per rank every rank knows                                        */
#define POINT_RECORD 4  /* a point sent: its index on the asking rank, its coordinates                  */
#define REGION_RECORD 19 /* a region sent: its index, origin (3), axes (9), lo (3), hi (3)               */

static int CompareKeys(const PetscInt a[3], const PetscInt b[3])
{
  for (PetscInt k = 0; k < 3; k++)
    if (a[k] != b[k]) return a[k] < b[k] ? -1 : 1;
  return 0;
}

typedef struct {
  PetscInt key[3], at;
} Keyed;

static int CompareKeyed(const void *a, const void *b)
{
  const Keyed *x = (const Keyed *)a, *y = (const Keyed *)b;
  const int    c = CompareKeys(x->key, y->key);

  return c ? c : (x->at < y->at ? -1 : x->at > y->at);
}

/* A growing list of (rank, item): what to send where */
typedef struct {
  PetscInt     n, max;
  PetscMPIInt *rank;
  PetscInt    *item;
} Routes;

static PetscErrorCode RoutesAdd(Routes *r, PetscMPIInt rank, PetscInt item)
{
  PetscFunctionBegin;
  if (r->n == r->max) {
    r->max = PetscMax(64, 2 * r->max);
    PetscCall(PetscRealloc(r->max * sizeof(PetscMPIInt), &r->rank));
    PetscCall(PetscRealloc(r->max * sizeof(PetscInt), &r->item));
  }
  r->rank[r->n]   = rank;
  r->item[r->n++] = item;
  PetscFunctionReturn(0);
}

static PetscErrorCode RoutesDestroy(Routes *r)
{
  PetscFunctionBegin;
  PetscCall(PetscFree(r->rank));
  PetscCall(PetscFree(r->item));
  PetscFunctionReturn(0);
}

/* A growing buffer of reals; room for need more */
static PetscErrorCode Reserve(PetscReal **buf, PetscInt *max, PetscInt used, PetscInt need)
{
  PetscFunctionBegin;
  if (used + need > *max) {
    *max = PetscMax(2 * *max, used + need + 1024);
    PetscCall(PetscRealloc(*max * sizeof(PetscReal), buf));
  }
  PetscFunctionReturn(0);
}

/* Sends count[r] reals of send (packed in rank order) to each rank r; recv gets rcount[r] from each, in rank order */
static PetscErrorCode Exchange(SSStarSearch s, const PetscMPIInt count[], const PetscReal send[], PetscMPIInt rcount[], PetscReal **recv)
{
  PetscMPIInt *sdispl, *rdispl, stotal = 0, rtotal = 0;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Alltoall(count, 1, MPI_INT, rcount, 1, MPI_INT, s->comm));
  PetscCall(PetscMalloc2(s->size, &sdispl, s->size, &rdispl));
  for (PetscMPIInt r = 0; r < s->size; r++) {
    sdispl[r] = stotal;
    rdispl[r] = rtotal;
    stotal += count[r];
    rtotal += rcount[r];
  }
  PetscCall(PetscMalloc1(rtotal + 1, recv));
  PetscCallMPI(MPI_Alltoallv(send, count, sdispl, MPIU_REAL, *recv, rcount, rdispl, MPIU_REAL, s->comm));
  PetscCall(PetscFree2(sdispl, rdispl));
  PetscFunctionReturn(0);
}

static void PackPoint(const void *ctx, PetscInt i, PetscReal rec[])
{
  const PetscReal *p = (const PetscReal *)ctx;

  rec[0] = (PetscReal)i;
  for (PetscInt k = 0; k < 3; k++) rec[1 + k] = p[3 * i + k];
}

static void PackRegion(const void *ctx, PetscInt i, PetscReal rec[])
{
  const SSStarRegion *r = &((const SSStarRegion *)ctx)[i];

  rec[0] = (PetscReal)i;
  for (PetscInt k = 0; k < 3; k++) {
    rec[1 + k]  = r->origin[k];
    rec[13 + k] = r->lo[k];
    rec[16 + k] = r->hi[k];
  }
  for (PetscInt k = 0; k < 9; k++) rec[4 + k] = r->axes[k];
}

static void UnpackRegion(const PetscReal rec[], SSStarRegion *r)
{
  for (PetscInt k = 0; k < 3; k++) {
    r->origin[k] = rec[1 + k];
    r->lo[k]     = rec[13 + k];
    r->hi[k]     = rec[16 + k];
  }
  for (PetscInt k = 0; k < 9; k++) r->axes[k] = rec[4 + k];
}

/* A triangle as an answer: [index of the question, d2, key (3), x (9), q (3), w (3), feature, data (m)] */
#define HIT_RECORD(m) (21 + (m))

static void PackHit(SSStarSearch s, PetscInt question, PetscInt t, const PetscReal p[3], PetscReal rec[])
{
  const PetscReal      *x;
  SSStarTriangleFeature feature = SSSTAR_TRIANGLE_FACE;
  PetscReal             q[3] = {0, 0, 0}, w[3] = {0, 0, 0};

  x = &s->tree->x[9 * t];
  if (p) SSStarClosestPointOnTriangle(p, &x[0], &x[3], &x[6], q, w, &feature);
  rec[0] = (PetscReal)question;
  rec[1] = p ? PetscSqr(p[0] - q[0]) + PetscSqr(p[1] - q[1]) + PetscSqr(p[2] - q[2]) : 0;
  for (PetscInt k = 0; k < 3; k++) {
    rec[2 + k]  = (PetscReal)s->key[3 * t + k];
    rec[14 + k] = q[k];
    rec[17 + k] = w[k];
  }
  for (PetscInt k = 0; k < 9; k++) rec[5 + k] = x[k];
  rec[20] = (PetscReal)feature;
  for (PetscInt k = 0; k < s->m; k++) rec[21 + k] = s->data[s->m * t + k];
}

static void UnpackHit(PetscInt m, const PetscReal rec[], SSStarSearchHit *hit, PetscReal data[])
{
  hit->d2 = rec[1];
  for (PetscInt k = 0; k < 3; k++) {
    hit->key[k] = (PetscInt)rec[2 + k];
    hit->q[k]   = rec[14 + k];
    hit->w[k]   = rec[17 + k];
  }
  for (PetscInt k = 0; k < 9; k++) hit->x[k] = rec[5 + k];
  hit->feature = (SSStarTriangleFeature)(PetscInt)rec[20];
  for (PetscInt k = 0; k < m; k++) data[k] = rec[21 + k];
}

/* The squared distance within which the candidates of a closest distance sqrt(d2) lie */
static PetscReal Bound2(PetscReal d2, PetscReal tol)
{
  return tol > 0 ? PetscSqr(PetscSqrtReal(d2) + tol) : d2;
}

static PetscReal RoundOff(SSStarSearch s, const PetscReal p[3])
{
  return SSSTAR_ROUNDOFF * (s->scale + PetscMax(PetscAbsReal(p[0]), PetscMax(PetscAbsReal(p[1]), PetscAbsReal(p[2]))));
}

/*@C
   SSStarSearchCreate - a search over triangles spread over the ranks of a communicator

   Collective

   Input Parameters:
+  comm - the communicator
.  n    - the number of triangles this rank holds (any, 0 too)
.  x    - their vertices, 9 per triangle (a, b, c)
.  key  - 3 integers per triangle: how ties are broken (the least key, lexicographically, wins); keys are unique
.  m    - the number of reals of data per triangle (0 for none)
-  data - m per triangle: what the answers carry along, or NULL when m is 0

   Output Parameter:
.  search - the search; triangles, keys and data are copied

   Notes:
   Each rank builds a tree over its triangles (SSStarTreeCreate()) and every rank learns the boxes of the top nodes of
   every tree (at most 16 per rank). Where the triangles lie decides what the queries cost, not what they answer:
   spread them by owner or with SSStarTrianglesPartition(). -info prints each rank's triangles and memory.

   Level: developer

.seealso: `SSStarSearchClosest()`, `SSStarSearchFindInRegions()`, `SSStarSearchDestroy()`, `SSStarTreeCreate()`,
          `SSStarTrianglesPartition()`
@*/
PetscErrorCode SSStarSearchCreate(MPI_Comm comm, PetscInt n, const PetscReal x[], const PetscInt key[], PetscInt m, const PetscReal data[], SSStarSearch *search)
{
  SSStarSearch s;
  Keyed       *order;
  PetscReal   *xs, mine[6 * SEARCH_BOXES];
  PetscInt     nb;
  PetscMPIInt *counts, *displs, nbm;
  size_t       bytes;

  PetscFunctionBegin;
  PetscCall(SSStarInitializePackage());
  PetscCall(PetscLogEventBegin(SSSTAR_Search, 0, 0, 0, 0));
  PetscCall(PetscNew(&s));
  s->comm = comm;
  s->n    = n;
  s->m    = m;
  PetscCallMPI(MPI_Comm_size(comm, &s->size));
  PetscCallMPI(MPI_Comm_rank(comm, &s->rank));
  PetscCall(PetscMalloc1(n + 1, &order));
  for (PetscInt t = 0; t < n; t++) {
    for (PetscInt k = 0; k < 3; k++) order[t].key[k] = key[3 * t + k];
    order[t].at = t;
  }
  qsort(order, (size_t)n, sizeof(Keyed), CompareKeyed);
  PetscCall(PetscMalloc1(9 * n + 1, &xs));
  PetscCall(PetscMalloc1(3 * n + 1, &s->key));
  PetscCall(PetscMalloc1(m * n + 1, &s->data));
  for (PetscInt t = 0; t < n; t++) {
    const PetscInt i = order[t].at;

    for (PetscInt k = 0; k < 9; k++) xs[9 * t + k] = x[9 * i + k];
    for (PetscInt k = 0; k < 3; k++) s->key[3 * t + k] = key[3 * i + k];
    for (PetscInt k = 0; k < m; k++) s->data[m * t + k] = data[m * i + k];
    PetscCheck(t == 0 || CompareKeys(&s->key[3 * (t - 1)], &s->key[3 * t]), PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "Two triangles have the key (%" PetscInt_FMT ", %" PetscInt_FMT ", %" PetscInt_FMT ")", s->key[3 * t], s->key[3 * t + 1], s->key[3 * t + 2]);
  }
  PetscCall(PetscFree(order));
  PetscCall(SSStarTreeCreate(n, xs, &s->tree));
  PetscCall(PetscFree(xs));
  PetscCall(MPIU_Allreduce(&n, &s->N, 1, MPIU_INT, MPI_SUM, comm));
  PetscCall(MPIU_Allreduce(&s->tree->scale, &s->scale, 1, MPIU_REAL, MPIU_MAX, comm));
  nb = 0;
  if (n) PetscCall(SSStarTreeGetBoxes(s->tree, SEARCH_BOXES, &nb, mine));
  nbm = (PetscMPIInt)(6 * nb);
  PetscCall(PetscMalloc2(s->size, &counts, s->size, &displs));
  PetscCallMPI(MPI_Allgather(&nbm, 1, MPI_INT, counts, 1, MPI_INT, comm));
  PetscCall(PetscMalloc1(s->size + 1, &s->boxStart));
  s->boxStart[0] = 0;
  for (PetscMPIInt r = 0; r < s->size; r++) {
    displs[r]          = (PetscMPIInt)(6 * s->boxStart[r]);
    s->boxStart[r + 1] = s->boxStart[r] + counts[r] / 6;
  }
  PetscCall(PetscMalloc1(6 * s->boxStart[s->size] + 1, &s->boxes));
  PetscCallMPI(MPI_Allgatherv(mine, nbm, MPIU_REAL, s->boxes, counts, displs, MPIU_REAL, comm));
  PetscCall(PetscFree2(counts, displs));
  PetscCall(SSStarSearchGetSize(s, NULL, NULL, &bytes));
  PetscCall(PetscInfo(NULL, "SSStarSearch: %" PetscInt_FMT " of %" PetscInt_FMT " triangles on rank %d, %" PetscInt_FMT " bytes\n", n, s->N, s->rank, (PetscInt)bytes));
  *search = s;
  PetscCall(PetscLogEventEnd(SSSTAR_Search, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/*@C
   SSStarSearchDestroy - frees a search

   Not Collective

   Input Parameter:
.  search - the search

   Level: developer

.seealso: `SSStarSearchCreate()`
@*/
PetscErrorCode SSStarSearchDestroy(SSStarSearch *search)
{
  PetscFunctionBegin;
  if (!*search) PetscFunctionReturn(0);
  PetscCall(SSStarTreeDestroy(&(*search)->tree));
  PetscCall(PetscFree((*search)->key));
  PetscCall(PetscFree((*search)->data));
  PetscCall(PetscFree((*search)->boxStart));
  PetscCall(PetscFree((*search)->boxes));
  PetscCall(PetscFree(*search));
  PetscFunctionReturn(0);
}

/* A question's answers (question: index on the asking rank, then what it asks), appended to buf (max, used) */
typedef PetscErrorCode (*Answer)(SSStarSearch, const PetscReal question[], PetscReal tol, PetscReal **buf, PetscInt *max, PetscInt *used);

/* A point's: this rank's triangles within tol of its closest one (for tol = 0 the closest alone, the least key among
   equally close ones) */
static PetscErrorCode AnswerPoint(SSStarSearch s, const PetscReal question[], PetscReal tol, PetscReal **buf, PetscInt *max, PetscInt *used)
{
  const PetscInt   record = HIT_RECORD(s->m), asker = (PetscInt)question[0];
  const PetscReal *p      = &question[1];
  PetscInt         t, nf;
  const PetscInt  *found;
  PetscReal        d2, bound2, reach, box[6];
  SSStarRegion     region;

  PetscFunctionBegin;
  PetscCall(SSStarTreeClosest(s->tree, p, &t, &d2));
  if (t < 0) PetscFunctionReturn(0);
  if (tol == 0) {
    PetscCall(Reserve(buf, max, *used, record));
    PackHit(s, asker, t, p, &(*buf)[*used]);
    *used += record;
    PetscFunctionReturn(0);
  }
  bound2 = Bound2(d2, tol);
  reach  = PetscSqrtReal(bound2) + RoundOff(s, p);
  for (PetscInt k = 0; k < 3; k++) {
    box[k]     = p[k] - reach;
    box[3 + k] = p[k] + reach;
  }
  SSStarRegionBox(box, &region);
  PetscCall(SSStarTreeFindInRegion(s->tree, &region, &nf, &found));
  for (PetscInt f = 0; f < nf; f++) {
    PetscCall(Reserve(buf, max, *used, record));
    PackHit(s, asker, found[f], p, &(*buf)[*used]);
    if ((*buf)[*used + 1] <= bound2) *used += record;
  }
  PetscFunctionReturn(0);
}

/* A region's: this rank's triangles that meet it, without a closest point */
static PetscErrorCode AnswerRegion(SSStarSearch s, const PetscReal question[], PetscReal tol, PetscReal **buf, PetscInt *max, PetscInt *used)
{
  const PetscInt  record = HIT_RECORD(s->m);
  SSStarRegion    region;
  PetscInt        nf;
  const PetscInt *found;

  PetscFunctionBegin;
  UnpackRegion(question, &region);
  PetscCall(SSStarTreeFindInRegion(s->tree, &region, &nf, &found));
  PetscCall(Reserve(buf, max, *used, record * nf));
  for (PetscInt f = 0; f < nf; f++, *used += record) PackHit(s, (PetscInt)question[0], found[f], NULL, &(*buf)[*used]);
  PetscFunctionReturn(0);
}

/*
   The questions of the routes (record reals each, written by pack) sent to their ranks; each rank's answers to what
   it was asked (answer); the nback answers that came back here (HIT_RECORD each)
*/
static PetscErrorCode Ask(SSStarSearch s, const Routes *routes, PetscInt record, void (*pack)(const void *, PetscInt, PetscReal[]), const void *ctx, Answer answer, PetscReal tol, PetscInt *nback, PetscReal **back)
{
  PetscMPIInt *count, *at, *rcount;
  PetscReal   *send, *asked, *buf = NULL;
  PetscInt     max = 0, used = 0, j = 0;

  PetscFunctionBegin;
  PetscCall(PetscCalloc3(s->size, &count, s->size, &at, s->size, &rcount));
  for (PetscInt e = 0; e < routes->n; e++) count[routes->rank[e]] += (PetscMPIInt)record;
  for (PetscMPIInt r = 1; r < s->size; r++) at[r] = at[r - 1] + count[r - 1];
  PetscCall(PetscMalloc1(record * routes->n + 1, &send));
  for (PetscInt e = 0; e < routes->n; e++) {
    (*pack)(ctx, routes->item[e], &send[at[routes->rank[e]]]);
    at[routes->rank[e]] += (PetscMPIInt)record;
  }
  PetscCall(Exchange(s, count, send, rcount, &asked));
  PetscCall(PetscFree(send));
  for (PetscMPIInt r = 0; r < s->size; r++) { /* the answers to each rank in turn */
    const PetscInt start = used;

    for (PetscInt e = 0; e < rcount[r] / record; e++, j++) PetscCall((*answer)(s, &asked[record * j], tol, &buf, &max, &used));
    count[r] = (PetscMPIInt)(used - start);
  }
  PetscCall(Exchange(s, count, buf, rcount, back));
  *nback = 0;
  for (PetscMPIInt r = 0; r < s->size; r++) *nback += rcount[r] / HIT_RECORD(s->m);
  PetscCall(PetscFree(buf));
  PetscCall(PetscFree(asked));
  PetscCall(PetscFree3(count, at, rcount));
  PetscFunctionReturn(0);
}

/*@C
   SSStarSearchClosest - for each point, the closest triangle on any rank

   Collective

   Input Parameters:
+  search - the search
.  np     - the number of points of this rank
.  p      - their coordinates, 3 per point
-  tol    - ties: among the triangles whose distance is within tol of the closest distance, the least key wins (0: among
            the closest, exactly)

   Output Parameters:
+  hit  - per point: the triangle, its key, the squared distance, the closest point on it, its barycentric coordinates
          and feature (SSStarClosestPointOnTriangle()); key[0] = -1 when no rank holds a triangle
-  data - per point, the triangle's m reals of data, or NULL when m is 0

   Notes:
   The answer is that of a loop over all triangles of all ranks: d the distance |p - q| of the closest point q, dmin
   the least d; of the triangles with d <= dmin + tol (for tol = 0: with d2 = dmin^2 exactly), the least key. It does
   not depend on the number of ranks nor on where the triangles are. Each point goes to the ranks that may hold a
   candidate: those with a box nearer than the nearest of (this rank's closest triangle, the farthest point of any
   rank's box) plus tol.

   Level: developer

.seealso: `SSStarSearchCreate()`, `SSStarTreeClosest()`, `SSStarSearchFindInRegions()`
@*/
PetscErrorCode SSStarSearchClosest(SSStarSearch search, PetscInt np, const PetscReal p[], PetscReal tol, SSStarSearchHit hit[], PetscReal data[])
{
  const PetscInt record = HIT_RECORD(search->m);
  Routes         routes = {0, 0, NULL, NULL};
  PetscReal     *back, *d2min;
  PetscInt       nback;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(SSSTAR_Search, 0, 0, 0, 0));
  for (PetscInt i = 0; i < np; i++) {
    const PetscReal *x = &p[3 * i];
    PetscReal        d2 = PETSC_MAX_REAL, reach;
    PetscInt         t  = -1;

    if (search->n) PetscCall(SSStarTreeClosest(search->tree, x, &t, &d2));
    reach = t >= 0 ? PetscSqrtReal(d2) : PETSC_MAX_REAL;
    for (PetscInt b = 0; b < search->boxStart[search->size]; b++) reach = PetscMin(reach, PetscSqrtReal(SSStarBoxFarthest2(x, &search->boxes[6 * b])));
    if (reach == PETSC_MAX_REAL) continue; /* no triangle anywhere */
    reach += tol + 2 * RoundOff(search, x);
    for (PetscMPIInt r = 0; r < search->size; r++)
      for (PetscInt b = search->boxStart[r]; b < search->boxStart[r + 1]; b++)
        if (SSStarBoxDistance2(x, &search->boxes[6 * b]) <= PetscSqr(reach)) {
          PetscCall(RoutesAdd(&routes, r, i));
          break;
        }
  }
  PetscCall(Ask(search, &routes, POINT_RECORD, PackPoint, p, AnswerPoint, tol, &nback, &back));
  PetscCall(RoutesDestroy(&routes));
  PetscCall(PetscMalloc1(np + 1, &d2min));
  for (PetscInt i = 0; i < np; i++) {
    d2min[i] = PETSC_MAX_REAL;
    PetscCall(PetscMemzero(&hit[i], sizeof(hit[i])));
    hit[i].key[0] = hit[i].key[1] = hit[i].key[2] = -1;
    hit[i].d2                                     = PETSC_MAX_REAL;
    for (PetscInt k = 0; k < search->m; k++) data[search->m * i + k] = 0;
  }
  for (PetscInt e = 0; e < nback; e++) {
    const PetscInt i = (PetscInt)back[record * e];

    d2min[i] = PetscMin(d2min[i], back[record * e + 1]);
  }
  for (PetscInt e = 0; e < nback; e++) {
    const PetscReal *rec = &back[record * e];
    const PetscInt   i   = (PetscInt)rec[0], key[3] = {(PetscInt)rec[2], (PetscInt)rec[3], (PetscInt)rec[4]};

    if (rec[1] <= Bound2(d2min[i], tol) && (hit[i].key[0] < 0 || CompareKeys(key, hit[i].key) < 0)) UnpackHit(search->m, rec, &hit[i], &data[search->m * i]);
  }
  PetscCall(PetscFree(d2min));
  PetscCall(PetscFree(back));
  PetscCall(PetscLogEventEnd(SSSTAR_Search, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/*@C
   SSStarSearchFindInRegions - for each region, the triangles on any rank whose bounding box in its frame meets it

   Collective

   Input Parameters:
+  search  - the search
.  nr      - the number of regions of this rank
-  regions - the regions (bounds may be infinite: a prism along an axis)

   Output Parameters:
+  offset - nr + 1: region i's triangles are offset[i] .. offset[i + 1] - 1
.  hit    - the triangles (vertices, key), each region's in the order of their keys
-  data   - their m reals of data each

   Notes:
   The triangles SSStarTreeFindInRegion() finds, over all ranks: those a loop over every triangle would find. Free the
   three arrays with PetscFree().

   Level: developer

.seealso: `SSStarSearchCreate()`, `SSStarTreeFindInRegion()`, `SSStarRegionBox()`, `SSStarSearchClosest()`
@*/
PetscErrorCode SSStarSearchFindInRegions(SSStarSearch search, PetscInt nr, const SSStarRegion regions[], PetscInt *offset[], SSStarSearchHit *hit[], PetscReal *data[])
{
  const PetscInt record = HIT_RECORD(search->m);
  Routes         routes = {0, 0, NULL, NULL};
  PetscReal     *back;
  PetscInt       nback, *at;
  Keyed         *order;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(SSSTAR_Search, 0, 0, 0, 0));
  for (PetscInt i = 0; i < nr; i++)
    for (PetscMPIInt r = 0; r < search->size; r++)
      for (PetscInt b = search->boxStart[r]; b < search->boxStart[r + 1]; b++)
        if (SSStarBoxMeetsRegion(&search->boxes[6 * b], &regions[i], search->scale)) {
          PetscCall(RoutesAdd(&routes, r, i));
          break;
        }
  PetscCall(Ask(search, &routes, REGION_RECORD, PackRegion, regions, AnswerRegion, 0, &nback, &back));
  PetscCall(RoutesDestroy(&routes));
  PetscCall(PetscCalloc1(nr + 1, offset));
  PetscCall(PetscMalloc1(nback + 1, hit));
  PetscCall(PetscMalloc1(search->m * nback + 1, data));
  PetscCall(PetscMalloc1(nback + 1, &order));
  PetscCall(PetscMalloc1(nr + 1, &at));
  for (PetscInt e = 0; e < nback; e++) (*offset)[(PetscInt)back[record * e] + 1]++;
  for (PetscInt i = 0; i < nr; i++) {
    (*offset)[i + 1] += (*offset)[i];
    at[i] = (*offset)[i];
  }
  for (PetscInt e = 0; e < nback; e++) { /* by region, then by key */
    const PetscReal *rec = &back[record * e];
    Keyed           *o   = &order[at[(PetscInt)rec[0]]++];

    for (PetscInt k = 0; k < 3; k++) o->key[k] = (PetscInt)rec[2 + k];
    o->at = e;
  }
  for (PetscInt i = 0; i < nr; i++) qsort(&order[(*offset)[i]], (size_t)((*offset)[i + 1] - (*offset)[i]), sizeof(Keyed), CompareKeyed);
  for (PetscInt e = 0; e < nback; e++) UnpackHit(search->m, &back[record * order[e].at], &(*hit)[e], &(*data)[search->m * e]);
  PetscCall(PetscFree(at));
  PetscCall(PetscFree(order));
  PetscCall(PetscFree(back));
  PetscCall(PetscLogEventEnd(SSSTAR_Search, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/*@C
   SSStarSearchGetSize - the triangles of this rank and of all, and the memory the search holds on this rank

   Not Collective

   Input Parameter:
.  search - the search

   Output Parameters:
+  n     - the triangles on this rank, or pass NULL
.  N     - on all ranks, or pass NULL
-  bytes - the memory of this rank's tree, keys, data and the boxes of every rank, or pass NULL

   Level: developer

.seealso: `SSStarSearchCreate()`, `SSStarTreeGetSize()`
@*/
PetscErrorCode SSStarSearchGetSize(SSStarSearch search, PetscInt *n, PetscInt *N, size_t *bytes)
{
  size_t tree;

  PetscFunctionBegin;
  if (n) *n = search->n;
  if (N) *N = search->N;
  PetscCall(SSStarTreeGetSize(search->tree, NULL, NULL, &tree));
  if (bytes) *bytes = sizeof(*search) + tree + (size_t)search->n * (3 * sizeof(PetscInt) + search->m * sizeof(PetscReal)) + (size_t)(search->size + 1) * sizeof(PetscInt) + (size_t)(6 * search->boxStart[search->size]) * sizeof(PetscReal);
  PetscFunctionReturn(0);
}

/* Parts first .. first + parts - 1 for the triangles idx: halves of the parts get shares of the triangles split at the
   matching quantile of their centroids along the longest extent */
static PetscErrorCode Bisect(PetscInt n, PetscInt idx[], const PetscReal centroid[], PetscMPIInt first, PetscMPIInt parts, PetscMPIInt part[], PetscReal work[])
{
  PetscReal      lo[3] = {PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL}, hi[3] = {PETSC_MIN_REAL, PETSC_MIN_REAL, PETSC_MIN_REAL};
  PetscInt       axis = 0, nl;
  PetscMPIInt    left = parts / 2;

  PetscFunctionBegin;
  if (parts == 1 || n == 0) {
    for (PetscInt j = 0; j < n; j++) part[idx[j]] = first;
    PetscFunctionReturn(0);
  }
  for (PetscInt j = 0; j < n; j++)
    for (PetscInt k = 0; k < 3; k++) {
      lo[k] = PetscMin(lo[k], centroid[3 * idx[j] + k]);
      hi[k] = PetscMax(hi[k], centroid[3 * idx[j] + k]);
    }
  for (PetscInt k = 1; k < 3; k++)
    if (hi[k] - lo[k] > hi[axis] - lo[axis]) axis = k;
  for (PetscInt j = 0; j < n; j++) work[j] = centroid[3 * idx[j] + axis];
  PetscCall(PetscSortRealWithArrayInt(n, work, idx));
  nl = (PetscInt)(((PetscInt64)n * left) / parts);
  PetscCall(Bisect(nl, idx, centroid, first, left, part, work));
  PetscCall(Bisect(n - nl, idx + nl, centroid, first + left, parts - left, part, work));
  PetscFunctionReturn(0);
}

/*@C
   SSStarTrianglesPartition - parts of about equal size of a set of triangles, each compact in space: recursive
   coordinate bisection of their centroids

   Not Collective

   Input Parameters:
+  n     - the number of triangles
.  x     - their vertices, 9 per triangle
-  parts - the number of parts

   Output Parameter:
.  part - the part of each triangle, 0 .. parts - 1

   Notes:
   The parts are split in two halves, and the triangles at the matching quantile of their centroids along the
   centroids' longest extent, until one part is left: part sizes differ by at most one per level. Hand the triangles
   of part r to rank r for an SSStarSearchCreate() whose ranks' boxes overlap little.

   Level: developer

.seealso: `SSStarSearchCreate()`
@*/
PetscErrorCode SSStarTrianglesPartition(PetscInt n, const PetscReal x[], PetscMPIInt parts, PetscMPIInt part[])
{
  PetscInt  *idx;
  PetscReal *centroid, *work;

  PetscFunctionBegin;
  PetscCheck(parts >= 1, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "The number of parts %d must be positive", parts);
  PetscCall(PetscMalloc3(n + 1, &idx, 3 * n + 1, &centroid, n + 1, &work));
  for (PetscInt t = 0; t < n; t++) {
    idx[t] = t;
    for (PetscInt k = 0; k < 3; k++) centroid[3 * t + k] = (x[9 * t + k] + x[9 * t + 3 + k] + x[9 * t + 6 + k]) / 3;
  }
  PetscCall(Bisect(n, idx, centroid, 0, parts, part, work));
  PetscCall(PetscFree3(idx, centroid, work));
  PetscFunctionReturn(0);
}
