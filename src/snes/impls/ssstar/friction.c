/*
   The friction laws of the contact nodes and their parameters, as declared (SNESSSStarSetFrictionLaw(),
   SNESSSStarSetLawParameter(), per node SNESSSStarSetNodeFrictionLaws() and SNESSSStarSetNodeLawParameter()), and what
   the last set-up made of them per node. The per-node data are built at the set-up (contact.c); every check of the
   declaration is collective (SSStarCheckAllRanks()).
*/
#include "ssstarimpl.h"
#include "laws/lawimpl.h"

/* The setting of a parameter of the registered laws, created when first named; an error for an unknown name */
static PetscErrorCode GetSetting(SSStarContact *ct, const char name[], SSStarLawSetting **setting)
{
  const SSStarLawParameter *par;

  PetscFunctionBegin;
  PetscCall(SSStarContactFindSetting(ct, name, setting));
  if (*setting) PetscFunctionReturn(0);
  PetscCall(SSStarLawGetParameter(name, &par));
  PetscCall(PetscRealloc(sizeof(SSStarLawSetting) * (ct->nsettings + 1), &ct->settings));
  *setting = &ct->settings[ct->nsettings++];
  PetscCall(PetscMemzero(*setting, sizeof(**setting)));
  PetscCall(PetscStrncpy((*setting)->name, name, sizeof((*setting)->name)));
  (*setting)->size = SSStarLawParameterSize(par->kind);
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

PetscErrorCode SSStarContactSetLaw(SSStarContact *ct, const char law[])
{
  PetscFunctionBegin;
  PetscCall(SSStarLawFind(law, &ct->law));
  SSStarContactDeclared(ct);
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
  PetscCall(SSStarLawCheckValues(par, values, msg, sizeof(msg)));
  PetscCheck(!msg[0], comm, PETSC_ERR_ARG_OUTOFRANGE, "-snes_ssstar_%s %s", name, msg);
  PetscCall(GetSetting(ct, name, &setting));
  for (PetscInt k = 0; k < n; k++) setting->value[k] = values[k];
  setting->set = PETSC_TRUE;
  SSStarContactDeclared(ct);
  PetscFunctionReturn(0);
}

/* The value for every node of a law parameter, if set */
PetscErrorCode SSStarContactGetParameter(SSStarContact *ct, const char name[], PetscInt *n, PetscReal values[], PetscBool *set)
{
  SSStarLawSetting         *setting;
  const SSStarLawParameter *par;

  PetscFunctionBegin;
  PetscCall(SSStarLawGetParameter(name, &par));
  PetscCall(SSStarContactFindSetting(ct, name, &setting));
  *n   = SSStarLawParameterSize(par->kind);
  *set = (PetscBool)(setting && setting->set);
  for (PetscInt k = 0; k < *n; k++) values[k] = *set ? setting->value[k] : 0.0;
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

static PetscErrorCode SNESSSStarSetFrictionLaw_SSStar(SNES snes, const char law[])
{
  PetscFunctionBegin;
  PetscCall(SSStarContactSetLaw(&((SNES_SSStar *)snes->data)->contact, law));
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

static PetscErrorCode SNESSSStarGetFrictionLaw_SSStar(SNES snes, const char *law[])
{
  PetscFunctionBegin;
  PetscCall(SSStarLawGetInfo(((SNES_SSStar *)snes->data)->contact.law->index, law, NULL, NULL, NULL));
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

static PetscErrorCode SNESSSStarSetLawParameter_SSStar(SNES snes, const char name[], PetscInt n, const PetscReal values[])
{
  PetscFunctionBegin;
  PetscCall(SSStarContactSetParameter(PetscObjectComm((PetscObject)snes), &((SNES_SSStar *)snes->data)->contact, name, n, values));
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

static PetscErrorCode SNESSSStarGetFriction_SSStar(SNES snes, PetscReal *friction)
{
  PetscInt  n;
  PetscBool set;

  PetscFunctionBegin;
  PetscCall(SSStarContactGetParameter(&((SNES_SSStar *)snes->data)->contact, "friction", &n, friction, &set));
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

static PetscErrorCode SNESSSStarSetNodeLawParameter_SSStar(SNES snes, const char name[], Vec v)
{
  SSStarContact    *ct = &((SNES_SSStar *)snes->data)->contact;
  SSStarLawSetting *setting;
  PetscInt          n;

  PetscFunctionBegin;
  PetscCall(GetSetting(ct, name, &setting));
  PetscCall(SSStarContactDeclaredNodes(ct, &n));
  PetscCall(SSStarContactCheckNodeVector(PetscObjectComm((PetscObject)snes), v, n, setting->size, "SNESSSStarSetNodeLawParameter: the values"));
  PetscCall(SSStarContactReplaceVec(&setting->perNode, v));
  SSStarContactDeclared(ct);
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

static PetscErrorCode SNESSSStarSetNodeFrictionLaws_SSStar(SNES snes, PetscInt n, const PetscInt laws[])
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
  SSStarContactDeclared(ct);
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

static PetscErrorCode SNESSSStarGetNodeFrictionLaws_SSStar(SNES snes, PetscInt n, PetscInt laws[])
{
  SSStarContact *ct = &((SNES_SSStar *)snes->data)->contact;

  PetscFunctionBegin;
  PetscCall(SSStarContactCheckNodeArrays(snes, ct, n, "SNESSSStarGetNodeFrictionLaws"));
  for (PetscInt i = 0; i < ct->nnodes; i++) laws[ct->order[i]] = ct->nodeFriction[i].law->index;
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

static PetscErrorCode SNESSSStarGetNodeLawParameter_SSStar(SNES snes, const char name[], PetscInt n, PetscReal values[])
{
  SSStarContact            *ct = &((SNES_SSStar *)snes->data)->contact;
  const SSStarLawParameter *par;
  PetscInt                  size;

  PetscFunctionBegin;
  PetscCall(SSStarLawGetParameter(name, &par));
  PetscCall(SSStarContactCheckNodeArrays(snes, ct, n, "SNESSSStarGetNodeLawParameter"));
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

/* The implementations of the public functions above, composed on the SNES (SNESSSStarComposeFunctions()) */
static const SSStarComposed Composed[] = {
    {"SNESSSStarSetFrictionLaw_C", (PetscVoidFunction)SNESSSStarSetFrictionLaw_SSStar},
    {"SNESSSStarGetFrictionLaw_C", (PetscVoidFunction)SNESSSStarGetFrictionLaw_SSStar},
    {"SNESSSStarSetLawParameter_C", (PetscVoidFunction)SNESSSStarSetLawParameter_SSStar},
    {"SNESSSStarGetFriction_C", (PetscVoidFunction)SNESSSStarGetFriction_SSStar},
    {"SNESSSStarSetNodeLawParameter_C", (PetscVoidFunction)SNESSSStarSetNodeLawParameter_SSStar},
    {"SNESSSStarGetNodeLawParameter_C", (PetscVoidFunction)SNESSSStarGetNodeLawParameter_SSStar},
    {"SNESSSStarSetNodeFrictionLaws_C", (PetscVoidFunction)SNESSSStarSetNodeFrictionLaws_SSStar},
    {"SNESSSStarGetNodeFrictionLaws_C", (PetscVoidFunction)SNESSSStarGetNodeFrictionLaws_SSStar},
};

PetscErrorCode SNESSSStarComposeFriction(SNES snes, PetscBool on)
{
  PetscFunctionBegin;
  PetscCall(SNESSSStarComposeTable(snes, Composed, PETSC_STATIC_ARRAY_LENGTH(Composed), on));
  PetscFunctionReturn(0);
}
