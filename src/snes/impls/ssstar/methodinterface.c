/*
   The public functions of the SNES type "ssstar" for its method and its results: the scaling, the iteration, the
   linear solves of the Newton steps, the globalization, and what the last solve did. Setters are no-ops on a SNES of
   another type (PetscTryMethod).
*/
#include "ssstarimpl.h"

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

/*@
   SNESSSStarSetMethod - chooses the iteration: the semismooth* Newton method (SSSTAR_METHOD_NEWTON, the default) or
   the first-order baseline SSSTAR_METHOD_FIXEDPOINT, u <- u + R^T z with the approximation step z alone
   (docs/derivation.md section 1), for comparisons (bench/accuracy.py)

   Logically Collective

   Input Parameters:
+  snes   - the SNES
-  method - SSSTAR_METHOD_NEWTON or SSSTAR_METHOD_FIXEDPOINT

   Options Database Key:
.  -snes_ssstar_method <newton> - newton or fixedpoint

   Notes:
   The fixed-point iteration is a projected (with friction, proximal) gradient method: its gamma is 1/||P||_inf
   unless -snes_ssstar_scaling sets it, small enough for it to converge on frictionless and Tresca problems, at a
   linear rate 1 - lambda_min(P)/||P||_inf; with Coulomb friction it is not guaranteed to converge. It has no Newton
   step, hence no globalization; the stopping rule is the same.

   Level: advanced

.seealso: `SNESSSStarGetMethod()`, `SNESSSStarSetScaling()`
@*/
PetscErrorCode SNESSSStarSetMethod(SNES snes, SSStarMethod method)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscTryMethod(snes, "SNESSSStarSetMethod_C", (SNES, SSStarMethod), (snes, method));
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarGetMethod - the iteration chosen by SNESSSStarSetMethod()

   Not Collective

   Input Parameter:
.  snes - the SNES

   Output Parameter:
.  method - SSSTAR_METHOD_NEWTON or SSSTAR_METHOD_FIXEDPOINT

   Level: advanced

.seealso: `SNESSSStarSetMethod()`
@*/
PetscErrorCode SNESSSStarGetMethod(SNES snes, SSStarMethod *method)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscUseMethod(snes, "SNESSSStarGetMethod_C", (SNES, SSStarMethod *), (snes, method));
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

/*@
   SNESSSStarGetReason - why the last solve stopped, finer than SNESGetConvergedReason()

   Not Collective

   Input Parameter:
.  snes - the SNES

   Output Parameter:
.  reason - the sub-reason (SSStarReason; SSStarReasons[] names it)

   Notes:
   -snes_converged_reason prints it on the line "ssstar: ..."; docs/guide/converged.md ("When it does not converge") maps each onto the
   SNESConvergedReason.

   Level: beginner

.seealso: `SNESGetConvergedReason()`, `SNESSSStarGetTolerance()`, `SNESSSStarGetRemedyCounts()`
@*/
PetscErrorCode SNESSSStarGetReason(SNES snes, SSStarReason *reason)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscUseMethod(snes, "SNESSSStarGetReason_C", (SNES, SSStarReason *), (snes, reason));
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
   Where ||z|| has met its threshold and the law residual has not, the iteration takes whole Newton steps solved to
   the floor (polishing) until it does, or stops with SSSTAR_REASON_LAW_STALLED when it no longer halves (its round-off
   floor is above the tolerance).

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

/*@
   SNESSSStarGetUnbalancedMotion - after a solve that found no equilibrium (SSSTAR_REASON_NO_EQUILIBRIUM): the rigid
   motion of a floating body along which the load does work that no contact force the friction laws allow resists

   Not Collective

   Input Parameter:
.  snes - the SNES

   Output Parameters:
+  motion     - the motion, a combination of the vectors of K's null space in the layout of the SNES vector (owned by
                the SNES), or NULL when the last solve did not stop for this reason; pass NULL if not wanted
.  body       - the floating body it moves most: the vectors of K's null space that move common dofs make one body,
                numbered in the order of their first vector (-1 when there is no motion); or NULL
.  direction  - the direction the body slides in (unit, global axes): the mean tangential part of the motion at its
                contact points, or where it only lifts off its mean translation; or NULL
-  unbalanced - the part of the load on the body's rigid-body motions that no admissible contact force balances,
                relative to the whole (a block on a slope of angle alpha with friction phi < tan alpha:
                sin(alpha - arctan phi)); or NULL

   Notes:
   A floating body is one held by contact alone: its rigid-body motions are declared as K's null space
   (MatSetNullSpace()). Before its first iteration every solve checks that contact forces inside the friction cones
   can balance the load on those motions (docs/derivation.md section 14); where they cannot, no equilibrium exists,
   and the solve stops with SNES_DIVERGED_DTOL and this motion (down a slope steeper than its friction angle allows,
   lifting off the slope at that angle; along a push on a frictionless plane).

   Level: intermediate

.seealso: `SNESSSStarGetReason()`, `MatSetNullSpace()`
@*/
PetscErrorCode SNESSSStarGetUnbalancedMotion(SNES snes, Vec *motion, PetscInt *body, PetscReal direction[3], PetscReal *unbalanced)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscUseMethod(snes, "SNESSSStarGetUnbalancedMotion_C", (SNES, Vec *, PetscInt *, PetscReal[3], PetscReal *), (snes, motion, body, direction, unbalanced));
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarGetTolerance - the threshold the last solve's stopping rule compared ||z|| with

   Not Collective

   Input Parameter:
.  snes - the SNES

   Output Parameter:
.  tol - max(atol, rtol max(||u||, ||gamma f||)) at the last iterate (SNESConvergedSSStar())

   Level: intermediate

.seealso: `SNESConvergedSSStar()`, `SNESGetFunctionNorm()`, `SNESSSStarGetReason()`
@*/
PetscErrorCode SNESSSStarGetTolerance(SNES snes, PetscReal *tol)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscValidRealPointer(tol, 2);
  PetscUseMethod(snes, "SNESSSStarGetTolerance_C", (SNES, PetscReal *), (snes, tol));
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarSetGlobalization - turns the globalization of ssstar on or off and sets its parameters

   Logically Collective

   Input Parameters:
+  snes          - the SNES
.  on            - PETSC_TRUE (default): damped steps on the merit function ||z|| and remedies (a full step or a
                   doubled gamma after a failed line search, a regularized Newton step or fixed-point iterations for a
                   singular Newton matrix, a doubled gamma on a cycle); PETSC_FALSE: the plain iteration
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
