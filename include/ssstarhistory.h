#ifndef SSSTARHISTORY_H
#define SSSTARHISTORY_H

/*
   Load histories (docs/load-paths.md): a vector of a fixed number of components as a piecewise-linear function of
   the pseudo-time t, written in an option's value -- knots "t:v1,v2,v3" separated by ';' with increasing times
   ("0:0,0,0;1:0,0,-1;2:0.8,0,-1"), or a plain vector "v1,v2,v3", a constant -- and the times a load path is solved
   at (-steps: a list of times, or a count of equal steps; by default the knots of every history).
*/
#include <petscsys.h>

typedef struct _n_SSStarHistory *SSStarHistory;

PETSC_EXTERN PetscErrorCode SSStarHistoryCreateFromString(MPI_Comm, const char[], const char[], PetscInt, SSStarHistory *);
PETSC_EXTERN PetscErrorCode SSStarHistoryCreateFromOptions(MPI_Comm, PetscOptions, const char[], PetscInt, SSStarHistory *, PetscBool *);
PETSC_EXTERN PetscErrorCode SSStarHistoryDestroy(SSStarHistory *);
PETSC_EXTERN PetscErrorCode SSStarHistoryEvaluate(SSStarHistory, PetscReal, PetscReal[]);
PETSC_EXTERN PetscErrorCode SSStarHistoryGetKnots(SSStarHistory, PetscInt *, const PetscReal *[], const PetscReal *[]);
PETSC_EXTERN PetscErrorCode SSStarHistoryDescribe(SSStarHistory, char[], size_t);
PETSC_EXTERN PetscErrorCode SSStarHistoryMergeKnots(PetscInt, const SSStarHistory[], PetscInt *, PetscReal *[]);
PETSC_EXTERN PetscErrorCode SSStarHistoryParseSteps(MPI_Comm, const char[], const char[], PetscInt, const PetscReal[], PetscInt *, PetscReal *[]);

#endif
