#ifndef SSSTARMEMINFO_H
#define SSSTARMEMINFO_H

/* What the machine has (src/sys/meminfo.c): the scene's check before the mesh and the reduction's before the factorization read it here */
#include <petscsys.h>

PETSC_INTERN PetscErrorCode SSStarMemAvailable(PetscLogDouble *);

#endif
