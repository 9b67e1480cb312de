#ifndef SSSTARPAIRS_H
#define SSSTARPAIRS_H

/* A contact pair's master triangles (pairs.c), which the dual mortar (mortar.c) integrates the slave faces against */
#include "sceneimpl.h"

/* A master triangle: its vertices, their global x-dofs (-1: held fixed) and file indices, its body, its unit normal out of the master body */
typedef struct {
  PetscReal x[9], n[3];
  PetscInt  dof[3], tag[3], body;
} SSStarMasterTriangle;

PETSC_INTERN PetscErrorCode SSStarMortarRows(SSStarScene, PetscInt, PetscInt, const SSStarMasterTriangle[], PetscReal, PetscBool[], SSStarMasters *);

#endif
