/*
   The stepper of a scene's path, one for every program (examples/contact, the Python module): the times of the path,
   each step solved from the last accepted one -- with large sliding solved again, linearized at its solution, while the
   contact measured there moves (SSStarSceneCheckStep()) --, and a step that does not converge retried at the midpoint
   towards the last accepted time and carried on to its time in sub-steps of that size, at most a given number of
   halvings per step. The program prints what it likes of each step (SSStarStep) and decides what comes next.
*/
#include "../sceneimpl.h"

/*@C
   SSStarSceneGetPathTimes - the times of the scene's path: the value of -steps (a list of times, or a count of equal
   steps between the first and the last knot), by default the knots of its histories, or one step at t = 0 when the
   loads and motions are constants

   Collective

   Input Parameters:
+  scene - the scene, after SSStarSceneSetFromOptions()
-  steps - the value of -steps, or NULL for the default

   Output Parameters:
+  n     - the number of times (at least 1)
-  times - the times, increasing (free with PetscFree())

   Notes:
   A malformed -steps (a count 0, negative or fractional, a time that is not a finite number, times that do not
   increase) is refused with an error naming -steps (SSStarHistoryParseSteps()): call it before the mesh is made.
   Without knots, -end_time T gives -steps N its span [0, T]. With -dynamics the motion starts at t = 0: -steps is
   required, a time 0 is the initial state (dropped) and a time before it refused.

   Level: intermediate

.seealso: `SSStarSceneAdvance()`, `SSStarSceneGetKnots()`, `SSStarHistoryParseSteps()`
@*/
PetscErrorCode SSStarSceneGetPathTimes(SSStarScene scene, const char steps[], PetscInt *n, PetscReal *times[])
{
  PetscInt   nknots;
  PetscReal *knots;

  PetscFunctionBegin;
  PetscCall(SSStarSceneGetKnots(scene, &nknots, &knots));
  if (scene->endTime > 0 && !nknots) { /* -end_time: the span of -steps N */
    PetscCall(PetscFree(knots));
    PetscCall(PetscMalloc1(2, &knots));
    knots[0] = 0;
    knots[1] = scene->endTime;
    nknots   = 2;
  }
  PetscCheck(!scene->dynamics || steps, scene->comm, PETSC_ERR_ARG_WRONG, "Option -dynamics needs -steps: the times t1,t2,... of the time steps, or a count N of equal steps from 0 to the last knot of the histories (or to -end_time)");
  PetscCall(SSStarHistoryParseSteps(scene->comm, "-steps", steps, nknots, knots, n, times));
  PetscCall(PetscFree(knots));
  if (scene->dynamics) { /* the motion starts at t = 0: a time 0 is the initial state, not a step */
    PetscInt k = 0;

    for (PetscInt j = 0; j < *n; j++) {
      PetscCheck((*times)[j] >= 0, scene->comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -steps: the time %g is before t = 0, where the motion of -dynamics starts", (double)(*times)[j]);
      if ((*times)[j] > 0) (*times)[k++] = (*times)[j];
    }
    *n = k;
    PetscCheck(k, scene->comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -steps: -dynamics needs a time after t = 0");
  }
  if (!*n) { /* constant loads and motions: one step */
    PetscCall(PetscFree(*times));
    PetscCall(PetscMalloc1(1, times));
    (*times)[0] = 0;
    *n          = 1;
  }
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneSetSolver - hands the scene's problem to the SNES that solves it: F(u) = K u - load with Jacobian K, or a
   hyperelastic scene's residual and tangent (SSStarSceneSetProblem()), and, with contact groups, the contact
   (SSStarSceneSetContact()); with -dynamics the time step's F(u) = A u - b instead (docs/derivation.md (16.6)), the
   load then the physical load of the step

   Collective

   Input Parameters:
+  scene - the scene, after SSStarSceneSetUp()
.  snes  - the SNES: an ssstar with contact groups, any SNES without (a linear solve)
.  K     - the stiffness (SSStarSceneAssemble())
-  load  - the load vector the SNES keeps: the steps of a path (SSStarSceneSolveStep(), SSStarSceneAdvance()) assemble
           their load into it; a static program sets its values itself

   Level: beginner

.seealso: `SSStarSceneAssemble()`, `SSStarSceneSetContact()`, `SSStarSceneSolveStep()`, `SSStarSceneAdvance()`
@*/
PetscErrorCode SSStarSceneSetSolver(SSStarScene scene, SNES snes, Mat K, Vec load)
{
  PetscFunctionBegin;
  if (scene->dynamics) PetscCall(SSStarDynamicsSetUp(scene, snes, K, load)); /* dynamics/dynamics.c */
  else PetscCall(SSStarSceneSetProblem(scene, snes, K, load));
  if (scene->nContact) PetscCall(SSStarSceneSetContact(scene, snes));
  PetscCall(PetscObjectReference((PetscObject)load));
  PetscCall(VecDestroy(&scene->stepLoad));
  scene->stepLoad = load;
  scene->solver   = snes;
  PetscFunctionReturn(0);
}

/* A step's outcome before its solve */
static void ClearStep(SSStarStep *step, PetscReal t)
{
  step->time           = t;
  step->cuts           = 0;
  step->linearizations = 0;
  step->iterations     = 0;
  step->reason         = SNES_CONVERGED_ITERATING;
  step->accepted       = PETSC_FALSE;
  step->reached        = PETSC_FALSE;
  step->stopped        = PETSC_FALSE;
  step->noEquilibrium  = PETSC_FALSE;
  step->retry          = t;
  step->why            = NULL;
}

/*@C
   SSStarSceneSolveStep - solves the step of the scene's path at the time t from the last accepted step (the reference
   before the first): the load at t, the obstacles where their motions put them at t, incremental friction from the
   last accepted step; with large sliding solved again, linearized at its solution, while the contact measured there
   moves. Not accepted: SSStarSceneAcceptStep() accepts it, another solve replaces it

   Collective

   Input Parameters:
+  scene - the scene, after SSStarSceneSetSolver()
.  snes  - its SNES
.  u     - the displacement: set to the last accepted step's, then the step's solution (or its last iterate)
-  t     - the time of the step, not before the last accepted step's

   Output Parameter:
.  step - what the step was: its time, linearizations and their iterations in all, its SNESConvergedReason (a contact
          that did not settle in -sliding_max_it linearizations is SNES_DIVERGED_MAX_IT) and why it did not converge

   Level: intermediate

.seealso: `SSStarSceneAdvance()`, `SSStarSceneAcceptStep()`, `SSStarSceneSetStep()`, `SSStarSceneCheckStep()`
@*/
PetscErrorCode SSStarSceneSolveStep(SSStarScene scene, SNES snes, Vec u, PetscReal t, SSStarStep *step)
{
  PetscBool consistent = PETSC_TRUE, again = PETSC_TRUE;

  PetscFunctionBegin;
  PetscCheck(scene->stepLoad, scene->comm, PETSC_ERR_ARG_WRONGSTATE, "SSStarSceneSolveStep: call SSStarSceneSetSolver() first");
  PetscCheck(!PetscIsInfOrNanReal(t), scene->comm, PETSC_ERR_ARG_OUTOFRANGE, "The time %g of a step is not a finite number", (double)t);
  PetscCheck(!scene->stepped || t >= scene->acceptedTime, scene->comm, PETSC_ERR_ARG_OUTOFRANGE, "The time %g of a step is before the last accepted step's, %g: a path goes forward in time", (double)t, (double)scene->acceptedTime);
  ClearStep(step, t);
  if (!scene->stepStart) { /* the first step starts from u as it is */
    PetscCall(VecDuplicate(u, &scene->stepStart));
    PetscCall(VecCopy(u, scene->stepStart));
  }
  PetscCall(SSStarSceneAssembleLoad(scene, t, scene->stepLoad));
  PetscCall(SSStarSceneSetStep(scene, snes, t));
  PetscCall(VecCopy(scene->stepStart, u));
  while (again) {
    PetscInt  its;
    PetscBool linear;

    if (scene->dynamics) { /* the time step's A and b (after a new linearization: its projection again) */
      PetscCall(SSStarDynamicsBeginStep(scene, t, u, (PetscBool)!step->linearizations, &step->reason));
      if (step->reason <= 0) {
        step->why = "the projection of the predictor onto the admissible set (-dynamics_scheme stabilized) did not converge";
        PetscCall(SNESSetConvergedReason(snes, step->reason));
        PetscFunctionReturn(0);
      }
    }
    PetscCall(SNESSolve(snes, NULL, u));
    PetscCall(SNESGetConvergedReason(snes, &step->reason));
    PetscCall(PetscObjectTypeCompare((PetscObject)snes, SNESKSPONLY, &linear));
    its = 0; /* none for one linear solve (ksponly) */
    if (!linear) PetscCall(SNESGetIterationNumber(snes, &its));
    step->linearizations++;
    step->iterations += its;
    if (step->reason <= 0) {
      step->why = SNESConvergedReasons[step->reason];
      PetscFunctionReturn(0);
    }
    PetscCall(SSStarSceneCheckStep(scene, snes, u, &consistent, &again));
  }
  if (!consistent) { /* so for the file too (its row, failed_step, converged_reason) */
    step->reason = SNES_DIVERGED_MAX_IT;
    step->why    = "the contact measured at its solution did not settle in -sliding_max_it linearizations";
    PetscCall(SNESSetConvergedReason(snes, step->reason));
  }
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneAdvance - the next step of the scene's path towards the time target: solved from the last accepted step
   (SSStarSceneSolveStep()) and, converged, accepted (SSStarSceneAcceptStep()) and written into the file being written
   (SSStarSceneOutputBegin()); a step that does not converge is halved towards the last accepted time (the first step
   towards its histories' start), at most maxCuts times, and the path goes on to target in sub-steps of the halved size

   Collective

   Input Parameters:
+  scene   - the scene, after SSStarSceneSetSolver()
.  snes    - its SNES
.  u       - the displacement: the step's solution (or the last iterate of a step that failed)
.  target  - the time to reach; call again with the same target until step->reached or step->stopped
-  maxCuts - the halvings of a step before the path stops (-steps_max_cuts)

   Output Parameter:
.  step - what the call did: a step accepted at step->time (step->reached when that is target), or one that did not
          converge and is retried at step->retry (neither accepted nor stopped), or the path's end (step->stopped: after
          maxCuts halvings, or at once where no equilibrium exists, step->noEquilibrium); step->cuts the halvings so far,
          step->why why a solve failed

   Notes:
   A step that stops the path is written with its last iterate, so that the file says where it stopped (failed_step,
   failed_time). Where no equilibrium exists at t no sub-step reaches it: the path stops without halving.

   Level: intermediate

.seealso: `SSStarSceneSolveStep()`, `SSStarSceneGetPathTimes()`, `SSStarSceneOutputBegin()`, `SSStarSceneAcceptStep()`
@*/
PetscErrorCode SSStarSceneAdvance(SSStarScene scene, SNES snes, Vec u, PetscReal target, PetscInt maxCuts, SSStarStep *step)
{
  SSStarStepper *s = &scene->stepper;

  PetscFunctionBegin;
  PetscCheck(maxCuts >= 0, scene->comm, PETSC_ERR_ARG_OUTOFRANGE, "-steps_max_cuts %" PetscInt_FMT ": must be >= 0", maxCuts);
  if (!s->active || s->target != target) { /* a new step of the path */
    s->active = PETSC_TRUE;
    s->target = target;
    s->t      = target;
    s->dt     = 0;
    s->cuts   = 0;
  }
  PetscCall(SSStarSceneSolveStep(scene, snes, u, s->t, step));
  step->cuts = s->cuts;
  if (step->reason > 0) {
    Vec r;

    PetscCall(SNESGetFunction(snes, &r, NULL, NULL));
    PetscCall(SSStarSceneAcceptStep(scene, u, r));
    if (scene->output) PetscCall(SSStarSceneOutputStep(scene, snes, u, s->cuts));
    step->accepted = PETSC_TRUE;
    step->reached  = (PetscBool)(s->t == target);
    s->active      = (PetscBool)!step->reached;
    s->t           = s->t + s->dt < target - 1e-6 * s->dt ? s->t + s->dt : target; /* on to the step's time in sub-steps of
                                                                            the cut size (a rounding's remainder: to it) */
    step->retry    = s->t;
  } else {
    PetscInt     nknots;
    PetscReal   *knots, from;
    SSStarReason sub = SSSTAR_REASON_ITERATING;
    PetscBool    isssstar;

    PetscCall(SSStarSceneGetKnots(scene, &nknots, &knots));
    from = scene->stepped ? scene->acceptedTime : (nknots ? PetscMin(knots[0], s->t) : s->t);
    PetscCall(PetscFree(knots));
    PetscCall(PetscObjectTypeCompare((PetscObject)snes, SNESSSSTAR, &isssstar));
    if (isssstar && scene->nContact) PetscCall(SNESSSStarGetReason(snes, &sub));
    step->noEquilibrium = (PetscBool)(sub == SSSTAR_REASON_NO_EQUILIBRIUM);
    if (s->cuts < maxCuts && s->t > from && !step->noEquilibrium) {
      s->cuts++;
      s->dt       = (s->t - from) / 2;
      s->t        = from + s->dt;
      step->retry = s->t;
    } else {
      if (scene->output) PetscCall(SSStarSceneOutputStep(scene, snes, u, s->cuts)); /* its last iterate */
      step->stopped = PETSC_TRUE;
      s->active     = PETSC_FALSE;
    }
  }
  PetscFunctionReturn(0);
}
