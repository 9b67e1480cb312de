/*
   auto: the route of a contact solve chosen from what each costs (docs/guide/choosing-a-route.md). The dense route
   factors K once with the contact dofs as its Schur block (MUMPS's flops, known after its analysis) and then factors a
   dense 3p x 3p Newton matrix at each Newton step ((2/3)(3p)^3 = 18 p^3 flops); the whole body solves a multigrid-
   preconditioned Krylov system of all the dofs of K at each step, whose iterations grow where K holds the body only
   softly (a soft spring, or contact alone: the Newton matrices are nearly singular wherever no contact node sticks).
*/
#include "reductionimpl.h"

/* Newton steps a contact solve is assumed to take (the prism: 7 to 11): the dense route's factorization of K is paid once */
#define SSSTAR_AUTO_NEWTON_STEPS 10.0
/* the whole body's work per dof of K and Newton step, in flops of a dense LU, for a body K holds firmly (measured) */
#define SSSTAR_AUTO_WHOLE_FLOPS 1.5e5
/* the holding below which the whole body's Krylov iterations grow, as the square root of holding / this */
#define SSSTAR_AUTO_HELD 1e-4
/* the growth for a body K does not hold at all (held by contact alone) */
#define SSSTAR_AUTO_FLOATING 1e3

/*@
   SSStarReductionAutoCosts - auto's cost model: the estimated work of a contact solve on the dense route and on the
   whole body, in flops of a dense LU factorization

   Not Collective

   Input Parameters:
+  dofs        - the dofs of K
.  contactDofs - the contact dofs, 3p (P is 3p x 3p)
.  holding     - how firmly K holds the body: the smallest Rayleigh quotient of its rigid-body motions relative to its
                 mean diagonal entry (about the share of nodes next to a held face for a body held by Dirichlet
                 conditions, 1e-5 and less for one held by a soft spring, 0 for one held by contact alone)
-  factorFlops - MUMPS's flops to factor K with its Schur block of the contact dofs (0: not known)

   Output Parameters:
+  dense - S (factorFlops / S + (2/3) (3p)^3): the factorization of K once and a dense LU of the Newton matrix at each
           of S = 10 Newton steps (18 p^3 flops each)
-  whole - S W dofs: W = 1.5e5 per dof and Newton step for a firmly held body (the Krylov iterations and multigrid
           set-ups of the whole body, measured against the dense LU's flops on the same machine), growing as
           sqrt(1e-4 / holding) below a holding of 1e-4, and 1000-fold for a body held by contact alone

   Notes:
   auto takes the dense route where dense <= whole and its memory (MUMPS's factors, P and the dense work) fits, else
   the whole body. The constants were measured by bench/auto.py on prism levels, an unstructured slab, contact on most
   of the surface and on small patches (docs/guide/choosing-a-route.md).

   Level: developer

.seealso: `SSStarReductionSetType()`, `SSStarReductionGetAutoCosts()`
@*/
PetscErrorCode SSStarReductionAutoCosts(PetscReal dofs, PetscReal contactDofs, PetscReal holding, PetscReal factorFlops, PetscReal *dense, PetscReal *whole)
{
  const PetscReal S = SSSTAR_AUTO_NEWTON_STEPS;
  PetscReal       growth;

  PetscFunctionBegin;
  growth = holding >= SSSTAR_AUTO_HELD ? 1.0 : PetscMin(SSSTAR_AUTO_FLOATING, PetscSqrtReal(SSSTAR_AUTO_HELD / PetscMax(holding, 0)));
  *dense = factorFlops + S * 2.0 / 3.0 * contactDofs * contactDofs * contactDofs;
  *whole = S * SSSTAR_AUTO_WHOLE_FLOPS * growth * dofs;
  PetscFunctionReturn(0);
}

/*
   How firmly K holds the body: min over its rigid-body motions r of (r^T K r / r^T r) / mean(diag K). The motions are
   K's near-null space (the scenes attach it), else the three translations of a K of 3 dofs per node; 1 (held) when
   neither is known or K has no diagonal to compare with.
*/
static PetscErrorCode Holding(Mat K, PetscReal *holding)
{
  MatNullSpace      nsp;
  const Vec        *modes = NULL;
  Vec               own[3] = {NULL, NULL, NULL}, d, Kr;
  PetscInt          n = 0, bs, N, lo, hi;
  PetscBool         hasConstant, hasDiagonal;
  PetscReal         mean;
  PetscScalar       sum;

  PetscFunctionBegin;
  *holding = 1.0;
  PetscCall(MatHasOperation(K, MATOP_GET_DIAGONAL, &hasDiagonal));
  if (!hasDiagonal) PetscFunctionReturn(0); /* a K without a diagonal (a shell): taken for held */
  PetscCall(MatGetNearNullSpace(K, &nsp));
  if (nsp) PetscCall(MatNullSpaceGetVecs(nsp, &hasConstant, &n, &modes));
  PetscCall(MatGetBlockSize(K, &bs));
  PetscCall(MatGetSize(K, &N, NULL));
  if (!n && bs == 3) { /* the translations */
    for (PetscInt k = 0; k < 3; k++) {
      PetscCall(MatCreateVecs(K, &own[k], NULL));
      PetscCall(VecGetOwnershipRange(own[k], &lo, &hi));
      for (PetscInt i = lo + (3 - lo % 3 + k) % 3; i < hi; i += 3) PetscCall(VecSetValue(own[k], i, 1.0, INSERT_VALUES));
      PetscCall(VecAssemblyBegin(own[k]));
      PetscCall(VecAssemblyEnd(own[k]));
    }
    modes = own;
    n     = 3;
  }
  if (!n || !N) PetscFunctionReturn(0);
  PetscCall(MatCreateVecs(K, &d, &Kr));
  PetscCall(MatGetDiagonal(K, d));
  PetscCall(VecSum(d, &sum));
  mean = PetscAbsReal(PetscRealPart(sum)) / N;
  for (PetscInt k = 0; k < n && mean > 0; k++) {
    PetscScalar rKr;
    PetscReal   rr;

    PetscCall(MatMult(K, modes[k], Kr));
    PetscCall(VecDot(Kr, modes[k], &rKr));
    PetscCall(VecNorm(modes[k], NORM_2, &rr));
    if (rr > 0) *holding = PetscMin(*holding, PetscAbsReal(PetscRealPart(rKr)) / (rr * rr * mean));
  }
  PetscCall(VecDestroy(&d));
  PetscCall(VecDestroy(&Kr));
  for (PetscInt k = 0; k < 3; k++) PetscCall(VecDestroy(&own[k]));
  PetscFunctionReturn(0);
}

/*
   auto resolved (the type to set): direct where the dense route's estimated work is no more than the whole body's (SSStarReductionAutoCosts())
   and its memory fits, else none. The dense route's LUs alone decide first when they cost more than the whole body
   (large problems: MUMPS is not even ordered); else MUMPS orders and analyses K with its Schur block for its flops and
   memory, and that analysis is kept for the factorization when direct is taken.
*/
PetscErrorCode SSStarReductionResolveAuto(SSStarReduction red, Mat K, SSStarReductionType *type)
{
  PetscInt       N, NC, mC;
  PetscBool      fits = PETSC_TRUE;
  PetscReal      dense, whole;
  PetscLogDouble flops = 0, sparse = 0, bytes;
  const char    *why;

  PetscFunctionBegin;
  PetscCall(MatGetSize(K, &N, NULL));
  PetscCall(ISGetSize(red->isC, &NC));
  PetscCall(ISGetLocalSize(red->isC, &mC));
  PetscCall(Holding(K, &red->autoHolding));
  PetscCall(SSStarReductionAutoCosts(N, NC, red->autoHolding, 0, &dense, &whole));
  bytes = 8.0 * NC * (1 + SSSTAR_DENSE_WORK) * (PetscLogDouble)mC;
  if (dense <= whole) PetscCall(SSStarReductionFitsMemory(red->comm, red->memoryLimit, 0, bytes, &fits));
  why = fits ? "the dense LUs alone cost more" : "P does not fit";
  if (dense <= whole && fits) { /* MUMPS's flops and memory decide */
    PetscCall(SSStarReductionAnalyse_Direct(red, K, &flops, &sparse, &bytes));
    PetscCall(SSStarReductionAutoCosts(N, NC, red->autoHolding, flops, &dense, &whole));
    PetscCall(SSStarReductionFitsMemory(red->comm, red->memoryLimit, sparse, bytes, &fits));
    why = !fits ? "MUMPS's factors and P do not fit" : dense <= whole ? "the dense route costs less" : "the dense route costs more";
    if (dense > whole || !fits) { /* the analysis is dropped */
      PetscCall((*red->ops.destroy)(red));
      PetscCall(PetscFree(red->data));
      PetscCall(PetscMemzero(&red->ops, sizeof(red->ops)));
    }
  }
  *type            = dense <= whole && fits ? SSSTARREDUCTIONDIRECT : SSSTARREDUCTIONNONE;
  red->autoChosen  = PETSC_TRUE;
  red->autoCost[0] = dense;
  red->autoCost[1] = whole;
  PetscCall(PetscInfo(K, "auto: %" PetscInt_FMT " dofs, %" PetscInt_FMT " contact dofs, holding %g, MUMPS's flops %g: dense route %g, whole body %g (LU flops): %s (%s)\n", N, NC, (double)red->autoHolding, (double)flops, (double)dense, (double)whole, *type, why));
  PetscFunctionReturn(0);
}

/*@C
   SSStarReductionGetAutoCosts - what auto estimated when it chose the reduction's type (SSStarReductionAutoCosts())

   Not Collective

   Input Parameter:
.  red - the reduction, set up

   Output Parameters:
+  chosen  - whether auto chose the type
.  dense   - the dense route's estimated work (flops of a dense LU), or pass NULL
.  whole   - the whole body's, or pass NULL
-  holding - how firmly K holds the body, or pass NULL

   Level: developer

.seealso: `SSStarReductionAutoCosts()`, `SSStarReductionGetType()`
@*/
PetscErrorCode SSStarReductionGetAutoCosts(SSStarReduction red, PetscBool *chosen, PetscReal *dense, PetscReal *whole, PetscReal *holding)
{
  PetscFunctionBegin;
  *chosen = red->autoChosen;
  if (dense) *dense = red->autoCost[0];
  if (whole) *whole = red->autoCost[1];
  if (holding) *holding = red->autoHolding;
  PetscFunctionReturn(0);
}
