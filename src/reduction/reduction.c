/*
   Reduction of K u = F to the contact dofs C (docs/derivation.md section 0):
   P = K_CC - K_CI K_II^-1 K_IC,  f = F_C - K_CI K_II^-1 F_I,  and the recovery u_I = K_II^-1 (F_I - K_IC u_C),
   or no reduction at all (none: the contact problem stays on the whole body, P is never formed).

   The registry of types and the set-up of a reduction (auto resolved by auto.c), the singular-K check. What the types
   share (option names, the memory checks before a factorization, MUMPS's failures in words) is shared.c; the
   implementations are direct.c, mumps.c, explicit.c and none.c (reductionimpl.h), registered by regall.c.
*/
#include "reductionimpl.h"
#include <petscmat.h>
#include <stdio.h>

PetscFunctionList SSStarReductionList = NULL;
static char     **ReductionNames      = NULL; /* the registered types in their order, then auto; NULL-terminated */
static PetscInt   NumReductionNames   = 0;

static PetscErrorCode ReductionNamesDestroy(void)
{
  PetscFunctionBegin;
  for (PetscInt k = 0; k < NumReductionNames; k++) PetscCall(PetscFree(ReductionNames[k]));
  PetscCall(PetscFree(ReductionNames));
  NumReductionNames = 0;
  PetscFunctionReturn(0);
}

/* name into the list of names before auto, unless it is there */
static PetscErrorCode ReductionNamesAdd(const char name[])
{
  PetscBool seen = PETSC_FALSE;

  PetscFunctionBegin;
  if (!ReductionNames) {
    PetscCall(PetscCalloc1(2, &ReductionNames));
    PetscCall(PetscStrallocpy(SSSTARREDUCTIONAUTO, &ReductionNames[0]));
    NumReductionNames = 1;
    PetscCall(PetscRegisterFinalize(ReductionNamesDestroy));
  }
  for (PetscInt k = 0; k < NumReductionNames && !seen; k++) PetscCall(PetscStrcmp(name, ReductionNames[k], &seen));
  if (seen) PetscFunctionReturn(0);
  PetscCall(PetscRealloc(sizeof(char *) * (NumReductionNames + 2), &ReductionNames));
  ReductionNames[NumReductionNames]     = ReductionNames[NumReductionNames - 1]; /* auto stays last */
  PetscCall(PetscStrallocpy(name, &ReductionNames[NumReductionNames - 1]));
  ReductionNames[++NumReductionNames] = NULL;
  PetscFunctionReturn(0);
}

/*@C
   SSStarReductionRegister - adds a reduction type

   Not Collective

   Input Parameters:
+  name   - its name (SSStarReductionSetType(), -snes_ssstar_reduction)
-  create - computes the operator from K (P, or K itself) and fills the ops (src/reduction/reductionimpl.h)

   Level: advanced

.seealso: `SSStarReductionRegisterAll()`, `SSStarReductionSetType()`
@*/
PetscErrorCode SSStarReductionRegister(const char name[], PetscErrorCode (*create)(SSStarReduction, Mat))
{
  PetscFunctionBegin;
  PetscCall(PetscFunctionListAdd(&SSStarReductionList, name, create));
  PetscCall(ReductionNamesAdd(name));
  PetscFunctionReturn(0);
}

/*@C
   SSStarReductionGetNames - the choices of SSStarReductionSetType(): the registered reduction types in the order of
   their registration, then auto

   Not Collective

   Output Parameters:
+  n     - the number of names (auto included), or pass NULL
-  names - the names, NULL-terminated (owned by ssstar), or pass NULL

   Notes:
   After SSStarInitializePackage(): direct, mumps, explicit, none, auto. auto is no type: direct where the dense
   route is the faster one and P fits, else none.

   Level: intermediate

.seealso: `SSStarReductionRegister()`, `SSStarReductionSetType()`, `SNESSSStarSetReductionType()`
@*/
PetscErrorCode SSStarReductionGetNames(PetscInt *n, const char *const *names[])
{
  PetscFunctionBegin;
  if (n) *n = NumReductionNames;
  if (names) *names = (const char *const *)ReductionNames;
  PetscFunctionReturn(0);
}


/* u from u_C: the implementation's recovery, then u_C itself on C (not its round-off image) */
static PetscErrorCode RecoverWithContact(SSStarReduction red, Vec F, Vec uC, Vec rC, Vec u)
{
  PetscFunctionBegin;
  PetscCall((*red->ops.recover)(red, F, uC, rC, u));
  PetscCall(VecISCopy(u, red->isC, SCATTER_FORWARD, uC));
  PetscFunctionReturn(0);
}

/*
   The Cholesky factorizations of K (K_II) do not pivot, and MUMPS does not look for zero pivots there: a singular K_II
   factors into garbage. Solving K_II x = b for a b of positive, irregular entries tells: the relative residual is
   round-off for a K_II of any reasonable condition, and of the order of b itself for a singular one.
*/
static PetscErrorCode CheckInteriorSolve(SSStarReduction red, Mat K)
{
  Vec          b, f, zero, x, r, rI, bI;
  PetscInt     lo, hi;
  PetscScalar *ba;
  PetscReal    rnorm, bnorm;

  PetscFunctionBegin;
  PetscCall(MatCreateVecs(K, &x, &b));
  PetscCall(VecDuplicate(b, &r));
  PetscCall(VecGetOwnershipRange(b, &lo, &hi));
  PetscCall(VecGetArrayWrite(b, &ba));
  for (PetscInt i = lo; i < hi; i++) ba[i - lo] = 1.0 + 0.5 * PetscSinReal((PetscReal)i);
  PetscCall(VecRestoreArrayWrite(b, &ba));
  PetscCall(MatCreateVecs(red->P, &f, &zero));
  PetscCall(VecZeroEntries(zero));
  PetscCall((*red->ops.reduceload)(red, b, f)); /* the contact force of u_C = 0 is -f */
  PetscCall(VecScale(f, -1.0));
  PetscCall(RecoverWithContact(red, b, zero, f, x));
  PetscCall(MatMult(K, x, r));
  PetscCall(VecAXPY(r, -1.0, b));
  PetscCall(VecGetSubVector(r, red->isI, &rI));
  PetscCall(VecGetSubVector(b, red->isI, &bI));
  PetscCall(VecNorm(rI, NORM_INFINITY, &rnorm));
  PetscCall(VecNorm(bI, NORM_INFINITY, &bnorm));
  PetscCall(VecRestoreSubVector(b, red->isI, &bI));
  PetscCall(VecRestoreSubVector(r, red->isI, &rI));
  PetscCall(PetscInfo(K, "K_II x = b solved to a relative residual %g\n", (double)(rnorm / bnorm)));
  PetscCheck(rnorm <= SSSTAR_SINGULAR_RESIDUAL * bnorm, PetscObjectComm((PetscObject)K), PETSC_ERR_MAT_CH_ZRPVT,
             "K is singular: is the body held? (Dirichlet conditions). K_II, K without the contact dofs, is singular or nearly so: a solve with it leaves a relative residual of %.1e, so some part of the body is held neither by Dirichlet conditions nor through the contact dofs", (double)(rnorm / bnorm));
  PetscCall(VecDestroy(&b));
  PetscCall(VecDestroy(&x));
  PetscCall(VecDestroy(&r));
  PetscCall(VecDestroy(&f));
  PetscCall(VecDestroy(&zero));
  PetscFunctionReturn(0);
}


/*@C
   SSStarReductionCreate - a reduction of K u = F to a subset of its dofs, of type auto until SSStarReductionSetType()

   Collective

   Input Parameter:
.  comm - the communicator of K

   Output Parameter:
.  red - the reduction

   Notes:
   SSStarReductionSetUp() computes it.

   Level: developer

.seealso: `SSStarReductionSetType()`, `SSStarReductionSetUp()`, `SSStarReductionDestroy()`
@*/
PetscErrorCode SSStarReductionCreate(MPI_Comm comm, SSStarReduction *red)
{
  PetscFunctionBegin;
  PetscCall(PetscNew(red));
  (*red)->comm = comm;
  PetscCall(PetscStrallocpy(SSSTARREDUCTIONAUTO, &(*red)->type));
  PetscFunctionReturn(0);
}

/*@C
   SSStarReductionSetType - how K is reduced: a registered type (direct, mumps, explicit, none) or auto (direct or
   none, by size and memory, decided by SSStarReductionSetUp())

   Not Collective

   Input Parameters:
+  red  - the reduction, before SSStarReductionSetUp()
-  type - the type

   Level: developer

.seealso: `SSStarReductionRegister()`, `SSStarReductionGetType()`
@*/
PetscErrorCode SSStarReductionSetType(SSStarReduction red, SSStarReductionType type)
{
  PetscBool isauto;
  PetscErrorCode (*create)(SSStarReduction, Mat) = NULL;

  PetscFunctionBegin;
  PetscCall(PetscStrcmp(type, SSSTARREDUCTIONAUTO, &isauto));
  if (!isauto) PetscCall(PetscFunctionListFind(SSStarReductionList, type, &create));
  PetscCheck(isauto || create, PETSC_COMM_SELF, PETSC_ERR_ARG_UNKNOWN_TYPE, "Unknown reduction type %s", type);
  PetscCall(PetscFree(red->type));
  PetscCall(PetscStrallocpy(type, &red->type));
  PetscFunctionReturn(0);
}

/*@C
   SSStarReductionSetOptionsPrefix - the prefix of the options of the reduction's solvers: -<prefix>schur_direct_mumps_*
   (direct), -<prefix>schur_mat_mumps_* (mumps), -<prefix>interior_ksp_*, -<prefix>interior_pc_* (explicit)

   Not Collective

   Input Parameters:
+  red    - the reduction
-  prefix - the prefix (an SNES passes its own), or NULL

   Level: developer

.seealso: `SSStarReductionSetUp()`
@*/
PetscErrorCode SSStarReductionSetOptionsPrefix(SSStarReduction red, const char prefix[])
{
  PetscFunctionBegin;
  PetscCall(PetscFree(red->prefix));
  PetscCall(PetscStrallocpy(prefix, &red->prefix));
  PetscFunctionReturn(0);
}

/*@C
   SSStarReductionSetMemoryLimit - the memory the reduction may plan for

   Not Collective

   Input Parameters:
+  red         - the reduction
-  memoryLimit - GB (1e9 bytes) per rank; 0: MemAvailable of each node split over its ranks (the default)

   Level: developer

.seealso: `SSStarReductionSetUp()`
@*/
PetscErrorCode SSStarReductionSetMemoryLimit(SSStarReduction red, PetscReal memoryLimit)
{
  PetscFunctionBegin;
  red->memoryLimit = memoryLimit;
  PetscFunctionReturn(0);
}

/*@C
   SSStarReductionSetUp - the reduction of K u = F to the dofs isC: the Schur complement P = K_CC - K_CI K_II^-1 K_IC,
   or none (K itself)

   Collective

   Input Parameters:
+  red - the reduction
.  K   - the (SPD) stiffness
.  isC - owned global dofs of the contact nodes (3 per node), in the order P is to have
-  isI - all other owned dofs

   Notes:
   P is dense and distributed by rows like isC. The factorization that gave P is kept for the recovery.
   Before factorizing, the memory each rank needs (MUMPS's estimate after its analysis, P, and SSSTAR_DENSE_WORK
   more dense matrices of P's size for the caller) is compared with the memory limit: the reduction refuses, on every
   rank, with the estimate and the limit in the message. MUMPS's failures (a singular K, memory) are raised on every
   rank. auto is resolved here (SSStarReductionGetType() tells to what).

   Level: developer

.seealso: `SSStarReductionCreate()`, `SSStarReductionGetSchurComplement()`, `SSStarReductionReduceLoad()`,
          `SSStarReductionRecover()`
@*/
PetscErrorCode SSStarReductionSetUp(SSStarReduction red, Mat K, IS isC, IS isI)
{
  PetscBool isauto;
  PetscErrorCode (*create)(SSStarReduction, Mat) = NULL;

  PetscFunctionBegin;
  PetscCheck(!red->P, red->comm, PETSC_ERR_ARG_WRONGSTATE, "SSStarReductionSetUp: the reduction is set up already");
  PetscCall(PetscObjectReference((PetscObject)isC));
  PetscCall(PetscObjectReference((PetscObject)isI));
  red->isC = isC;
  red->isI = isI;
  PetscCall(PetscStrcmp(red->type, SSSTARREDUCTIONAUTO, &isauto));
  if (isauto) {
    SSStarReductionType chosen;

    PetscCall(SSStarReductionResolveAuto(red, K, &chosen)); /* auto.c */
    PetscCall(SSStarReductionSetType(red, chosen));
  }
  PetscCall(PetscFunctionListFind(SSStarReductionList, red->type, &create));
  PetscCheck(create, red->comm, PETSC_ERR_ARG_UNKNOWN_TYPE, "Unknown reduction type %s", red->type);
  PetscCall(PetscLogEventBegin(SSSTAR_Schur, K, 0, 0, 0));
  PetscCall((*create)(red, K));
  if (!red->wholeBody) {
    PetscCall(PetscObjectSetName((PetscObject)red->P, "P"));
    PetscCall(CheckInteriorSolve(red, K));
  }
  PetscCall(PetscLogEventEnd(SSSTAR_Schur, K, 0, 0, 0));
  PetscFunctionReturn(0);
}

/*@C
   SSStarReductionGetType - the type of the reduction: as set, and after SSStarReductionSetUp() as computed (auto
   resolved to direct or none)

   Not Collective

   Input Parameter:
.  red - the reduction

   Output Parameter:
.  type - its type (owned by the reduction)

   Level: developer

.seealso: `SSStarReductionSetType()`
@*/
PetscErrorCode SSStarReductionGetType(SSStarReduction red, SSStarReductionType *type)
{
  PetscFunctionBegin;
  *type = red->type;
  PetscFunctionReturn(0);
}

/*@C
   SSStarReductionIsWholeBody - whether the operator of the reduction is K itself (none): the contact problem keeps the
   whole body, its interior dofs unknowns beside the contact dofs; else it is P on the contact dofs alone

   Not Collective

   Input Parameter:
.  red - the reduction, set up

   Output Parameter:
.  wholeBody - PETSC_TRUE for K

   Level: developer

.seealso: `SSStarReductionGetOperator()`
@*/
PetscErrorCode SSStarReductionIsWholeBody(SSStarReduction red, PetscBool *wholeBody)
{
  PetscFunctionBegin;
  *wholeBody = red->wholeBody;
  PetscFunctionReturn(0);
}

/*@C
   SSStarReductionGetOperator - the operator the contact problem lives on: P (3p x 3p, dense, rows distributed like
   isC) after a Schur reduction, K itself for none; owned by the reduction

   Not Collective

   Input Parameter:
.  red - the reduction

   Output Parameter:
.  A - P, or K

   Level: developer

.seealso: `SSStarReductionGetSchurComplement()`
@*/
PetscErrorCode SSStarReductionGetOperator(SSStarReduction red, Mat *A)
{
  PetscFunctionBegin;
  *A = red->P;
  PetscFunctionReturn(0);
}

/*@C
   SSStarReductionGetSchurComplement - P (3p x 3p, dense, rows distributed like isC); owned by the reduction

   Not Collective

   Input Parameter:
.  red - the reduction (not of type none)

   Output Parameter:
.  P - the Schur complement

   Level: developer

.seealso: `SSStarReductionGetOperator()`
@*/
PetscErrorCode SSStarReductionGetSchurComplement(SSStarReduction red, Mat *P)
{
  PetscFunctionBegin;
  PetscCheck(!red->wholeBody, red->comm, PETSC_ERR_ARG_WRONGSTATE, "The reduction %s forms no Schur complement", red->type);
  *P = red->P;
  PetscFunctionReturn(0);
}

/*@C
   SSStarReductionReduceLoad - f = F_C - K_CI K_II^-1 F_I, the load reduced to the contact dofs (a vector like P's;
   for none, F itself)

   Collective

   Input Parameters:
+  red - the reduction
-  F   - the whole load

   Output Parameter:
.  f - the reduced load

   Level: developer

.seealso: `SSStarReductionCreate()`
@*/
PetscErrorCode SSStarReductionReduceLoad(SSStarReduction red, Vec F, Vec f)
{
  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(SSSTAR_Schur, 0, 0, 0, 0));
  PetscCall((*red->ops.reduceload)(red, F, f));
  PetscCall(PetscLogEventEnd(SSSTAR_Schur, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/*@C
   SSStarReductionRecover - the full displacement u (a vector of K) of the load F from the contact displacement uC
   and the contact force rC = P uC - f (for none: uC is already the whole u)

   Collective

   Input Parameters:
+  red - the reduction
.  F   - the whole load
.  uC  - the contact displacement
-  rC  - the contact force P uC - f

   Output Parameter:
.  u - the whole displacement

   Level: developer

.seealso: `SSStarReductionCreate()`
@*/
PetscErrorCode SSStarReductionRecover(SSStarReduction red, Vec F, Vec uC, Vec rC, Vec u)
{
  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(SSSTAR_Recovery, 0, 0, 0, 0));
  if (red->wholeBody) PetscCall((*red->ops.recover)(red, F, uC, rC, u));
  else PetscCall(RecoverWithContact(red, F, uC, rC, u));
  PetscCall(PetscLogEventEnd(SSSTAR_Recovery, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/*@C
   SSStarReductionDestroy - frees the reduction (its factorization and P)

   Collective

   Input Parameter:
.  red - the reduction

   Level: developer

.seealso: `SSStarReductionCreate()`
@*/
PetscErrorCode SSStarReductionDestroy(SSStarReduction *red)
{
  PetscFunctionBegin;
  if (!*red) PetscFunctionReturn(0);
  if ((*red)->ops.destroy) PetscCall((*(*red)->ops.destroy)(*red));
  PetscCall(PetscFree((*red)->data));
  PetscCall(ISDestroy(&(*red)->isC));
  PetscCall(ISDestroy(&(*red)->isI));
  PetscCall(MatDestroy(&(*red)->P));
  PetscCall(PetscFree((*red)->type));
  PetscCall(PetscFree((*red)->prefix));
  PetscCall(PetscFree(*red));
  PetscFunctionReturn(0);
}
