/*
   Where the contact of a load path's step is measured (-sliding, docs/derivation.md section 13).

   Large sliding (the default): at every step, at the current configuration -- the reference displaced by the last
   accepted solution -- against the obstacles where their motions put them in the step: each node's gap, normal and frame,
   and a pair's master faces, found again (the search asked at the current positions), B declared again; the step
   then solves the incremental problem (10.5) linearized about that configuration.

   Small sliding (-sliding small): at the reference configuration. A node's normal offset against its obstacle
   translated by d is then the first-order gap g - n.d (10.4), exact for a plane and first order in |d| for a ball,
   cylinder or mesh. Its error against the exact gap -- the node's distance to the translated obstacle, the obstacle
   asked at x - d -- is measured at every step: a step where it exceeds -small_sliding_tol times |d| at a node within
   |d| of the obstacle is refused, naming the obstacle, the step and the error, rather than solved with a gap the
   motion has made wrong.
*/
#include "../sceneimpl.h"

const char *const SSStarSlidings[] = {"large", "small"};

/* The worst node of a check over the ranks: its excess over the bound first, then the data of the message */
typedef struct {
  PetscReal excess; /* error - bound: > 0 refuses                                        */
  PetscReal data[8]; /* group, file index, x (3), the first-order gap, the exact gap, |d| */
} WorstNode;

/* The node of largest excess over the ranks (the lowest rank's of equal ones): its data reach every rank */
static PetscErrorCode ShareWorst(MPI_Comm comm, WorstNode *w)
{
  PetscReal   excess;
  PetscMPIInt rank, size, owner;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(MPIU_Allreduce(&w->excess, &excess, 1, MPIU_REAL, MPI_MAX, comm));
  owner = w->excess == excess ? rank : size;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &owner, 1, MPI_INT, MPI_MIN, comm));
  PetscCallMPI(MPI_Bcast(w->data, 8, MPIU_REAL, owner, comm));
  w->excess = excess;
  PetscFunctionReturn(0);
}

/*
   SSStarSceneCheckSmallSliding - with small sliding, refuses the step to time t (the path's step number step, 1-based)
   when a moved obstacle's first-order gap g - n.d_i (d_i the motion of the obstacle's point the node faces, (16.3)) is
   off the exact gap by more than -small_sliding_tol |d_i| + the contact tolerance at a node of its group that is within
   |d_i| of it (by either gap). Collective.
*/
PetscErrorCode SSStarSceneCheckSmallSliding(SSStarScene scene, PetscInt step, PetscReal t)
{
  PetscInt        *group, moved = 0;
  PetscReal       *gap, *normal, *dnode, tol;
  SSStarPlacement *at;
  WorstNode        worst = {PETSC_MIN_REAL, {0, 0, 0, 0, 0, 0, 0, 0}};

  PetscFunctionBegin;
  if (scene->sliding != SSSTAR_SLIDING_SMALL) PetscFunctionReturn(0);
  PetscCall(PetscMalloc1(scene->nContact, &at)); /* the placements at t */
  for (PetscInt g = 0; g < scene->nContact; g++) {
    PetscCall(SSStarMotionPlacementAt(&scene->contact[g].motion, t, &at[g]));
    if (SSStarMotionIsSet(&scene->contact[g].motion) && !scene->contact[g].master[0]) moved++;
  }
  if (!moved) {
    PetscCall(PetscFree(at));
    PetscFunctionReturn(0);
  }
  PetscCall(SSStarSceneContactTolerance(scene, &tol));
  PetscCall(PetscMalloc4(scene->n + 1, &group, scene->n + 1, &gap, 3 * scene->n + 1, &normal, 3 * scene->n + 1, &dnode));
  for (PetscInt i = 0; i < scene->n; i++) {
    const SSStarContactGroup *cg = &scene->contact[scene->group[i]];

    group[i] = SSStarMotionIsSet(&cg->motion) && !cg->master[0] ? scene->group[i] : -1;
    SSStarSceneObstacleDisplacement(scene, i, &at[scene->group[i]], &dnode[3 * i]);
  }
  PetscCall(SSStarSceneObstacleGaps(scene, scene->n, group, scene->coords, at, tol, gap, normal));
  for (PetscInt i = 0; i < scene->n; i++) {
    const PetscReal *di = &dnode[3 * i], dd = PetscSqrtReal(SSStarDot3(di, di));
    const PetscReal  linear = scene->gap[i] - SSStarDot3(&scene->normal[3 * i], di), excess = PetscAbsReal(gap[i] - linear) - scene->smallSlidingTol * dd - tol;

    if (group[i] < 0 || PetscMin(linear, gap[i]) > dd || excess <= worst.excess) continue;
    worst.excess  = excess;
    worst.data[0] = (PetscReal)scene->group[i];
    worst.data[1] = (PetscReal)scene->tag[i];
    for (PetscInt k = 0; k < 3; k++) worst.data[2 + k] = scene->coords[3 * i + k];
    worst.data[5] = linear;
    worst.data[6] = gap[i];
    worst.data[7] = dd;
  }
  PetscCall(PetscFree4(group, gap, normal, dnode));
  PetscCall(ShareWorst(scene->comm, &worst));
  if (worst.excess > 0) {
    const PetscInt            g  = (PetscInt)worst.data[0];
    const SSStarContactGroup *cg = &scene->contact[g];
    const PetscReal          *w = worst.data, dg[3] = {at[g].d[0], at[g].d[1], at[g].d[2]};
    char                      shape[256];

    PetscCall(PetscFree(at));
    PetscCall(SSStarObstacleDescribe(cg->obstacle, shape, sizeof(shape)));
    SETERRQ(scene->comm, PETSC_ERR_ARG_OUTOFRANGE, "Step %" PetscInt_FMT " (t = %g): the obstacle of -obstacle_%s (%s) moved by (%g, %g, %g)%s (-obstacle_%s_motion%s%s%s): its first-order gap g - n.d = %g at mesh node %" PetscInt_FMT " (0-based, file order) at (%g, %g, %g) is off the exact gap %g by %g, more than -small_sliding_tol %g times |d| = %g: the motion is too large against the obstacle's curvature for small sliding", step, (double)t, cg->name, shape, (double)dg[0], (double)dg[1], (double)dg[2], cg->motion.rotation ? " and turned" : "", cg->name, cg->motion.rotation ? ", -obstacle_" : "", cg->motion.rotation ? cg->name : "", cg->motion.rotation ? "_rotation" : "", (double)w[5], (PetscInt)w[1], (double)w[2], (double)w[3], (double)w[4], (double)w[6], (double)PetscAbsReal(w[6] - w[5]), (double)scene->smallSlidingTol, (double)w[7]);
  }
  PetscCall(PetscFree(at));
  PetscFunctionReturn(0);
}

/*
   The step's contact linearized at the configuration X + at (large sliding, docs/derivation.md (13.4)): gaps, normals,
   frames and a pair's masters measured there against the obstacles where their motions put them in the step (unless
   measured already), B declared to the SNES again, and what the offsets of the step are made of re-expressed: the
   gap g as the measured gap less w_n(at), so that o_n = g - B_n at, and the slip w_t^(k-1) = B_t u^(k-1) - R_t d_i^(k-1)
   of the last accepted solution in the new frame, d_i the motion of the obstacle's point the node faces (16.3).
   Collective.
*/
static PetscErrorCode LinearizeAt(SSStarScene scene, SNES snes, Vec at, PetscBool measured)
{
  PetscReal *w;
  Vec        gaps;

  PetscFunctionBegin;
  if (!measured) PetscCall(SSStarSceneBuildContactOperator(scene, at));
  PetscCall(PetscMalloc1(3 * scene->n + 1, &w));
  PetscCall(SSStarSceneRelativeDisplacement(scene, at, w)); /* B at - R d */
  for (PetscInt i = 0; i < scene->n; i++) scene->gap[i] -= w[3 * i + 2];
  if (at != scene->uAccepted) PetscCall(SSStarSceneRelativeDisplacement(scene, scene->uAccepted, w));
  for (PetscInt i = 0; i < scene->n; i++) {
    const SSStarMotion *motion = &scene->contact[scene->group[i]].motion;
    const PetscReal    *R      = &scene->frame[9 * i];
    PetscReal           now[3], before[3], step[3];

    SSStarSceneObstacleDisplacement(scene, i, &motion->now, now);
    SSStarSceneObstacleDisplacement(scene, i, &motion->before, before);
    for (PetscInt k = 0; k < 3; k++) step[k] = now[k] - before[k];
    for (PetscInt k = 0; k < 2; k++) scene->slipPrev[2 * i + k] = w[3 * i + k] + SSStarDot3(&R[3 * k], step);
  }
  PetscCall(PetscFree(w));
  PetscCall(SSStarSceneNodeVec(scene, 1, scene->gap, &gaps));
  PetscCall(SNESSSStarSetContactOperator(snes, scene->isC, scene->B, gaps));
  PetscCall(VecDestroy(&gaps));
  PetscFunctionReturn(0);
}

/*
   SSStarSceneMeasureContact - large sliding, at the start of a step: its contact linearized at the current
   configuration, the reference displaced by the last accepted solution (scene->uAccepted). Nothing to do before the
   first step when no obstacle has moved (the reference B stands), nor when no obstacle moves in this step, the step
   follows the accepted one directly (not set again after a failure), and the contact measured at the current
   configuration is the one the last step ended with (SSStarSceneRelinearizeContact() with that step's states: a pair
   whose bodies barely slid keeps its masters, and its reduction). Collective.
*/
PetscErrorCode SSStarSceneMeasureContact(SSStarScene scene, SNES snes)
{
  PetscBool moved = PETSC_FALSE, moving = PETSC_FALSE;

  PetscFunctionBegin;
  scene->relinearizations = 0;
  for (PetscInt g = 0; g < scene->nContact; g++) {
    const SSStarMotion *motion = &scene->contact[g].motion;
    SSStarPlacement     rest;

    SSStarPlacementIdentity(&rest);
    if (!SSStarPlacementEqual(&motion->now, &rest)) moved = PETSC_TRUE;
    if (!SSStarPlacementEqual(&motion->now, &motion->before)) moving = PETSC_TRUE;
  }
  if (!scene->stepped && !moved) PetscFunctionReturn(0);
  if (scene->lastLinearization && !moving) { /* the linearization and the states of the last accepted solve */
    PetscBool consistent;
    PetscReal error, scale;

    scene->lastLinearization = PETSC_FALSE;
    PetscCall(SSStarSceneRelinearizeContact(scene, snes, scene->uAccepted, &consistent, &error, &scale));
    PetscFunctionReturn(0);
  }
  scene->lastLinearization = PETSC_FALSE; /* a step set again after a failure starts from a fresh measure */
  PetscCall(LinearizeAt(scene, snes, scene->uAccepted, PETSC_FALSE));
  PetscFunctionReturn(0);
}

/*
   SSStarSceneMeasureContactAt - large sliding within a solve of a hyperelastic scene's step: the contact linearized at
   the iterate u (docs/derivation.md (17.5), section 18), the step's gaps and slips re-expressed there. Collective.
*/
PetscErrorCode SSStarSceneMeasureContactAt(SSStarScene scene, SNES snes, Vec u)
{
  PetscFunctionBegin;
  PetscCall(LinearizeAt(scene, snes, u, PETSC_FALSE));
  PetscFunctionReturn(0);
}

/* What a linearization holds (the scene's gaps, normals, frames, masters and B), to put back */
typedef struct {
  PetscReal *gap, *normal, *point, *frame, *masterWeight;
  PetscInt  *masterStart, *masterDof, pairFallback;
  Mat        B;
} Linearization;

/* The frames, masters and B of the scene and of l exchanged */
static void Swap(SSStarScene scene, Linearization *l)
{
  PetscReal *frame = scene->frame, *weight = scene->masterWeight;
  PetscInt  *start = scene->masterStart, *dof = scene->masterDof, fallback = scene->pairFallback;
  Mat        B     = scene->B;

  scene->frame        = l->frame;
  scene->masterWeight = l->masterWeight;
  scene->masterStart  = l->masterStart;
  scene->masterDof    = l->masterDof;
  scene->pairFallback = l->pairFallback;
  scene->B            = l->B;
  l->frame            = frame;
  l->masterWeight     = weight;
  l->masterStart      = start;
  l->masterDof        = dof;
  l->pairFallback     = fallback;
  l->B                = B;
}

/* The scene's linearization into l; the scene is left without frames, masters and B (to be measured again) */
static PetscErrorCode Keep(SSStarScene scene, Linearization *l)
{
  PetscFunctionBegin;
  PetscCall(PetscMemzero(l, sizeof(*l)));
  PetscCall(PetscMalloc3(scene->n + 1, &l->gap, 3 * scene->n + 1, &l->normal, 3 * scene->n + 1, &l->point));
  PetscCall(PetscArraycpy(l->gap, scene->gap, scene->n));
  PetscCall(PetscArraycpy(l->normal, scene->normal, 3 * scene->n));
  if (scene->obstaclePoint) PetscCall(PetscArraycpy(l->point, scene->obstaclePoint, 3 * scene->n));
  Swap(scene, l);
  PetscFunctionReturn(0);
}

/* Back to the linearization kept (restore: the one measured since is dropped), or drop the one kept */
static PetscErrorCode PutBack(SSStarScene scene, Linearization *l, PetscBool restore)
{
  PetscFunctionBegin;
  if (restore) {
    PetscCall(PetscArraycpy(scene->gap, l->gap, scene->n));
    PetscCall(PetscArraycpy(scene->normal, l->normal, 3 * scene->n));
    if (scene->obstaclePoint) PetscCall(PetscArraycpy(scene->obstaclePoint, l->point, 3 * scene->n));
    Swap(scene, l);
  }
  PetscCall(PetscFree(l->frame));
  PetscCall(PetscFree3(l->masterStart, l->masterDof, l->masterWeight));
  PetscCall(MatDestroy(&l->B));
  PetscCall(PetscFree3(l->gap, l->normal, l->point));
  PetscFunctionReturn(0);
}

/*
   SSStarSceneRelinearizeContact - large sliding, after a solve u of the step: the contact measured at X + u against the
   step's linearization (docs/derivation.md (13.5)). The geometric error is, over the nodes touching at u (states), the
   exact gap there, and over the others the exact penetration, against -sliding_tol times the largest normal
   displacement n.u of a touching node. Within it (consistent): the linearization the step was solved with stays.
   Beyond it: the step is linearized at X + u (again: solve it again from u). Collective.
*/
PetscErrorCode SSStarSceneRelinearizeContact(SSStarScene scene, SNES snes, Vec u, PetscBool *consistent, PetscReal *error, PetscReal *scale)
{
  const SSStarState *states;
  Linearization      kept;
  PetscReal          tol, e[2] = {0, 0};
  const PetscScalar *ua;
  Vec                uC;

  PetscFunctionBegin;
  PetscCall(SSStarSceneContactTolerance(scene, &tol));
  PetscCall(SNESSSStarGetStates(snes, &states, NULL));
  PetscCall(VecGetSubVector(u, scene->isC, &uC));
  PetscCall(VecGetArrayRead(uC, &ua));
  for (PetscInt i = 0; i < scene->n; i++) { /* the scale: the normal displacements of the touching nodes */
    const PetscReal ui[3] = {PetscRealPart(ua[3 * i]), PetscRealPart(ua[3 * i + 1]), PetscRealPart(ua[3 * i + 2])};

    if (states[i] != SSSTAR_STATE_L && states[i] != SSSTAR_STATE_LS) e[1] = PetscMax(e[1], PetscAbsReal(SSStarDot3(&scene->normal[3 * i], ui)));
  }
  PetscCall(VecRestoreArrayRead(uC, &ua));
  PetscCall(VecRestoreSubVector(u, scene->isC, &uC));
  PetscCall(Keep(scene, &kept));
  PetscCall(SSStarSceneBuildContactOperator(scene, u)); /* the exact gaps at X + u */
  for (PetscInt i = 0; i < scene->n; i++) {
    const PetscBool touching = (PetscBool)(states[i] != SSSTAR_STATE_L && states[i] != SSSTAR_STATE_LS);
    const PetscReal ei       = touching ? PetscAbsReal(scene->gap[i]) : PetscMax(0, -scene->gap[i]);

    if (ei > e[0]) PetscCall(PetscInfo(NULL, "node %" PetscInt_FMT " (file index) %s, its gap at the solution %g, normal (%g, %g, %g), kept (%g, %g, %g)\n", scene->tag[i], touching ? "touching" : "separated", (double)scene->gap[i], (double)scene->normal[3 * i], (double)scene->normal[3 * i + 1], (double)scene->normal[3 * i + 2], (double)kept.normal[3 * i], (double)kept.normal[3 * i + 1], (double)kept.normal[3 * i + 2]));
    e[0] = PetscMax(e[0], ei);
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, e, 2, MPIU_REAL, MPI_MAX, scene->comm));
  *error      = e[0];
  *scale      = e[1];
  *consistent = (PetscBool)(e[0] <= scene->slidingTol * e[1] + tol);
  PetscCall(PutBack(scene, &kept, *consistent));
  if (!*consistent) PetscCall(LinearizeAt(scene, snes, u, PETSC_TRUE));
  PetscFunctionReturn(0);
}
