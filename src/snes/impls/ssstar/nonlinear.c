/*
   The residual of the SNES type "ssstar" when it is not affine (docs/derivation.md section 17). The iteration of
   ssstar.c runs on c(u) and its Jacobian A; for an affine F(u) = K u - b (SNESSSStarSetLinearProblem(), or declared by
   SNESSSStarSetAffine()) they are c = A u - f with the A of the set-up, and F is checked against that model at the
   solution. Any other F is treated as nonlinear, on the whole body (problem.c refuses a Schur reduction):

     c(u) = T^T F(T u) at every iterate and trial point (an F evaluation each, problem.c: the merit ||z|| is F's);
     its Jacobian evaluated again at the iterates as -snes_lag_jacobian says (A, the Newton step and the floating
       bodies' motions follow);
     the contact measured again at every iterate when the program gives a contact update (SNESSSStarSetContactUpdate():
       normals, gaps, offsets, master weights at the current configuration), which makes the problem nonlinear too.
*/
#include "ssstarimpl.h"

/* Before the set-up of a solve: the contact update at the initial guess, so that the set-up takes what it declares */
PetscErrorCode SSStarNonlinearMeasureAtStart(SNES snes)
{
  SSStarContact *ct = &((SNES_SSStar *)snes->data)->contact;

  PetscFunctionBegin;
  if (!ct->update) PetscFunctionReturn(0);
  PetscCallBack("SNESSSStar contact update", (*ct->update)(snes, snes->vec_sol, ct->updateCtx));
  PetscFunctionReturn(0);
}

/* After the set-up, at the first iterate u: the counts of the solve, where the Jacobian and the contact were taken */
PetscErrorCode SSStarNonlinearBegin(SNES snes)
{
  SNES_SSStar   *ss = (SNES_SSStar *)snes->data;
  SSStarProblem *pb = &ss->problem;

  PetscFunctionBegin;
  pb->jacobians      = 1; /* the set-up's */
  pb->measures       = ss->contact.update ? 1 : 0;
  pb->affineMismatch = 0;
  ss->jacobiansLast  = 1;
  if (!pb->x)
    for (Vec *w = &pb->x; w <= &pb->xMeasured; w++) PetscCall(VecDuplicate(snes->vec_sol, w));
  if (!pb->nonlinear) PetscFunctionReturn(0);
  PetscCall(SSStarProblemIterateVector(&ss->contact, pb, ss->u, pb->xJ));
  PetscCall(VecCopy(pb->xJ, pb->xMeasured));
  PetscFunctionReturn(0);
}

/*
   The contact measured at the iterate u (a contact update given): the program's update declares it at x = T u; a
   declaration that changed is taken (problem.c), the iterate expressed in new points' variables where T changed (then
   its c again), and the Newton step built for the new frames. Once per iterate: nothing when it was measured there.
*/
PetscErrorCode SSStarNonlinearMeasureContact(SNES snes)
{
  SNES_SSStar        *ss = (SNES_SSStar *)snes->data;
  SSStarContact      *ct = &ss->contact;
  SSStarProblem      *pb = &ss->problem;
  SSStarContactLayout layout;
  PetscBool           same, rebuilt, variables;

  PetscFunctionBegin;
  if (!ct->update) PetscFunctionReturn(0);
  PetscCall(SSStarProblemIterateVector(ct, pb, ss->u, pb->x));
  PetscCall(VecEqual(pb->x, pb->xMeasured, &same));
  if (same) PetscFunctionReturn(0);
  PetscCall(VecCopy(pb->x, pb->xMeasured));
  PetscCallBack("SNESSSStar contact update", (*ct->update)(snes, pb->xMeasured, ct->updateCtx));
  pb->measures++;
  PetscCall(SSStarProblemTakeMeasuredContact(snes, ct, pb, &rebuilt, &variables));
  PetscCall(SSStarContactSetUpOffsets(PetscObjectComm((PetscObject)snes), ct, &ss->offsetScale)); /* offsets may change without a declaration */
  if (!rebuilt) PetscFunctionReturn(0);
  if (variables) { /* the same configuration in the new points' variables */
    PetscCall(SSStarProblemGetInitialGuess(ct, pb, pb->xMeasured, ss->u));
    PetscCall(SNESSSStarResidual(snes, ss->u, ss->c));
  }
  PetscCall(SSStarProblemGetLayout(ct, pb, &layout));
  PetscCall(SSStarNewtonUpdateStiffness(ss->newton, pb->newtonType, pb->A, &layout));
  PetscFunctionReturn(0);
}

/*
   Before the Newton step of iteration k: the Jacobian at the iterate when -snes_lag_jacobian asks for one there (as
   SNESComputeJacobian() decides: -1 never again, -2 once more, n every n-th iteration, counted across solves with
   -snes_lag_jacobian_persists) and it was not evaluated at this very point. A Jacobian routine that changed nothing
   (K's state kept) leaves A and the Newton step's factorizations as they are.
*/
PetscErrorCode SSStarNonlinearJacobian(SNES snes, PetscInt k)
{
  SNES_SSStar        *ss = (SNES_SSStar *)snes->data;
  SSStarContact      *ct = &ss->contact;
  SSStarProblem      *pb = &ss->problem;
  SSStarContactLayout layout;
  PetscObjectState    state;
  PetscBool           same;
  Mat                 K;

  PetscFunctionBegin;
  if (!pb->nonlinear || pb->affine) PetscFunctionReturn(0);
  if (snes->lagjacobian == -2) snes->lagjacobian = -1;
  else if (snes->lagjacobian == -1) PetscFunctionReturn(0);
  else if (snes->lagjacobian > 1 && (k + snes->jac_iter) % snes->lagjacobian) PetscFunctionReturn(0);
  PetscCall(SSStarProblemIterateVector(ct, pb, ss->u, pb->x));
  PetscCall(VecEqual(pb->x, pb->xJ, &same));
  if (same) PetscFunctionReturn(0);
  PetscCall(VecCopy(pb->x, pb->xJ));
  PetscCall(SSStarProblemComputeJacobian(snes, pb->xJ, &K));
  pb->jacobians++;
  PetscCall(PetscObjectStateGet((PetscObject)K, &state));
  if (K == pb->K && state == pb->Kstate) PetscFunctionReturn(0);
  PetscCheck(K == pb->K, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_WRONGSTATE, "ssstar: the Jacobian matrix changed within a solve (SNESSetJacobian() with another Mat): give the same matrix new values");
  PetscCall(SSStarProblemTakeJacobian(snes, ct, pb, K));
  PetscCall(SSStarProblemGetLayout(ct, pb, &layout));
  PetscCall(SSStarNewtonUpdateStiffness(ss->newton, pb->newtonType, pb->A, &layout));
  PetscFunctionReturn(0);
}

/*
   A residual declared affine, checked at the solution: F there (snes->vec_func, in the points' variables T^T F)
   against the model the iteration solved, c = A u - f at the contact dofs and 0 at the other dofs (they are in
   equilibrium by the reduction's recovery). A converged solve whose F is off by more than ten times the round-off of
   A u - f and the law's tolerance of its forces (docs/derivation.md (12.2), (17.6)) did not solve F: it ends with
   SSSTAR_REASON_NOT_AFFINE (SNES_DIVERGED_LOCAL_MIN).
*/
PetscErrorCode SSStarNonlinearCheckAffine(SNES snes)
{
  SNES_SSStar       *ss = (SNES_SSStar *)snes->data;
  SSStarContact     *ct = &ss->contact;
  SSStarProblem     *pb = &ss->problem;
  Vec                w  = snes->vec_func;
  const PetscScalar *wa, *ca;
  const PetscInt    *idx = NULL;
  PetscInt           n, rstart;
  PetscReal          off = 0, xmax, bmax, scale, tol;

  PetscFunctionBegin;
  if (pb->nonlinear || snes->reason <= 0) PetscFunctionReturn(0);
  if (ct->T) {
    PetscCall(MatMultTranspose(ct->T, snes->vec_func, pb->v));
    w = pb->v;
  }
  PetscCall(VecGetOwnershipRange(w, &rstart, NULL));
  PetscCall(VecGetLocalSize(w, &n));
  PetscCall(VecGetArrayRead(w, &wa));
  PetscCall(VecGetArrayRead(ss->c, &ca));
  if (!ct->dofs || pb->wholeBody)
    for (PetscInt j = 0; j < n; j++) off = PetscMax(off, PetscAbsScalar(wa[j] - ca[j]));
  else { /* the reduced route: c at the contact dofs, 0 at the others */
    PetscInt   nC;
    PetscBool *contact;

    PetscCall(ISGetLocalSize(ct->isC, &nC));
    PetscCall(ISGetIndices(ct->isC, &idx));
    PetscCall(PetscCalloc1(n + 1, &contact));
    for (PetscInt k = 0; k < nC; k++) {
      contact[idx[k] - rstart] = PETSC_TRUE;
      off                      = PetscMax(off, PetscAbsScalar(wa[idx[k] - rstart] - ca[k]));
    }
    for (PetscInt j = 0; j < n; j++)
      if (!contact[j]) off = PetscMax(off, PetscAbsScalar(wa[j]));
    PetscCall(PetscFree(contact));
    PetscCall(ISRestoreIndices(ct->isC, &idx));
  }
  PetscCall(VecRestoreArrayRead(ss->c, &ca));
  PetscCall(VecRestoreArrayRead(w, &wa));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &off, 1, MPIU_REAL, MPIU_MAX, PetscObjectComm((PetscObject)snes)));
  PetscCall(VecNorm(snes->vec_sol, NORM_INFINITY, &xmax));
  PetscCall(VecNorm(pb->b, NORM_INFINITY, &bmax));
  scale = PetscMax(ss->lawForce, bmax);
  tol   = 10 * PetscMax(SNESSSStarLawTolerance(snes) * scale, SSSTAR_LAW_FORCE_FLOOR * (pb->maxRowSum * xmax + bmax));
  pb->affineMismatch = scale > 0 ? off / scale : off;
  if (off <= tol) PetscFunctionReturn(0);
  PetscCall(PetscInfo(snes, "F at the solution is off the affine model by %g (tolerance %g): not affine\n", (double)off, (double)tol));
  ss->reason   = SSSTAR_REASON_NOT_AFFINE;
  snes->reason = SNES_DIVERGED_LOCAL_MIN;
  PetscFunctionReturn(0);
}

/* ", residual nonlinear: 5 Jacobian evaluations, 12 function evaluations" or ", residual affine (F checked at the solution: off by 2e-16)" */
PetscErrorCode SSStarNonlinearFormatCounts(SNES snes, char buf[], size_t len)
{
  SSStarProblem *pb = &((SNES_SSStar *)snes->data)->problem;
  char           measured[128] = "";

  PetscFunctionBegin;
  if (pb->measures) PetscCall(PetscSNPrintf(measured, sizeof(measured), ", %" PetscInt_FMT " contact updates", pb->measures));
  if (pb->nonlinear) PetscCall(PetscSNPrintf(buf, len, "residual %s: %" PetscInt_FMT " Jacobian evaluation%s, %" PetscInt_FMT " function evaluations%s", pb->affine ? "affine, the contact measured at the iterates" : "nonlinear", pb->jacobians, pb->jacobians == 1 ? "" : "s", snes->nfuncs, measured));
  else PetscCall(PetscSNPrintf(buf, len, "residual affine: 1 Jacobian evaluation, F checked at the solution (off the model by %.2g of its force scale)", (double)pb->affineMismatch));
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarNonlinearView(SNES snes, PetscViewer viewer)
{
  SNES_SSStar   *ss = (SNES_SSStar *)snes->data;
  SSStarProblem *pb = &ss->problem;
  PetscBool      affine;
  char           lag[64];

  PetscFunctionBegin;
  PetscCall(SSStarProblemIsAffine(snes, pb, &affine));
  if (snes->lagjacobian == -1) PetscCall(PetscSNPrintf(lag, sizeof(lag), "never again after the first"));
  else if (snes->lagjacobian == 1) PetscCall(PetscSNPrintf(lag, sizeof(lag), "at every iterate"));
  else PetscCall(PetscSNPrintf(lag, sizeof(lag), "every %" PetscInt_FMT " iterations", snes->lagjacobian));
  if (affine) PetscCall(PetscViewerASCIIPrintf(viewer, "  residual: affine, F(u) = K u - b (%s): the Jacobian evaluated once per solve, F checked at the solution\n", pb->affineSet ? "declared, SNESSSStarSetAffine()" : "SNESSSStarSetLinearProblem()"));
  else PetscCall(PetscViewerASCIIPrintf(viewer, "  residual: nonlinear (not declared affine): F evaluated at every iterate and trial point, the Jacobian %s (-snes_lag_jacobian)%s\n", lag, ss->contact.dofs ? ", on the whole body" : ""));
  if (ss->contact.update) PetscCall(PetscViewerASCIIPrintf(viewer, "  contact measured again at every iterate (SNESSSStarSetContactUpdate())\n"));
  if (ss->reason != SSSTAR_REASON_ITERATING) {
    char counts[256];

    PetscCall(SSStarNonlinearFormatCounts(snes, counts, sizeof(counts)));
    PetscCall(PetscViewerASCIIPrintf(viewer, "    last solve: %s\n", counts));
  }
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarSetAffine - declares whether the SNES function is affine, F(u) = K u - b with the Jacobian K: then the
   Jacobian is evaluated once per solve and every residual of the iteration is c = A u - f (the fast route: the Schur
   reduction, dense LU); otherwise F is evaluated at the iterates and its Jacobian again as -snes_lag_jacobian says,
   on the whole body (docs/derivation.md section 17)

   Logically Collective

   Input Parameters:
+  snes   - the SNES
-  affine - PETSC_TRUE: affine; PETSC_FALSE: nonlinear

   Options Database Key:
.  -snes_ssstar_affine <auto> - true or false: the declaration; auto: none (F decides)

   Notes:
   Without a declaration F is affine when it is SNESSSStarSetLinearProblem()'s and nonlinear otherwise: a program that
   gives its own SNESSetFunction() and SNESSetJacobian() gets the nonlinear iteration unless it declares its F affine.
   A residual declared affine is checked at the solution: a converged solve whose F is off the affine model by more
   than the law's tolerance of its forces ends with SSSTAR_REASON_NOT_AFFINE (SNES_DIVERGED_LOCAL_MIN) instead of a
   wrong CONVERGED. A contact update (SNESSSStarSetContactUpdate()) makes the iteration nonlinear whatever F is.

   Level: intermediate

.seealso: `SNESSSStarGetAffine()`, `SNESSSStarSetLinearProblem()`, `SNESSSStarSetContactUpdate()`, `SNESSetLagJacobian()`
@*/
PetscErrorCode SNESSSStarSetAffine(SNES snes, PetscBool affine)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscValidLogicalCollectiveBool(snes, affine, 2);
  PetscTryMethod(snes, "SNESSSStarSetAffine_C", (SNES, PetscBool), (snes, affine));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarSetAffine_SSStar(SNES snes, PetscBool affine)
{
  SSStarProblem *pb = &((SNES_SSStar *)snes->data)->problem;

  PetscFunctionBegin;
  pb->affineSet      = PETSC_TRUE;
  pb->affineDeclared = affine;
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarGetAffine - whether the next solve treats the SNES function as affine: as declared by
   SNESSSStarSetAffine(), else whether it is SNESSSStarSetLinearProblem()'s

   Not Collective

   Input Parameter:
.  snes - the SNES

   Output Parameter:
.  affine - PETSC_TRUE: affine, the Jacobian evaluated once; PETSC_FALSE: nonlinear

   Level: intermediate

.seealso: `SNESSSStarSetAffine()`, `SNESSSStarGetNonlinearCounts()`
@*/
PetscErrorCode SNESSSStarGetAffine(SNES snes, PetscBool *affine)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscValidBoolPointer(affine, 2);
  PetscUseMethod(snes, "SNESSSStarGetAffine_C", (SNES, PetscBool *), (snes, affine));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarGetAffine_SSStar(SNES snes, PetscBool *affine)
{
  PetscFunctionBegin;
  PetscCall(SSStarProblemIsAffine(snes, &((SNES_SSStar *)snes->data)->problem, affine));
  PetscFunctionReturn(0);
}

/*@C
   SNESSSStarSetContactUpdate - a routine that measures the contact at the current configuration: the solver calls it
   with the iterate at the start of a solve and at every new iterate of its Newton loop, and it declares the contact
   there again (normals, gaps, offsets, master dofs and weights: SNESSSStarSetContactNodes(),
   SNESSSStarSetContactOperator(), SNESSSStarSetContactOffsets()), for large deformation and large sliding

   Logically Collective

   Input Parameters:
+  snes   - the SNES
.  update - the routine, update(snes, x, ctx) with x the whole displacement of the iterate (the SNES vector's layout;
            read it, do not keep it), or NULL to measure no more
-  ctx    - its context, or NULL

   Notes:
   The declaration at x must be the contact linearized there (docs/derivation.md sections 13 and 17): rows B and gaps g
   with w = B u + g exact at u = x to first order (a rigid obstacle: the normal at the closest point and
   g = dist(x) - n.x; a slave node: the master triangle it faces and its weights). The points and their own dofs stay
   (another number of points or other dofs is refused). The iteration is then nonlinear (on the whole body) whatever F
   is; the step's trial points keep the contact measured at the iterate, and the geometric stiffness of a curved
   contact (its curvature times the contact force) is not in the Newton matrix, so the iterates converge linearly at
   that rate on a curved obstacle and as F's Newton iteration on a flat one. The contact measured the same way at the
   solution, the update's geometry holds there to the tolerance of the solve.

   Level: advanced

.seealso: `SNESSSStarSetAffine()`, `SNESSSStarSetContactOperator()`, `SNESSSStarSetContactOffsets()`,
          `SNESSSStarGetNonlinearCounts()`
@*/
PetscErrorCode SNESSSStarSetContactUpdate(SNES snes, PetscErrorCode (*update)(SNES, Vec, void *), void *ctx)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscTryMethod(snes, "SNESSSStarSetContactUpdate_C", (SNES, PetscErrorCode(*)(SNES, Vec, void *), void *), (snes, update, ctx));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarSetContactUpdate_SSStar(SNES snes, PetscErrorCode (*update)(SNES, Vec, void *), void *ctx)
{
  SSStarContact *ct = &((SNES_SSStar *)snes->data)->contact;

  PetscFunctionBegin;
  ct->update    = update;
  ct->updateCtx = ctx;
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarGetNonlinearCounts - what the last solve evaluated besides F: the Jacobian and the contact

   Not Collective

   Input Parameter:
.  snes - the SNES

   Output Parameters:
+  jacobians - Jacobian evaluations (1 for an affine residual: the set-up's), or pass NULL
-  updates   - calls of the contact update (SNESSSStarSetContactUpdate()), or pass NULL

   Notes:
   SNESGetNumberFunctionEvals() counts the evaluations of F.

   Level: intermediate

.seealso: `SNESSSStarSetAffine()`, `SNESSSStarSetContactUpdate()`, `SNESSetLagJacobian()`
@*/
PetscErrorCode SNESSSStarGetNonlinearCounts(SNES snes, PetscInt *jacobians, PetscInt *updates)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscUseMethod(snes, "SNESSSStarGetNonlinearCounts_C", (SNES, PetscInt *, PetscInt *), (snes, jacobians, updates));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarGetNonlinearCounts_SSStar(SNES snes, PetscInt *jacobians, PetscInt *updates)
{
  SSStarProblem *pb = &((SNES_SSStar *)snes->data)->problem;

  PetscFunctionBegin;
  if (jacobians) *jacobians = pb->jacobians;
  if (updates) *updates = pb->measures;
  PetscFunctionReturn(0);
}

/* The implementations of the public functions above, composed on the SNES (SNESSSStarComposeFunctions()) */
static const SSStarComposed Composed[] = {
    {"SNESSSStarSetAffine_C", (PetscVoidFunction)SNESSSStarSetAffine_SSStar},
    {"SNESSSStarGetAffine_C", (PetscVoidFunction)SNESSSStarGetAffine_SSStar},
    {"SNESSSStarSetContactUpdate_C", (PetscVoidFunction)SNESSSStarSetContactUpdate_SSStar},
    {"SNESSSStarGetNonlinearCounts_C", (PetscVoidFunction)SNESSSStarGetNonlinearCounts_SSStar},
};

PetscErrorCode SNESSSStarComposeNonlinear(SNES snes, PetscBool on)
{
  PetscFunctionBegin;
  PetscCall(SNESSSStarComposeTable(snes, Composed, PETSC_STATIC_ARRAY_LENGTH(Composed), on));
  PetscFunctionReturn(0);
}
