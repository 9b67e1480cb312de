/*
   The contact of the SNES type "ssstar": what the user declared (the contact points with their rows of the contact
   operator B, the friction laws and their parameters) and what the solver derives from it per node, in its order.
   One route: SNESSSStarSetContactNodes() declares points against rigid planes, whose rows of B (each node's own dofs
   turned into its frame) are built here and go the way of SNESSSStarSetContactOperator()'s B (operator.c).

   Every check of the declaration is collective (SSStarCheckAllRanks()): a wrong entry on one rank ends every rank with
   its message, so that no rank waits in a collective call.
*/
#include "ssstarimpl.h"
#include "laws/lawimpl.h"

/* The message of the first failed check of this rank; checks after it are skipped */
#define SSSTAR_MESSAGE_LEN 512

/* A per-node vector must have per entries for each of the nnodes owned contact nodes (nnodes < 0: not known yet) */
static PetscErrorCode CheckNodeVector(MPI_Comm comm, Vec v, PetscInt nnodes, PetscInt per, const char what[])
{
  PetscInt n    = per * nnodes;
  char     msg[SSSTAR_MESSAGE_LEN] = "";

  PetscFunctionBegin;
  if (v && nnodes >= 0) PetscCall(VecGetLocalSize(v, &n));
  if (n != per * nnodes) PetscCall(PetscSNPrintf(msg, sizeof(msg), "%s: %" PetscInt_FMT " local entries, expected %" PetscInt_FMT " (%" PetscInt_FMT " per contact node)", what, n, per * nnodes, per));
  PetscCall(SSStarCheckAllRanks(comm, PETSC_ERR_ARG_SIZ, msg));
  PetscFunctionReturn(0);
}

static PetscErrorCode ReplaceVec(Vec *stored, Vec v)
{
  PetscFunctionBegin;
  if (v) PetscCall(PetscObjectReference((PetscObject)v));
  PetscCall(VecDestroy(stored));
  *stored = v;
  PetscFunctionReturn(0);
}

/* Owned contact nodes as declared so far (-1: every dof, so not known before the set-up) */
static PetscErrorCode DeclaredNodes(SSStarContact *ct, PetscInt *n)
{
  PetscFunctionBegin;
  *n = -1;
  if (ct->dofs) {
    PetscCall(ISGetLocalSize(ct->dofs, n));
    *n /= 3;
  }
  PetscFunctionReturn(0);
}

/* Every declaration change invalidates the per-node data and the problem */
static void Declared(SSStarContact *ct)
{
  ct->declared++;
}

static PetscErrorCode FindSetting(SSStarContact *ct, const char name[], SSStarLawSetting **setting)
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

/* The setting of a parameter of the registered laws, created when first named; an error for an unknown name */
static PetscErrorCode GetSetting(SSStarContact *ct, const char name[], SSStarLawSetting **setting)
{
  const SSStarLawParameter *par;

  PetscFunctionBegin;
  PetscCall(FindSetting(ct, name, setting));
  if (*setting) PetscFunctionReturn(0);
  PetscCall(SSStarLawGetParameter(name, &par));
  PetscCall(PetscRealloc(sizeof(SSStarLawSetting) * (ct->nsettings + 1), &ct->settings));
  *setting = &ct->settings[ct->nsettings++];
  PetscCall(PetscMemzero(*setting, sizeof(**setting)));
  PetscCall(PetscStrncpy((*setting)->name, name, sizeof((*setting)->name)));
  (*setting)->size = SSStarLawParameterSize(par->kind);
  PetscFunctionReturn(0);
}

/* What is wrong with the values of a parameter ("-0.1: the friction coefficient must be a number >= 0"), or "" */
static PetscErrorCode CheckValues(const SSStarLawParameter *par, const PetscReal v[], char msg[], size_t len)
{
  PetscFunctionBegin;
  msg[0] = 0;
  if (par->kind == SSSTAR_LAW_DIRECTION) {
    if (PetscIsInfOrNanReal(v[0]) || PetscIsInfOrNanReal(v[1]) || PetscIsInfOrNanReal(v[2]) || (v[0] == 0 && v[1] == 0 && v[2] == 0)) PetscCall(PetscSNPrintf(msg, len, "%g,%g,%g: the %s must be a nonzero vector", (double)v[0], (double)v[1], (double)v[2], par->description));
  } else if (PetscIsInfOrNanReal(v[0]) || v[0] < 0) PetscCall(PetscSNPrintf(msg, len, "%g: the %s must be a number >= 0", (double)v[0], par->description));
  PetscFunctionReturn(0);
}

/* Coulomb, and the parameters of the laws with a default at it (the table's: coulomb's friction 0.3) */
PetscErrorCode SSStarContactInitialize(SSStarContact *ct)
{
  PetscInt           nparams;
  const char *const *names;

  PetscFunctionBegin;
  ct->built = -1;
  PetscCall(SSStarContactSetLaw(ct, SSSTARLAWCOULOMB));
  PetscCall(SSStarLawGetParameterNames(&nparams, &names));
  for (PetscInt p = 0; p < nparams; p++) {
    const SSStarLawParameter *par;

    PetscCall(SSStarLawGetParameter(names[p], &par));
    if (par->hasDefault) PetscCall(SSStarContactSetParameter(PETSC_COMM_SELF, ct, par->name, 1, &par->defaultValue));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SNESSSStarSetContactNodes_SSStar(SNES snes, IS dofs, Vec normals, Vec gaps)
{
  SSStarContact *ct   = &((SNES_SSStar *)snes->data)->contact;
  MPI_Comm       comm = PetscObjectComm((PetscObject)snes);
  PetscInt       n;
  char           msg[SSSTAR_MESSAGE_LEN] = "";

  PetscFunctionBegin;
  PetscCall(ISGetLocalSize(dofs, &n));
  if (n % 3) PetscCall(PetscSNPrintf(msg, sizeof(msg), "SNESSSStarSetContactNodes: the IS of contact dofs has %" PetscInt_FMT " local entries, not 3 per node", n));
  PetscCall(SSStarCheckAllRanks(comm, PETSC_ERR_ARG_SIZ, msg));
  PetscCall(CheckNodeVector(comm, normals, n / 3, 3, "SNESSSStarSetContactNodes: the normals"));
  PetscCall(CheckNodeVector(comm, gaps, n / 3, 1, "SNESSSStarSetContactNodes: the gaps"));
  for (PetscInt s = 0; s < ct->nsettings; s++) PetscCall(CheckNodeVector(comm, ct->settings[s].perNode, n / 3, ct->settings[s].size, "SNESSSStarSetNodeLawParameter: the values"));
  PetscCall(PetscObjectReference((PetscObject)dofs));
  PetscCall(ISDestroy(&ct->dofs));
  ct->dofs = dofs;
  PetscCall(ReplaceVec(&ct->normals, normals));
  PetscCall(ReplaceVec(&ct->gaps, gaps));
  PetscCall(MatDestroy(&ct->B)); /* built from the normals at the set-up */
  Declared(ct);
  PetscFunctionReturn(0);
}

PetscErrorCode SNESSSStarSetContactOperator_SSStar(SNES snes, IS dofs, Mat B, Vec gaps)
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

PetscErrorCode SSStarContactSetLaw(SSStarContact *ct, const char law[])
{
  PetscFunctionBegin;
  PetscCall(SSStarLawFind(law, &ct->law));
  Declared(ct);
  PetscFunctionReturn(0);
}

/* The value of a law parameter for every node without one of its own (logically collective: the same on every rank) */
PetscErrorCode SSStarContactSetParameter(MPI_Comm comm, SSStarContact *ct, const char name[], PetscInt n, const PetscReal values[])
{
  SSStarLawSetting         *setting;
  const SSStarLawParameter *par;
  char                      msg[SSSTAR_MESSAGE_LEN];

  PetscFunctionBegin;
  PetscCall(SSStarLawGetParameter(name, &par));
  PetscCheck(n == SSStarLawParameterSize(par->kind), comm, PETSC_ERR_ARG_SIZ, "-snes_ssstar_%s: %" PetscInt_FMT " values given, it takes %" PetscInt_FMT, name, n, SSStarLawParameterSize(par->kind));
  PetscCall(CheckValues(par, values, msg, sizeof(msg)));
  PetscCheck(!msg[0], comm, PETSC_ERR_ARG_OUTOFRANGE, "-snes_ssstar_%s %s", name, msg);
  PetscCall(GetSetting(ct, name, &setting));
  for (PetscInt k = 0; k < n; k++) setting->value[k] = values[k];
  setting->set = PETSC_TRUE;
  Declared(ct);
  PetscFunctionReturn(0);
}

/* The value for every node of a law parameter, if set */
PetscErrorCode SSStarContactGetParameter(SSStarContact *ct, const char name[], PetscInt *n, PetscReal values[], PetscBool *set)
{
  SSStarLawSetting         *setting;
  const SSStarLawParameter *par;

  PetscFunctionBegin;
  PetscCall(SSStarLawGetParameter(name, &par));
  PetscCall(FindSetting(ct, name, &setting));
  *n   = SSStarLawParameterSize(par->kind);
  *set = (PetscBool)(setting && setting->set);
  for (PetscInt k = 0; k < *n; k++) values[k] = *set ? setting->value[k] : 0.0;
  PetscFunctionReturn(0);
}

PetscErrorCode SNESSSStarSetNodeLawParameter_SSStar(SNES snes, const char name[], Vec v)
{
  SSStarContact    *ct = &((SNES_SSStar *)snes->data)->contact;
  SSStarLawSetting *setting;
  PetscInt          n;

  PetscFunctionBegin;
  PetscCall(GetSetting(ct, name, &setting));
  PetscCall(DeclaredNodes(ct, &n));
  PetscCall(CheckNodeVector(PetscObjectComm((PetscObject)snes), v, n, setting->size, "SNESSSStarSetNodeLawParameter: the values"));
  PetscCall(ReplaceVec(&setting->perNode, v));
  Declared(ct);
  PetscFunctionReturn(0);
}

PetscErrorCode SNESSSStarSetNodeFrictionLaws_SSStar(SNES snes, PetscInt n, const PetscInt laws[])
{
  SSStarContact *ct = &((SNES_SSStar *)snes->data)->contact;
  PetscInt       nlaws;
  char           msg[SSSTAR_MESSAGE_LEN] = "";

  PetscFunctionBegin;
  PetscCall(SSStarLawGetNames(&nlaws, NULL));
  for (PetscInt i = 0; laws && i < n && !msg[0]; i++)
    if (laws[i] < 0 || laws[i] >= nlaws) PetscCall(PetscSNPrintf(msg, sizeof(msg), "SNESSSStarSetNodeFrictionLaws: law %" PetscInt_FMT " of contact node %" PetscInt_FMT " is not in the table of laws (0..%" PetscInt_FMT ", SSStarLawGetNames())", laws[i], i, nlaws - 1));
  PetscCall(SSStarCheckAllRanks(PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_OUTOFRANGE, msg));
  PetscCall(PetscFree(ct->nodeLaws));
  ct->nNodeLaws = n;
  if (laws) {
    PetscCall(PetscMalloc1(n, &ct->nodeLaws));
    PetscCall(PetscArraycpy(ct->nodeLaws, laws, n));
  }
  Declared(ct);
  PetscFunctionReturn(0);
}

/*
   The offsets of a load path's step (docs/derivation.md (10.4)): data of the next solves, not of the declaration, so
   that the per-node data and the reduction (P) stay. Checked here where the node count is known, again at each solve.
*/
PetscErrorCode SNESSSStarSetContactOffsets_SSStar(SNES snes, Vec offsets)
{
  SSStarContact *ct = &((SNES_SSStar *)snes->data)->contact;
  PetscInt       n;

  PetscFunctionBegin;
  PetscCall(SSStarContactGetNodeCount(snes, ct, &n));
  if (offsets) PetscCall(CheckNodeVector(PetscObjectComm((PetscObject)snes), offsets, n, 3, "SNESSSStarSetContactOffsets: the offsets"));
  PetscCall(ReplaceVec(&ct->offsets, offsets));
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
  PetscCall(CheckNodeVector(comm, ct->offsets, ct->nnodes, 3, "SNESSSStarSetContactOffsets: the offsets"));
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
static PetscErrorCode BuildNodeOperator(MPI_Comm comm, SSStarContact *ct, Vec x, Mat *B)
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

      PetscCall(FindSetting(ct, par->name, &setting));
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
      PetscCall(CheckValues(par, v, bad, sizeof(bad)));
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
    for (PetscInt s = 0; s < ct->nsettings; s++) PetscCall(CheckNodeVector(comm, ct->settings[s].perNode, ct->nnodes, ct->settings[s].size, "SNESSSStarSetNodeLawParameter: the values"));
    PetscCall(BuildOrder(comm, ct));
    PetscCall(BuildInterior(comm, ct, snes->vec_func));
    if (!B) PetscCall(BuildNodeOperator(comm, ct, snes->vec_func, &B));
    PetscCall(SSStarContactBuildOperator(comm, ct, B, snes->vec_func));
    if (!ct->B) PetscCall(MatDestroy(&B));
  } else {
    PetscCall(VecGetLocalSize(snes->vec_func, &n));
    if (n % 3) PetscCall(PetscSNPrintf(msg, sizeof(msg), "ssstar: local vector size %" PetscInt_FMT " is not a multiple of 3 (one (u_t1, u_t2, u_n) block per contact node); to solve on a whole body, call SNESSSStarSetContactNodes()", n));
    PetscCall(SSStarCheckAllRanks(comm, PETSC_ERR_ARG_SIZ, msg));
    ct->nnodes = n / 3;
    for (PetscInt s = 0; s < ct->nsettings; s++) PetscCall(CheckNodeVector(comm, ct->settings[s].perNode, ct->nnodes, ct->settings[s].size, "SNESSSStarSetNodeLawParameter: the values"));
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
  PetscCall(DeclaredNodes(ct, n));
  if (*n < 0 && snes->vec_func) {
    PetscCall(VecGetLocalSize(snes->vec_func, n));
    *n /= 3;
  }
  PetscFunctionReturn(0);
}

/* The arrays of a getter must have one entry per node of this rank */
static PetscErrorCode CheckNodeArrays(SNES snes, SSStarContact *ct, PetscInt n, const char caller[])
{
  char msg[SSSTAR_MESSAGE_LEN] = "";

  PetscFunctionBegin;
  PetscCheck(snes->vec_func, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_WRONGSTATE, "%s: call SNESSetUp() or SNESSolve() first", caller);
  PetscCall(SSStarContactSetUp(snes, ct, NULL));
  if (n != ct->nnodes) PetscCall(PetscSNPrintf(msg, sizeof(msg), "%s: arrays of %" PetscInt_FMT " entries for the %" PetscInt_FMT " contact nodes of this rank", caller, n, ct->nnodes));
  PetscCall(SSStarCheckAllRanks(PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_SIZ, msg));
  PetscFunctionReturn(0);
}

PetscErrorCode SNESSSStarGetNodeFrictionLaws_SSStar(SNES snes, PetscInt n, PetscInt laws[])
{
  SSStarContact *ct = &((SNES_SSStar *)snes->data)->contact;

  PetscFunctionBegin;
  PetscCall(CheckNodeArrays(snes, ct, n, "SNESSSStarGetNodeFrictionLaws"));
  for (PetscInt i = 0; i < ct->nnodes; i++) laws[ct->order[i]] = ct->nodeFriction[i].law->index;
  PetscFunctionReturn(0);
}

PetscErrorCode SNESSSStarGetNodeLawParameter_SSStar(SNES snes, const char name[], PetscInt n, PetscReal values[])
{
  SSStarContact            *ct = &((SNES_SSStar *)snes->data)->contact;
  const SSStarLawParameter *par;
  PetscInt                  size;

  PetscFunctionBegin;
  PetscCall(SSStarLawGetParameter(name, &par));
  PetscCall(CheckNodeArrays(snes, ct, n, "SNESSSStarGetNodeLawParameter"));
  size = SSStarLawParameterSize(par->kind);
  for (PetscInt i = 0; i < ct->nnodes; i++) {
    const SSStarFriction *fr = &ct->nodeFriction[i];
    const PetscInt        p  = SSStarLawFindParameter(fr->law, name);
    const PetscReal      *R  = ct->frames ? &ct->frames[9 * i] : NULL;
    PetscReal            *v  = &values[size * ct->order[i]];

    for (PetscInt k = 0; k < size; k++) v[k] = 0.0;
    if (p < 0) continue;
    if (par->kind != SSSTAR_LAW_DIRECTION) v[0] = fr->value[SSStarLawParameterOffset(fr->law, p)];
    else { /* the direction in use, in global axes: R^T of the node's */
      const PetscReal *a = &fr->value[SSStarLawParameterOffset(fr->law, p)];

      for (PetscInt k = 0; k < 3; k++) v[k] = R ? R[k] * a[0] + R[3 + k] * a[1] + R[6 + k] * a[2] : a[k];
    }
  }
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

      PetscCall(FindSetting(ct, law->params[p].name, &setting));
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
      PetscCall(FindSetting(ct, ct->law->params[p].name, &setting));
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
