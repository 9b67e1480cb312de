/*
   A bounding-volume tree over triangles (include/ssstargeometry.h): each node's box holds its triangles, split in two
   halves at the median of their centroids along the longest extent of the centroids, down to leaves of at most
   LEAF_SIZE triangles. It answers the triangle closest to a point (SSStarTreeClosest(): the triangle a loop over all
   of them finds) and the triangles whose bounding box in a region's frame meets the region (SSStarTreeFindInRegion()).
   The search over the ranks (search.c) builds one on each rank.
*/
#include "geometryimpl.h"

#define LEAF_SIZE 4
#define MAX_DEPTH 128 /* the depth is log2(n / LEAF_SIZE) + 1; a stack of this many entries holds any traversal */

/*@C
   SSStarRegionBox - the region of an axis-aligned box

   Not Collective

   Input Parameter:
.  box - its lower corner (3) and upper corner (3)

   Output Parameter:
.  r - the region: origin 0, the coordinate axes, the box's bounds

   Level: developer

.seealso: `SSStarTreeFindInRegion()`, `SSStarSearchFindInRegions()`
@*/
void SSStarRegionBox(const PetscReal box[6], SSStarRegion *r)
{
  for (PetscInt k = 0; k < 3; k++) {
    r->origin[k] = 0;
    r->lo[k]     = box[k];
    r->hi[k]     = box[3 + k];
    for (PetscInt c = 0; c < 3; c++) r->axes[3 * k + c] = k == c ? 1 : 0;
  }
}

/*
   Whether the triangle's bounding box in the region's frame meets the region: its vertices' coordinates along each
   axis, measured from the origin, overlap [lo, hi]. The arithmetic of the dual mortar's overlap test (mortar.c), so
   that both decide alike.
*/
static PetscBool TriangleMeetsRegion(const PetscReal x[9], const SSStarRegion *r)
{
  for (PetscInt a = 0; a < 3; a++) {
    const PetscReal *e  = &r->axes[3 * a];
    PetscReal        lo = PETSC_MAX_REAL, hi = PETSC_MIN_REAL;

    for (PetscInt k = 0; k < 3; k++) {
      PetscReal v = 0;

      for (PetscInt c = 0; c < 3; c++) v += (x[3 * k + c] - r->origin[c]) * e[c];
      lo = PetscMin(lo, v);
      hi = PetscMax(hi, v);
    }
    if (lo > r->hi[a] || hi < r->lo[a]) return PETSC_FALSE;
  }
  return PETSC_TRUE;
}

/* Whether a box may hold a triangle that meets the region: the box's extent along each axis, widened by round-off */
PetscBool SSStarBoxMeetsRegion(const PetscReal box[6], const SSStarRegion *r, PetscReal scale)
{
  PetscReal reach = PetscMax(scale, PetscMax(PetscAbsReal(r->origin[0]), PetscMax(PetscAbsReal(r->origin[1]), PetscAbsReal(r->origin[2]))));

  for (PetscInt a = 0; a < 3; a++) {
    const PetscReal *e      = &r->axes[3 * a];
    PetscReal        centre = 0, radius = 0, h;

    for (PetscInt c = 0; c < 3; c++) {
      centre += ((box[c] + box[3 + c]) / 2 - r->origin[c]) * e[c];
      radius += PetscAbsReal(e[c]) * (box[3 + c] - box[c]) / 2;
    }
    h = SSSTAR_ROUNDOFF * (PetscAbsReal(e[0]) + PetscAbsReal(e[1]) + PetscAbsReal(e[2])) * 2 * reach;
    if (centre - radius > r->hi[a] + h || centre + radius < r->lo[a] - h) return PETSC_FALSE;
  }
  return PETSC_TRUE;
}

/* The squared distance from p to the farthest point of a box: no triangle in the box is farther */
PetscReal SSStarBoxFarthest2(const PetscReal p[3], const PetscReal box[6])
{
  PetscReal d2 = 0;

  for (PetscInt k = 0; k < 3; k++) d2 += PetscSqr(PetscMax(PetscAbsReal(p[k] - box[k]), PetscAbsReal(p[k] - box[3 + k])));
  return d2;
}

static void TriangleBoxUnion(const PetscReal x[9], PetscReal box[6])
{
  PetscReal tb[6];

  SSStarTriangleBox(&x[0], &x[3], &x[6], tb);
  for (PetscInt k = 0; k < 3; k++) {
    box[k]     = PetscMin(box[k], tb[k]);
    box[3 + k] = PetscMax(box[3 + k], tb[3 + k]);
  }
}

/* Node i over perm[start .. start + count - 1]: its box; split at the median centroid along their longest extent */
static PetscErrorCode Build(SSStarTree tree, PetscInt i, PetscInt start, PetscInt count, const PetscReal centroid[], PetscReal work[])
{
  SSStarTreeNode *node = &tree->node[i];
  PetscReal       clo[3] = {PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL}, chi[3] = {PETSC_MIN_REAL, PETSC_MIN_REAL, PETSC_MIN_REAL};
  PetscInt        axis = 0, half = count / 2, child;

  PetscFunctionBegin;
  for (PetscInt k = 0; k < 3; k++) {
    node->box[k]     = PETSC_MAX_REAL;
    node->box[3 + k] = PETSC_MIN_REAL;
  }
  for (PetscInt j = start; j < start + count; j++) {
    const PetscReal *c = &centroid[3 * tree->perm[j]];

    TriangleBoxUnion(&tree->x[9 * tree->perm[j]], node->box);
    for (PetscInt k = 0; k < 3; k++) {
      clo[k] = PetscMin(clo[k], c[k]);
      chi[k] = PetscMax(chi[k], c[k]);
    }
  }
  if (count <= LEAF_SIZE) {
    node->start = start;
    node->count = count;
    PetscFunctionReturn(0);
  }
  for (PetscInt k = 1; k < 3; k++)
    if (chi[k] - clo[k] > chi[axis] - clo[axis]) axis = k;
  for (PetscInt j = 0; j < count; j++) work[j] = centroid[3 * tree->perm[start + j] + axis];
  PetscCall(PetscSortRealWithArrayInt(count, work, &tree->perm[start]));
  child = tree->nnodes;
  tree->nnodes += 2;
  node->start = child;
  node->count = 0;
  PetscCall(Build(tree, child, start, half, centroid, work));
  PetscCall(Build(tree, child + 1, start + half, count - half, centroid, work));
  PetscFunctionReturn(0);
}

/*@C
   SSStarTreeCreate - a bounding-volume tree over triangles

   Not Collective

   Input Parameters:
+  n - the number of triangles
-  x - their vertices, 9 per triangle (a, b, c); copied

   Output Parameter:
.  tree - the tree

   Notes:
   Each node's box is the union of its triangles' boxes; a node splits its triangles in two halves at the median of
   their centroids along the longest extent of the centroids, down to leaves of at most 4 triangles, so the depth is
   about log2(n/4) whatever the triangles (degenerate, repeated or all alike). Triangles are numbered 0 .. n-1 in the
   order given.

   Level: developer

.seealso: `SSStarTreeClosest()`, `SSStarTreeFindInRegion()`, `SSStarTreeDestroy()`, `SSStarSearchCreate()`
@*/
PetscErrorCode SSStarTreeCreate(PetscInt n, const PetscReal x[], SSStarTree *tree)
{
  SSStarTree t;
  PetscReal *centroid, *work;

  PetscFunctionBegin;
  PetscCheck(n >= 0, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "The number of triangles %" PetscInt_FMT " is negative", n);
  PetscCall(PetscNew(&t));
  t->n = n;
  PetscCall(PetscMalloc1(9 * n + 1, &t->x));
  PetscCall(PetscArraycpy(t->x, x, 9 * n));
  PetscCall(PetscMalloc1(n + 1, &t->perm));
  PetscCall(PetscMalloc1(2 * n + 1, &t->node));
  PetscCall(PetscMalloc2(3 * n + 1, &centroid, n + 1, &work));
  for (PetscInt i = 0; i < n; i++) {
    t->perm[i] = i;
    for (PetscInt k = 0; k < 3; k++) centroid[3 * i + k] = (x[9 * i + k] + x[9 * i + 3 + k] + x[9 * i + 6 + k]) / 3;
  }
  for (PetscInt i = 0; i < 9 * n; i++) t->scale = PetscMax(t->scale, PetscAbsReal(x[i]));
  if (n > 0) {
    t->nnodes = 1;
    PetscCall(Build(t, 0, 0, n, centroid, work));
    PetscCall(PetscRealloc(t->nnodes * sizeof(SSStarTreeNode), &t->node)); /* fewer than n of the 2 n reserved */
  }
  PetscCall(PetscFree2(centroid, work));
  *tree = t;
  PetscFunctionReturn(0);
}

/*@C
   SSStarTreeDestroy - frees a tree

   Not Collective

   Input Parameter:
.  tree - the tree

   Level: developer

.seealso: `SSStarTreeCreate()`
@*/
PetscErrorCode SSStarTreeDestroy(SSStarTree *tree)
{
  PetscFunctionBegin;
  if (!*tree) PetscFunctionReturn(0);
  PetscCall(PetscFree((*tree)->x));
  PetscCall(PetscFree((*tree)->perm));
  PetscCall(PetscFree((*tree)->node));
  PetscCall(PetscFree((*tree)->found));
  PetscCall(PetscFree(*tree));
  PetscFunctionReturn(0);
}

/*@C
   SSStarTreeClosest - the triangle closest to a point

   Not Collective

   Input Parameters:
+  tree - the tree
-  p    - the point

   Output Parameters:
+  t  - the closest triangle (-1 for a tree without triangles)
-  d2 - its squared distance to p (PETSC_MAX_REAL for a tree without triangles)

   Notes:
   The distance of each triangle is that of its closest point q of SSStarClosestPointOnTriangle(),
   d2 = (p0 - q0)^2 + (p1 - q1)^2 + (p2 - q2)^2; the answer is the least (d2, t): the triangle a loop over all of them
   in order keeping the first of the smallest d2 finds, bit for bit (ties go to the lowest number). A node is passed
   over only when its box lies farther than the best distance so far by more than round-off (1e-12 of the
   coordinates' magnitude), so that no triangle the loop would choose is pruned.

   Level: developer

.seealso: `SSStarTreeCreate()`, `SSStarClosestPointOnTriangle()`, `SSStarSearchClosest()`
@*/
PetscErrorCode SSStarTreeClosest(SSStarTree tree, const PetscReal p[3], PetscInt *t, PetscReal *d2)
{
  struct {
    PetscInt  node;
    PetscReal d2;
  } stack[MAX_DEPTH];
  PetscInt  top = 0, best = -1;
  PetscReal best2 = PETSC_MAX_REAL, limit2 = PETSC_MAX_REAL, h;

  PetscFunctionBegin;
  h = SSSTAR_ROUNDOFF * (tree->scale + PetscMax(PetscAbsReal(p[0]), PetscMax(PetscAbsReal(p[1]), PetscAbsReal(p[2]))));
  if (tree->nnodes) {
    stack[0].node = 0;
    stack[0].d2   = SSStarBoxDistance2(p, tree->node[0].box);
    top           = 1;
  }
  while (top > 0) {
    const SSStarTreeNode *node;

    top--;
    if (stack[top].d2 > limit2) continue;
    node = &tree->node[stack[top].node];
    if (node->count) {
      for (PetscInt j = node->start; j < node->start + node->count; j++) {
        const PetscInt   i = tree->perm[j];
        const PetscReal *x = &tree->x[9 * i];
        PetscReal        q[3], e2;

        SSStarClosestPointOnTriangle(p, &x[0], &x[3], &x[6], q, NULL, NULL);
        e2 = PetscSqr(p[0] - q[0]) + PetscSqr(p[1] - q[1]) + PetscSqr(p[2] - q[2]);
        if (e2 < best2 || (e2 == best2 && i < best)) {
          best2  = e2;
          best   = i;
          limit2 = PetscSqr(PetscSqrtReal(best2) + h);
        }
      }
    } else {
      const PetscReal dl = SSStarBoxDistance2(p, tree->node[node->start].box), dr = SSStarBoxDistance2(p, tree->node[node->start + 1].box);
      const PetscInt  near = dl <= dr ? node->start : node->start + 1;

      PetscCheck(top + 2 <= MAX_DEPTH, PETSC_COMM_SELF, PETSC_ERR_PLIB, "The tree is deeper than %d", MAX_DEPTH);
      stack[top].node     = near == node->start ? node->start + 1 : node->start; /* the farther child waits */
      stack[top++].d2     = PetscMax(dl, dr);
      stack[top].node     = near;
      stack[top++].d2     = PetscMin(dl, dr);
    }
  }
  *t  = best;
  *d2 = best2;
  PetscFunctionReturn(0);
}

/*@C
   SSStarTreeFindInRegion - the triangles whose bounding box in a region's frame meets the region

   Not Collective

   Input Parameters:
+  tree   - the tree
-  region - the region (SSStarRegionBox() for an axis-aligned box)

   Output Parameters:
+  n    - the number of triangles found
-  list - the triangles, in increasing order; owned by the tree, valid until its next search

   Notes:
   A triangle is found when, along each of the region's axes e, the coordinates (v - origin) . e of its vertices v
   (computed in that order: x, then y, then z) overlap [lo, hi]: for an axis-aligned box, the triangles whose boxes
   meet it (closed intervals). The same set as a loop over all triangles, bit for bit: a node is passed over only when
   its box misses the region by more than round-off.

   Level: developer

.seealso: `SSStarTreeCreate()`, `SSStarRegionBox()`, `SSStarSearchFindInRegions()`
@*/
PetscErrorCode SSStarTreeFindInRegion(SSStarTree tree, const SSStarRegion *region, PetscInt *n, const PetscInt *list[])
{
  PetscInt stack[MAX_DEPTH], top = 0;

  PetscFunctionBegin;
  tree->nfound = 0;
  if (tree->nnodes) stack[top++] = 0;
  while (top > 0) {
    const SSStarTreeNode *node = &tree->node[stack[--top]];

    if (!SSStarBoxMeetsRegion(node->box, region, tree->scale)) continue;
    if (node->count) {
      for (PetscInt j = node->start; j < node->start + node->count; j++) {
        const PetscInt i = tree->perm[j];

        if (!TriangleMeetsRegion(&tree->x[9 * i], region)) continue;
        if (tree->nfound == tree->maxfound) {
          tree->maxfound = PetscMax(64, 2 * tree->maxfound);
          PetscCall(PetscRealloc(tree->maxfound * sizeof(PetscInt), &tree->found));
        }
        tree->found[tree->nfound++] = i;
      }
    } else {
      PetscCheck(top + 2 <= MAX_DEPTH, PETSC_COMM_SELF, PETSC_ERR_PLIB, "The tree is deeper than %d", MAX_DEPTH);
      stack[top++] = node->start + 1;
      stack[top++] = node->start;
    }
  }
  PetscCall(PetscSortInt(tree->nfound, tree->found));
  *n    = tree->nfound;
  *list = tree->found;
  PetscFunctionReturn(0);
}

/*@C
   SSStarTreeGetBoxes - the boxes of the tree's top nodes: at most max boxes that together hold every triangle

   Not Collective

   Input Parameters:
+  tree - the tree
-  max  - the most boxes wanted (at least 1)

   Output Parameters:
+  nb    - the number of boxes (0 for a tree without triangles)
-  boxes - their lower and upper corners, 6 per box (room for max)

   Notes:
   The nodes of the deepest level of the tree (leaves above it included) that has at most max nodes. Each box holds at
   least one triangle. The search over the ranks tells the other ranks where this rank's triangles are with them.

   Level: developer

.seealso: `SSStarTreeCreate()`, `SSStarSearchCreate()`
@*/
PetscErrorCode SSStarTreeGetBoxes(SSStarTree tree, PetscInt max, PetscInt *nb, PetscReal boxes[])
{
  PetscInt *level, *next, n = 0;

  PetscFunctionBegin;
  PetscCheck(max >= 1, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "At least one box must be wanted, not %" PetscInt_FMT, max);
  PetscCall(PetscMalloc2(max, &level, max, &next));
  if (tree->nnodes) level[n++] = 0;
  for (;;) {
    PetscInt m = 0, inner = 0;

    for (PetscInt j = 0; j < n; j++)
      if (!tree->node[level[j]].count) inner++;
    if (!inner || n + inner > max) break;
    for (PetscInt j = 0; j < n; j++) {
      const SSStarTreeNode *node = &tree->node[level[j]];

      if (node->count) next[m++] = level[j];
      else {
        next[m++] = node->start;
        next[m++] = node->start + 1;
      }
    }
    PetscCall(PetscArraycpy(level, next, m));
    n = m;
  }
  for (PetscInt j = 0; j < n; j++) PetscCall(PetscArraycpy(&boxes[6 * j], tree->node[level[j]].box, 6));
  *nb = n;
  PetscCall(PetscFree2(level, next));
  PetscFunctionReturn(0);
}

/*@C
   SSStarTreeGetSize - the tree's triangles, nodes and memory

   Not Collective

   Input Parameter:
.  tree - the tree

   Output Parameters:
+  n      - the number of triangles, or pass NULL
.  nnodes - the number of nodes, or pass NULL
-  bytes  - the memory it holds (triangles, order, nodes, the answer of its last region search), or pass NULL

   Level: developer

.seealso: `SSStarTreeCreate()`, `SSStarSearchGetSize()`
@*/
PetscErrorCode SSStarTreeGetSize(SSStarTree tree, PetscInt *n, PetscInt *nnodes, size_t *bytes)
{
  PetscFunctionBegin;
  if (n) *n = tree->n;
  if (nnodes) *nnodes = tree->nnodes;
  if (bytes) *bytes = sizeof(*tree) + (size_t)tree->n * (9 * sizeof(PetscReal) + sizeof(PetscInt)) + (size_t)tree->nnodes * sizeof(SSStarTreeNode) + (size_t)tree->maxfound * sizeof(PetscInt);
  PetscFunctionReturn(0);
}
