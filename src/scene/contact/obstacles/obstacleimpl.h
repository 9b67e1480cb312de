#ifndef SSSTAROBSTACLEIMPL_H
#define SSSTAROBSTACLEIMPL_H

/* What a shape of rigid obstacle implements (obstacles/<shape>.c), the registry (obstacles/register.c) and the
   helpers the shapes share (obstacles/numbers.c) */
#include "obstacle.h"
#include <ssstargeometry.h>

typedef struct {
  /* reads the shape from numbers, the value of option after "<shape>:" (spec: the whole value, for messages) */
  PetscErrorCode (*setfromstring)(SSStarObstacle, MPI_Comm, const char option[], const char spec[], const char numbers[]);
  /* the signed distance of x (positive outside), the unit normal out of the obstacle; tol: x on the surface */
  PetscErrorCode (*gap)(SSStarObstacle, const PetscReal x[3], PetscReal tol, PetscReal *gap, PetscReal n[3]);
  /* the same for n points at once, collective: a shape whose data are spread over the ranks sets it instead of gap */
  PetscErrorCode (*gaps)(SSStarObstacle, PetscInt n, const PetscReal x[], PetscReal tol, PetscReal gap[], PetscReal normal[]);
  PetscErrorCode (*describe)(SSStarObstacle, char text[], size_t len);
  PetscErrorCode (*attributes)(SSStarObstacle, SSStarAttributeWriter *);
  PetscErrorCode (*destroy)(SSStarObstacle);
  const char *insideHint; /* what to check when a node starts inside the obstacle */
} SSStarObstacleOps;

struct _n_SSStarObstacle {
  char              type[32];
  SSStarObstacleOps ops;
  void             *data;
  PetscReal         reference[3]; /* the point it turns about (-obstacle_<G>_rotation): set by its setfromstring */
};

PETSC_INTERN PetscErrorCode SSStarObstacleRegister(const char[], const char[], PetscErrorCode (*)(SSStarObstacle));
PETSC_INTERN PetscErrorCode SSStarObstacleFind(const char[], PetscErrorCode (**)(SSStarObstacle));
PETSC_INTERN PetscErrorCode SSStarObstacleForms(const char **, const char **);
PETSC_INTERN PetscErrorCode SSStarObstacleParseNumbers(MPI_Comm, const char[], const char[], const char[], PetscInt, const char[], PetscReal[]);
PETSC_INTERN PetscErrorCode SSStarObstacleUnitVector(MPI_Comm, const char[], const char[], const char[], const PetscReal[3], PetscReal[3]);

#endif
