/*
   The Newton step of ssstar: what every implementation shares (newtonimpl.h). The SNES creates one SSStarNewton and
   keeps it; each SNESSolve gives it the stiffness A and the name of the implementation that fits it (registered by
   newtonregall.c).
*/
#include "newtonimpl.h"
#include "../../../../sys/meminfo.h"

PetscFunctionList SSStarNewtonList = NULL;

/* Adds an implementation of the Newton step: create fills the ops (newtonimpl.h) */
PetscErrorCode SSStarNewtonRegister(const char name[], PetscErrorCode (*create)(SSStarNewton))
{
  PetscFunctionBegin;
  PetscCall(PetscFunctionListAdd(&SSStarNewtonList, name, create));
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarNewtonCreate(SNES snes, SSStarNewton *newton)
{
  PetscFunctionBegin;
  PetscCall(PetscNew(newton));
  (*newton)->snes      = snes;
  (*newton)->reuse     = 0;
  (*newton)->luThreads = 1;
  (*newton)->pcReuse   = SSSTAR_PC_REUSE_DEFAULT;
  (*newton)->plainDofs = SSSTAR_PLAIN_AGGREGATION_DOFS;
  (*newton)->smoothedFits = -1;
  (*newton)->overCorrection = SSSTAR_MG_OVERCORRECTION;
  (*newton)->wLevels        = SSSTAR_MG_W_LEVELS;
  (*newton)->rcond     = -1;
  (*newton)->rtol      = 1e-10;
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarNewtonSetReuse(SSStarNewton nt, PetscReal fraction)
{
  PetscFunctionBegin;
  nt->reuse = fraction;
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarNewtonGetReuse(SSStarNewton nt, PetscReal *fraction)
{
  PetscFunctionBegin;
  *fraction = nt->reuse;
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarNewtonSetPCReuse(SSStarNewton nt, PetscReal fraction)
{
  PetscFunctionBegin;
  nt->pcReuse = fraction;
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarNewtonGetPCReuse(SSStarNewton nt, PetscReal *fraction)
{
  PetscFunctionBegin;
  *fraction = nt->pcReuse;
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarNewtonSetPlainAggregationDofs(SSStarNewton nt, PetscInt dofs)
{
  PetscFunctionBegin;
  nt->plainDofs = dofs;
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarNewtonSetSmoothedAggregationFits(SSStarNewton nt, PetscBool fits)
{
  PetscFunctionBegin;
  nt->smoothedFits = fits ? 1 : 0;
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarNewtonGetPlainAggregationDofs(SSStarNewton nt, PetscInt *dofs)
{
  PetscFunctionBegin;
  *dofs = nt->plainDofs;
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarNewtonSetMGOverCorrection(SSStarNewton nt, PetscReal alpha, PetscInt wLevels)
{
  PetscFunctionBegin;
  nt->overCorrection = alpha;
  nt->wLevels        = wLevels;
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarNewtonGetMGOverCorrection(SSStarNewton nt, PetscReal *alpha, PetscInt *wLevels)
{
  PetscFunctionBegin;
  *alpha   = nt->overCorrection;
  *wLevels = nt->wLevels;
  PetscFunctionReturn(0);
}

/* Takes effect with the next stiffness A */
PetscErrorCode SSStarNewtonSetLUThreads(SSStarNewton nt, PetscInt threads)
{
  PetscFunctionBegin;
  nt->luThreads = threads;
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarNewtonGetLUThreads(SSStarNewton nt, PetscInt *threads)
{
  PetscFunctionBegin;
  *threads = nt->luThreads;
  PetscFunctionReturn(0);
}

/* Drops everything built for a stiffness A (the settings stay) */
PetscErrorCode SSStarNewtonReset(SSStarNewton nt)
{
  PetscFunctionBegin;
  if (!nt) PetscFunctionReturn(0);
  if (nt->ops.reset) PetscCall((*nt->ops.reset)(nt));
  PetscCall(PetscFree(nt->data));
  PetscCall(PetscMemzero(&nt->ops, sizeof(nt->ops)));
  PetscCall(MatDestroy(&nt->A));
  PetscCall(PetscFree(nt->type));
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarReleaseWork - frees what the Newton steps of the last solve built: the Krylov solver's preconditioner (the
   multigrid hierarchy on the whole body, the Newton matrix's factorization on the dense route) and the step's work
   vectors. The solution's data stay: SNESGetFunction()'s vector, SNESSSStarGetStates(), the reason, the iterations,
   the law residual, the reduction of K (the Schur complement P of the dense route and its factorization)

   Collective

   Input Parameter:
.  snes - the SNES after SNESSolve() (nothing happens for an SNES of another type)

   Notes:
   Call it after the last solve, before writing the solution (SSStarSceneWriteSolution()) or other post-processing:
   their memory then comes out of the solver's instead of adding to the process's peak (docs/guide/scale.md, "The
   output's memory"). A later SNESSolve() builds what it needs again, at the cost of a new set-up. examples/prism and
   examples/contact call it before the output, and after the last step of a load path.

   Level: advanced

.seealso: `SNESSSStarGetStates()`, `SSStarSceneWriteSolution()`, `SSStarSceneOutputEnd()`
@*/
PetscErrorCode SNESSSStarReleaseWork(SNES snes)
{
  PetscBool isssstar;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscCall(PetscObjectTypeCompare((PetscObject)snes, SNESSSSTAR, &isssstar));
  if (isssstar) PetscCall(SSStarNewtonReset(((SNES_SSStar *)snes->data)->newton));
  PetscFunctionReturn(0);
}

/*
   The stiffness A (P, or K on the whole body) with the given implementation, the scaling gamma and the contact nodes'
   layout, for one SNESSolve: the counts start afresh; what was built for another A is dropped
*/
PetscErrorCode SSStarNewtonSetStiffness(SSStarNewton nt, const char type[], Mat A, PetscReal gamma, const SSStarContactLayout *layout)
{
  PetscBool        sameType;
  PetscObjectState state;
  PetscErrorCode (*create)(SSStarNewton) = NULL;

  PetscFunctionBegin;
  nt->gamma     = gamma;
  nt->rcond     = -1;
  nt->nSteps    = 0;
  nt->nFactor   = 0;
  nt->factorSeconds = 0;
  nt->nReused   = 0;
  nt->nKrylov   = 0;
  nt->nFallback = 0;
  nt->nRefined  = 0;
  nt->layout    = *layout;
  PetscCall(PetscStrcmp(type, nt->type, &sameType));
  PetscCall(PetscObjectStateGet((PetscObject)A, &state));
  if (A == nt->A && state == nt->Astate && sameType && nt->ops.setup) {
    if (nt->ops.setscaling) PetscCall((*nt->ops.setscaling)(nt)); /* gamma may have changed */
    PetscFunctionReturn(0);
  }
  PetscCall(SSStarNewtonReset(nt));
  PetscCall(PetscFunctionListFind(SSStarNewtonList, type, &create));
  PetscCheck(create, PetscObjectComm((PetscObject)A), PETSC_ERR_ARG_UNKNOWN_TYPE, "Unknown Newton step %s", type);
  PetscCall(PetscObjectReference((PetscObject)A));
  nt->A      = A;
  nt->Astate = state;
  PetscCall(PetscStrallocpy(type, &nt->type));
  /* the SNES's KSP may be the implementation's (SNESSetFromOptions gave it the user's Jacobian: drop that), and a
     multigrid of another A keeps its levels through a reset (GAMG's coarse solvers of the old sizes): a fresh
     preconditioner, its type from the implementation's defaults and the options again */
  PetscCall(KSPReset(nt->snes->ksp));
  {
    PC pc;

    PetscCall(KSPGetPC(nt->snes->ksp, &pc));
    PetscCall(PCSetType(pc, PCNONE));
  }
  PetscCall((*create)(nt));
  PetscCall((*nt->ops.setup)(nt));
  PetscFunctionReturn(0);
}

/*
   A with new values (a nonlinear residual's Jacobian at a new iterate) or the contact nodes in new frames (the contact
   measured again), within a solve: what was built for them is built again, the counts of the solve go on
*/
PetscErrorCode SSStarNewtonUpdateStiffness(SSStarNewton nt, const char type[], Mat A, const SSStarContactLayout *layout)
{
  const PetscInt       counts[6] = {nt->nSteps, nt->nFactor, nt->nReused, nt->nKrylov, nt->nFallback, nt->nRefined};
  const PetscLogDouble factorSeconds = nt->factorSeconds;

  PetscFunctionBegin;
  PetscCall(PetscObjectReference((PetscObject)A)); /* A may be the one the reset drops */
  PetscCall(SSStarNewtonReset(nt));
  PetscCall(SSStarNewtonSetStiffness(nt, type, A, nt->gamma, layout));
  PetscCall(MatDestroy(&A));
  nt->nSteps    = counts[0];
  nt->nFactor   = counts[1];
  nt->nReused   = counts[2];
  nt->nKrylov   = counts[3];
  nt->nFallback = counts[4];
  nt->nRefined  = counts[5];
  nt->factorSeconds = factorSeconds;
  PetscFunctionReturn(0);
}

/* A new gamma for the same A (the globalization's rescaling): the factorizations of the old one do not apply */
PetscErrorCode SSStarNewtonSetScaling(SSStarNewton nt, PetscReal gamma)
{
  PetscFunctionBegin;
  nt->gamma = gamma;
  if (nt->ops.setscaling) PetscCall((*nt->ops.setscaling)(nt));
  PetscFunctionReturn(0);
}

/* Inexact Newton: the linear solve of the next step stops at ||r|| <= max(rtol ||b||, atol) */
PetscErrorCode SSStarNewtonSetTolerances(SSStarNewton nt, PetscReal rtol, PetscReal atol)
{
  PetscFunctionBegin;
  nt->rtol = rtol;
  nt->atol = atol;
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarNewtonSetKSPDefaults(SSStarNewton nt, KSPType ktype, PCType pctype)
{
  KSP       ksp = nt->snes->ksp;
  PC        pc;
  PetscBool set;

  PetscFunctionBegin;
  PetscCall(PetscOptionsHasName(((PetscObject)ksp)->options, ((PetscObject)ksp)->prefix, "-ksp_type", &set));
  if (!set) PetscCall(KSPSetType(ksp, ktype));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PetscOptionsHasName(((PetscObject)pc)->options, ((PetscObject)pc)->prefix, "-pc_type", &set));
  if (!set) PetscCall(PCSetType(pc, pctype));
  PetscFunctionReturn(0);
}

PetscBool SSStarKnownRow(const PetscReal S[9], const PetscReal T[9], PetscInt r)
{
  for (PetscInt k = 0; k < 3; k++)
    if (S[3 * r + k] != 0.0 || T[3 * r + k] != (PetscReal)(k == r)) return PETSC_FALSE;
  return PETSC_TRUE;
}

void SSStarRotateBack(const PetscReal *R, const PetscScalar y[3], PetscScalar x[3])
{
  for (PetscInt k = 0; k < 3; k++) x[k] = R ? R[k] * y[0] + R[3 + k] * y[1] + R[6 + k] * y[2] : y[k];
}

/*
   Solves the Newton system (newtonimpl.h) for du; solved is PETSC_FALSE (on every rank) when its matrix is singular or
   the linear solve failed
*/
PetscErrorCode SSStarNewtonSolve(SSStarNewton nt, const PetscReal S[], const PetscReal T[], Vec y, Vec du, PetscBool *solved)
{
  PetscFunctionBegin;
  nt->nSteps++;
  if (nt->layout.floating) { /* floating bodies: the motions the step leaves free (docs/derivation.md (14.5)) */
    unsigned char *known;

    PetscCall(PetscMalloc1(nt->layout.nnodes + 1, &known));
    for (PetscInt i = 0; i < nt->layout.nnodes; i++) {
      known[i] = 0;
      for (PetscInt r = 0; r < 3; r++)
        if (SSStarKnownRow(&S[9 * i], &T[9 * i], r)) known[i] |= (unsigned char)(1 << r);
    }
    PetscCall(SSStarFloatingFreeMotions(nt->layout.floating, known, T));
    PetscCall(PetscFree(known));
  }
  PetscCall((*nt->ops.solve)(nt, S, T, y, du, solved));
  PetscFunctionReturn(0);
}

/*
   The last step's linear system (SSStarNewtonSolve) solved on from its solution to the tolerances set since, when
   the solve stopped short of them: refined is PETSC_TRUE (on every rank) when du changed. Solves by a factorization
   are exact already.
*/
PetscErrorCode SSStarNewtonRefine(SSStarNewton nt, Vec du, PetscBool *refined)
{
  PetscFunctionBegin;
  *refined = PETSC_FALSE;
  if (nt->ops.refine) PetscCall((*nt->ops.refine)(nt, du, refined));
  if (*refined) nt->nRefined++;
  PetscFunctionReturn(0);
}

/* The step with every contact dof known: du_i = R_i^T y_i at the contact nodes, the free dofs in equilibrium */
PetscErrorCode SSStarNewtonSolveKnown(SSStarNewton nt, Vec y, Vec du, PetscBool *solved)
{
  const SSStarContactLayout *L = &nt->layout;
  const PetscScalar         *ya;
  PetscScalar               *da;

  PetscFunctionBegin;
  if (nt->layout.floating) nt->layout.floating->nfree = 0; /* the contact dofs hold every motion */
  if (nt->ops.solveknown) {
    nt->nSteps++;
    PetscCall((*nt->ops.solveknown)(nt, y, du, solved));
    PetscFunctionReturn(0);
  }
  PetscCall(VecGetArrayRead(y, &ya));
  PetscCall(VecGetArrayWrite(du, &da));
  for (PetscInt i = 0; i < L->nnodes; i++) {
    const PetscScalar yi[3] = {ya[L->dofs[3 * i]], ya[L->dofs[3 * i + 1]], ya[L->dofs[3 * i + 2]]};
    PetscScalar       di[3];

    SSStarRotateBack(L->frames ? &L->frames[9 * i] : NULL, yi, di);
    for (PetscInt k = 0; k < 3; k++) da[L->dofs[3 * i + k]] = di[k];
  }
  PetscCall(VecRestoreArrayWrite(du, &da));
  PetscCall(VecRestoreArrayRead(y, &ya));
  *solved = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* 1/cond_1 of the last factored Newton matrix (LAPACK's estimate), or -1 when the implementation gives none */
PetscErrorCode SSStarNewtonGetConditionEstimate(SSStarNewton nt, PetscReal *rcond)
{
  PetscFunctionBegin;
  *rcond = nt->rcond;
  PetscFunctionReturn(0);
}

/* In the current SNESSolve: the wall time of the factorizations (LU or multigrid set-ups), in seconds */
PetscErrorCode SSStarNewtonGetFactorTime(SSStarNewton nt, PetscLogDouble *seconds)
{
  PetscFunctionBegin;
  *seconds = nt->factorSeconds;
  PetscFunctionReturn(0);
}

/* In the current SNESSolve: factorizations (LU or multigrid set-ups), steps on older ones, Krylov iterations */
PetscErrorCode SSStarNewtonGetCounts(SSStarNewton nt, PetscInt *factorizations, PetscInt *reused, PetscInt *krylov)
{
  PetscFunctionBegin;
  if (factorizations) *factorizations = nt->nFactor;
  if (reused) *reused = nt->nReused;
  if (krylov) *krylov = nt->nKrylov;
  PetscFunctionReturn(0);
}

/* Newton systems solved in the current SNESSolve */
PetscErrorCode SSStarNewtonGetSteps(SSStarNewton nt, PetscInt *steps)
{
  PetscFunctionBegin;
  *steps = nt->nSteps;
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarNewtonView(SSStarNewton nt, PetscViewer viewer)
{
  PetscFunctionBegin;
  if (!nt->ops.view) PetscFunctionReturn(0); /* no stiffness A yet */
  PetscCall((*nt->ops.view)(nt, viewer));
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarNewtonDestroy(SSStarNewton *nt)
{
  PetscFunctionBegin;
  if (!*nt) PetscFunctionReturn(0);
  PetscCall(SSStarNewtonReset(*nt));
  PetscCall(PetscFree(*nt));
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarSetLUReuse - with a dense P, keep the LU factors of the Newton matrix and solve the next steps by GMRES
   preconditioned with them while at most this fraction of the contact nodes changed which of their rows are known
   (sticking, normal contact) since the factorization; a fresh LU when more did or GMRES does not converge
   (-snes_ssstar_newton_ksp_max_it, -snes_ssstar_newton_ksp_rtol). Default 0: the old LU only while no node changed;
   a negative fraction gives a fresh LU at every step.

   Logically Collective

   Input Parameters:
+  snes     - the SNES
-  fraction - the fraction of the contact nodes

   Options Database Key:
.  -snes_ssstar_lu_reuse <fraction> - the fraction, at most 1 (negative: a fresh LU at every step)

   Level: advanced

.seealso: `SNESSSStarGetNewtonStepCounts()`, `SNESSSStarSetLUThreads()`
@*/
PetscErrorCode SNESSSStarSetLUReuse(SNES snes, PetscReal fraction)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscTryMethod(snes, "SNESSSStarSetLUReuse_C", (SNES, PetscReal), (snes, fraction));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarSetLUReuse_SSStar(SNES snes, PetscReal fraction)
{
  PetscFunctionBegin;
  PetscCheck(fraction <= 1 && !PetscIsInfOrNanReal(fraction), PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_OUTOFRANGE, "-snes_ssstar_lu_reuse %g must be at most 1 (negative: never)", (double)fraction);
  PetscCall(SSStarNewtonSetReuse(((SNES_SSStar *)snes->data)->newton, fraction));
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarSetLUThreads - on several ranks with a dense P, the LU of the Newton matrix is computed on rank 0 while the
   other ranks sleep: this many BLAS (OpenBLAS) threads of rank 0 compute it, 0 for as many as the cores rank 0 may run
   on (start with mpiexec --bind-to none), at most the ranks of its node. Default 1: the BLAS is left as it is (as on one
   rank, where OPENBLAS_NUM_THREADS decides). Takes effect at the next SNESSolve() with a new P.

   Logically Collective

   Input Parameters:
+  snes    - the SNES
-  threads - the BLAS threads of rank 0, >= 0

   Options Database Key:
.  -snes_ssstar_lu_threads <n> - the threads

   Level: advanced

.seealso: `SNESSSStarSetLUReuse()`
@*/
PetscErrorCode SNESSSStarSetLUThreads(SNES snes, PetscInt threads)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscTryMethod(snes, "SNESSSStarSetLUThreads_C", (SNES, PetscInt), (snes, threads));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarSetLUThreads_SSStar(SNES snes, PetscInt threads)
{
  PetscFunctionBegin;
  PetscCheck(threads >= 0, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_OUTOFRANGE, "-snes_ssstar_lu_threads %" PetscInt_FMT " must be >= 0 (0: the cores rank 0 may run on)", threads);
  PetscCall(SSStarNewtonSetLUThreads(((SNES_SSStar *)snes->data)->newton, threads));
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarSetPCReuse - whole body (reduction none): keep the preconditioner (multigrid) of an earlier Newton step
   while at most this fraction of the contact nodes changed which of their rows are known since it was built; a new
   one (on the old interpolation, with PCGAMG) when more did

   Logically Collective

   Input Parameters:
+  snes     - the SNES
-  fraction - at most 1; negative: a new preconditioner at every step (default 0.3)

   Options Database Key:
.  -snes_ssstar_pc_reuse <fraction> - the fraction

   Level: advanced

.seealso: `SNESSSStarSetKSPRtolMax()`, `SNESSSStarGetNewtonStepCounts()`
@*/
PetscErrorCode SNESSSStarSetPCReuse(SNES snes, PetscReal fraction)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscTryMethod(snes, "SNESSSStarSetPCReuse_C", (SNES, PetscReal), (snes, fraction));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarSetPCReuse_SSStar(SNES snes, PetscReal fraction)
{
  PetscFunctionBegin;
  PetscCheck(fraction <= 1 && !PetscIsInfOrNanReal(fraction), PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_OUTOFRANGE, "-snes_ssstar_pc_reuse %g must be at most 1 (negative: never)", (double)fraction);
  PetscCall(SSStarNewtonSetPCReuse(((SNES_SSStar *)snes->data)->newton, fraction));
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarSetPlainAggregationDofs - whole body (reduction none): the multigrid (PCGAMG) of the Newton steps
   aggregates plainly, with W-cycles on the two finest levels and the Galerkin products all at once (the memory lever,
   docs/guide/scale.md), on problems of at least this many dofs of K; smoothed aggregation below, unless its set-up
   would not fit the memory. -pc_gamg_agg_nsmooths chooses for every size.

   Logically Collective

   Input Parameters:
+  snes - the SNES
-  dofs - the size from which the aggregation is plain (default 200000; 0: always; negative: only where the smoothed
          one would not fit the memory)

   Options Database Key:
.  -snes_ssstar_plain_aggregation_dofs <200000> - the size

   Level: advanced

.seealso: `SNESSSStarSetPCReuse()`, `SNESSSStarSetMemoryLimit()`
@*/
PetscErrorCode SNESSSStarSetPlainAggregationDofs(SNES snes, PetscInt dofs)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscTryMethod(snes, "SNESSSStarSetPlainAggregationDofs_C", (SNES, PetscInt), (snes, dofs));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarSetPlainAggregationDofs_SSStar(SNES snes, PetscInt dofs)
{
  PetscFunctionBegin;
  PetscCall(SSStarNewtonSetPlainAggregationDofs(((SNES_SSStar *)snes->data)->newton, dofs));
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarSetSmoothedAggregationFits - whole body (reduction none): the caller's estimate of the run's memory
   (SSStarEstimateMemory(), made before the mesh) says whether the multigrid's smoothed aggregation fits the memory
   limit; where it does not, the multigrid aggregates plainly, as the estimate printed before the work says

   Logically Collective

   Input Parameters:
+  snes - the SNES
-  fits - PETSC_TRUE: smoothed aggregation fits; PETSC_FALSE: plain aggregation (with W-cycles and the products all at
          once, as SNESSSStarSetPlainAggregationDofs())

   Notes:
   The scenes call it (SSStarSceneSetContact()), so that the aggregation the solver takes is the one the printed
   estimate assumed. Without it the solver judges by itself at each set-up of its multigrid, from the memory its rank
   holds then (VmRSS: it also counts memory freed before and not given back, e.g. a nested start's coarse solves) and
   the smoothed set-up's bytes per dof (docs/guide/large-problems.md, "Where the memory goes"). K of at least
   -snes_ssstar_plain_aggregation_dofs dofs aggregates plainly either way; -pc_gamg_agg_nsmooths chooses for every size.

   Level: developer

.seealso: `SNESSSStarSetPlainAggregationDofs()`, `SNESSSStarSetMemoryLimit()`, `SSStarEstimateMemory()`
@*/
PetscErrorCode SNESSSStarSetSmoothedAggregationFits(SNES snes, PetscBool fits)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscValidLogicalCollectiveBool(snes, fits, 2);
  PetscTryMethod(snes, "SNESSSStarSetSmoothedAggregationFits_C", (SNES, PetscBool), (snes, fits));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarSetSmoothedAggregationFits_SSStar(SNES snes, PetscBool fits)
{
  PetscFunctionBegin;
  PetscCall(SSStarNewtonSetSmoothedAggregationFits(((SNES_SSStar *)snes->data)->newton, fits));
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarSetMGOverCorrection - whole body (reduction none): where ssstar's multigrid aggregates plainly
   (SNESSSStarSetPlainAggregationDofs()), its wLevels finest levels W-cycle (V below, unless -pc_mg_cycle_type
   chooses) and the coarse corrections into those levels are multiplied by alpha (the interpolations scaled by sqrt(alpha) after each set-up, the coarse operators kept): plain
   aggregation's piecewise rigid interpolation under-corrects the smooth error, and the scaled correction makes up for
   it (Vanek's and Notay's over-correction; docs/guide/scale.md, "The multigrid's rate"). The preconditioner stays
   symmetric (CG applies).

   Logically Collective

   Input Parameters:
+  snes    - the SNES
.  alpha   - in [1, 2]: 1 leaves the corrections as the Galerkin ones (default 1.8); above 2 the multigrid can be
             indefinite
-  wLevels - the finest levels that W-cycle, at least 0 (default 2; PETSC_DEFAULT keeps the current)

   Options Database Keys:
+  -snes_ssstar_mg_overcorrection <1.8> - the factor
-  -snes_ssstar_mg_w_levels <2> - the W-cycled levels

   Level: advanced

.seealso: `SNESSSStarSetPlainAggregationDofs()`, `SNESSSStarSetPCReuse()`
@*/
PetscErrorCode SNESSSStarSetMGOverCorrection(SNES snes, PetscReal alpha, PetscInt wLevels)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscTryMethod(snes, "SNESSSStarSetMGOverCorrection_C", (SNES, PetscReal, PetscInt), (snes, alpha, wLevels));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarSetMGOverCorrection_SSStar(SNES snes, PetscReal alpha, PetscInt wLevels)
{
  SSStarNewton nt = ((SNES_SSStar *)snes->data)->newton;

  PetscFunctionBegin;
  PetscCheck(alpha >= 1 && alpha <= 2, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_OUTOFRANGE, "-snes_ssstar_mg_overcorrection %g must be in [1, 2]", (double)alpha);
  PetscCheck(wLevels >= 0 || wLevels == PETSC_DEFAULT, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_OUTOFRANGE, "-snes_ssstar_mg_w_levels %" PetscInt_FMT " must be at least 0", wLevels);
  PetscCall(SSStarNewtonSetMGOverCorrection(nt, alpha, wLevels == PETSC_DEFAULT ? nt->wLevels : wLevels));
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarGetNewtonStepCounts - how the Newton steps of the last SNESSolve() were solved

   Not Collective

   Input Parameter:
.  snes - the SNES

   Output Parameters:
+  factorizations - LU factorizations of the Newton matrix (dense P), or pass NULL
.  reused         - steps solved on an older LU (by GMRES, SNESSSStarSetLUReuse()), or pass NULL
-  krylov         - their Krylov iterations (also in SNESGetLinearSolveIterations()), or pass NULL

   Level: advanced

.seealso: `SNESSSStarSetLUReuse()`, `SNESSSStarGetConditionEstimate()`
@*/
PetscErrorCode SNESSSStarGetNewtonStepCounts(SNES snes, PetscInt *factorizations, PetscInt *reused, PetscInt *krylov)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscUseMethod(snes, "SNESSSStarGetNewtonStepCounts_C", (SNES, PetscInt *, PetscInt *, PetscInt *), (snes, factorizations, reused, krylov));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarGetNewtonStepCounts_SSStar(SNES snes, PetscInt *factorizations, PetscInt *reused, PetscInt *krylov)
{
  PetscFunctionBegin;
  PetscCall(SSStarNewtonGetCounts(((SNES_SSStar *)snes->data)->newton, factorizations, reused, krylov));
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarGetConditionEstimate - LAPACK's estimate of 1/cond_1 of the last LU-factored Newton matrix

   Not Collective

   Input Parameter:
.  snes - the SNES

   Output Parameter:
.  rcond - the estimate for a dense P (the system of the unknown dofs, A_RR), or -1 when none is known (sparse P,
           no factorization yet, a singular matrix)

   Level: advanced

.seealso: `SNESSSStarGetNewtonStepCounts()`
@*/
PetscErrorCode SNESSSStarGetConditionEstimate(SNES snes, PetscReal *rcond)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscUseMethod(snes, "SNESSSStarGetConditionEstimate_C", (SNES, PetscReal *), (snes, rcond));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarGetConditionEstimate_SSStar(SNES snes, PetscReal *rcond)
{
  PetscFunctionBegin;
  PetscCall(SSStarNewtonGetConditionEstimate(((SNES_SSStar *)snes->data)->newton, rcond));
  PetscFunctionReturn(0);
}

/* The implementations of the public functions above, composed on the SNES (SNESSSStarComposeFunctions()) */
static const SSStarComposed Composed[] = {
    {"SNESSSStarSetLUReuse_C", (PetscVoidFunction)SNESSSStarSetLUReuse_SSStar},
    {"SNESSSStarSetLUThreads_C", (PetscVoidFunction)SNESSSStarSetLUThreads_SSStar},
    {"SNESSSStarSetPCReuse_C", (PetscVoidFunction)SNESSSStarSetPCReuse_SSStar},
    {"SNESSSStarSetPlainAggregationDofs_C", (PetscVoidFunction)SNESSSStarSetPlainAggregationDofs_SSStar},
    {"SNESSSStarSetSmoothedAggregationFits_C", (PetscVoidFunction)SNESSSStarSetSmoothedAggregationFits_SSStar},
    {"SNESSSStarSetMGOverCorrection_C", (PetscVoidFunction)SNESSSStarSetMGOverCorrection_SSStar},
    {"SNESSSStarGetNewtonStepCounts_C", (PetscVoidFunction)SNESSSStarGetNewtonStepCounts_SSStar},
    {"SNESSSStarGetConditionEstimate_C", (PetscVoidFunction)SNESSSStarGetConditionEstimate_SSStar},
};

PetscErrorCode SNESSSStarComposeNewton(SNES snes, PetscBool on)
{
  PetscFunctionBegin;
  PetscCall(SNESSSStarComposeTable(snes, Composed, PETSC_STATIC_ARRAY_LENGTH(Composed), on));
  PetscFunctionReturn(0);
}
