#ifndef SSSTARGEOMETRYIMPL_H
#define SSSTARGEOMETRYIMPL_H

/* The tree's data (tree.c) and the box tests the tree and the search (search.c) share */
#include <ssstargeometry.h>

/* A node: its box; a leaf (count > 0) holds the triangles perm[start .. start + count - 1], an inner node (count = 0)
   the children start and start + 1 */
typedef struct {
  PetscReal box[6];
  PetscInt  start, count;
} SSStarTreeNode;

struct _n_SSStarTree {
  PetscInt        n;        /* triangles                                                          */
  PetscReal      *x;        /* their vertices, 9 per triangle, in the order given                 */
  PetscInt       *perm;     /* the triangles in leaf order                                        */
  PetscInt        nnodes;
  SSStarTreeNode *node;     /* node 0 is the root                                                 */
  PetscReal       scale;    /* the largest coordinate magnitude: the scale of round-off            */
  PetscInt       *found;    /* SSStarTreeFindInRegion()'s answer, nfound of room maxfound          */
  PetscInt        nfound, maxfound;
};

struct _n_SSStarSearch {
  MPI_Comm    comm;
  PetscMPIInt size, rank;
  SSStarTree  tree;     /* over this rank's triangles, in the order of their keys                    */
  PetscInt    n, N;     /* triangles on this rank, on all                                            */
  PetscInt   *key;      /* 3 per triangle, in the tree's order                                       */
  PetscInt    m;        /* data per triangle                                                         */
  PetscReal  *data;     /* m per triangle, in the tree's order                                       */
  PetscInt   *boxStart; /* size + 1: rank r's top boxes are boxStart[r] .. boxStart[r + 1] - 1        */
  PetscReal  *boxes;    /* 6 per box: where each rank's triangles are (SSStarTreeGetBoxes())          */
  PetscReal   scale;    /* the largest coordinate magnitude on any rank                              */
};

/* How far round-off can move a distance or a projection computed from coordinates of magnitude scale: the box tests
   give way by this much, so that pruning never drops a triangle an exhaustive loop would keep */
#define SSSTAR_ROUNDOFF 1e-12

PETSC_INTERN PetscBool SSStarBoxMeetsRegion(const PetscReal[6], const SSStarRegion *, PetscReal);
PETSC_INTERN PetscReal SSStarBoxFarthest2(const PetscReal[3], const PetscReal[6]);

#endif
