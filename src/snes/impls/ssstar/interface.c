/*
   The public functions of the SNES type "ssstar". Setters are no-ops on a SNES of another type (PetscTryMethod), so
   a program may declare its contact nodes and still run with -snes_type ksponly.
*/
#include "ssstarimpl.h"

/*@
   SNESSSStarSetContactNodes - declares the contact nodes of a whole-body problem F(u) = K u - b with Jacobian K

   Collective

   Input Parameters:
+  snes    - the SNES
.  dofs    - for each contact node owned by this rank, the global indices of its x, y, z dofs in the SNES vector
             (3 per node, in node order; owned by this rank)
.  normals - NULL for (0, 0, 1), or 3 entries per contact node (layout as dofs): the unit normal of the obstacle
             plane, pointing into the body
-  gaps    - NULL for 0, or 1 entry per contact node: the initial distance to the obstacle

   Notes:
   SNESSolve() reduces K to the contact dofs by a Schur complement (-snes_ssstar_reduction), solves the contact
   problem in each node's frame (t1, t2, n) with non-penetration u.n + gap >= 0, and returns the whole u;
   SNESGetFunction() then holds K u - b, whose contact entries are the contact forces (global axes).
   K must be SPD: Dirichlet dofs eliminated or given identity rows. The SNES keeps references to the arguments.
   On a SNES of another type the call does nothing, so a program may declare its nodes and run -snes_type ksponly.

   Level: beginner

.seealso: `SNESSSStarGetContactNodes()`, `SNESSSStarSetContactOperator()`, `SNESSSStarSetContactProblem()`,
          `SNESSSStarSetFrictionCoefficients()`, `SNESSSStarGetStates()`
@*/
PetscErrorCode SNESSSStarSetContactNodes(SNES snes, IS dofs, Vec normals, Vec gaps)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscValidHeaderSpecific(dofs, IS_CLASSID, 2);
  if (normals) PetscValidHeaderSpecific(normals, VEC_CLASSID, 3);
  if (gaps) PetscValidHeaderSpecific(gaps, VEC_CLASSID, 4);
  PetscTryMethod(snes, "SNESSSStarSetContactNodes_C", (SNES, IS, Vec, Vec), (snes, dofs, normals, gaps));
  PetscFunctionReturn(0);
}

/*@C
   SNESSSStarGetContactNodes - the number of contact nodes of this rank and what SNESSSStarSetContactNodes() declared

   Not Collective

   Input Parameter:
.  snes - the SNES

   Output Parameters:
+  n       - the contact nodes of this rank: 1/3 of the declared dofs; in the reduced use 1/3 of the local size of
             the SNES function vector once it exists (SNESSetFunction() with a vector, SNESSSStarSetContactProblem(),
             SNESSetUp()), -1 before
.  dofs    - the declared IS of contact dofs, or NULL (reduced use)
.  normals - the declared normals, or NULL
-  gaps    - the declared gaps, or NULL

   Notes:
   Any output may be NULL. The objects belong to the SNES. On a SNES of another type n is -1 and the rest NULL.

   Level: intermediate

.seealso: `SNESSSStarSetContactNodes()`, `SNESSSStarGetStates()`, `SNESSSStarGetNodeFriction()`
@*/
PetscErrorCode SNESSSStarGetContactNodes(SNES snes, PetscInt *n, IS *dofs, Vec *normals, Vec *gaps)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  if (n) *n = -1;
  if (dofs) *dofs = NULL;
  if (normals) *normals = NULL;
  if (gaps) *gaps = NULL;
  PetscTryMethod(snes, "SNESSSStarGetContactNodes_C", (SNES, PetscInt *, IS *, Vec *, Vec *), (snes, n, dofs, normals, gaps));
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarSetContactOperator - declares the contact points of a whole-body problem F(u) = K u - b by a contact
   operator B: w = B u + g is each point's relative displacement in its frame (t1, t2, n), with non-penetration
   w_n >= 0 and the friction law on w_t; the contact force on the body is B^T lambda

   Collective

   Input Parameters:
+  snes - the SNES
.  dofs - for each contact point owned by this rank, the global indices of its own x, y, z dofs (its slave node; 3 per
          point, owned by this rank)
.  B    - the contact operator: 3 rows per point (t1, t2, n; rows distributed like dofs), a column per dof of u
-  gaps - NULL for 0, or 1 entry per point: g, the initial normal distance

   Notes:
   B's 3x3 block at a point's own dofs must be a positive multiple d R of a rotation R (rows t1, t2, n): the point's
   frame. Its other entries, on dofs of other nodes (a master surface; on no point's own dofs), say what the point is
   compared with: B_i = d R (E_own - M_i). A rigid obstacle is M_i = 0 (what SNESSSStarSetContactNodes() declares); a
   point of one body against the surface of another has M_i = the interpolation weights of the master nodes.
   SNESSolve() changes to the points' variables (u_own - M u per point), reduces or keeps the whole body as for
   SNESSSStarSetContactNodes(), and returns the whole u; SNESGetFunction() holds K u - b, the contact forces (on the
   slave nodes and, with the opposite sign, spread on the master nodes). A B that is rank-deficient (a singular or
   non-rotation block at a point's own dofs, a point's own dofs used as another point's master dofs) is refused,
   naming the point. docs/contact-operator.md derives the reduced operator and checks it.

   Level: intermediate

.seealso: `SNESSSStarSetContactNodes()`, `SNESSSStarSetFrictionCoefficients()`, `SNESSSStarSetNodeFrictionLaws()`
@*/
PetscErrorCode SNESSSStarSetContactOperator(SNES snes, IS dofs, Mat B, Vec gaps)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscValidHeaderSpecific(dofs, IS_CLASSID, 2);
  PetscValidHeaderSpecific(B, MAT_CLASSID, 3);
  if (gaps) PetscValidHeaderSpecific(gaps, VEC_CLASSID, 4);
  PetscTryMethod(snes, "SNESSSStarSetContactOperator_C", (SNES, IS, Mat, Vec), (snes, dofs, B, gaps));
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarSetFrictionLaw - sets the friction law of every contact node without a law of its own (default coulomb)

   Logically Collective

   Input Parameters:
+  snes - the SNES
-  law  - SSSTAR_FRICTION_NONE, SSSTAR_FRICTION_TRESCA or SSSTAR_FRICTION_COULOMB

   Options Database Key:
.  -snes_ssstar_friction_law <coulomb> - none, tresca or coulomb

   Notes:
   tresca needs SNESSSStarSetSlipBounds(). SNESSSStarSetNodeFrictionLaws() sets one law per node.

   Level: beginner

.seealso: `SNESSSStarGetFrictionLaw()`, `SNESSSStarSetNodeFrictionLaws()`, `SNESSSStarSetFriction()`,
          `SNESSSStarSetSlipBounds()`
@*/
PetscErrorCode SNESSSStarSetFrictionLaw(SNES snes, SSStarFrictionLaw law)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscTryMethod(snes, "SNESSSStarSetFrictionLaw_C", (SNES, SSStarFrictionLaw), (snes, law));
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarGetFrictionLaw - the friction law of the nodes without a law of their own

   Not Collective

   Input Parameter:
.  snes - the SNES

   Output Parameter:
.  law - the law

   Level: beginner

.seealso: `SNESSSStarSetFrictionLaw()`, `SNESSSStarGetNodeFriction()`
@*/
PetscErrorCode SNESSSStarGetFrictionLaw(SNES snes, SSStarFrictionLaw *law)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscUseMethod(snes, "SNESSSStarGetFrictionLaw_C", (SNES, SSStarFrictionLaw *), (snes, law));
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarSetFriction - sets the Coulomb friction coefficient phi of every node without one of its own (default 0.3)

   Logically Collective

   Input Parameters:
+  snes - the SNES
-  phi  - the coefficient, >= 0

   Options Database Key:
.  -snes_ssstar_friction <0.3> - the coefficient

   Level: beginner

.seealso: `SNESSSStarGetFriction()`, `SNESSSStarSetFrictionCoefficients()`, `SNESSSStarSetFrictionLaw()`
@*/
PetscErrorCode SNESSSStarSetFriction(SNES snes, PetscReal phi)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscTryMethod(snes, "SNESSSStarSetFriction_C", (SNES, PetscReal), (snes, phi));
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarGetFriction - the Coulomb coefficient of the nodes without a coefficient of their own

   Not Collective

   Input Parameter:
.  snes - the SNES

   Output Parameter:
.  phi - the coefficient

   Level: beginner

.seealso: `SNESSSStarSetFriction()`, `SNESSSStarGetNodeFriction()`
@*/
PetscErrorCode SNESSSStarGetFriction(SNES snes, PetscReal *phi)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscUseMethod(snes, "SNESSSStarGetFriction_C", (SNES, PetscReal *), (snes, phi));
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarSetFrictionCoefficients - one Coulomb coefficient per contact node

   Collective

   Input Parameters:
+  snes - the SNES
-  phi  - 1 entry (>= 0, or PETSC_DEFAULT) per contact node owned by the rank, in the order of the contact nodes; NULL: back to the
          scalar of SNESSSStarSetFriction()

   Notes:
   The SNES keeps a reference to phi. The coefficient applies to the nodes whose law is coulomb. An entry PETSC_DEFAULT
   gives its node the coefficient of SNESSSStarSetFriction() (-snes_ssstar_friction) as it is at SNESSolve(): a scene
   hands over the coefficients of its groups without fixing the solver's default (SSStarSceneSetContact()). Any other
   entry must be a number >= 0.

   Level: intermediate

.seealso: `SNESSSStarSetFriction()`, `SNESSSStarSetNodeFrictionLaws()`, `SNESSSStarGetNodeFriction()`
@*/
PetscErrorCode SNESSSStarSetFrictionCoefficients(SNES snes, Vec phi)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  if (phi) PetscValidHeaderSpecific(phi, VEC_CLASSID, 2);
  PetscTryMethod(snes, "SNESSSStarSetFrictionCoefficients_C", (SNES, Vec), (snes, phi));
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarSetSlipBounds - the Tresca slip bound s of each contact node: |r_t| <= s, and r_t = -s u_t/|u_t| where
   the node slips

   Collective

   Input Parameters:
+  snes - the SNES
-  s    - 1 entry (>= 0, a force in the units of F) per contact node owned by the rank, in node order

   Notes:
   The bound applies to the nodes whose law is tresca (SNESSSStarSetFrictionLaw(), SNESSSStarSetNodeFrictionLaws()).

   Level: intermediate

.seealso: `SNESSSStarSetFrictionLaw()`, `SNESSSStarSetNodeFrictionLaws()`, `SNESSSStarGetNodeFriction()`
@*/
PetscErrorCode SNESSSStarSetSlipBounds(SNES snes, Vec s)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  if (s) PetscValidHeaderSpecific(s, VEC_CLASSID, 2);
  PetscTryMethod(snes, "SNESSSStarSetSlipBounds_C", (SNES, Vec), (snes, s));
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarSetNodeFrictionLaws - one friction law per contact node owned by the rank

   Not Collective

   Input Parameters:
+  snes - the SNES
.  n    - the number of contact nodes of this rank
-  laws - the law of each, in node order (copied); NULL: every node has the law of SNESSSStarSetFrictionLaw()

   Level: intermediate

.seealso: `SNESSSStarSetFrictionLaw()`, `SNESSSStarSetFrictionCoefficients()`, `SNESSSStarSetSlipBounds()`,
          `SNESSSStarGetNodeFriction()`
@*/
PetscErrorCode SNESSSStarSetNodeFrictionLaws(SNES snes, PetscInt n, const SSStarFrictionLaw laws[])
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscTryMethod(snes, "SNESSSStarSetNodeFrictionLaws_C", (SNES, PetscInt, const SSStarFrictionLaw[]), (snes, n, laws));
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarSetReductionType - how K is reduced to the contact dofs in the whole-body use: a Schur complement P
   (direct, mumps, explicit), none (the Newton steps on the whole body, P never formed) or auto (direct where the dense
   P is the faster route and fits the memory, else none); default auto

   Logically Collective

   Input Parameters:
+  snes - the SNES
-  type - SSSTAR_REDUCTION_DIRECT, SSSTAR_REDUCTION_MUMPS, SSSTAR_REDUCTION_EXPLICIT, SSSTAR_REDUCTION_NONE (no
          reduction: the Newton steps on the whole body) or SSSTAR_REDUCTION_AUTO (the default: direct or none, by
          size and memory)

   Options Database Key:
.  -snes_ssstar_reduction <auto> - direct, mumps, explicit, none or auto

   Level: intermediate

.seealso: `SNESSSStarGetReductionType()`, `SSStarReductionCreate()`, `SNESSSStarSetMemoryLimit()`
@*/
PetscErrorCode SNESSSStarSetReductionType(SNES snes, SSStarReductionType type)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscTryMethod(snes, "SNESSSStarSetReductionType_C", (SNES, SSStarReductionType), (snes, type));
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarGetReductionType - the reduction of the last SNESSolve() (auto resolved to direct or none), or the one
   set before the first

   Not Collective

   Input Parameter:
.  snes - the SNES

   Output Parameter:
.  type - SSSTAR_REDUCTION_DIRECT, SSSTAR_REDUCTION_MUMPS, SSSTAR_REDUCTION_EXPLICIT, SSSTAR_REDUCTION_NONE or (before
          the first solve) SSSTAR_REDUCTION_AUTO

   Level: intermediate

.seealso: `SNESSSStarSetReductionType()`
@*/
PetscErrorCode SNESSSStarGetReductionType(SNES snes, SSStarReductionType *type)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscUseMethod(snes, "SNESSSStarGetReductionType_C", (SNES, SSStarReductionType *), (snes, type));
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
   SNESSSStarSetMemoryLimit - the memory the reduction of K may plan for; it refuses before factorizing K when its
   estimate exceeds it

   Logically Collective

   Input Parameters:
+  snes      - the SNES
-  gigabytes - GB (1e9 bytes) per rank; 0 (the default): MemAvailable of each node split over its ranks

   Options Database Key:
.  -snes_ssstar_memory_limit <0> - the limit

   Level: intermediate

.seealso: `SNESSSStarSetReductionType()`, `SSStarCheckMemory()`
@*/
PetscErrorCode SNESSSStarSetMemoryLimit(SNES snes, PetscReal gigabytes)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscTryMethod(snes, "SNESSSStarSetMemoryLimit_C", (SNES, PetscReal), (snes, gigabytes));
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
   -snes_converged_reason prints it on the line "ssstar: ..."; README "When it does not converge" maps each onto the
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

/*@C
   SNESSSStarGetNodeFriction - the friction law, Coulomb coefficient and Tresca slip bound the solver uses at each
   contact node of this rank, in the order the nodes were declared

   Not Collective

   Input Parameters:
+  snes - the SNES, after SNESSetUp() or SNESSolve()
-  n    - the number of contact nodes of this rank (the length of each array)

   Output Parameters:
+  laws   - the law of each node, or NULL
.  phi    - the Coulomb coefficient of each node (meaningful where the law is coulomb), or NULL
-  bounds - the Tresca slip bound of each node (a force; meaningful where the law is tresca), or NULL

   Notes:
   What SNESSSStarSetFrictionLaw(), SNESSSStarSetFriction(), SNESSSStarSetFrictionCoefficients(),
   SNESSSStarSetSlipBounds() and SNESSSStarSetNodeFrictionLaws() together gave each node; the output files of the
   scenes record it (/contact/friction_law, /contact/friction, /contact/slip_bound).

   Level: intermediate

.seealso: `SNESSSStarSetNodeFrictionLaws()`, `SNESSSStarSetFrictionCoefficients()`, `SNESSSStarSetSlipBounds()`
@*/
PetscErrorCode SNESSSStarGetNodeFriction(SNES snes, PetscInt n, SSStarFrictionLaw laws[], PetscReal phi[], PetscReal bounds[])
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscUseMethod(snes, "SNESSSStarGetNodeFriction_C", (SNES, PetscInt, SSStarFrictionLaw[], PetscReal[], PetscReal[]), (snes, n, laws, phi, bounds));
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
   Cycles and stagnation are detected in both cases; without globalization they end the solve. README, "When it does
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

/*@
   SNESSSStarGetReducedProblem - P and f of the last solve: c(u) = P u - f on the contact dofs (global axes, in the
   order of the contact nodes sorted by their first dof)

   Not Collective

   Input Parameter:
.  snes - the SNES, after SNESSolve()

   Output Parameters:
+  P - the reduced operator (owned by the SNES), or pass NULL
-  f - the reduced load (owned by the SNES), or pass NULL

   Notes:
   An error before the first solve, and after a solve on the whole body (reduction none), which never forms P.

   Level: advanced

.seealso: `SNESSSStarSetContactProblem()`, `SNESSSStarSetReductionType()`
@*/
PetscErrorCode SNESSSStarGetReducedProblem(SNES snes, Mat *P, Vec *f)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscUseMethod(snes, "SNESSSStarGetReducedProblem_C", (SNES, Mat *, Vec *), (snes, P, f));
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
   SNESSSStarSetContactProblem - sets the SNES function c(u) = P u - f and the Jacobian P of a reduced contact problem
   0 in P u - f + Q(u), for a program that has P (dense or sparse, 3 dofs per contact node) and f

   Collective

   Input Parameters:
+  snes - the SNES
.  P    - the reduced stiffness, 3 rows per contact node (u_t1, u_t2, u_n), SPD
-  f    - the reduced load, laid out like P's rows

   Notes:
   Works with any SNES type; the SNES keeps references to P and f. After SNESSolve(), SNESGetFunction()
   gives the reaction r = P u - f at the solution.

   Level: intermediate

.seealso: `SNESSSStarSetContactNodes()`, `SNESSSStarGetReducedProblem()`
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
