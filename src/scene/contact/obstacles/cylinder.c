/*
   An infinite rigid cylinder touched from outside (-obstacle_<G> cylinder:px,py,pz,ax,ay,az,R), its axis through p
   along a: gap = distance to the axis - R, normal from the axis to the node
*/
#include "obstacleimpl.h"

typedef struct {
  PetscReal point[3], axis[3], radius; /* axis: a unit vector */
} Cylinder;

static PetscErrorCode SetFromString_Cylinder(SSStarObstacle ob, MPI_Comm comm, const char option[], const char spec[], const char numbers[])
{
  Cylinder *cyl = (Cylinder *)ob->data;
  PetscReal v[7];

  PetscFunctionBegin;
  PetscCall(SSStarObstacleParseNumbers(comm, option, spec, numbers, 7, "px,py,pz,ax,ay,az,R", v));
  PetscCall(SSStarObstacleUnitVector(comm, option, spec, "axis", &v[3], cyl->axis));
  PetscCheck(v[6] > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option %s %s: the radius %g must be positive", option, spec, (double)v[6]);
  for (PetscInt k = 0; k < 3; k++) cyl->point[k] = ob->reference[k] = v[k];
  cyl->radius = v[6];
  PetscFunctionReturn(0);
}

static PetscErrorCode Gap_Cylinder(SSStarObstacle ob, const PetscReal x[3], PetscReal tol, PetscReal *gap, PetscReal n[3])
{
  const Cylinder *cyl = (const Cylinder *)ob->data;
  PetscReal       d[3], along, len;

  PetscFunctionBegin;
  for (PetscInt k = 0; k < 3; k++) d[k] = x[k] - cyl->point[k];
  along = SSStarDot3(d, cyl->axis);
  for (PetscInt k = 0; k < 3; k++) d[k] -= along * cyl->axis[k];
  len  = PetscSqrtReal(SSStarDot3(d, d));
  *gap = len - cyl->radius;
  for (PetscInt k = 0; k < 3; k++) n[k] = len > 0 ? d[k] / len : (k == 2 ? 1.0 : 0.0); /* on the axis: deep inside, refused */
  PetscFunctionReturn(0);
}

static PetscErrorCode Describe_Cylinder(SSStarObstacle ob, char text[], size_t len)
{
  const Cylinder  *cyl = (const Cylinder *)ob->data;
  const PetscReal *p = cyl->point, *a = cyl->axis;

  PetscFunctionBegin;
  PetscCall(PetscSNPrintf(text, len, "rigid cylinder of radius %g, axis through (%g, %g, %g) along (%g, %g, %g)", (double)cyl->radius, (double)p[0], (double)p[1], (double)p[2], (double)a[0], (double)a[1], (double)a[2]));
  PetscFunctionReturn(0);
}

static PetscErrorCode Attributes_Cylinder(SSStarObstacle ob, SSStarAttributeWriter *w)
{
  const Cylinder *cyl = (const Cylinder *)ob->data;

  PetscFunctionBegin;
  PetscCall((*w->reals)(w->ctx, "point", 3, cyl->point));
  PetscCall((*w->reals)(w->ctx, "axis", 3, cyl->axis));
  PetscCall((*w->reals)(w->ctx, "radius", 1, &cyl->radius));
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarObstacleCreate_Cylinder(SSStarObstacle ob)
{
  PetscFunctionBegin;
  PetscCall(PetscNew((Cylinder **)&ob->data));
  ob->ops.setfromstring = SetFromString_Cylinder;
  ob->ops.gap           = Gap_Cylinder;
  ob->ops.describe      = Describe_Cylinder;
  ob->ops.attributes    = Attributes_Cylinder;
  ob->ops.insideHint    = "the body touches the cylinder from outside: is the axis or the radius wrong?";
  PetscFunctionReturn(0);
}
