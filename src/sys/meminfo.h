#ifndef SSSTARMEMINFO_H
#define SSSTARMEMINFO_H

/* What the machine has (src/sys/meminfo.c): the scene's check before the mesh and the reduction's before the factorization read it here */
#include <petscsys.h>

PETSC_INTERN PetscErrorCode SSStarMemAvailable(PetscLogDouble *);
/* "0.233 GB per rank" (the largest rank's resident memory), with -ssstar_progress_ranks " (rank 0: 0.231, least: 0.210)" */
PETSC_INTERN PetscErrorCode SSStarMemoryText(MPI_Comm, char[], size_t);

#endif
