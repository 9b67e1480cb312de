/*
   The SNES type "ssstar": semismooth* Newton method for 0 in c(u) + Q(u) (docs/derivation.md section 7), on the contact
   dofs of a reduced problem or on the whole body (problem.c says which: the layout of the stiffness A's vectors). The
   iteration is here; the per-node work in nodesteps.c, the globalization in globalization.c, the declaration in
   contact.c and friction.c, the problem in problem.c, options and views in view.c. Each public function sits beside the
   type's implementation in the file of its concept, composed from there (SNESSSStarComposeFunctions()).
*/
#include "ssstarimpl.h"

const char *const SSStarMethods[] = {"newton", "fixedpoint", "SSStarMethod", "SSSTAR_METHOD_", NULL};
const char *const SSStarReasons[] = {"ITERATING", "CONVERGED_ABSOLUTE", "CONVERGED_RELATIVE", "MAX_IT", "NAN_OR_INF", "SINGULAR_NEWTON_MATRIX", "STAGNATION", "CYCLE", "LAW_STALLED", "NO_EQUILIBRIUM", "USER_TEST", "NOT_AFFINE", "SSStarReason", "SSSTAR_REASON_", NULL};

/*
   gamma = 1/mean(diag K_CC) unless the user set it (section 6); the fixed-point baseline takes 1/(the largest sum
   |K_ij| of a contact row), which bounds 1/lambda_max(P) from below: a step short enough to converge. In the reduced
   use K_CC is P itself.
*/
static PetscErrorCode SNESSSStarComputeScaling(SNES snes)
{
  SNES_SSStar   *ss = (SNES_SSStar *)snes->data;
  SSStarProblem *pb = &ss->problem;

  PetscFunctionBegin;
  if (ss->scaling_user > 0) {
    ss->scaling = ss->scaling_user;
    PetscFunctionReturn(0);
  }
  if (ss->method == SSSTAR_METHOD_FIXEDPOINT) {
    PetscCheck(pb->maxRowSum > 0, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_WRONG, "ssstar: the contact rows of the stiffness sum to %g, not positive; set -snes_ssstar_scaling", (double)pb->maxRowSum);
    ss->scaling = 1 / pb->maxRowSum;
    PetscFunctionReturn(0);
  }
  PetscCheck(pb->meanDiag > 0, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_WRONG, "ssstar: the mean diagonal entry of the stiffness at the contact dofs is %g, not positive; set -snes_ssstar_scaling", (double)pb->meanDiag);
  ss->scaling = 1 / pb->meanDiag;
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSetUp_SSStar(SNES snes)
{
  SNES_SSStar *ss = (SNES_SSStar *)snes->data;
  PetscInt     n;

  PetscFunctionBegin;
  PetscCheck(snes->jacobian, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_WRONGSTATE, "ssstar needs the matrix K (or P): call SNESSetJacobian() or SNESSSStarSetLinearProblem()");
  PetscCall(SSStarContactSetUp(snes, &ss->contact, NULL));
  n = ss->contact.nnodes;
  PetscCall(PetscFree2(ss->states, ss->userStates));
  PetscCall(PetscFree2(ss->S, ss->T));
  PetscCall(PetscCalloc2(n, &ss->states, n, &ss->userStates));
  PetscCall(PetscMalloc2(9 * n, &ss->S, 9 * n, &ss->T));
  PetscCall(VecDestroy(&ss->d));
  PetscCall(VecDestroy(&ss->b));
  PetscCall(VecCreateMPI(PetscObjectComm((PetscObject)snes), 3 * n, PETSC_DETERMINE, &ss->d));
  PetscCall(VecDuplicate(ss->d, &ss->b));
  PetscFunctionReturn(0);
}

/* The vectors of the iteration, in the layout of the stiffness A (they change with it) */
static PetscErrorCode CreateWorkVectors(SNES snes)
{
  SNES_SSStar *ss = (SNES_SSStar *)snes->data;
  PetscInt     n = -1, m;
  PetscBool    fits;

  PetscFunctionBegin;
  PetscCall(MatGetLocalSize(ss->problem.A, &m, NULL));
  if (ss->u) PetscCall(VecGetLocalSize(ss->u, &n));
  fits = (PetscBool)(n == m); /* decided together: a rank may own no dof of either layout */
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &fits, 1, MPIU_BOOL, MPI_LAND, PetscObjectComm((PetscObject)snes)));
  if (fits) PetscFunctionReturn(0);
  PetscCall(VecDestroy(&ss->u));
  PetscCall(MatCreateVecs(ss->problem.A, &ss->u, NULL));
  for (Vec *w = &ss->c; w <= &ss->ca; w++) {
    PetscCall(VecDestroy(w));
    PetscCall(VecDuplicate(ss->u, w));
  }
  PetscFunctionReturn(0);
}

/* The sub-reason behind the SNESConvergedReason the convergence test gave */
static SSStarReason SubReason(SNES snes)
{
  if (snes->ops->converged != SNESConvergedSSStar) return SSSTAR_REASON_USER;
  switch (snes->reason) {
  case SNES_CONVERGED_FNORM_ABS:
    return SSSTAR_REASON_CONVERGED_ABS;
  case SNES_CONVERGED_FNORM_RELATIVE:
    return SSSTAR_REASON_CONVERGED_REL;
  case SNES_DIVERGED_FNORM_NAN:
    return SSSTAR_REASON_NAN;
  default:
    return SSSTAR_REASON_USER;
  }
}

/* The first entry of v that is NaN or Inf (global index), or -1 */
static PetscErrorCode FirstNonFinite(Vec v, PetscInt *first)
{
  const PetscScalar *a;
  PetscInt           n, lo, mine = PETSC_MAX_INT;

  PetscFunctionBegin;
  PetscCall(VecGetLocalSize(v, &n));
  PetscCall(VecGetOwnershipRange(v, &lo, NULL));
  PetscCall(VecGetArrayRead(v, &a));
  for (PetscInt i = 0; i < n; i++)
    if (PetscIsInfOrNanScalar(a[i])) {
      mine = lo + i;
      break;
    }
  PetscCall(VecRestoreArrayRead(v, &a));
  PetscCall(MPIU_Allreduce(&mine, first, 1, MPIU_INT, MPI_MIN, PetscObjectComm((PetscObject)v)));
  if (*first == PETSC_MAX_INT) *first = -1;
  PetscFunctionReturn(0);
}

/* " (node 3 of the solver's order)" after the position of a contact dof in a reduced space; nothing on the whole body */
static PetscErrorCode NodeOfRow(SSStarProblem *pb, PetscInt row, char buf[], size_t len)
{
  PetscFunctionBegin;
  buf[0] = 0;
  if (!pb->wholeBody) PetscCall(PetscSNPrintf(buf, len, " (node %" PetscInt_FMT " of the solver's order)", row / 3));
  PetscFunctionReturn(0);
}

/* Refuses what no iteration can solve: NaN or Inf in A, f or the initial guess, tolerances that are not numbers */
static PetscErrorCode CheckProblem(SNES snes)
{
  SNES_SSStar   *ss    = (SNES_SSStar *)snes->data;
  SSStarProblem *pb    = &ss->problem;
  MPI_Comm       comm  = PetscObjectComm((PetscObject)snes);
  PetscBool      whole = pb->wholeBody;
  const char    *dof   = whole ? "dof" : "contact dof";
  char           node[64];
  Vec            rowsum;
  PetscInt       first;

  PetscFunctionBegin;
  PetscCheck(snes->rtol >= 0 && snes->rtol < 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "-snes_rtol %g: must be in [0, 1)", (double)snes->rtol);
  PetscCheck(snes->abstol >= 0 && !PetscIsInfOrNanReal(snes->abstol), comm, PETSC_ERR_ARG_OUTOFRANGE, "-snes_atol %g: must be a number >= 0", (double)snes->abstol);
  PetscCall(VecDuplicate(pb->f, &rowsum)); /* A 1: a row with a NaN or an Inf sums to NaN or Inf */
  PetscCall(VecSet(ss->ut, 1.0));
  PetscCall(MatMult(pb->A, ss->ut, rowsum));
  PetscCall(FirstNonFinite(rowsum, &first));
  PetscCall(VecDestroy(&rowsum));
  PetscCall(NodeOfRow(pb, first, node, sizeof(node)));
  PetscCheck(first < 0, comm, PETSC_ERR_FP, "ssstar: the %s has NaN or Inf entries in row %" PetscInt_FMT "%s: the stiffness K is not finite", whole ? "stiffness K" : "reduced stiffness P", first, node);
  PetscCall(FirstNonFinite(pb->f, &first));
  PetscCall(NodeOfRow(pb, first, node, sizeof(node)));
  PetscCheck(first < 0, comm, PETSC_ERR_FP, "ssstar: the %s is NaN or Inf at %s %" PetscInt_FMT "%s: the load b is not finite", whole ? "load b" : "reduced load f", dof, first, node);
  PetscCall(FirstNonFinite(ss->u, &first));
  PetscCall(NodeOfRow(pb, first, node, sizeof(node)));
  PetscCheck(first < 0, comm, PETSC_ERR_FP, "ssstar: the initial guess is NaN or Inf at %s %" PetscInt_FMT "%s", dof, first, node);
  PetscFunctionReturn(0);
}

/* The problem of this solve: A, f, gamma, the Newton step for A, the displacement scale, the first iterate */
static PetscErrorCode SetUpSolve(SNES snes)
{
  SNES_SSStar        *ss = (SNES_SSStar *)snes->data;
  SSStarContact      *ct = &ss->contact;
  SSStarProblem      *pb = &ss->problem;
  SSStarContactLayout layout;

  PetscFunctionBegin;
  PetscCall(SSStarNonlinearMeasureAtStart(snes)); /* a contact update declares the contact at the initial guess */
  PetscCall(SSStarProblemSetUp(snes, ct, pb));
  PetscCall(SSStarContactSetUpOffsets(PetscObjectComm((PetscObject)snes), ct, &ss->offsetScale));
  PetscCall(CreateWorkVectors(snes));
  PetscCall(SNESSSStarComputeScaling(snes));
  PetscCall(SSStarProblemGetLayout(ct, pb, &layout));
  PetscCall(SSStarNewtonSetStiffness(ss->newton, pb->newtonType, pb->A, ss->scaling, &layout));
  PetscCall(SSStarProblemGetInitialGuess(ct, pb, snes->vec_sol, ss->u));
  PetscCall(SSStarNonlinearBegin(snes));
  PetscCall(CheckProblem(snes));
  PetscCall(SNESSSStarStart(snes)); /* the load's scale; on the whole body the free dofs in equilibrium (start.c) */
  PetscCall(SNESSSStarRecordStart(snes, ss->u, ss->c));
  ss->lawForce  = 0; /* not measured yet */
  ss->lawBest   = PETSC_MAX_REAL;
  ss->lawStalls = 0;
  ss->polishing = PETSC_FALSE;
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSolve_SSStar(SNES snes)
{
  SNES_SSStar   *ss = (SNES_SSStar *)snes->data;
  SSStarContact *ct = &ss->contact;
  SSStarProblem *pb = &ss->problem;
  PetscReal      znorm, unorm, xnorm, dunorm = 0, duprev = 0, z0 = 0; /* the last two Newton steps' lengths */
  PetscBool      solved;

  PetscFunctionBegin;
  snes->reason = SNES_CONVERGED_ITERATING;
  ss->reason   = SSSTAR_REASON_ITERATING;
  PetscCall(PetscTime(&ss->tStart));
  PetscCall(PetscObjectSAWsTakeAccess((PetscObject)snes));
  snes->iter = 0;
  snes->norm = 0;
  PetscCall(PetscObjectSAWsGrantAccess((PetscObject)snes));

  PetscCall(SetUpSolve(snes));
  PetscCall(SSStarGlobalizationBegin(snes));
  {
    PetscBool taken;

    PetscCall(SNESSSStarApproximationStep(snes, ss->u, ss->c, &znorm));
    PetscCall(SNESSSStarLawResidual(snes, ss->u, ss->c));
    PetscCall(SNESSSStarElasticTrial(snes, &taken));
  }
  PetscCall(SNESSSStarCheckEquilibrium(snes)); /* floating bodies: a load no contact force can balance ends here (balance.c) */

  for (PetscInt k = 0; snes->reason == SNES_CONVERGED_ITERATING; k++) {
    SSStarReason stop = SSSTAR_REASON_ITERATING;

    PetscCall(SSStarNonlinearMeasureContact(snes)); /* a contact update: the contact at this iterate (nonlinear.c) */
    PetscCall(SNESSSStarApproximationStep(snes, ss->u, ss->c, &znorm));
    PetscCall(SNESSSStarLawResidual(snes, ss->u, ss->c));
    PetscCall(SNESSSStarContactNorm(snes, ss->u, &unorm));
    PetscCall(SNESSSStarClassify(snes));
    if (ss->method == SSSTAR_METHOD_NEWTON) PetscCall(SSStarGlobalizationDetect(snes, k, znorm));
    PetscCall(PetscObjectSAWsTakeAccess((PetscObject)snes));
    snes->iter = k;
    snes->norm = znorm;
    if (k == 0) snes->ttol = znorm * snes->rtol; /* for SNESConvergedDefault(), if the user chose it */
    PetscCall(PetscObjectSAWsGrantAccess((PetscObject)snes));
    if (k == 0) PetscCall(SNESSSStarStartNorm(snes, znorm, &z0)); /* ||z_0|| of the forcing (start.c) */
    PetscCall(SNESLogConvergenceHistory(snes, znorm, snes->linear_its));
    PetscCall(SNESMonitor(snes, k, znorm));
    xnorm         = PetscMax(PetscMax(unorm, ss->scale), ss->offsetScale);
    ss->tolerance = PetscMax(snes->abstol, snes->rtol * xnorm);
    PetscUseTypeMethod(snes, converged, k, xnorm, dunorm, znorm, &snes->reason, snes->cnvP);
    PetscCall(PetscInfo(snes, "Iteration %" PetscInt_FMT ": ||z|| %g, threshold %g, law residual %g (tolerance %g)\n", k, (double)znorm, (double)ss->tolerance, (double)ss->lawResidual, (double)SNESSSStarLawTolerance(snes)));
    if (snes->reason) {
      ss->reason = SubReason(snes);
      if (snes->reason > 0) {
        ss->pathDisplacement = PetscMax(ss->pathDisplacement, ss->lawDisplacement);
        ss->pathForce        = PetscMax(ss->pathForce, ss->lawForce);
      }
      break;
    }
    if (k >= snes->max_its) {
      ss->reason   = SSSTAR_REASON_MAX_IT;
      snes->reason = SNES_DIVERGED_MAX_IT;
      break;
    }
    /* ||z|| is small enough, the law on the iterate as written is not (section 12): Newton steps solved to the floor
       (taken whole once the states have settled, globalized before: section 19b) until it is, or it stops halving
       while the states stay and the steps stop growing (its round-off floor). Steps that grow while rho decreases are no floor: the creep of the iteration at a kink of the law, where
       a slow mode's slip is set by the curvature of the sliding directions and Newton lengthens it by 3/2 per step
       (docs/derivation.md section 19) */
    ss->polishing = (PetscBool)(snes->ops->converged == SNESConvergedSSStar && znorm <= ss->tolerance);
    if (ss->polishing) {
      const PetscBool creeping = (PetscBool)(dunorm > duprev && ss->lawResidual < ss->lawBest);

      if (ss->lawResidual > 0.5 * ss->lawBest && ss->glob.changed == 0 && !creeping) ss->lawStalls++;
      ss->lawBest = PetscMin(ss->lawBest, ss->lawResidual);
      PetscCall(PetscInfo(snes, "Polishing at iteration %" PetscInt_FMT ": law residual %g, steps %g after %g%s, %" PetscInt_FMT " stalls\n", k, (double)ss->lawResidual, (double)dunorm, (double)duprev, creeping ? " (creeping)" : "", ss->lawStalls));
      if (ss->lawStalls > SSSTAR_LAW_MAX_STALLS) {
        ss->reason   = SSSTAR_REASON_LAW_STALLED;
        snes->reason = SNES_DIVERGED_LOCAL_MIN;
        break;
      }
    }
    PetscCall(SSStarNonlinearJacobian(snes, k)); /* a nonlinear residual: its Jacobian at this iterate (-snes_lag_jacobian) */
    if (ss->method == SSSTAR_METHOD_FIXEDPOINT) { /* u <- u + R^T z (section 1) */
      PetscCall(SNESSSStarSetLinearTolerances(snes, znorm, PetscMin(ss->etaMax, znorm / z0)));
      PetscCall(SNESSSStarFixedPointStep(snes, ss->u, ss->c, &solved));
      dunorm = znorm;
      if (solved) continue;
      stop = SSSTAR_REASON_SINGULAR_NEWTON;
    }
    /* a cycle is broken by a new gamma (the iterate stays); the plain iteration, or one out of rescalings, stops */
    else if (ss->glob.detected == SSSTAR_DETECTED_CYCLE) {
      PetscBool broken = PETSC_FALSE;

      if (ss->glob.on) PetscCall(SSStarGlobalizationBreakCycle(snes, &broken));
      if (broken) continue;
      stop = SSSTAR_REASON_CYCLE;
    } else if (ss->glob.detected == SSSTAR_DETECTED_STAGNATION) stop = SSSTAR_REASON_STAGNATION;
    if (!stop) {
      /* inexact Newton: eta = ||z||/||z_0|| (superlinear near the solution), at most etaMax, while no remedy acted.
         Once one did, every step is solved to the floor (eta = 0), as the dense route solves it: the globalization
         acts where the linear model of ||z|| fails, and there the error of the step, not its residual, decides the
         next states. Where the body nearly floats (soft springs, no node sticking) that error is the residual times
         the inverse of the Newton matrix's smallest eigenvalue: 2600 ||z|| at the contact nodes for gamma ||r|| =
         0.1 ||z|| on scenes/tilted_roller.opts with the shear reversed. Once the states repeat after a full step,
         the step is likely the last one: exact too. (||z||/||z_0||)^2 saves no Newton iteration at level 16 and
         costs 30 % more Krylov iterations (186 against 144). The first step: eta_max of ||z_0|| as the forcing
         measures it (SNESSSStarStartNorm(): a coarser mesh's start without its free dofs' residual) */
      PetscInt remedies = 0;

      for (PetscInt r = 0; r < SSSTAR_NUM_REMEDIES; r++) remedies += ss->glob.counts[r];
      const PetscReal eta = remedies || ss->polishing || (ss->glob.changed == 0 && ss->glob.shownAlpha == 1) ? 0.0 : (k ? PetscMin(ss->etaMax, znorm / z0) : ss->etaMax * z0 / znorm);

      /* the likely last step (not one after a remedy, nor polishing): solved to -snes_ssstar_ksp_floor of the stopping
         rule, the other steps with eta = 0 to a tenth (docs/derivation.md section 19a) */
      ss->lastStep = (PetscBool)(!remedies && !ss->polishing && eta == 0.0);
      if (ss->glob.on) PetscCall(SSStarGlobalizationReversedSlips(snes)); /* polishing: a reversed slip's step at its kink (docs/derivation.md section 19c) */
      /* a singular Newton matrix: the regularized step, else fixed-point iterations, else stop */
      PetscCall(SNESSSStarNewtonStep(snes, znorm, eta, PETSC_FALSE, &solved));
      if (!solved && ss->glob.on && ct->coupled > 0) {
        PetscCall(SSStarGlobalizationRecord(&ss->glob, SSSTAR_REMEDY_REGULARIZED));
        PetscCall(SNESSSStarNewtonStep(snes, znorm, eta, PETSC_TRUE, &solved));
      }
      ss->lastStep = PETSC_FALSE;
      if (!solved) {
        PetscBool improved = PETSC_FALSE;

        if (ss->glob.on) PetscCall(SSStarGlobalizationFixedPoint(snes, znorm, &improved));
        if (improved) continue;
        stop = SSSTAR_REASON_SINGULAR_NEWTON;
      } else {
        PetscCall(SNESSSStarExtendFreeStep(snes)); /* floating bodies: free motions to the first contact (balance.c) */
        duprev = dunorm;
        PetscCall(SNESSSStarContactNorm(snes, ss->dv, &dunorm));
        PetscCall(SSStarGlobalizationStep(snes, k, znorm, ss->polishing, &stop));
      }
    }
    if (stop) {
      ss->reason = stop;
      switch (stop) {
      case SSSTAR_REASON_SINGULAR_NEWTON:
        snes->reason = SNES_DIVERGED_LINEAR_SOLVE;
        break;
      case SSSTAR_REASON_NAN:
        snes->reason = SNES_DIVERGED_FNORM_NAN;
        break;
      case SSSTAR_REASON_STAGNATION:
        snes->reason = SNES_DIVERGED_LOCAL_MIN;
        break;
      default: /* a cycle: the steps do not decrease ||z|| and come back */
        snes->reason = SNES_DIVERGED_LINE_SEARCH;
      }
      break;
    }
  }
  /* the last iterate and its c = A u - f, the contact force: the SNES vector gets the whole u, F(u) its residual */
  PetscCall(SNESSSStarResidual(snes, ss->u, ss->c));
  PetscCall(SSStarProblemSetSolution(ct, pb, ss->u, ss->c, snes->vec_sol));
  PetscCall(SNESComputeFunction(snes, snes->vec_sol, snes->vec_func));
  PetscCall(SSStarNonlinearCheckAffine(snes)); /* an affine residual: F there against the model (nonlinear.c) */
  PetscFunctionReturn(0);
}

/*@C
   SNESConvergedSSStar - the default convergence test of ssstar: converged when ||z|| <= atol (CONVERGED_FNORM_ABS)
   or ||z|| <= rtol max(||u||, ||gamma f||, ||o_t||) (CONVERGED_FNORM_RELATIVE), with z the approximation step, gamma f
   the reduced load in displacement units (docs/derivation.md section 6), o_t the tangential contact offsets of a load
   path's step (SNESSSStarSetContactOffsets(); 0 without) and atol, rtol from SNESSetTolerances(); and in both cases
   when the law residual of the iterate as written is within its tolerance (SNESSSStarSetLawTolerance(),
   docs/derivation.md section 12)

   Collective

   Input Parameters:
+  snes  - the SNES
.  it    - iteration
.  xnorm - max(||u||, ||gamma f||, ||o_t||): the displacement scale of the problem
.  snorm - ||du|| of the last Newton step
.  fnorm - ||z||
-  ctx   - unused

   Output Parameter:
.  reason - SNES_CONVERGED_FNORM_ABS, SNES_CONVERGED_FNORM_RELATIVE, SNES_DIVERGED_FNORM_NAN or
            SNES_CONVERGED_ITERATING

   Options Database Keys:
+  -snes_rtol <1e-10> - rtol
-  -snes_atol <1e-50> - atol

   Notes:
   Both norms are in the units of u, so the rule does not depend on the units of the problem (nor on the size of
   the loads). SNESSetConvergenceTest() replaces it, as for every SNES.

   Level: intermediate

.seealso: `SNESSSStarGetTolerance()`, `SNESSetTolerances()`, `SNESSetConvergenceTest()`
@*/
PetscErrorCode SNESConvergedSSStar(SNES snes, PetscInt it, PetscReal xnorm, PetscReal snorm, PetscReal fnorm, SNESConvergedReason *reason, void *ctx)
{
  SNES_SSStar *ss = (SNES_SSStar *)snes->data;
  PetscBool    law;

  PetscFunctionBegin;
  *reason = SNES_CONVERGED_ITERATING;
  law = (PetscBool)(ss->lawResidual <= SNESSSStarLawTolerance(snes));
  if (PetscIsInfOrNanReal(fnorm)) *reason = SNES_DIVERGED_FNORM_NAN;
  else if (!law) *reason = SNES_CONVERGED_ITERATING;
  else if (fnorm <= snes->abstol) *reason = SNES_CONVERGED_FNORM_ABS;
  else if (fnorm <= snes->rtol * xnorm) *reason = SNES_CONVERGED_FNORM_RELATIVE;
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarSetMethod - chooses the iteration: the semismooth* Newton method (SSSTAR_METHOD_NEWTON, the default) or
   the first-order baseline SSSTAR_METHOD_FIXEDPOINT, u <- u + R^T z with the approximation step z alone
   (docs/derivation.md section 1), for comparisons (bench/accuracy.py)

   Logically Collective

   Input Parameters:
+  snes   - the SNES
-  method - SSSTAR_METHOD_NEWTON or SSSTAR_METHOD_FIXEDPOINT

   Options Database Key:
.  -snes_ssstar_method <newton> - newton or fixedpoint

   Notes:
   The fixed-point iteration is a projected (with friction, proximal) gradient method: its gamma is 1/||P||_inf
   unless -snes_ssstar_scaling sets it, small enough for it to converge on frictionless and Tresca problems, at a
   linear rate 1 - lambda_min(P)/||P||_inf; with Coulomb friction it is not guaranteed to converge. It has no Newton
   step, hence no globalization; the stopping rule is the same.

   Level: advanced

.seealso: `SNESSSStarGetMethod()`, `SNESSSStarSetScaling()`
@*/
PetscErrorCode SNESSSStarSetMethod(SNES snes, SSStarMethod method)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscTryMethod(snes, "SNESSSStarSetMethod_C", (SNES, SSStarMethod), (snes, method));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarSetMethod_SSStar(SNES snes, SSStarMethod method)
{
  PetscFunctionBegin;
  PetscCheck(method == SSSTAR_METHOD_NEWTON || method == SSSTAR_METHOD_FIXEDPOINT, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_OUTOFRANGE, "ssstar: unknown method %d", (int)method);
  ((SNES_SSStar *)snes->data)->method = method;
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarGetMethod - the iteration chosen by SNESSSStarSetMethod()

   Not Collective

   Input Parameter:
.  snes - the SNES

   Output Parameter:
.  method - SSSTAR_METHOD_NEWTON or SSSTAR_METHOD_FIXEDPOINT

   Level: advanced

.seealso: `SNESSSStarSetMethod()`
@*/
PetscErrorCode SNESSSStarGetMethod(SNES snes, SSStarMethod *method)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscUseMethod(snes, "SNESSSStarGetMethod_C", (SNES, SSStarMethod *), (snes, method));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarGetMethod_SSStar(SNES snes, SSStarMethod *method)
{
  PetscFunctionBegin;
  *method = ((SNES_SSStar *)snes->data)->method;
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarGetReason - why the last solve stopped, finer than SNESGetConvergedReason()

   Not Collective

   Input Parameter:
.  snes - the SNES

   Output Parameter:
.  reason - the sub-reason (SSStarReason; SSStarReasons[] names it)

   Notes:
   -snes_converged_reason prints it on the line "ssstar: ..."; docs/guide/converged.md ("When it does not converge") maps each onto the
   SNESConvergedReason.

   Level: beginner

.seealso: `SNESGetConvergedReason()`, `SNESSSStarGetTolerance()`, `SNESSSStarGetRemedyCounts()`
@*/
PetscErrorCode SNESSSStarGetReason(SNES snes, SSStarReason *reason)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscUseMethod(snes, "SNESSSStarGetReason_C", (SNES, SSStarReason *), (snes, reason));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarGetReason_SSStar(SNES snes, SSStarReason *reason)
{
  PetscFunctionBegin;
  *reason = ((SNES_SSStar *)snes->data)->reason;
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarGetTolerance - the threshold the last solve's stopping rule compared ||z|| with

   Not Collective

   Input Parameter:
.  snes - the SNES

   Output Parameter:
.  tol - max(atol, rtol max(||u||, ||gamma f||)) at the last iterate (SNESConvergedSSStar())

   Level: intermediate

.seealso: `SNESConvergedSSStar()`, `SNESGetFunctionNorm()`, `SNESSSStarGetReason()`
@*/
PetscErrorCode SNESSSStarGetTolerance(SNES snes, PetscReal *tol)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscValidRealPointer(tol, 2);
  PetscUseMethod(snes, "SNESSSStarGetTolerance_C", (SNES, PetscReal *), (snes, tol));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarGetTolerance_SSStar(SNES snes, PetscReal *tol)
{
  PetscFunctionBegin;
  *tol = ((SNES_SSStar *)snes->data)->tolerance;
  PetscFunctionReturn(0);
}

/* The implementations of the public functions above, composed on the SNES */
static const SSStarComposed Composed[] = {
    {"SNESSSStarSetMethod_C", (PetscVoidFunction)SNESSSStarSetMethod_SSStar},
    {"SNESSSStarGetMethod_C", (PetscVoidFunction)SNESSSStarGetMethod_SSStar},
    {"SNESSSStarGetReason_C", (PetscVoidFunction)SNESSSStarGetReason_SSStar},
    {"SNESSSStarGetTolerance_C", (PetscVoidFunction)SNESSSStarGetTolerance_SSStar},
};

/* on: composes the type's implementations of the public functions on the SNES, each room's next to its public
   functions (SNESCreate_SSStar()); off: removes them (SNESDestroy_SSStar()) */
static PetscErrorCode SNESSSStarComposeFunctions(SNES snes, PetscBool on)
{
  PetscFunctionBegin;
  PetscCall(SNESSSStarComposeTable(snes, Composed, PETSC_STATIC_ARRAY_LENGTH(Composed), on));
  PetscCall(SNESSSStarComposeContact(snes, on));
  PetscCall(SNESSSStarComposeFriction(snes, on));
  PetscCall(SNESSSStarComposeProblem(snes, on));
  PetscCall(SNESSSStarComposeNewton(snes, on));
  PetscCall(SNESSSStarComposeNodeSteps(snes, on));
  PetscCall(SNESSSStarComposeStart(snes, on));
  PetscCall(SNESSSStarComposeGlobalization(snes, on));
  PetscCall(SNESSSStarComposeFloating(snes, on));
  PetscCall(SNESSSStarComposeNonlinear(snes, on));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESReset_SSStar(SNES snes)
{
  SNES_SSStar *ss = (SNES_SSStar *)snes->data;

  PetscFunctionBegin;
  PetscCall(SSStarContactReset(&ss->contact));
  PetscCall(SSStarProblemReset(&ss->problem));
  PetscCall(SSStarNewtonReset(ss->newton));
  PetscCall(PetscFree2(ss->states, ss->userStates));
  PetscCall(PetscFree2(ss->S, ss->T));
  PetscCall(PetscFree(ss->start));
  ss->pathDisplacement = ss->pathForce = 0;
  PetscCall(VecDestroy(&ss->u));
  for (Vec *w = &ss->c; w <= &ss->ca; w++) PetscCall(VecDestroy(w));
  PetscCall(VecDestroy(&ss->d));
  PetscCall(VecDestroy(&ss->b));
  PetscCall(SSStarGlobalizationDestroy(&ss->glob));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESDestroy_SSStar(SNES snes)
{
  SNES_SSStar *ss = (SNES_SSStar *)snes->data;

  PetscFunctionBegin;
  PetscCall(SNESReset_SSStar(snes));
  PetscCall(SSStarContactDestroy(&ss->contact));
  PetscCall(SSStarNewtonDestroy(&ss->newton));
  PetscCall(SNESSSStarComposeFunctions(snes, PETSC_FALSE));
  PetscCall(PetscFree(snes->data));
  PetscFunctionReturn(0);
}

/*MC
   SNESSSSTAR - "ssstar": semismooth* Newton method for 3D contact with friction (Coulomb, Tresca or none)

   Whole body: the SNES function is F(u) = K u - b, the Jacobian K, and SNESSSStarSetContactNodes() names the contact
   nodes' dofs, the obstacle's normals and the gaps; SNESSolve() reduces K to the contact dofs (Schur complement P)
   and solves there, or solves on the whole body with K (reduction none: Krylov + multigrid, P never formed), and
   returns the whole u; SNESGetFunction() then holds K u - b, the contact forces.
   Reduced: the SNES function is c(u) = P u - f and the Jacobian P, one (u_t1, u_t2, u_n) block per contact node.

   Each iteration: an approximation step (a closed-form projection per node, in the node's frame), a classification
   of every node into the states of Table 1, and a Newton step through the reduced system (S P + T) du = (S + T) z.

   Options Database Keys:
+  -snes_ssstar_friction_law <coulomb> - none, tresca or coulomb
.  -snes_ssstar_friction <0.3> - Coulomb friction coefficient
.  -snes_ssstar_affine <auto> - true: F(u) = K u - b, the Jacobian once per solve; false: F evaluated at the iterates, the Jacobian as -snes_lag_jacobian says, on the whole body; auto: true for SNESSSStarSetLinearProblem()'s F, false for a program's own
.  -snes_ssstar_reduction <auto> - whole-body use: K reduced to the contact dofs (direct, mumps, explicit), none (the Newton step on the whole body, P never formed) or auto (direct on small problems, none on large ones)
.  -snes_ssstar_memory_limit <0> - GB per rank the reduction may plan for (0: MemAvailable of the node per rank)
.  -snes_ssstar_scaling <0> - scaling gamma of the approximation step (0: 1/mean(diag K_CC), the contact block of K)
.  -snes_ssstar_method <newton> - newton (semismooth*) or fixedpoint (the first-order baseline u <- u + z)
.  -snes_ssstar_state_tol <1e-13> - relative tolerance of the state classification
.  -snes_ssstar_monitor_states - print the number of nodes per state at every iteration, and the remedies
.  -snes_ssstar_monitor_progress - a line at the end of the set-up and one per iterate: ||z||, nodes that changed state, the step's seconds and Krylov iterations, memory
.  -snes_ssstar_globalization <true> - damped steps on ||z|| and remedies; false: the plain iteration
.  -snes_ssstar_damping_min <0.015625> - smallest damping factor of the line search
.  -snes_ssstar_stagnation_its <20> - stop after this many iterations without a smaller ||z||
.  -snes_ssstar_lu_threads <1> - on several ranks, rank 0's BLAS threads for the LU of the Newton matrix (0: the cores it may run on)
.  -snes_ssstar_lu_reuse <0> - dense P: solve a Newton step by GMRES on the last LU while at most this fraction of the nodes changed their known rows since it (0: only when none changed; negative: a fresh LU at every step); -snes_ssstar_newton_ksp_* set that GMRES
.  -snes_ssstar_pc_reuse <0.3> - whole body: keep the multigrid of an earlier Newton step while at most this fraction of the nodes changed their known rows (negative: a new one every step)
.  -snes_ssstar_plain_aggregation_dofs <200000> - whole body: the multigrid aggregates plainly (W-cycles on the two finest levels, the products all at once: the memory lever) on K of at least this many dofs (0: always; negative: only where smoothed aggregation would not fit the memory)
.  -snes_ssstar_mg_overcorrection <1.8> - whole body, plain aggregation: the W-cycled levels' coarse corrections times this (1: the Galerkin ones; at most 2)
.  -snes_ssstar_mg_w_levels <2> - whole body, plain aggregation: the finest levels that W-cycle, V below (unless -pc_mg_cycle_type)
.  -snes_ssstar_ksp_rtol_max <0.1> - whole body: the loosest relative tolerance of a Newton step's linear solve; it tightens as min(this, ||z||/||z_0||); once a remedy acted, and for a step whose full step fails, the floor (a tenth of the stopping threshold)
.  -snes_ssstar_ksp_floor <0.1> - whole body: the step that is likely the last (the states of the full step before it repeated) is solved to this fraction of the stopping threshold and of the law's tolerance (docs/derivation.md section 19a)
.  -ksp_type, -pc_type, -ksp_rtol, ... - whole body: the linear solver of the Newton steps (default CG or GMRES with PCGAMG: smoothed aggregation below -snes_ssstar_plain_aggregation_dofs where its set-up fits the memory, else plain with W-cycles on the two finest levels and the products all at once, as -pc_gamg_agg_nsmooths 0 gives; -pc_mg_cycle_type, -matptap_via choose others; a multigrid or Newton matrix CG finds indefinite: that step and the later ones by GMRES; -ksp_rtol fixes the tolerance)
.  -snes_rtol <1e-10> - stop when ||z|| <= rtol max(||u||, ||gamma f||) (SNESConvergedSSStar()) and the law residual of the iterate as written is within its tolerance
.  -snes_ssstar_law_rtol <0> - that tolerance (0: max(rtol, 1e-8); docs/derivation.md section 12)
-  -snes_atol <1e-50> - or when ||z|| <= atol

M*/
PETSC_EXTERN PetscErrorCode SNESCreate_SSStar(SNES snes)
{
  SNES_SSStar *ss;
  PC           pc;
  PetscBool    registered = PETSC_FALSE;

  PetscFunctionBegin;
  snes->ops->setup          = SNESSetUp_SSStar;
  snes->ops->solve          = SNESSolve_SSStar;
  snes->ops->destroy        = SNESDestroy_SSStar;
  snes->ops->setfromoptions = SNESSetFromOptions_SSStar;
  snes->ops->view           = SNESView_SSStar;
  snes->ops->reset          = SNESReset_SSStar;
  snes->ops->converged      = SNESConvergedSSStar;
  snes->usesksp             = PETSC_TRUE;
  snes->usesnpc             = PETSC_FALSE;
  snes->alwayscomputesfinalresidual = PETSC_TRUE;
  snes->rtol                = 1e-10;

  PetscCall(PetscNew(&ss));
  PetscCall(SSStarContactInitialize(&ss->contact));
  PetscCall(PetscStrncpy(ss->problem.reductionType, SSSTARREDUCTIONAUTO, sizeof(ss->problem.reductionType)));
  ss->problem.built         = -1;
  ss->etaMax                = 0.1;
  ss->kspFloor              = SSSTAR_FLOOR_FRACTION;
  ss->state_tol             = 1e-13;
  ss->glob.on               = PETSC_TRUE;
  ss->glob.dampingMin       = 1.0 / 64;
  ss->glob.stagnationIts    = 20;
  snes->data                = (void *)ss;
  PetscCall(SSStarNewtonCreate(snes, &ss->newton));

  /* the SNES's KSP solves the Newton steps on the whole body (the sparse path sets LU for itself) */
  PetscCall(SNESGetKSP(snes, &snes->ksp));
  PetscCall(KSPSetType(snes->ksp, KSPGMRES));
  PetscCall(KSPGetPC(snes->ksp, &pc));
  PetscCall(PCSetType(pc, PCGAMG));
  for (PetscInt i = 0; i < snes->numberreasonviews; i++)
    if (snes->reasonview[i] == SNESSSStarConvergedReasonView) registered = PETSC_TRUE;
  if (!registered) PetscCall(SNESConvergedReasonViewSet(snes, SNESSSStarConvergedReasonView, NULL, NULL));

  PetscCall(SNESSSStarComposeFunctions(snes, PETSC_TRUE));
  PetscFunctionReturn(0);
}
