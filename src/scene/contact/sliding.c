/*
   Rigid obstacles that move (-obstacle_<G>_motion): a node's normal offset against its obstacle translated by d is the
   first-order gap g - n.d (docs/derivation.md (10.4); small sliding: gap and normal at the reference configuration),
   exact for a plane and first order in |d| for a ball, cylinder or mesh. Its error against the exact gap -- the node's
   distance to the translated obstacle, the obstacle asked at x - d -- is measured at every step: a step where it
   exceeds -small_sliding_tol times |d| at a node within |d| of the obstacle is refused, naming the obstacle, the step
   and the error, rather than solved with a gap the motion has made wrong.
*/
#include "../sceneimpl.h"

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
   SSStarSceneCheckSmallSliding - refuses the step to time t (the path's step number step, 1-based) when a moved
   obstacle's first-order gap g - n.d is off the exact gap by more than -small_sliding_tol |d| + the contact tolerance
   at a node of its group that is within |d| of it (by either gap). Collective.
*/
PetscErrorCode SSStarSceneCheckSmallSliding(SSStarScene scene, PetscInt step, PetscReal t)
{
  PetscInt  *group, moved = 0;
  PetscReal *x, *gap, *normal, *d, tol;
  WorstNode  worst = {PETSC_MIN_REAL, {0, 0, 0, 0, 0, 0, 0, 0}};

  PetscFunctionBegin;
  PetscCall(PetscCalloc1(3 * scene->nContact, &d)); /* the translations at t */
  for (PetscInt g = 0; g < scene->nContact; g++)
    if (scene->contact[g].motion && !scene->contact[g].master[0]) {
      PetscCall(SSStarHistoryEvaluate(scene->contact[g].motion, t, &d[3 * g]));
      moved++;
    }
  if (!moved) {
    PetscCall(PetscFree(d));
    PetscFunctionReturn(0);
  }
  PetscCall(SSStarSceneContactTolerance(scene, &tol));
  PetscCall(PetscMalloc4(scene->n + 1, &group, 3 * scene->n + 1, &x, scene->n + 1, &gap, 3 * scene->n + 1, &normal));
  for (PetscInt i = 0; i < scene->n; i++) {
    const SSStarContactGroup *cg = &scene->contact[scene->group[i]];

    group[i] = cg->motion && !cg->master[0] ? scene->group[i] : -1;
    for (PetscInt k = 0; k < 3; k++) x[3 * i + k] = scene->coords[3 * i + k] - d[3 * scene->group[i] + k]; /* the obstacle moved by d: x - d against it */
  }
  PetscCall(SSStarSceneObstacleGaps(scene, scene->n, group, x, tol, gap, normal));
  for (PetscInt i = 0; i < scene->n; i++) {
    const PetscReal *di = &d[3 * scene->group[i]], dd = PetscSqrtReal(SSStarDot3(di, di));
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
  PetscCall(PetscFree4(group, x, gap, normal));
  PetscCall(ShareWorst(scene->comm, &worst));
  if (worst.excess > 0) {
    const PetscInt            g  = (PetscInt)worst.data[0];
    const SSStarContactGroup *cg = &scene->contact[g];
    const PetscReal          *w = worst.data, dg[3] = {d[3 * g], d[3 * g + 1], d[3 * g + 2]};
    char                      shape[256];

    PetscCall(PetscFree(d));
    PetscCall(SSStarObstacleDescribe(cg->obstacle, shape, sizeof(shape)));
    SETERRQ(scene->comm, PETSC_ERR_ARG_OUTOFRANGE, "Step %" PetscInt_FMT " (t = %g): the obstacle of -obstacle_%s (%s) moved by (%g, %g, %g) (-obstacle_%s_motion): its first-order gap g - n.d = %g at mesh node %" PetscInt_FMT " (0-based, file order) at (%g, %g, %g) is off the exact gap %g by %g, more than -small_sliding_tol %g times |d| = %g: the motion is too large against the obstacle's curvature for small sliding", step, (double)t, cg->name, shape, (double)dg[0], (double)dg[1], (double)dg[2], cg->name, (double)w[5], (PetscInt)w[1], (double)w[2], (double)w[3], (double)w[4], (double)w[6], (double)PetscAbsReal(w[6] - w[5]), (double)scene->smallSlidingTol, (double)w[7]);
  }
  PetscCall(PetscFree(d));
  PetscFunctionReturn(0);
}
