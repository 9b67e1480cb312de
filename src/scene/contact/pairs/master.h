#ifndef SSSTARMASTER_H
#define SSSTARMASTER_H

/*
   The master surface of a contact pair as a search over the ranks (master.c): its triangles, which node-to-surface
   (pairs.c) projects the slave nodes onto and the dual mortar (mortar.c) integrates the slave faces against
*/
#include "../../sceneimpl.h"

/* A master triangle: its vertices, their global x-dofs (-1: held fixed), its unit normal out of the master body */
typedef struct {
  PetscReal x[9], n[3];
  PetscInt  dof[3];
} SSStarMasterTriangle;

#define SSSTAR_MASTER_DATA 6 /* what a master triangle carries in the search: its normal (3), its x-dofs (3) */

/* The master triangle a search found (its data: the normal, the x-dofs) */
static inline void SSStarMasterTriangleFromHit(const SSStarSearchHit *hit, const PetscReal data[], SSStarMasterTriangle *t)
{
  for (PetscInt k = 0; k < 9; k++) t->x[k] = hit->x[k];
  for (PetscInt k = 0; k < 3; k++) {
    t->n[k]   = data[k];
    t->dof[k] = (PetscInt)data[3 + k];
  }
}

PETSC_INTERN PetscErrorCode SSStarMasterSearchCreate(SSStarScene, PetscInt, SSStarSearch *, PetscInt *, PetscInt **);

#endif
