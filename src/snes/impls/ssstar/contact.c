/*
   The contact of the SNES type "ssstar": what the user declared (the contact points with their rows of the contact
   operator B; the friction laws and their parameters are friction.c's) and what the solver derives from it per node,
   in its order; the public functions of the declaration, each beside the type's implementation.
   One route: SNESSSStarSetContactNodes() declares points against rigid planes, whose rows of B (each node's own dofs
   turned into its frame) are built here and go the way of SNESSSStarSetContactOperator()'s B (contactoperator.c).

   Every check of the declaration is collective (SSStarCheckAllRanks()): a wrong entry on one rank ends every rank with
   its message, so that no rank waits in a collective call.
*/
#include "ssstarimpl.h"
#include "laws/lawimpl.h"

/* A per-node vector must have per entries for each of the nnodes owned contact nodes (nnodes < 0: not known yet) */
PetscErrorCode SSStarContactCheckNodeVector(MPI_Comm comm, Vec v, PetscInt nnodes, PetscInt per, const char what[])
{
  PetscInt n    = per * nnodes;
  char     msg[SSSTAR_MESSAGE_LEN] = "";

  PetscFunctionBegin;
  if (v && nnodes >= 0) PetscCall(VecGetLocalSize(v, &n));
  if (n != per * nnodes) PetscCall(PetscSNPrintf(msg, sizeof(msg), "%s: %" PetscInt_FMT " local entries, expected %" PetscInt_FMT " (%" PetscInt_FMT " per contact node)", what, n, per * nnodes, per));
  PetscCall(SSStarCheckAllRanks(comm, PETSC_ERR_ARG_SIZ, msg));
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarContactReplaceVec(Vec *stored, Vec v)
{
  PetscFunctionBegin;
  if (v) PetscCall(PetscObjectReference((PetscObject)v));
  PetscCall(VecDestroy(stored));
  *stored = v;
  PetscFunctionReturn(0);
}

/* Owned contact nodes as declared so far (-1: every dof, so not known before the set-up) */
PetscErrorCode SSStarContactDeclaredNodes(SSStarContact *ct, PetscInt *n)
{
  PetscFunctionBegin;
  *n = -1;
  if (ct->dofs) {
    PetscCall(ISGetLocalSize(ct->dofs, n));
    *n /= 3;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarContactFindSetting(SSStarContact *ct, const char name[], SSStarLawSetting **setting)
{
  PetscFunctionBegin;
  *setting = NULL;
  for (PetscInt s = 0; s < ct->nsettings && !*setting; s++) {
    PetscBool same;

    PetscCall(PetscStrcmp(name, ct->settings[s].name, &same));
    if (same) *setting = &ct->settings[s];
  }
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

static PetscErrorCode SNESSSStarSetContactNodes_SSStar(SNES snes, IS dofs, Vec normals, Vec gaps)
{
  SSStarContact *ct   = &((SNES_SSStar *)snes->data)->contact;
  MPI_Comm       comm = PetscObjectComm((PetscObject)snes);
  PetscInt       n;
  char           msg[SSSTAR_MESSAGE_LEN] = "";

  PetscFunctionBegin;
  PetscCall(ISGetLocalSize(dofs, &n));
  if (n % 3) PetscCall(PetscSNPrintf(msg, sizeof(msg), "SNESSSStarSetContactNodes: the IS of contact dofs has %" PetscInt_FMT " local entries, not 3 per node", n));
  PetscCall(SSStarCheckAllRanks(comm, PETSC_ERR_ARG_SIZ, msg));
  PetscCall(SSStarContactCheckNodeVector(comm, normals, n / 3, 3, "SNESSSStarSetContactNodes: the normals"));
  PetscCall(SSStarContactCheckNodeVector(comm, gaps, n / 3, 1, "SNESSSStarSetContactNodes: the gaps"));
  for (PetscInt s = 0; s < ct->nsettings; s++) PetscCall(SSStarContactCheckNodeVector(comm, ct->settings[s].perNode, n / 3, ct->settings[s].size, "SNESSSStarSetNodeLawParameter: the values"));
  PetscCall(PetscObjectReference((PetscObject)dofs));
  PetscCall(ISDestroy(&ct->dofs));
  ct->dofs = dofs;
  PetscCall(SSStarContactReplaceVec(&ct->normals, normals));
  PetscCall(SSStarContactReplaceVec(&ct->gaps, gaps));
  PetscCall(MatDestroy(&ct->B)); /* built from the normals at the set-up */
  SSStarContactDeclared(ct);
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

static PetscErrorCode SNESSSStarSetContactOperator_SSStar(SNES snes, IS dofs, Mat B, Vec gaps)
{
  SSStarContact *ct = &((SNES_SSStar *)snes->data)->contact;
  PetscInt       n, m;
  char           msg[SSSTAR_MESSAGE_LEN] = "";

  PetscFunctionBegin;
  PetscCall(ISGetLocalSize(dofs, &n));
  PetscCall(MatGetLocalSize(B, &m, NULL));
  if (m != n) PetscCall(PetscSNPrintf(msg, sizeof(msg), "SNESSSStarSetContactOperator: B has %" PetscInt_FMT " local rows, expected 3 per contact point (%" PetscInt_FMT ")", m, n));
  PetscCall(SSStarCheckAllRanks(PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_SIZ, msg));
  PetscCall(SNESSSStarSetContactNodes_SSStar(snes, dofs, NULL, gaps));
  PetscCall(PetscObjectReference((PetscObject)B));
  ct->B = B;
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

/*
   The offsets of a load path's step (docs/derivation.md (10.4)): data of the next solves, not of the declaration, so
   that the per-node data and the reduction (P) stay. Checked here where the node count is known, again at each solve.
*/
static PetscErrorCode SNESSSStarSetContactOffsets_SSStar(SNES snes, Vec offsets)
{
  SSStarContact *ct = &((SNES_SSStar *)snes->data)->contact;
  PetscInt       n;

  PetscFunctionBegin;
  PetscCall(SSStarContactGetNodeCount(snes, ct, &n));
  if (offsets) PetscCall(SSStarContactCheckNodeVector(PetscObjectComm((PetscObject)snes), offsets, n, 3, "SNESSSStarSetContactOffsets: the offsets"));
  PetscCall(SSStarContactReplaceVec(&ct->offsets, offsets));
  PetscFunctionReturn(0);
}

/*
   The offsets of this solve in the solver's order, as the kernels see them (o_i / d_i, like the gaps), and the norm of
   their tangential parts (the displacement scale of a step whose solution may be u = 0, docs/derivation.md section
   10, "Scaling"); none without offsets (then the gaps: (0, 0, g_i / d_i))
*/
PetscErrorCode SSStarContactSetUpOffsets(MPI_Comm comm, SSStarContact *ct, PetscReal *tangentNorm)
{
  const PetscScalar *a;
  PetscReal          sum = 0;
  char               msg[SSSTAR_MESSAGE_LEN] = "";

  PetscFunctionBegin;
  PetscCall(PetscFree(ct->offset));
  *tangentNorm = 0;
  if (!ct->offsets) PetscFunctionReturn(0);
  PetscCall(SSStarContactCheckNodeVector(comm, ct->offsets, ct->nnodes, 3, "SNESSSStarSetContactOffsets: the offsets"));
  PetscCall(PetscMalloc1(3 * ct->nnodes, &ct->offset));
  PetscCall(VecGetArrayRead(ct->offsets, &a));
  for (PetscInt i = 0; i < ct->nnodes; i++) {
    const PetscInt j = ct->order[i];

    for (PetscInt k = 0; k < 3; k++) {
      const PetscReal o = PetscRealPart(a[3 * j + k]);

      if (PetscIsInfOrNanReal(o) && !msg[0]) PetscCall(PetscSNPrintf(msg, sizeof(msg), "SNESSSStarSetContactOffsets: offset %" PetscInt_FMT " of contact node %" PetscInt_FMT " is %g", k, j, (double)o));
      ct->offset[3 * i + k] = ct->pointScale ? o / ct->pointScale[i] : o;
    }
    sum += PetscSqr(ct->offset[3 * i]) + PetscSqr(ct->offset[3 * i + 1]);
  }
  PetscCall(VecRestoreArrayRead(ct->offsets, &a));
  PetscCall(SSStarCheckAllRanks(comm, PETSC_ERR_ARG_OUTOFRANGE, msg));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &sum, 1, MPIU_REAL, MPIU_SUM, comm));
  *tangentNorm = PetscSqrtReal(sum);
  PetscFunctionReturn(0);
}

/* The solver's node order: the user's nodes sorted by their first dof, so that P's rows follow the dofs. */
static PetscErrorCode BuildOrder(MPI_Comm comm, SSStarContact *ct)
{
  const PetscInt *idx;
  PetscInt       *first, *sorted, n = ct->nnodes;
  PetscBool       isSorted = PETSC_TRUE;

  PetscFunctionBegin;
  PetscCall(ISGetIndices(ct->dofs, &idx));
  for (PetscInt i = 1; i < n; i++)
    if (idx[3 * i] < idx[3 * (i - 1)]) isSorted = PETSC_FALSE;
  PetscCall(PetscMalloc1(n, &ct->order));
  for (PetscInt i = 0; i < n; i++) ct->order[i] = i;
  if (!isSorted) {
    PetscCall(PetscMalloc1(n, &first));
    for (PetscInt i = 0; i < n; i++) first[i] = idx[3 * i];
    PetscCall(PetscSortIntWithArray(n, first, ct->order));
    PetscCall(PetscFree(first));
  }
  PetscCall(PetscMalloc1(3 * n, &sorted));
  for (PetscInt i = 0; i < n; i++)
    for (PetscInt k = 0; k < 3; k++) sorted[3 * i + k] = idx[3 * ct->order[i] + k];
  PetscCall(ISRestoreIndices(ct->dofs, &idx));
  PetscCall(ISCreateGeneral(comm, 3 * n, sorted, PETSC_OWN_POINTER, &ct->isC));
  PetscFunctionReturn(0);
}

/* The owned dofs that are not contact dofs; every contact dof must be owned by the rank that declares it */
static PetscErrorCode BuildInterior(MPI_Comm comm, SSStarContact *ct, Vec x)
{
  PetscInt        lo, hi, n;
  PetscMPIInt     rank;
  IS              sortedC;
  const PetscInt *idx;
  char            msg[SSSTAR_MESSAGE_LEN] = "";

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(VecGetOwnershipRange(x, &lo, &hi));
  PetscCall(ISGetLocalSize(ct->isC, &n));
  PetscCall(ISGetIndices(ct->isC, &idx));
  for (PetscInt i = 0; i < n && !msg[0]; i++)
    if (idx[i] < lo || idx[i] >= hi) PetscCall(PetscSNPrintf(msg, sizeof(msg), "SNESSSStarSetContactNodes: dof %" PetscInt_FMT " of contact node %" PetscInt_FMT " of rank %d is not owned by that rank (it owns %" PetscInt_FMT "..%" PetscInt_FMT "): a rank declares the nodes whose dofs it owns", idx[i], ct->order[i / 3], rank, lo, hi - 1));
  PetscCall(ISRestoreIndices(ct->isC, &idx));
  PetscCall(SSStarCheckAllRanks(comm, PETSC_ERR_ARG_OUTOFRANGE, msg));
  PetscCall(ISDuplicate(ct->isC, &sortedC));
  PetscCall(ISSort(sortedC));
  PetscCall(ISComplement(sortedC, lo, hi, &ct->isI));
  PetscCall(ISDestroy(&sortedC));
  PetscFunctionReturn(0);
}

/*
   The rows of B of nodes against rigid planes: node i's own dofs turned into its frame (t1, t2, n) from the normal n
   (SSStarNodeFrame(); the identity without normals). The normals must be unit vectors.
*/
static PetscErrorCode BuildNodeContactOperator(MPI_Comm comm, SSStarContact *ct, Vec x, Mat *B)
{
  const PetscScalar *na = NULL;
  const PetscInt    *idx;
  PetscInt           m, rstart;
  char               msg[SSSTAR_MESSAGE_LEN] = "";

  PetscFunctionBegin;
  if (ct->normals) PetscCall(VecGetArrayRead(ct->normals, &na));
  for (PetscInt j = 0; na && j < ct->nnodes && !msg[0]; j++) {
    const PetscScalar *n   = &na[3 * j];
    const PetscReal    len = PetscSqrtReal(PetscRealPart(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]));

    if (!(PetscAbsReal(len - 1) <= 1e-8)) PetscCall(PetscSNPrintf(msg, sizeof(msg), "SNESSSStarSetContactNodes: the normal (%g, %g, %g) of contact node %" PetscInt_FMT " is not a unit vector", (double)PetscRealPart(n[0]), (double)PetscRealPart(n[1]), (double)PetscRealPart(n[2]), j));
  }
  PetscCall(SSStarCheckAllRanks(comm, PETSC_ERR_ARG_OUTOFRANGE, msg));
  PetscCall(VecGetLocalSize(x, &m));
  PetscCall(MatCreateAIJ(comm, 3 * ct->nnodes, m, PETSC_DETERMINE, PETSC_DETERMINE, 3, NULL, 3, NULL, B));
  PetscCall(MatGetOwnershipRange(*B, &rstart, NULL));
  PetscCall(ISGetIndices(ct->dofs, &idx));
  for (PetscInt j = 0; j < ct->nnodes; j++) { /* the user's order: B's rows are laid out like the dofs */
    const PetscInt rows[3] = {rstart + 3 * j, rstart + 3 * j + 1, rstart + 3 * j + 2};
    PetscReal      R[9]    = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    PetscScalar    Rs[9];

    if (na) {
      const PetscReal n[3] = {PetscRealPart(na[3 * j]), PetscRealPart(na[3 * j + 1]), PetscRealPart(na[3 * j + 2])};

      SSStarNodeFrame(n, R);
    }
    for (PetscInt k = 0; k < 9; k++) Rs[k] = R[k];
    PetscCall(MatSetValues(*B, 3, rows, 3, &idx[3 * j], Rs, INSERT_VALUES));
  }
  PetscCall(ISRestoreIndices(ct->dofs, &idx));
  if (na) PetscCall(VecRestoreArrayRead(ct->normals, &na));
  PetscCall(MatAssemblyBegin(*B, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*B, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

/*
   The law of every node and its values (section 0 and the law's own section in docs/derivation.md): a node's own
   value of a parameter (SNESSSStarSetNodeLawParameter(); SSSTAR_NOT_GIVEN: none), else the value for every node
   (SNESSSStarSetLawParameter(), -snes_ssstar_<name>); a direction turned into the node's frame. Then the law checks
   and prepares them.
*/
static PetscErrorCode BuildFriction(MPI_Comm comm, SSStarContact *ct)
{
  PetscInt local = 0;
  char     msg[SSSTAR_MESSAGE_LEN] = "";

  PetscFunctionBegin;
  PetscCall(SSStarLawGetNames(&ct->nlaws, NULL));
  PetscCall(PetscCalloc1(ct->nlaws, &ct->lawCounts));
  PetscCall(PetscMalloc1(ct->nnodes, &ct->nodeFriction));
  if (ct->nodeLaws && ct->nNodeLaws != ct->nnodes) PetscCall(PetscSNPrintf(msg, sizeof(msg), "SNESSSStarSetNodeFrictionLaws: %" PetscInt_FMT " laws for %" PetscInt_FMT " contact nodes", ct->nNodeLaws, ct->nnodes));
  for (PetscInt i = 0; i < ct->nnodes && !msg[0]; i++) {
    const PetscInt   j  = ct->order[i]; /* the user's node */
    SSStarFriction  *fr = &ct->nodeFriction[i];
    const PetscReal *R  = ct->frames ? &ct->frames[9 * i] : NULL;
    const char      *problem;

    if (ct->nodeLaws) PetscCall(SSStarLawGet(ct->nodeLaws[j], &fr->law));
    else fr->law = ct->law;
    PetscCall(PetscArrayzero(fr->value, SSSTAR_LAW_MAX_VALUES));
    for (PetscInt p = 0; p < fr->law->nparams && !msg[0]; p++) {
      const SSStarLawParameter *par    = &fr->law->params[p];
      const PetscInt            offset = SSStarLawParameterOffset(fr->law, p);
      SSStarLawSetting         *setting;
      PetscReal                 v[3]   = {0, 0, 0};
      PetscBool                 given  = PETSC_FALSE;
      char                      bad[256];

      PetscCall(SSStarContactFindSetting(ct, par->name, &setting));
      if (setting && setting->perNode) {
        const PetscScalar *a;

        PetscCall(VecGetArrayRead(setting->perNode, &a));
        given = (PetscBool)!PetscIsNanReal(PetscRealPart(a[setting->size * j]));
        for (PetscInt k = 0; given && k < setting->size; k++) v[k] = PetscRealPart(a[setting->size * j + k]);
        PetscCall(VecRestoreArrayRead(setting->perNode, &a));
      }
      if (!given && setting && setting->set) {
        given = PETSC_TRUE;
        for (PetscInt k = 0; k < setting->size; k++) v[k] = setting->value[k];
      }
      if (!given) {
        PetscCall(PetscSNPrintf(msg, sizeof(msg), "Contact node %" PetscInt_FMT " has the friction law %s but no %s: give it with -snes_ssstar_%s, SNESSSStarSetLawParameter() or SNESSSStarSetNodeLawParameter()", j, fr->law->name, par->name, par->name));
        break;
      }
      PetscCall(SSStarLawCheckValues(par, v, bad, sizeof(bad)));
      if (bad[0]) PetscCall(PetscSNPrintf(msg, sizeof(msg), "Contact node %" PetscInt_FMT " (law %s), its %s %s", j, fr->law->name, par->name, bad));
      if (par->kind == SSSTAR_LAW_DIRECTION)
        for (PetscInt r = 0; r < 3; r++) fr->value[offset + r] = R ? R[3 * r] * v[0] + R[3 * r + 1] * v[1] + R[3 * r + 2] * v[2] : v[r];
      else fr->value[offset] = v[0];
    }
    if (msg[0]) break;
    problem = fr->law->ops.prepare ? fr->law->ops.prepare(fr) : NULL;
    if (problem) PetscCall(PetscSNPrintf(msg, sizeof(msg), "Contact node %" PetscInt_FMT " (law %s): %s", j, fr->law->name, problem));
    ct->lawCounts[fr->law->index]++;
    if (fr->law->coupled) local++;
  }
  PetscCall(SSStarCheckAllRanks(comm, PETSC_ERR_ARG_WRONG, msg));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, ct->lawCounts, ct->nlaws, MPIU_INT, MPI_SUM, comm));
  PetscCall(MPIU_Allreduce(&local, &ct->coupled, 1, MPIU_INT, MPI_SUM, comm));
  PetscFunctionReturn(0);
}

/* The initial gaps in the solver's order, as the kernels see them: w_i / d_i = R_i (u_s - M_i u) + g_i / d_i */
static PetscErrorCode BuildGaps(MPI_Comm comm, SSStarContact *ct)
{
  const PetscScalar *a;
  char               msg[SSSTAR_MESSAGE_LEN] = "";

  PetscFunctionBegin;
  if (!ct->gaps) PetscFunctionReturn(0);
  PetscCall(PetscMalloc1(ct->nnodes, &ct->gap));
  PetscCall(VecGetArrayRead(ct->gaps, &a));
  for (PetscInt i = 0; i < ct->nnodes; i++) {
    const PetscReal g = PetscRealPart(a[ct->order[i]]);

    if (PetscIsInfOrNanReal(g) && !msg[0]) PetscCall(PetscSNPrintf(msg, sizeof(msg), "The gap (SNESSSStarSetContactNodes) of contact node %" PetscInt_FMT " is %g", ct->order[i], (double)g));
    ct->gap[i] = ct->pointScale ? g / ct->pointScale[i] : g;
  }
  PetscCall(VecRestoreArrayRead(ct->gaps, &a));
  PetscCall(SSStarCheckAllRanks(comm, PETSC_ERR_ARG_OUTOFRANGE, msg));
  PetscFunctionReturn(0);
}

/*
   The per-node data in the solver's order, rebuilt when the declaration changed (rebuilt says whether it was).
   Collective, and every check collective.
*/
PetscErrorCode SSStarContactSetUp(SNES snes, SSStarContact *ct, PetscBool *rebuilt)
{
  MPI_Comm comm = PetscObjectComm((PetscObject)snes);
  PetscInt n;
  char     msg[SSSTAR_MESSAGE_LEN] = "";

  PetscFunctionBegin;
  if (rebuilt) *rebuilt = PETSC_FALSE;
  if (ct->built == ct->declared) PetscFunctionReturn(0);
  PetscCall(SSStarContactReset(ct));
  if (rebuilt) *rebuilt = PETSC_TRUE;
  if (ct->dofs) {
    Mat B = ct->B;

    PetscCall(ISGetLocalSize(ct->dofs, &n));
    ct->nnodes = n / 3;
    for (PetscInt s = 0; s < ct->nsettings; s++) PetscCall(SSStarContactCheckNodeVector(comm, ct->settings[s].perNode, ct->nnodes, ct->settings[s].size, "SNESSSStarSetNodeLawParameter: the values"));
    PetscCall(BuildOrder(comm, ct));
    PetscCall(BuildInterior(comm, ct, snes->vec_func));
    if (!B) PetscCall(BuildNodeContactOperator(comm, ct, snes->vec_func, &B));
    PetscCall(SSStarContactOperatorSetUp(comm, ct, B, snes->vec_func));
    if (!ct->B) PetscCall(MatDestroy(&B));
  } else {
    PetscCall(VecGetLocalSize(snes->vec_func, &n));
    if (n % 3) PetscCall(PetscSNPrintf(msg, sizeof(msg), "ssstar: local vector size %" PetscInt_FMT " is not a multiple of 3 (one (u_t1, u_t2, u_n) block per contact node); to solve on a whole body, call SNESSSStarSetContactNodes()", n));
    PetscCall(SSStarCheckAllRanks(comm, PETSC_ERR_ARG_SIZ, msg));
    ct->nnodes = n / 3;
    for (PetscInt s = 0; s < ct->nsettings; s++) PetscCall(SSStarContactCheckNodeVector(comm, ct->settings[s].perNode, ct->nnodes, ct->settings[s].size, "SNESSSStarSetNodeLawParameter: the values"));
    PetscCall(PetscMalloc1(ct->nnodes, &ct->order));
    for (PetscInt i = 0; i < ct->nnodes; i++) ct->order[i] = i;
  }
  PetscCall(BuildFriction(comm, ct));
  PetscCall(BuildGaps(comm, ct));
  ct->built = ct->declared;
  PetscFunctionReturn(0);
}

/* The contact nodes of this rank: declared, or (reduced use) 1/3 of the function vector once it exists; -1 before */
PetscErrorCode SSStarContactGetNodeCount(SNES snes, SSStarContact *ct, PetscInt *n)
{
  PetscFunctionBegin;
  PetscCall(SSStarContactDeclaredNodes(ct, n));
  if (*n < 0 && snes->vec_func) {
    PetscCall(VecGetLocalSize(snes->vec_func, n));
    *n /= 3;
  }
  PetscFunctionReturn(0);
}

/* The arrays of a getter must have one entry per node of this rank */
PetscErrorCode SSStarContactCheckNodeArrays(SNES snes, SSStarContact *ct, PetscInt n, const char caller[])
{
  char msg[SSSTAR_MESSAGE_LEN] = "";

  PetscFunctionBegin;
  PetscCheck(snes->vec_func, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_WRONGSTATE, "%s: call SNESSetUp() or SNESSolve() first", caller);
  PetscCall(SSStarContactSetUp(snes, ct, NULL));
  if (n != ct->nnodes) PetscCall(PetscSNPrintf(msg, sizeof(msg), "%s: arrays of %" PetscInt_FMT " entries for the %" PetscInt_FMT " contact nodes of this rank", caller, n, ct->nnodes));
  PetscCall(SSStarCheckAllRanks(PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_SIZ, msg));
  PetscFunctionReturn(0);
}

/* The parameters of the laws in use, set for every node: "  Coulomb friction coefficient phi = 0.3 (or per node)" */
PetscErrorCode SSStarContactViewParameters(SSStarContact *ct, PetscViewer viewer)
{
  PetscFunctionBegin;
  for (PetscInt l = 0; l < ct->nlaws; l++) {
    SSStarLaw law;

    if (!ct->lawCounts[l]) continue;
    PetscCall(SSStarLawGet(l, &law));
    for (PetscInt p = 0; p < law->nparams; p++) {
      SSStarLawSetting *setting;

      PetscCall(SSStarContactFindSetting(ct, law->params[p].name, &setting));
      if (!setting || !setting->set) continue;
      if (setting->size == 1) PetscCall(PetscViewerASCIIPrintf(viewer, "  %s %s %s = %g%s\n", law->label, law->params[p].description, law->params[p].symbol, (double)setting->value[0], setting->perNode ? " (or per node)" : ""));
      else PetscCall(PetscViewerASCIIPrintf(viewer, "  %s %s %s = (%g, %g, %g)%s\n", law->label, law->params[p].description, law->params[p].symbol, (double)setting->value[0], (double)setting->value[1], (double)setting->value[2], setting->perNode ? " (or per node)" : ""));
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarContactView(SSStarContact *ct, PetscViewer viewer)
{
  char counts[256] = "", effects[256] = "";

  PetscFunctionBegin;
  if (!ct->nodeFriction) {
    SSStarLawSetting *setting;

    PetscCall(PetscViewerASCIIPrintf(viewer, "  friction law %s%s", ct->law->name, ct->nodeLaws ? " (and per node)" : ""));
    PetscCall(PetscViewerASCIIUseTabs(viewer, PETSC_FALSE));
    for (PetscInt p = 0; p < ct->law->nparams; p++) {
      PetscCall(SSStarContactFindSetting(ct, ct->law->params[p].name, &setting));
      if (setting && setting->set && setting->size == 1) PetscCall(PetscViewerASCIIPrintf(viewer, ", %s = %g%s", ct->law->params[p].name, (double)setting->value[0], setting->perNode ? " (and per node)" : ""));
    }
    PetscCall(PetscViewerASCIIPrintf(viewer, "\n"));
    PetscCall(PetscViewerASCIIUseTabs(viewer, PETSC_TRUE));
    PetscFunctionReturn(0);
  }
  for (PetscInt l = 0; l < ct->nlaws; l++) {
    SSStarLaw law;
    char      item[64];

    PetscCall(SSStarLawGet(l, &law));
    PetscCall(PetscSNPrintf(item, sizeof(item), "%s%" PetscInt_FMT " %s", l ? ", " : "", ct->lawCounts[l], law->label));
    PetscCall(PetscStrlcat(counts, item, sizeof(counts)));
    if (ct->lawCounts[l] && law->effect) {
      PetscCall(PetscStrlcat(effects, ", ", sizeof(effects)));
      PetscCall(PetscStrlcat(effects, law->effect, sizeof(effects)));
    }
  }
  if (ct->B || ct->T) PetscCall(PetscViewerASCIIPrintf(viewer, "  contact points by a contact operator B%s\n", ct->T ? ", compared with master dofs (changed to the points' variables, T^T K T)" : ""));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  contact nodes: %s%s%s\n", counts, ct->frames ? "; tilted obstacle normals (local frames)" : "", ct->gap ? "; initial gaps" : ""));
  PetscCall(SSStarContactViewParameters(ct, viewer));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  active effects: non-penetration%s\n", effects));
  PetscFunctionReturn(0);
}

/* Drops what was derived from the declaration */
PetscErrorCode SSStarContactReset(SSStarContact *ct)
{
  PetscFunctionBegin;
  PetscCall(ISDestroy(&ct->isC));
  PetscCall(ISDestroy(&ct->isI));
  PetscCall(PetscFree(ct->order));
  PetscCall(PetscFree(ct->frames));
  PetscCall(PetscFree(ct->gap));
  PetscCall(PetscFree(ct->offset));
  PetscCall(PetscFree(ct->pointScale));
  PetscCall(MatDestroy(&ct->T));
  PetscCall(PetscFree(ct->nodeFriction));
  PetscCall(PetscFree(ct->lawCounts));
  ct->nlaws   = 0;
  ct->coupled = 0;
  ct->nnodes  = 0;
  ct->built   = -1;
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarContactDestroy(SSStarContact *ct)
{
  PetscFunctionBegin;
  PetscCall(SSStarContactReset(ct));
  PetscCall(ISDestroy(&ct->dofs));
  PetscCall(MatDestroy(&ct->B));
  PetscCall(VecDestroy(&ct->normals));
  PetscCall(VecDestroy(&ct->gaps));
  PetscCall(VecDestroy(&ct->offsets));
  for (PetscInt s = 0; s < ct->nsettings; s++) PetscCall(VecDestroy(&ct->settings[s].perNode));
  PetscCall(PetscFree(ct->settings));
  ct->nsettings = 0;
  PetscCall(PetscFree(ct->nodeLaws));
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

static PetscErrorCode SNESSSStarGetContactOffsets_SSStar(SNES snes, Vec *offsets)
{
  PetscFunctionBegin;
  *offsets = ((SNES_SSStar *)snes->data)->contact.offsets;
  PetscFunctionReturn(0);
}

/* The implementations of the public functions above, composed on the SNES (SNESSSStarComposeFunctions()) */
static const SSStarComposed Composed[] = {
    {"SNESSSStarSetContactNodes_C", (PetscVoidFunction)SNESSSStarSetContactNodes_SSStar},
    {"SNESSSStarGetContactNodes_C", (PetscVoidFunction)SNESSSStarGetContactNodes_SSStar},
    {"SNESSSStarSetContactOperator_C", (PetscVoidFunction)SNESSSStarSetContactOperator_SSStar},
    {"SNESSSStarSetContactOffsets_C", (PetscVoidFunction)SNESSSStarSetContactOffsets_SSStar},
    {"SNESSSStarGetContactOffsets_C", (PetscVoidFunction)SNESSSStarGetContactOffsets_SSStar},
};

PetscErrorCode SNESSSStarComposeContact(SNES snes, PetscBool on)
{
  PetscFunctionBegin;
  PetscCall(SNESSSStarComposeTable(snes, Composed, PETSC_STATIC_ARRAY_LENGTH(Composed), on));
  PetscFunctionReturn(0);
}
