/*
   The contact declaration of the SNES type "ssstar" (which dofs touch which obstacle, with which friction) and the
   reduced problem c(u) = P u - f on the contact dofs: a Schur complement of the user's K in the whole-body use,
   the user's own P in the reduced use.
*/
#include "ssstarimpl.h"

/* A per-node vector must have per entries for each of the nnodes owned contact nodes (nnodes < 0: not known yet) */
static PetscErrorCode CheckNodeVector(Vec v, PetscInt nnodes, PetscInt per, const char what[])
{
  PetscInt n;

  PetscFunctionBegin;
  if (!v || nnodes < 0) PetscFunctionReturn(0);
  PetscCall(VecGetLocalSize(v, &n));
  PetscCheck(n == per * nnodes, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "%s has %" PetscInt_FMT " local entries, expected %" PetscInt_FMT " (%" PetscInt_FMT " per contact node)", what, n, per * nnodes, per);
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

/* Every declaration change invalidates the per-node data and the reduced problem */
static void Declared(SSStarContact *ct)
{
  ct->declared++;
}

PetscErrorCode SNESSSStarSetContactNodes_SSStar(SNES snes, IS dofs, Vec normals, Vec gaps)
{
  SSStarContact *ct = &((SNES_SSStar *)snes->data)->contact;
  PetscInt       n;

  PetscFunctionBegin;
  PetscCall(ISGetLocalSize(dofs, &n));
  PetscCheck(n % 3 == 0, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "SNESSSStarSetContactNodes: the IS of contact dofs has %" PetscInt_FMT " local entries, not 3 per node", n);
  PetscCall(PetscObjectReference((PetscObject)dofs));
  PetscCall(ISDestroy(&ct->dofs));
  ct->dofs = dofs;
  PetscCall(CheckNodeVector(normals, n / 3, 3, "SNESSSStarSetContactNodes: the normals"));
  PetscCall(CheckNodeVector(gaps, n / 3, 1, "SNESSSStarSetContactNodes: the gaps"));
  PetscCall(CheckNodeVector(ct->coefficients, n / 3, 1, "SNESSSStarSetFrictionCoefficients: the coefficients"));
  PetscCall(CheckNodeVector(ct->bounds, n / 3, 1, "SNESSSStarSetSlipBounds: the bounds"));
  PetscCall(ReplaceVec(&ct->normals, normals));
  PetscCall(ReplaceVec(&ct->gaps, gaps));
  PetscCall(MatDestroy(&ct->B)); /* planes: no contact operator */
  Declared(ct);
  PetscFunctionReturn(0);
}

PetscErrorCode SNESSSStarSetContactOperator_SSStar(SNES snes, IS dofs, Mat B, Vec gaps)
{
  SSStarContact *ct = &((SNES_SSStar *)snes->data)->contact;
  PetscInt       n, m;

  PetscFunctionBegin;
  PetscCall(ISGetLocalSize(dofs, &n));
  PetscCheck(n % 3 == 0, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "SNESSSStarSetContactOperator: the IS of the points' own dofs has %" PetscInt_FMT " local entries, not 3 per point", n);
  PetscCall(MatGetLocalSize(B, &m, NULL));
  PetscCheck(m == n, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "SNESSSStarSetContactOperator: B has %" PetscInt_FMT " local rows, expected 3 per contact point (%" PetscInt_FMT ")", m, n);
  PetscCall(SNESSSStarSetContactNodes_SSStar(snes, dofs, NULL, gaps));
  PetscCall(PetscObjectReference((PetscObject)B));
  PetscCall(MatDestroy(&ct->B));
  ct->B = B;
  PetscFunctionReturn(0);
}

PetscErrorCode SNESSSStarSetFrictionCoefficients_SSStar(SNES snes, Vec phi)
{
  SSStarContact *ct = &((SNES_SSStar *)snes->data)->contact;
  PetscInt       n;

  PetscFunctionBegin;
  PetscCall(DeclaredNodes(ct, &n));
  PetscCall(CheckNodeVector(phi, n, 1, "SNESSSStarSetFrictionCoefficients: the coefficients"));
  PetscCall(ReplaceVec(&ct->coefficients, phi));
  Declared(ct);
  PetscFunctionReturn(0);
}

PetscErrorCode SNESSSStarSetSlipBounds_SSStar(SNES snes, Vec s)
{
  SSStarContact *ct = &((SNES_SSStar *)snes->data)->contact;
  PetscInt       n;

  PetscFunctionBegin;
  PetscCall(DeclaredNodes(ct, &n));
  PetscCall(CheckNodeVector(s, n, 1, "SNESSSStarSetSlipBounds: the bounds"));
  PetscCall(ReplaceVec(&ct->bounds, s));
  Declared(ct);
  PetscFunctionReturn(0);
}

PetscErrorCode SNESSSStarSetNodeFrictionLaws_SSStar(SNES snes, PetscInt n, const SSStarFrictionLaw laws[])
{
  SSStarContact *ct = &((SNES_SSStar *)snes->data)->contact;

  PetscFunctionBegin;
  PetscCall(PetscFree(ct->nodeLaws));
  ct->nNodeLaws = n;
  if (laws) {
    PetscCall(PetscMalloc1(n, &ct->nodeLaws));
    for (PetscInt i = 0; i < n; i++) {
      PetscCheck(laws[i] >= SSSTAR_FRICTION_NONE && laws[i] <= SSSTAR_FRICTION_COULOMB, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "SNESSSStarSetNodeFrictionLaws: law %d of node %" PetscInt_FMT " is not none, tresca or coulomb", (int)laws[i], i);
      ct->nodeLaws[i] = laws[i];
    }
  }
  Declared(ct);
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarContactSetLaw(SSStarContact *ct, SSStarFrictionLaw law, PetscReal phi)
{
  PetscFunctionBegin;
  ct->law      = law;
  ct->friction = phi;
  Declared(ct);
  PetscFunctionReturn(0);
}

/* The solver's node order: the user's nodes sorted by their first dof, so that P's rows follow the dofs. */
static PetscErrorCode BuildOrder(MPI_Comm comm, SSStarContact *ct)
{
  const PetscInt *idx;
  PetscInt       *first, *sorted, n = ct->nnodes;
  PetscBool       isSorted = PETSC_TRUE;

  PetscFunctionBegin;
  PetscCall(PetscFree(ct->order));
  PetscCall(ISDestroy(&ct->isC));
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
static PetscErrorCode BuildInterior(SSStarContact *ct, Vec x)
{
  PetscInt lo, hi, n;
  IS       sortedC;
  const PetscInt *idx;

  PetscFunctionBegin;
  PetscCall(ISDestroy(&ct->isI));
  PetscCall(VecGetOwnershipRange(x, &lo, &hi));
  PetscCall(ISGetLocalSize(ct->isC, &n));
  PetscCall(ISGetIndices(ct->isC, &idx));
  for (PetscInt i = 0; i < n; i++) PetscCheck(idx[i] >= lo && idx[i] < hi, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "SNESSSStarSetContactNodes: dof %" PetscInt_FMT " of contact node %" PetscInt_FMT " is not owned by this rank (owned: %" PetscInt_FMT "..%" PetscInt_FMT ")", idx[i], ct->order[i / 3], lo, hi - 1);
  PetscCall(ISRestoreIndices(ct->isC, &idx));
  PetscCall(ISDuplicate(ct->isC, &sortedC));
  PetscCall(ISSort(sortedC));
  PetscCall(ISComplement(sortedC, lo, hi, &ct->isI));
  PetscCall(ISDestroy(&sortedC));
  PetscFunctionReturn(0);
}

static PetscErrorCode BuildFrames(MPI_Comm comm, SSStarContact *ct)
{
  const PetscScalar *na;
  PetscBool          tilted = PETSC_FALSE;

  PetscFunctionBegin;
  PetscCall(PetscFree(ct->frames));
  if (!ct->normals) PetscFunctionReturn(0);
  PetscCall(VecGetArrayRead(ct->normals, &na));
  for (PetscInt i = 0; i < ct->nnodes; i++) {
    const PetscScalar *n   = &na[3 * ct->order[i]];
    const PetscReal    len = PetscSqrtReal(PetscRealPart(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]));

    PetscCheck(PetscAbsReal(len - 1) <= 1e-8, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "SNESSSStarSetContactNodes: the normal (%g, %g, %g) of contact node %" PetscInt_FMT " is not a unit vector", (double)PetscRealPart(n[0]), (double)PetscRealPart(n[1]), (double)PetscRealPart(n[2]), ct->order[i]);
    if (n[0] != 0.0 || n[1] != 0.0 || n[2] != 1.0) tilted = PETSC_TRUE;
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &tilted, 1, MPIU_BOOL, MPI_LOR, comm));
  if (tilted) {
    PetscCall(PetscMalloc1(9 * ct->nnodes, &ct->frames));
    for (PetscInt i = 0; i < ct->nnodes; i++) {
      const PetscReal n[3] = {PetscRealPart(na[3 * ct->order[i]]), PetscRealPart(na[3 * ct->order[i] + 1]), PetscRealPart(na[3 * ct->order[i] + 2])};

      SSStarNodeFrame(n, &ct->frames[9 * i]);
    }
  }
  PetscCall(VecRestoreArrayRead(ct->normals, &na));
  PetscFunctionReturn(0);
}

/*
   A per-node value of the user's vector v (NULL: fallback), checked to be finite and >= 0 unless negative is allowed;
   with allowDefault an entry PETSC_DEFAULT takes the fallback too
*/
static PetscErrorCode NodeValues(SSStarContact *ct, Vec v, PetscReal fallback, PetscBool allowNegative, PetscBool allowDefault, const char what[], PetscReal out[])
{
  const PetscScalar *a;

  PetscFunctionBegin;
  if (!v) {
    for (PetscInt i = 0; i < ct->nnodes; i++) out[i] = fallback;
    PetscFunctionReturn(0);
  }
  PetscCall(VecGetArrayRead(v, &a));
  for (PetscInt i = 0; i < ct->nnodes; i++) {
    out[i] = PetscRealPart(a[ct->order[i]]);
    if (allowDefault && out[i] == (PetscReal)PETSC_DEFAULT) out[i] = fallback;
    PetscCheck(!PetscIsInfOrNanReal(out[i]) && (allowNegative || out[i] >= 0), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "%s of contact node %" PetscInt_FMT " is %g", what, ct->order[i], (double)out[i]);
  }
  PetscCall(VecRestoreArrayRead(v, &a));
  PetscFunctionReturn(0);
}

static PetscErrorCode BuildFriction(MPI_Comm comm, SSStarContact *ct)
{
  PetscReal *phi, *bound;

  PetscFunctionBegin;
  PetscCall(PetscFree(ct->nodeFriction));
  PetscCall(PetscFree(ct->gap));
  PetscCheck(!ct->nodeLaws || ct->nNodeLaws == ct->nnodes, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "SNESSSStarSetNodeFrictionLaws: %" PetscInt_FMT " laws for %" PetscInt_FMT " contact nodes", ct->nNodeLaws, ct->nnodes);
  PetscCall(PetscMalloc1(ct->nnodes, &ct->nodeFriction));
  PetscCall(PetscMalloc2(ct->nnodes, &phi, ct->nnodes, &bound));
  PetscCall(NodeValues(ct, ct->coefficients, ct->friction, PETSC_FALSE, PETSC_TRUE, "The friction coefficient (SNESSSStarSetFrictionCoefficients)", phi));
  PetscCall(NodeValues(ct, ct->bounds, 0.0, PETSC_FALSE, PETSC_FALSE, "The slip bound (SNESSSStarSetSlipBounds)", bound));
  PetscCall(PetscArrayzero(ct->lawCounts, 3));
  for (PetscInt i = 0; i < ct->nnodes; i++) {
    SSStarFriction *fr = &ct->nodeFriction[i];

    fr->law   = ct->nodeLaws ? ct->nodeLaws[ct->order[i]] : ct->law;
    fr->phi   = phi[i];
    fr->bound = bound[i];
    PetscCheck(fr->law != SSSTAR_FRICTION_TRESCA || ct->bounds, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONGSTATE, "Contact node %" PetscInt_FMT " has Tresca friction but no slip bound: call SNESSSStarSetSlipBounds()", ct->order[i]);
    ct->lawCounts[fr->law]++;
  }
  PetscCall(PetscFree2(phi, bound));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, ct->lawCounts, 3, MPIU_INT, MPI_SUM, comm));
  ct->hasFriction = (PetscBool)(ct->lawCounts[SSSTAR_FRICTION_TRESCA] + ct->lawCounts[SSSTAR_FRICTION_COULOMB] > 0);
  if (ct->gaps) {
    PetscCall(PetscMalloc1(ct->nnodes, &ct->gap));
    PetscCall(NodeValues(ct, ct->gaps, 0.0, PETSC_TRUE, PETSC_FALSE, "The gap (SNESSSStarSetContactNodes)", ct->gap));
  }
  PetscFunctionReturn(0);
}

/* The per-node data in the solver's order, rebuilt when the declaration changed */
PetscErrorCode SSStarContactSetUp(SNES snes, SSStarContact *ct)
{
  MPI_Comm comm = PetscObjectComm((PetscObject)snes);
  PetscInt n;

  PetscFunctionBegin;
  if (ct->built == ct->declared) PetscFunctionReturn(0);
  PetscCall(SSStarContactReset(ct));
  if (ct->dofs) {
    PetscCall(ISGetLocalSize(ct->dofs, &n));
    ct->nnodes = n / 3;
    PetscCall(BuildOrder(comm, ct));
    PetscCall(BuildInterior(ct, snes->vec_func));
  } else {
    PetscCall(VecGetLocalSize(snes->vec_func, &n));
    PetscCheck(n % 3 == 0, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "ssstar: local vector size %" PetscInt_FMT " is not a multiple of 3 (one (u_t1, u_t2, u_n) block per contact node); to solve on a whole body, call SNESSSStarSetContactNodes()", n);
    ct->nnodes = n / 3;
    PetscCall(PetscMalloc1(ct->nnodes, &ct->order));
    for (PetscInt i = 0; i < ct->nnodes; i++) ct->order[i] = i;
  }
  PetscCall(CheckNodeVector(ct->coefficients, ct->nnodes, 1, "SNESSSStarSetFrictionCoefficients: the coefficients"));
  PetscCall(CheckNodeVector(ct->bounds, ct->nnodes, 1, "SNESSSStarSetSlipBounds: the bounds"));
  if (ct->B) PetscCall(SSStarContactBuildOperator(comm, ct, snes->vec_func));
  else PetscCall(BuildFrames(comm, ct));
  PetscCall(BuildFriction(comm, ct));
  if (ct->gap && ct->pointScale) /* w_i / d_i = R_i (u_s - M_i u) + g_i / d_i */
    for (PetscInt i = 0; i < ct->nnodes; i++) ct->gap[i] /= ct->pointScale[i];
  ct->built = ct->declared;
  PetscFunctionReturn(0);
}

/*
   K from the user's Jacobian routine. Not SNESComputeJacobian(): it hands K to the SNES's KSP, which belongs to the
   Newton system here.
*/
static PetscErrorCode ComputeK(SNES snes, Mat *K)
{
  Mat   A, B;
  void *ctx;
  PetscErrorCode (*jac)(SNES, Vec, Mat, Mat, void *);

  PetscFunctionBegin;
  PetscCall(SNESGetJacobian(snes, &A, &B, &jac, &ctx));
  if (jac) {
    PetscCall(PetscLogEventBegin(SNES_JacobianEval, snes, snes->vec_sol, A, B));
    PetscCallBack("SNES callback Jacobian", (*jac)(snes, snes->vec_sol, A, B, ctx));
    PetscCall(PetscLogEventEnd(SNES_JacobianEval, snes, snes->vec_sol, A, B));
  }
  *K = A;
  PetscFunctionReturn(0);
}

/* The mean diagonal entry of the contact rows of K and their largest sum |K_ij| (the scaling's data, section 6) */
static PetscErrorCode ContactRowStatistics(SSStarContact *ct, Mat K)
{
  PetscInt           n, rstart, ncols;
  const PetscInt    *rows = NULL, *cols;
  const PetscScalar *vals;
  PetscReal          sums[2] = {0, 0}, rowmax = 0;

  PetscFunctionBegin;
  PetscCall(MatGetOwnershipRange(K, &rstart, NULL));
  if (ct->isC) {
    PetscCall(ISGetLocalSize(ct->isC, &n));
    PetscCall(ISGetIndices(ct->isC, &rows));
  } else PetscCall(MatGetLocalSize(K, &n, NULL));
  for (PetscInt k = 0; k < n; k++) {
    const PetscInt row = rows ? rows[k] : rstart + k;
    PetscReal      sum = 0;

    PetscCall(MatGetRow(K, row, &ncols, &cols, &vals));
    for (PetscInt j = 0; j < ncols; j++) {
      sum += PetscAbsScalar(vals[j]);
      if (cols[j] == row) sums[0] += PetscRealPart(vals[j]);
    }
    PetscCall(MatRestoreRow(K, row, &ncols, &cols, &vals));
    rowmax = PetscMax(rowmax, sum);
  }
  if (rows) PetscCall(ISRestoreIndices(ct->isC, &rows));
  sums[1] = n;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, sums, 2, MPIU_REAL, MPIU_SUM, PetscObjectComm((PetscObject)K)));
  PetscCall(MPIU_Allreduce(&rowmax, &ct->maxRowSum, 1, MPIU_REAL, MPIU_MAX, PetscObjectComm((PetscObject)K)));
  ct->meanDiag = sums[1] > 0 ? sums[0] / sums[1] : 0;
  PetscFunctionReturn(0);
}

/* Where the contact dofs sit in A's vectors: 3 i + k in a reduced space, their own offsets on the whole body */
static PetscErrorCode BuildLayout(SSStarContact *ct, PetscBool wholeBody)
{
  PetscInt        rstart, nlocal, *mark;
  const PetscInt *idx;

  PetscFunctionBegin;
  PetscCall(PetscFree(ct->layoutDofs));
  PetscCall(PetscFree(ct->free));
  ct->nfree = 0;
  PetscCall(PetscMalloc1(3 * ct->nnodes, &ct->layoutDofs));
  if (!wholeBody) {
    for (PetscInt k = 0; k < 3 * ct->nnodes; k++) ct->layoutDofs[k] = k;
    PetscFunctionReturn(0);
  }
  PetscCall(MatGetOwnershipRange(ct->A, &rstart, NULL));
  PetscCall(MatGetLocalSize(ct->A, &nlocal, NULL));
  PetscCall(ISGetIndices(ct->isC, &idx));
  PetscCall(PetscCalloc1(nlocal, &mark));
  for (PetscInt k = 0; k < 3 * ct->nnodes; k++) {
    ct->layoutDofs[k]        = idx[k] - rstart;
    mark[idx[k] - rstart] = 1;
  }
  PetscCall(ISRestoreIndices(ct->isC, &idx));
  ct->nfree = nlocal - 3 * ct->nnodes;
  PetscCall(PetscMalloc1(ct->nfree, &ct->free));
  for (PetscInt j = 0, a = 0; j < nlocal; j++)
    if (!mark[j]) ct->free[a++] = j;
  PetscCall(PetscFree(mark));
  PetscFunctionReturn(0);
}

/* The Newton step that fits A: the whole body for none, else by P's storage */
static PetscErrorCode ChooseNewton(SSStarContact *ct)
{
  PetscBool dense;

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompareAny((PetscObject)ct->A, &dense, MATDENSE, MATMPIDENSE, MATSEQDENSE, ""));
  ct->newtonType = dense ? SSSTAR_NEWTON_DENSE : SSSTAR_NEWTON_SPARSE;
  PetscFunctionReturn(0);
}

/*
   A and f for the current K and load: the Jacobian is evaluated once (c is affine), b = -F(0), and in the whole-body
   use K is reduced to the contact dofs, or kept (reduction none), again only when K changed.
*/
PetscErrorCode SSStarContactSetUpProblem(SNES snes, SSStarContact *ct)
{
  Mat                 K = NULL;
  PetscObjectState    state;
  Vec                 zero, bC;
  PetscInt            nI = 0;
  SSStarReductionType type = SSSTAR_REDUCTION_DIRECT;

  PetscFunctionBegin;
  PetscCall(ComputeK(snes, &K));
  PetscCall(PetscObjectStateGet((PetscObject)K, &state));
  if (K != ct->K || state != ct->Kstate || !ct->A) {
    PetscCall(SSStarReductionDestroy(&ct->reduction));
    PetscCall(MatDestroy(&ct->A));
    PetscCall(MatDestroy(&ct->Kw));
    PetscCall(VecDestroy(&ct->f));
    PetscCall(SSStarContactTransformStiffness(ct, K, &ct->Kw));
    PetscCall(ContactRowStatistics(ct, ct->Kw));
    if (ct->isI) PetscCall(ISGetSize(ct->isI, &nI));
    if (ct->dofs && nI > 0) {
      PetscCall(SSStarReductionCreate(ct->Kw, ct->isC, ct->isI, ct->reductionType, ct->memoryLimit, &ct->reduction));
      PetscCall(SSStarReductionGetOperator(ct->reduction, &ct->A));
      PetscCall(PetscObjectReference((PetscObject)ct->A));
      PetscCall(SSStarReductionGetType(ct->reduction, &type));
    } else if (ct->dofs) { /* every dof a contact dof, in another order */
      PetscCall(MatCreateSubMatrix(ct->Kw, ct->isC, ct->isC, MAT_INITIAL_MATRIX, &ct->A));
    } else {
      PetscCall(PetscObjectReference((PetscObject)K));
      ct->A = K;
    }
    if (type == SSSTAR_REDUCTION_NONE) ct->newtonType = SSSTAR_NEWTON_FULL;
    else PetscCall(ChooseNewton(ct));
    PetscCall(BuildLayout(ct, (PetscBool)(type == SSSTAR_REDUCTION_NONE)));
    PetscCall(MatCreateVecs(ct->A, &ct->f, NULL));
    ct->K      = K;
    ct->Kstate = state;
  }
  if (!ct->b) PetscCall(VecDuplicate(snes->vec_func, &ct->b));
  PetscCall(VecDuplicate(snes->vec_sol, &zero));
  PetscCall(VecZeroEntries(zero));
  PetscCall(SNESComputeFunction(snes, zero, ct->b));
  PetscCall(VecDestroy(&zero));
  PetscCall(VecScale(ct->b, -1.0));
  PetscCall(VecDestroy(&ct->bw));
  if (ct->T) { /* the load in the points' variables: T^T b */
    PetscCall(VecDuplicate(ct->b, &ct->bw));
    PetscCall(MatMultTranspose(ct->T, ct->b, ct->bw));
  } else {
    PetscCall(PetscObjectReference((PetscObject)ct->b));
    ct->bw = ct->b;
  }
  if (ct->reduction) PetscCall(SSStarReductionReduceLoad(ct->reduction, ct->bw, ct->f));
  else if (ct->dofs) {
    PetscCall(VecGetSubVector(ct->bw, ct->isC, &bC));
    PetscCall(VecCopy(bC, ct->f));
    PetscCall(VecRestoreSubVector(ct->bw, ct->isC, &bC));
  } else PetscCall(VecCopy(ct->b, ct->f));
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarContactGetLayout(SSStarContact *ct, SSStarContactLayout *layout)
{
  PetscFunctionBegin;
  layout->nnodes = ct->nnodes;
  layout->dofs   = ct->layoutDofs;
  layout->frames = ct->frames;
  PetscFunctionReturn(0);
}

/* u, the solver's unknown, from the SNES vector x (in the points' variables, T^-1 x) */
PetscErrorCode SSStarContactGetInitialGuess(SSStarContact *ct, Vec x, Vec u)
{
  Vec v, vC;

  PetscFunctionBegin;
  if (!ct->dofs) {
    PetscCall(VecCopy(x, u));
    PetscFunctionReturn(0);
  }
  PetscCall(VecDuplicate(x, &v));
  PetscCall(SSStarContactToPointVariables(ct, x, v));
  if (ct->newtonType == SSSTAR_NEWTON_FULL) PetscCall(VecCopy(v, u));
  else {
    PetscCall(VecGetSubVector(v, ct->isC, &vC));
    PetscCall(VecCopy(vC, u));
    PetscCall(VecRestoreSubVector(v, ct->isC, &vC));
  }
  PetscCall(VecDestroy(&v));
  PetscFunctionReturn(0);
}

/*
   The SNES vector x from the solution u and its contact force c = A u - f: in the whole-body use v = K^-1 (b + E_C c)
   (or u itself on the whole body), in the points' variables, and x = T v
*/
PetscErrorCode SSStarContactSetSolution(SSStarContact *ct, Vec u, Vec c, Vec x)
{
  Vec v;

  PetscFunctionBegin;
  if (!ct->dofs) {
    PetscCall(VecCopy(u, x));
    PetscFunctionReturn(0);
  }
  PetscCall(VecDuplicate(x, &v));
  if (ct->reduction) PetscCall(SSStarReductionRecover(ct->reduction, ct->bw, u, c, v));
  else PetscCall(VecISCopy(v, ct->isC, SCATTER_FORWARD, u));
  if (ct->T) PetscCall(MatMult(ct->T, v, x));
  else PetscCall(VecCopy(v, x));
  PetscCall(VecDestroy(&v));
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarContactView(SSStarContact *ct, PetscViewer viewer)
{
  PetscFunctionBegin;
  if (ct->dofs && ct->reduction) {
    SSStarReductionType type;
    char                chosen[64] = "";

    PetscCall(SSStarReductionGetType(ct->reduction, &type));
    if (ct->reductionType == SSSTAR_REDUCTION_AUTO) PetscCall(PetscSNPrintf(chosen, sizeof(chosen), " (chosen by auto)"));
    if (type == SSSTAR_REDUCTION_NONE) PetscCall(PetscViewerASCIIPrintf(viewer, "  whole-body problem: solved on the whole body, P never formed (reduction none%s)\n", chosen));
    else PetscCall(PetscViewerASCIIPrintf(viewer, "  whole-body problem: K reduced to the contact dofs by the %s Schur complement%s\n", SSStarReductionTypes[type], chosen));
  } else if (ct->dofs) PetscCall(PetscViewerASCIIPrintf(viewer, "  whole-body problem: reduction %s (decided at the first solve)\n", SSStarReductionTypes[ct->reductionType]));
  else PetscCall(PetscViewerASCIIPrintf(viewer, "  reduced problem: every dof is a contact dof (c = P u - f)\n"));
  if (!ct->nodeFriction) {
    PetscCall(PetscViewerASCIIPrintf(viewer, "  friction law %s%s", SSStarFrictionLaws[ct->law], ct->nodeLaws ? " (and per node)" : ""));
    if (ct->law == SSSTAR_FRICTION_COULOMB) PetscCall(PetscViewerASCIIPrintf(viewer, ", phi = %g%s", (double)ct->friction, ct->coefficients ? " (and per node)" : ""));
    PetscCall(PetscViewerASCIIPrintf(viewer, "\n"));
    PetscFunctionReturn(0);
  }
  if (ct->B) PetscCall(PetscViewerASCIIPrintf(viewer, "  contact points by a contact operator B%s\n", ct->T ? ", compared with master dofs (changed to the points' variables, T^T K T)" : ""));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  contact nodes: %" PetscInt_FMT " frictionless, %" PetscInt_FMT " Tresca, %" PetscInt_FMT " Coulomb%s%s\n", ct->lawCounts[SSSTAR_FRICTION_NONE], ct->lawCounts[SSSTAR_FRICTION_TRESCA], ct->lawCounts[SSSTAR_FRICTION_COULOMB], ct->frames ? "; tilted obstacle normals (local frames)" : "", ct->gap ? "; initial gaps" : ""));
  if (ct->lawCounts[SSSTAR_FRICTION_COULOMB]) PetscCall(PetscViewerASCIIPrintf(viewer, "  Coulomb friction coefficient phi = %g%s\n", (double)ct->friction, ct->coefficients ? " (or per node)" : ""));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  active effects: non-penetration%s%s\n", ct->lawCounts[SSSTAR_FRICTION_TRESCA] ? ", Tresca friction" : "", ct->lawCounts[SSSTAR_FRICTION_COULOMB] ? ", Coulomb friction" : ""));
  PetscFunctionReturn(0);
}

/* Drops what was derived from the declaration and from K */
PetscErrorCode SSStarContactReset(SSStarContact *ct)
{
  PetscFunctionBegin;
  PetscCall(ISDestroy(&ct->isC));
  PetscCall(ISDestroy(&ct->isI));
  PetscCall(PetscFree(ct->order));
  PetscCall(PetscFree(ct->frames));
  PetscCall(PetscFree(ct->gap));
  PetscCall(PetscFree(ct->nodeFriction));
  PetscCall(SSStarReductionDestroy(&ct->reduction));
  PetscCall(MatDestroy(&ct->A));
  PetscCall(MatDestroy(&ct->Kw));
  PetscCall(MatDestroy(&ct->T));
  PetscCall(PetscFree(ct->pointScale));
  PetscCall(VecDestroy(&ct->f));
  PetscCall(VecDestroy(&ct->b));
  PetscCall(VecDestroy(&ct->bw));
  PetscCall(PetscFree(ct->layoutDofs));
  PetscCall(PetscFree(ct->free));
  ct->nfree  = 0;
  ct->K      = NULL;
  ct->nnodes = 0;
  ct->built  = -1;
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
  PetscCall(VecDestroy(&ct->coefficients));
  PetscCall(VecDestroy(&ct->bounds));
  PetscCall(PetscFree(ct->nodeLaws));
  PetscFunctionReturn(0);
}
