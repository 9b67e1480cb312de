/* The implementations of the Newton step: one line per implementation (one file each, newtonimpl.h) */
#include "newtonimpl.h"

PetscBool SSStarNewtonRegisterAllCalled = PETSC_FALSE;

/* Registers dense, sparse and wholebody (SSStarInitializePackage() calls it) */
PetscErrorCode SSStarNewtonRegisterAll(void)
{
  PetscFunctionBegin;
  if (SSStarNewtonRegisterAllCalled) PetscFunctionReturn(0);
  SSStarNewtonRegisterAllCalled = PETSC_TRUE;
  PetscCall(SSStarNewtonRegister(SSSTARNEWTONDENSE, SSStarNewtonCreate_Dense));
  PetscCall(SSStarNewtonRegister(SSSTARNEWTONSPARSE, SSStarNewtonCreate_Sparse));
  PetscCall(SSStarNewtonRegister(SSSTARNEWTONWHOLEBODY, SSStarNewtonCreate_WholeBody));
  PetscFunctionReturn(0);
}
