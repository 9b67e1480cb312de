/*
   No reduction: the contact problem stays on the whole body (the SNES's whole-body Newton step), P is never formed.
   The operator is K itself, the load F itself, and the iterate is already the whole displacement.
*/
#include "reductionimpl.h"

static PetscErrorCode SSStarReductionReduceLoad_None(SSStarReduction red, Vec F, Vec f)
{
  PetscFunctionBegin;
  PetscCall(VecCopy(F, f));
  PetscFunctionReturn(0);
}

static PetscErrorCode SSStarReductionRecover_None(SSStarReduction red, Vec F, Vec uC, Vec rC, Vec u)
{
  PetscFunctionBegin;
  PetscCall(VecCopy(uC, u));
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarReductionCreate_None(SSStarReduction red, Mat K)
{
  PetscFunctionBegin;
  red->ops.reduceload = SSStarReductionReduceLoad_None;
  red->ops.recover    = SSStarReductionRecover_None;
  red->wholeBody      = PETSC_TRUE;
  PetscCall(PetscObjectReference((PetscObject)K));
  red->P = K;
  PetscFunctionReturn(0);
}
