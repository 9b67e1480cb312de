/*
   Rigid obstacles of the scenes (-obstacle_<G>): shapes registered by name (obstacles/register.c), one file per shape
   in obstacles/ (plane.c, sphere.c, cylinder.c, mesh.c), each made from its option's value "<shape>:<numbers>" (six
   numbers alone: a plane). For each contact node the obstacle gives its initial gap and the unit normal of its frame,
   pointing out of the obstacle into the body. Small deformation: both at the reference configuration.

   A new shape is a file obstacles/<shape>.c with its SSStarObstacleCreate_<Shape>() and its registration in
   obstacles/register.c (a declaration and one line in SSStarObstacleRegisterAll()): the option, its refusals, -help,
   the scene's view and the output's attributes follow from the shape's ops.
*/
#include "obstacleimpl.h"

/*
   SSStarObstacleCreateFromString - the obstacle of an option's value: "<shape>:<numbers>" for a registered shape, or
   numbers alone (a plane); errors name the option
*/
PetscErrorCode SSStarObstacleCreateFromString(MPI_Comm comm, const char option[], const char value[], SSStarObstacle *ob)
{
  const char *colon   = strchr(value, ':'), *numbers = value, *forms, *last;
  char        name[sizeof((*ob)->type)] = "plane";
  PetscErrorCode (*create)(SSStarObstacle) = NULL;

  PetscFunctionBegin;
  *ob = NULL;
  if (colon && (size_t)(colon - value) < sizeof(name)) {
    PetscCall(PetscStrncpy(name, value, (size_t)(colon - value) + 1));
    PetscCall(SSStarObstacleFind(name, &create));
    if (create) numbers = colon + 1;
  }
  if (!create) {
    PetscCall(SSStarObstacleForms(&forms, &last));
    PetscCheck(!value[0] || (value[0] >= '0' && value[0] <= '9') || value[0] == '-' || value[0] == '+' || value[0] == '.', comm, PETSC_ERR_ARG_WRONG, "Option %s %s: unknown obstacle; give %s or %s", option, value, forms, last);
    PetscCall(PetscStrncpy(name, "plane", sizeof(name)));
    PetscCall(SSStarObstacleFind(name, &create));
  }
  PetscCall(PetscNew(ob));
  PetscCall(PetscStrncpy((*ob)->type, name, sizeof((*ob)->type)));
  PetscCall((*create)(*ob));
  PetscCall((*(*ob)->ops.setfromstring)(*ob, comm, option, value, numbers));
  PetscFunctionReturn(0);
}

/* SSStarObstacleHelp - the line of -help for -obstacle_<G>, with the forms of the registered shapes */
PetscErrorCode SSStarObstacleHelp(char text[], size_t len)
{
  const char *forms, *last;

  PetscFunctionBegin;
  PetscCall(SSStarObstacleForms(&forms, &last));
  PetscCall(PetscSNPrintf(text, len, "  -obstacle_<G> <0,0,0,0,0,1>: the rigid obstacle of G (its normal out of it, into the body), a registered shape:\n      %s or %s\n", forms, last));
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
   SSStarObstacleGaps - the signed distances of n points to the obstacle (positive outside it) and the unit normals of
   their frames (out of the obstacle, into the body); tol: the distance within which a point lies on the obstacle's
   surface. Collective on the communicator the obstacle was made on (a mesh obstacle's triangles are spread over its
   ranks): every rank calls it, with its own points, 0 too.
*/
PetscErrorCode SSStarObstacleGaps(SSStarObstacle ob, PetscInt n, const PetscReal x[], PetscReal tol, PetscReal gap[], PetscReal normal[])
{
  PetscFunctionBegin;
  if (ob->ops.gaps) PetscCall((*ob->ops.gaps)(ob, n, x, tol, gap, normal));
  else
    for (PetscInt i = 0; i < n; i++) PetscCall((*ob->ops.gap)(ob, &x[3 * i], tol, &gap[i], &normal[3 * i]));
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

/* SSStarObstacleReferencePoint - the point a rotation of the obstacle turns about: a plane's point, a ball's centre, a
   cylinder's point on its axis, the mean of a mesh obstacle's vertices */
void SSStarObstacleReferencePoint(SSStarObstacle ob, PetscReal c[3])
{
  for (PetscInt k = 0; k < 3; k++) c[k] = ob->reference[k];
}
