#ifndef SSSTARGEOMETRY_H
#define SSSTARGEOMETRY_H

/*
   Geometry the scenes share (src/geometry/): 3-vectors, the closest point of a triangle, triangle normals and
   bounding boxes, and the pseudo-normals of a triangulated surface with the checks that make its inside and outside
   well defined (triangle.c, surface.c); a bounding-volume tree over triangles (tree.c) and the search over triangles
   spread over the ranks of a communicator, a tree on each (search.c). Rigid mesh obstacles, contact pairs, the dual
   mortar and the output use it.
*/
#include <petscsys.h>

static inline PetscReal SSStarDot3(const PetscReal a[3], const PetscReal b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* c = a x b (c may not alias a or b) */
static inline void SSStarCross3(const PetscReal a[3], const PetscReal b[3], PetscReal c[3])
{
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

/* The feature of a triangle a, b, c a closest point lies on */
typedef enum {
  SSSTAR_TRIANGLE_FACE,
  SSSTAR_TRIANGLE_EDGE_AB,
  SSSTAR_TRIANGLE_EDGE_BC,
  SSSTAR_TRIANGLE_EDGE_CA,
  SSSTAR_TRIANGLE_VERTEX_A,
  SSSTAR_TRIANGLE_VERTEX_B,
  SSSTAR_TRIANGLE_VERTEX_C
} SSStarTriangleFeature;

PETSC_EXTERN void SSStarClosestPointOnTriangle(const PetscReal[3], const PetscReal[3], const PetscReal[3], const PetscReal[3], PetscReal[3], PetscReal[3], SSStarTriangleFeature *);
PETSC_EXTERN PetscReal SSStarTriangleNormal(const PetscReal[3], const PetscReal[3], const PetscReal[3], PetscReal[3]);
PETSC_EXTERN void SSStarTriangleBox(const PetscReal[3], const PetscReal[3], const PetscReal[3], PetscReal[6]);
PETSC_EXTERN PetscReal SSStarBoxDistance2(const PetscReal[3], const PetscReal[6]);

/* What makes a triangulated surface unfit to bound a body (SSStarSurfacePseudoNormals()) */
typedef enum {
  SSSTAR_SURFACE_OK,
  SSSTAR_SURFACE_ZERO_AREA,     /* triangle[0] has zero area                                          */
  SSSTAR_SURFACE_NONMANIFOLD,   /* the edge vertex[0]-vertex[1] is shared by count > 2 triangles       */
  SSSTAR_SURFACE_MISORIENTED    /* triangle[0] and triangle[1] run their common edge the same way       */
} SSStarSurfaceDefect;

typedef struct {
  SSStarSurfaceDefect defect;
  PetscInt            triangle[2], vertex[2], count;
} SSStarSurfaceCheck;

PETSC_EXTERN PetscErrorCode SSStarSurfacePseudoNormals(PetscInt, const PetscReal[], PetscInt, const PetscInt[], PetscReal[], SSStarSurfaceCheck *);


/* A region of space: the points y with lo[k] <= axes[k] . (y - origin) <= hi[k], k = 0, 1, 2 (bounds may be infinite);
   SSStarRegionBox() makes the axis-aligned box lo <= y <= hi */
typedef struct {
  PetscReal origin[3], axes[9]; /* axes: three rows, not necessarily unit or orthogonal */
  PetscReal lo[3], hi[3];
} SSStarRegion;

PETSC_EXTERN void SSStarRegionBox(const PetscReal[6], SSStarRegion *);

/* A bounding-volume tree over triangles (src/geometry/tree.c) */
typedef struct _n_SSStarTree *SSStarTree;

PETSC_EXTERN PetscErrorCode SSStarTreeCreate(PetscInt, const PetscReal[], SSStarTree *);
PETSC_EXTERN PetscErrorCode SSStarTreeDestroy(SSStarTree *);
PETSC_EXTERN PetscErrorCode SSStarTreeClosest(SSStarTree, const PetscReal[3], PetscInt *, PetscReal *);
PETSC_EXTERN PetscErrorCode SSStarTreeFindInRegion(SSStarTree, const SSStarRegion *, PetscInt *, const PetscInt *[]);
PETSC_EXTERN PetscErrorCode SSStarTreeGetBoxes(SSStarTree, PetscInt, PetscInt *, PetscReal[]);
PETSC_EXTERN PetscErrorCode SSStarTreeGetSize(SSStarTree, PetscInt *, PetscInt *, size_t *);

/* Triangles spread over the ranks of a communicator, a tree on each rank (src/geometry/search.c) */
typedef struct _n_SSStarSearch *SSStarSearch;

/* A triangle a search found: its vertices and key, and for SSStarSearchClosest() the point's closest point on it */
typedef struct {
  PetscReal             x[9];   /* its vertices a, b, c                                                   */
  PetscInt              key[3]; /* its key (SSStarSearchCreate()); key[0] = -1: no triangle              */
  PetscReal             d2;     /* the squared distance of the point to it                               */
  PetscReal             q[3];   /* the closest point                                                      */
  PetscReal             w[3];   /* its barycentric coordinates                                            */
  SSStarTriangleFeature feature; /* the face, edge or vertex q lies on                                    */
} SSStarSearchHit;

PETSC_EXTERN PetscLogEvent SSSTAR_Search;
PETSC_EXTERN PetscErrorCode SSStarSearchCreate(MPI_Comm, PetscInt, const PetscReal[], const PetscInt[], PetscInt, const PetscReal[], SSStarSearch *);
PETSC_EXTERN PetscErrorCode SSStarSearchDestroy(SSStarSearch *);
PETSC_EXTERN PetscErrorCode SSStarSearchClosest(SSStarSearch, PetscInt, const PetscReal[], PetscReal, SSStarSearchHit[], PetscReal[]);
PETSC_EXTERN PetscErrorCode SSStarSearchFindInRegions(SSStarSearch, PetscInt, const SSStarRegion[], PetscInt *[], SSStarSearchHit *[], PetscReal *[]);
PETSC_EXTERN PetscErrorCode SSStarSearchGetSize(SSStarSearch, PetscInt *, PetscInt *, size_t *);
PETSC_EXTERN PetscErrorCode SSStarTrianglesPartition(PetscInt, const PetscReal[], PetscMPIInt, PetscMPIInt[]);

#endif
