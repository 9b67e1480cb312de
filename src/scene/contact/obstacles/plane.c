/* A rigid plane (-obstacle_<G> plane:px,py,pz,nx,ny,nz, or the six numbers alone): a point on it, its normal into the body */
#include "obstacleimpl.h"

typedef struct {
  PetscReal point[3], normal[3]; /* the normal: a unit vector, into the body */
} Plane;

static PetscErrorCode SetFromString_Plane(SSStarObstacle ob, MPI_Comm comm, const char option[], const char spec[], const char numbers[])
{
  Plane    *plane = (Plane *)ob->data;
  PetscReal v[6];

  PetscFunctionBegin;
  PetscCall(SSStarObstacleParseNumbers(comm, option, spec, numbers, 6, "px,py,pz,nx,ny,nz", v));
  PetscCall(SSStarObstacleUnitVector(comm, option, spec, "normal", &v[3], plane->normal));
  for (PetscInt k = 0; k < 3; k++) plane->point[k] = ob->reference[k] = v[k];
  PetscFunctionReturn(0);
}

static PetscErrorCode Gap_Plane(SSStarObstacle ob, const PetscReal x[3], PetscReal tol, PetscReal *gap, PetscReal n[3])
{
  const Plane *plane = (const Plane *)ob->data;
  PetscReal    d[3];

  PetscFunctionBegin;
  for (PetscInt k = 0; k < 3; k++) d[k] = x[k] - plane->point[k];
  *gap = SSStarDot3(d, plane->normal);
  for (PetscInt k = 0; k < 3; k++) n[k] = plane->normal[k];
  PetscFunctionReturn(0);
}

static PetscErrorCode Describe_Plane(SSStarObstacle ob, char text[], size_t len)
{
  const Plane     *plane = (const Plane *)ob->data;
  const PetscReal *p = plane->point, *a = plane->normal;

  PetscFunctionBegin;
  PetscCall(PetscSNPrintf(text, len, "plane through (%g, %g, %g) with normal (%g, %g, %g)", (double)p[0], (double)p[1], (double)p[2], (double)a[0], (double)a[1], (double)a[2]));
  PetscFunctionReturn(0);
}

static PetscErrorCode Attributes_Plane(SSStarObstacle ob, SSStarAttributeWriter *w)
{
  const Plane *plane = (const Plane *)ob->data;

  PetscFunctionBegin;
  PetscCall((*w->reals)(w->ctx, "point", 3, plane->point));
  PetscCall((*w->reals)(w->ctx, "normal", 3, plane->normal));
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarObstacleCreate_Plane(SSStarObstacle ob)
{
  PetscFunctionBegin;
  PetscCall(PetscNew((Plane **)&ob->data));
  ob->ops.setfromstring = SetFromString_Plane;
  ob->ops.gap           = Gap_Plane;
  ob->ops.describe      = Describe_Plane;
  ob->ops.attributes    = Attributes_Plane;
  ob->ops.insideHint    = "does the normal point into the body?";
  PetscFunctionReturn(0);
}
