#ifndef SSSTAROBSTACLE_H
#define SSSTAROBSTACLE_H

/*
   The rigid obstacle of a contact group (-obstacle_<G>): a shape registered by name (obstacles/register.c; one file per
   shape in obstacles/), made from the option's value, which gives each contact node its initial gap and the unit
   normal of its frame, and says what it is (obstacle.c).
*/
#include <petscsys.h>

typedef struct _n_SSStarObstacle *SSStarObstacle;

/* Where an obstacle writes what it is: named values (the attributes of an HDF5 group, for the output) */
typedef struct {
  void *ctx;
  PetscErrorCode (*reals)(void *, const char[], PetscInt, const PetscReal[]);
  PetscErrorCode (*integer)(void *, const char[], PetscInt);
  PetscErrorCode (*string)(void *, const char[], const char[]);
} SSStarAttributeWriter;

PETSC_INTERN PetscErrorCode SSStarObstacleCreateFromString(MPI_Comm, const char[], const char[], SSStarObstacle *);
PETSC_INTERN PetscErrorCode SSStarObstacleCreateDefault(SSStarObstacle *);
PETSC_INTERN PetscErrorCode SSStarObstacleHelp(char[], size_t);
PETSC_INTERN PetscErrorCode SSStarObstacleDestroy(SSStarObstacle *);
PETSC_INTERN PetscErrorCode SSStarObstacleGaps(SSStarObstacle, PetscInt, const PetscReal[], PetscReal, PetscReal[], PetscReal[]);
PETSC_INTERN PetscErrorCode SSStarObstacleDescribe(SSStarObstacle, char[], size_t);
PETSC_INTERN PetscErrorCode SSStarObstacleWriteAttributes(SSStarObstacle, SSStarAttributeWriter *);
PETSC_INTERN const char    *SSStarObstacleInsideHint(SSStarObstacle);
PETSC_INTERN void           SSStarObstacleReferencePoint(SSStarObstacle, PetscReal[3]);

#endif
