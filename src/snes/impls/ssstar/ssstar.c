/*
   The SNES type "ssstar": semismooth* Newton method for 0 in c(u) + Q(u) (docs/derivation.md section 7), on the contact
   dofs of a reduced problem or on the whole body (contact.c says which: the layout of the operator's vectors).
*/
#include "ssstarimpl.h"

const char *const SSStarMethods[] = {"newton", "fixedpoint", "SSStarMethod", "SSSTAR_METHOD_", NULL};
const char *const SSStarReasons[] = {"ITERATING", "CONVERGED_ABSOLUTE", "CONVERGED_RELATIVE", "MAX_IT", "NAN_OR_INF", "SINGULAR_NEWTON_MATRIX", "STAGNATION", "CYCLE", "USER_TEST", "SSStarReason", "SSSTAR_REASON_", NULL};

/* A Newton matrix whose estimated 1/cond is below this is treated as singular: its LU solution has no reliable digit */
#define SSSTAR_RCOND_MIN 1e-12
/* whole body: relative tolerance of the solves that put the free dofs in equilibrium before the first iteration */
#define SSSTAR_EQUILIBRIUM_RTOL 1e-4

/*
   gamma = 1/mean(diag K_CC) unless the user set it (section 6); the fixed-point baseline takes 1/(the largest sum
   |K_ij| of a contact row), which bounds 1/lambda_max(P) from below: a step short enough to converge. In the reduced
   use K_CC is P itself.
*/
static PetscErrorCode SNESSSStarComputeScaling(SNES snes)
{
  SNES_SSStar   *ss = (SNES_SSStar *)snes->data;
  SSStarContact *ct = &ss->contact;

  PetscFunctionBegin;
  if (ss->scaling_user > 0) {
    ss->scaling = ss->scaling_user;
    PetscFunctionReturn(0);
  }
  if (ss->method == SSSTAR_METHOD_FIXEDPOINT) {
    PetscCheck(ct->maxRowSum > 0, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_WRONG, "ssstar: the contact rows of the stiffness sum to %g, not positive; set -snes_ssstar_scaling", (double)ct->maxRowSum);
    ss->scaling = 1 / ct->maxRowSum;
    PetscFunctionReturn(0);
  }
  PetscCheck(ct->meanDiag > 0, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_WRONG, "ssstar: the mean diagonal entry of the stiffness at the contact dofs is %g, not positive; set -snes_ssstar_scaling", (double)ct->meanDiag);
  ss->scaling = 1 / ct->meanDiag;
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
  PetscCall(VecDestroy(&ss->d));
  PetscCall(VecDestroy(&ss->b));
  PetscCall(VecCreateMPI(PetscObjectComm((PetscObject)snes), 3 * n, PETSC_DETERMINE, &ss->d));
  PetscCall(VecDuplicate(ss->d, &ss->b));
  PetscFunctionReturn(0);
}

/* The vectors of the iteration, in the layout of the operator A (they change with it) */
static PetscErrorCode CreateWorkVectors(SNES snes)
{
  SNES_SSStar *ss = (SNES_SSStar *)snes->data;
  PetscInt     n = -1, m;
  PetscBool    fits;

  PetscFunctionBegin;
  PetscCall(MatGetLocalSize(ss->contact.A, &m, NULL));
  if (ss->u) PetscCall(VecGetLocalSize(ss->u, &n));
  fits = (PetscBool)(n == m); /* decided together: a rank may own no dof of either layout */
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &fits, 1, MPIU_BOOL, MPI_LAND, PetscObjectComm((PetscObject)snes)));
  if (fits) PetscFunctionReturn(0);
  PetscCall(VecDestroy(&ss->u));
  PetscCall(MatCreateVecs(ss->contact.A, &ss->u, NULL));
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

/* y = R x (R NULL: identity), x the entries of node i in a vector of the operator */
static void NodeRotate(const SSStarContact *ct, PetscInt i, const PetscScalar *a, PetscReal y[3])
{
  const PetscInt  *dof = &ct->layoutDofs[3 * i];
  const PetscReal *R   = ct->frames ? &ct->frames[9 * i] : NULL;

  for (PetscInt k = 0; k < 3; k++) y[k] = R ? R[3 * k] * PetscRealPart(a[dof[0]]) + R[3 * k + 1] * PetscRealPart(a[dof[1]]) + R[3 * k + 2] * PetscRealPart(a[dof[2]]) : PetscRealPart(a[dof[k]]);
}

/* v_i = R_i u_i + g_i e3: the iterate in node i's frame, with the gap */
static void NodeIterate(const SSStarContact *ct, PetscInt i, const PetscScalar *ua, PetscReal v[3])
{
  NodeRotate(ct, i, ua, v);
  if (ct->gap) v[2] += ct->gap[i];
}

/* c = A u - f */
PetscErrorCode SNESSSStarResidual(SNES snes, Vec u, Vec c)
{
  SSStarContact *ct = &((SNES_SSStar *)snes->data)->contact;

  PetscFunctionBegin;
  PetscCall(MatMult(ct->A, u, c));
  PetscCall(VecAXPY(c, -1.0, ct->f));
  PetscFunctionReturn(0);
}

/* ||u_C||: the norm of the contact dofs of u. The branch is the same on every rank: a rank may own no free dof */
static PetscErrorCode ContactNorm(SNES snes, Vec u, PetscReal *norm)
{
  SSStarContact     *ct = &((SNES_SSStar *)snes->data)->contact;
  const PetscScalar *ua;
  PetscReal          sum = 0;

  PetscFunctionBegin;
  if (ct->newtonType != SSSTAR_NEWTON_FULL) {
    PetscCall(VecNorm(u, NORM_2, norm));
    PetscFunctionReturn(0);
  }
  PetscCall(VecGetArrayRead(u, &ua));
  for (PetscInt k = 0; k < 3 * ct->nnodes; k++) sum += PetscRealPart(ua[ct->layoutDofs[k]] * ua[ct->layoutDofs[k]]);
  PetscCall(VecRestoreArrayRead(u, &ua));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &sum, 1, MPIU_REAL, MPIU_SUM, PetscObjectComm((PetscObject)snes)));
  *norm = PetscSqrtReal(sum);
  PetscFunctionReturn(0);
}

/*
   Section 1 on every local node of the iterate u with c = A u - f, in the node's frame, with the scaled
   c = gamma (A u - f) (section 6): z, d, b into ss->z, ss->d, ss->b, and ||z||. A free dof (whole body) has no
   contact law: z = -gamma c, the residual of its equilibrium in displacement units.
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
    const SSStarFriction fr  = ScaledFriction(ss, i);
    const PetscInt      *dof = &ct->layoutDofs[3 * i];
    PetscReal            v[3], cv[3], z[3];

    NodeIterate(ct, i, ua, v);
    NodeRotate(ct, i, ca, cv);
    for (PetscInt k = 0; k < 3; k++) cv[k] *= ss->scaling;
    SSStarApproximationStep(&fr, v, cv, z, &da[3 * i], &ba[3 * i]);
    for (PetscInt k = 0; k < 3; k++) za[dof[k]] = z[k];
  }
  for (PetscInt j = 0; j < ct->nfree; j++) za[ct->free[j]] = -ss->scaling * ca[ct->free[j]];
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
static PetscErrorCode SNESSSStarClassify(SNES snes)
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
  tol_b = ss->state_tol * PetscMax(ss->scaling * ss->fnorm_inf, norms[2]);
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
   Whole body: the tolerances of the next linear solve (inexact Newton). Its residual r (units of gamma^-1 y) moves
   the next ||z|| by about gamma ||r||: gamma ||r|| <= eta ||z|| (eta: see SNESSolve_SSStar), never below a tenth of
   the stopping threshold. The bound is on ||z||, not relative to the right-hand side: the eliminated known dofs
   make that large, and one CG iteration could meet a relative tolerance with a useless step. Once a full step
   left every node in its state, the problem is locally linear and one exact step ends it (as on the dense route):
   eta = 0, the floor alone.
*/
static PetscErrorCode SetLinearTolerances(SNES snes, PetscReal znorm, PetscReal rtol)
{
  SNES_SSStar *ss = (SNES_SSStar *)snes->data;
  PetscReal    unorm, threshold;

  PetscFunctionBegin;
  if (ss->contact.newtonType != SSSTAR_NEWTON_FULL) PetscFunctionReturn(0);
  PetscCall(ContactNorm(snes, ss->u, &unorm));
  threshold = PetscMax(snes->abstol, snes->rtol * PetscMax(unorm, ss->scale));
  PetscCall(SSStarNewtonSetTolerances(ss->newton, 0.0, PetscMax(rtol * znorm, 0.1 * threshold) / ss->scaling));
  PetscFunctionReturn(0);
}

/*
   Section 5 in the nodes' frames: S, T per node, y = (S + T) z (and y = z on the free dofs), then the Newton system
   for du. solved is false when its matrix is singular or, by the estimate of its condition, nearly so.

   regularized: the coupling phi om of the sliding (M1) rows of S dropped, i.e. the normal force in the linearized
   sliding law frozen at the iterate. Every row is then a row of gamma P, or a unit row, or a row of gamma P plus
   the PSD W of section 3 on the node's tangential dofs: after the unit rows the matrix is gamma P_FF + W_FF with
   P_FF a principal submatrix of the SPD P, nonsingular.
*/
static PetscErrorCode SNESSSStarNewtonStep(SNES snes, PetscReal znorm, PetscReal eta, PetscBool regularized, PetscBool *solved)
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
    const SSStarFriction fr  = ScaledFriction(ss, i);
    const PetscInt      *dof = &ct->layoutDofs[3 * i];
    PetscReal           *S = &ss->S[9 * i], *T = &ss->T[9 * i];

    SSStarReducedBlocks(ss->states[i], &fr, &da[3 * i], &ba[3 * i], S, T);
    if (regularized) S[2] = S[5] = 0.0;
    for (PetscInt r = 0; r < 3; r++) {
      ya[dof[r]] = 0;
      for (PetscInt k = 0; k < 3; k++) ya[dof[r]] += (S[3 * r + k] + T[3 * r + k]) * za[dof[k]];
    }
  }
  for (PetscInt j = 0; j < ct->nfree; j++) ya[ct->free[j]] = za[ct->free[j]];
  PetscCall(VecRestoreArrayWrite(ss->y, &ya));
  PetscCall(VecRestoreArrayRead(ss->b, &ba));
  PetscCall(VecRestoreArrayRead(ss->d, &da));
  PetscCall(VecRestoreArrayRead(ss->z, &za));
  PetscCall(SetLinearTolerances(snes, znorm, eta));
  PetscCall(SSStarNewtonSolve(ss->newton, ss->S, ss->T, ss->y, ss->dv, solved));
  if (*solved) {
    PetscReal rcond;

    PetscCall(SSStarNewtonGetConditionEstimate(ss->newton, &rcond));
    if (rcond >= 0 && rcond < SSSTAR_RCOND_MIN) *solved = PETSC_FALSE;
  }
  PetscCall(PetscLogEventEnd(SSSTAR_NewtonStep, snes, 0, 0, 0));
  PetscFunctionReturn(0);
}

/*
   Whole body: the Newton step of this iteration solved on to the floor tolerance (eta = 0), when its inexact solve
   stopped earlier: the damped steps and remedies then act on the step the dense route takes. refined: ss->dv changed.
*/
PetscErrorCode SNESSSStarRefineNewtonStep(SNES snes, PetscReal znorm, PetscBool *refined)
{
  SNES_SSStar *ss = (SNES_SSStar *)snes->data;

  PetscFunctionBegin;
  *refined = PETSC_FALSE;
  if (ss->contact.newtonType != SSSTAR_NEWTON_FULL) PetscFunctionReturn(0);
  PetscCall(SetLinearTolerances(snes, znorm, 0.0));
  PetscCall(SSStarNewtonRefine(ss->newton, ss->dv, refined));
  PetscFunctionReturn(0);
}

/*
   The fixed-point step u <- u + R^T z of the approximation step z at u (section 1; z is ss->z), with c = A u - f
   updated; on the whole body the free dofs follow the contact dofs into equilibrium (one linear solve).
*/
PetscErrorCode SNESSSStarFixedPointStep(SNES snes, Vec u, Vec c, PetscBool *solved)
{
  SNES_SSStar *ss = (SNES_SSStar *)snes->data;

  PetscFunctionBegin;
  PetscCall(SSStarNewtonSolveKnown(ss->newton, ss->z, ss->dv, solved));
  if (!*solved) PetscFunctionReturn(0);
  PetscCall(VecAXPY(u, 1.0, ss->dv));
  PetscCall(SNESSSStarResidual(snes, u, c));
  PetscFunctionReturn(0);
}

/*
   Whole body: the free dofs of u put in equilibrium with its contact dofs (K u - b = 0 there), and the load reduced
   to the contact dofs, f = -(K u0 - b)_C with u0 in equilibrium and u0_C = 0: what a reduction would give. Into
   ss->scale, ss->fnorm_inf; u and c = K u - b on return.
*/
static PetscErrorCode Equilibrate(SNES snes)
{
  SNES_SSStar       *ss = (SNES_SSStar *)snes->data;
  SSStarContact     *ct = &ss->contact;
  PetscReal          sums[2] = {0, 0}, unorm;
  const PetscScalar *ca;
  PetscBool          solved;
  Vec                uC = ss->ut;

  PetscFunctionBegin;
  PetscCall(ContactNorm(snes, ss->u, &unorm));
  PetscCall(VecCopy(ss->u, uC));
  PetscCall(VecZeroEntries(ss->u));
  PetscCall(SNESSSStarResidual(snes, ss->u, ss->c));
  for (PetscInt pass = 0; pass < (unorm > 0 ? 2 : 1); pass++) {
    PetscScalar *za;

    /* pass 0: from u = 0; pass 1: to the given contact displacement. The known step moves the contact dofs by y */
    PetscCall(VecGetArrayWrite(ss->z, &za));
    if (pass == 0) {
      for (PetscInt k = 0; k < 3 * ct->nnodes; k++) za[ct->layoutDofs[k]] = 0;
    } else {
      const PetscScalar *ga;

      PetscCall(VecGetArrayRead(uC, &ga));
      for (PetscInt i = 0; i < ct->nnodes; i++) {
        PetscReal y[3];

        NodeRotate(ct, i, ga, y);
        for (PetscInt k = 0; k < 3; k++) za[ct->layoutDofs[3 * i + k]] = y[k];
      }
      PetscCall(VecRestoreArrayRead(uC, &ga));
    }
    PetscCall(VecRestoreArrayWrite(ss->z, &za));
    PetscCall(VecGetArrayRead(ss->c, &ca));
    PetscCall(VecGetArrayWrite(ss->z, &za));
    for (PetscInt j = 0; j < ct->nfree; j++) za[ct->free[j]] = -ss->scaling * ca[ct->free[j]];
    PetscCall(VecRestoreArrayWrite(ss->z, &za));
    PetscCall(VecRestoreArrayRead(ss->c, &ca));
    PetscCall(SSStarNewtonSetTolerances(ss->newton, SSSTAR_EQUILIBRIUM_RTOL, 0.0));
    PetscCall(SNESSSStarFixedPointStep(snes, ss->u, ss->c, &solved));
    PetscCheck(solved, PetscObjectComm((PetscObject)snes), PETSC_ERR_NOT_CONVERGED, "ssstar: the linear solve with K, the contact dofs held, failed (is the body held? Dirichlet conditions; see -ksp_converged_reason)");
    if (pass > 0) continue;
    /* f = -(K u0 - b)_C, in the global frame */
    PetscCall(VecGetArrayRead(ss->c, &ca));
    for (PetscInt k = 0; k < 3 * ct->nnodes; k++) {
      const PetscReal fk = -PetscRealPart(ca[ct->layoutDofs[k]]);

      sums[0] += fk * fk;
      sums[1] = PetscMax(sums[1], PetscAbsReal(fk));
    }
    PetscCall(VecRestoreArrayRead(ss->c, &ca));
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &sums[0], 1, MPIU_REAL, MPIU_SUM, PetscObjectComm((PetscObject)snes)));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &sums[1], 1, MPIU_REAL, MPIU_MAX, PetscObjectComm((PetscObject)snes)));
  ss->scale     = ss->scaling * PetscSqrtReal(sums[0]);
  ss->fnorm_inf = sums[1];
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
static PetscErrorCode NodeOfRow(SSStarContact *ct, PetscInt row, char buf[], size_t len)
{
  PetscFunctionBegin;
  buf[0] = 0;
  if (ct->newtonType != SSSTAR_NEWTON_FULL) PetscCall(PetscSNPrintf(buf, len, " (node %" PetscInt_FMT " of the solver's order)", row / 3));
  PetscFunctionReturn(0);
}

/* Refuses what no iteration can solve: NaN or Inf in A, f or the initial guess, tolerances that are not numbers */
static PetscErrorCode CheckProblem(SNES snes)
{
  SNES_SSStar   *ss    = (SNES_SSStar *)snes->data;
  SSStarContact *ct    = &ss->contact;
  MPI_Comm       comm  = PetscObjectComm((PetscObject)snes);
  PetscBool      whole = (PetscBool)(ct->newtonType == SSSTAR_NEWTON_FULL);
  const char    *dof   = whole ? "dof" : "contact dof";
  char           node[64];
  Vec            rowsum;
  PetscInt       first;

  PetscFunctionBegin;
  PetscCheck(snes->rtol >= 0 && snes->rtol < 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "-snes_rtol %g: must be in [0, 1)", (double)snes->rtol);
  PetscCheck(snes->abstol >= 0 && !PetscIsInfOrNanReal(snes->abstol), comm, PETSC_ERR_ARG_OUTOFRANGE, "-snes_atol %g: must be a number >= 0", (double)snes->abstol);
  PetscCall(VecDuplicate(ct->f, &rowsum)); /* A 1: a row with a NaN or an Inf sums to NaN or Inf */
  PetscCall(VecSet(ss->ut, 1.0));
  PetscCall(MatMult(ct->A, ss->ut, rowsum));
  PetscCall(FirstNonFinite(rowsum, &first));
  PetscCall(VecDestroy(&rowsum));
  PetscCall(NodeOfRow(ct, first, node, sizeof(node)));
  PetscCheck(first < 0, comm, PETSC_ERR_FP, "ssstar: the %s has NaN or Inf entries in row %" PetscInt_FMT "%s: the stiffness K is not finite", whole ? "stiffness K" : "reduced stiffness P", first, node);
  PetscCall(FirstNonFinite(ct->f, &first));
  PetscCall(NodeOfRow(ct, first, node, sizeof(node)));
  PetscCheck(first < 0, comm, PETSC_ERR_FP, "ssstar: the %s is NaN or Inf at %s %" PetscInt_FMT "%s: the load b is not finite", whole ? "load b" : "reduced load f", dof, first, node);
  PetscCall(FirstNonFinite(ss->u, &first));
  PetscCall(NodeOfRow(ct, first, node, sizeof(node)));
  PetscCheck(first < 0, comm, PETSC_ERR_FP, "ssstar: the initial guess is NaN or Inf at %s %" PetscInt_FMT "%s", dof, first, node);
  PetscFunctionReturn(0);
}

/* The problem of this solve: A, f, gamma, the Newton step for A, the displacement scale, the first iterate */
static PetscErrorCode SetUpSolve(SNES snes)
{
  SNES_SSStar        *ss = (SNES_SSStar *)snes->data;
  SSStarContact      *ct = &ss->contact;
  SSStarContactLayout layout;

  PetscFunctionBegin;
  PetscCall(SSStarContactSetUpProblem(snes, ct));
  PetscCall(CreateWorkVectors(snes));
  PetscCall(SNESSSStarComputeScaling(snes));
  PetscCall(SSStarContactGetLayout(ct, &layout));
  PetscCall(SSStarNewtonSetOperator(ss->newton, ct->newtonType, ct->A, ss->scaling, &layout));
  PetscCall(SSStarContactGetInitialGuess(ct, snes->vec_sol, ss->u));
  PetscCall(CheckProblem(snes));
  if (ct->newtonType == SSSTAR_NEWTON_FULL) PetscCall(Equilibrate(snes));
  else {
    PetscCall(VecNorm(ct->f, NORM_2, &ss->scale));
    PetscCall(VecNorm(ct->f, NORM_INFINITY, &ss->fnorm_inf));
    ss->scale *= ss->scaling;
    PetscCall(SNESSSStarResidual(snes, ss->u, ss->c));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSolve_SSStar(SNES snes)
{
  SNES_SSStar   *ss = (SNES_SSStar *)snes->data;
  SSStarContact *ct = &ss->contact;
  PetscReal      znorm, unorm, dunorm = 0, z0 = 0;
  PetscBool      solved;

  PetscFunctionBegin;
  snes->reason = SNES_CONVERGED_ITERATING;
  ss->reason   = SSSTAR_REASON_ITERATING;
  PetscCall(PetscObjectSAWsTakeAccess((PetscObject)snes));
  snes->iter = 0;
  snes->norm = 0;
  PetscCall(PetscObjectSAWsGrantAccess((PetscObject)snes));

  PetscCall(SetUpSolve(snes));
  PetscCall(SSStarGlobalizationBegin(snes));

  for (PetscInt k = 0;; k++) {
    SSStarReason stop = SSSTAR_REASON_ITERATING;

    PetscCall(SNESSSStarApproximationStep(snes, ss->u, ss->c, &znorm));
    PetscCall(ContactNorm(snes, ss->u, &unorm));
    PetscCall(SNESSSStarClassify(snes));
    if (ss->method == SSSTAR_METHOD_NEWTON) PetscCall(SSStarGlobalizationDetect(snes, k, znorm));
    PetscCall(PetscObjectSAWsTakeAccess((PetscObject)snes));
    snes->iter = k;
    snes->norm = znorm;
    if (k == 0) snes->ttol = znorm * snes->rtol; /* for SNESConvergedDefault(), if the user chose it */
    PetscCall(PetscObjectSAWsGrantAccess((PetscObject)snes));
    if (k == 0) z0 = znorm;
    PetscCall(SNESLogConvergenceHistory(snes, znorm, snes->linear_its));
    PetscCall(SNESMonitor(snes, k, znorm));
    ss->tolerance = PetscMax(snes->abstol, snes->rtol * PetscMax(unorm, ss->scale));
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
      PetscCall(SetLinearTolerances(snes, znorm, PetscMin(ss->etaMax, znorm / z0)));
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
         0.1 ||z|| on scenes/tilted_roller.opts with the shear reversed. Once the states repeat after a full step, the step is likely the
         last one: exact too. (||z||/||z_0||)^2 saves no Newton iteration at level 16 and costs 30 % more Krylov
         iterations (186 against 144) */
      PetscInt remedies = 0;

      for (PetscInt r = 0; r < SSSTAR_NUM_REMEDIES; r++) remedies += ss->glob.counts[r];
      const PetscReal eta = remedies || (ss->glob.changed == 0 && ss->glob.shownAlpha == 1) ? 0.0 : PetscMin(ss->etaMax, znorm / z0);

      /* a singular Newton matrix: the regularized step, else fixed-point iterations, else stop */
      PetscCall(SNESSSStarNewtonStep(snes, znorm, eta, PETSC_FALSE, &solved));
      if (!solved && ss->glob.on && ct->lawCounts[SSSTAR_FRICTION_COULOMB] > 0) {
        PetscCall(SSStarGlobalizationRecord(&ss->glob, SSSTAR_REMEDY_REGULARIZED));
        PetscCall(SNESSSStarNewtonStep(snes, znorm, eta, PETSC_TRUE, &solved));
      }
      if (!solved) {
        PetscBool improved = PETSC_FALSE;

        if (ss->glob.on) PetscCall(SSStarGlobalizationFixedPoint(snes, znorm, &improved));
        if (improved) continue;
        stop = SSSTAR_REASON_SINGULAR_NEWTON;
      } else {
        PetscCall(ContactNorm(snes, ss->dv, &dunorm));
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
  /* the last iterate and its c = A u - f, the contact force: the SNES vector gets the whole u, F(u) its residual */
  PetscCall(SNESSSStarResidual(snes, ss->u, ss->c));
  PetscCall(SSStarContactSetSolution(ct, ss->u, ss->c, snes->vec_sol));
  PetscCall(SNESComputeFunction(snes, snes->vec_sol, snes->vec_func));
  PetscFunctionReturn(0);
}

/*@C
   SNESConvergedSSStar - the default convergence test of ssstar: converged when ||z|| <= atol (CONVERGED_FNORM_ABS)
   or ||z|| <= rtol max(||u||, ||gamma f||) (CONVERGED_FNORM_RELATIVE), with z the approximation step, gamma f the
   reduced load in displacement units (docs/derivation.md section 6) and atol, rtol from SNESSetTolerances()

   Collective

   Input Parameters:
+  snes  - the SNES
.  it    - iteration
.  xnorm - max(||u||, ||gamma f||): the displacement scale of the problem
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
  PetscCall(VecDestroy(&ss->d));
  PetscCall(VecDestroy(&ss->b));
  PetscCall(SSStarGlobalizationDestroy(&ss->glob));
  PetscFunctionReturn(0);
}

#define SSSTAR_COMPOSED(F) "SNESSSStar" #F "_C"
static const char *const ComposedNames[] = {SSSTAR_COMPOSED(SetContactNodes), SSSTAR_COMPOSED(SetContactOperator), SSSTAR_COMPOSED(SetFrictionLaw), SSSTAR_COMPOSED(GetFrictionLaw), SSSTAR_COMPOSED(SetFriction), SSSTAR_COMPOSED(GetFriction), SSSTAR_COMPOSED(SetFrictionCoefficients), SSSTAR_COMPOSED(SetSlipBounds), SSSTAR_COMPOSED(SetNodeFrictionLaws), SSSTAR_COMPOSED(SetReductionType), SSSTAR_COMPOSED(GetReductionType), SSSTAR_COMPOSED(SetPCReuse), SSSTAR_COMPOSED(SetKSPRtolMax), SSSTAR_COMPOSED(SetMemoryLimit), SSSTAR_COMPOSED(SetScaling), SSSTAR_COMPOSED(GetScaling), SSSTAR_COMPOSED(SetStateTolerance), SSSTAR_COMPOSED(GetStates), SSSTAR_COMPOSED(GetReason), SSSTAR_COMPOSED(GetTolerance), SSSTAR_COMPOSED(GetContactNodes), SSSTAR_COMPOSED(GetNodeFriction), SSSTAR_COMPOSED(GetReducedProblem), SSSTAR_COMPOSED(SetLUReuse), SSSTAR_COMPOSED(GetNewtonStepCounts), SSSTAR_COMPOSED(GetConditionEstimate), SSSTAR_COMPOSED(SetLUThreads), SSSTAR_COMPOSED(SetGlobalization), SSSTAR_COMPOSED(GetRemedyCounts), SSSTAR_COMPOSED(SetMethod), SSSTAR_COMPOSED(GetMethod)};

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
  PetscCall(PetscOptionsEnum("-snes_ssstar_reduction", "Whole-body use: K reduced to the contact dofs (direct, mumps, explicit), or none (the whole body, P never formed), or auto", "SNESSSStarSetReductionType", SSStarReductionTypes, (PetscEnum)ct->reductionType, (PetscEnum *)&rtype, &set));
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
  PetscCall(SSStarNewtonGetPCReuse(ss->newton, &value));
  PetscCall(PetscOptionsReal("-snes_ssstar_pc_reuse", "Whole body: keep the multigrid of an earlier Newton step while at most this fraction of the nodes changed their known rows since it (negative: a new one every step)", "SNESSSStarSetPCReuse", value, &value, &set));
  if (set) PetscCall(SNESSSStarSetPCReuse(snes, value));
  PetscCall(PetscOptionsReal("-snes_ssstar_ksp_rtol_max", "Whole body: the loosest relative tolerance of a Newton step's linear solve (it tightens with ||z||/||z_0||)", "SNESSSStarSetKSPRtolMax", ss->etaMax, &value, &set));
  if (set) PetscCall(SNESSSStarSetKSPRtolMax(snes, value));
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
  else if (ss->method == SSSTAR_METHOD_FIXEDPOINT) PetscCall(PetscViewerASCIIPrintf(viewer, "  approximation-step scaling gamma = 1/(largest contact row sum of K)%s%g\n", ss->scaling > 0 ? " = " : "", ss->scaling > 0 ? (double)ss->scaling : 0.0));
  else PetscCall(PetscViewerASCIIPrintf(viewer, "  approximation-step scaling gamma = 1/mean(diag K_CC)%s%g\n", ss->scaling > 0 ? " = " : "", ss->scaling > 0 ? (double)ss->scaling : 0.0));
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
   SNESSSStarMonitorStates - prints, at every iteration, how many contact nodes are in each state of Table 1, with
   the remedies that led to the iterate

   Collective

   Input Parameters:
+  snes  - the SNES
.  its   - the iteration
.  znorm - ||z||
-  vf    - the viewer and its format

   Options Database Key:
.  -snes_ssstar_monitor_states - activates it

   Level: intermediate

.seealso: `SNESMonitorSet()`, `SNESSSStarGetStates()`
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
    PetscCall(MatDestroy(&ct->A)); /* the next solve sets the problem up again */
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarGetReductionType_SSStar(SNES snes, SSStarReductionType *type)
{
  SSStarContact *ct = &((SNES_SSStar *)snes->data)->contact;

  PetscFunctionBegin;
  *type = ct->reductionType;
  if (ct->reduction) PetscCall(SSStarReductionGetType(ct->reduction, type));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarSetPCReuse_SSStar(SNES snes, PetscReal fraction)
{
  PetscFunctionBegin;
  PetscCheck(fraction <= 1 && !PetscIsInfOrNanReal(fraction), PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_OUTOFRANGE, "-snes_ssstar_pc_reuse %g must be at most 1 (negative: never)", (double)fraction);
  PetscCall(SSStarNewtonSetPCReuse(((SNES_SSStar *)snes->data)->newton, fraction));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarSetKSPRtolMax_SSStar(SNES snes, PetscReal rtol)
{
  PetscFunctionBegin;
  PetscCheck(rtol > 0 && rtol < 1, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_OUTOFRANGE, "-snes_ssstar_ksp_rtol_max %g must be in (0, 1)", (double)rtol);
  ((SNES_SSStar *)snes->data)->etaMax = rtol;
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

static PetscErrorCode SNESSSStarGetContactNodes_SSStar(SNES snes, PetscInt *n, IS *dofs, Vec *normals, Vec *gaps)
{
  SSStarContact *ct = &((SNES_SSStar *)snes->data)->contact;
  PetscInt       size;

  PetscFunctionBegin;
  if (n) {
    if (ct->dofs) {
      PetscCall(ISGetLocalSize(ct->dofs, &size));
      *n = size / 3;
    } else if (snes->vec_func) {
      PetscCall(VecGetLocalSize(snes->vec_func, &size));
      *n = size / 3;
    }
  }
  if (dofs) *dofs = ct->dofs;
  if (normals) *normals = ct->normals;
  if (gaps) *gaps = ct->gaps;
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarGetTolerance_SSStar(SNES snes, PetscReal *tol)
{
  PetscFunctionBegin;
  *tol = ((SNES_SSStar *)snes->data)->tolerance;
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarGetNodeFriction_SSStar(SNES snes, PetscInt n, SSStarFrictionLaw laws[], PetscReal phi[], PetscReal bounds[])
{
  SSStarContact *ct = &((SNES_SSStar *)snes->data)->contact;

  PetscFunctionBegin;
  PetscCheck(snes->vec_func, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_WRONGSTATE, "SNESSSStarGetNodeFriction: call SNESSetUp() or SNESSolve() first");
  PetscCall(SSStarContactSetUp(snes, ct));
  PetscCheck(n == ct->nnodes, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "SNESSSStarGetNodeFriction: arrays of %" PetscInt_FMT " entries for the %" PetscInt_FMT " contact nodes of this rank", n, ct->nnodes);
  for (PetscInt i = 0; i < ct->nnodes; i++) {
    const PetscInt        j  = ct->order[i]; /* the user's node */
    const SSStarFriction *fr = &ct->nodeFriction[i];

    if (laws) laws[j] = fr->law;
    if (phi) phi[j] = fr->phi;
    if (bounds) bounds[j] = fr->bound;
  }
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
  PetscCheck(ct->A, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_WRONGSTATE, "SNESSSStarGetReducedProblem: no reduced problem before SNESSolve()");
  PetscCheck(ct->newtonType != SSSTAR_NEWTON_FULL, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_WRONGSTATE, "SNESSSStarGetReducedProblem: the last solve ran on the whole body (reduction none): no P was formed");
  if (P) *P = ct->A;
  if (f) *f = ct->f;
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
.  -snes_ssstar_reduction <auto> - whole-body use: K reduced to the contact dofs (direct, mumps, explicit), none (the Newton step on the whole body, P never formed) or auto (direct on small problems, none on large ones)
.  -snes_ssstar_memory_limit <0> - GB per rank the reduction may plan for (0: MemAvailable of the node per rank)
.  -snes_ssstar_scaling <0> - scaling gamma of the approximation step (0: 1/mean(diag K_CC), the contact block of K)
.  -snes_ssstar_method <newton> - newton (semismooth*) or fixedpoint (the first-order baseline u <- u + z)
.  -snes_ssstar_state_tol <1e-13> - relative tolerance of the state classification
.  -snes_ssstar_monitor_states - print the number of nodes per state at every iteration, and the remedies
.  -snes_ssstar_globalization <true> - damped steps on ||z|| and remedies; false: the plain iteration
.  -snes_ssstar_damping_min <0.015625> - smallest damping factor of the line search
.  -snes_ssstar_stagnation_its <20> - stop after this many iterations without a smaller ||z||
.  -snes_ssstar_lu_threads <1> - on several ranks, rank 0's BLAS threads for the LU of the Newton matrix (0: the cores it may run on)
.  -snes_ssstar_lu_reuse <0> - dense P: solve a Newton step by GMRES on the last LU while at most this fraction of the nodes changed their known rows since it (0: only when none changed; negative: a fresh LU at every step); -snes_ssstar_newton_ksp_* set that GMRES
.  -snes_ssstar_pc_reuse <0.3> - whole body: keep the multigrid of an earlier Newton step while at most this fraction of the nodes changed their known rows (negative: a new one every step)
.  -snes_ssstar_ksp_rtol_max <0.1> - whole body: the loosest relative tolerance of a Newton step's linear solve; it tightens as min(this, ||z||/||z_0||); once a remedy acted, and for a step whose full step fails, the floor (a tenth of the stopping threshold)
.  -ksp_type, -pc_type, -ksp_rtol, ... - whole body: the linear solver of the Newton steps (default CG or GMRES with PCGAMG; -ksp_rtol fixes the tolerance)
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
  ss->contact.reductionType = SSSTAR_REDUCTION_AUTO;
  ss->etaMax                = 0.1;
  ss->contact.built         = -1;
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

  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(SetContactNodes), SNESSSStarSetContactNodes_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(SetContactOperator), SNESSSStarSetContactOperator_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(SetFrictionLaw), SNESSSStarSetFrictionLaw_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(GetFrictionLaw), SNESSSStarGetFrictionLaw_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(SetFriction), SNESSSStarSetFriction_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(GetFriction), SNESSSStarGetFriction_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(SetFrictionCoefficients), SNESSSStarSetFrictionCoefficients_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(SetSlipBounds), SNESSSStarSetSlipBounds_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(SetNodeFrictionLaws), SNESSSStarSetNodeFrictionLaws_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(SetReductionType), SNESSSStarSetReductionType_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(GetReductionType), SNESSSStarGetReductionType_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(SetPCReuse), SNESSSStarSetPCReuse_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(SetKSPRtolMax), SNESSSStarSetKSPRtolMax_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(SetMemoryLimit), SNESSSStarSetMemoryLimit_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(SetScaling), SNESSSStarSetScaling_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(GetScaling), SNESSSStarGetScaling_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(SetStateTolerance), SNESSSStarSetStateTolerance_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(SetMethod), SNESSSStarSetMethod_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(GetMethod), SNESSSStarGetMethod_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(GetStates), SNESSSStarGetStates_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(GetReason), SNESSSStarGetReason_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(GetTolerance), SNESSSStarGetTolerance_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(GetContactNodes), SNESSSStarGetContactNodes_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(GetNodeFriction), SNESSSStarGetNodeFriction_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(GetReducedProblem), SNESSSStarGetReducedProblem_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(SetGlobalization), SNESSSStarSetGlobalization_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(GetRemedyCounts), SNESSSStarGetRemedyCounts_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(SetLUReuse), SNESSSStarSetLUReuse_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(GetNewtonStepCounts), SNESSSStarGetNewtonStepCounts_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(GetConditionEstimate), SNESSSStarGetConditionEstimate_SSStar));
  PetscCall(PetscObjectComposeFunction((PetscObject)snes, SSSTAR_COMPOSED(SetLUThreads), SNESSSStarSetLUThreads_SSStar));
  PetscFunctionReturn(0);
}
