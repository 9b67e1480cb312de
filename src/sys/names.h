#ifndef SSSTARNAMES_H
#define SSSTARNAMES_H

/* Misspelt names (src/sys/names.c): the unknown options (src/options.c) and groups (src/scene/sceneoptions.c) are
   refused with the nearest known name by this distance */
#include <petscsys.h>

PETSC_INTERN PetscInt SSStarNameDistance(const char[], size_t, const char[], size_t);

#endif
