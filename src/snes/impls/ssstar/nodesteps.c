/*
   The per-node work of an iteration of the SNES type "ssstar" on any iterate (u, c = A u - f), in the nodes' frames:
   the approximation step, the classification and the Newton step's right-hand side and blocks (docs/derivation.md
   sections 1, 2, 5), the fixed-point step; used by the iteration (ssstar.c) and the globalization (globalization.c).
*/
#include "ssstarimpl.h"
#include "laws/lawimpl.h"

/* A Newton matrix whose estimated 1/cond is below this is treated as singular: its LU solution has no reliable digit */
#define SSSTAR_RCOND_MIN 1e-12

/* The scaled friction of node i: the kernels see gamma c (section 6), so a force of the law (Tresca's bound) too */
SSStarFriction SNESSSStarScaledFriction(SNES_SSStar *ss, PetscInt i)
{
  SSStarFriction fr = ss->contact.nodeFriction[i];

  for (PetscInt p = 0; p < fr.law->nparams; p++)
    if (fr.law->params[p].kind == SSSTAR_LAW_FORCE) fr.value[SSStarLawParameterOffset(fr.law, p)] *= ss->scaling;
  return fr;
}

/* y = R x (R NULL: identity), x the entries of node i in a vector of the operator */
void SNESSSStarNodeRotate(const SSStarContact *ct, const SSStarProblem *pb, PetscInt i, const PetscScalar *a, PetscReal y[3])
{
  const PetscInt  *dof = &pb->layoutDofs[3 * i];
  const PetscReal *R   = ct->frames ? &ct->frames[9 * i] : NULL;

  for (PetscInt k = 0; k < 3; k++) y[k] = R ? R[3 * k] * PetscRealPart(a[dof[0]]) + R[3 * k + 1] * PetscRealPart(a[dof[1]]) + R[3 * k + 2] * PetscRealPart(a[dof[2]]) : PetscRealPart(a[dof[k]]);
}

/* v_i = R_i u_i + o_i: the iterate in node i's frame, with its offset (docs/derivation.md (10.5)), o_i = g_i e3 unless
   a load path's step set the offsets */
void SNESSSStarNodeIterate(const SSStarContact *ct, const SSStarProblem *pb, PetscInt i, const PetscScalar *ua, PetscReal v[3])
{
  SNESSSStarNodeRotate(ct, pb, i, ua, v);
  if (ct->offset)
    for (PetscInt k = 0; k < 3; k++) v[k] += ct->offset[3 * i + k];
  else if (ct->gap) v[2] += ct->gap[i];
}

/* c = A u - f */
PetscErrorCode SNESSSStarResidual(SNES snes, Vec u, Vec c)
{
  SSStarProblem *pb = &((SNES_SSStar *)snes->data)->problem;

  PetscFunctionBegin;
  PetscCall(MatMult(pb->A, u, c));
  PetscCall(VecAXPY(c, -1.0, pb->f));
  PetscFunctionReturn(0);
}

/* ||u_C||: the norm of the contact dofs of u */
PetscErrorCode SNESSSStarContactNorm(SNES snes, Vec u, PetscReal *norm)
{
  SSStarContact     *ct = &((SNES_SSStar *)snes->data)->contact;
  SSStarProblem     *pb = &((SNES_SSStar *)snes->data)->problem;
  const PetscScalar *ua;
  PetscReal          sum = 0;

  PetscFunctionBegin;
  if (!pb->wholeBody) {
    PetscCall(VecNorm(u, NORM_2, norm));
    PetscFunctionReturn(0);
  }
  PetscCall(VecGetArrayRead(u, &ua));
  for (PetscInt k = 0; k < 3 * ct->nnodes; k++) sum += PetscRealPart(ua[pb->layoutDofs[k]] * ua[pb->layoutDofs[k]]);
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
  SSStarProblem     *pb = &ss->problem;
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
    const SSStarFriction fr  = SNESSSStarScaledFriction(ss, i);
    const PetscInt      *dof = &pb->layoutDofs[3 * i];
    PetscReal            v[3], cv[3], z[3];

    SNESSSStarNodeIterate(ct, pb, i, ua, v);
    SNESSSStarNodeRotate(ct, pb, i, ca, cv);
    for (PetscInt k = 0; k < 3; k++) cv[k] *= ss->scaling;
    SSStarApproximationStep(&fr, v, cv, z, &da[3 * i], &ba[3 * i]);
    for (PetscInt k = 0; k < 3; k++) za[dof[k]] = z[k];
  }
  for (PetscInt j = 0; j < pb->nfree; j++) za[pb->free[j]] = -ss->scaling * ca[pb->free[j]];
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
PetscErrorCode SNESSSStarClassify(SNES snes)
{
  SNES_SSStar       *ss = (SNES_SSStar *)snes->data;
  SSStarContact     *ct = &ss->contact;
  SSStarProblem     *pb = &ss->problem;
  const PetscScalar *ua, *da, *ba;
  PetscReal          norms[3] = {0, 0, 0}, tol_d, tol_b;

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(ss->u, &ua));
  PetscCall(VecGetArrayRead(ss->d, &da));
  PetscCall(VecGetArrayRead(ss->b, &ba));
  for (PetscInt i = 0; i < ct->nnodes; i++) {
    PetscReal v[3];

    SNESSSStarNodeIterate(ct, pb, i, ua, v);
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
    const SSStarFriction fr = SNESSSStarScaledFriction(ss, i);

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
   Whole body: the floor of a linear solve's residual r (units of gamma^-1 y, as the Newton steps'): a fraction of the
   stopping threshold, a tenth of it
*/
PetscErrorCode SNESSSStarLinearFloor(SNES snes, PetscReal *floor)
{
  SNES_SSStar *ss = (SNES_SSStar *)snes->data;
  PetscReal    unorm;

  PetscFunctionBegin;
  PetscCall(SNESSSStarContactNorm(snes, ss->u, &unorm));
  *floor = 0.1 * PetscMax(snes->abstol, snes->rtol * PetscMax(PetscMax(unorm, ss->scale), ss->offsetScale)) / ss->scaling;
  PetscFunctionReturn(0);
}

/*
   Whole body: the tolerances of the next linear solve (inexact Newton; the steps on P are exact). Its residual r moves
   the next ||z|| by about gamma ||r||: gamma ||r|| <= eta ||z|| (eta: see SNESSolve_SSStar), never below the floor.
   The bound is on ||z||, not relative to the right-hand side: the eliminated known dofs make that large, and one CG
   iteration could meet a relative tolerance with a useless step. Once a full step left every node in its state, the
   problem is locally linear and one exact step ends it (as on the dense route): eta = 0, the floor alone.
*/
PetscErrorCode SNESSSStarSetLinearTolerances(SNES snes, PetscReal znorm, PetscReal rtol)
{
  SNES_SSStar *ss = (SNES_SSStar *)snes->data;
  PetscReal    floor;

  PetscFunctionBegin;
  if (!ss->problem.wholeBody) PetscFunctionReturn(0); /* the steps on P are solved exactly (dense or sparse LU) */
  PetscCall(SNESSSStarLinearFloor(snes, &floor));
  PetscCall(SSStarNewtonSetTolerances(ss->newton, 0.0, PetscMax(rtol * znorm / ss->scaling, floor)));
  PetscFunctionReturn(0);
}

/*
   Section 5 in the nodes' frames: S, T per node, y = (S + T) z (and y = z on the free dofs), then the Newton system
   for du. solved is false when its matrix is singular or, by the estimate of its condition, nearly so.

   regularized: the coupling k (phi om for Coulomb) of the sliding (M1) rows of S dropped, i.e. the normal force in the
   linearized sliding law frozen at the iterate (the laws whose friction depends on the normal force have one). Every row is then a row of gamma P, or a unit row, or a row of gamma P plus
   the PSD W of section 3 on the node's tangential dofs: after the unit rows the matrix is gamma P_FF + W_FF with
   P_FF a principal submatrix of the SPD P, nonsingular.
*/
PetscErrorCode SNESSSStarNewtonStep(SNES snes, PetscReal znorm, PetscReal eta, PetscBool regularized, PetscBool *solved)
{
  SNES_SSStar       *ss = (SNES_SSStar *)snes->data;
  SSStarContact     *ct = &ss->contact;
  SSStarProblem     *pb = &ss->problem;
  const PetscScalar *za, *da, *ba;
  PetscScalar       *ya;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(SSSTAR_NewtonStep, snes, 0, 0, 0));
  PetscCall(VecGetArrayRead(ss->z, &za));
  PetscCall(VecGetArrayRead(ss->d, &da));
  PetscCall(VecGetArrayRead(ss->b, &ba));
  PetscCall(VecGetArrayWrite(ss->y, &ya));
  for (PetscInt i = 0; i < ct->nnodes; i++) {
    const SSStarFriction fr  = SNESSSStarScaledFriction(ss, i);
    const PetscInt      *dof = &pb->layoutDofs[3 * i];
    PetscReal           *S = &ss->S[9 * i], *T = &ss->T[9 * i];

    SSStarReducedBlocks(ss->states[i], &fr, &da[3 * i], &ba[3 * i], S, T);
    if (regularized) S[2] = S[5] = 0.0;
    for (PetscInt r = 0; r < 3; r++) {
      ya[dof[r]] = 0;
      for (PetscInt k = 0; k < 3; k++) ya[dof[r]] += (S[3 * r + k] + T[3 * r + k]) * za[dof[k]];
    }
  }
  for (PetscInt j = 0; j < pb->nfree; j++) ya[pb->free[j]] = za[pb->free[j]];
  PetscCall(VecRestoreArrayWrite(ss->y, &ya));
  PetscCall(VecRestoreArrayRead(ss->b, &ba));
  PetscCall(VecRestoreArrayRead(ss->d, &da));
  PetscCall(VecRestoreArrayRead(ss->z, &za));
  PetscCall(SNESSSStarSetLinearTolerances(snes, znorm, eta));
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
  if (!ss->problem.wholeBody) PetscFunctionReturn(0);
  PetscCall(SNESSSStarSetLinearTolerances(snes, znorm, 0.0));
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

