/*
   The globalization of ssstar: the plain iteration of docs/derivation.md section 7 converges from a good starting point
   only, and may cycle or stall far from the solution (docs/guide/converged.md, "When it does not converge"). Here:

   - the merit function is ||z||, the norm of the approximation step (the natural residual: zero exactly at the
     solutions, in the units of u);
   - a Newton step is accepted when it decreases the merit enough, else it is damped (alpha = 1/2, 1/4, ... down to
     dampingMin): ||z+|| <= (1 - sigma alpha + eta_k) ||z|| at iteration k. eta_k = 2^-(k+1) is a summable
     allowance, as in Li and Fukushima's derivative-free line search: the first steps of a healthy iteration may
     raise ||z|| a little, as they do at level 10 of the default scene, by a factor e at most in all;
   - on the whole body a Newton step solved inexactly (a Krylov residual bounded by a fraction of ||z||) that fails
     the test is first solved on to the floor tolerance and tried again: where the body nearly floats its error is far
     larger than its residual, and the damping would search along a wrong direction (ssstar.c: after a remedy every
     step is solved so);
   - when no damping decreases the merit (a local minimum of ||z||, a kink), the full step is taken anyway or the
     scaling gamma of the approximation step is doubled, in turn; gamma > 0 does not change the solutions (section 6)
     but changes the approximation step, the states and the Newton step;
   - a singular Newton matrix gets a regularized step (ssstar.c), and if that is singular too, a few fixed-point
     iterations of the approximation step with a gamma small enough for them to be contractive;
   - cycles (the states of two iterations ago and ||z|| back to its value then, twice in a row) are broken by a
     rescaling, and a solve whose smallest ||z|| has not decreased for stagnationIts iterations stops.
   Without globalization the detection still stops the plain iteration, with an honest reason.
*/
#include "ssstarimpl.h"

const char *const SSStarRemedies[] = {"damped steps", "full steps after a failed line search", "rescalings of gamma", "regularized Newton steps", "fixed-point rounds", "SSStarRemedy", "SSSTAR_REMEDY_", NULL};

/* Armijo's sufficient decrease of the merit: ||z(u + alpha du)|| <= (1 - SIGMA alpha + eta_k) ||z(u)|| */
#define SSSTAR_SIGMA 1e-4
/* ||z|| "back to its value two iterations ago": within this relative distance */
#define SSSTAR_CYCLE_TOL 1e-2
/* a slip that reverses twice is a cycle when ||z|| is back within this relative distance of its value two iterations
   ago (section 19c: looser than SSSTAR_CYCLE_TOL, for the inexact steps of the whole body) */
#define SSSTAR_SLIP_CYCLE_TOL 0.1
/* gamma is doubled at most this often in a solve (up to 2^10 times its initial value) */
#define SSSTAR_MAX_RESCALES 10
/* fixed-point iterations of the approximation step in one round */
#define SSSTAR_FIXED_POINT_ITS 5

PetscErrorCode SSStarGlobalizationDestroy(SSStarGlobalization *glob)
{
  PetscFunctionBegin;
  PetscCall(PetscFree(glob->older[0]));
  PetscCall(PetscFree(glob->older[1])); /* apart: Detect() swaps them */
  PetscCall(PetscFree(glob->slip));
  glob->nnodes = 0;
  PetscFunctionReturn(0);
}

/* A new solve: the history, the counts and gamma0 start afresh */
PetscErrorCode SSStarGlobalizationBegin(SNES snes)
{
  SNES_SSStar         *ss   = (SNES_SSStar *)snes->data;
  SSStarGlobalization *glob = &ss->glob;

  PetscFunctionBegin;
  if (glob->nnodes != ss->contact.nnodes || !glob->older[0]) {
    PetscCall(SSStarGlobalizationDestroy(glob));
    glob->nnodes = ss->contact.nnodes;
    PetscCall(PetscMalloc1(glob->nnodes, &glob->older[0]));
    PetscCall(PetscMalloc1(glob->nnodes, &glob->older[1]));
    PetscCall(PetscMalloc1(3 * glob->nnodes + 1, &glob->slip));
  }
  PetscCall(PetscArrayzero(glob->slip, 3 * glob->nnodes));
  glob->reversed   = 0;
  glob->shownStuck = 0;
  glob->stuck      = 0;
  glob->zbest      = PETSC_MAX_REAL;
  glob->kbest      = 0;
  glob->nhist      = 0;
  glob->recurred   = PETSC_FALSE;
  glob->lsFailures = 0;
  glob->cycles     = 0;
  glob->gamma0     = ss->scaling;
  glob->alpha      = 0;
  glob->shownAlpha = 0;
  glob->detected   = SSSTAR_DETECTED_NONE;
  glob->flipping   = 0;
  PetscCall(PetscArrayzero(glob->counts, SSSTAR_NUM_REMEDIES));
  PetscCall(PetscArrayzero(glob->pending, SSSTAR_NUM_REMEDIES));
  PetscCall(PetscArrayzero(glob->shown, SSSTAR_NUM_REMEDIES));
  PetscFunctionReturn(0);
}

/* A remedy applied on the way to the next iterate */
PetscErrorCode SSStarGlobalizationRecord(SSStarGlobalization *glob, SSStarRemedy remedy)
{
  PetscFunctionBegin;
  glob->counts[remedy]++;
  glob->pending[remedy] = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/*
   Iterate k with ||z|| = znorm and the states of ss->states: records them and detects a cycle (the states of
   iterate k - 2 and ||z|| within SSSTAR_CYCLE_TOL of its value then, at k and at k - 1) or stagnation (no new
   smallest ||z|| for stagnationIts iterations). The remedies recorded since the last iterate led to this one:
   -snes_ssstar_monitor_states shows them with it.
*/
PetscErrorCode SSStarGlobalizationDetect(SNES snes, PetscInt k, PetscReal znorm)
{
  SNES_SSStar         *ss   = (SNES_SSStar *)snes->data;
  SSStarGlobalization *glob = &ss->glob;
  PetscInt             local[3] = {0, 0, 0}; /* nodes not in their state of k - 2, flipping with period 2, not in their state of k - 1 */
  PetscBool            recurs = PETSC_FALSE;
  SSStarState         *oldest;

  PetscFunctionBegin;
  PetscCall(PetscArraycpy(glob->shown, glob->pending, SSSTAR_NUM_REMEDIES));
  PetscCall(PetscArrayzero(glob->pending, SSSTAR_NUM_REMEDIES));
  glob->shownAlpha = glob->alpha;
  glob->alpha      = 0;
  glob->shownStuck = glob->reversed;
  glob->reversed   = 0;
  for (PetscInt j = 3; j > 0; j--) glob->zhist[j] = glob->zhist[j - 1];
  glob->zhist[0] = znorm;
  glob->nhist++;
  if (znorm < glob->zbest) {
    glob->zbest = znorm;
    glob->kbest = k;
  }
  glob->flipping = 0;
  glob->changed  = -1;
  if (glob->nhist >= 2) {
    for (PetscInt i = 0; i < glob->nnodes; i++) {
      if (ss->states[i] != glob->older[0][i]) local[2]++;
      if (glob->nhist < 3) continue;
      if (ss->states[i] != glob->older[1][i]) local[0]++;
      else if (ss->states[i] != glob->older[0][i]) local[1]++;
    }
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, local, 3, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)snes)));
    glob->changed = local[2];
  }
  if (glob->nhist >= 3) {
    glob->flipping = local[1];
    recurs         = (PetscBool)(local[0] == 0 && PetscAbsReal(znorm - glob->zhist[2]) <= SSSTAR_CYCLE_TOL * znorm);
  }
  if (recurs && glob->recurred) {
    glob->detected = SSSTAR_DETECTED_CYCLE;
    glob->cycles++;
  } else if (k - glob->kbest >= glob->stagnationIts) glob->detected = SSSTAR_DETECTED_STAGNATION;
  else glob->detected = SSSTAR_DETECTED_NONE;
  glob->recurred = recurs;
  /* the states of k become those of k - 1 */
  oldest         = glob->older[1];
  glob->older[1] = glob->older[0];
  glob->older[0] = oldest;
  PetscCall(PetscArraycpy(glob->older[0], ss->states, glob->nnodes));
  PetscFunctionReturn(0);
}

/*
   Before the Newton step of iterate k (docs/derivation.md section 19c): a node sliding at k and at k - 1 whose slip d_t
   points against the one at k - 1 reversed, i.e. crossed the kink d_t = 0 of its law between the two iterates. Nodes
   that reversed at k - 1 too, while ||z|| came back to within SSSTAR_SLIP_CYCLE_TOL of its value two iterations ago,
   flip across the kink in a cycle: the two-cycle of (12.5) on a slow mode that the approximation step at gamma does not
   resolve (a stiff body on a soft spring: the slide flips by +-phi N/k, every node slides at every iterate, so the
   cycle detection on the states does not see it). Their Newton element for this step is the one at the kink: stuck
   where they are (M3+, target d = 0). glob->slip holds each node's d_t at k - 1 (0 unless it slid) and 1 where it
   reversed there.
*/
PetscErrorCode SSStarGlobalizationReversedSlips(SNES snes)
{
  SNES_SSStar         *ss      = (SNES_SSStar *)snes->data;
  SSStarGlobalization *glob    = &ss->glob;
  const PetscBool      cycling = (PetscBool)(glob->nhist >= 3 && glob->zhist[0] > (1 - SSSTAR_SLIP_CYCLE_TOL) * glob->zhist[2]);
  const PetscScalar   *ua;
  PetscScalar         *za, *da;
  PetscInt             stuck = 0;

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(ss->u, &ua));
  PetscCall(VecGetArray(ss->z, &za));
  PetscCall(VecGetArray(ss->d, &da));
  for (PetscInt i = 0; i < glob->nnodes; i++) {
    PetscReal      *s       = &glob->slip[3 * i];
    const PetscReal t[2]    = {PetscRealPart(da[3 * i]), PetscRealPart(da[3 * i + 1])};
    const PetscBool sliding = (PetscBool)(ss->states[i] == SSSTAR_STATE_M1);
    const PetscBool reverse = (PetscBool)(sliding && s[0] * t[0] + s[1] * t[1] < 0);

    if (reverse && s[2] > 0 && cycling) {
      SNESSSStarStickNode(ss, i, ua, za, da);
      s[0] = s[1] = s[2] = 0;
      stuck++;
    } else {
      s[0] = sliding ? t[0] : 0;
      s[1] = sliding ? t[1] : 0;
      s[2] = reverse ? 1 : 0;
    }
  }
  PetscCall(VecRestoreArray(ss->d, &da));
  PetscCall(VecRestoreArray(ss->z, &za));
  PetscCall(VecRestoreArrayRead(ss->u, &ua));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &stuck, 1, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)snes)));
  glob->reversed = stuck;
  glob->stuck += stuck;
  if (stuck) PetscCall(PetscInfo(snes, "%" PetscInt_FMT " sliding nodes reversed their slip twice in a row, ||z|| back to %g of its value then: their step stuck at the kink\n", stuck, (double)(glob->zhist[0] / glob->zhist[2])));
  PetscFunctionReturn(0);
}

/*
   Doubles gamma (section 6: the same solutions, another approximation step). The history of ||z|| is forgotten:
   ||z|| with another gamma is another merit function.
*/
static PetscErrorCode Rescale(SNES snes)
{
  SNES_SSStar         *ss   = (SNES_SSStar *)snes->data;
  SSStarGlobalization *glob = &ss->glob;

  PetscFunctionBegin;
  ss->scaling *= 2;
  ss->scale *= 2;
  PetscCall(SSStarNewtonSetScaling(ss->newton, ss->scaling));
  glob->zbest    = PETSC_MAX_REAL;
  glob->nhist    = 0;
  glob->recurred = PETSC_FALSE;
  PetscCall(SSStarGlobalizationRecord(glob, SSSTAR_REMEDY_RESCALE));
  PetscFunctionReturn(0);
}

static PetscBool CanRescale(SNES_SSStar *ss)
{
  return (PetscBool)(ss->glob.counts[SSSTAR_REMEDY_RESCALE] < SSSTAR_MAX_RESCALES);
}

/* A detected cycle: broken by a rescaling while there are rescalings left */
PetscErrorCode SSStarGlobalizationBreakCycle(SNES snes, PetscBool *broken)
{
  SNES_SSStar *ss = (SNES_SSStar *)snes->data;

  PetscFunctionBegin;
  *broken = CanRescale(ss);
  if (*broken) PetscCall(Rescale(snes));
  PetscFunctionReturn(0);
}

/* The iterate becomes (v, cv) */
static PetscErrorCode Accept(SNES_SSStar *ss, Vec v, Vec cv)
{
  PetscFunctionBegin;
  PetscCall(VecCopy(v, ss->u));
  PetscCall(VecCopy(cv, ss->c));
  PetscFunctionReturn(0);
}

/* The full Newton step: ut = u + dv (dv in the global frame), ct = A ut - f, and ||z|| there */
static PetscErrorCode TryFullStep(SNES snes, PetscReal *mfull)
{
  SNES_SSStar *ss = (SNES_SSStar *)snes->data;

  PetscFunctionBegin;
  PetscCall(VecWAXPY(ss->ut, 1.0, ss->dv, ss->u));
  PetscCall(SNESSSStarResidual(snes, ss->ut, ss->ct));
  PetscCall(SNESSSStarApproximationStep(snes, ss->ut, ss->ct, mfull));
  PetscFunctionReturn(0);
}

/*
   The step of iteration k from u along the Newton step ss->dv (global frame), ||z|| = znorm at u. Without globalization
   the full step, unless ||z|| is NaN or Inf there (F not defined: then halved until it is, else reason NAN and u stays
   the last finite iterate). With it: the full step if it decreases ||z|| enough, else the first damped one that does,
   else a remedy: the full step anyway (odd failures) or a doubled gamma without a step (even failures). reason is set
   when nothing can be done. A polishing step (||z|| at its threshold, the law residual rho not: section 12) is taken
   whole once the states have settled (no node changed its state at u: the local regime, the creep and the round-off
   floor of section 19, where the decrease of ||z|| says nothing), and globalized as any other step before: section
   19b (at a loose rtol the threshold is met with nodes still changing state, and whole steps crept along the soft
   modes that ||z|| hardly weighs).
*/
PetscErrorCode SSStarGlobalizationStep(SNES snes, PetscInt k, PetscReal znorm, PetscBool polishing, SSStarReason *reason)
{
  SNES_SSStar         *ss    = (SNES_SSStar *)snes->data;
  SSStarGlobalization *glob  = &ss->glob;
  const PetscReal      eta   = PetscPowReal(0.5, (PetscReal)(k + 1));
  const PetscBool      whole = (PetscBool)(polishing && glob->changed == 0);
  PetscReal            mfull, m, alpha;
  PetscBool            finite, full;

  PetscFunctionBegin;
  *reason = SSSTAR_REASON_ITERATING;
  PetscCall(PetscLogEventBegin(SSSTAR_LineSearch, snes, 0, 0, 0));
  PetscCall(TryFullStep(snes, &mfull));
  /* an inexact step (whole body) that fails is solved on to the floor tolerance first: its error, which the linear
     residual does not show where the body nearly floats, would mislead the damping and the remedies */
  if (glob->on && !whole && !(mfull <= (1 - SSSTAR_SIGMA + eta) * znorm)) {
    PetscBool refined;

    PetscCall(SNESSSStarRefineNewtonStep(snes, znorm, &refined));
    if (refined) PetscCall(SNESSSStarExtendFreeStep(snes)); /* floating bodies (balance.c) */
    if (refined) PetscCall(TryFullStep(snes, &mfull));
  }
  finite = (PetscBool)!PetscIsInfOrNanReal(mfull);
  if (finite && (!glob->on || whole || mfull <= (1 - SSSTAR_SIGMA + eta) * znorm)) {
    PetscCall(Accept(ss, ss->ut, ss->ct));
    glob->alpha = 1;
    PetscCall(PetscLogEventEnd(SSSTAR_LineSearch, snes, 0, 0, 0));
    PetscFunctionReturn(0);
  }
  /* damped: u + alpha dv, and P (u + alpha dv) - f = c + alpha (ct - c); a nonlinear c evaluated there. A full step
     where ||z|| is not finite (F not defined there: SNESSetFunctionDomainError(), an inverted cell of a hyperelastic
     body) is halved until it is, as PETSc's line searches do, also without globalization or when polishing */
  for (alpha = 0.5; alpha >= glob->dampingMin; alpha /= 2) {
    PetscCall(VecWAXPY(ss->ua, alpha, ss->dv, ss->u));
    if (ss->problem.nonlinear) PetscCall(SNESSSStarResidual(snes, ss->ua, ss->ca));
    else PetscCall(VecAXPBYPCZ(ss->ca, 1 - alpha, alpha, 0.0, ss->c, ss->ct));
    PetscCall(SNESSSStarApproximationStep(snes, ss->ua, ss->ca, &m));
    if (!PetscIsInfOrNanReal(m) && (!glob->on || whole || m <= (1 - SSSTAR_SIGMA * alpha + eta) * znorm)) {
      PetscCall(Accept(ss, ss->ua, ss->ca));
      glob->alpha = alpha;
      PetscCall(SSStarGlobalizationRecord(glob, SSSTAR_REMEDY_DAMPED));
      PetscCall(PetscLogEventEnd(SSSTAR_LineSearch, snes, 0, 0, 0));
      PetscFunctionReturn(0);
    }
  }
  PetscCall(PetscLogEventEnd(SSSTAR_LineSearch, snes, 0, 0, 0));
  if (!glob->on || whole) { /* no damped step where ||z|| is finite */
    *reason = SSSTAR_REASON_NAN;
    PetscFunctionReturn(0);
  }
  /* no damping decreases ||z||: u is near a local minimum (or a kink) of ||z|| that is not a solution */
  glob->lsFailures++;
  full = (PetscBool)(finite && (glob->lsFailures % 2 == 1 || !CanRescale(ss)));
  if (full) {
    PetscCall(Accept(ss, ss->ut, ss->ct));
    glob->alpha = 1;
    PetscCall(SSStarGlobalizationRecord(glob, SSSTAR_REMEDY_FULL_STEP));
  } else if (CanRescale(ss)) PetscCall(Rescale(snes));
  else *reason = SSSTAR_REASON_STAGNATION;
  PetscFunctionReturn(0);
}

/*
   No Newton step exists (its matrix is singular, regularized or not): SSSTAR_FIXED_POINT_ITS iterations
   u <- u + z of the approximation step with gamma = 1/(the largest sum |K_ij| of a contact row), which bounds
   1/lambda_max(P): a projected (and, with friction, proximal) gradient step short enough to decrease the energy of
   the frictionless and Tresca problems. improved: they decreased ||z|| (with the solve's gamma) enough, and the
   iterate moved there.
*/
PetscErrorCode SSStarGlobalizationFixedPoint(SNES snes, PetscReal znorm, PetscBool *improved)
{
  SNES_SSStar *ss    = (SNES_SSStar *)snes->data;
  PetscReal    gamma = ss->scaling, znew;
  PetscBool    solved = PETSC_TRUE;

  PetscFunctionBegin;
  PetscCall(VecCopy(ss->u, ss->ut));
  PetscCall(VecCopy(ss->c, ss->ct));
  ss->scaling = 1 / ss->problem.maxRowSum;
  for (PetscInt i = 0; i < SSSTAR_FIXED_POINT_ITS && solved; i++) {
    PetscCall(SNESSSStarApproximationStep(snes, ss->ut, ss->ct, &znew));
    PetscCall(SNESSSStarFixedPointStep(snes, ss->ut, ss->ct, &solved));
  }
  ss->scaling = gamma;
  PetscCall(SNESSSStarApproximationStep(snes, ss->ut, ss->ct, &znew));
  *improved = (PetscBool)(solved && znew <= (1 - SSSTAR_SIGMA) * znorm);
  if (*improved) PetscCall(Accept(ss, ss->ut, ss->ct));
  PetscCall(SSStarGlobalizationRecord(&ss->glob, SSSTAR_REMEDY_FIXED_POINT));
  PetscFunctionReturn(0);
}

/* For -snes_ssstar_monitor_states: "; damped step alpha = 0.25; cycle detected (4 nodes flip with period 2)" */
PetscErrorCode SSStarGlobalizationFormatEvents(SSStarGlobalization *glob, char buf[], size_t len)
{
  static const char *const label[] = {"damped step", "full step after a failed line search", "gamma doubled", "regularized Newton step", "fixed-point round"};
  size_t                   used    = 0;

  PetscFunctionBegin;
  buf[0] = 0;
  for (PetscInt r = 0; r < SSSTAR_NUM_REMEDIES; r++) {
    if (!glob->shown[r]) continue;
    if (r == SSSTAR_REMEDY_DAMPED) PetscCall(PetscSNPrintf(buf + used, len - used, "; %s alpha = %g", label[r], (double)glob->shownAlpha));
    else PetscCall(PetscSNPrintf(buf + used, len - used, "; %s", label[r]));
    PetscCall(PetscStrlen(buf, &used));
  }
  if (glob->detected == SSSTAR_DETECTED_CYCLE) PetscCall(PetscSNPrintf(buf + used, len - used, "; cycle detected"));
  else if (glob->detected == SSSTAR_DETECTED_STAGNATION) PetscCall(PetscSNPrintf(buf + used, len - used, "; no decrease of ||z|| for %" PetscInt_FMT " iterations", glob->stagnationIts));
  PetscCall(PetscStrlen(buf, &used));
  if (glob->flipping) PetscCall(PetscSNPrintf(buf + used, len - used, "; %" PetscInt_FMT " nodes flip with period 2", glob->flipping));
  PetscCall(PetscStrlen(buf, &used));
  if (glob->shownStuck) PetscCall(PetscSNPrintf(buf + used, len - used, "; %" PetscInt_FMT " nodes stuck at a reversed slip", glob->shownStuck));
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarGlobalizationView(SSStarGlobalization *glob, PetscViewer viewer)
{
  PetscFunctionBegin;
  if (glob->on) PetscCall(PetscViewerASCIIPrintf(viewer, "  globalization: damped steps on ||z|| (alpha >= %g), remedies on; stop after %" PetscInt_FMT " iterations without a smaller ||z||\n", (double)glob->dampingMin, glob->stagnationIts));
  else PetscCall(PetscViewerASCIIPrintf(viewer, "  globalization: off (the plain iteration); stop after %" PetscInt_FMT " iterations without a smaller ||z||, or on a cycle\n", glob->stagnationIts));
  PetscFunctionReturn(0);
}

/* The remedies of the last solve, one line: "damped steps 2, full steps after a failed line search 0, ..." */
PetscErrorCode SSStarGlobalizationViewCounts(SSStarGlobalization *glob, PetscViewer viewer)
{
  PetscFunctionBegin;
  PetscCall(PetscViewerASCIIPrintf(viewer, "  remedies:"));
  PetscCall(PetscViewerASCIIUseTabs(viewer, PETSC_FALSE));
  for (PetscInt r = 0; r < SSSTAR_NUM_REMEDIES; r++) PetscCall(PetscViewerASCIIPrintf(viewer, "%s %s %" PetscInt_FMT, r ? "," : "", SSStarRemedies[r], glob->counts[r]));
  PetscCall(PetscViewerASCIIPrintf(viewer, "; cycles detected %" PetscInt_FMT "; nodes stuck at a reversed slip %" PetscInt_FMT "\n", glob->cycles, glob->stuck));
  PetscCall(PetscViewerASCIIUseTabs(viewer, PETSC_TRUE));
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarSetGlobalization - turns the globalization of ssstar on or off and sets its parameters

   Logically Collective

   Input Parameters:
+  snes          - the SNES
.  on            - PETSC_TRUE (default): damped steps on the merit function ||z|| and remedies (a full step or a
                   doubled gamma after a failed line search, a regularized Newton step or fixed-point iterations for a
                   singular Newton matrix, a doubled gamma on a cycle, the stuck element for a sliding node whose
                   slip reversed twice in a cycle, docs/derivation.md section 19c); PETSC_FALSE: the plain iteration
.  dampingMin    - the smallest damping factor of the line search (default 1/64), or PETSC_DEFAULT
-  stagnationIts - stop (SNES_DIVERGED_LOCAL_MIN, sub-reason STAGNATION) after this many iterations without a smaller
                   ||z|| (default 20), or PETSC_DEFAULT

   Options Database Keys:
+  -snes_ssstar_globalization <true> - on or off
.  -snes_ssstar_damping_min <0.015625> - dampingMin
-  -snes_ssstar_stagnation_its <20> - stagnationIts

   Notes:
   Cycles and stagnation are detected in both cases; without globalization they end the solve. docs/guide/converged.md, "When it does
   not converge"; SNESSSStarGetRemedyCounts() tells what the last solve needed.

   Level: advanced

.seealso: `SNESSSStarGetRemedyCounts()`, `SNESSSStarGetReason()`
@*/
PetscErrorCode SNESSSStarSetGlobalization(SNES snes, PetscBool on, PetscReal dampingMin, PetscInt stagnationIts)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscValidLogicalCollectiveBool(snes, on, 2);
  PetscValidLogicalCollectiveReal(snes, dampingMin, 3);
  PetscValidLogicalCollectiveInt(snes, stagnationIts, 4);
  PetscTryMethod(snes, "SNESSSStarSetGlobalization_C", (SNES, PetscBool, PetscReal, PetscInt), (snes, on, dampingMin, stagnationIts));
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

/*@
   SNESSSStarGetRemedyCounts - how often the last solve used each remedy of the globalization

   Not Collective

   Input Parameter:
.  snes - the SNES

   Output Parameter:
.  counts - SSSTAR_NUM_REMEDIES counts, in SSStarRemedy order (SSStarRemedies[] names them)

   Level: advanced

.seealso: `SNESSSStarSetGlobalization()`, `SNESSSStarGetReason()`
@*/
PetscErrorCode SNESSSStarGetRemedyCounts(SNES snes, PetscInt counts[SSSTAR_NUM_REMEDIES])
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscUseMethod(snes, "SNESSSStarGetRemedyCounts_C", (SNES, PetscInt[]), (snes, counts));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarGetRemedyCounts_SSStar(SNES snes, PetscInt counts[])
{
  PetscFunctionBegin;
  PetscCall(PetscArraycpy(counts, ((SNES_SSStar *)snes->data)->glob.counts, SSSTAR_NUM_REMEDIES));
  PetscFunctionReturn(0);
}

/* The implementations of the public functions above, composed on the SNES (SNESSSStarComposeFunctions()) */
static const SSStarComposed Composed[] = {
    {"SNESSSStarSetGlobalization_C", (PetscVoidFunction)SNESSSStarSetGlobalization_SSStar},
    {"SNESSSStarGetRemedyCounts_C", (PetscVoidFunction)SNESSSStarGetRemedyCounts_SSStar},
};

PetscErrorCode SNESSSStarComposeGlobalization(SNES snes, PetscBool on)
{
  PetscFunctionBegin;
  PetscCall(SNESSSStarComposeTable(snes, Composed, PETSC_STATIC_ARRAY_LENGTH(Composed), on));
  PetscFunctionReturn(0);
}
