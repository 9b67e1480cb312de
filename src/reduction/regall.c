/* The reduction types of ssstar: one line per type (one file per type in this folder). auto is no type: reduction.c
   resolves it to direct or none. */
#include "reductionimpl.h"

PetscBool SSStarReductionRegisterAllCalled = PETSC_FALSE;

/*@C
   SSStarReductionRegisterAll - registers the reduction types of ssstar: direct, mumps, explicit, none

   Not Collective

   Notes:
   SSStarInitializePackage() calls it.

   Level: advanced

.seealso: `SSStarReductionRegister()`, `SSStarReductionSetType()`
@*/
PetscErrorCode SSStarReductionRegisterAll(void)
{
  PetscFunctionBegin;
  if (SSStarReductionRegisterAllCalled) PetscFunctionReturn(0);
  SSStarReductionRegisterAllCalled = PETSC_TRUE;
  PetscCall(SSStarReductionRegister(SSSTARREDUCTIONDIRECT, SSStarReductionCreate_Direct));
  PetscCall(SSStarReductionRegister(SSSTARREDUCTIONMUMPS, SSStarReductionCreate_MUMPS));
  PetscCall(SSStarReductionRegister(SSSTARREDUCTIONEXPLICIT, SSStarReductionCreate_Explicit));
  PetscCall(SSStarReductionRegister(SSSTARREDUCTIONNONE, SSStarReductionCreate_None));
  PetscFunctionReturn(0);
}
