/*
   The per-node work of an iteration of the SNES type "ssstar" on any iterate (u, c = A u - f), in the nodes' frames:
   the approximation step, the classification and the Newton step's right-hand side and blocks (docs/derivation.md
   sections 1, 2, 5), the fixed-point step; used by the iteration (ssstar.c) and the globalization (globalization.c).
*/
#include "ssstarimpl.h"
#include "laws/lawimpl.h"

/* A Newton matrix whose estimated 1/cond is below this is treated as singular: its LU solution has no reliable digit */
#define SSSTAR_RCOND_MIN 1e-12

/* The friction of node i for the kernels at the scaling gamma: they see gamma c (section 6), so a force of the law
   (Tresca's bound) too */
SSStarFriction SNESSSStarScaledFriction(SNES_SSStar *ss, PetscInt i, PetscReal gamma)
{
  SSStarFriction fr = ss->contact.nodeFriction[i];

  for (PetscInt p = 0; p < fr.law->nparams; p++)
    if (fr.law->params[p].kind == SSSTAR_LAW_FORCE) fr.value[SSStarLawParameterOffset(fr.law, p)] *= gamma;
  return fr;
}

/* y = R x (R NULL: identity), x the entries of node i in a vector of the stiffness A */
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

/* c = A u - f, or from F itself for a residual treated as nonlinear (problem.c, docs/derivation.md section 17) */
PetscErrorCode SNESSSStarResidual(SNES snes, Vec u, Vec c)
{
  SSStarProblem *pb = &((SNES_SSStar *)snes->data)->problem;

  PetscFunctionBegin;
  if (pb->nonlinear) {
    PetscCall(SSStarProblemFunctionResidual(snes, u, c));
    PetscFunctionReturn(0);
  }
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
    const SSStarFriction fr  = SNESSSStarScaledFriction(ss, i, ss->scaling);
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

/*
   The law residual of the iterate u (c = A u - f) as the output writes it (docs/derivation.md section 12): every point's
   relative displacement w_i = d_i v_i (the file's gap and slip, its increment on a load path) and force r_i = R_i c_i
   (the file's reaction) lie within rho U and rho F of a pair (w*, r*) that satisfies the law exactly, and the free
   dofs are in equilibrium to rho F, with

     U = max(|w|_inf, |u_C - u_C(start)|_inf, SSSTAR_LAW_FLOOR max(|u_C|_inf, |f|_inf / mean diag K_CC))   the step's displacements
     F = max(|r|_inf, |r - r(start)|_inf, SSSTAR_LAW_FORCE_FLOOR (max_i sum_j |A_ij| |u|_inf + |f|_inf))   and forces

   each at least SSSTAR_LAW_FLOOR times the largest of the solves since the set-up (a step of a load path where nothing
   touches and nothing is loaded has forces of round-off alone: they are measured against the path's).

   rho is |z|_inf / U of the approximation step (12.1) at (w, r) with gamma_w = U/F: (w + z, -b/gamma_w) is that pair.
   Without floors: the step's own scales alone (the elastic trial's choice, where the rounding does not matter).
*/
static PetscErrorCode LawResidual(SNES snes, Vec u, Vec c, PetscBool floors, PetscReal *rho, PetscReal *Uout, PetscReal *Fout)
{
  SNES_SSStar       *ss = (SNES_SSStar *)snes->data;
  SSStarContact     *ct = &ss->contact;
  SSStarProblem     *pb = &ss->problem;
  const PetscScalar *ua, *ca;
  PetscReal          scales[5] = {0, 0, 0, 0, 0}, res[2] = {0, 0}, gammaw, U, F; /* |w|, |u_C - u_C(start)|, |u_C|, |r|, |r - r(start)| */

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(u, &ua));
  PetscCall(VecGetArrayRead(c, &ca));
  for (PetscInt i = 0; i < ct->nnodes; i++) {
    const PetscReal scale = ct->pointScale ? ct->pointScale[i] : 1.0;
    PetscReal       v[3], r[3];

    SNESSSStarNodeIterate(ct, pb, i, ua, v);
    SNESSSStarNodeRotate(ct, pb, i, ca, r);
    for (PetscInt k = 0; k < 3; k++) {
      const PetscInt  dof = pb->layoutDofs[3 * i + k];
      const PetscReal uk = PetscRealPart(ua[dof]), ck = PetscRealPart(ca[dof]);

      scales[0] = PetscMax(scales[0], PetscAbsReal(scale * v[k]));
      scales[1] = PetscMax(scales[1], PetscAbsReal(uk - ss->start[6 * i + k]));
      scales[2] = PetscMax(scales[2], PetscAbsReal(uk));
      scales[3] = PetscMax(scales[3], PetscAbsReal(r[k]));
      scales[4] = PetscMax(scales[4], PetscAbsReal(ck - ss->start[6 * i + 3 + k]));
    }
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, scales, 5, MPIU_REAL, MPIU_MAX, PetscObjectComm((PetscObject)snes)));
  U = PetscMax(scales[0], scales[1]);
  F = PetscMax(scales[3], scales[4]);
  if (floors) {
    U = PetscMax(PetscMax(U, SSSTAR_LAW_FLOOR * scales[2]), SSSTAR_LAW_FLOOR * ss->pathDisplacement);
    if (pb->meanDiag > 0) U = PetscMax(U, SSSTAR_LAW_FLOOR * ss->fnorm_inf / pb->meanDiag); /* every point stuck where it was: the load's displacement scale */
    F = PetscMax(PetscMax(F, SSSTAR_LAW_FORCE_FLOOR * (pb->maxRowSum * scales[2] + ss->fnorm_inf)), SSSTAR_LAW_FLOOR * ss->pathForce);
  }
  *Uout = U;
  *Fout = F;
  if (U == 0) U = 1; /* nothing moves: a displacement error is absolute */
  if (F == 0) F = 1; /* no force at all: a force error is absolute */
  gammaw = U / F;
  for (PetscInt i = 0; i < ct->nnodes; i++) {
    const PetscReal scale = ct->pointScale ? ct->pointScale[i] : 1.0;
    const SSStarFriction fr   = SNESSSStarScaledFriction(ss, i, gammaw);
    PetscReal            v[3], cv[3], z[3], d[3], b[3];

    SNESSSStarNodeIterate(ct, pb, i, ua, v);
    SNESSSStarNodeRotate(ct, pb, i, ca, cv);
    for (PetscInt k = 0; k < 3; k++) {
      v[k] *= scale;
      cv[k] *= gammaw;
    }
    SSStarApproximationStep(&fr, v, cv, z, d, b);
    for (PetscInt k = 0; k < 3; k++) res[0] = PetscMax(res[0], PetscAbsReal(z[k]) / U);
  }
  for (PetscInt j = 0; j < pb->nfree; j++) res[1] = PetscMax(res[1], PetscAbsScalar(ca[pb->free[j]]) / F);
  PetscCall(VecRestoreArrayRead(c, &ca));
  PetscCall(VecRestoreArrayRead(u, &ua));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, res, 2, MPIU_REAL, MPIU_MAX, PetscObjectComm((PetscObject)snes)));
  *rho = PetscMax(res[0], res[1]);
  PetscFunctionReturn(0);
}

/* The law residual of (u, c) with its floors, into ss->lawResidual, lawDisplacement (U), lawForce (F) */
PetscErrorCode SNESSSStarLawResidual(SNES snes, Vec u, Vec c)
{
  SNES_SSStar *ss = (SNES_SSStar *)snes->data;

  PetscFunctionBegin;
  PetscCall(LawResidual(snes, u, c, PETSC_TRUE, &ss->lawResidual, &ss->lawDisplacement, &ss->lawForce));
  PetscFunctionReturn(0);
}

/* The tolerance of the law residual: as set (-snes_ssstar_law_rtol), else max(rtol, SSSTAR_LAW_RTOL_DEFAULT) */
PetscReal SNESSSStarLawTolerance(SNES snes)
{
  SNES_SSStar *ss = (SNES_SSStar *)snes->data;

  return ss->lawRtol > 0 ? ss->lawRtol : PetscMax(snes->rtol, SSSTAR_LAW_RTOL_DEFAULT);
}

/* The contact dofs of the first iterate u of a solve and of its c = A u - f, from which the law residual measures the
   step's displacements and forces */
PetscErrorCode SNESSSStarRecordStart(SNES snes, Vec u, Vec c)
{
  SNES_SSStar       *ss = (SNES_SSStar *)snes->data;
  SSStarProblem     *pb = &ss->problem;
  const PetscScalar *ua, *ca;

  PetscFunctionBegin;
  PetscCall(PetscFree(ss->start));
  PetscCall(PetscMalloc1(6 * ss->contact.nnodes + 1, &ss->start));
  PetscCall(VecGetArrayRead(u, &ua));
  PetscCall(VecGetArrayRead(c, &ca));
  for (PetscInt i = 0; i < ss->contact.nnodes; i++)
    for (PetscInt k = 0; k < 3; k++) {
      ss->start[6 * i + k]     = PetscRealPart(ua[pb->layoutDofs[3 * i + k]]);
      ss->start[6 * i + 3 + k] = PetscRealPart(ca[pb->layoutDofs[3 * i + k]]);
    }
  PetscCall(VecRestoreArrayRead(c, &ca));
  PetscCall(VecRestoreArrayRead(u, &ua));
  PetscFunctionReturn(0);
}

/* Node i stuck where it is (state M3+, target v = 0: d = 0, z = -v), in the arrays of ss->u, ss->z and ss->d */
void SNESSSStarStickNode(SNES_SSStar *ss, PetscInt i, const PetscScalar *ua, PetscScalar *za, PetscScalar *da)
{
  PetscReal v[3];

  SNESSSStarNodeIterate(&ss->contact, &ss->problem, i, ua, v);
  ss->states[i] = SSSTAR_STATE_M3P;
  for (PetscInt k = 0; k < 3; k++) {
    za[ss->problem.layoutDofs[3 * i + k]] = -v[k];
    da[3 * i + k]                         = 0;
  }
}

/*
   The elastic trial of a load path's step (docs/derivation.md section 12.3), from its first iterate u (the last step's
   solution) after the approximation step there: if the step's offsets moved nodes in contact (d_3 = 0) along their
   obstacles (|v_t| above the rounding of w = R u + o), one Newton step with every such node stuck where its obstacle
   took it (state M3+, target v = 0: SNESSSStarStickNode()) and the others as classified; taken (the iterate moves there)
   when it lowers the law residual measured with the step's own scales (not their round-off floors: a stiff body far
   from its reference computes its forces only to round-off, and the floor would hide that the old sliding forces point
   the wrong way). A block dragged back by its plane sticks and comes back with it: the trial is its answer, which the
   approximation step's own classification (the nodes sliding the way they slid) reaches only by luck.
*/
PetscErrorCode SNESSSStarElasticTrial(SNES snes, PetscBool *taken)
{
  SNES_SSStar       *ss = (SNES_SSStar *)snes->data;
  SSStarContact     *ct = &ss->contact;
  SSStarProblem     *pb = &ss->problem;
  const PetscScalar *ua;
  PetscScalar       *za, *da, *ba;
  PetscReal          moved[2] = {0, 0}, before, after, U, F, znorm; /* the largest |v_t| in contact, |u_C| */
  PetscBool          solved;

  PetscFunctionBegin;
  *taken = PETSC_FALSE;
  if (!ct->offsets) PetscFunctionReturn(0);
  PetscCall(VecGetArrayRead(ss->u, &ua));
  PetscCall(VecGetArrayRead(ss->d, (const PetscScalar **)&da));
  for (PetscInt i = 0; i < ct->nnodes; i++) {
    PetscReal v[3];

    SNESSSStarNodeIterate(ct, pb, i, ua, v);
    if (PetscRealPart(da[3 * i + 2]) == 0) moved[0] = PetscMax(moved[0], PetscSqrtReal(v[0] * v[0] + v[1] * v[1]));
    for (PetscInt k = 0; k < 3; k++) moved[1] = PetscMax(moved[1], PetscAbsScalar(ua[pb->layoutDofs[3 * i + k]]));
  }
  PetscCall(VecRestoreArrayRead(ss->d, (const PetscScalar **)&da));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, moved, 2, MPIU_REAL, MPIU_MAX, PetscObjectComm((PetscObject)snes)));
  if (moved[0] <= SSSTAR_LAW_FLOOR * moved[1]) {
    PetscCall(VecRestoreArrayRead(ss->u, &ua));
    PetscFunctionReturn(0);
  }
  PetscCall(VecGetArray(ss->z, &za));
  PetscCall(VecGetArray(ss->d, &da));
  PetscCall(VecGetArray(ss->b, &ba));
  for (PetscInt i = 0; i < ct->nnodes; i++)
    if (PetscRealPart(da[3 * i + 2]) == 0) SNESSSStarStickNode(ss, i, ua, za, da);
  PetscCall(VecRestoreArray(ss->b, &ba));
  PetscCall(VecRestoreArray(ss->d, &da));
  PetscCall(VecRestoreArray(ss->z, &za));
  PetscCall(VecRestoreArrayRead(ss->u, &ua));
  PetscCall(LawResidual(snes, ss->u, ss->c, PETSC_FALSE, &before, &U, &F));
  PetscCall(VecNorm(ss->z, NORM_2, &znorm));
  PetscCall(SNESSSStarNewtonStep(snes, znorm, 0.0, PETSC_FALSE, &solved));
  if (!solved) PetscFunctionReturn(0);
  PetscCall(VecWAXPY(ss->ut, 1.0, ss->dv, ss->u));
  PetscCall(SNESSSStarResidual(snes, ss->ut, ss->ct));
  PetscCall(VecNorm(ss->ct, NORM_INFINITY, &after)); /* a trial where F is not defined (c = Inf: an inverted cell) is not taken */
  if (!PetscIsInfOrNanReal(after)) PetscCall(LawResidual(snes, ss->ut, ss->ct, PETSC_FALSE, &after, &U, &F));
  *taken = (PetscBool)(after < before);
  if (*taken) {
    PetscCall(VecCopy(ss->ut, ss->u));
    PetscCall(VecCopy(ss->ct, ss->c));
  }
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
    const SSStarFriction fr = SNESSSStarScaledFriction(ss, i, ss->scaling);

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
   stopping threshold, and of the law's tolerance of forces (section 12) once the law residual has been measured: on a
   stiff body gamma^-1 times the first is far above the contact forces. The fraction is a tenth (SSSTAR_FLOOR_FRACTION),
   and -snes_ssstar_ksp_floor (default the same tenth) for the step that is likely the last (ss->lastStep): there the
   step's residual is what the stopping rule measures next (docs/derivation.md section 19a)
*/
PetscErrorCode SNESSSStarLinearFloor(SNES snes, PetscReal *floor)
{
  SNES_SSStar    *ss       = (SNES_SSStar *)snes->data;
  const PetscReal fraction = ss->lastStep ? ss->kspFloor : SSSTAR_FLOOR_FRACTION;
  PetscReal       unorm;

  PetscFunctionBegin;
  PetscCall(SNESSSStarContactNorm(snes, ss->u, &unorm));
  *floor = fraction * PetscMax(snes->abstol, snes->rtol * PetscMax(PetscMax(unorm, ss->scale), ss->offsetScale)) / ss->scaling;
  if (ss->lawForce > 0) *floor = PetscMin(*floor, fraction * SNESSSStarLawTolerance(snes) * ss->lawForce);
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
  PetscCall(PetscInfo(snes, "Linear tolerance: eta %g of ||z|| %g, i.e. %g, the floor %g%s\n", (double)rtol, (double)znorm, (double)(rtol * znorm / ss->scaling), (double)floor, ss->lastStep ? " (the likely last step)" : ""));
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
    const SSStarFriction fr  = SNESSSStarScaledFriction(ss, i, ss->scaling);
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

/*@
   SNESSSStarSetScaling - sets gamma, the scaling of the approximation step (docs/derivation.md section 6)

   Logically Collective

   Input Parameters:
+  snes  - the SNES
-  gamma - > 0, or 0 (the default): gamma = 1/mean(diag P), the contact block of K on the whole body

   Options Database Key:
.  -snes_ssstar_scaling <0> - the scaling

   Notes:
   gamma does not change the solutions, only the path to them and the units of ||z|| (a displacement for the default).

   Level: advanced

.seealso: `SNESSSStarGetScaling()`, `SNESConvergedSSStar()`
@*/
PetscErrorCode SNESSSStarSetScaling(SNES snes, PetscReal gamma)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscTryMethod(snes, "SNESSSStarSetScaling_C", (SNES, PetscReal), (snes, gamma));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarSetScaling_SSStar(SNES snes, PetscReal gamma)
{
  PetscFunctionBegin;
  PetscCheck(gamma >= 0 && !PetscIsInfOrNanReal(gamma), PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_OUTOFRANGE, "-snes_ssstar_scaling %g: gamma must be > 0 (or 0 for 1/mean diag P)", (double)gamma);
  ((SNES_SSStar *)snes->data)->scaling_user = gamma;
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarGetScaling - gamma: the one set by the user, else 1/mean(diag P) of the last solve (0 before it)

   Not Collective

   Input Parameter:
.  snes - the SNES

   Output Parameter:
.  gamma - the scaling

   Level: advanced

.seealso: `SNESSSStarSetScaling()`
@*/
PetscErrorCode SNESSSStarGetScaling(SNES snes, PetscReal *gamma)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscUseMethod(snes, "SNESSSStarGetScaling_C", (SNES, PetscReal *), (snes, gamma));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarGetScaling_SSStar(SNES snes, PetscReal *gamma)
{
  SNES_SSStar *ss = (SNES_SSStar *)snes->data;

  PetscFunctionBegin;
  *gamma = ss->scaling_user > 0 ? ss->scaling_user : ss->scaling;
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarSetStateTolerance - sets tau, the relative tolerance of the contact-state classification (default 1e-13;
   docs/derivation.md section 2)

   Logically Collective

   Input Parameters:
+  snes - the SNES
-  tau  - >= 0; 0 classifies by exact zeros

   Options Database Key:
.  -snes_ssstar_state_tol <1e-13> - the tolerance

   Level: advanced

.seealso: `SSStarClassify()`, `SNESSSStarGetStates()`
@*/
PetscErrorCode SNESSSStarSetStateTolerance(SNES snes, PetscReal tau)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscTryMethod(snes, "SNESSSStarSetStateTolerance_C", (SNES, PetscReal), (snes, tau));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarSetStateTolerance_SSStar(SNES snes, PetscReal tau)
{
  PetscFunctionBegin;
  PetscCheck(tau >= 0 && tau < 1, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_OUTOFRANGE, "-snes_ssstar_state_tol %g must be in [0, 1)", (double)tau);
  ((SNES_SSStar *)snes->data)->state_tol = tau;
  PetscFunctionReturn(0);
}

/*@C
   SNESSSStarGetStates - the state of each owned contact node at the last iterate, and the global counts per state

   Not Collective

   Input Parameter:
.  snes - the SNES, after SNESSolve()

   Output Parameters:
+  states - the states of the contact nodes of this rank, in the order they were declared (owned by the SNES), or
            pass NULL
-  counts - the number of nodes in each state over all ranks (SSSTAR_NUM_STATES entries), or pass NULL

   Notes:
   The states are those of Table 1 (SSStarState, docs/derivation.md section 2); SSStarStateNames[] names them.

   Level: beginner

.seealso: `SNESSSStarGetReason()`, `SNESSSStarMonitorStates()`, `SSStarClassify()`
@*/
PetscErrorCode SNESSSStarGetStates(SNES snes, const SSStarState *states[], PetscInt counts[SSSTAR_NUM_STATES])
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscUseMethod(snes, "SNESSSStarGetStates_C", (SNES, const SSStarState *[], PetscInt[]), (snes, states, counts));
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

/*@
   SNESSSStarSetLawTolerance - the tolerance of the law residual of a converged iterate: a solve converges only when,
   besides ||z||, every contact point's relative displacement and force as the output writes them lie within rtol U
   and rtol F of a pair that satisfies the friction law exactly, and the other dofs are in equilibrium to rtol F
   (docs/derivation.md section 12; U the step's largest displacement, F the largest contact force)

   Logically Collective

   Input Parameters:
+  snes - the SNES
-  rtol - in (0, 1), or 0 (the default): max(the SNES's rtol, 1e-8)

   Options Database Key:
.  -snes_ssstar_law_rtol <rtol> - the tolerance

   Notes:
   Where ||z|| has met its threshold and the law residual has not, the iteration takes Newton steps solved to the
   floor (polishing; whole once the states have settled, globalized before) until it does, or stops with
   SSSTAR_REASON_LAW_STALLED when it no longer halves (its round-off floor is above the tolerance).

   Level: intermediate

.seealso: `SNESSSStarGetLawResidual()`, `SNESConvergedSSStar()`, `SNESSetTolerances()`
@*/
PetscErrorCode SNESSSStarSetLawTolerance(SNES snes, PetscReal rtol)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscTryMethod(snes, "SNESSSStarSetLawTolerance_C", (SNES, PetscReal), (snes, rtol));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarSetLawTolerance_SSStar(SNES snes, PetscReal rtol)
{
  PetscFunctionBegin;
  PetscCheck(rtol >= 0 && rtol < 1, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_OUTOFRANGE, "-snes_ssstar_law_rtol %g must be in (0, 1), or 0 for max(-snes_rtol, 1e-8)", (double)rtol);
  ((SNES_SSStar *)snes->data)->lawRtol = rtol;
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarGetLawResidual - the law residual of the last iterate as the output writes it (docs/derivation.md
   section 12), the tolerance it was held to, and its scales

   Not Collective

   Input Parameter:
.  snes - the SNES

   Output Parameters:
+  residual - rho: every contact point's (w, r) lies within rho U, rho F of a pair satisfying the law, the other dofs are
              in equilibrium to rho F (NULL if not wanted)
.  tol      - the law tolerance (SNESSSStarSetLawTolerance()): a converged solve has residual <= tol (NULL if not wanted)
.  U        - the displacement scale: the largest relative displacement, or displacement in the solve (NULL if not wanted)
-  F        - the force scale: the largest contact force (NULL if not wanted)

   Level: intermediate

.seealso: `SNESSSStarSetLawTolerance()`, `SNESSSStarGetTolerance()`
@*/
PetscErrorCode SNESSSStarGetLawResidual(SNES snes, PetscReal *residual, PetscReal *tol, PetscReal *U, PetscReal *F)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscUseMethod(snes, "SNESSSStarGetLawResidual_C", (SNES, PetscReal *, PetscReal *, PetscReal *, PetscReal *), (snes, residual, tol, U, F));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarGetLawResidual_SSStar(SNES snes, PetscReal *residual, PetscReal *tol, PetscReal *U, PetscReal *F)
{
  SNES_SSStar *ss = (SNES_SSStar *)snes->data;

  PetscFunctionBegin;
  if (residual) *residual = ss->lawResidual;
  if (tol) *tol = SNESSSStarLawTolerance(snes);
  if (U) *U = ss->lawDisplacement;
  if (F) *F = ss->lawForce;
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarSetKSPRtolMax - whole body (reduction none): the loosest relative tolerance of the linear solve of a
   Newton step (inexact Newton). The tolerance of step k is min(rtol, ||z_k||/||z_0||) while no remedy of the
   globalization acted, with an absolute floor of a tenth of the stopping threshold; once one did, and for a step whose
   full step fails the line search, the floor alone; -ksp_rtol fixes it instead.

   Logically Collective

   Input Parameters:
+  snes - the SNES
-  rtol - in (0, 1) (default 0.1)

   Options Database Key:
.  -snes_ssstar_ksp_rtol_max <rtol> - the tolerance

   Level: advanced

.seealso: `SNESSSStarSetPCReuse()`
@*/
PetscErrorCode SNESSSStarSetKSPRtolMax(SNES snes, PetscReal rtol)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscTryMethod(snes, "SNESSSStarSetKSPRtolMax_C", (SNES, PetscReal), (snes, rtol));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarSetKSPRtolMax_SSStar(SNES snes, PetscReal rtol)
{
  PetscFunctionBegin;
  PetscCheck(rtol > 0 && rtol < 1, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_OUTOFRANGE, "-snes_ssstar_ksp_rtol_max %g must be in (0, 1)", (double)rtol);
  ((SNES_SSStar *)snes->data)->etaMax = rtol;
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarSetKSPFloor - whole body (reduction none): how far the linear solve of the step that is likely the last
   goes, as a fraction of the stopping rule: its residual r is solved until gamma ||r|| is at most this fraction of the
   threshold of ||z|| and ||r|| at most this fraction of the law's tolerance of forces (docs/derivation.md section 19a).
   The step is likely the last when the states of the full step before it repeated and no remedy acted; every other
   step solved to the floor (after a remedy, polishing) keeps a tenth.

   Logically Collective

   Input Parameters:
+  snes     - the SNES
-  fraction - in (0, 1] (default 0.1, SSSTAR_FLOOR_FRACTION)

   Options Database Key:
.  -snes_ssstar_ksp_floor <fraction> - the fraction

   Notes:
   0.5 saves 3 Krylov iterations at level 16 of examples/prism (the same Newton steps), but leaves the law with less
   room than an independent measure of it wants (docs/derivation.md section 19a: 1.06e-8 against 1e-8 in
   tests/test_operator on 2 ranks), so the default is the tenth of the other steps; where the step leaves ||z|| or the
   law residual above its threshold, one more Newton step follows.

   Level: advanced

.seealso: `SNESSSStarSetKSPRtolMax()`, `SNESConvergedSSStar()`, `SNESSSStarSetLawTolerance()`
@*/
PetscErrorCode SNESSSStarSetKSPFloor(SNES snes, PetscReal fraction)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscTryMethod(snes, "SNESSSStarSetKSPFloor_C", (SNES, PetscReal), (snes, fraction));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarSetKSPFloor_SSStar(SNES snes, PetscReal fraction)
{
  PetscFunctionBegin;
  PetscCheck(fraction > 0 && fraction <= 1, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_OUTOFRANGE, "-snes_ssstar_ksp_floor %g must be in (0, 1]", (double)fraction);
  ((SNES_SSStar *)snes->data)->kspFloor = fraction;
  PetscFunctionReturn(0);
}

/* The implementations of the public functions above, composed on the SNES (SNESSSStarComposeFunctions()) */
static const SSStarComposed Composed[] = {
    {"SNESSSStarSetScaling_C", (PetscVoidFunction)SNESSSStarSetScaling_SSStar},
    {"SNESSSStarGetScaling_C", (PetscVoidFunction)SNESSSStarGetScaling_SSStar},
    {"SNESSSStarSetStateTolerance_C", (PetscVoidFunction)SNESSSStarSetStateTolerance_SSStar},
    {"SNESSSStarGetStates_C", (PetscVoidFunction)SNESSSStarGetStates_SSStar},
    {"SNESSSStarSetLawTolerance_C", (PetscVoidFunction)SNESSSStarSetLawTolerance_SSStar},
    {"SNESSSStarGetLawResidual_C", (PetscVoidFunction)SNESSSStarGetLawResidual_SSStar},
    {"SNESSSStarSetKSPRtolMax_C", (PetscVoidFunction)SNESSSStarSetKSPRtolMax_SSStar},
    {"SNESSSStarSetKSPFloor_C", (PetscVoidFunction)SNESSSStarSetKSPFloor_SSStar},
};

PetscErrorCode SNESSSStarComposeNodeSteps(SNES snes, PetscBool on)
{
  PetscFunctionBegin;
  PetscCall(SNESSSStarComposeTable(snes, Composed, PETSC_STATIC_ARRAY_LENGTH(Composed), on));
  PetscFunctionReturn(0);
}
