/*
   The SNES type "ssstar": semismooth* Newton method for 0 in c(u) + Q(u) (DERIVATION.md section 7).
*/
#include "ssstarimpl.h"

const char *const SSStarMethods[] = {"newton", "fixedpoint", "SSStarMethod", "SSSTAR_METHOD_", NULL};
const char *const SSStarReasons[] = {"ITERATING", "CONVERGED_ABSOLUTE", "CONVERGED_RELATIVE", "MAX_IT", "NAN_OR_INF", "SINGULAR_NEWTON_MATRIX", "STAGNATION", "CYCLE", "USER_TEST", "SSStarReason", "SSSTAR_REASON_", NULL};

/* A Newton matrix whose estimated 1/cond is below this is treated as singular: its LU solution has no reliable digit */
#define SSSTAR_RCOND_MIN 1e-12

/* gamma = 1/mean(diag P) unless the user set it (section 6) */
static PetscErrorCode SNESSSStarComputeScaling(SNES snes, Mat P)
{
  SNES_SSStar *ss = (SNES_SSStar *)snes->data;
  Vec          diag;
  PetscScalar  sum;
  PetscInt     N;

  PetscFunctionBegin;
  if (ss->scaling_user > 0) {
    ss->scaling = ss->scaling_user;
    PetscFunctionReturn(0);
  }
  if (ss->method == SSSTAR_METHOD_FIXEDPOINT) { /* 1/||P||_inf <= 1/lambda_max(P): a step short enough to converge */
    PetscReal pnorm;

    PetscCall(MatNorm(P, NORM_INFINITY, &pnorm));
    PetscCheck(pnorm > 0, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_WRONG, "ssstar: ||P||_inf = %g, not positive; set -snes_ssstar_scaling", (double)pnorm);
    ss->scaling = 1 / pnorm;
    PetscFunctionReturn(0);
  }
  PetscCall(MatCreateVecs(P, &diag, NULL));
  PetscCall(MatGetDiagonal(P, diag));
  PetscCall(VecSum(diag, &sum));
  PetscCall(VecGetSize(diag, &N));
  PetscCall(VecDestroy(&diag));
  PetscCheck(PetscRealPart(sum) > 0, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_WRONG, "ssstar: mean diagonal of P is %g, not positive; set -snes_ssstar_scaling", N ? (double)PetscRealPart(sum) / N : 0.0);
  ss->scaling = N / PetscRealPart(sum);
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSetUp_SSStar(SNES snes)
{
  SNES_SSStar *ss = (SNES_SSStar *)snes->data;
  PetscInt     n;

  PetscFunctionBegin;
  PetscCheck(snes->jacobian, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_WRONGSTATE, "ssstar needs the matrix K (or P): call SNESSetJacobian()");
  PetscCall(SSStarContactSetUp(snes, &ss->contact));
  n = ss->contact.nnodes;
  PetscCall(PetscFree2(ss->states, ss->userStates));
  PetscCall(PetscFree2(ss->S, ss->T));
  PetscCall(PetscCalloc2(n, &ss->states, n, &ss->userStates));
  PetscCall(PetscMalloc2(9 * n, &ss->S, 9 * n, &ss->T));
  PetscCall(VecDestroy(&ss->u));
  PetscCall(VecCreateMPI(PetscObjectComm((PetscObject)snes), 3 * n, PETSC_DETERMINE, &ss->u));
  for (Vec *w = &ss->c; w <= &ss->ca; w++) {
    PetscCall(VecDestroy(w));
    PetscCall(VecDuplicate(ss->u, w));
  }
  PetscFunctionReturn(0);
}

/* The scaled friction of node i: a Tresca bound is a force and the kernels see gamma c (section 6) */
static SSStarFriction ScaledFriction(SNES_SSStar *ss, PetscInt i)
{
  SSStarFriction fr = ss->contact.nodeFriction[i];

  fr.bound *= ss->scaling;
  return fr;
}

/* y = R x (R NULL: identity) */
static void Rotate(const PetscReal *R, const PetscScalar x[3], PetscReal y[3])
{
  for (PetscInt k = 0; k < 3; k++) y[k] = R ? R[3 * k] * x[0] + R[3 * k + 1] * x[1] + R[3 * k + 2] * x[2] : PetscRealPart(x[k]);
}

/* v_i = R_i u_i + g_i e3: the iterate in node i's frame, with the gap */
static void NodeIterate(const SSStarContact *ct, PetscInt i, const PetscScalar *ua, PetscReal v[3])
{
  Rotate(ct->frames ? &ct->frames[9 * i] : NULL, &ua[3 * i], v);
  if (ct->gap) v[2] += ct->gap[i];
}

/* c = P u - f */
PetscErrorCode SNESSSStarResidual(SNES snes, Vec u, Vec c)
{
  SSStarContact *ct = &((SNES_SSStar *)snes->data)->contact;

  PetscFunctionBegin;
  PetscCall(MatMult(ct->P, u, c));
  PetscCall(VecAXPY(c, -1.0, ct->f));
  PetscFunctionReturn(0);
}

/* x += R^T y (R NULL: identity) */
static void AddRotatedBack(const PetscReal *R, const PetscScalar y[3], PetscScalar x[3])
{
  for (PetscInt k = 0; k < 3; k++) x[k] += R ? R[k] * y[0] + R[3 + k] * y[1] + R[6 + k] * y[2] : y[k];
}

/* u += alpha R^T dv: a step given in the nodes' frames (the fixed-point step z) */
PetscErrorCode SNESSSStarAddStep(SNES snes, Vec u, PetscReal alpha, Vec dv)
{
  SSStarContact     *ct = &((SNES_SSStar *)snes->data)->contact;
  PetscScalar       *ua;
  const PetscScalar *dva;

  PetscFunctionBegin;
  PetscCall(VecGetArray(u, &ua));
  PetscCall(VecGetArrayRead(dv, &dva));
  for (PetscInt i = 0; i < ct->nnodes; i++) {
    const PetscScalar step[3] = {alpha * dva[3 * i], alpha * dva[3 * i + 1], alpha * dva[3 * i + 2]};

    AddRotatedBack(ct->frames ? &ct->frames[9 * i] : NULL, step, &ua[3 * i]);
  }
  PetscCall(VecRestoreArrayRead(dv, &dva));
  PetscCall(VecRestoreArray(u, &ua));
  PetscFunctionReturn(0);
}

/*
   Section 1 on every local node of the iterate u with c = P u - f, in the node's frame, with the scaled
   c = gamma (P u - f) (section 6): z, d, b into ss->z, ss->d, ss->b, and ||z||
*/
PetscErrorCode SNESSSStarApproximationStep(SNES snes, Vec u, Vec c, PetscReal *znorm)
{
  SNES_SSStar       *ss = (SNES_SSStar *)snes->data;
  SSStarContact     *ct = &ss->contact;
  const PetscScalar *ua, *ca;
  PetscScalar       *za, *da, *ba;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(SSSTAR_ApproxStep, snes, 0, 0, 0));
  PetscCall(VecGetArrayRead(u, &ua));
  PetscCall(VecGetArrayRead(c, &ca));
  PetscCall(VecGetArrayWrite(ss->z, &za));
  PetscCall(VecGetArrayWrite(ss->d, &da));
  PetscCall(VecGetArrayWrite(ss->b, &ba));
  for (PetscInt i = 0; i < ct->nnodes; i++) {
    const SSStarFriction fr = ScaledFriction(ss, i);
    PetscReal            v[3], c[3];

    NodeIterate(ct, i, ua, v);
    Rotate(ct->frames ? &ct->frames[9 * i] : NULL, &ca[3 * i], c);
    for (PetscInt k = 0; k < 3; k++) c[k] *= ss->scaling;
    SSStarApproximationStep(&fr, v, c, &za[3 * i], &da[3 * i], &ba[3 * i]);
  }
  PetscCall(VecRestoreArrayWrite(ss->b, &ba));
  PetscCall(VecRestoreArrayWrite(ss->d, &da));
  PetscCall(VecRestoreArrayWrite(ss->z, &za));
  PetscCall(VecRestoreArrayRead(c, &ca));
  PetscCall(VecRestoreArrayRead(u, &ua));
  PetscCall(VecNorm(ss->z, NORM_2, znorm));
  PetscCall(PetscLogEventEnd(SSSTAR_ApproxStep, snes, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* Section 2 with tol_d = tau max(|v|, |d|), tol_b = tau max(|gamma f|, |b|) (infinity norms over all nodes) */
static PetscErrorCode SNESSSStarClassify(SNES snes, PetscReal fnorm_inf)
{
  SNES_SSStar       *ss = (SNES_SSStar *)snes->data;
  SSStarContact     *ct = &ss->contact;
  const PetscScalar *ua, *da, *ba;
  PetscReal          norms[3] = {0, 0, 0}, tol_d, tol_b;

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(ss->u, &ua));
  PetscCall(VecGetArrayRead(ss->d, &da));
  PetscCall(VecGetArrayRead(ss->b, &ba));
  for (PetscInt i = 0; i < ct->nnodes; i++) {
    PetscReal v[3];

    NodeIterate(ct, i, ua, v);
    for (PetscInt k = 0; k < 3; k++) {
      norms[0] = PetscMax(norms[0], PetscAbsReal(v[k]));
      norms[1] = PetscMax(norms[1], PetscAbsScalar(da[3 * i + k]));
      norms[2] = PetscMax(norms[2], PetscAbsScalar(ba[3 * i + k]));
    }
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, norms, 3, MPIU_REAL, MPIU_MAX, PetscObjectComm((PetscObject)snes)));
  tol_d = ss->state_tol * PetscMax(norms[0], norms[1]);
  tol_b = ss->state_tol * PetscMax(ss->scaling * fnorm_inf, norms[2]);
  PetscCall(PetscArrayzero(ss->counts, SSSTAR_NUM_STATES));
  for (PetscInt i = 0; i < ct->nnodes; i++) {
    const SSStarFriction fr = ScaledFriction(ss, i);

    ss->states[i] = SSStarClassify(&fr, &da[3 * i], &ba[3 * i], tol_d, tol_b);
    ss->counts[ss->states[i]]++;
    ss->userStates[ct->order[i]] = ss->states[i];
  }
  PetscCall(VecRestoreArrayRead(ss->b, &ba));
  PetscCall(VecRestoreArrayRead(ss->d, &da));
  PetscCall(VecRestoreArrayRead(ss->u, &ua));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, ss->counts, SSSTAR_NUM_STATES, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)snes)));
  PetscFunctionReturn(0);
}

/*
   Section 5 in the nodes' frames: S, T per node, y = (S + T) z, then (gamma S R P + T R) du = y. solved is false
   when the matrix is singular or, by the estimate of its condition, nearly so.

   regularized: the coupling phi om of the sliding (M1) rows of S dropped, i.e. the normal force in the linearized
   sliding law frozen at the iterate. Every row is then a row of gamma P, or a unit row, or a row of gamma P plus
   the PSD W of section 3 on the node's tangential dofs: after the unit rows the matrix is gamma P_FF + W_FF with
   P_FF a principal submatrix of the SPD P, nonsingular.
*/
static PetscErrorCode SNESSSStarNewtonStep(SNES snes, PetscBool regularized, PetscBool *solved)
{
  SNES_SSStar       *ss = (SNES_SSStar *)snes->data;
  SSStarContact     *ct = &ss->contact;
  const PetscScalar *za, *da, *ba;
  PetscScalar       *ya;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(SSSTAR_NewtonStep, snes, 0, 0, 0));
  PetscCall(VecGetArrayRead(ss->z, &za));
  PetscCall(VecGetArrayRead(ss->d, &da));
  PetscCall(VecGetArrayRead(ss->b, &ba));
  PetscCall(VecGetArrayWrite(ss->y, &ya));
  for (PetscInt i = 0; i < ct->nnodes; i++) {
    const SSStarFriction fr = ScaledFriction(ss, i);
    PetscReal           *S = &ss->S[9 * i], *T = &ss->T[9 * i];

    SSStarReducedBlocks(ss->states[i], &fr, &da[3 * i], &ba[3 * i], S, T);
    if (regularized) S[2] = S[5] = 0.0;
    for (PetscInt r = 0; r < 3; r++) {
      ya[3 * i + r] = 0;
      for (PetscInt k = 0; k < 3; k++) ya[3 * i + r] += (S[3 * r + k] + T[3 * r + k]) * za[3 * i + k];
    }
  }
  PetscCall(VecRestoreArrayWrite(ss->y, &ya));
  PetscCall(VecRestoreArrayRead(ss->b, &ba));
  PetscCall(VecRestoreArrayRead(ss->d, &da));
  PetscCall(VecRestoreArrayRead(ss->z, &za));
  PetscCall(SSStarNewtonSolve(ss->newton, ct->frames, ss->S, ss->T, ss->y, ss->dv, solved));
  if (*solved) {
    PetscReal rcond;

    PetscCall(SSStarNewtonGetConditionEstimate(ss->newton, &rcond));
    if (rcond >= 0 && rcond < SSSTAR_RCOND_MIN) *solved = PETSC_FALSE;
  }
  PetscCall(PetscLogEventEnd(SSSTAR_NewtonStep, snes, 0, 0, 0));
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

/* Refuses what no iteration can solve: NaN or Inf in P, f or the initial guess, tolerances that are not numbers */
static PetscErrorCode CheckProblem(SNES snes)
{
  SNES_SSStar   *ss   = (SNES_SSStar *)snes->data;
  SSStarContact *ct   = &ss->contact;
  MPI_Comm       comm = PetscObjectComm((PetscObject)snes);
  Vec            rowsum;
  PetscInt       first;

  PetscFunctionBegin;
  PetscCheck(snes->rtol >= 0 && snes->rtol < 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "-snes_rtol %g: must be in [0, 1)", (double)snes->rtol);
  PetscCheck(snes->abstol >= 0 && !PetscIsInfOrNanReal(snes->abstol), comm, PETSC_ERR_ARG_OUTOFRANGE, "-snes_atol %g: must be a number >= 0", (double)snes->abstol);
  PetscCall(VecDuplicate(ct->f, &rowsum)); /* P 1: a row with a NaN or an Inf sums to NaN or Inf */
  PetscCall(VecSet(ss->ut, 1.0));
  PetscCall(MatMult(ct->P, ss->ut, rowsum));
  PetscCall(FirstNonFinite(rowsum, &first));
  PetscCall(VecDestroy(&rowsum));
  PetscCheck(first < 0, comm, PETSC_ERR_FP, "ssstar: the reduced stiffness P has NaN or Inf entries in row %" PetscInt_FMT " (node %" PetscInt_FMT " of the solver's order): the stiffness K is not finite", first, first / 3);
  PetscCall(FirstNonFinite(ct->f, &first));
  PetscCheck(first < 0, comm, PETSC_ERR_FP, "ssstar: the reduced load f is NaN or Inf at contact dof %" PetscInt_FMT " (node %" PetscInt_FMT " of the solver's order): the load b is not finite", first, first / 3);
  PetscCall(FirstNonFinite(ss->u, &first));
  PetscCheck(first < 0, comm, PETSC_ERR_FP, "ssstar: the initial guess is NaN or Inf at contact dof %" PetscInt_FMT " (node %" PetscInt_FMT " of the solver's order)", first, first / 3);
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSolve_SSStar(SNES snes)
{
  SNES_SSStar   *ss = (SNES_SSStar *)snes->data;
  SSStarContact *ct = &ss->contact;
  PetscReal      znorm, unorm, dunorm = 0, fnorm_inf;
  PetscBool      solved;

  PetscFunctionBegin;
  snes->reason = SNES_CONVERGED_ITERATING;
  ss->reason   = SSSTAR_REASON_ITERATING;
  PetscCall(PetscObjectSAWsTakeAccess((PetscObject)snes));
  snes->iter = 0;
  snes->norm = 0;
  PetscCall(PetscObjectSAWsGrantAccess((PetscObject)snes));

  PetscCall(SSStarContactSetUpProblem(snes, ct));
  PetscCall(SNESSSStarComputeScaling(snes, ct->P));
  if (ss->method == SSSTAR_METHOD_NEWTON) PetscCall(SSStarNewtonSetOperator(ss->newton, ct->P, ss->scaling));
  PetscCall(VecNorm(ct->f, NORM_2, &ss->scale));
  PetscCall(VecNorm(ct->f, NORM_INFINITY, &fnorm_inf));
  ss->scale *= ss->scaling;
  PetscCall(SSStarContactGetInitialGuess(ct, snes->vec_sol, ss->u));
  PetscCall(CheckProblem(snes));
  PetscCall(SSStarGlobalizationBegin(snes));
  PetscCall(SNESSSStarResidual(snes, ss->u, ss->c));

  for (PetscInt k = 0;; k++) {
    SSStarReason stop = SSSTAR_REASON_ITERATING;

    PetscCall(SNESSSStarApproximationStep(snes, ss->u, ss->c, &znorm));
    PetscCall(VecNorm(ss->u, NORM_2, &unorm));
    PetscCall(SNESSSStarClassify(snes, fnorm_inf));
    if (ss->method == SSSTAR_METHOD_NEWTON) PetscCall(SSStarGlobalizationDetect(snes, k, znorm));
    PetscCall(PetscObjectSAWsTakeAccess((PetscObject)snes));
    snes->iter = k;
    snes->norm = znorm;
    if (k == 0) snes->ttol = znorm * snes->rtol; /* for SNESConvergedDefault(), if the user chose it */
    PetscCall(PetscObjectSAWsGrantAccess((PetscObject)snes));
    PetscCall(SNESLogConvergenceHistory(snes, znorm, snes->linear_its));
    PetscCall(SNESMonitor(snes, k, znorm));
    PetscUseTypeMethod(snes, converged, k, PetscMax(unorm, ss->scale), dunorm, znorm, &snes->reason, snes->cnvP);
    if (snes->reason) {
      ss->reason = SubReason(snes);
      break;
    }
    if (k >= snes->max_its) {
      ss->reason   = SSSTAR_REASON_MAX_IT;
      snes->reason = SNES_DIVERGED_MAX_IT;
      break;
    }
    if (ss->method == SSSTAR_METHOD_FIXEDPOINT) { /* u <- u + R^T z (section 1) */
      PetscCall(SNESSSStarAddStep(snes, ss->u, 1.0, ss->z));
      PetscCall(SNESSSStarResidual(snes, ss->u, ss->c));
      dunorm = znorm;
      continue;
    }
    /* a cycle is broken by a new gamma (the iterate stays); the plain iteration, or one out of rescalings, stops */
    if (ss->glob.detected == SSSTAR_DETECTED_CYCLE) {
      PetscBool broken = PETSC_FALSE;

      if (ss->glob.on) PetscCall(SSStarGlobalizationBreakCycle(snes, &broken));
      if (broken) continue;
      stop = SSSTAR_REASON_CYCLE;
    } else if (ss->glob.detected == SSSTAR_DETECTED_STAGNATION) stop = SSSTAR_REASON_STAGNATION;
    if (!stop) {
      /* a singular Newton matrix: the regularized step, else fixed-point iterations, else stop */
      PetscCall(SNESSSStarNewtonStep(snes, PETSC_FALSE, &solved));
      if (!solved && ss->glob.on && ct->lawCounts[SSSTAR_FRICTION_COULOMB] > 0) {
        PetscCall(SSStarGlobalizationRecord(&ss->glob, SSSTAR_REMEDY_REGULARIZED));
        PetscCall(SNESSSStarNewtonStep(snes, PETSC_TRUE, &solved));
      }
      if (!solved) {
        PetscBool improved = PETSC_FALSE;

        if (ss->glob.on) PetscCall(SSStarGlobalizationFixedPoint(snes, znorm, &improved));
        if (improved) continue;
        stop = SSSTAR_REASON_SINGULAR_NEWTON;
      } else {
        PetscCall(VecNorm(ss->dv, NORM_2, &dunorm));
        PetscCall(SSStarGlobalizationStep(snes, k, znorm, &stop));
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
  /* the last iterate and its c = P u - f, the contact force: the SNES vector gets the whole u, F(u) its residual */
  PetscCall(SNESSSStarResidual(snes, ss->u, ss->c));
  PetscCall(SSStarContactSetSolution(ct, ss->u, ss->c, snes->vec_sol));
  PetscCall(SNESComputeFunction(snes, snes->vec_sol, snes->vec_func));
  PetscFunctionReturn(0);
}

/*@C
   SNESConvergedSSStar - the default convergence test of ssstar: converged when ||z|| <= atol (CONVERGED_FNORM_ABS)
   or ||z|| <= rtol max(||u||, ||gamma f||) (CONVERGED_FNORM_RELATIVE), with z the approximation step, gamma f the
   reduced load in displacement units (section 6) and atol, rtol from SNESSetTolerances() (-snes_atol, -snes_rtol)

   Input Parameters:
+  snes  - the SNES
.  it    - iteration
.  xnorm - max(||u||, ||gamma f||): the displacement scale of the problem
.  snorm - ||du|| of the last Newton step
-  fnorm - ||z||

   Notes:
   Both norms are in the units of u, so the rule does not depend on the units of the problem (nor on the size of
   the loads). SNESSetConvergenceTest() replaces it, as for every SNES.
@*/
PetscErrorCode SNESConvergedSSStar(SNES snes, PetscInt it, PetscReal xnorm, PetscReal snorm, PetscReal fnorm, SNESConvergedReason *reason, void *ctx)
{
  PetscFunctionBegin;
  *reason = SNES_CONVERGED_ITERATING;
  if (PetscIsInfOrNanReal(fnorm)) *reason = SNES_DIVERGED_FNORM_NAN;
  else if (fnorm <= snes->abstol) *reason = SNES_CONVERGED_FNORM_ABS;
  else if (fnorm <= snes->rtol * xnorm) *reason = SNES_CONVERGED_FNORM_RELATIVE;
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESReset_SSStar(SNES snes)
{
  SNES_SSStar *ss = (SNES_SSStar *)snes->data;

  PetscFunctionBegin;
  PetscCall(SSStarContactReset(&ss->contact));
  PetscCall(SSStarNewtonReset(ss->newton));
  PetscCall(PetscFree2(ss->states, ss->userStates));
  PetscCall(PetscFree2(ss->S, ss->T));
  PetscCall(VecDestroy(&ss->u));
  for (Vec *w = &ss->c; w <= &ss->ca; w++) PetscCall(VecDestroy(w));
  PetscCall(SSStarGlobalizationDestroy(&ss->glob));
  PetscFunctionReturn(0);
}

#define SSSTAR_COMPOSED(F) "SNESSSStar" #F "_C"
static const char *const ComposedNames[] = {SSSTAR_COMPOSED(SetContactNodes), SSSTAR_COMPOSED(SetFrictionLaw), SSSTAR_COMPOSED(GetFrictionLaw), SSSTAR_COMPOSED(SetFriction), SSSTAR_COMPOSED(GetFriction), SSSTAR_COMPOSED(SetFrictionCoefficients), SSSTAR_COMPOSED(SetSlipBounds), SSSTAR_COMPOSED(SetNodeFrictionLaws), SSSTAR_COMPOSED(SetReductionType), SSSTAR_COMPOSED(SetMemoryLimit), SSSTAR_COMPOSED(SetScaling), SSSTAR_COMPOSED(GetScaling), SSSTAR_COMPOSED(SetStateTolerance), SSSTAR_COMPOSED(GetStates), SSSTAR_COMPOSED(GetReason), SSSTAR_COMPOSED(GetReducedProblem), SSSTAR_COMPOSED(SetLUReuse), SSSTAR_COMPOSED(GetNewtonStepCounts), SSSTAR_COMPOSED(GetConditionEstimate), SSSTAR_COMPOSED(SetLUThreads), SSSTAR_COMPOSED(SetGlobalization), SSSTAR_COMPOSED(GetRemedyCounts), SSSTAR_COMPOSED(SetMethod), SSSTAR_COMPOSED(GetMethod)};

static PetscErrorCode SNESDestroy_SSStar(SNES snes)
{
  SNES_SSStar *ss = (SNES_SSStar *)snes->data;

  PetscFunctionBegin;
  PetscCall(SNESReset_SSStar(snes));
  PetscCall(SSStarContactDestroy(&ss->contact));
  PetscCall(SSStarNewtonDestroy(&ss->newton));
  for (size_t k = 0; k < PETSC_STATIC_ARRAY_LENGTH(ComposedNames); k++) PetscCall(PetscObjectComposeFunction((PetscObject)snes, ComposedNames[k], NULL));
  PetscCall(PetscFree(snes->data));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSetFromOptions_SSStar(SNES snes, PetscOptionItems *PetscOptionsObject)
{
  SNES_SSStar        *ss = (SNES_SSStar *)snes->data;
  SSStarContact      *ct = &ss->contact;
  PetscReal           value;
  SSStarFrictionLaw   law;
  SSStarReductionType rtype;
  SSStarMethod        method;
  PetscBool           set;
  PetscInt            threads;

  PetscFunctionBegin;
  PetscOptionsHeadBegin(PetscOptionsObject, "SNES ssstar options (semismooth* Newton for contact with friction)");
  PetscCall(PetscOptionsEnum("-snes_ssstar_friction_law", "Friction law of the contact nodes", "SNESSSStarSetFrictionLaw", SSStarFrictionLaws, (PetscEnum)ct->law, (PetscEnum *)&law, &set));
  if (set) PetscCall(SNESSSStarSetFrictionLaw(snes, law));
  PetscCall(PetscOptionsReal("-snes_ssstar_friction", "Coulomb friction coefficient phi >= 0", "SNESSSStarSetFriction", ct->friction, &value, &set));
  if (set) PetscCall(SNESSSStarSetFriction(snes, value));
  PetscCall(PetscOptionsEnum("-snes_ssstar_reduction", "Schur complement of K on the contact dofs (whole-body use)", "SNESSSStarSetReductionType", SSStarReductionTypes, (PetscEnum)ct->reductionType, (PetscEnum *)&rtype, &set));
  if (set) PetscCall(SNESSSStarSetReductionType(snes, rtype));
  PetscCall(PetscOptionsReal("-snes_ssstar_memory_limit", "Memory (GB per rank) the reduction of K may plan for (0: MemAvailable per rank)", "SNESSSStarSetMemoryLimit", ct->memoryLimit, &value, &set));
  if (set) PetscCall(SNESSSStarSetMemoryLimit(snes, value));
  PetscCall(PetscOptionsReal("-snes_ssstar_scaling", "Scaling gamma of the approximation step (0: 1/mean diag P)", "SNESSSStarSetScaling", ss->scaling_user, &value, &set));
  if (set) PetscCall(SNESSSStarSetScaling(snes, value));
  PetscCall(PetscOptionsEnum("-snes_ssstar_method", "The iteration: newton (semismooth*) or fixedpoint (u <- u + z, a first-order baseline)", "SNESSSStarSetMethod", SSStarMethods, (PetscEnum)ss->method, (PetscEnum *)&method, &set));
  if (set) PetscCall(SNESSSStarSetMethod(snes, method));
  PetscCall(PetscOptionsReal("-snes_ssstar_state_tol", "Relative tolerance tau of the contact-state classification", "SNESSSStarSetStateTolerance", ss->state_tol, &value, &set));
  if (set) PetscCall(SNESSSStarSetStateTolerance(snes, value));
  PetscCall(SSStarNewtonGetReuse(ss->newton, &value));
  PetscCall(PetscOptionsReal("-snes_ssstar_lu_reuse", "Solve a Newton step by GMRES on the last LU while at most this fraction of the nodes changed their known rows since it (negative: a fresh LU at every step)", "SNESSSStarSetLUReuse", value, &value, &set));
  if (set) PetscCall(SNESSSStarSetLUReuse(snes, value));
  PetscCall(SSStarNewtonGetLUThreads(ss->newton, &threads));
  PetscCall(PetscOptionsInt("-snes_ssstar_lu_threads", "BLAS threads of rank 0 for the LU of the Newton matrix on several ranks (0: the cores it may run on; 1: leave the BLAS)", "SNESSSStarSetLUThreads", threads, &threads, &set));
  if (set) PetscCall(SNESSSStarSetLUThreads(snes, threads));
  {
    PetscBool on = ss->glob.on, setOn, setDamping, setStagnation;
    PetscInt  its;

    PetscCall(PetscOptionsBool("-snes_ssstar_globalization", "Damped steps on ||z|| and remedies (false: the plain iteration)", "SNESSSStarSetGlobalization", on, &on, &setOn));
    PetscCall(PetscOptionsReal("-snes_ssstar_damping_min", "Smallest damping factor of the line search on ||z||", "SNESSSStarSetGlobalization", ss->glob.dampingMin, &value, &setDamping));
    PetscCall(PetscOptionsInt("-snes_ssstar_stagnation_its", "Stop after this many iterations without a smaller ||z||", "SNESSSStarSetGlobalization", ss->glob.stagnationIts, &its, &setStagnation));
    if (setOn || setDamping || setStagnation) PetscCall(SNESSSStarSetGlobalization(snes, on, setDamping ? value : PETSC_DEFAULT, setStagnation ? its : PETSC_DEFAULT));
  }
  PetscCall(SNESMonitorSetFromOptions(snes, "-snes_ssstar_monitor_states", "Monitor the number of contact nodes in each state, and the remedies", "SNESSSStarMonitorStates", SNESSSStarMonitorStates, NULL));
  PetscOptionsHeadEnd();
  PetscFunctionReturn(0);
}

/* "L 14 M1 55 M2 0 M3+ 15 M3- 0 M4 0" (LS, a Tresca state, only when some node has it) */
static PetscErrorCode FormatStateCounts(const PetscInt counts[], char buf[], size_t len)
{
  size_t used = 0;

  PetscFunctionBegin;
  buf[0] = 0;
  for (PetscInt s = 0; s < SSSTAR_NUM_STATES; s++) {
    if (s == SSSTAR_STATE_LS && !counts[s]) continue;
    PetscCall(PetscSNPrintf(buf + used, len - used, "%s%s %" PetscInt_FMT, s ? " " : "", SSStarStateNames[s], counts[s]));
    PetscCall(PetscStrlen(buf, &used));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESView_SSStar(SNES snes, PetscViewer viewer)
{
  SNES_SSStar *ss = (SNES_SSStar *)snes->data;
  PetscBool    isascii;

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &isascii));
  if (!isascii) PetscFunctionReturn(0);
  PetscCall(SSStarContactView(&ss->contact, viewer));
  if (ss->method != SSSTAR_METHOD_NEWTON) PetscCall(PetscViewerASCIIPrintf(viewer, "  method: %s (u <- u + z, no Newton step)\n", SSStarMethods[ss->method]));
  if (ss->scaling_user > 0) PetscCall(PetscViewerASCIIPrintf(viewer, "  approximation-step scaling gamma = %g\n", (double)ss->scaling_user));
  else if (ss->method == SSSTAR_METHOD_FIXEDPOINT) PetscCall(PetscViewerASCIIPrintf(viewer, "  approximation-step scaling gamma = 1/||P||_inf%s%g\n", ss->scaling > 0 ? " = " : "", ss->scaling > 0 ? (double)ss->scaling : 0.0));
  else PetscCall(PetscViewerASCIIPrintf(viewer, "  approximation-step scaling gamma = 1/mean(diag P)%s%g\n", ss->scaling > 0 ? " = " : "", ss->scaling > 0 ? (double)ss->scaling : 0.0));
  if (snes->ops->converged == SNESConvergedSSStar) PetscCall(PetscViewerASCIIPrintf(viewer, "  stopping rule ||z|| <= max(atol, rtol max(||u||, ||gamma f||)), atol = %g, rtol = %g\n", (double)snes->abstol, (double)snes->rtol));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  state tolerance tau = %g\n", (double)ss->state_tol));
  PetscCall(SSStarNewtonView(ss->newton, viewer));
  PetscCall(SSStarGlobalizationView(&ss->glob, viewer));
  if (ss->reason != SSSTAR_REASON_ITERATING) {
    char counts[256];

    PetscCall(FormatStateCounts(ss->counts, counts, sizeof(counts)));
    PetscCall(PetscViewerASCIIPrintf(viewer, "  last solve: %s after %" PetscInt_FMT " iterations, ||z|| = %g; contact states %s\n", SSStarReasons[ss->reason], snes->iter, (double)snes->norm, counts));
    PetscCall(SSStarGlobalizationViewCounts(&ss->glob, viewer));
  }
  PetscFunctionReturn(0);
}

/* With -snes_converged_reason, a line after PETSc's with the finer reason of ssstar */
static PetscErrorCode SNESSSStarConvergedReasonView(SNES snes, void *ctx)
{
  PetscViewer       viewer;
  PetscViewerFormat format;
  PetscBool         flg, isssstar;

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)snes, SNESSSSTAR, &isssstar));
  if (!isssstar) PetscFunctionReturn(0);
  PetscCall(PetscOptionsGetViewer(PetscObjectComm((PetscObject)snes), ((PetscObject)snes)->options, ((PetscObject)snes)->prefix, "-snes_converged_reason", &viewer, &format, &flg));
  if (!flg) PetscFunctionReturn(0);
  PetscCall(PetscViewerASCIIAddTab(viewer, ((PetscObject)snes)->tablevel));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  ssstar: %s, ||z|| = %g\n", SSStarReasons[((SNES_SSStar *)snes->data)->reason], (double)snes->norm));
  PetscCall(PetscViewerASCIISubtractTab(viewer, ((PetscObject)snes)->tablevel));
  PetscCall(PetscViewerDestroy(&viewer));
  PetscFunctionReturn(0);
}

/*@C
   SNESSSStarMonitorStates - prints, at every iteration, how many contact nodes are in each state of Table 1

   Options Database Key:
.  -snes_ssstar_monitor_states - activates it
@*/
PetscErrorCode SNESSSStarMonitorStates(SNES snes, PetscInt its, PetscReal znorm, PetscViewerAndFormat *vf)
{
  SNES_SSStar *ss     = (SNES_SSStar *)snes->data;
  PetscViewer  viewer = vf->viewer;
  char         counts[256], events[512];
  PetscInt     nlu, nreused, nkrylov;

  PetscFunctionBegin;
  PetscCall(PetscViewerPushFormat(viewer, vf->format));
  PetscCall(PetscViewerASCIIAddTab(viewer, ((PetscObject)snes)->tablevel));
  PetscCall(FormatStateCounts(ss->counts, counts, sizeof(counts)));
  PetscCall(SSStarNewtonGetCounts(ss->newton, &nlu, &nreused, &nkrylov));
  PetscCall(SSStarGlobalizationFormatEvents(&ss->glob, events, sizeof(events)));
  PetscCall(PetscViewerASCIIPrintf(viewer, "%3" PetscInt_FMT " SSStar states %s; Newton steps so far: %" PetscInt_FMT " LU, %" PetscInt_FMT " on an old LU (%" PetscInt_FMT " Krylov its)%s\n", its, counts, nlu, nreused, nkrylov, events));
  PetscCall(PetscViewerASCIISubtractTab(viewer, ((PetscObject)snes)->tablevel));
  PetscCall(PetscViewerPopFormat(viewer));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarSetFrictionLaw_SSStar(SNES snes, SSStarFrictionLaw law)
{
  SSStarContact *ct = &((SNES_SSStar *)snes->data)->contact;

  PetscFunctionBegin;
  PetscCheck(law >= SSSTAR_FRICTION_NONE && law <= SSSTAR_FRICTION_COULOMB, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_OUTOFRANGE, "-snes_ssstar_friction_law %d: not none, tresca or coulomb", (int)law);
  PetscCall(SSStarContactSetLaw(ct, law, ct->friction));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarGetFrictionLaw_SSStar(SNES snes, SSStarFrictionLaw *law)
{
  PetscFunctionBegin;
  *law = ((SNES_SSStar *)snes->data)->contact.law;
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarSetFriction_SSStar(SNES snes, PetscReal phi)
{
  SSStarContact *ct = &((SNES_SSStar *)snes->data)->contact;

  PetscFunctionBegin;
  PetscCheck(phi >= 0 && !PetscIsInfOrNanReal(phi), PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_OUTOFRANGE, "-snes_ssstar_friction %g: the friction coefficient must be a number >= 0", (double)phi);
  PetscCall(SSStarContactSetLaw(ct, ct->law, phi));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarGetFriction_SSStar(SNES snes, PetscReal *phi)
{
  PetscFunctionBegin;
  *phi = ((SNES_SSStar *)snes->data)->contact.friction;
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarSetReductionType_SSStar(SNES snes, SSStarReductionType type)
{
  SSStarContact *ct = &((SNES_SSStar *)snes->data)->contact;

  PetscFunctionBegin;
  if (type != ct->reductionType) {
    ct->reductionType = type;
    PetscCall(MatDestroy(&ct->P)); /* the next solve reduces K again */
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarSetMemoryLimit_SSStar(SNES snes, PetscReal gigabytes)
{
  SSStarContact *ct = &((SNES_SSStar *)snes->data)->contact;

  PetscFunctionBegin;
  PetscCheck(gigabytes >= 0 && !PetscIsInfOrNanReal(gigabytes), PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_OUTOFRANGE, "-snes_ssstar_memory_limit %g: the limit must be > 0 GB (or 0 for the available memory)", (double)gigabytes);
  ct->memoryLimit = gigabytes;
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarSetScaling_SSStar(SNES snes, PetscReal gamma)
{
  PetscFunctionBegin;
  PetscCheck(gamma >= 0 && !PetscIsInfOrNanReal(gamma), PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_OUTOFRANGE, "-snes_ssstar_scaling %g: gamma must be > 0 (or 0 for 1/mean diag P)", (double)gamma);
  ((SNES_SSStar *)snes->data)->scaling_user = gamma;
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarGetScaling_SSStar(SNES snes, PetscReal *gamma)
{
  SNES_SSStar *ss = (SNES_SSStar *)snes->data;

  PetscFunctionBegin;
  *gamma = ss->scaling_user > 0 ? ss->scaling_user : ss->scaling;
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarSetStateTolerance_SSStar(SNES snes, PetscReal tau)
{
  PetscFunctionBegin;
  PetscCheck(tau >= 0 && tau < 1, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_OUTOFRANGE, "-snes_ssstar_state_tol %g must be in [0, 1)", (double)tau);
  ((SNES_SSStar *)snes->data)->state_tol = tau;
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarSetMethod_SSStar(SNES snes, SSStarMethod method)
{
  PetscFunctionBegin;
  PetscCheck(method == SSSTAR_METHOD_NEWTON || method == SSSTAR_METHOD_FIXEDPOINT, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_OUTOFRANGE, "ssstar: unknown method %d", (int)method);
  ((SNES_SSStar *)snes->data)->method = method;
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarGetMethod_SSStar(SNES snes, SSStarMethod *method)
{
  PetscFunctionBegin;
  *method = ((SNES_SSStar *)snes->data)->method;
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarSetLUReuse_SSStar(SNES snes, PetscReal fraction)
{
  PetscFunctionBegin;
  PetscCheck(fraction <= 1 && !PetscIsInfOrNanReal(fraction), PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_OUTOFRANGE, "-snes_ssstar_lu_reuse %g must be at most 1 (negative: never)", (double)fraction);
  PetscCall(SSStarNewtonSetReuse(((SNES_SSStar *)snes->data)->newton, fraction));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarGetNewtonStepCounts_SSStar(SNES snes, PetscInt *factorizations, PetscInt *reused, PetscInt *krylov)
{
  PetscFunctionBegin;
  PetscCall(SSStarNewtonGetCounts(((SNES_SSStar *)snes->data)->newton, factorizations, reused, krylov));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarSetLUThreads_SSStar(SNES snes, PetscInt threads)
{
  PetscFunctionBegin;
  PetscCheck(threads >= 0, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_OUTOFRANGE, "-snes_ssstar_lu_threads %" PetscInt_FMT " must be >= 0 (0: the cores rank 0 may run on)", threads);
  PetscCall(SSStarNewtonSetLUThreads(((SNES_SSStar *)snes->data)->newton, threads));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarGetConditionEstimate_SSStar(SNES snes, PetscReal *rcond)
{
  PetscFunctionBegin;
  PetscCall(SSStarNewtonGetConditionEstimate(((SNES_SSStar *)snes->data)->newton, rcond));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarGetStates_SSStar(SNES snes, const SSStarState *states[], PetscInt counts[])
{
  SNES_SSStar *ss = (SNES_SSStar *)snes->data;

  PetscFunctionBegin;
  if (states) *states = ss->userStates;
  if (counts) PetscCall(PetscArraycpy(counts, ss->counts, SSSTAR_NUM_STATES));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarGetReason_SSStar(SNES snes, SSStarReason *reason)
{
  PetscFunctionBegin;
  *reason = ((SNES_SSStar *)snes->data)->reason;
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarSetGlobalization_SSStar(SNES snes, PetscBool on, PetscReal dampingMin, PetscInt stagnationIts)
{
  SSStarGlobalization *glob = &((SNES_SSStar *)snes->data)->glob;

  PetscFunctionBegin;
  glob->on = on;
  if (dampingMin != PETSC_DEFAULT) {
    PetscCheck(dampingMin > 0 && dampingMin <= 1, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_OUTOFRANGE, "-snes_ssstar_damping_min %g: must be in (0, 1]", (double)dampingMin);
    glob->dampingMin = dampingMin;
  }
  if (stagnationIts != PETSC_DEFAULT) {
    PetscCheck(stagnationIts >= 1, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_OUTOFRANGE, "-snes_ssstar_stagnation_its %" PetscInt_FMT ": must be >= 1", stagnationIts);
    glob->stagnationIts = stagnationIts;
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarGetRemedyCounts_SSStar(SNES snes, PetscInt counts[])
{
  PetscFunctionBegin;
  PetscCall(PetscArraycpy(counts, ((SNES_SSStar *)snes->data)->glob.counts, SSSTAR_NUM_REMEDIES));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarGetReducedProblem_SSStar(SNES snes, Mat *P, Vec *f)
{
  SSStarContact *ct = &((SNES_SSStar *)snes->data)->contact;

  PetscFunctionBegin;
  PetscCheck(ct->P, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_WRONGSTATE, "SNESSSStarGetReducedProblem: no reduced problem before SNESSolve()");
  if (P) *P = ct->P;
  if (f) *f = ct->f;
  PetscFunctionReturn(0);
}

/*MC
   SNESSSSTAR - "ssstar": semismooth* Newton method for 3D contact with friction (Coulomb, Tresca or none)

   Whole body: the SNES function is F(u) = K u - b, the Jacobian K, and SNESSSStarSetContactNodes() names the contact
   nodes' dofs, the obstacle's normals and the gaps; SNESSolve() reduces K to the contact dofs (Schur complement P),
   solves there and returns the whole u; SNESGetFunction() then holds K u - b, the contact forces.
   Reduced: the SNES function is c(u) = P u - f and the Jacobian P, one (u_t1, u_t2, u_n) block per contact node.

   Each iteration: an approximation step (a closed-form projection per node, in the node's frame), a classification
   of every node into the states of Table 1, and a Newton step through the reduced system (S P + T) du = (S + T) z.

   Options Database Keys:
+  -snes_ssstar_friction_law <coulomb> - none, tresca or coulomb
.  -snes_ssstar_friction <0.3> - Coulomb friction coefficient
.  -snes_ssstar_reduction <direct> - Schur complement of K: direct, mumps or explicit
.  -snes_ssstar_memory_limit <0> - GB per rank the reduction may plan for (0: MemAvailable of the node per rank)
.  -snes_ssstar_scaling <0> - scaling gamma of the approximation step (0: 1/mean(diag P))
.  -snes_ssstar_method <newton> - newton (semismooth*) or fixedpoint (the first-order baseline u <- u + z)
.  -snes_ssstar_state_tol <1e-13> - relative tolerance of the state classification
.  -snes_ssstar_monitor_states - print the number of nodes per state at every iteration, and the remedies
.  -snes_ssstar_globalization <true> - damped steps on ||z|| and remedies; false: the plain iteration
.  -snes_ssstar_damping_min <0.015625> - smallest damping factor of the line search
.  -snes_ssstar_stagnation_its <20> - stop after this many iterations without a smaller ||z||
.  -snes_ssstar_lu_threads <1> - on several ranks, rank 0's BLAS threads for the LU of the Newton matrix (0: the cores it may run on)
.  -snes_ssstar_lu_reuse <0> - dense P: solve a Newton step by GMRES on the last LU while at most this fraction of the nodes changed their known rows since it (negative: never); -snes_ssstar_newton_ksp_* set that GMRES
.  -snes_rtol <1e-10> - stop when ||z|| <= rtol max(||u||, ||gamma f||) (SNESConvergedSSStar())
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
  ss->contact.law           = SSSTAR_FRICTION_COULOMB;
  ss->contact.friction      = 0.3;
  ss->contact.reductionType = SSSTAR_REDUCTION_DIRECT;
  ss->contact.built         = -1;
  ss->state_tol             = 1e-13;
  ss->glob.on               = PETSC_TRUE;
  ss->glob.dampingMin       = 1.0 / 64;
  ss->glob.stagnationIts    = 20;
  snes->data                = (void *)ss;
  PetscCall(SSStarNewtonCreate(snes, &ss->newton));

  PetscCall(SNESGetKSP(snes, &snes->ksp));
  PetscCall(KSPSetType(snes->ksp, KSPPREONLY));
  PetscCall(KSPGetPC(snes->ksp, &pc));
  PetscCall(PCSetType(pc, PCLU));
  for (PetscInt i = 0; i < snes->numberreasonviews; i++)
    if (snes->reasonview[i] == SNESSSStarConvergedReasonView) registered = PETSC_TRUE;
  if (!registered) PetscCall(SNESConvergedReasonViewSet(snes, SNESSSStarConvergedReasonView, NULL, NULL));

  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(SetContactNodes), SNESSSStarSetContactNodes_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(SetFrictionLaw), SNESSSStarSetFrictionLaw_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(GetFrictionLaw), SNESSSStarGetFrictionLaw_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(SetFriction), SNESSSStarSetFriction_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(GetFriction), SNESSSStarGetFriction_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(SetFrictionCoefficients), SNESSSStarSetFrictionCoefficients_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(SetSlipBounds), SNESSSStarSetSlipBounds_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(SetNodeFrictionLaws), SNESSSStarSetNodeFrictionLaws_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(SetReductionType), SNESSSStarSetReductionType_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(SetMemoryLimit), SNESSSStarSetMemoryLimit_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(SetScaling), SNESSSStarSetScaling_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(GetScaling), SNESSSStarGetScaling_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(SetStateTolerance), SNESSSStarSetStateTolerance_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(SetMethod), SNESSSStarSetMethod_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(GetMethod), SNESSSStarGetMethod_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(GetStates), SNESSSStarGetStates_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(GetReason), SNESSSStarGetReason_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(GetReducedProblem), SNESSSStarGetReducedProblem_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(SetGlobalization), SNESSSStarSetGlobalization_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(GetRemedyCounts), SNESSSStarGetRemedyCounts_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(SetLUReuse), SNESSSStarSetLUReuse_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(GetNewtonStepCounts), SNESSSStarGetNewtonStepCounts_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(GetConditionEstimate), SNESSSStarGetConditionEstimate_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(SetLUThreads), SNESSSStarSetLUThreads_SSStar));
  PetscFunctionReturn(0);
}
