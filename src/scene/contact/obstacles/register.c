/*
   The shapes of rigid obstacles (-obstacle_<G> <shape>:...), registered by name in a PetscFunctionList: each is a file
   obstacles/<shape>.c whose SSStarObstacleCreate_<Shape>() fills an obstacle's ops (obstacleimpl.h).
*/
#include "obstacleimpl.h"

static PetscFunctionList SSStarObstacleList       = NULL;
static PetscBool         SSStarObstacleRegistered = PETSC_FALSE;
static char              SSStarObstacleFormList[1024]; /* "plane:..., sphere:... or mesh:FILE.msh", for the refusal */
static PetscInt          SSStarObstacleCount = 0;
static char              SSStarObstacleLastForm[256];

static PetscErrorCode SSStarObstacleFinalize(void)
{
  PetscFunctionBegin;
  PetscCall(PetscFunctionListDestroy(&SSStarObstacleList));
  SSStarObstacleRegistered = PETSC_FALSE;
  SSStarObstacleCount      = 0;
  SSStarObstacleFormList[0] = 0;
  PetscFunctionReturn(0);
}

/*
   SSStarObstacleRegister - adds a shape: name (the prefix of -obstacle_<G> name:...), form (how its value reads, for
   the messages) and the function that sets an obstacle's ops
*/
PetscErrorCode SSStarObstacleRegister(const char name[], const char form[], PetscErrorCode (*create)(SSStarObstacle))
{
  PetscFunctionBegin;
  PetscCall(PetscFunctionListAdd(&SSStarObstacleList, name, create));
  if (SSStarObstacleCount) { /* the forms joined by ", " and a last " or " */
    if (SSStarObstacleCount > 1) PetscCall(PetscStrlcat(SSStarObstacleFormList, ", ", sizeof(SSStarObstacleFormList)));
    PetscCall(PetscStrlcat(SSStarObstacleFormList, SSStarObstacleLastForm, sizeof(SSStarObstacleFormList)));
  }
  PetscCall(PetscStrncpy(SSStarObstacleLastForm, form, sizeof(SSStarObstacleLastForm)));
  SSStarObstacleCount++;
  PetscFunctionReturn(0);
}

PETSC_INTERN PetscErrorCode SSStarObstacleCreate_Plane(SSStarObstacle);
PETSC_INTERN PetscErrorCode SSStarObstacleCreate_Sphere(SSStarObstacle);
PETSC_INTERN PetscErrorCode SSStarObstacleCreate_Cylinder(SSStarObstacle);
PETSC_INTERN PetscErrorCode SSStarObstacleCreate_Mesh(SSStarObstacle);

/* SSStarObstacleRegisterAll - the shapes of -obstacle_<G>, once: a new shape is one line here (and its declaration above) */
static PetscErrorCode SSStarObstacleRegisterAll(void)
{
  PetscFunctionBegin;
  if (SSStarObstacleRegistered) PetscFunctionReturn(0);
  SSStarObstacleRegistered = PETSC_TRUE;
  PetscCall(PetscRegisterFinalize(SSStarObstacleFinalize));
  PetscCall(SSStarObstacleRegister("plane", "plane:px,py,pz,nx,ny,nz (or the six numbers)", SSStarObstacleCreate_Plane));
  PetscCall(SSStarObstacleRegister("sphere", "sphere:cx,cy,cz,R", SSStarObstacleCreate_Sphere));
  PetscCall(SSStarObstacleRegister("cylinder", "cylinder:px,py,pz,ax,ay,az,R", SSStarObstacleCreate_Cylinder));
  PetscCall(SSStarObstacleRegister("mesh", "mesh:FILE.msh", SSStarObstacleCreate_Mesh));
  PetscFunctionReturn(0);
}

/* SSStarObstacleFind - the function that makes a shape, by name (NULL: no such shape) */
PetscErrorCode SSStarObstacleFind(const char name[], PetscErrorCode (**create)(SSStarObstacle))
{
  PetscFunctionBegin;
  PetscCall(SSStarObstacleRegisterAll());
  PetscCall(PetscFunctionListFind(SSStarObstacleList, name, create));
  PetscFunctionReturn(0);
}

/* SSStarObstacleForms - the values of the shapes, for a message: "A, B, C" and the last "D" (give A, B, C or D) */
PetscErrorCode SSStarObstacleForms(const char **forms, const char **last)
{
  PetscFunctionBegin;
  PetscCall(SSStarObstacleRegisterAll());
  *forms = SSStarObstacleFormList;
  *last  = SSStarObstacleLastForm;
  PetscFunctionReturn(0);
}
