/* A rigid ball touched from outside (-obstacle_<G> sphere:cx,cy,cz,R): gap |x - c| - R, normal (x - c)/|x - c| */
#include "obstacleimpl.h"

typedef struct {
  PetscReal centre[3], radius;
} Sphere;

static PetscErrorCode SetFromString_Sphere(SSStarObstacle ob, MPI_Comm comm, const char option[], const char spec[], const char numbers[])
{
  Sphere   *ball = (Sphere *)ob->data;
  PetscReal v[4];

  PetscFunctionBegin;
  PetscCall(SSStarObstacleParseNumbers(comm, option, spec, numbers, 4, "cx,cy,cz,R", v));
  PetscCheck(v[3] > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option %s %s: the radius %g must be positive", option, spec, (double)v[3]);
  for (PetscInt k = 0; k < 3; k++) ball->centre[k] = ob->reference[k] = v[k];
  ball->radius = v[3];
  PetscFunctionReturn(0);
}

static PetscErrorCode Gap_Sphere(SSStarObstacle ob, const PetscReal x[3], PetscReal tol, PetscReal *gap, PetscReal n[3])
{
  const Sphere *ball = (const Sphere *)ob->data;
  PetscReal     d[3], len;

  PetscFunctionBegin;
  for (PetscInt k = 0; k < 3; k++) d[k] = x[k] - ball->centre[k];
  len  = PetscSqrtReal(SSStarDot3(d, d));
  *gap = len - ball->radius;
  for (PetscInt k = 0; k < 3; k++) n[k] = len > 0 ? d[k] / len : (k == 2 ? 1.0 : 0.0); /* at the centre: deep inside, refused */
  PetscFunctionReturn(0);
}

static PetscErrorCode Describe_Sphere(SSStarObstacle ob, char text[], size_t len)
{
  const Sphere    *ball = (const Sphere *)ob->data;
  const PetscReal *p    = ball->centre;

  PetscFunctionBegin;
  PetscCall(PetscSNPrintf(text, len, "rigid ball of radius %g centred at (%g, %g, %g)", (double)ball->radius, (double)p[0], (double)p[1], (double)p[2]));
  PetscFunctionReturn(0);
}

static PetscErrorCode Attributes_Sphere(SSStarObstacle ob, SSStarAttributeWriter *w)
{
  const Sphere *ball = (const Sphere *)ob->data;

  PetscFunctionBegin;
  PetscCall((*w->reals)(w->ctx, "centre", 3, ball->centre));
  PetscCall((*w->reals)(w->ctx, "radius", 1, &ball->radius));
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarObstacleCreate_Sphere(SSStarObstacle ob)
{
  PetscFunctionBegin;
  PetscCall(PetscNew((Sphere **)&ob->data));
  ob->ops.setfromstring = SetFromString_Sphere;
  ob->ops.gap           = Gap_Sphere;
  ob->ops.describe      = Describe_Sphere;
  ob->ops.attributes    = Attributes_Sphere;
  ob->ops.insideHint    = "the body touches the ball from outside: is the centre or the radius wrong?";
  PetscFunctionReturn(0);
}
