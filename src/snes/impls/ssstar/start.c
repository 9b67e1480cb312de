/*
   The start of a solve: the load's scale (||gamma f||, ||f||_inf, with f the load reduced to the contact dofs) and, on
   the whole body, the free dofs of the first iterate in equilibrium with its contact dofs (docs/derivation.md section
   6; docs/guide/scale.md, "One multigrid set-up on the finest mesh"). A nested iteration's start hands the load's scale
   of its coarser mesh's solve over (SNESSSStarSetCoarseLoadScale()): the finest mesh then needs no linear solve before
   its first Newton step.
*/
#include "ssstarimpl.h"

/* whole body: relative tolerance of the solves that put the free dofs in equilibrium before the first iteration */
#define SSSTAR_EQUILIBRIUM_RTOL 1e-4
/* ... and of the one from u = 0 that only gives the load's scale (||gamma f||, a given u being the start): one digit
   of the residual gives the scale to 1e-3 (prism level 12: 1.13526e-3 against 1.13621e-3 at 1e-2, in 6 CG
   iterations instead of 10) */
#define SSSTAR_SCALE_RTOL 1e-1

/* The free dofs of ss->u corrected with its contact dofs held, from c = K u - b there, to max(rtol ||r0||, atol);
   solved NULL: a failed linear solve is an error */
static PetscErrorCode CorrectFreeDofs(SNES snes, PetscReal rtol, PetscReal atol, PetscBool *solved)
{
  SNES_SSStar       *ss = (SNES_SSStar *)snes->data;
  SSStarProblem     *pb = &ss->problem;
  const PetscScalar *ca;
  PetscScalar       *za;
  PetscBool          ok;

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(ss->c, &ca));
  PetscCall(VecGetArrayWrite(ss->z, &za));
  for (PetscInt k = 0; k < 3 * ss->contact.nnodes; k++) za[pb->layoutDofs[k]] = 0;
  for (PetscInt j = 0; j < pb->nfree; j++) za[pb->free[j]] = -ss->scaling * ca[pb->free[j]];
  PetscCall(VecRestoreArrayWrite(ss->z, &za));
  PetscCall(VecRestoreArrayRead(ss->c, &ca));
  PetscCall(SSStarNewtonSetTolerances(ss->newton, rtol, atol));
  PetscCall(SNESSSStarFixedPointStep(snes, ss->u, ss->c, &ok));
  if (solved) *solved = ok;
  else PetscCheck(ok, PetscObjectComm((PetscObject)snes), PETSC_ERR_NOT_CONVERGED, "ssstar: the linear solve with K, the contact dofs held, failed (is the body held? Dirichlet conditions; see -ksp_converged_reason)");
  PetscFunctionReturn(0);
}

/* The contact nodes of the problem (global) */
static PetscErrorCode GlobalContactNodes(SNES snes, PetscInt *n)
{
  PetscFunctionBegin;
  PetscCall(MPIU_Allreduce(&((SNES_SSStar *)snes->data)->contact.nnodes, n, 1, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)snes)));
  PetscFunctionReturn(0);
}

/* ss->scale = gamma ||f||, ss->fnorm_inf = ||f||_inf from ||f|| and ||f||_inf */
static PetscErrorCode SetScale(SNES snes, PetscReal fnorm, PetscReal fmax, const char *from)
{
  SNES_SSStar *ss = (SNES_SSStar *)snes->data;

  PetscFunctionBegin;
  ss->scale     = ss->scaling * fnorm;
  ss->fnorm_inf = fmax;
  PetscCall(PetscInfo(snes, "The load's scale %s: ||gamma f|| %g, ||f||_inf %g\n", from, (double)ss->scale, (double)ss->fnorm_inf));
  PetscFunctionReturn(0);
}

/* The load's scale with f = -c at the contact dofs */
static PetscErrorCode SetLoadScale(SNES snes)
{
  SNES_SSStar       *ss = (SNES_SSStar *)snes->data;
  const PetscInt    *dofs = ss->problem.layoutDofs;
  PetscReal          sums[2] = {0, 0};
  const PetscScalar *ca;

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(ss->c, &ca));
  for (PetscInt k = 0; k < 3 * ss->contact.nnodes; k++) {
    const PetscReal fk = -PetscRealPart(ca[dofs[k]]);

    sums[0] += fk * fk;
    sums[1] = PetscMax(sums[1], PetscAbsReal(fk));
  }
  PetscCall(VecRestoreArrayRead(ss->c, &ca));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &sums[0], 1, MPIU_REAL, MPIU_SUM, PetscObjectComm((PetscObject)snes)));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &sums[1], 1, MPIU_REAL, MPIU_MAX, PetscObjectComm((PetscObject)snes)));
  PetscCall(SetScale(snes, PetscSqrtReal(sums[0]), sums[1], "from u0"));
  PetscFunctionReturn(0);
}

/*
   The load's scale of a coarser mesh's solve carried to this mesh as its contact forces scale: a node's force with
   the area it carries, 1/n for n contact nodes on the same surface; so ||f||_inf times n_c/n and ||f|| (n entries)
   times sqrt(n_c/n). gamma is this problem's own.
*/
static PetscErrorCode SetCoarseLoadScale(SNES snes)
{
  SNES_SSStar *ss = (SNES_SSStar *)snes->data;
  PetscInt     n;
  PetscReal    ratio;

  PetscFunctionBegin;
  PetscCall(GlobalContactNodes(snes, &n));
  ratio = (PetscReal)ss->coarseNodes / (PetscReal)n;
  PetscCall(SetScale(snes, ss->coarseLoad[0] * PetscSqrtReal(ratio), ss->coarseLoad[1] * ratio, "from the coarser mesh's"));
  PetscFunctionReturn(0);
}

/*
   A nonlinear residual (docs/derivation.md section 17): the guess, free dofs included (F is not K u - b: the top of a
   body prescribed in the guess stays), corrected by one linearized step of the free dofs with the contact dofs held,
   kept where it solved and F is defined there; the load's scale from the contact forces at that point
*/
static PetscErrorCode EquilibrateNonlinear(SNES snes)
{
  SNES_SSStar *ss = (SNES_SSStar *)snes->data;
  PetscReal    cmax;
  PetscBool    solved;

  PetscFunctionBegin;
  PetscCall(VecCopy(ss->u, ss->ut));
  PetscCall(SNESSSStarResidual(snes, ss->u, ss->c));
  PetscCall(CorrectFreeDofs(snes, SSSTAR_EQUILIBRIUM_RTOL, 0.0, &solved));
  if (solved) PetscCall(VecNorm(ss->c, NORM_INFINITY, &cmax));
  if (!solved || PetscIsInfOrNanReal(cmax)) {
    PetscCall(VecCopy(ss->ut, ss->u));
    PetscCall(SNESSSStarResidual(snes, ss->u, ss->c));
  }
  PetscCall(SetLoadScale(snes));
  PetscFunctionReturn(0);
}

/*
   Whole body: the free dofs of u put in equilibrium with its contact dofs (K u - b = 0 there), and the load reduced
   to the contact dofs, f = -(K u0 - b)_C with u0 in equilibrium and u0_C = 0: what a reduction would give. Into
   ss->scale, ss->fnorm_inf; u and c = K u - b on return.
*/
static PetscErrorCode Equilibrate(SNES snes)
{
  SNES_SSStar *ss = (SNES_SSStar *)snes->data;
  PetscReal    unorm, floor;
  Vec          uC = ss->ut;

  PetscFunctionBegin;
  if (ss->problem.nonlinear) {
    PetscCall(EquilibrateNonlinear(snes));
    PetscFunctionReturn(0);
  }
  PetscCall(SNESSSStarContactNorm(snes, ss->u, &unorm));
  /* a coarser mesh's solution with its load's scale: no solve. Its free dofs are the finer mesh's interpolation of
     the coarser mesh's equilibrium; the first Newton step puts them in equilibrium with its contact dofs, as it would
     after the correction below (solved no tighter than that step) */
  ss->freeUnbalanced = (PetscBool)(ss->coarseNodes > 0 && unorm > 0);
  if (ss->freeUnbalanced) {
    PetscCall(SNESSSStarResidual(snes, ss->u, ss->c));
    PetscCall(SetCoarseLoadScale(snes));
    PetscFunctionReturn(0);
  }
  PetscCall(VecCopy(ss->u, uC));
  /* from u = 0: u0, and f = -(K u0 - b)_C in the global frame; with a given u, u0 gives only the scale of f */
  PetscCall(VecZeroEntries(ss->u));
  PetscCall(SNESSSStarResidual(snes, ss->u, ss->c));
  PetscCall(CorrectFreeDofs(snes, unorm == 0 ? SSSTAR_EQUILIBRIUM_RTOL : SSSTAR_SCALE_RTOL, 0.0, NULL));
  PetscCall(SetLoadScale(snes));
  if (unorm == 0) PetscFunctionReturn(0);
  /* a given u: its free dofs corrected from its own, relative to its own residual (not to the whole load's, from u0),
     down to the Newton steps' floor: a guess already in equilibrium (the step before on a load path) keeps its
     accuracy, which a body that nearly floats needs (from u0, a relative 1e-4 of the load left a stiff block on a
     soft spring 300 times the stopping threshold away, and the path's release stagnated there). No tighter than the
     first Newton step solves after it (etaMax of its own residual): the steps equilibrate the free dofs on their way
     (a nested iteration's start at level 16: 9 -> 1 Krylov iterations, the same Newton steps) */
  PetscCall(VecCopy(uC, ss->u));
  PetscCall(SNESSSStarResidual(snes, ss->u, ss->c));
  PetscCall(SNESSSStarLinearFloor(snes, &floor));
  PetscCall(CorrectFreeDofs(snes, ss->etaMax, floor, NULL));
  PetscFunctionReturn(0);
}

/* The load's scale of this solve and c = A u - f at the first iterate (on the whole body u's free dofs in equilibrium,
   unless a coarser mesh's scale was given); a coarser mesh's scale serves one solve */
PetscErrorCode SNESSSStarStart(SNES snes)
{
  SNES_SSStar   *ss = (SNES_SSStar *)snes->data;
  SSStarProblem *pb = &ss->problem;

  PetscFunctionBegin;
  ss->freeUnbalanced = PETSC_FALSE;
  if (pb->wholeBody) PetscCall(Equilibrate(snes));
  else {
    PetscReal fnorm, fmax;

    PetscCall(VecNorm(pb->f, NORM_2, &fnorm));
    PetscCall(VecNorm(pb->f, NORM_INFINITY, &fmax));
    PetscCall(SetScale(snes, fnorm, fmax, "of the reduced load"));
    PetscCall(SNESSSStarResidual(snes, ss->u, ss->c));
  }
  ss->coarseNodes = 0;
  PetscFunctionReturn(0);
}

/*
   ||z_0|| as the inexact Newton forcing measures it (eta_k = ||z_k||/||z_0||, the first step to eta_max ||z_0||): the
   first iterate's ||z||, or, when its free dofs were left out of equilibrium (a coarser mesh's start), the norm of z at
   its contact dofs alone. There the free dofs' residual, the interpolation's (9 times the contact dofs' part at
   prism level 16), is no measure of the contact problem's distance: a first step to a tenth of it left the free dofs
   in the error that took prism level 24 a sixth Newton step. Once a start is in equilibrium z_0 is zero on them.
*/
PetscErrorCode SNESSSStarStartNorm(SNES snes, PetscReal znorm, PetscReal *z0)
{
  SNES_SSStar       *ss = (SNES_SSStar *)snes->data;
  const PetscScalar *za;
  PetscReal          sum = 0;

  PetscFunctionBegin;
  *z0 = znorm;
  if (!ss->freeUnbalanced) PetscFunctionReturn(0);
  PetscCall(VecGetArrayRead(ss->z, &za));
  for (PetscInt k = 0; k < 3 * ss->contact.nnodes; k++) sum += PetscRealPart(za[ss->problem.layoutDofs[k]] * PetscConj(za[ss->problem.layoutDofs[k]]));
  PetscCall(VecRestoreArrayRead(ss->z, &za));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &sum, 1, MPIU_REAL, MPIU_SUM, PetscObjectComm((PetscObject)snes)));
  *z0 = PetscSqrtReal(sum);
  PetscCall(PetscInfo(snes, "||z_0|| of the forcing at the contact dofs: %g (the free dofs' residual of the start left to the first Newton step)\n", (double)*z0));
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarSetCoarseLoadScale - the load's scale of the next solve taken from a solve of the same problem on a
   coarser mesh (nested iteration): on the whole body the start then needs no linear solve, and the finest mesh sets
   up its multigrid once, for its first Newton step

   Logically Collective

   Input Parameters:
+  snes   - the SNES of the finer mesh
-  coarse - an ssstar SNES that solved the problem on a coarser mesh of the same contact surface

   Notes:
   The load's scale is ||gamma f|| and ||f||_inf with f the load reduced to the contact dofs (the stopping rule's
   displacement scale where ||u|| is small, and the law residual's floors). Without this call a solve on the whole body
   from a given u gets it from a loose solve from u = 0 (to a relative 1e-1, the scale to about 1e-3) and corrects the
   given u's free dofs: two linear solves with the contact dofs held, which need a multigrid of their own. From a
   coarser mesh the forces are carried as the contact forces scale with the area each of the n contact nodes carries:
   ||f||_inf times n_coarse/n, ||f|| times sqrt(n_coarse/n), gamma this mesh's; the prism's level 8 gives level 16's
   ||gamma f|| to 0.6 % and its ||f||_inf to 17 % (the largest force sits at the held edge, a singularity), a change
   of the stopping threshold only where ||gamma f|| sets it, and of the law residual's floors. The given u's free dofs are
   then put in equilibrium by the first Newton step. The scale serves the next SNESSolve() only, with a nonzero initial
   guess on the whole body of a linear problem; otherwise it is ignored. SSStarSceneSolveNested() calls it.

   Level: developer

.seealso: `SSStarSceneSolveNested()`, `SNESConvergedSSStar()`
@*/
PetscErrorCode SNESSSStarSetCoarseLoadScale(SNES snes, SNES coarse)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscValidHeaderSpecific(coarse, SNES_CLASSID, 2);
  PetscTryMethod(snes, "SNESSSStarSetCoarseLoadScale_C", (SNES, SNES), (snes, coarse));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarSetCoarseLoadScale_SSStar(SNES snes, SNES coarse)
{
  SNES_SSStar *ss = (SNES_SSStar *)snes->data, *sc;
  PetscBool    isssstar;

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)coarse, SNESSSSTAR, &isssstar));
  PetscCheck(isssstar, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_WRONG, "ssstar: the coarser mesh's solver of SNESSSStarSetCoarseLoadScale() is not of type ssstar");
  sc = (SNES_SSStar *)coarse->data;
  PetscCheck(sc->scaling > 0, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_WRONGSTATE, "ssstar: the coarser mesh's solver of SNESSSStarSetCoarseLoadScale() has not solved");
  ss->coarseLoad[0] = sc->scale / sc->scaling;
  ss->coarseLoad[1] = sc->fnorm_inf;
  PetscCall(GlobalContactNodes(coarse, &ss->coarseNodes));
  PetscFunctionReturn(0);
}

static const SSStarComposed Composed[] = {
    {"SNESSSStarSetCoarseLoadScale_C", (PetscVoidFunction)SNESSSStarSetCoarseLoadScale_SSStar},
};

PetscErrorCode SNESSSStarComposeStart(SNES snes, PetscBool on)
{
  PetscFunctionBegin;
  PetscCall(SNESSSStarComposeTable(snes, Composed, PETSC_STATIC_ARRAY_LENGTH(Composed), on));
  PetscFunctionReturn(0);
}
