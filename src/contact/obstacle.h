#ifndef SSSTAROBSTACLE_H
#define SSSTAROBSTACLE_H

#include <petscsys.h>

/* The rigid obstacle of a contact group (-obstacle_<G>): its shape, and for a mesh its triangles */
typedef enum {
  SSSTAR_OBSTACLE_PLANE,
  SSSTAR_OBSTACLE_SPHERE,
  SSSTAR_OBSTACLE_CYLINDER,
  SSSTAR_OBSTACLE_MESH
} SSStarObstacleType;

typedef struct {
  SSStarObstacleType type;
  PetscReal          point[3];  /* plane: a point on it; sphere: the centre; cylinder: a point of the axis   */
  PetscReal          dir[3];    /* plane: the unit normal into the body; cylinder: the unit axis direction   */
  PetscReal          radius;    /* sphere, cylinder                                                          */
  char               file[PETSC_MAX_PATH_LEN]; /* mesh: the gmsh file                                      */
  PetscInt           nv, nt;    /* mesh: vertices, triangles                                                 */
  PetscReal         *xv;        /* mesh: 3 per vertex                                                        */
  PetscInt          *tri;       /* mesh: 3 vertex indices per triangle, counterclockwise seen from outside   */
  PetscReal         *pn;        /* mesh: pseudo-normals, 7 x 3 per triangle: face, edges 01 12 20, vertices  */
  PetscReal         *box;       /* mesh: bounding box per triangle, 6                                        */
} SSStarObstacle;

PETSC_INTERN PetscErrorCode SSStarObstacleSetFromString(MPI_Comm, const char[], const char[], SSStarObstacle *);
PETSC_INTERN PetscErrorCode SSStarObstacleReset(SSStarObstacle *);
PETSC_INTERN PetscErrorCode SSStarObstacleGap(const SSStarObstacle *, const PetscReal[3], PetscReal, PetscReal *, PetscReal[3]);
PETSC_INTERN PetscErrorCode SSStarObstacleDescribe(const SSStarObstacle *, char[], size_t);
PETSC_INTERN const char    *SSStarObstacleInsideHint(const SSStarObstacle *);

#endif
