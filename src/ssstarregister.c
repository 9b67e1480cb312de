/*
   Package registration: linked use (SSStarInitializePackage) and -dll_append (PetscDLLibraryRegister_ssstar). The
   registration file of ssstar: the SNES type, the friction laws, the reductions and the Newton steps (one register-all
   function per family), the log events.
*/
#include "snes/impls/ssstar/ssstarimpl.h"
#include "snes/impls/ssstar/laws/lawimpl.h"
#include "reduction/reductionimpl.h"
#include <ssstarscene.h>

PETSC_EXTERN PetscErrorCode SNESCreate_SSStar(SNES);

PetscLogEvent SSSTAR_ApproxStep, SSSTAR_NewtonStep, SSSTAR_LineSearch;
PetscLogEvent SSSTAR_NewtonAssemble, SSSTAR_NewtonFactor, SSSTAR_NewtonKrylov;
PetscLogEvent SSSTAR_Mesh, SSSTAR_Assembly, SSSTAR_Output, SSSTAR_Schur, SSSTAR_Recovery;
PetscLogEvent SSSTAR_MeshGmsh, SSSTAR_MeshCache, SSSTAR_MeshBuild, SSSTAR_MeshFaces, SSSTAR_MeshLabel;
PetscLogEvent SSSTAR_SchurOrdering, SSSTAR_SchurAnalysis, SSSTAR_SchurFactor, SSSTAR_SchurScatter;
PetscLogEvent SSSTAR_Search;

static PetscBool SSStarPackageInitialized = PETSC_FALSE;

/*@C
   SSStarFinalizePackage - called by PetscFinalize(): empties the tables of laws, reductions and Newton steps; the next
   SSStarInitializePackage() registers again

   Not Collective

   Level: developer

.seealso: `SSStarInitializePackage()`
@*/
PetscErrorCode SSStarFinalizePackage(void)
{
  PetscFunctionBegin;
  PetscCall(SSStarLawDestroyAll());
  PetscCall(PetscFunctionListDestroy(&SSStarReductionList));
  PetscCall(PetscFunctionListDestroy(&SSStarNewtonList));
  SSStarLawRegisterAllCalled       = PETSC_FALSE;
  SSStarReductionRegisterAllCalled = PETSC_FALSE;
  SSStarNewtonRegisterAllCalled    = PETSC_FALSE;
  SSStarPackageInitialized         = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/*@C
   SSStarGetVersionNumber - the version of the ssstar library at hand (SSSTAR_VERSION_MAJOR, _MINOR, _SUBMINOR of the
   ssstar.h it was built with), for a program that loads it at run time (the Python module checks it against its own)

   Not Collective

   Output Parameters:
+  major    - the major version, or pass NULL
.  minor    - the minor version, or pass NULL
-  subminor - the subminor version, or pass NULL

   Level: beginner

.seealso: `SSStarInitializePackage()`
@*/
PetscErrorCode SSStarGetVersionNumber(PetscInt *major, PetscInt *minor, PetscInt *subminor)
{
  PetscFunctionBegin;
  if (major) *major = SSSTAR_VERSION_MAJOR;
  if (minor) *minor = SSSTAR_VERSION_MINOR;
  if (subminor) *subminor = SSSTAR_VERSION_SUBMINOR;
  PetscFunctionReturn(0);
}

/*@C
   SSStarInitializePackage - registers the SNES type "ssstar" (SNESSSSTAR), its friction laws (SSStarLawRegisterAll()),
   reductions (SSStarReductionRegisterAll()) and Newton steps, and the log events of ssstar

   Not Collective

   Notes:
   A program linked with libssstar calls it after PetscInitialize(); with -dll_append /path/libssstar.so PETSc calls
   it (through PetscDLLibraryRegister_ssstar()). Calling it again does nothing; PetscFinalize() undoes it.

   Level: beginner

.seealso: `SSStarFinalizePackage()`, `SNESSetType()`
@*/
PetscErrorCode SSStarInitializePackage(void)
{
  PetscFunctionBegin;
  if (SSStarPackageInitialized) PetscFunctionReturn(0);
  SSStarPackageInitialized = PETSC_TRUE;
  PetscCall(SNESInitializePackage());
  PetscCall(SNESRegister(SNESSSSTAR, SNESCreate_SSStar));
  PetscCall(SSStarLawRegisterAll());
  PetscCall(SSStarReductionRegisterAll());
  PetscCall(SSStarNewtonRegisterAll());
  PetscCall(PetscLogEventRegister("SSStarAS", SNES_CLASSID, &SSSTAR_ApproxStep));
  PetscCall(PetscLogEventRegister("SSStarNS", SNES_CLASSID, &SSSTAR_NewtonStep));
  PetscCall(PetscLogEventRegister("SSStarLS", SNES_CLASSID, &SSSTAR_LineSearch));
  PetscCall(PetscLogEventRegister("SSStarNSAssemble", SNES_CLASSID, &SSSTAR_NewtonAssemble));
  PetscCall(PetscLogEventRegister("SSStarNSFactor", SNES_CLASSID, &SSSTAR_NewtonFactor));
  PetscCall(PetscLogEventRegister("SSStarNSKrylov", SNES_CLASSID, &SSSTAR_NewtonKrylov));
  PetscCall(PetscLogEventRegister("SSStarMesh", DM_CLASSID, &SSSTAR_Mesh));
  PetscCall(PetscLogEventRegister("SSStarMeshGmsh", DM_CLASSID, &SSSTAR_MeshGmsh));
  PetscCall(PetscLogEventRegister("SSStarMeshCache", DM_CLASSID, &SSSTAR_MeshCache));
  PetscCall(PetscLogEventRegister("SSStarMeshBuild", DM_CLASSID, &SSSTAR_MeshBuild));
  PetscCall(PetscLogEventRegister("SSStarMeshFaces", DM_CLASSID, &SSSTAR_MeshFaces));
  PetscCall(PetscLogEventRegister("SSStarMeshLabel", DM_CLASSID, &SSSTAR_MeshLabel));
  PetscCall(PetscLogEventRegister("SSStarAssembly", DM_CLASSID, &SSSTAR_Assembly));
  PetscCall(PetscLogEventRegister("SSStarOutput", DM_CLASSID, &SSSTAR_Output));
  PetscCall(PetscLogEventRegister("SSStarSearch", DM_CLASSID, &SSSTAR_Search));
  PetscCall(PetscLogEventRegister("SSStarSchur", MAT_CLASSID, &SSSTAR_Schur));
  PetscCall(PetscLogEventRegister("SSStarRecovery", MAT_CLASSID, &SSSTAR_Recovery));
  PetscCall(PetscLogEventRegister("SSStarOrdering", MAT_CLASSID, &SSSTAR_SchurOrdering));
  PetscCall(PetscLogEventRegister("SSStarAnalysis", MAT_CLASSID, &SSSTAR_SchurAnalysis));
  PetscCall(PetscLogEventRegister("SSStarFactor", MAT_CLASSID, &SSSTAR_SchurFactor));
  PetscCall(PetscLogEventRegister("SSStarSchurScat", MAT_CLASSID, &SSSTAR_SchurScatter));
  PetscCall(PetscRegisterFinalize(SSStarFinalizePackage));
  PetscFunctionReturn(0);
}

#if defined(PETSC_HAVE_DYNAMIC_LIBRARIES)
/* Called by PETSc when the library is loaded with -dll_append <dir>/libssstar.so */
PETSC_EXTERN PetscErrorCode PetscDLLibraryRegister_ssstar(void)
{
  PetscFunctionBegin;
  PetscCall(SSStarInitializePackage());
  PetscFunctionReturn(0);
}
#endif
