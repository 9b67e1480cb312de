/*
   The SNES type "ssstar": semismooth* Newton method for 0 in c(u) + Q(u) (DERIVATION.md section 7).
*/
#include "ssstarimpl.h"

const char *const SSStarReasons[] = {"ITERATING", "CONVERGED_ZNORM", "MAX_IT", "NAN_OR_INF", "SINGULAR_NEWTON_MATRIX", "SSStarReason", "SSSTAR_REASON_", NULL};

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
  PetscCall(MatCreateVecs(P, &diag, NULL));
  PetscCall(MatGetDiagonal(P, diag));
  PetscCall(VecSum(diag, &sum));
  PetscCall(VecGetSize(diag, &N));
  PetscCall(VecDestroy(&diag));
  PetscCheck(PetscRealPart(sum) > 0, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_WRONG, "ssstar: mean diagonal of P is %g, not positive; set -snes_ssstar_scaling", (double)PetscRealPart(sum) / N);
  ss->scaling = N / PetscRealPart(sum);
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSetUp_SSStar(SNES snes)
{
  SNES_SSStar *ss = (SNES_SSStar *)snes->data;
  PetscInt     n, N;
  PC           pc;
  MatSolverType solver;
  PetscMPIInt  size;
  PetscBool    isdense;

  PetscFunctionBegin;
  PetscCheck(snes->jacobian, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_WRONGSTATE, "ssstar needs the matrix P: call SNESSetJacobian()");
  PetscCall(SNESSetWorkVecs(snes, 6));
  PetscCall(VecGetLocalSize(snes->vec_sol, &n));
  PetscCall(VecGetSize(snes->vec_sol, &N));
  PetscCheck(n % 3 == 0, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "ssstar: local vector size %" PetscInt_FMT " is not a multiple of 3 (one (u_t1, u_t2, u_n) block per contact node)", n);
  ss->nnodes = n / 3;
  PetscCall(PetscFree(ss->states));
  PetscCall(PetscCalloc1(ss->nnodes, &ss->states));

  /* S and T keep a fixed full 3x3 block-diagonal pattern so that S P can be recomputed in place */
  PetscCall(MatDestroy(&ss->S));
  PetscCall(MatDestroy(&ss->T));
  PetscCall(MatCreateAIJ(PetscObjectComm((PetscObject)snes), n, n, N, N, 3, NULL, 0, NULL, &ss->S));
  PetscCall(MatSetBlockSize(ss->S, 3));
  PetscCall(MatSetOption(ss->S, MAT_IGNORE_ZERO_ENTRIES, PETSC_FALSE));
  PetscCall(MatDuplicate(ss->S, MAT_DO_NOT_COPY_VALUES, &ss->T));

  PetscCall(KSPGetPC(snes->ksp, &pc));
  PetscCall(PCFactorGetMatSolverType(pc, &solver));
  PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)snes), &size));
  PetscCall(PetscObjectTypeCompareAny((PetscObject)snes->jacobian, &isdense, MATDENSE, MATMPIDENSE, MATSEQDENSE, ""));
  /* parallel dense LU is ScaLAPACK's, on a MATSCALAPACK copy of A; parallel sparse LU is MUMPS's */
  ss->scalapack = (PetscBool)(size > 1 && isdense);
  if (!solver && size > 1 && !isdense) PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  PetscFunctionReturn(0);
}

/* Section 1 on every local node, with the scaled c = gamma (P u - f) (section 6) */
static PetscErrorCode SNESSSStarApproximationStep(SNES snes, Vec x, Vec c, Vec z, Vec d, Vec b)
{
  SNES_SSStar       *ss = (SNES_SSStar *)snes->data;
  const PetscScalar *xa, *ca;
  PetscScalar       *za, *da, *ba;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(SSSTAR_ApproxStep, snes, 0, 0, 0));
  PetscCall(VecGetArrayRead(x, &xa));
  PetscCall(VecGetArrayRead(c, &ca));
  PetscCall(VecGetArrayWrite(z, &za));
  PetscCall(VecGetArrayWrite(d, &da));
  PetscCall(VecGetArrayWrite(b, &ba));
  for (PetscInt i = 0; i < ss->nnodes; i++) {
    const PetscReal gc[3] = {ss->scaling * ca[3 * i], ss->scaling * ca[3 * i + 1], ss->scaling * ca[3 * i + 2]};
    SSStarApproximationStep(ss->friction, &xa[3 * i], gc, &za[3 * i], &da[3 * i], &ba[3 * i]);
  }
  PetscCall(VecRestoreArrayWrite(b, &ba));
  PetscCall(VecRestoreArrayWrite(d, &da));
  PetscCall(VecRestoreArrayWrite(z, &za));
  PetscCall(VecRestoreArrayRead(c, &ca));
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscCall(PetscLogEventEnd(SSSTAR_ApproxStep, snes, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* Section 2 with tol_d = tau max(|u|, |d|), tol_b = tau max(|gamma f|, |b|) (infinity norms) */
static PetscErrorCode SNESSSStarClassify(SNES snes, Vec x, Vec d, Vec b, PetscReal fnorm_inf)
{
  SNES_SSStar       *ss = (SNES_SSStar *)snes->data;
  const PetscScalar *da, *ba;
  PetscReal          xn, dn, bn, tol_d, tol_b;

  PetscFunctionBegin;
  PetscCall(VecNorm(x, NORM_INFINITY, &xn));
  PetscCall(VecNorm(d, NORM_INFINITY, &dn));
  PetscCall(VecNorm(b, NORM_INFINITY, &bn));
  tol_d = ss->state_tol * PetscMax(xn, dn);
  tol_b = ss->state_tol * PetscMax(ss->scaling * fnorm_inf, bn);
  PetscCall(PetscArrayzero(ss->counts, SSSTAR_NUM_STATES));
  PetscCall(VecGetArrayRead(d, &da));
  PetscCall(VecGetArrayRead(b, &ba));
  for (PetscInt i = 0; i < ss->nnodes; i++) {
    ss->states[i] = SSStarClassify(ss->friction, &da[3 * i], &ba[3 * i], tol_d, tol_b);
    ss->counts[ss->states[i]]++;
  }
  PetscCall(VecRestoreArrayRead(b, &ba));
  PetscCall(VecRestoreArrayRead(d, &da));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, ss->counts, SSSTAR_NUM_STATES, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)snes)));
  PetscFunctionReturn(0);
}

/*
   Sets up the KSP (the LU factorization of the Newton matrix). Dense LU (LAPACK, ScaLAPACK) raises an error on a
   zero pivot where sparse LU only flags it: catch that error so that a singular Newton matrix ends the solve with
   SNES_DIVERGED_LINEAR_SOLVE instead of aborting the program.
*/
static PetscErrorCode FactorNewtonMatrix(SNES snes, PetscBool *factored)
{
  PetscErrorCode ierr;
  PetscBool      ok;

  PetscFunctionBegin;
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  ierr = KSPSetUp(snes->ksp);
  PetscCall(PetscPopErrorHandler());
  if (ierr != PETSC_ERR_MAT_LU_ZRPVT && ierr != PETSC_ERR_LIB) PetscCall(ierr);
  ok = (PetscBool)(ierr == 0);
  PetscCall(MPIU_Allreduce(&ok, factored, 1, MPIU_BOOL, MPI_LAND, PetscObjectComm((PetscObject)snes)));
  PetscFunctionReturn(0);
}

/*
   Section 5: A = gamma S P + T and y = (S + T) z, then A du = y.
   Returns PETSC_FALSE when the linear solve failed.
*/
static PetscErrorCode SNESSSStarNewtonStep(SNES snes, Mat P, Vec z, Vec d, Vec b, Vec y, Vec du, PetscBool *solved)
{
  SNES_SSStar       *ss = (SNES_SSStar *)snes->data;
  const PetscScalar *za, *da, *ba;
  PetscScalar       *ya;
  PetscInt           rstart;
  KSPConvergedReason kspreason;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(SSSTAR_NewtonStep, snes, 0, 0, 0));
  PetscCall(MatGetOwnershipRange(ss->S, &rstart, NULL));
  PetscCall(VecGetArrayRead(z, &za));
  PetscCall(VecGetArrayRead(d, &da));
  PetscCall(VecGetArrayRead(b, &ba));
  PetscCall(VecGetArrayWrite(y, &ya));
  for (PetscInt i = 0; i < ss->nnodes; i++) {
    const PetscInt idx[3] = {rstart + 3 * i, rstart + 3 * i + 1, rstart + 3 * i + 2};
    PetscReal      S[9], T[9];

    SSStarReducedBlocks(ss->states[i], ss->friction, &da[3 * i], &ba[3 * i], S, T);
    for (PetscInt r = 0; r < 3; r++) {
      ya[3 * i + r] = 0;
      for (PetscInt k = 0; k < 3; k++) ya[3 * i + r] += (S[3 * r + k] + T[3 * r + k]) * za[3 * i + k];
    }
    PetscCall(MatSetValues(ss->S, 3, idx, 3, idx, S, INSERT_VALUES));
    PetscCall(MatSetValues(ss->T, 3, idx, 3, idx, T, INSERT_VALUES));
  }
  PetscCall(VecRestoreArrayWrite(y, &ya));
  PetscCall(VecRestoreArrayRead(b, &ba));
  PetscCall(VecRestoreArrayRead(d, &da));
  PetscCall(VecRestoreArrayRead(z, &za));
  PetscCall(MatAssemblyBegin(ss->S, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(ss->S, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyBegin(ss->T, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(ss->T, MAT_FINAL_ASSEMBLY));

  PetscCall(MatMatMult(ss->S, P, ss->SP ? MAT_REUSE_MATRIX : MAT_INITIAL_MATRIX, PETSC_DEFAULT, &ss->SP));
  if (!ss->A) {
    PetscCall(MatDuplicate(ss->SP, MAT_COPY_VALUES, &ss->A));
    PetscCall(MatScale(ss->A, ss->scaling));
    PetscCall(MatAXPY(ss->A, 1.0, ss->T, DIFFERENT_NONZERO_PATTERN));
  } else {
    PetscCall(MatCopy(ss->SP, ss->A, SUBSET_NONZERO_PATTERN));
    PetscCall(MatScale(ss->A, ss->scaling));
    PetscCall(MatAXPY(ss->A, 1.0, ss->T, SUBSET_NONZERO_PATTERN));
  }
  if (ss->scalapack) {
    /* MATSCALAPACK chooses its own row layout: move y and du to it and back */
    PetscCall(MatConvert(ss->A, MATSCALAPACK, ss->Ascalapack ? MAT_REUSE_MATRIX : MAT_INITIAL_MATRIX, &ss->Ascalapack));
    if (!ss->toScalapack) {
      PetscInt lo, hi;
      IS       own;

      PetscCall(MatCreateVecs(ss->Ascalapack, &ss->duScalapack, &ss->yScalapack));
      PetscCall(VecGetOwnershipRange(y, &lo, &hi));
      PetscCall(ISCreateStride(PETSC_COMM_SELF, hi - lo, lo, 1, &own));
      PetscCall(VecScatterCreate(y, own, ss->yScalapack, own, &ss->toScalapack));
      PetscCall(ISDestroy(&own));
    }
    PetscCall(KSPSetOperators(snes->ksp, ss->Ascalapack, ss->Ascalapack));
    PetscCall(FactorNewtonMatrix(snes, solved));
    if (!*solved) goto done;
    PetscCall(VecScatterBegin(ss->toScalapack, y, ss->yScalapack, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterEnd(ss->toScalapack, y, ss->yScalapack, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(KSPSolve(snes->ksp, ss->yScalapack, ss->duScalapack));
    PetscCall(VecScatterBegin(ss->toScalapack, ss->duScalapack, du, INSERT_VALUES, SCATTER_REVERSE));
    PetscCall(VecScatterEnd(ss->toScalapack, ss->duScalapack, du, INSERT_VALUES, SCATTER_REVERSE));
  } else {
    PetscCall(KSPSetOperators(snes->ksp, ss->A, ss->A));
    PetscCall(FactorNewtonMatrix(snes, solved));
    if (!*solved) goto done;
    PetscCall(KSPSolve(snes->ksp, y, du));
  }
  PetscCall(KSPGetConvergedReason(snes->ksp, &kspreason));
  *solved = (PetscBool)(kspreason >= 0);
done:
  PetscCall(PetscLogEventEnd(SSSTAR_NewtonStep, snes, 0, 0, 0));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSolve_SSStar(SNES snes)
{
  SNES_SSStar *ss = (SNES_SSStar *)snes->data;
  Vec          x = snes->vec_sol, c = snes->work[0], z = snes->work[1], d = snes->work[2], b = snes->work[3], y = snes->work[4], du = snes->work[5];
  Mat          P = snes->jacobian;
  PetscReal    znorm, fnorm_inf;
  PetscBool    solved;

  PetscFunctionBegin;
  snes->reason = SNES_CONVERGED_ITERATING;
  ss->reason   = SSSTAR_REASON_ITERATING;
  PetscCall(PetscObjectSAWsTakeAccess((PetscObject)snes));
  snes->iter = 0;
  snes->norm = 0;
  PetscCall(PetscObjectSAWsGrantAccess((PetscObject)snes));

  /* c(u) = P u - f is affine: P once, and |f| from c(0) */
  PetscCall(SNESComputeJacobian(snes, x, snes->jacobian, snes->jacobian_pre));
  if (ss->P != P) { /* S P is reused across solves only for the same P */
    PetscCall(MatDestroy(&ss->SP));
    PetscCall(MatDestroy(&ss->A));
    ss->P = P;
  }
  PetscCall(SNESSSStarComputeScaling(snes, P));
  PetscCall(VecZeroEntries(z));
  PetscCall(SNESComputeFunction(snes, z, c));
  PetscCall(VecNorm(c, NORM_INFINITY, &fnorm_inf));

  for (PetscInt k = 0;; k++) {
    PetscCall(SNESComputeFunction(snes, x, c));
    if (snes->vec_func) PetscCall(VecCopy(c, snes->vec_func)); /* SNESGetFunction() gives r = P u - f at the last iterate */
    PetscCall(SNESSSStarApproximationStep(snes, x, c, z, d, b));
    PetscCall(VecNorm(z, NORM_2, &znorm));
    PetscCall(SNESSSStarClassify(snes, x, d, b, fnorm_inf));
    PetscCall(PetscObjectSAWsTakeAccess((PetscObject)snes));
    snes->iter = k;
    snes->norm = znorm;
    PetscCall(PetscObjectSAWsGrantAccess((PetscObject)snes));
    PetscCall(SNESLogConvergenceHistory(snes, znorm, snes->linear_its));
    PetscCall(SNESMonitor(snes, k, znorm));
    if (PetscIsInfOrNanReal(znorm)) {
      ss->reason   = SSSTAR_REASON_NAN;
      snes->reason = SNES_DIVERGED_FNORM_NAN;
    } else if (znorm <= ss->atol) {
      ss->reason   = SSSTAR_REASON_CONVERGED;
      snes->reason = SNES_CONVERGED_FNORM_ABS;
    } else if (k >= snes->max_its) {
      ss->reason   = SSSTAR_REASON_MAX_IT;
      snes->reason = SNES_DIVERGED_MAX_IT;
    }
    if (snes->reason) break;

    PetscCall(SNESSSStarNewtonStep(snes, P, z, d, b, y, du, &solved));
    if (!solved) {
      ss->reason   = SSSTAR_REASON_SINGULAR_NEWTON;
      snes->reason = SNES_DIVERGED_LINEAR_SOLVE;
      break;
    }
    PetscCall(VecAXPY(x, 1.0, du));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESReset_SSStar(SNES snes)
{
  SNES_SSStar *ss = (SNES_SSStar *)snes->data;

  PetscFunctionBegin;
  PetscCall(MatDestroy(&ss->S));
  PetscCall(MatDestroy(&ss->T));
  PetscCall(MatDestroy(&ss->SP));
  PetscCall(MatDestroy(&ss->A));
  ss->P = NULL;
  PetscCall(MatDestroy(&ss->Ascalapack));
  PetscCall(VecDestroy(&ss->yScalapack));
  PetscCall(VecDestroy(&ss->duScalapack));
  PetscCall(VecScatterDestroy(&ss->toScalapack));
  PetscCall(PetscFree(ss->states));
  ss->nnodes = 0;
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESDestroy_SSStar(SNES snes)
{
  PetscFunctionBegin;
  PetscCall(SNESReset_SSStar(snes));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, "SNESSSStarSetFriction_C", NULL));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, "SNESSSStarGetFriction_C", NULL));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, "SNESSSStarSetScaling_C", NULL));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, "SNESSSStarGetScaling_C", NULL));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, "SNESSSStarSetTolerance_C", NULL));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, "SNESSSStarGetTolerance_C", NULL));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, "SNESSSStarSetStateTolerance_C", NULL));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, "SNESSSStarGetStates_C", NULL));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, "SNESSSStarGetReason_C", NULL));
  PetscCall(PetscFree(snes->data));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSetFromOptions_SSStar(SNES snes, PetscOptionItems *PetscOptionsObject)
{
  SNES_SSStar *ss = (SNES_SSStar *)snes->data;
  PetscReal    value;
  PetscBool    set;

  PetscFunctionBegin;
  PetscOptionsHeadBegin(PetscOptionsObject, "SNES ssstar options (semismooth* Newton for Coulomb contact)");
  PetscCall(PetscOptionsReal("-snes_ssstar_friction", "Coulomb friction coefficient phi >= 0", "SNESSSStarSetFriction", ss->friction, &value, &set));
  if (set) PetscCall(SNESSSStarSetFriction(snes, value));
  PetscCall(PetscOptionsReal("-snes_ssstar_scaling", "Scaling gamma of the approximation step (0: 1/mean diag P)", "SNESSSStarSetScaling", ss->scaling_user, &value, &set));
  if (set) PetscCall(SNESSSStarSetScaling(snes, value));
  PetscCall(PetscOptionsReal("-snes_ssstar_atol", "Stop when ||z|| <= atol", "SNESSSStarSetTolerance", ss->atol, &value, &set));
  if (set) PetscCall(SNESSSStarSetTolerance(snes, value));
  PetscCall(PetscOptionsReal("-snes_ssstar_state_tol", "Relative tolerance tau of the contact-state classification", "SNESSSStarSetStateTolerance", ss->state_tol, &value, &set));
  if (set) PetscCall(SNESSSStarSetStateTolerance(snes, value));
  PetscCall(SNESMonitorSetFromOptions(snes, "-snes_ssstar_monitor_states", "Monitor the number of contact nodes in each state", "SNESSSStarMonitorStates", SNESSSStarMonitorStates, NULL));
  PetscOptionsHeadEnd();
  PetscFunctionReturn(0);
}

/* "L 14 M1 55 M2 0 M3+ 15 M3- 0 M4 0" */
static PetscErrorCode FormatStateCounts(const PetscInt counts[], char buf[], size_t len)
{
  size_t used = 0;

  PetscFunctionBegin;
  buf[0] = 0;
  for (PetscInt s = 0; s < SSSTAR_NUM_STATES; s++) {
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
  PetscCall(PetscViewerASCIIPrintf(viewer, "  friction coefficient phi = %g\n", (double)ss->friction));
  if (ss->scaling_user > 0) PetscCall(PetscViewerASCIIPrintf(viewer, "  approximation-step scaling gamma = %g\n", (double)ss->scaling_user));
  else PetscCall(PetscViewerASCIIPrintf(viewer, "  approximation-step scaling gamma = 1/mean(diag P)%s%g\n", ss->scaling > 0 ? " = " : "", ss->scaling > 0 ? (double)ss->scaling : 0.0));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  stopping rule ||z|| <= %g, state tolerance tau = %g\n", (double)ss->atol, (double)ss->state_tol));
  if (ss->reason != SSSTAR_REASON_ITERATING) {
    char counts[256];

    PetscCall(FormatStateCounts(ss->counts, counts, sizeof(counts)));
    PetscCall(PetscViewerASCIIPrintf(viewer, "  last solve: %s; contact states %s\n", SSStarReasons[ss->reason], counts));
  }
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
  char         counts[256];

  PetscFunctionBegin;
  PetscCall(PetscViewerPushFormat(viewer, vf->format));
  PetscCall(PetscViewerASCIIAddTab(viewer, ((PetscObject)snes)->tablevel));
  PetscCall(FormatStateCounts(ss->counts, counts, sizeof(counts)));
  PetscCall(PetscViewerASCIIPrintf(viewer, "%3" PetscInt_FMT " SSStar states %s\n", its, counts));
  PetscCall(PetscViewerASCIISubtractTab(viewer, ((PetscObject)snes)->tablevel));
  PetscCall(PetscViewerPopFormat(viewer));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarSetFriction_SSStar(SNES snes, PetscReal phi)
{
  PetscFunctionBegin;
  PetscCheck(phi >= 0, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_OUTOFRANGE, "-snes_ssstar_friction %g: the friction coefficient must be >= 0", (double)phi);
  ((SNES_SSStar *)snes->data)->friction = phi;
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarGetFriction_SSStar(SNES snes, PetscReal *phi)
{
  PetscFunctionBegin;
  *phi = ((SNES_SSStar *)snes->data)->friction;
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarSetScaling_SSStar(SNES snes, PetscReal gamma)
{
  PetscFunctionBegin;
  PetscCheck(gamma >= 0, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_OUTOFRANGE, "-snes_ssstar_scaling %g: gamma must be > 0 (or 0 for 1/mean diag P)", (double)gamma);
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

static PetscErrorCode SNESSSStarSetTolerance_SSStar(SNES snes, PetscReal atol)
{
  PetscFunctionBegin;
  PetscCheck(atol >= 0, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_OUTOFRANGE, "-snes_ssstar_atol %g must be >= 0", (double)atol);
  ((SNES_SSStar *)snes->data)->atol = atol;
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarGetTolerance_SSStar(SNES snes, PetscReal *atol)
{
  PetscFunctionBegin;
  *atol = ((SNES_SSStar *)snes->data)->atol;
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarSetStateTolerance_SSStar(SNES snes, PetscReal tau)
{
  PetscFunctionBegin;
  PetscCheck(tau >= 0 && tau < 1, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_OUTOFRANGE, "-snes_ssstar_state_tol %g must be in [0, 1)", (double)tau);
  ((SNES_SSStar *)snes->data)->state_tol = tau;
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarGetStates_SSStar(SNES snes, const SSStarState *states[], PetscInt counts[])
{
  SNES_SSStar *ss = (SNES_SSStar *)snes->data;

  PetscFunctionBegin;
  if (states) *states = ss->states;
  if (counts) PetscCall(PetscArraycpy(counts, ss->counts, SSSTAR_NUM_STATES));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarGetReason_SSStar(SNES snes, SSStarReason *reason)
{
  PetscFunctionBegin;
  *reason = ((SNES_SSStar *)snes->data)->reason;
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarSetFriction - sets the Coulomb friction coefficient phi (default 0.3)

   Options Database Key:
.  -snes_ssstar_friction <phi> - the coefficient
@*/
PetscErrorCode SNESSSStarSetFriction(SNES snes, PetscReal phi)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscTryMethod(snes, "SNESSSStarSetFriction_C", (SNES, PetscReal), (snes, phi));
  PetscFunctionReturn(0);
}

PetscErrorCode SNESSSStarGetFriction(SNES snes, PetscReal *phi)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscUseMethod(snes, "SNESSSStarGetFriction_C", (SNES, PetscReal *), (snes, phi));
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarSetScaling - sets gamma, the scaling of the approximation step (DERIVATION.md section 6);
   0 (the default) means gamma = 1/mean(diag P)

   Options Database Key:
.  -snes_ssstar_scaling <gamma> - the scaling
@*/
PetscErrorCode SNESSSStarSetScaling(SNES snes, PetscReal gamma)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscTryMethod(snes, "SNESSSStarSetScaling_C", (SNES, PetscReal), (snes, gamma));
  PetscFunctionReturn(0);
}

PetscErrorCode SNESSSStarGetScaling(SNES snes, PetscReal *gamma)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscUseMethod(snes, "SNESSSStarGetScaling_C", (SNES, PetscReal *), (snes, gamma));
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarSetTolerance - sets epsilon of the stopping rule ||z|| <= epsilon (default 1e-12)

   Options Database Key:
.  -snes_ssstar_atol <eps> - the tolerance
@*/
PetscErrorCode SNESSSStarSetTolerance(SNES snes, PetscReal atol)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscTryMethod(snes, "SNESSSStarSetTolerance_C", (SNES, PetscReal), (snes, atol));
  PetscFunctionReturn(0);
}

PetscErrorCode SNESSSStarGetTolerance(SNES snes, PetscReal *atol)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscUseMethod(snes, "SNESSSStarGetTolerance_C", (SNES, PetscReal *), (snes, atol));
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarSetStateTolerance - sets tau of the contact-state classification (default 1e-13)

   Options Database Key:
.  -snes_ssstar_state_tol <tau> - the tolerance
@*/
PetscErrorCode SNESSSStarSetStateTolerance(SNES snes, PetscReal tau)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscTryMethod(snes, "SNESSSStarSetStateTolerance_C", (SNES, PetscReal), (snes, tau));
  PetscFunctionReturn(0);
}

/*@C
   SNESSSStarGetStates - the state of each local contact node at the last iterate, and the global counts per state
@*/
PetscErrorCode SNESSSStarGetStates(SNES snes, const SSStarState *states[], PetscInt counts[SSSTAR_NUM_STATES])
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscUseMethod(snes, "SNESSSStarGetStates_C", (SNES, const SSStarState *[], PetscInt[]), (snes, states, counts));
  PetscFunctionReturn(0);
}

PetscErrorCode SNESSSStarGetReason(SNES snes, SSStarReason *reason)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscUseMethod(snes, "SNESSSStarGetReason_C", (SNES, SSStarReason *), (snes, reason));
  PetscFunctionReturn(0);
}

/*MC
   SNESSSSTAR - "ssstar": semismooth* Newton method for 3D contact with Coulomb friction

   The SNES function must be c(u) = P u - f and the Jacobian P; vectors hold one (u_t1, u_t2, u_n)
   block per contact node. Each iteration: an approximation step (a closed-form projection per
   node), a classification of every node into the states of Table 1, and a Newton step through
   the reduced system (S P + T) du = (S + T) z, solved with the SNES's KSP (default: LU).

   Options Database Keys:
+  -snes_ssstar_friction <0.3> - friction coefficient
.  -snes_ssstar_scaling <0> - scaling gamma of the approximation step (0: 1/mean(diag P))
.  -snes_ssstar_atol <1e-12> - stopping rule ||z|| <= atol
.  -snes_ssstar_state_tol <1e-13> - relative tolerance of the state classification
-  -snes_ssstar_monitor_states - print the number of nodes per state at every iteration
M*/
PETSC_EXTERN PetscErrorCode SNESCreate_SSStar(SNES snes)
{
  SNES_SSStar *ss;
  PC           pc;

  PetscFunctionBegin;
  snes->ops->setup          = SNESSetUp_SSStar;
  snes->ops->solve          = SNESSolve_SSStar;
  snes->ops->destroy        = SNESDestroy_SSStar;
  snes->ops->setfromoptions = SNESSetFromOptions_SSStar;
  snes->ops->view           = SNESView_SSStar;
  snes->ops->reset          = SNESReset_SSStar;
  snes->usesksp             = PETSC_TRUE;
  snes->usesnpc             = PETSC_FALSE;
  snes->alwayscomputesfinalresidual = PETSC_FALSE;

  PetscCall(PetscNew(&ss));
  ss->friction  = 0.3;
  ss->atol      = 1e-12;
  ss->state_tol = 1e-13;
  snes->data    = (void *)ss;

  PetscCall(SNESGetKSP(snes, &snes->ksp));
  PetscCall(KSPSetType(snes->ksp, KSPPREONLY));
  PetscCall(KSPGetPC(snes->ksp, &pc));
  PetscCall(PCSetType(pc, PCLU));

  PetscCall(PetscObjectComposeFunction((PetscObject)snes, "SNESSSStarSetFriction_C", SNESSSStarSetFriction_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, "SNESSSStarGetFriction_C", SNESSSStarGetFriction_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, "SNESSSStarSetScaling_C", SNESSSStarSetScaling_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, "SNESSSStarGetScaling_C", SNESSSStarGetScaling_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, "SNESSSStarSetTolerance_C", SNESSSStarSetTolerance_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, "SNESSSStarGetTolerance_C", SNESSSStarGetTolerance_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, "SNESSSStarSetStateTolerance_C", SNESSSStarSetStateTolerance_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, "SNESSSStarGetStates_C", SNESSSStarGetStates_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, "SNESSSStarGetReason_C", SNESSSStarGetReason_SSStar));
  PetscFunctionReturn(0);
}

typedef struct {
  Mat P;
  Vec f;
} ContactProblem;

static PetscErrorCode ContactProblemFunction(SNES snes, Vec u, Vec c, void *ctx)
{
  ContactProblem *cp = (ContactProblem *)ctx;

  PetscFunctionBegin;
  PetscCall(MatMult(cp->P, u, c));
  PetscCall(VecAXPY(c, -1.0, cp->f));
  PetscFunctionReturn(0);
}

static PetscErrorCode ContactProblemJacobian(SNES snes, Vec u, Mat J, Mat Jpre, void *ctx)
{
  PetscFunctionBegin;
  PetscFunctionReturn(0); /* J = P, constant */
}

static PetscErrorCode ContactProblemDestroy(void *ctx)
{
  ContactProblem *cp = (ContactProblem *)ctx;

  PetscFunctionBegin;
  PetscCall(MatDestroy(&cp->P));
  PetscCall(VecDestroy(&cp->f));
  PetscCall(PetscFree(cp));
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarSetContactProblem - sets the SNES function c(u) = P u - f and the Jacobian P of a contact problem
   0 in P u - f + Q(u), for a program that has P (dense or sparse, 3 dofs per contact node) and f

   Notes:
   Works with any SNES type; the SNES keeps references to P and f. After SNESSolve(), SNESGetFunction()
   gives the reaction r = P u - f at the solution.
@*/
PetscErrorCode SNESSSStarSetContactProblem(SNES snes, Mat P, Vec f)
{
  ContactProblem *cp;
  PetscContainer  container;
  Vec             r;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscValidHeaderSpecific(P, MAT_CLASSID, 2);
  PetscValidHeaderSpecific(f, VEC_CLASSID, 3);
  PetscCall(PetscNew(&cp));
  PetscCall(PetscObjectReference((PetscObject)P));
  PetscCall(PetscObjectReference((PetscObject)f));
  cp->P = P;
  cp->f = f;
  PetscCall(PetscContainerCreate(PetscObjectComm((PetscObject)snes), &container));
  PetscCall(PetscContainerSetPointer(container, cp));
  PetscCall(PetscContainerSetUserDestroy(container, ContactProblemDestroy));
  PetscCall(PetscObjectCompose((PetscObject)snes, "SNESSSStarContactProblem", (PetscObject)container));
  PetscCall(PetscContainerDestroy(&container));
  PetscCall(VecDuplicate(f, &r));
  PetscCall(SNESSetFunction(snes, r, ContactProblemFunction, cp));
  PetscCall(VecDestroy(&r));
  PetscCall(SNESSetJacobian(snes, P, P, ContactProblemJacobian, cp));
  PetscFunctionReturn(0);
}
