/*
   The problem the iteration of the SNES type "ssstar" runs on, c(u) = A u - f: the user's reduced P and f, or the
   user's K reduced to the contact dofs (a Schur complement P, src/reduction/), or K itself on the whole body (the
   reduction none). The reduction says which (SSStarReductionIsWholeBody()); the Newton step that fits A is chosen
   here, by name. A residual that is not affine (nonlinear.c) runs on c(u) = T^T F(T u) with A its Jacobian at the
   iterate, on the whole body or in the reduced use.
*/
#include "ssstarimpl.h"

/*
   K, the user's Jacobian at x. Not SNESComputeJacobian(): it hands K to the SNES's KSP, which belongs to the Newton
   system here.
*/
PetscErrorCode SSStarProblemComputeJacobian(SNES snes, Vec x, Mat *K)
{
  Mat   A, B;
  void *ctx;
  PetscErrorCode (*jac)(SNES, Vec, Mat, Mat, void *);

  PetscFunctionBegin;
  PetscCall(SNESGetJacobian(snes, &A, &B, &jac, &ctx));
  if (jac) {
    PetscCall(PetscLogEventBegin(SNES_JacobianEval, snes, x, A, B));
    PetscCallBack("SNES callback Jacobian", (*jac)(snes, x, A, B, ctx));
    PetscCall(PetscLogEventEnd(SNES_JacobianEval, snes, x, A, B));
  }
  *K = A;
  PetscFunctionReturn(0);
}

/* The mean diagonal entry of the contact rows of K and their largest sum |K_ij| (the scaling's data, section 6) */
static PetscErrorCode ContactRowStatistics(SSStarContact *ct, SSStarProblem *pb, Mat K)
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
  PetscCall(MPIU_Allreduce(&rowmax, &pb->maxRowSum, 1, MPIU_REAL, MPIU_MAX, PetscObjectComm((PetscObject)K)));
  pb->meanDiag = sums[1] > 0 ? sums[0] / sums[1] : 0;
  PetscFunctionReturn(0);
}

/* Where the contact dofs sit in A's vectors: 3 i + k in a reduced space, their own offsets on the whole body */
static PetscErrorCode BuildLayout(SSStarContact *ct, SSStarProblem *pb)
{
  PetscInt        rstart, nlocal, *mark;
  const PetscInt *idx;

  PetscFunctionBegin;
  PetscCall(PetscFree(pb->layoutDofs));
  PetscCall(PetscFree(pb->free));
  pb->nfree = 0;
  PetscCall(PetscMalloc1(3 * ct->nnodes, &pb->layoutDofs));
  if (!pb->wholeBody) {
    for (PetscInt k = 0; k < 3 * ct->nnodes; k++) pb->layoutDofs[k] = k;
    PetscFunctionReturn(0);
  }
  PetscCall(MatGetOwnershipRange(pb->A, &rstart, NULL));
  PetscCall(MatGetLocalSize(pb->A, &nlocal, NULL));
  PetscCall(ISGetIndices(ct->isC, &idx));
  PetscCall(PetscCalloc1(nlocal, &mark));
  for (PetscInt k = 0; k < 3 * ct->nnodes; k++) {
    pb->layoutDofs[k]     = idx[k] - rstart;
    mark[idx[k] - rstart] = 1;
  }
  PetscCall(ISRestoreIndices(ct->isC, &idx));
  pb->nfree = nlocal - 3 * ct->nnodes;
  PetscCall(PetscMalloc1(pb->nfree, &pb->free));
  for (PetscInt j = 0, a = 0; j < nlocal; j++)
    if (!mark[j]) pb->free[a++] = j;
  PetscCall(PetscFree(mark));
  PetscFunctionReturn(0);
}

/* The Newton step that fits A: the whole body's, else by P's storage */
static PetscErrorCode ChooseNewton(SSStarProblem *pb)
{
  PetscBool dense;

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompareAny((PetscObject)pb->A, &dense, MATDENSE, MATMPIDENSE, MATSEQDENSE, ""));
  pb->newtonType = pb->wholeBody ? SSSTARNEWTONWHOLEBODY : dense ? SSSTARNEWTONDENSE : SSSTARNEWTONSPARSE;
  PetscFunctionReturn(0);
}

/*
   The reduction of K (in the points' variables) to the contact dofs, with the SNES's options prefix for its solvers. A
   nonlinear residual stays on the whole body (docs/derivation.md section 17): the Schur complement of its Jacobian
   would be computed again at every iterate.
*/
static PetscErrorCode CreateReduction(SNES snes, SSStarContact *ct, SSStarProblem *pb, PetscBool nonlinear)
{
  const char *prefix, *type = pb->reductionType;

  PetscFunctionBegin;
  if (nonlinear) {
    PetscBool isauto, none;

    PetscCall(PetscStrcmp(type, SSSTARREDUCTIONAUTO, &isauto));
    PetscCall(PetscStrcmp(type, SSSTARREDUCTIONNONE, &none));
    PetscCheck(isauto || none, PetscObjectComm((PetscObject)snes), PETSC_ERR_SUP, "ssstar: -snes_ssstar_reduction %s with a residual treated as nonlinear (%s): the Schur complement of the Jacobian would be computed again at every iterate; such a residual is solved on the whole body (-snes_ssstar_reduction none or auto), or declare it affine (SNESSSStarSetAffine(), -snes_ssstar_affine)", type,
               ct->update ? "the contact is measured at the iterates, SNESSSStarSetContactUpdate()" : "not declared affine");
    type = SSSTARREDUCTIONNONE;
  }
  PetscCall(SNESGetOptionsPrefix(snes, &prefix));
  PetscCall(SSStarReductionCreate(PetscObjectComm((PetscObject)snes), &pb->reduction));
  PetscCall(SSStarReductionSetType(pb->reduction, type));
  PetscCall(SSStarReductionSetOptionsPrefix(pb->reduction, prefix));
  PetscCall(SSStarReductionSetMemoryLimit(pb->reduction, pb->memoryLimit));
  PetscCall(SSStarReductionSetUp(pb->reduction, pb->Kw, ct->isC, ct->isI));
  PetscCall(SSStarReductionGetOperator(pb->reduction, &pb->A));
  PetscCall(PetscObjectReference((PetscObject)pb->A));
  PetscCall(SSStarReductionIsWholeBody(pb->reduction, &pb->wholeBody));
  PetscFunctionReturn(0);
}

/*
   The declaration of this solve: one changed since the last solve (a load path measured at the current configuration
   declares its points again at every step) is built here, with the same number of points. What the Newton step built
   in the old frames (the whole body's K in the nodes' frames) is dropped. Whether the problem set up for the old one
   stands: the reduction depends on K, the contact dofs and T only, so it is kept when the points and their dofs are the
   same and neither declaration has master dofs (rigid obstacles whose frames and gaps changed); the floating bodies'
   motions at the contact points (floating.c) are taken again in the new frames.
*/
static PetscErrorCode TakeDeclaration(SNES snes, SSStarContact *ct, SSStarProblem *pb, Mat K)
{
  MPI_Comm       comm   = PetscObjectComm((PetscObject)snes);
  const PetscInt nnodes = ct->nnodes;
  PetscBool      rebuilt, other, same = PETSC_FALSE;

  PetscFunctionBegin;
  PetscCall(SSStarContactSetUp(snes, ct, &rebuilt));
  if (!rebuilt || !pb->A) PetscFunctionReturn(0);
  PetscCall(SSStarNewtonReset(((SNES_SSStar *)snes->data)->newton));
  other = (PetscBool)(ct->nnodes != nnodes);
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &other, 1, MPIU_BOOL, MPI_LOR, comm));
  PetscCheck(!other, comm, PETSC_ERR_ARG_WRONGSTATE, "ssstar: the contact points were declared again, in other numbers: a new declaration between solves keeps the points (SNESReset() for others)");
  if (pb->isC && ct->isC) PetscCall(ISEqual(pb->isC, ct->isC, &same));
  if (same && !ct->T && pb->Kw == K) { /* the problem stands; the floating bodies' motions at the points change frames */
    pb->built = ct->built;
    if (pb->floating.m) PetscCall(SSStarFloatingSetUp(ct, K, pb->nonlinear, &pb->floating));
  }
  PetscFunctionReturn(0);
}

/*
   A and f for the current K, load and declaration (TakeDeclaration() first): the Jacobian is evaluated at the SNES
   vector, b = -F(0), and in the whole-body use K is reduced to the contact dofs, or kept (reduction none), again only
   when K or the declaration changed (not for new frames and gaps of rigid obstacles alone). An affine residual keeps
   this A for the whole solve; a nonlinear one (docs/derivation.md section 17) is solved on the whole body, its
   Jacobian evaluated again at the iterates (nonlinear.c).
*/
PetscErrorCode SSStarProblemSetUp(SNES snes, SSStarContact *ct, SSStarProblem *pb)
{
  Mat              K = NULL;
  PetscObjectState state;
  Vec              zero, bC;
  PetscInt         nI = 0;
  PetscBool        affine, nonlinear;

  PetscFunctionBegin;
  PetscCall(SSStarProblemIsAffine(snes, pb, &affine));
  nonlinear = (PetscBool)(!affine || ct->update);
  PetscCall(SSStarProblemComputeJacobian(snes, snes->vec_sol, &K));
  if (!affine && snes->lagjacobian == -2) snes->lagjacobian = -1; /* computed now, never again (SNESSetLagJacobian()) */
  PetscCall(PetscObjectStateGet((PetscObject)K, &state));
  PetscCall(TakeDeclaration(snes, ct, pb, K));
  if (K != pb->K || state != pb->Kstate || !pb->A || pb->built != ct->built || nonlinear != pb->nonlinear) {
    PetscCall(SSStarProblemReset(pb));
    PetscCall(SSStarContactTransformStiffness(ct, K, &pb->Kw));
    PetscCall(ContactRowStatistics(ct, pb, pb->Kw));
    PetscCall(SSStarFloatingSetUp(ct, K, nonlinear, &pb->floating)); /* floating bodies (floating.c): checked before any factorization */
    if (ct->isI) PetscCall(ISGetSize(ct->isI, &nI));
    pb->wholeBody = PETSC_FALSE;
    if (ct->dofs && nI > 0) PetscCall(CreateReduction(snes, ct, pb, nonlinear));
    else if (ct->dofs) { /* every dof a contact dof, in another order */
      PetscCall(MatCreateSubMatrix(pb->Kw, ct->isC, ct->isC, MAT_INITIAL_MATRIX, &pb->A));
    } else {
      PetscCall(PetscObjectReference((PetscObject)K));
      pb->A = K;
    }
    PetscCall(ChooseNewton(pb));
    if (pb->floating.m) {
      PetscBool sparse;

      PetscCall(PetscStrcmp(pb->newtonType, SSSTARNEWTONSPARSE, &sparse));
      PetscCheck(!sparse, PetscObjectComm((PetscObject)snes), PETSC_ERR_SUP, "ssstar: a sparse reduced P with a null space (floating bodies) is not supported: give P as a dense matrix, or K with its contact nodes");
    }
    PetscCall(BuildLayout(ct, pb));
    PetscCall(MatCreateVecs(pb->A, &pb->f, NULL));
    pb->K      = K;
    pb->Kstate = state;
    pb->builds++;
    pb->built  = ct->built;
    if (ct->isC) PetscCall(PetscObjectReference((PetscObject)ct->isC));
    pb->isC = ct->isC;
  }
  pb->affine    = affine;
  pb->nonlinear = nonlinear;
  if (!pb->b) PetscCall(VecDuplicate(snes->vec_func, &pb->b));
  PetscCall(VecDuplicate(snes->vec_sol, &zero));
  PetscCall(VecZeroEntries(zero));
  PetscCall(SNESComputeFunction(snes, zero, pb->b));
  PetscCall(VecDestroy(&zero));
  PetscCall(VecScale(pb->b, -1.0));
  PetscCall(VecDestroy(&pb->bw));
  if (ct->T) { /* the load in the points' variables: T^T b */
    PetscCall(VecDuplicate(pb->b, &pb->bw));
    PetscCall(MatMultTranspose(ct->T, pb->b, pb->bw));
  } else {
    PetscCall(PetscObjectReference((PetscObject)pb->b));
    pb->bw = pb->b;
  }
  if (pb->reduction) PetscCall(SSStarReductionReduceLoad(pb->reduction, pb->bw, pb->f));
  else if (ct->dofs) {
    PetscCall(VecGetSubVector(pb->bw, ct->isC, &bC));
    PetscCall(VecCopy(bC, pb->f));
    PetscCall(VecRestoreSubVector(pb->bw, ct->isC, &bC));
  } else PetscCall(VecCopy(pb->b, pb->f));
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarProblemGetLayout(SSStarContact *ct, SSStarProblem *pb, SSStarContactLayout *layout)
{
  PetscFunctionBegin;
  layout->nnodes = ct->nnodes;
  layout->dofs   = pb->layoutDofs;
  layout->frames = ct->frames;
  layout->floating = pb->floating.m ? &pb->floating : NULL;
  PetscFunctionReturn(0);
}

/* u, the solver's unknown, from the SNES vector x (in the points' variables, T^-1 x) */
PetscErrorCode SSStarProblemGetInitialGuess(SSStarContact *ct, SSStarProblem *pb, Vec x, Vec u)
{
  Vec v, vC;

  PetscFunctionBegin;
  if (!ct->dofs) {
    PetscCall(VecCopy(x, u));
    PetscFunctionReturn(0);
  }
  PetscCall(VecDuplicate(x, &v));
  PetscCall(SSStarContactToPointVariables(ct, x, v));
  if (pb->wholeBody) PetscCall(VecCopy(v, u));
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
   (or u itself on the whole body), in the points' variables, and x = T v; for a nonlinear residual T u
*/
PetscErrorCode SSStarProblemSetSolution(SSStarContact *ct, SSStarProblem *pb, Vec u, Vec c, Vec x)
{
  Vec v;

  PetscFunctionBegin;
  if (pb->nonlinear) { /* u is where F was evaluated: no recovery, no least-norm motion (F is not K u - b) */
    PetscCall(SSStarProblemIterateVector(ct, pb, u, x));
    PetscFunctionReturn(0);
  }
  if (!ct->dofs) {
    PetscCall(VecCopy(u, x));
    PetscCall(SSStarFloatingLeastNorm(&pb->floating, x));
    PetscFunctionReturn(0);
  }
  PetscCall(VecDuplicate(x, &v));
  if (pb->reduction) PetscCall(SSStarReductionRecover(pb->reduction, pb->bw, u, c, v));
  else PetscCall(VecISCopy(v, ct->isC, SCATTER_FORWARD, u));
  if (ct->T) PetscCall(MatMult(ct->T, v, x));
  else PetscCall(VecCopy(v, x));
  PetscCall(VecDestroy(&v));
  PetscCall(SSStarFloatingLeastNorm(&pb->floating, x)); /* motions no contact resists: the least-norm solution */
  PetscFunctionReturn(0);
}

/* A registered reduction or auto; the next solve sets the problem up again */
PetscErrorCode SSStarProblemSetReductionType(SSStarProblem *pb, const char type[])
{
  PetscBool same, isauto;
  PetscErrorCode (*create)(SSStarReduction, Mat) = NULL;

  PetscFunctionBegin;
  PetscCall(PetscStrcmp(type, SSSTARREDUCTIONAUTO, &isauto));
  if (!isauto) PetscCall(PetscFunctionListFind(SSStarReductionList, type, &create));
  PetscCheck(isauto || create, PETSC_COMM_SELF, PETSC_ERR_ARG_UNKNOWN_TYPE, "Unknown reduction type %s", type);
  PetscCall(PetscStrcmp(type, pb->reductionType, &same));
  if (same) PetscFunctionReturn(0);
  PetscCall(PetscStrncpy(pb->reductionType, type, sizeof(pb->reductionType)));
  PetscCall(MatDestroy(&pb->A));
  PetscFunctionReturn(0);
}

/* The reduction of the last solve (auto resolved), or the one set before the first */
PetscErrorCode SSStarProblemGetReductionType(SSStarProblem *pb, const char *type[])
{
  PetscFunctionBegin;
  *type = pb->reductionType;
  if (pb->reduction) PetscCall(SSStarReductionGetType(pb->reduction, type));
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarProblemView(SSStarContact *ct, SSStarProblem *pb, PetscViewer viewer)
{
  PetscBool isauto;

  PetscFunctionBegin;
  PetscCall(PetscStrcmp(pb->reductionType, SSSTARREDUCTIONAUTO, &isauto));
  if (ct->dofs && pb->reduction) {
    const char *type;

    PetscCall(SSStarReductionGetType(pb->reduction, &type));
    PetscBool chosen;
    PetscReal dense, whole, holding;

    if (pb->wholeBody) PetscCall(PetscViewerASCIIPrintf(viewer, "  whole-body problem: solved on the whole body, P never formed (reduction %s%s)\n", type, isauto ? " (chosen by auto)" : ""));
    else PetscCall(PetscViewerASCIIPrintf(viewer, "  whole-body problem: K reduced to the contact dofs by the %s Schur complement%s\n", type, isauto ? " (chosen by auto)" : ""));
    PetscCall(SSStarReductionGetAutoCosts(pb->reduction, &chosen, &dense, &whole, &holding));
    if (chosen) PetscCall(PetscViewerASCIIPrintf(viewer, "    auto's estimates (flops of a dense LU): the dense route %.3g, the whole body %.3g (K holds the body by %.2g)\n", (double)dense, (double)whole, (double)holding));
  } else if (ct->dofs) PetscCall(PetscViewerASCIIPrintf(viewer, "  whole-body problem: reduction %s (decided at the first solve)\n", pb->reductionType));
  else PetscCall(PetscViewerASCIIPrintf(viewer, "  reduced problem: every dof is a contact dof (c = P u - f)\n"));
  PetscCall(SSStarFloatingView(&pb->floating, viewer));
  PetscFunctionReturn(0);
}

/* Drops what was derived from K and the declaration (the settings stay) */
PetscErrorCode SSStarProblemReset(SSStarProblem *pb)
{
  PetscFunctionBegin;
  PetscCall(SSStarReductionDestroy(&pb->reduction));
  PetscCall(MatDestroy(&pb->A));
  PetscCall(MatDestroy(&pb->Kw));
  PetscCall(VecDestroy(&pb->f));
  PetscCall(VecDestroy(&pb->b));
  PetscCall(VecDestroy(&pb->bw));
  PetscCall(PetscFree(pb->layoutDofs));
  PetscCall(PetscFree(pb->free));
  PetscCall(ISDestroy(&pb->isC));
  PetscCall(SSStarFloatingReset(&pb->floating));
  for (Vec *w = &pb->x; w <= &pb->xMeasured; w++) PetscCall(VecDestroy(w));
  pb->nfree     = 0;
  pb->K         = NULL;
  pb->built     = -1;
  pb->wholeBody = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/*
   x, the SNES vector of the solver's u: T v with v = u on the whole body and in the reduced use, u at the contact
   dofs of a problem whose every dof is a contact dof
*/
PetscErrorCode SSStarProblemIterateVector(SSStarContact *ct, SSStarProblem *pb, Vec u, Vec x)
{
  PetscFunctionBegin;
  if (!ct->dofs) {
    PetscCall(VecCopy(u, x));
    PetscFunctionReturn(0);
  }
  if (pb->wholeBody) PetscCall(VecCopy(u, pb->v));
  else PetscCall(VecISCopy(pb->v, ct->isC, SCATTER_FORWARD, u));
  if (ct->T) PetscCall(MatMult(ct->T, pb->v, x));
  else PetscCall(VecCopy(pb->v, x));
  PetscFunctionReturn(0);
}

/* c from F(x): T^T F, at the contact dofs unless on the whole body */
static PetscErrorCode ContactResidual(SSStarContact *ct, SSStarProblem *pb, Vec F, Vec c)
{
  Vec w = F, wC;

  PetscFunctionBegin;
  if (!ct->dofs) {
    PetscCall(VecCopy(F, c));
    PetscFunctionReturn(0);
  }
  if (ct->T) {
    PetscCall(MatMultTranspose(ct->T, F, pb->v));
    w = pb->v;
  }
  if (pb->wholeBody) PetscCall(VecCopy(w, c));
  else {
    PetscCall(VecGetSubVector(w, ct->isC, &wC));
    PetscCall(VecCopy(wC, c));
    PetscCall(VecRestoreSubVector(w, ct->isC, &wC));
  }
  PetscFunctionReturn(0);
}

/*
   c = c(u) from F itself. A point where the program's F is not defined (SNESSetFunctionDomainError(): an inverted
   element of a hyperelastic body) has c = Inf: the line search halves a step that leads there until F is defined,
   as PETSc's line searches do with a domain error.
*/
PetscErrorCode SSStarProblemFunctionResidual(SNES snes, Vec u, Vec c)
{
  SNES_SSStar   *ss = (SNES_SSStar *)snes->data;
  SSStarProblem *pb = &ss->problem;
  PetscBool      outside;

  PetscFunctionBegin;
  PetscCall(SSStarProblemIterateVector(&ss->contact, pb, u, pb->x));
  PetscCall(SNESComputeFunction(snes, pb->x, pb->Fx));
  PetscCall(MPIU_Allreduce(&snes->domainerror, &outside, 1, MPIU_BOOL, MPI_LOR, PetscObjectComm((PetscObject)snes)));
  snes->domainerror = PETSC_FALSE;
  if (outside) PetscCall(VecSet(c, (PetscReal)INFINITY)); /* not PETSC_INFINITY: PETSC_MAX_REAL/4 is a finite number */
  else PetscCall(ContactResidual(&ss->contact, pb, pb->Fx, c));
  PetscFunctionReturn(0);
}

/*
   The Jacobian K evaluated again (a nonlinear residual at a new iterate): K in the points' variables and A follow (the
   same matrices, new values) and the floating bodies' motions (the null space K carries now)
*/
PetscErrorCode SSStarProblemTakeJacobian(SNES snes, SSStarContact *ct, SSStarProblem *pb, Mat K)
{
  PetscFunctionBegin;
  if (ct->T) PetscCall(MatPtAP(K, ct->T, MAT_REUSE_MATRIX, PETSC_DEFAULT, &pb->Kw));
  if (ct->dofs && !pb->wholeBody) PetscCall(MatCreateSubMatrix(pb->Kw, ct->isC, ct->isC, MAT_REUSE_MATRIX, &pb->A));
  PetscCall(SSStarFloatingSetUp(ct, K, pb->nonlinear, &pb->floating));
  PetscCall(PetscObjectStateGet((PetscObject)K, &pb->Kstate));
  PetscFunctionReturn(0);
}

/*
   The contact declared again within a solve (a contact update at an iterate, docs/derivation.md section 17), with the
   same points: taken as between solves (TakeDeclaration()); where the change of variables T was or is part of it, the
   points' variables change, and K in them and A (on the whole body) are built again. rebuilt: the declaration changed;
   variables: the points' variables did (the iterate must be expressed in them again).
*/
PetscErrorCode SSStarProblemTakeMeasuredContact(SNES snes, SSStarContact *ct, SSStarProblem *pb, PetscBool *rebuilt, PetscBool *variables)
{
  const PetscObjectState built = ct->built;
  PetscBool              same  = PETSC_FALSE;

  PetscFunctionBegin;
  *variables = PETSC_FALSE;
  PetscCall(TakeDeclaration(snes, ct, pb, pb->K));
  *rebuilt = (PetscBool)(ct->built != built);
  if (!*rebuilt) PetscFunctionReturn(0);
  if (pb->isC && ct->isC) PetscCall(ISEqual(pb->isC, ct->isC, &same));
  PetscCheck(same, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_WRONGSTATE, "ssstar: the contact update (SNESSSStarSetContactUpdate()) declared points with other dofs: it may change their normals, gaps, offsets and master dofs, not the points");
  if (pb->built == ct->built) PetscFunctionReturn(0); /* rigid obstacles: new frames and gaps, the same problem */
  PetscCall(MatDestroy(&pb->Kw));
  PetscCall(SSStarContactTransformStiffness(ct, pb->K, &pb->Kw));
  PetscCall(SSStarReductionDestroy(&pb->reduction));
  PetscCall(MatDestroy(&pb->A));
  PetscCall(CreateReduction(snes, ct, pb, PETSC_TRUE));
  PetscCall(SSStarFloatingSetUp(ct, pb->K, pb->nonlinear, &pb->floating));
  pb->built  = ct->built;
  *variables = PETSC_TRUE;
  PetscFunctionReturn(0);
}

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

/* Whether F is affine in this solve: as declared (SNESSSStarSetAffine()), else when it is SNESSSStarSetLinearProblem()'s */
PetscErrorCode SSStarProblemIsAffine(SNES snes, SSStarProblem *pb, PetscBool *affine)
{
  PetscErrorCode (*function)(SNES, Vec, Vec, void *);

  PetscFunctionBegin;
  if (pb->affineSet) {
    *affine = pb->affineDeclared;
    PetscFunctionReturn(0);
  }
  PetscCall(SNESGetFunction(snes, NULL, &function, NULL));
  *affine = (PetscBool)(function == LinearProblemFunction);
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
   SNESSSStarSetContactOperator()); without a declaration every dof is a contact dof (the reduced use). This F is
   affine (SNESSSStarGetAffine()): ssstar evaluates K once per solve and may reduce it to the contact dofs; a program's own
   SNESSetFunction() and SNESSetJacobian() give a residual ssstar treats as nonlinear unless declared affine
   (SNESSSStarSetAffine(); docs/guide/nonlinear-residuals.md).

   Level: beginner

.seealso: `SNESSSStarSetContactNodes()`, `SNESSSStarGetReducedProblem()`, `SNESSSStarSetAffine()`, `SNESSetFunction()`, `SNESSetJacobian()`
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
   SNESSSStarGetReducedProblem - P and f of the last solve: c(u) = P u - f on the contact dofs (global axes, in the
   order of the contact nodes sorted by their first dof)

   Not Collective

   Input Parameter:
.  snes - the SNES, after SNESSolve()

   Output Parameters:
+  P - the reduced stiffness (owned by the SNES), or pass NULL
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

static PetscErrorCode SNESSSStarSetReductionType_SSStar(SNES snes, SSStarReductionType type)
{
  PetscFunctionBegin;
  PetscCall(SSStarProblemSetReductionType(&((SNES_SSStar *)snes->data)->problem, type));
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

static PetscErrorCode SNESSSStarGetReductionType_SSStar(SNES snes, SSStarReductionType *type)
{
  PetscFunctionBegin;
  PetscCall(SSStarProblemGetReductionType(&((SNES_SSStar *)snes->data)->problem, type));
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

static PetscErrorCode SNESSSStarSetMemoryLimit_SSStar(SNES snes, PetscReal gigabytes)
{
  PetscFunctionBegin;
  PetscCheck(gigabytes >= 0 && !PetscIsInfOrNanReal(gigabytes), PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_OUTOFRANGE, "-snes_ssstar_memory_limit %g: the limit must be > 0 GB (or 0 for the available memory)", (double)gigabytes);
  ((SNES_SSStar *)snes->data)->problem.memoryLimit = gigabytes;
  PetscFunctionReturn(0);
}

/* The implementations of the public functions above, composed on the SNES (SNESSSStarComposeFunctions()) */
static const SSStarComposed Composed[] = {
    {"SNESSSStarGetReducedProblem_C", (PetscVoidFunction)SNESSSStarGetReducedProblem_SSStar},
    {"SNESSSStarSetReductionType_C", (PetscVoidFunction)SNESSSStarSetReductionType_SSStar},
    {"SNESSSStarGetReductionType_C", (PetscVoidFunction)SNESSSStarGetReductionType_SSStar},
    {"SNESSSStarSetMemoryLimit_C", (PetscVoidFunction)SNESSSStarSetMemoryLimit_SSStar},
};

PetscErrorCode SNESSSStarComposeProblem(SNES snes, PetscBool on)
{
  PetscFunctionBegin;
  PetscCall(SNESSSStarComposeTable(snes, Composed, PETSC_STATIC_ARRAY_LENGTH(Composed), on));
  PetscFunctionReturn(0);
}
