/*
   The motion of a rigid obstacle (-obstacle_<G>_motion, -obstacle_<G>_rotation): a translation history d(t) and a
   rotation history (t:ax,ay,az,angle: the angle in radians about the axis a, through the obstacle's reference point c),
   one object per contact group. At a time t the obstacle is placed by

       x = Q(t) (X - c) + c + d(t)                                                      (docs/derivation.md (16.1))

   X a point of the obstacle as its option describes it, Q the rotation by the angle about the normalized axis
   (Rodrigues). A rolling cylinder (v t along the slab, the angle v t / R about its axis) or a punch turned about its
   normal is one motion. The obstacle is asked at X = Q^T (x - c - d) + c and its normal turned by Q; what a contact
   node's friction sees is the displacement of the obstacle's material point it touches (SSStarSceneObstacleDisplacement()).
*/
#include "../sceneimpl.h"

/* The identity placement: the obstacle as its option describes it */
void SSStarPlacementIdentity(SSStarPlacement *p)
{
  for (PetscInt k = 0; k < 9; k++) p->Q[k] = (k % 4 == 0) ? 1.0 : 0.0;
  p->d[0] = p->d[1] = p->d[2] = 0;
}

/* The rotation by angle about the axis a (|a| > 0, or angle 0): Q = cos I + sin [a]x + (1 - cos) a a^T, row-major */
void SSStarRotation(const PetscReal axis[3], PetscReal angle, PetscReal Q[9])
{
  const PetscReal len = PetscSqrtReal(SSStarDot3(axis, axis)), c = PetscCosReal(angle), s = PetscSinReal(angle);
  PetscReal       a[3] = {0, 0, 1};

  if (len > 0)
    for (PetscInt k = 0; k < 3; k++) a[k] = axis[k] / len;
  if (len == 0) angle = 0;
  Q[0] = c + (1 - c) * a[0] * a[0];
  Q[1] = (1 - c) * a[0] * a[1] - s * a[2];
  Q[2] = (1 - c) * a[0] * a[2] + s * a[1];
  Q[3] = (1 - c) * a[1] * a[0] + s * a[2];
  Q[4] = c + (1 - c) * a[1] * a[1];
  Q[5] = (1 - c) * a[1] * a[2] - s * a[0];
  Q[6] = (1 - c) * a[2] * a[0] - s * a[1];
  Q[7] = (1 - c) * a[2] * a[1] + s * a[0];
  Q[8] = c + (1 - c) * a[2] * a[2];
  if (angle == 0)
    for (PetscInt k = 0; k < 9; k++) Q[k] = (k % 4 == 0) ? 1.0 : 0.0;
}

/* x = Q (X - c) + c + d: where the placement puts the obstacle's point X */
void SSStarPlacementApply(const SSStarPlacement *p, const PetscReal c[3], const PetscReal X[3], PetscReal x[3])
{
  const PetscReal r[3] = {X[0] - c[0], X[1] - c[1], X[2] - c[2]};

  for (PetscInt k = 0; k < 3; k++) x[k] = SSStarDot3(&p->Q[3 * k], r) + c[k] + p->d[k];
}

/* X = Q^T (x - c - d) + c: the obstacle's point the placement puts at x */
void SSStarPlacementInverse(const SSStarPlacement *p, const PetscReal c[3], const PetscReal x[3], PetscReal X[3])
{
  const PetscReal r[3] = {x[0] - c[0] - p->d[0], x[1] - c[1] - p->d[1], x[2] - c[2] - p->d[2]};

  for (PetscInt k = 0; k < 3; k++) X[k] = p->Q[k] * r[0] + p->Q[3 + k] * r[1] + p->Q[6 + k] * r[2] + c[k];
}

/* Whether two placements are the same */
PetscBool SSStarPlacementEqual(const SSStarPlacement *a, const SSStarPlacement *b)
{
  for (PetscInt k = 0; k < 9; k++)
    if (a->Q[k] != b->Q[k]) return PETSC_FALSE;
  for (PetscInt k = 0; k < 3; k++)
    if (a->d[k] != b->d[k]) return PETSC_FALSE;
  return PETSC_TRUE;
}

/* Whether the obstacle has a motion (a translation or a rotation history) */
PetscBool SSStarMotionIsSet(const SSStarMotion *m)
{
  return (PetscBool)(m->translation || m->rotation);
}

/* The placement of the motion at the time t */
PetscErrorCode SSStarMotionPlacementAt(const SSStarMotion *m, PetscReal t, SSStarPlacement *p)
{
  PetscFunctionBegin;
  SSStarPlacementIdentity(p);
  if (m->translation) PetscCall(SSStarHistoryEvaluate(m->translation, t, p->d));
  if (m->rotation) {
    PetscReal r[4];

    PetscCall(SSStarHistoryEvaluate(m->rotation, t, r));
    SSStarRotation(r, r[3], p->Q);
  }
  PetscFunctionReturn(0);
}

/* The rotation vector (angle times the unit axis) of the rotation history at t, zero without one */
PetscErrorCode SSStarMotionRotationVector(const SSStarMotion *m, PetscReal t, PetscReal theta[3])
{
  PetscFunctionBegin;
  theta[0] = theta[1] = theta[2] = 0;
  if (m->rotation) {
    PetscReal r[4], len;

    PetscCall(SSStarHistoryEvaluate(m->rotation, t, r));
    len = PetscSqrtReal(SSStarDot3(r, r));
    for (PetscInt k = 0; k < 3 && len > 0; k++) theta[k] = r[3] * r[k] / len;
  }
  PetscFunctionReturn(0);
}

/*
   A rotation history of option (t:ax,ay,az,angle;... or ax,ay,az,angle), checked: an axis of zero length only with
   the angle 0
*/
PetscErrorCode SSStarMotionReadRotation(MPI_Comm comm, const char option[], SSStarHistory *rotation)
{
  PetscBool set;

  PetscFunctionBegin;
  PetscCall(SSStarHistoryDestroy(rotation));
  PetscCall(SSStarHistoryCreateFromOptions(comm, NULL, option, 4, rotation, &set));
  PetscCall(SSStarMotionCheckRotation(comm, option, *rotation));
  PetscFunctionReturn(0);
}

/* Refuses a rotation history with a knot (or constant) whose axis has zero length and whose angle is not 0 */
PetscErrorCode SSStarMotionCheckRotation(MPI_Comm comm, const char option[], SSStarHistory rotation)
{
  PetscInt         n;
  const PetscReal *times, *values;

  PetscFunctionBegin;
  PetscCall(SSStarHistoryGetKnots(rotation, &n, &times, &values));
  for (PetscInt k = 0; k < PetscMax(n, 1); k++) {
    PetscReal r[4];

    if (n) PetscCall(PetscArraycpy(r, &values[4 * k], 4));
    else PetscCall(SSStarHistoryEvaluate(rotation, 0, r));
    PetscCheck(SSStarDot3(r, r) > 0 || r[3] == 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option %s: the axis (%g, %g, %g) of the rotation by %g%s%g has no direction (give ax,ay,az,angle with a nonzero axis)", option, (double)r[0], (double)r[1], (double)r[2], (double)r[3], n ? " at t = " : "", n ? (double)times[k] : 0.0);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarMotionDestroy(SSStarMotion *m)
{
  PetscFunctionBegin;
  PetscCall(SSStarHistoryDestroy(&m->translation));
  PetscCall(SSStarHistoryDestroy(&m->rotation));
  PetscFunctionReturn(0);
}

/*
   The displacement of the obstacle's material point that contact node i touches (scene->obstaclePoint), from where its
   option describes it to where the placement p (its group's now or before) puts it: d_i = P(Y_i) - Y_i; zero for a
   node of a contact pair or of an obstacle without a motion
*/
void SSStarSceneObstacleDisplacement(SSStarScene scene, PetscInt i, const SSStarPlacement *p, PetscReal d[3])
{
  const SSStarContactGroup *cg = &scene->contact[scene->group[i]];
  const PetscReal          *Y  = &scene->obstaclePoint[3 * i];
  PetscReal                 y[3];

  d[0] = d[1] = d[2] = 0;
  if (cg->master[0] || !SSStarMotionIsSet(&cg->motion)) return;
  SSStarPlacementApply(p, cg->motion.center, Y, y);
  for (PetscInt k = 0; k < 3; k++) d[k] = y[k] - Y[k];
}
