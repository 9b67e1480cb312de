/* The friction laws of ssstar: one line per law (one file per law in this folder). Their order is their index. */
#include "lawimpl.h"

PetscBool SSStarLawRegisterAllCalled = PETSC_FALSE;

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
  PetscCall(SSStarLawRegister(SSSTARLAWNONE, SSStarLawCreate_None));
  PetscCall(SSStarLawRegister(SSSTARLAWTRESCA, SSStarLawCreate_Tresca));
  PetscCall(SSStarLawRegister(SSSTARLAWCOULOMB, SSStarLawCreate_Coulomb));
  PetscCall(SSStarLawRegister(SSSTARLAWORTHOTROPIC, SSStarLawCreate_Orthotropic));
  PetscFunctionReturn(0);
}
