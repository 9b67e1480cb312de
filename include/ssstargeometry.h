#ifndef SSSTARGEOMETRY_H
#define SSSTARGEOMETRY_H

/*
   Geometry the scenes share (src/geometry/): 3-vectors, the closest point of a triangle, triangle normals and
   bounding boxes, and the pseudo-normals of a triangulated surface with the checks that make its inside and outside
   well defined. Rigid mesh obstacles, contact pairs and the output use it; a search tree over triangles (issue 18)
   belongs here too (src/geometry/tree.c).
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

#endif
