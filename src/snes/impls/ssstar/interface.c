/*
   The public functions of the SNES type "ssstar" for what it solves: the linear problem, the contact declaration, the
   reduction of K, the friction laws and their parameters. Setters are no-ops on a SNES of another type
   (PetscTryMethod), so a program may declare its contact nodes and still run with -snes_type ksponly. Every collective
   entry checks its input on every rank (SSStarCheckAllRanks()).
*/
#include "ssstarimpl.h"

typedef struct {
  Mat K;
  Vec b;
} LinearProblem;

static PetscErrorCode LinearProblemFunction(SNES snes, Vec u, Vec r, void *ctx)
{
  LinearProblem *lp = (LinearProblem *)ctx;

  PetscFunctionBegin;
  PetscCall(MatMult(lp->K, u, r));
  PetscCall(VecAXPY(r, -1.0, lp->b));
  PetscFunctionReturn(0);
}

static PetscErrorCode LinearProblemJacobian(SNES snes, Vec u, Mat J, Mat Jpre, void *ctx)
{
  PetscFunctionBegin;
  PetscFunctionReturn(0); /* J = K, constant */
}

static PetscErrorCode LinearProblemDestroy(void *ctx)
{
  LinearProblem *lp = (LinearProblem *)ctx;

  PetscFunctionBegin;
  PetscCall(MatDestroy(&lp->K));
  PetscCall(VecDestroy(&lp->b));
  PetscCall(PetscFree(lp));
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarSetLinearProblem - sets the SNES function F(u) = K u - b and the Jacobian K of a linear elastic body (or
   c(u) = P u - f and P of a reduced contact problem, 3 dofs per contact node)

   Collective

   Input Parameters:
+  snes - the SNES
.  K    - the stiffness, SPD (Dirichlet dofs eliminated or given identity rows); or the reduced P
-  b    - the load, laid out like K's rows; or the reduced f

   Notes:
   Works with any SNES type; the SNES keeps references to K and b, so a program that changes b's values between
   solves (load steps) changes the load. After SNESSolve(), SNESGetFunction() holds K u - b: at the contact nodes the
   contact forces. A whole body declares its contact nodes (SNESSSStarSetContactNodes() or
   SNESSSStarSetContactOperator()); without a declaration every dof is a contact dof (the reduced use).

   Level: beginner

.seealso: `SNESSSStarSetContactNodes()`, `SNESSSStarGetReducedProblem()`, `SNESSetFunction()`, `SNESSetJacobian()`
@*/
PetscErrorCode SNESSSStarSetLinearProblem(SNES snes, Mat K, Vec b)
{
  LinearProblem *lp;
  PetscContainer container;
  Vec            r;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscValidHeaderSpecific(K, MAT_CLASSID, 2);
  PetscValidHeaderSpecific(b, VEC_CLASSID, 3);
  PetscCall(PetscNew(&lp));
  PetscCall(PetscObjectReference((PetscObject)K));
  PetscCall(PetscObjectReference((PetscObject)b));
  lp->K = K;
  lp->b = b;
  PetscCall(PetscContainerCreate(PetscObjectComm((PetscObject)snes), &container));
  PetscCall(PetscContainerSetPointer(container, lp));
  PetscCall(PetscContainerSetUserDestroy(container, LinearProblemDestroy));
  PetscCall(PetscObjectCompose((PetscObject)snes, "SNESSSStarLinearProblem", (PetscObject)container));
  PetscCall(PetscContainerDestroy(&container));
  PetscCall(VecDuplicate(b, &r));
  PetscCall(SNESSetFunction(snes, r, LinearProblemFunction, lp));
  PetscCall(VecDestroy(&r));
  PetscCall(SNESSetJacobian(snes, K, K, LinearProblemJacobian, lp));
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarSetContactNodes - declares the contact nodes of a whole-body problem F(u) = K u - b with Jacobian K
   against rigid planes

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
   It is SNESSSStarSetContactOperator() with B's rows built from the normals (each node's own dofs turned into its
   frame, no master dofs). Wrong sizes on any rank, a node whose dofs another rank owns, a normal that is not a unit
   vector are refused on every rank, naming the node.

   Level: beginner

.seealso: `SNESSSStarGetContactNodes()`, `SNESSSStarSetContactOperator()`, `SNESSSStarSetLinearProblem()`,
          `SNESSSStarSetNodeLawParameter()`, `SNESSSStarGetStates()`
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
             the SNES function vector once it exists (SNESSetFunction() with a vector, SNESSSStarSetLinearProblem(),
             SNESSetUp()), -1 before
.  dofs    - the declared IS of contact dofs, or NULL (reduced use)
.  normals - the declared normals, or NULL
-  gaps    - the declared gaps, or NULL

   Notes:
   Any output may be NULL. The objects belong to the SNES. On a SNES of another type n is -1 and the rest NULL.

   Level: intermediate

.seealso: `SNESSSStarSetContactNodes()`, `SNESSSStarGetStates()`, `SNESSSStarGetNodeFrictionLaws()`
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

.seealso: `SNESSSStarSetContactNodes()`, `SNESSSStarSetNodeLawParameter()`, `SNESSSStarSetNodeFrictionLaws()`
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
   SNESSSStarSetContactOffsets - the offsets of a step of a load path: each contact point's relative displacement is
   w = R u + o instead of R u + g e_3 (docs/derivation.md (10.4)-(10.5)), so that the tangential law holds for the slip
   increment of the step and the normal law on the current gap

   Logically Collective

   Input Parameters:
+  snes    - the SNES
-  offsets - 3 entries per contact point of this rank, in the order and layout of the declaration (as the normals of
             SNESSSStarSetContactNodes(); in the reduced use, as the SNES vector), in the point's frame (t1, t2, n); or
             NULL: back to the declared gaps, (0, 0, g)

   Notes:
   Step k of a quasi-static load path solves 0 in P u - f^k + Q(R u + o^k): for a node against a rigid obstacle that
   has moved by the translation d^k, o^k = (-R_t u^(k-1) - R_t (d^k - d^(k-1)), g - n.d^k) with u^(k-1) the solution
   of the step before; for a point of SNESSSStarSetContactOperator(), o^k = (-(B u^(k-1))_t, g) with B's rows. A
   sticking node then keeps its position relative to the obstacle, a sliding one is resisted against the direction of
   its increment. (0, 0, g) is the static problem.

   The values are read at every SNESSolve() (change the Vec's entries, or set another Vec, between the steps); unlike
   a new declaration they keep the reduction: P is computed once for the whole path. The stopping rule's displacement
   scale includes the norm of the tangential offsets (SNESConvergedSSStar()). The SNES keeps a reference to offsets.
   Wrong sizes and NaN or Inf are refused on every rank, naming the node.

   Level: intermediate

.seealso: `SNESSSStarGetContactOffsets()`, `SNESSSStarSetContactNodes()`, `SNESSSStarSetContactOperator()`,
          `SSStarSceneSetStep()`
@*/
PetscErrorCode SNESSSStarSetContactOffsets(SNES snes, Vec offsets)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  if (offsets) PetscValidHeaderSpecific(offsets, VEC_CLASSID, 2);
  PetscTryMethod(snes, "SNESSSStarSetContactOffsets_C", (SNES, Vec), (snes, offsets));
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarGetContactOffsets - the offsets set by SNESSSStarSetContactOffsets(), or NULL

   Not Collective

   Input Parameter:
.  snes - the SNES

   Output Parameter:
.  offsets - the Vec (owned by the SNES), or NULL when the declared gaps are in use (or the SNES is of another type)

   Level: intermediate

.seealso: `SNESSSStarSetContactOffsets()`
@*/
PetscErrorCode SNESSSStarGetContactOffsets(SNES snes, Vec *offsets)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscValidPointer(offsets, 2);
  *offsets = NULL;
  PetscTryMethod(snes, "SNESSSStarGetContactOffsets_C", (SNES, Vec *), (snes, offsets));
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

.seealso: `SNESSSStarSetLinearProblem()`, `SNESSSStarSetReductionType()`
@*/
PetscErrorCode SNESSSStarGetReducedProblem(SNES snes, Mat *P, Vec *f)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscUseMethod(snes, "SNESSSStarGetReducedProblem_C", (SNES, Mat *, Vec *), (snes, P, f));
  PetscFunctionReturn(0);
}

/*@C
   SNESSSStarSetReductionType - how K is reduced to the contact dofs in the whole-body use: a Schur complement P
   (direct, mumps, explicit), none (the Newton steps on the whole body, P never formed) or auto (direct where the dense
   P is the faster route and fits the memory, else none); default auto

   Logically Collective

   Input Parameters:
+  snes - the SNES
-  type - SSSTARREDUCTIONDIRECT ("direct"), SSSTARREDUCTIONMUMPS, SSSTARREDUCTIONEXPLICIT, SSSTARREDUCTIONNONE (no
          reduction: the Newton steps on the whole body), another registered type (SSStarReductionRegister()), or
          SSSTARREDUCTIONAUTO ("auto", the default: direct or none, by size and memory)

   Options Database Key:
.  -snes_ssstar_reduction <auto> - direct, mumps, explicit, none or auto

   Notes:
   The options of the reduction's solvers take the SNES's prefix: -<prefix>schur_direct_mumps_icntl_<i> (direct),
   -<prefix>schur_mat_mumps_* (mumps), -<prefix>interior_ksp_*, -<prefix>interior_pc_* (explicit).

   Level: intermediate

.seealso: `SNESSSStarGetReductionType()`, `SSStarReductionSetType()`, `SNESSSStarSetMemoryLimit()`
@*/
PetscErrorCode SNESSSStarSetReductionType(SNES snes, SSStarReductionType type)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscValidCharPointer(type, 2);
  PetscTryMethod(snes, "SNESSSStarSetReductionType_C", (SNES, SSStarReductionType), (snes, type));
  PetscFunctionReturn(0);
}

/*@C
   SNESSSStarGetReductionType - the reduction of the last SNESSolve() (auto resolved to direct or none), or the one
   set before the first

   Not Collective

   Input Parameter:
.  snes - the SNES

   Output Parameter:
.  type - "direct", "mumps", "explicit", "none" or (before the first solve) "auto"; owned by the SNES

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

/*@C
   SNESSSStarSetFrictionLaw - sets the friction law of every contact node without a law of its own (default coulomb)

   Logically Collective

   Input Parameters:
+  snes - the SNES
-  law  - the name of a law of the table (SSStarLawGetNames()): SSSTARLAWNONE ("none"), SSSTARLAWTRESCA ("tresca"),
          SSSTARLAWCOULOMB ("coulomb"), SSSTARLAWORTHOTROPIC ("orthotropic")

   Options Database Key:
.  -snes_ssstar_friction_law <coulomb> - none, tresca, coulomb or orthotropic

   Notes:
   A law takes its parameters from SNESSSStarSetLawParameter() (one value for every node) and
   SNESSSStarSetNodeLawParameter() (one per node): coulomb "friction" (0.3 unless set), tresca "slip_bound",
   orthotropic "friction_1" along "friction_direction" and "friction_2" across it. SNESSSStarSetNodeFrictionLaws()
   sets one law per node.

   Level: beginner

.seealso: `SNESSSStarGetFrictionLaw()`, `SNESSSStarSetNodeFrictionLaws()`, `SNESSSStarSetLawParameter()`,
          `SSStarLawGetNames()`
@*/
PetscErrorCode SNESSSStarSetFrictionLaw(SNES snes, const char law[])
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscValidCharPointer(law, 2);
  PetscTryMethod(snes, "SNESSSStarSetFrictionLaw_C", (SNES, const char[]), (snes, law));
  PetscFunctionReturn(0);
}

/*@C
   SNESSSStarGetFrictionLaw - the friction law of the nodes without a law of their own

   Not Collective

   Input Parameter:
.  snes - the SNES

   Output Parameter:
.  law - its name (owned by ssstar)

   Level: beginner

.seealso: `SNESSSStarSetFrictionLaw()`, `SNESSSStarGetNodeFrictionLaws()`
@*/
PetscErrorCode SNESSSStarGetFrictionLaw(SNES snes, const char *law[])
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscUseMethod(snes, "SNESSSStarGetFrictionLaw_C", (SNES, const char *[]), (snes, law));
  PetscFunctionReturn(0);
}

/*@C
   SNESSSStarSetLawParameter - sets a parameter of the friction laws for every contact node without a value of its own

   Logically Collective

   Input Parameters:
+  snes   - the SNES
.  name   - the parameter: "friction" (coulomb, default 0.3), "slip_bound" (tresca, a force), "friction_1",
            "friction_2", "friction_direction" (orthotropic), or one of another registered law (SSStarLawGetInfo())
.  n      - the number of values: 1, or 3 for a direction
-  values - a coefficient or force >= 0; a direction as x, y, z in global axes (projected onto each node's tangent
            plane)

   Options Database Keys:
+  -snes_ssstar_friction <0.3> - the Coulomb coefficient
.  -snes_ssstar_slip_bound <slip_bound> - the Tresca bound (no default)
.  -snes_ssstar_friction_1 <phi_1> - the orthotropic coefficient along the direction (no default)
.  -snes_ssstar_friction_2 <phi_2> - the orthotropic coefficient across it (no default)
-  -snes_ssstar_friction_direction <x,y,z> - the orthotropic direction (no default)

   Notes:
   A parameter applies to the nodes whose law has it. An unknown name is refused with the list of the parameters.

   Level: intermediate

.seealso: `SNESSSStarSetNodeLawParameter()`, `SNESSSStarSetFrictionLaw()`, `SNESSSStarSetFriction()`
@*/
PetscErrorCode SNESSSStarSetLawParameter(SNES snes, const char name[], PetscInt n, const PetscReal values[])
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscValidCharPointer(name, 2);
  PetscValidRealPointer(values, 4);
  PetscTryMethod(snes, "SNESSSStarSetLawParameter_C", (SNES, const char[], PetscInt, const PetscReal[]), (snes, name, n, values));
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarSetFriction - sets the Coulomb friction coefficient of every node without one of its own (default 0.3):
   SNESSSStarSetLawParameter(snes, "friction", 1, &friction)

   Logically Collective

   Input Parameters:
+  snes     - the SNES
-  friction - the coefficient, >= 0

   Options Database Key:
.  -snes_ssstar_friction <0.3> - the coefficient

   Level: beginner

.seealso: `SNESSSStarGetFriction()`, `SNESSSStarSetLawParameter()`, `SNESSSStarSetNodeLawParameter()`
@*/
PetscErrorCode SNESSSStarSetFriction(SNES snes, PetscReal friction)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscCall(SNESSSStarSetLawParameter(snes, "friction", 1, &friction));
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarGetFriction - the Coulomb coefficient of the nodes without a coefficient of their own

   Not Collective

   Input Parameter:
.  snes - the SNES

   Output Parameter:
.  friction - the coefficient

   Level: beginner

.seealso: `SNESSSStarSetFriction()`, `SNESSSStarGetNodeLawParameter()`
@*/
PetscErrorCode SNESSSStarGetFriction(SNES snes, PetscReal *friction)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscUseMethod(snes, "SNESSSStarGetFriction_C", (SNES, PetscReal *), (snes, friction));
  PetscFunctionReturn(0);
}

/*@C
   SNESSSStarSetNodeLawParameter - one value of a friction-law parameter per contact node

   Collective

   Input Parameters:
+  snes   - the SNES
.  name   - the parameter ("friction", "slip_bound", "friction_1", "friction_2", "friction_direction", ...)
-  values - 1 entry per contact node owned by the rank (3 for a direction, x, y, z in global axes), in the order of the
            contact nodes; NULL: back to the value of SNESSSStarSetLawParameter()

   Notes:
   The SNES keeps a reference to values. An entry SSSTAR_NOT_GIVEN (NaN; for a direction: its first component) gives its node
   the value of SNESSSStarSetLawParameter() as it is at SNESSolve(): a scene hands over the values of its groups without
   fixing the solver's default. The value applies where the node's law has the parameter; it is checked at the
   set-up (a number >= 0; a direction not normal to the node's plane), naming the node, on every rank. A vector of
   the wrong size on any rank is refused on every rank.

   Level: intermediate

.seealso: `SNESSSStarSetLawParameter()`, `SNESSSStarSetNodeFrictionLaws()`, `SNESSSStarGetNodeLawParameter()`
@*/
PetscErrorCode SNESSSStarSetNodeLawParameter(SNES snes, const char name[], Vec values)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscValidCharPointer(name, 2);
  if (values) PetscValidHeaderSpecific(values, VEC_CLASSID, 3);
  PetscTryMethod(snes, "SNESSSStarSetNodeLawParameter_C", (SNES, const char[], Vec), (snes, name, values));
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarSetNodeFrictionLaws - one friction law per contact node owned by the rank

   Collective

   Input Parameters:
+  snes - the SNES
.  n    - the number of contact nodes of this rank
-  laws - the index in the table of laws (SSStarLawGetIndex()) of each node's law, in node order (copied); NULL: every
          node has the law of SNESSSStarSetFrictionLaw()

   Level: intermediate

.seealso: `SNESSSStarSetFrictionLaw()`, `SSStarLawGetIndex()`, `SNESSSStarSetNodeLawParameter()`,
          `SNESSSStarGetNodeFrictionLaws()`
@*/
PetscErrorCode SNESSSStarSetNodeFrictionLaws(SNES snes, PetscInt n, const PetscInt laws[])
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscTryMethod(snes, "SNESSSStarSetNodeFrictionLaws_C", (SNES, PetscInt, const PetscInt[]), (snes, n, laws));
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarGetNodeFrictionLaws - the friction law the solver uses at each contact node of this rank

   Collective

   Input Parameters:
+  snes - the SNES, after SNESSetUp() or SNESSolve()
-  n    - the number of contact nodes of this rank (the length of laws)

   Output Parameter:
.  laws - the index in the table of laws of each node's law (SSStarLawGetNames()), in the order the nodes were
          declared

   Notes:
   What SNESSSStarSetFrictionLaw() and SNESSSStarSetNodeFrictionLaws() together gave each node; the output files record
   it (/contact/friction_law, with the names of the table).

   Level: intermediate

.seealso: `SNESSSStarGetNodeLawParameter()`, `SNESSSStarSetNodeFrictionLaws()`
@*/
PetscErrorCode SNESSSStarGetNodeFrictionLaws(SNES snes, PetscInt n, PetscInt laws[])
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscUseMethod(snes, "SNESSSStarGetNodeFrictionLaws_C", (SNES, PetscInt, PetscInt[]), (snes, n, laws));
  PetscFunctionReturn(0);
}

/*@C
   SNESSSStarGetNodeLawParameter - the value of a friction-law parameter the solver uses at each contact node of this
   rank

   Collective

   Input Parameters:
+  snes - the SNES, after SNESSetUp() or SNESSolve()
.  name - the parameter ("friction", "slip_bound", ...)
-  n    - the number of contact nodes of this rank

   Output Parameter:
.  values - 1 value per node (3 for a direction: the unit direction in use, in global axes), in the order the nodes
            were declared; 0 at the nodes whose law has no such parameter

   Notes:
   The output files of the scenes and SSStarWriteNodeFriction() record every parameter of the laws in use
   (/contact/<parameter>: friction, slip_bound, friction_1, friction_2, friction_direction).

   Level: intermediate

.seealso: `SNESSSStarGetNodeFrictionLaws()`, `SNESSSStarSetNodeLawParameter()`
@*/
PetscErrorCode SNESSSStarGetNodeLawParameter(SNES snes, const char name[], PetscInt n, PetscReal values[])
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscValidCharPointer(name, 2);
  PetscUseMethod(snes, "SNESSSStarGetNodeLawParameter_C", (SNES, const char[], PetscInt, PetscReal[]), (snes, name, n, values));
  PetscFunctionReturn(0);
}
