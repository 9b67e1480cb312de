/*
   The masters of the contact nodes as their contact sources find them (pairs.c, mortar.c): a growing list of (node,
   master x-dof, weight), which operator.c compresses into the rows of B.
*/
#include "../sceneimpl.h"

/* SSStarMastersAdd - node's row of B gets -weight R at the master vertex whose x-dof is dof */
PetscErrorCode SSStarMastersAdd(SSStarMasters *m, PetscInt node, PetscInt dof, PetscReal weight)
{
  PetscFunctionBegin;
  if (m->n == m->max) {
    m->max = PetscMax(64, 2 * m->max);
    PetscCall(PetscRealloc(m->max * sizeof(PetscInt), &m->node));
    PetscCall(PetscRealloc(m->max * sizeof(PetscInt), &m->dof));
    PetscCall(PetscRealloc(m->max * sizeof(PetscReal), &m->weight));
  }
  m->node[m->n]   = node;
  m->dof[m->n]    = dof;
  m->weight[m->n] = weight;
  m->n++;
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarMastersDestroy(SSStarMasters *m)
{
  PetscFunctionBegin;
  PetscCall(PetscFree(m->node));
  PetscCall(PetscFree(m->dof));
  PetscCall(PetscFree(m->weight));
  m->n = m->max = 0;
  PetscFunctionReturn(0);
}
