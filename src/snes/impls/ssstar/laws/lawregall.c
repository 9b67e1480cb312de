/* The friction laws of ssstar: one file per law in this folder, and here its declaration and its registration line.
   Their order is their index. */
#include "lawimpl.h"

PetscBool SSStarLawRegisterAllCalled = PETSC_FALSE;

PETSC_INTERN PetscErrorCode SSStarLawCreate_None(SSStarLaw);
PETSC_INTERN PetscErrorCode SSStarLawCreate_Tresca(SSStarLaw);
PETSC_INTERN PetscErrorCode SSStarLawCreate_Coulomb(SSStarLaw);
PETSC_INTERN PetscErrorCode SSStarLawCreate_Orthotropic(SSStarLaw);

/*@C
   SSStarLawRegisterAll - registers the friction laws of ssstar: none, tresca, coulomb, orthotropic (in this order:
   their indices 0, 1, 2, 3)

   Not Collective

   Notes:
   SSStarInitializePackage() calls it.

   Level: advanced

.seealso: `SSStarLawRegister()`, `SSStarLawGetNames()`
@*/
PetscErrorCode SSStarLawRegisterAll(void)
{
  PetscFunctionBegin;
  if (SSStarLawRegisterAllCalled) PetscFunctionReturn(0);
  SSStarLawRegisterAllCalled = PETSC_TRUE;
  PetscCall(SSStarLawRegister("none", SSStarLawCreate_None));
  PetscCall(SSStarLawRegister("tresca", SSStarLawCreate_Tresca));
  PetscCall(SSStarLawRegister("coulomb", SSStarLawCreate_Coulomb));
  PetscCall(SSStarLawRegister("orthotropic", SSStarLawCreate_Orthotropic));
  PetscFunctionReturn(0);
}
