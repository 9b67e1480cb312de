/*
   The table of friction laws: each law registered by name (SSStarLawRegister(); the laws of ssstar by
   SSStarLawRegisterAll(), lawregall.c) gets its place in the table, its index, which output files write per node
   (/contact/friction_law, with the names in the table's order). Everything that needs the number of laws, their names
   or their parameters asks the table.
*/
#include "lawimpl.h"

static SSStarLaw   *Laws       = NULL; /* the table, in the order of registration                        */
static PetscInt     NumLaws    = 0;
static const char **LawNames   = NULL; /* their names, NULL-terminated                                   */
static const char **ParamNames = NULL; /* the names of their parameters, each once, NULL-terminated      */
static PetscInt     NumParams  = 0;

const char *const SSStarLawParameterKinds[] = {"coefficient", "force", "direction", "SSStarLawParameterKind", "SSSTAR_LAW_", NULL};

PetscInt SSStarLawParameterSize(SSStarLawParameterKind kind)
{
  return kind == SSSTAR_LAW_DIRECTION ? 3 : 1;
}

PetscInt SSStarLawParameterOffset(SSStarLaw law, PetscInt p)
{
  PetscInt offset = 0;

  for (PetscInt q = 0; q < p; q++) offset += SSStarLawParameterSize(law->params[q].kind);
  return offset;
}

/* The parameter of this name in the registered laws (a name means the same in every law that has it), or NULL */
static const SSStarLawParameter *FindParameter(const char name[])
{
  for (PetscInt l = 0; l < NumLaws; l++)
    for (PetscInt p = 0; p < Laws[l]->nparams; p++) {
      PetscBool same;

      if (!PetscStrcmp(name, Laws[l]->params[p].name, &same) && same) return &Laws[l]->params[p];
    }
  return NULL;
}

/* The parameter names of the table, each once in the order the laws name them */
static PetscErrorCode ListParameters(void)
{
  PetscInt total = 0;

  PetscFunctionBegin;
  for (PetscInt l = 0; l < NumLaws; l++) total += Laws[l]->nparams;
  PetscCall(PetscFree(ParamNames));
  PetscCall(PetscMalloc1(total + 1, &ParamNames));
  NumParams = 0;
  for (PetscInt l = 0; l < NumLaws; l++)
    for (PetscInt p = 0; p < Laws[l]->nparams; p++) {
      PetscBool seen = PETSC_FALSE;

      for (PetscInt q = 0; q < NumParams && !seen; q++) PetscCall(PetscStrcmp(ParamNames[q], Laws[l]->params[p].name, &seen));
      if (!seen) ParamNames[NumParams++] = Laws[l]->params[p].name;
    }
  ParamNames[NumParams] = NULL;
  PetscFunctionReturn(0);
}

/*@C
   SSStarLawRegister - adds a friction law to the table of ssstar's laws

   Not Collective

   Input Parameters:
+  name   - its name (SNESSSStarSetFrictionLaw(), -snes_ssstar_friction_law)
-  create - fills the law: its label, parameters, properties and kernels (src/snes/impls/ssstar/laws/lawimpl.h)

   Notes:
   The law gets the next index of the table (SSStarLawGetNames()). Registering a name again replaces that law in its
   place. A parameter name used by several laws must be of the same kind and default in each (it is one setting of the
   solver, SNESSSStarSetLawParameter()). A law of ssstar is one file in src/snes/impls/ssstar/laws/ plus its
   registration in lawregall.c (its declaration and one line in SSStarLawRegisterAll()); the solver's and the scenes'
   options (-snes_ssstar_<parameter>, -friction_law_<G>, -<parameter>_<G>), their checks, -help, the views, the output
   (/contact/friction_law, /contact/<parameter>) and the Python module follow from the table (docs/guide/own-program.md, "Adding a friction
   law").

   Level: advanced

.seealso: `SSStarLawRegisterAll()`, `SSStarLawGetNames()`, `SNESSSStarSetFrictionLaw()`
@*/
PetscErrorCode SSStarLawRegister(const char name[], PetscErrorCode (*create)(SSStarLaw))
{
  SSStarLaw law = NULL;
  PetscInt  index = NumLaws;

  PetscFunctionBegin;
  for (PetscInt l = 0; l < NumLaws; l++) {
    PetscBool same;

    PetscCall(PetscStrcmp(name, Laws[l]->name, &same));
    if (same) index = l;
  }
  PetscCall(PetscNew(&law));
  PetscCall(PetscStrallocpy(name, &law->name));
  law->index = index;
  PetscCall((*create)(law));
  PetscCheck(law->nparams >= 0 && law->nparams <= SSSTAR_LAW_MAX_PARAMETERS && law->ops.tangential && law->ops.margin && law->ops.sliding && law->ops.frictionless, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Friction law %s: %" PetscInt_FMT " parameters (at most %d) or a kernel missing", name, law->nparams, SSSTAR_LAW_MAX_PARAMETERS);
  PetscCheck(SSStarLawParameterOffset(law, law->nparams) <= SSSTAR_LAW_MAX_VALUES, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Friction law %s: more than %d values per node", name, SSSTAR_LAW_MAX_VALUES);
  for (PetscInt p = 0; p < law->nparams; p++) {
    const SSStarLawParameter *par = &law->params[p], *earlier = FindParameter(par->name);

    PetscCheck(!earlier || (earlier->kind == par->kind && earlier->hasDefault == par->hasDefault && (!par->hasDefault || earlier->defaultValue == par->defaultValue)), PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "Friction law %s: its parameter %s is of another kind or default in an earlier law", name, par->name);
    PetscCheck(!par->hasDefault || (par->kind != SSSTAR_LAW_DIRECTION && par->defaultValue >= 0), PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "Friction law %s: the default of %s must be a number >= 0 (a direction has none)", name, par->name);
  }
  if (index < NumLaws) {
    PetscCall(PetscFree(Laws[index]->name));
    PetscCall(PetscFree(Laws[index]));
  } else {
    PetscCall(PetscRealloc(sizeof(SSStarLaw) * (NumLaws + 1), &Laws));
    PetscCall(PetscRealloc(sizeof(const char *) * (NumLaws + 2), &LawNames));
    NumLaws++;
  }
  Laws[index]       = law;
  LawNames[index]   = law->name;
  LawNames[NumLaws] = NULL;
  PetscCall(ListParameters());
  PetscFunctionReturn(0);
}

/* Empties the table (SSStarFinalizePackage()) */
PetscErrorCode SSStarLawDestroyAll(void)
{
  PetscFunctionBegin;
  for (PetscInt l = 0; l < NumLaws; l++) {
    PetscCall(PetscFree(Laws[l]->name));
    PetscCall(PetscFree(Laws[l]));
  }
  PetscCall(PetscFree(Laws));
  PetscCall(PetscFree(LawNames));
  PetscCall(PetscFree(ParamNames));
  NumLaws   = 0;
  NumParams = 0;
  PetscFunctionReturn(0);
}

/*@C
   SSStarLawGetNames - the registered friction laws: their number and names, in the order of the table (a law's
   index is its place here)

   Not Collective

   Output Parameters:
+  n     - the number of laws, or pass NULL
-  names - their names, NULL-terminated (owned by ssstar), or pass NULL

   Notes:
   SSStarInitializePackage() registers ssstar's laws: none, tresca, coulomb, orthotropic.

   Level: intermediate

.seealso: `SSStarLawGetIndex()`, `SSStarLawGetInfo()`, `SSStarLawRegister()`
@*/
PetscErrorCode SSStarLawGetNames(PetscInt *n, const char *const *names[])
{
  PetscFunctionBegin;
  if (n) *n = NumLaws;
  if (names) *names = LawNames;
  PetscFunctionReturn(0);
}

/* The law of the table with this name (upper or lower case), or an error naming the registered ones */
PetscErrorCode SSStarLawFind(const char name[], SSStarLaw *law)
{
  char list[256] = "";

  PetscFunctionBegin;
  for (PetscInt l = 0; l < NumLaws; l++) {
    PetscBool same;

    PetscCall(PetscStrcasecmp(name, Laws[l]->name, &same));
    if (same) {
      *law = Laws[l];
      PetscFunctionReturn(0);
    }
    PetscCall(PetscStrlcat(list, l ? ", " : "", sizeof(list)));
    PetscCall(PetscStrlcat(list, Laws[l]->name, sizeof(list)));
  }
  SETERRQ(PETSC_COMM_SELF, PETSC_ERR_ARG_UNKNOWN_TYPE, "Unknown friction law %s: the registered laws are %s", name, NumLaws ? list : "none yet (call SSStarInitializePackage())");
}

/*@C
   SSStarLawGetIndex - the index of a friction law in the table of laws

   Not Collective

   Input Parameter:
.  name - the law's name (upper or lower case)

   Output Parameter:
.  index - its place in the table (SSStarLawGetNames()), or -1 when no law has this name

   Level: intermediate

.seealso: `SSStarLawGetNames()`, `SNESSSStarSetNodeFrictionLaws()`
@*/
PetscErrorCode SSStarLawGetIndex(const char name[], PetscInt *index)
{
  PetscFunctionBegin;
  *index = -1;
  for (PetscInt l = 0; l < NumLaws && *index < 0; l++) {
    PetscBool same;

    PetscCall(PetscStrcasecmp(name, Laws[l]->name, &same));
    if (same) *index = l;
  }
  PetscFunctionReturn(0);
}

/* The law at an index of the table */
PetscErrorCode SSStarLawGet(PetscInt index, SSStarLaw *law)
{
  PetscFunctionBegin;
  PetscCheck(index >= 0 && index < NumLaws, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Friction law %" PetscInt_FMT ": the table has the laws 0..%" PetscInt_FMT, index, NumLaws - 1);
  *law = Laws[index];
  PetscFunctionReturn(0);
}

/*@C
   SSStarLawGetInfo - what a friction law of the table is: its name, its effect and its parameters

   Not Collective

   Input Parameter:
.  index - the law's index (SSStarLawGetIndex())

   Output Parameters:
+  name    - its name, or pass NULL
.  effect  - what it adds to the contact, e.g. "Coulomb friction" (NULL for frictionless contact), or pass NULL
.  nparams - the number of its parameters, or pass NULL
-  params  - their names (SNESSSStarSetLawParameter(); nparams of them, owned by ssstar), or pass NULL

   Level: intermediate

.seealso: `SSStarLawGetNames()`, `SSStarLawHasParameter()`
@*/
PetscErrorCode SSStarLawGetInfo(PetscInt index, const char *name[], const char *effect[], PetscInt *nparams, const char *const *params[])
{
  SSStarLaw law = NULL;

  PetscFunctionBegin;
  PetscCall(SSStarLawGet(index, &law));
  if (name) *name = law->name;
  if (effect) *effect = law->effect;
  if (nparams) *nparams = law->nparams;
  if (params) {
    for (PetscInt p = 0; p < law->nparams; p++) law->paramNames[p] = law->params[p].name;
    *params = law->paramNames;
  }
  PetscFunctionReturn(0);
}

/*@C
   SSStarLawHasParameter - whether a friction law of the table has a parameter of this name

   Not Collective

   Input Parameters:
+  index - the law's index
-  name  - the parameter's name ("friction", "slip_bound", ...)

   Output Parameter:
.  has - PETSC_TRUE if it has

   Level: intermediate

.seealso: `SSStarLawGetInfo()`, `SNESSSStarSetLawParameter()`
@*/
PetscErrorCode SSStarLawHasParameter(PetscInt index, const char name[], PetscBool *has)
{
  SSStarLaw law = NULL;

  PetscFunctionBegin;
  PetscCall(SSStarLawGet(index, &law));
  *has = PETSC_FALSE;
  for (PetscInt p = 0; p < law->nparams && !*has; p++) PetscCall(PetscStrcmp(name, law->params[p].name, has));
  PetscFunctionReturn(0);
}

/* Where parameter name is in law (-1: not its parameter) */
PetscInt SSStarLawFindParameter(SSStarLaw law, const char name[])
{
  for (PetscInt p = 0; p < law->nparams; p++) {
    PetscBool same;

    if (!PetscStrcmp(name, law->params[p].name, &same) && same) return p;
  }
  return -1;
}

/* The parameter of this name in the table; an error naming the parameters of the registered laws when none has it */
PetscErrorCode SSStarLawGetParameter(const char name[], const SSStarLawParameter **par)
{
  char list[512] = "";

  PetscFunctionBegin;
  *par = FindParameter(name);
  if (*par) PetscFunctionReturn(0);
  for (PetscInt l = 0; l < NumLaws; l++)
    for (PetscInt p = 0; p < Laws[l]->nparams; p++) {
      PetscCall(PetscStrlcat(list, list[0] ? ", " : "", sizeof(list)));
      PetscCall(PetscStrlcat(list, Laws[l]->params[p].name, sizeof(list)));
      PetscCall(PetscStrlcat(list, " (", sizeof(list)));
      PetscCall(PetscStrlcat(list, Laws[l]->name, sizeof(list)));
      PetscCall(PetscStrlcat(list, ")", sizeof(list)));
    }
  SETERRQ(PETSC_COMM_SELF, PETSC_ERR_ARG_UNKNOWN_TYPE, "No friction law has a parameter %s: the parameters are %s", name, list);
}

/* What is wrong with the values of a parameter ("-0.1: the friction coefficient must be a number >= 0"), or "" */
PetscErrorCode SSStarLawCheckValues(const SSStarLawParameter *par, const PetscReal v[], char msg[], size_t len)
{
  PetscFunctionBegin;
  msg[0] = 0;
  if (par->kind == SSSTAR_LAW_DIRECTION) {
    if (PetscIsInfOrNanReal(v[0]) || PetscIsInfOrNanReal(v[1]) || PetscIsInfOrNanReal(v[2]) || (v[0] == 0 && v[1] == 0 && v[2] == 0)) PetscCall(PetscSNPrintf(msg, len, "%g,%g,%g: the %s must be a nonzero vector", (double)v[0], (double)v[1], (double)v[2], par->description));
  } else if (PetscIsInfOrNanReal(v[0]) || v[0] < 0) PetscCall(PetscSNPrintf(msg, len, "%g: the %s must be a number >= 0", (double)v[0], par->description));
  PetscFunctionReturn(0);
}

/*@C
   SSStarLawGetParameterSize - the number of values per node of a parameter of the friction laws

   Not Collective

   Input Parameter:
.  name - the parameter ("friction", "slip_bound", "friction_direction", ...)

   Output Parameter:
.  size - 1 for a coefficient or a force, 3 for a direction; an error names the parameters of the laws when no law
          has this one

   Level: intermediate

.seealso: `SSStarLawGetInfo()`, `SNESSSStarSetLawParameter()`, `SNESSSStarGetNodeLawParameter()`
@*/
PetscErrorCode SSStarLawGetParameterSize(const char name[], PetscInt *size)
{
  const SSStarLawParameter *par;

  PetscFunctionBegin;
  PetscCall(SSStarLawGetParameter(name, &par));
  *size = SSStarLawParameterSize(par->kind);
  PetscFunctionReturn(0);
}

/*@C
   SSStarLawGetParameterNames - the parameters of the registered friction laws: each name once, in the order of the
   table (a name several laws have is one parameter, SNESSSStarSetLawParameter())

   Not Collective

   Output Parameters:
+  n     - the number of parameters, or pass NULL
-  names - their names, NULL-terminated (owned by ssstar), or pass NULL

   Notes:
   With ssstar's laws: friction, slip_bound, friction_1, friction_2, friction_direction. The scenes read each as the
   option -<name>_<G> of a contact group and write each as /contact/<name>.

   Level: intermediate

.seealso: `SSStarLawGetParameterInfo()`, `SSStarLawGetInfo()`, `SSStarLawGetNames()`
@*/
PetscErrorCode SSStarLawGetParameterNames(PetscInt *n, const char *const *names[])
{
  PetscFunctionBegin;
  if (n) *n = NumParams;
  if (names) *names = ParamNames;
  PetscFunctionReturn(0);
}

/*@C
   SSStarLawGetParameterInfo - what a parameter of the friction laws is

   Not Collective

   Input Parameter:
.  name - the parameter ("friction", "slip_bound", "friction_direction", ...)

   Output Parameters:
+  kind         - SSSTAR_LAW_COEFFICIENT (a number >= 0), SSSTAR_LAW_FORCE (>= 0, a force per contact node) or
                  SSSTAR_LAW_DIRECTION (x, y, z in global axes, nonzero), or pass NULL
.  size         - its number of values per node: 1, or 3 for a direction, or pass NULL
.  description  - "friction coefficient", for messages (owned by ssstar), or pass NULL
.  symbol       - "phi", for views (owned by ssstar), or pass NULL
.  hasDefault   - whether the solver gives it a value until one is set (coulomb's friction: 0.3), or pass NULL
-  defaultValue - that value (0 without one), or pass NULL

   Notes:
   An error names the parameters of the laws when no law has this one.

   Level: intermediate

.seealso: `SSStarLawGetParameterNames()`, `SSStarLawGetParameterSize()`, `SNESSSStarSetLawParameter()`
@*/
PetscErrorCode SSStarLawGetParameterInfo(const char name[], SSStarLawParameterKind *kind, PetscInt *size, const char *description[], const char *symbol[], PetscBool *hasDefault, PetscReal *defaultValue)
{
  const SSStarLawParameter *par;

  PetscFunctionBegin;
  PetscCall(SSStarLawGetParameter(name, &par));
  if (kind) *kind = par->kind;
  if (size) *size = SSStarLawParameterSize(par->kind);
  if (description) *description = par->description;
  if (symbol) *symbol = par->symbol;
  if (hasDefault) *hasDefault = par->hasDefault;
  if (defaultValue) *defaultValue = par->hasDefault ? par->defaultValue : 0.0;
  PetscFunctionReturn(0);
}

/*@C
   SSStarFrictionSet - a node's friction law and its values, for the per-node kernels

   Not Collective

   Input Parameters:
+  law    - the law's name
.  n      - the number of values
-  values - the values of the law's parameters in its order (SSStarLawGetInfo()): one per coefficient or force (a
            force in the units of the kernels' c), three per direction (in the node's frame)

   Output Parameter:
.  fr - the node's friction, as SSStarApproximationStep() and the other kernels take it

   Notes:
   The law checks the values and puts them in its form (the orthotropic law projects its direction onto the tangent
   plane and normalizes it); an error says what is wrong.

   Level: developer

.seealso: `SSStarApproximationStep()`, `SSStarLawGetInfo()`
@*/
PetscErrorCode SSStarFrictionSet(SSStarFriction *fr, const char law[], PetscInt n, const PetscReal values[])
{
  const char *problem;

  PetscFunctionBegin;
  PetscCall(SSStarLawFind(law, &fr->law));
  PetscCheck(n == SSStarLawParameterOffset(fr->law, fr->law->nparams), PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "SSStarFrictionSet: the law %s takes %" PetscInt_FMT " values, not %" PetscInt_FMT, law, SSStarLawParameterOffset(fr->law, fr->law->nparams), n);
  for (PetscInt k = 0; k < SSSTAR_LAW_MAX_VALUES; k++) fr->value[k] = k < n ? values[k] : 0.0;
  problem = fr->law->ops.prepare ? fr->law->ops.prepare(fr) : NULL;
  PetscCheck(!problem, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "SSStarFrictionSet: %s", problem);
  PetscFunctionReturn(0);
}
