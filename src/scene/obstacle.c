/*
   Rigid obstacles of the scenes (-obstacle_<G>): shapes registered by name, one file per shape in obstacles/
   (plane.c, sphere.c, cylinder.c, mesh.c), each made from its option's value "<shape>:<numbers>" (six numbers alone: a
   plane). For each contact node the obstacle gives its initial gap and the unit normal of its frame, pointing out of
   the obstacle into the body. Small deformation: both at the reference configuration.

   A new shape is a file obstacles/<shape>.c with its SSStarObstacleCreate_<Shape>() and one line in
   SSStarObstacleRegisterAll().
*/
#include "obstacleimpl.h"

static PetscFunctionList SSStarObstacleList       = NULL;
static PetscBool         SSStarObstacleRegistered = PETSC_FALSE;
static char              SSStarObstacleForms[1024]; /* "plane:..., sphere:... or mesh:FILE.msh", for the refusal */
static PetscInt          SSStarObstacleCount = 0;
static char              SSStarObstacleLastForm[256];

static PetscErrorCode SSStarObstacleFinalize(void)
{
  PetscFunctionBegin;
  PetscCall(PetscFunctionListDestroy(&SSStarObstacleList));
  SSStarObstacleRegistered = PETSC_FALSE;
  SSStarObstacleCount      = 0;
  SSStarObstacleForms[0]   = 0;
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
    if (SSStarObstacleCount > 1) PetscCall(PetscStrlcat(SSStarObstacleForms, ", ", sizeof(SSStarObstacleForms)));
    PetscCall(PetscStrlcat(SSStarObstacleForms, SSStarObstacleLastForm, sizeof(SSStarObstacleForms)));
  }
  PetscCall(PetscStrncpy(SSStarObstacleLastForm, form, sizeof(SSStarObstacleLastForm)));
  SSStarObstacleCount++;
  PetscFunctionReturn(0);
}

/* SSStarObstacleRegisterAll - the shapes of -obstacle_<G>, once */
PetscErrorCode SSStarObstacleRegisterAll(void)
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

/* The comma-separated numbers of a value: exactly n finite values */
PetscErrorCode SSStarObstacleParseNumbers(MPI_Comm comm, const char option[], const char spec[], const char numbers[], PetscInt n, const char form[], PetscReal v[])
{
  const char *s   = numbers;
  PetscInt    got = 0;

  PetscFunctionBegin;
  while (*s) {
    char     *end;
    PetscReal value = (PetscReal)strtod(s, &end);

    PetscCheck(end != s && (*end == ',' || !*end), comm, PETSC_ERR_ARG_WRONG, "Option %s %s: \"%s\" is not a list of numbers %s", option, spec, numbers, form);
    PetscCheck(got < n, comm, PETSC_ERR_ARG_WRONG, "Option %s %s needs %" PetscInt_FMT " comma-separated values %s (got more)", option, spec, n, form);
    PetscCheck(!PetscIsInfOrNanReal(value), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option %s %s: value %" PetscInt_FMT " is not a finite number (%g)", option, spec, got + 1, (double)value);
    v[got++] = value;
    s        = *end ? end + 1 : end;
  }
  PetscCheck(got == n, comm, PETSC_ERR_ARG_WRONG, "Option %s %s needs %" PetscInt_FMT " comma-separated values %s (got %" PetscInt_FMT ")", option, spec, n, form, got);
  PetscFunctionReturn(0);
}

/* A unit vector from v (what: its name in the message), refused when zero */
PetscErrorCode SSStarObstacleUnitVector(MPI_Comm comm, const char option[], const char spec[], const char what[], const PetscReal v[3], PetscReal u[3])
{
  const PetscReal len = PetscSqrtReal(SSStarDot3(v, v));

  PetscFunctionBegin;
  PetscCheck(len > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option %s %s: the %s (%g, %g, %g) is zero", option, spec, what, (double)v[0], (double)v[1], (double)v[2]);
  for (PetscInt k = 0; k < 3; k++) u[k] = v[k] / len;
  PetscFunctionReturn(0);
}

/*
   SSStarObstacleCreateFromString - the obstacle of an option's value: "<shape>:<numbers>" for a registered shape, or
   numbers alone (a plane); errors name the option
*/
PetscErrorCode SSStarObstacleCreateFromString(MPI_Comm comm, const char option[], const char value[], SSStarObstacle *ob)
{
  const char *colon   = strchr(value, ':'), *numbers = value;
  char        name[sizeof((*ob)->type)] = "plane";
  PetscErrorCode (*create)(SSStarObstacle) = NULL;

  PetscFunctionBegin;
  PetscCall(SSStarObstacleRegisterAll());
  *ob = NULL;
  if (colon && (size_t)(colon - value) < sizeof(name)) {
    PetscCall(PetscStrncpy(name, value, (size_t)(colon - value) + 1));
    PetscCall(PetscFunctionListFind(SSStarObstacleList, name, &create));
    if (create) numbers = colon + 1;
  }
  if (!create) {
    PetscCheck(!value[0] || (value[0] >= '0' && value[0] <= '9') || value[0] == '-' || value[0] == '+' || value[0] == '.', comm, PETSC_ERR_ARG_WRONG, "Option %s %s: unknown obstacle; give %s or %s", option, value, SSStarObstacleForms, SSStarObstacleLastForm);
    PetscCall(PetscStrncpy(name, "plane", sizeof(name)));
    PetscCall(PetscFunctionListFind(SSStarObstacleList, name, &create));
  }
  PetscCall(PetscNew(ob));
  PetscCall(PetscStrncpy((*ob)->type, name, sizeof((*ob)->type)));
  PetscCall((*create)(*ob));
  PetscCall((*(*ob)->ops.setfromstring)(*ob, comm, option, value, numbers));
  PetscFunctionReturn(0);
}

/* SSStarObstacleCreateDefault - the obstacle of a contact group without -obstacle_<G>: the plane z = 0, normal +z */
PetscErrorCode SSStarObstacleCreateDefault(SSStarObstacle *ob)
{
  PetscFunctionBegin;
  PetscCall(SSStarObstacleCreateFromString(PETSC_COMM_SELF, "-obstacle_<G>", "0,0,0,0,0,1", ob));
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarObstacleDestroy(SSStarObstacle *ob)
{
  PetscFunctionBegin;
  if (!*ob) PetscFunctionReturn(0);
  if ((*ob)->ops.destroy) PetscCall((*(*ob)->ops.destroy)(*ob));
  PetscCall(PetscFree((*ob)->data));
  PetscCall(PetscFree(*ob));
  PetscFunctionReturn(0);
}

/*
   SSStarObstacleGap - the signed distance of x to the obstacle (positive outside it) and the unit normal of its frame
   (out of the obstacle, into the body); tol: the distance within which x lies on the obstacle's surface
*/
PetscErrorCode SSStarObstacleGap(SSStarObstacle ob, const PetscReal x[3], PetscReal tol, PetscReal *gap, PetscReal n[3])
{
  PetscFunctionBegin;
  PetscCall((*ob->ops.gap)(ob, x, tol, gap, n));
  PetscFunctionReturn(0);
}

/* SSStarObstacleDescribe - the obstacle in words, for the scene's view and the output */
PetscErrorCode SSStarObstacleDescribe(SSStarObstacle ob, char text[], size_t len)
{
  PetscFunctionBegin;
  PetscCall((*ob->ops.describe)(ob, text, len));
  PetscFunctionReturn(0);
}

/* SSStarObstacleWriteAttributes - the obstacle's numbers by name (point, normal, centre, radius, axis, file, ...) */
PetscErrorCode SSStarObstacleWriteAttributes(SSStarObstacle ob, SSStarAttributeWriter *writer)
{
  PetscFunctionBegin;
  PetscCall((*ob->ops.attributes)(ob, writer));
  PetscFunctionReturn(0);
}

/* SSStarObstacleInsideHint - what to check when a node starts inside the obstacle */
const char *SSStarObstacleInsideHint(SSStarObstacle ob)
{
  return ob->ops.insideHint;
}
