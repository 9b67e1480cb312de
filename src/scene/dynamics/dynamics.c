/*
   Elastodynamics with contact and Coulomb friction (-dynamics, docs/derivation.md section 16): the steps of the path are
   time steps, each an affine problem for the solver ssstar with the contact and incremental friction of a load path:

     (16.5)  the predictor u^n + tau v^n projected onto the admissible set in the norm of M (-dynamics_scheme
             stabilized, Deuflhard-Krause-Ertel's contact-stabilized Newmark): a frictionless contact problem with M,
             solved by a second ssstar SNES; its velocity v~ = (u~ - u^n) / tau
     (16.6)  A u = b + r:  A = (1/2 + beta/tau) K + (2/tau^2 + alpha/tau) M,
             b = M (2/tau^2 u~ + alpha/tau u^n) + K ((beta/tau - 1/2) u^n) + (f^n + f^(n+1)) / 2,
             r the mean contact force of the step (the trapezoidal rule with the contact impulse of the step only)
     (16.7)  v^(n+1) = 2 (u^(n+1) - u^n) / tau - v~

   with Rayleigh damping C = alpha M + beta K (-damping alpha,beta). The energies of the step, their balance and what the
   scheme dissipates at impacts are kept for the table of the steps.
*/
#include "../sceneimpl.h"
#include <petsc/private/petscimpl.h> /* PetscObjectStateGet(): has the contact operator changed */

const char *const SSStarDynamicsSchemes[] = {"stabilized", "newmark", "SSStarDynamicsScheme", "SSSTAR_DYNAMICS_", NULL};

struct _n_SSStarDynamics {
  SSStarDynamicsScheme scheme;
  PetscBool            lumped;      /* -dynamics_mass lumped                                              */
  PetscReal            alpha, beta; /* -damping: C = alpha M + beta K                                    */
  PetscReal            velocity[3]; /* -initial_velocity                                                  */
  /* set up */
  Mat       K, M, A;                /* K (a reference), the mass, the step's operator (16.6)               */
  Vec       b;                      /* the step's load, the SNES's                                        */
  Vec       v, vTilde, fPrev;       /* v^n, the projected velocity, the load at the last accepted time     */
  Vec       w1, w2;                 /* work                                                               */
  PetscReal tau;                    /* the step A was built for (0: none yet)                             */
  SNES      projection;             /* (16.5): ssstar on M, frictionless (options -dynamics_projection_*) */
  PetscBool projectionReduction;    /* its reduction was given: else the step's solver's                  */
  Vec       projectionLoad;
  Mat       declared;               /* the contact operator declared to the projection, and its state      */
  PetscObjectState declaredState;
  /* the energies (16.8), cumulative, and the step's projection loss */
  PetscReal initial, kinetic, strain, work, impact, damping, friction, projectionLoss;
  /* contact episodes: steps in contact since the last step without */
  PetscInt  contactSteps;
  PetscReal contactStart;
};

/*
   SSStarDynamicsSetFromOptions - -dynamics and its options (every one refused without -dynamics, naming it); the per
   group -initial_velocity_<G> are read with the group options (sceneoptions.c)
*/
PetscErrorCode SSStarDynamicsSetFromOptions(SSStarScene scene)
{
  PetscBool      dynamics = PETSC_FALSE, set[4] = {PETSC_FALSE, PETSC_FALSE, PETSC_FALSE, PETSC_FALSE};
  SSStarDynamics d;
  PetscInt       scheme = SSSTAR_DYNAMICS_STABILIZED, mass = 0, n;
  PetscReal      damping[2] = {0, 0}, velocity[3] = {0, 0, 0};
  const char    *masses[] = {"consistent", "lumped"};

  PetscFunctionBegin;
  PetscOptionsBegin(scene->comm, NULL, "Dynamics: inertia, each step a time step (docs/derivation.md section 16)", "ssstar");
  PetscCall(PetscOptionsBool("-dynamics", "The steps of the path are time steps of elastodynamics (mass from -density)", NULL, dynamics, &dynamics, NULL));
  PetscCall(PetscOptionsEList("-dynamics_scheme", "stabilized (the predictor projected onto the admissible set: no energy gained at contact) or newmark (without the projection)", NULL, SSStarDynamicsSchemes, 2, SSStarDynamicsSchemes[scheme], &scheme, &set[0]));
  PetscCall(PetscOptionsEList("-dynamics_mass", "The mass matrix: consistent or lumped", NULL, masses, 2, masses[mass], &mass, &set[1]));
  n = 2;
  PetscCall(PetscOptionsRealArray("-damping", "Rayleigh damping alpha,beta: C = alpha M + beta K", NULL, damping, &n, &set[2]));
  PetscCheck(!set[2] || n == 2, scene->comm, PETSC_ERR_ARG_WRONG, "Option -damping needs 2 comma-separated values alpha,beta (got %" PetscInt_FMT ")", n);
  n = 3;
  PetscCall(PetscOptionsRealArray("-initial_velocity", "The initial velocity vx,vy,vz of every node (-initial_velocity_<G> for the nodes of a volume group)", NULL, velocity, &n, &set[3]));
  PetscCheck(!set[3] || n == 3, scene->comm, PETSC_ERR_ARG_WRONG, "Option -initial_velocity needs 3 comma-separated values vx,vy,vz (got %" PetscInt_FMT ")", n);
  PetscOptionsEnd();
  for (PetscInt k = 0; k < 4; k++) PetscCheck(dynamics || !set[k], scene->comm, PETSC_ERR_ARG_WRONG, "Option %s needs -dynamics", (const char *[]){"-dynamics_scheme", "-dynamics_mass", "-damping", "-initial_velocity"}[k]);
  PetscCheck(dynamics || !scene->nVelocities, scene->comm, PETSC_ERR_ARG_WRONG, "Option -initial_velocity_%s needs -dynamics", scene->nVelocities ? scene->velocities[0].name : "");
  for (PetscInt k = 0; k < 2; k++) PetscCheck(damping[k] >= 0 && !PetscIsInfOrNanReal(damping[k]), scene->comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -damping %g,%g: the coefficients must be numbers >= 0", (double)damping[0], (double)damping[1]);
  for (PetscInt k = 0; k < 3; k++) PetscCheck(!PetscIsInfOrNanReal(velocity[k]), scene->comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -initial_velocity: value %" PetscInt_FMT " is not a finite number", k + 1);
  PetscCall(SSStarDynamicsDestroy(scene));
  if (!dynamics) PetscFunctionReturn(0);
  PetscCall(PetscNew(&d));
  d->scheme = (SSStarDynamicsScheme)scheme;
  d->lumped = (PetscBool)(mass == 1);
  d->alpha  = damping[0];
  d->beta   = damping[1];
  PetscCall(PetscArraycpy(d->velocity, velocity, 3));
  scene->dynamics = d;
  if (d->scheme == SSSTAR_DYNAMICS_STABILIZED && scene->nContact) { /* (16.5)'s SNES: its options -dynamics_projection_* */
    PetscCall(SNESCreate(scene->comm, &d->projection));
    PetscCall(SNESSetOptionsPrefix(d->projection, "dynamics_projection_"));
    PetscCall(SNESSetType(d->projection, SNESSSSTAR));
    PetscCall(SNESSSStarSetFrictionLaw(d->projection, SSSTARLAWNONE));
    PetscCall(PetscOptionsHasName(NULL, "dynamics_projection_", "-snes_ssstar_reduction", &d->projectionReduction));
    PetscCall(SNESSetFromOptions(d->projection));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarDynamicsDestroy(SSStarScene scene)
{
  SSStarDynamics d = scene->dynamics;

  PetscFunctionBegin;
  if (!d) PetscFunctionReturn(0);
  PetscCall(MatDestroy(&d->K));
  PetscCall(MatDestroy(&d->M));
  PetscCall(MatDestroy(&d->A));
  PetscCall(VecDestroy(&d->b));
  PetscCall(VecDestroy(&d->v));
  PetscCall(VecDestroy(&d->vTilde));
  PetscCall(VecDestroy(&d->fPrev));
  PetscCall(VecDestroy(&d->w1));
  PetscCall(VecDestroy(&d->w2));
  PetscCall(SNESDestroy(&d->projection));
  PetscCall(VecDestroy(&d->projectionLoad));
  PetscCall(PetscFree(scene->dynamics));
  PetscFunctionReturn(0);
}

/* What the dynamics are (for the output's /scene): the scheme's name, the lumped mass, alpha and beta, v0 */
PetscErrorCode SSStarDynamicsDescribe(SSStarScene scene, const char **scheme, PetscBool *lumped, PetscReal damping[2], PetscReal velocity[3])
{
  SSStarDynamics d = scene->dynamics;

  PetscFunctionBegin;
  *scheme    = SSStarDynamicsSchemes[d->scheme];
  *lumped    = d->lumped;
  damping[0] = d->alpha;
  damping[1] = d->beta;
  PetscCall(PetscArraycpy(velocity, d->velocity, 3));
  PetscFunctionReturn(0);
}

/* The view's line of the dynamics */
PetscErrorCode SSStarDynamicsView(SSStarScene scene, PetscViewer viewer)
{
  SSStarDynamics d = scene->dynamics;

  PetscFunctionBegin;
  if (!d) PetscFunctionReturn(0);
  PetscCall(PetscViewerASCIIPrintf(viewer, "dynamics: scheme %s, %s mass, initial velocity (%g, %g, %g)%s", SSStarDynamicsSchemes[d->scheme], d->lumped ? "lumped" : "consistent", (double)d->velocity[0], (double)d->velocity[1], (double)d->velocity[2], scene->nVelocities ? " and per group" : ""));
  PetscCall(PetscViewerASCIIUseTabs(viewer, PETSC_FALSE));
  if (d->alpha > 0 || d->beta > 0) PetscCall(PetscViewerASCIIPrintf(viewer, ", Rayleigh damping %g M + %g K", (double)d->alpha, (double)d->beta));
  PetscCall(PetscViewerASCIIPrintf(viewer, "\n"));
  PetscCall(PetscViewerASCIIUseTabs(viewer, PETSC_TRUE));
  PetscFunctionReturn(0);
}

/* (1/2) x^T B x */
static PetscErrorCode HalfEnergy(Mat B, Vec x, Vec work, PetscReal *e)
{
  PetscScalar dot;

  PetscFunctionBegin;
  PetscCall(MatMult(B, x, work));
  PetscCall(VecDot(x, work, &dot));
  *e = 0.5 * PetscRealPart(dot);
  PetscFunctionReturn(0);
}

/*
   SSStarDynamicsSetUp - the mass, the step's operator A and load b (the SNES's problem: F(u) = A u - b), the initial
   velocity and the energy at t = 0, the projection's SNES (-dynamics_scheme stabilized, with contact)
*/
PetscErrorCode SSStarDynamicsSetUp(SSStarScene scene, SNES snes, Mat K, Vec load)
{
  SSStarDynamics d = scene->dynamics;
  MatNullSpace   near;

  PetscFunctionBegin;
  PetscCall(PetscObjectReference((PetscObject)K));
  d->K = K;
  PetscCall(SSStarAssembleMass(scene, K, d->lumped, &d->M)); /* mass.c */
  PetscCall(MatDuplicate(K, MAT_COPY_VALUES, &d->A));
  PetscCall(MatSetNullSpace(d->A, NULL)); /* the mass holds a floating body */
  PetscCall(MatGetNearNullSpace(K, &near));
  PetscCall(MatSetNearNullSpace(d->A, near));
  PetscCall(MatSetOption(d->A, MAT_SPD, PETSC_TRUE));
  PetscCall(VecDuplicate(load, &d->b));
  PetscCall(VecDuplicate(load, &d->v));
  PetscCall(VecDuplicate(load, &d->vTilde));
  PetscCall(VecDuplicate(load, &d->fPrev));
  PetscCall(VecDuplicate(load, &d->w1));
  PetscCall(VecDuplicate(load, &d->w2));
  PetscCall(SSStarInitialVelocity(scene, d->velocity, d->v)); /* mass.c */
  PetscCall(SSStarAssembleLoad(scene, 0, d->fPrev));         /* the load at t = 0 */
  PetscCall(HalfEnergy(d->M, d->v, d->w1, &d->initial));
  d->kinetic = d->initial;
  PetscCall(SNESSSStarSetLinearProblem(snes, d->A, d->b));
  if (d->projection) {
    PetscCall(VecDuplicate(load, &d->projectionLoad));
    PetscCall(SNESSSStarSetLinearProblem(d->projection, d->M, d->projectionLoad));
    if (!d->projectionReduction) { /* the path of the step's solver */
      SSStarReductionType type;

      PetscCall(SNESSSStarGetReductionType(snes, &type));
      PetscCall(SNESSSStarSetReductionType(d->projection, type));
    }
  }
  PetscFunctionReturn(0);
}

/* The step tau's operator A (16.6), built again only when tau changes (a cut step): the solver then reduces it again */
static PetscErrorCode StepOperator(SSStarDynamics d, PetscReal tau)
{
  PetscFunctionBegin;
  if (tau == d->tau) PetscFunctionReturn(0);
  PetscCall(MatCopy(d->K, d->A, SAME_NONZERO_PATTERN));
  PetscCall(MatScale(d->A, 0.5 + d->beta / tau));
  PetscCall(MatAXPY(d->A, 2 / (tau * tau) + d->alpha / tau, d->M, SAME_NONZERO_PATTERN));
  d->tau = tau;
  PetscFunctionReturn(0);
}

/*
   (16.5): u~, the predictor p = u^n + tau v^n projected onto the admissible set of the step's linearization in the
   norm of M, into p; left as it is where it is admissible (every contact node's linearized gap B_n p + o_n >= 0). The
   projection is solved for its correction x = u~ - p: M x = r with w = B x + (B p + o), so that its contact forces are
   measured against themselves, not against M p
*/
static PetscErrorCode Project(SSStarScene scene, Vec p, SNESConvergedReason *reason)
{
  SSStarDynamics     d = scene->dynamics;
  const PetscScalar *wa;
  PetscReal          tol, worst = PETSC_MAX_REAL;
  PetscObjectState   state;
  Vec                shifted, x;

  PetscFunctionBegin;
  *reason = SNES_CONVERGED_FNORM_ABS;
  if (!d->projection) PetscFunctionReturn(0);
  PetscCall(SSStarSceneContactTolerance(scene, &tol));
  PetscCall(MatCreateVecs(scene->B, NULL, &shifted));
  PetscCall(MatMultAdd(scene->B, p, scene->offsets, shifted)); /* B p + o: the predictor's w */
  PetscCall(VecGetArrayRead(shifted, &wa));
  for (PetscInt i = 0; i < scene->n; i++) worst = PetscMin(worst, PetscRealPart(wa[3 * i + 2]));
  PetscCall(VecRestoreArrayRead(shifted, &wa));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &worst, 1, MPIU_REAL, MPIU_MIN, scene->comm));
  if (worst >= -tol) {
    PetscCall(VecDestroy(&shifted));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscObjectStateGet((PetscObject)scene->B, &state));
  if (scene->B != d->declared || state != d->declaredState) { /* the step's linearization (large sliding: new each step) */
    Vec gaps;

    PetscCall(SSStarSceneNodeVec(scene, 1, scene->gap, &gaps));
    PetscCall(SNESSSStarSetContactOperator(d->projection, scene->isC, scene->B, gaps));
    PetscCall(VecDestroy(&gaps));
    d->declared      = scene->B;
    d->declaredState = state;
  }
  PetscCall(SNESSSStarSetContactOffsets(d->projection, shifted));
  PetscCall(VecZeroEntries(d->projectionLoad)); /* min 1/2 |x|_M^2 on the shifted set: M x + contact = 0 */
  PetscCall(VecDuplicate(p, &x));
  PetscCall(VecZeroEntries(x));
  PetscCall(SNESSolve(d->projection, NULL, x));
  PetscCall(SNESGetConvergedReason(d->projection, reason));
  PetscCall(VecAXPY(p, 1.0, x));
  PetscCall(SNESSSStarSetContactOffsets(d->projection, NULL)); /* shifted is freed */
  PetscCall(VecDestroy(&x));
  PetscCall(VecDestroy(&shifted));
  PetscFunctionReturn(0);
}

/*
   SSStarDynamicsBeginStep - the time step to t from the last accepted one (the start t = 0 before the first), after
   the step's contact was set (SSStarSceneSetStep()) or linearized again (SSStarSceneCheckStep()): A and b of (16.6)
   for the SNES, with the stabilized scheme the projected predictor (16.5); with guess, u~ into u (the solve's start).
   reason: the projection's, <= 0 when it did not converge (the step fails)
*/
PetscErrorCode SSStarDynamicsBeginStep(SSStarScene scene, PetscReal t, Vec u, PetscBool guess, SNESConvergedReason *reason)
{
  SSStarDynamics  d = scene->dynamics;
  const PetscReal start = scene->stepped ? scene->acceptedTime : 0, tau = t - start;
  Vec             un = scene->stepStart, uTilde = d->w2;
  PetscReal       before, after;

  PetscFunctionBegin;
  PetscCheck(tau > 0, scene->comm, PETSC_ERR_ARG_OUTOFRANGE, "The time %g of a step of -dynamics is not after %g, where the %s", (double)t, (double)start, scene->stepped ? "last accepted step ends" : "motion starts (t = 0)");
  PetscCall(StepOperator(d, tau));
  PetscCall(VecWAXPY(uTilde, tau, d->v, un)); /* the predictor u^n + tau v^n */
  PetscCall(Project(scene, uTilde, reason));
  if (*reason <= 0) PetscFunctionReturn(0);
  PetscCall(VecWAXPY(d->vTilde, -1.0, un, uTilde));
  PetscCall(VecScale(d->vTilde, 1 / tau));
  PetscCall(HalfEnergy(d->M, d->v, d->w1, &before));
  PetscCall(HalfEnergy(d->M, d->vTilde, d->w1, &after));
  d->projectionLoss = before - after;
  /* b = M (2/tau^2 u~ + alpha/tau u^n) + K ((beta/tau - 1/2) u^n) + (f^n + f^(n+1))/2 */
  PetscCall(VecCopy(uTilde, d->w1));
  PetscCall(VecAXPBY(d->w1, d->alpha / tau, 2 / (tau * tau), un));
  PetscCall(MatMult(d->M, d->w1, d->b));
  PetscCall(VecCopy(un, d->w1));
  PetscCall(VecScale(d->w1, d->beta / tau - 0.5));
  PetscCall(MatMultAdd(d->K, d->w1, d->b, d->b));
  PetscCall(VecAXPBYPCZ(d->b, 0.5, 0.5, 1.0, d->fPrev, scene->stepLoad));
  if (guess) PetscCall(VecCopy(uTilde, u));
  PetscFunctionReturn(0);
}

/* The cumulative friction dissipation of every contact node (10.9), summed */
static PetscErrorCode FrictionDissipation(SSStarScene scene, PetscReal *D)
{
  PetscFunctionBegin;
  *D = 0;
  for (PetscInt i = 0; i < scene->n; i++) *D += scene->dissipation[i];
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, D, 1, MPIU_REAL, MPIU_SUM, scene->comm));
  PetscFunctionReturn(0);
}

/*
   The work of the moving obstacles on the body in the step: sum over the contact nodes of r_i . (d_i^(n+1) - d_i^n),
   the motion of the obstacle's point each faces (16.3)
*/
static PetscErrorCode ObstacleWork(SSStarScene scene, Vec r, PetscReal *W)
{
  const PetscScalar *ra;
  Vec                rC;

  PetscFunctionBegin;
  *W = 0;
  PetscCall(VecGetSubVector(r, scene->isC, &rC));
  PetscCall(VecGetArrayRead(rC, &ra));
  for (PetscInt i = 0; i < scene->n; i++) {
    const SSStarMotion *motion = &scene->contact[scene->group[i]].motion;
    PetscReal           now[3], before[3];

    SSStarSceneObstacleDisplacement(scene, i, &motion->now, now);
    SSStarSceneObstacleDisplacement(scene, i, &motion->before, before);
    for (PetscInt k = 0; k < 3; k++) *W += PetscRealPart(ra[3 * i + k]) * (now[k] - before[k]);
  }
  PetscCall(VecRestoreArrayRead(rC, &ra));
  PetscCall(VecRestoreSubVector(r, scene->isC, &rC));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, W, 1, MPIU_REAL, MPIU_SUM, scene->comm));
  PetscFunctionReturn(0);
}

/*
   SSStarDynamicsAccept - the step's solution u (r = A u - b: the mean contact force of the step at the contact dofs)
   accepted, before the scene forgets u^n (its stepStart) and where the obstacles were: the velocity (16.7), the
   energies and their balance (16.8); a contact that lasted fewer than 3 steps is said (the steps do not resolve it)
*/
PetscErrorCode SSStarDynamicsAccept(SSStarScene scene, SNES snes, Vec u, Vec r)
{
  SSStarDynamics d = scene->dynamics;
  Vec            du = d->w2;
  PetscScalar    dot;
  PetscReal      tau = d->tau, loads, contact, obstacles, friction, damping, e;
  PetscInt       touching = 0;

  PetscFunctionBegin;
  PetscCall(VecWAXPY(du, -1.0, scene->stepStart, u)); /* u^(n+1) - u^n */
  /* the work of the loads (f^n + f^(n+1))/2 . du and of the contact forces r . du */
  PetscCall(VecAXPBY(d->fPrev, 0.5, 0.5, scene->stepLoad)); /* (f^n + f^(n+1))/2 */
  PetscCall(VecDot(d->fPrev, du, &dot));
  loads = PetscRealPart(dot);
  PetscCall(VecDot(r, du, &dot));
  contact = PetscRealPart(dot);
  PetscCall(ObstacleWork(scene, r, &obstacles));
  /* Rayleigh damping: du^T C du / tau */
  PetscCall(HalfEnergy(d->M, du, d->w1, &e));
  damping = 2 * d->alpha * e / tau;
  PetscCall(HalfEnergy(d->K, du, d->w1, &e));
  damping += 2 * d->beta * e / tau;
  /* v^(n+1) = 2 du / tau - v~ */
  PetscCall(VecCopy(du, d->v));
  PetscCall(VecAXPBY(d->v, -1.0, 2 / tau, d->vTilde));
  PetscCall(HalfEnergy(d->M, d->v, d->w1, &d->kinetic));
  PetscCall(HalfEnergy(d->K, u, d->w1, &d->strain));
  PetscCall(FrictionDissipation(scene, &friction));
  d->work += loads + obstacles;
  d->damping += damping;
  /* what the scheme dissipates at impacts: the projection's loss and sum lambda_n g^n = W_obstacles - r.du - D_friction */
  d->impact += d->projectionLoss + obstacles - contact - (friction - d->friction);
  d->friction = friction;
  PetscCall(VecCopy(scene->stepLoad, d->fPrev));
  /* contact episodes */
  if (scene->nContact) {
    const SSStarState *states;

    PetscCall(SNESSSStarGetStates(snes, &states, NULL));
    for (PetscInt i = 0; i < scene->n; i++) touching += states[i] != SSSTAR_STATE_L && states[i] != SSSTAR_STATE_LS;
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &touching, 1, MPIU_INT, MPI_SUM, scene->comm));
  }
  if (touching) {
    if (!d->contactSteps) d->contactStart = scene->stepTime;
    d->contactSteps++;
  } else {
    if (d->contactSteps && d->contactSteps < 3) PetscCall(PetscPrintf(scene->comm, "dynamics: a contact lasted %" PetscInt_FMT " step%s (t %g to %g): the time step %g does not resolve the impact (its duration and force); give smaller steps\n", d->contactSteps, d->contactSteps > 1 ? "s" : "", (double)d->contactStart, (double)scene->acceptedTime, (double)tau));
    d->contactSteps = 0;
  }
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneGetEnergies - the energies of a scene with -dynamics after its last accepted step (docs/derivation.md
   (16.8)): kinetic 1/2 v^T M v, strain 1/2 u^T K u, the work of the loads and of the moving obstacles since t = 0, the
   energy dissipated by friction, by Rayleigh damping and by the scheme at impacts, and the balance

   Not Collective

   Input Parameter:
.  scene - the scene

   Output Parameters:
+  energies - the energies (zero without -dynamics)
-  dynamics - whether the scene has -dynamics, or pass NULL

   Notes:
   error = kinetic + strain + friction + damping - (initial + work) is what the scheme gained (> 0) or lost (< 0); the
   stabilized scheme gains nothing at contact: error = -impact up to the solver's tolerance, impact >= 0 with obstacles
   at rest.

   Level: intermediate

.seealso: `SSStarSceneAdvance()`, `SSStarSceneGetStepRow()`
@*/
PetscErrorCode SSStarSceneGetEnergies(SSStarScene scene, SSStarEnergies *energies, PetscBool *dynamics)
{
  SSStarDynamics d = scene->dynamics;

  PetscFunctionBegin;
  PetscCall(PetscMemzero(energies, sizeof(*energies)));
  if (dynamics) *dynamics = (PetscBool)(d != NULL);
  if (!d) PetscFunctionReturn(0);
  energies->initial  = d->initial;
  energies->kinetic  = d->kinetic;
  energies->strain   = d->strain;
  energies->work     = d->work;
  energies->friction = d->friction;
  energies->damping  = d->damping;
  energies->impact   = d->impact;
  energies->error    = d->kinetic + d->strain + d->friction + d->damping - d->initial - d->work;
  PetscFunctionReturn(0);
}

/* The velocity of the last accepted step (v^0 before the first), or NULL without -dynamics */
PetscErrorCode SSStarDynamicsGetVelocity(SSStarScene scene, Vec *v)
{
  PetscFunctionBegin;
  *v = scene->dynamics ? scene->dynamics->v : NULL;
  PetscFunctionReturn(0);
}
