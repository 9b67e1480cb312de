/* The node an error is about, found on some rank and reported by every rank (nodes.c, prescribed.c, ...) */
#include "sceneimpl.h"

/* SSStarSceneShareBadNode - the node an error is about: the owner's data reach every rank (the lowest file index wins) */
PetscErrorCode SSStarSceneShareBadNode(MPI_Comm comm, SSStarBadNode *bad, PetscBool *found)
{
  PetscInt  tag = bad->tag >= 0 ? bad->tag : PETSC_MAX_INT, first;
  PetscReal data[7];

  PetscFunctionBegin;
  PetscCall(MPIU_Allreduce(&tag, &first, 1, MPIU_INT, MPI_MIN, comm));
  *found = (PetscBool)(first != PETSC_MAX_INT);
  if (!*found) PetscFunctionReturn(0);
  for (PetscInt k = 0; k < 7; k++) data[k] = 0;
  if (tag == first) {
    data[0] = (PetscReal)bad->group;
    data[1] = (PetscReal)bad->other;
    data[2] = bad->x[0];
    data[3] = bad->x[1];
    data[4] = bad->x[2];
    data[5] = bad->gap;
    data[6] = 1;
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, data, 7, MPIU_REAL, MPIU_SUM, comm));
  bad->tag   = first;
  bad->group = (PetscInt)(data[0] / data[6]);
  bad->other = (PetscInt)(data[1] / data[6]);
  for (PetscInt k = 0; k < 3; k++) bad->x[k] = data[2 + k] / data[6];
  bad->gap = data[5] / data[6];
  PetscFunctionReturn(0);
}
