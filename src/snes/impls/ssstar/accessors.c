/*
   The implementations of the SNES type "ssstar" of the public setters and getters (interface.c calls them through the
   functions composed on the SNES): they check their input and hand it to the contact (contact.c), the problem
   (problem.c), the Newton step (newton.c) or the globalization.
*/
#include "ssstarimpl.h"
#include "laws/lawimpl.h"

static PetscErrorCode SNESSSStarSetFrictionLaw_SSStar(SNES snes, const char law[])
{
  PetscFunctionBegin;
  PetscCall(SSStarContactSetLaw(&((SNES_SSStar *)snes->data)->contact, law));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarGetFrictionLaw_SSStar(SNES snes, const char *law[])
{
  PetscFunctionBegin;
  PetscCall(SSStarLawGetInfo(((SNES_SSStar *)snes->data)->contact.law->index, law, NULL, NULL, NULL));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarSetLawParameter_SSStar(SNES snes, const char name[], PetscInt n, const PetscReal values[])
{
  PetscFunctionBegin;
  PetscCall(SSStarContactSetParameter(PetscObjectComm((PetscObject)snes), &((SNES_SSStar *)snes->data)->contact, name, n, values));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarGetFriction_SSStar(SNES snes, PetscReal *friction)
{
  PetscInt  n;
  PetscBool set;

  PetscFunctionBegin;
  PetscCall(SSStarContactGetParameter(&((SNES_SSStar *)snes->data)->contact, "friction", &n, friction, &set));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarSetReductionType_SSStar(SNES snes, SSStarReductionType type)
{
  PetscFunctionBegin;
  PetscCall(SSStarProblemSetReductionType(&((SNES_SSStar *)snes->data)->problem, type));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarGetReductionType_SSStar(SNES snes, SSStarReductionType *type)
{
  PetscFunctionBegin;
  PetscCall(SSStarProblemGetReductionType(&((SNES_SSStar *)snes->data)->problem, type));
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
  PetscFunctionBegin;
  PetscCheck(gigabytes >= 0 && !PetscIsInfOrNanReal(gigabytes), PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_OUTOFRANGE, "-snes_ssstar_memory_limit %g: the limit must be > 0 GB (or 0 for the available memory)", (double)gigabytes);
  ((SNES_SSStar *)snes->data)->problem.memoryLimit = gigabytes;
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

  PetscFunctionBegin;
  if (n) PetscCall(SSStarContactGetNodeCount(snes, ct, n));
  if (dofs) *dofs = ct->dofs;
  if (normals) *normals = ct->normals;
  if (gaps) *gaps = ct->gaps;
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarGetContactOffsets_SSStar(SNES snes, Vec *offsets)
{
  PetscFunctionBegin;
  *offsets = ((SNES_SSStar *)snes->data)->contact.offsets;
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarGetTolerance_SSStar(SNES snes, PetscReal *tol)
{
  PetscFunctionBegin;
  *tol = ((SNES_SSStar *)snes->data)->tolerance;
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarSetLawTolerance_SSStar(SNES snes, PetscReal rtol)
{
  PetscFunctionBegin;
  PetscCheck(rtol >= 0 && rtol < 1, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_OUTOFRANGE, "-snes_ssstar_law_rtol %g must be in (0, 1), or 0 for max(-snes_rtol, 1e-8)", (double)rtol);
  ((SNES_SSStar *)snes->data)->lawRtol = rtol;
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
  SSStarProblem *pb = &((SNES_SSStar *)snes->data)->problem;

  PetscFunctionBegin;
  PetscCheck(pb->A, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_WRONGSTATE, "SNESSSStarGetReducedProblem: no reduced problem before SNESSolve()");
  PetscCheck(!pb->wholeBody, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_WRONGSTATE, "SNESSSStarGetReducedProblem: the last solve ran on the whole body (reduction none): no P was formed");
  if (P) *P = pb->A;
  if (f) *f = pb->f;
  PetscFunctionReturn(0);
}


/* The type's implementations of the public functions (interface.c calls them through these names) */
static const struct {
  const char       *name;
  PetscVoidFunction fn;
} Composed[] = {
    {"SNESSSStarSetContactNodes_C", (PetscVoidFunction)SNESSSStarSetContactNodes_SSStar},
    {"SNESSSStarSetContactOperator_C", (PetscVoidFunction)SNESSSStarSetContactOperator_SSStar},
    {"SNESSSStarSetFrictionLaw_C", (PetscVoidFunction)SNESSSStarSetFrictionLaw_SSStar},
    {"SNESSSStarGetFrictionLaw_C", (PetscVoidFunction)SNESSSStarGetFrictionLaw_SSStar},
    {"SNESSSStarSetLawParameter_C", (PetscVoidFunction)SNESSSStarSetLawParameter_SSStar},
    {"SNESSSStarGetFriction_C", (PetscVoidFunction)SNESSSStarGetFriction_SSStar},
    {"SNESSSStarSetNodeLawParameter_C", (PetscVoidFunction)SNESSSStarSetNodeLawParameter_SSStar},
    {"SNESSSStarSetNodeFrictionLaws_C", (PetscVoidFunction)SNESSSStarSetNodeFrictionLaws_SSStar},
    {"SNESSSStarGetNodeFrictionLaws_C", (PetscVoidFunction)SNESSSStarGetNodeFrictionLaws_SSStar},
    {"SNESSSStarGetNodeLawParameter_C", (PetscVoidFunction)SNESSSStarGetNodeLawParameter_SSStar},
    {"SNESSSStarSetReductionType_C", (PetscVoidFunction)SNESSSStarSetReductionType_SSStar},
    {"SNESSSStarGetReductionType_C", (PetscVoidFunction)SNESSSStarGetReductionType_SSStar},
    {"SNESSSStarSetPCReuse_C", (PetscVoidFunction)SNESSSStarSetPCReuse_SSStar},
    {"SNESSSStarSetKSPRtolMax_C", (PetscVoidFunction)SNESSSStarSetKSPRtolMax_SSStar},
    {"SNESSSStarSetMemoryLimit_C", (PetscVoidFunction)SNESSSStarSetMemoryLimit_SSStar},
    {"SNESSSStarSetScaling_C", (PetscVoidFunction)SNESSSStarSetScaling_SSStar},
    {"SNESSSStarGetScaling_C", (PetscVoidFunction)SNESSSStarGetScaling_SSStar},
    {"SNESSSStarSetStateTolerance_C", (PetscVoidFunction)SNESSSStarSetStateTolerance_SSStar},
    {"SNESSSStarSetMethod_C", (PetscVoidFunction)SNESSSStarSetMethod_SSStar},
    {"SNESSSStarGetMethod_C", (PetscVoidFunction)SNESSSStarGetMethod_SSStar},
    {"SNESSSStarGetStates_C", (PetscVoidFunction)SNESSSStarGetStates_SSStar},
    {"SNESSSStarGetReason_C", (PetscVoidFunction)SNESSSStarGetReason_SSStar},
    {"SNESSSStarGetTolerance_C", (PetscVoidFunction)SNESSSStarGetTolerance_SSStar},
    {"SNESSSStarSetLawTolerance_C", (PetscVoidFunction)SNESSSStarSetLawTolerance_SSStar},
    {"SNESSSStarGetLawResidual_C", (PetscVoidFunction)SNESSSStarGetLawResidual_SSStar},
    {"SNESSSStarGetContactNodes_C", (PetscVoidFunction)SNESSSStarGetContactNodes_SSStar},
    {"SNESSSStarSetContactOffsets_C", (PetscVoidFunction)SNESSSStarSetContactOffsets_SSStar},
    {"SNESSSStarGetContactOffsets_C", (PetscVoidFunction)SNESSSStarGetContactOffsets_SSStar},
    {"SNESSSStarGetReducedProblem_C", (PetscVoidFunction)SNESSSStarGetReducedProblem_SSStar},
    {"SNESSSStarSetGlobalization_C", (PetscVoidFunction)SNESSSStarSetGlobalization_SSStar},
    {"SNESSSStarGetRemedyCounts_C", (PetscVoidFunction)SNESSSStarGetRemedyCounts_SSStar},
    {"SNESSSStarSetLUReuse_C", (PetscVoidFunction)SNESSSStarSetLUReuse_SSStar},
    {"SNESSSStarGetNewtonStepCounts_C", (PetscVoidFunction)SNESSSStarGetNewtonStepCounts_SSStar},
    {"SNESSSStarGetConditionEstimate_C", (PetscVoidFunction)SNESSSStarGetConditionEstimate_SSStar},
    {"SNESSSStarSetLUThreads_C", (PetscVoidFunction)SNESSSStarSetLUThreads_SSStar},
};

/* on: composes every function on the SNES (SNESCreate_SSStar()); off: removes them (SNESDestroy_SSStar()) */
PetscErrorCode SNESSSStarComposeFunctions(SNES snes, PetscBool on)
{
  PetscFunctionBegin;
  for (size_t k = 0; k < PETSC_STATIC_ARRAY_LENGTH(Composed); k++) PetscCall(PetscObjectComposeFunction((PetscObject)snes, Composed[k].name, on ? Composed[k].fn : NULL));
  PetscFunctionReturn(0);
}
