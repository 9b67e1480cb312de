/*
   The friction law of a contact group, read from the table of laws (SSStarLawGetNames(), SSStarLawGetParameterNames()):
   -friction_law_<G> names any registered law and every parameter of the laws is the option -<parameter>_<G>, read,
   checked, shown and handed to the solver by what the table says of it (its number of values and its kind), so that a
   new law needs nothing here.
*/
#include "../sceneimpl.h"

/* The parameter of this name given for the group, or NULL */
static const SSStarGroupParameter *FindGiven(const SSStarContactGroup *cg, const char name[])
{
  for (PetscInt k = 0; k < cg->nparams; k++) {
    PetscBool same;

    if (!PetscStrcmp(name, cg->params[k].name, &same) && same) return &cg->params[k];
  }
  return NULL;
}

/* The names of the laws of the table that have the parameter (NULL: every law), joined by ", " and conjunction before
   the last: "none, tresca, coulomb or orthotropic" */
static PetscErrorCode JoinLaws(const char parameter[], const char conjunction[], char text[], size_t len)
{
  PetscInt           nlaws, n = 0;
  const char *const *laws;
  const char       **chosen;

  PetscFunctionBegin;
  PetscCall(SSStarLawGetNames(&nlaws, &laws));
  PetscCall(PetscMalloc1(nlaws, &chosen));
  for (PetscInt l = 0; l < nlaws; l++) {
    PetscBool has = PETSC_TRUE;

    if (parameter) PetscCall(SSStarLawHasParameter(l, parameter, &has));
    if (has) chosen[n++] = laws[l];
  }
  text[0] = 0;
  for (PetscInt k = 0; k < n; k++) {
    PetscCall(PetscStrlcat(text, k == 0 ? "" : k == n - 1 ? conjunction : ", ", len));
    PetscCall(PetscStrlcat(text, chosen[k], len));
  }
  PetscCall(PetscFree(chosen));
  PetscFunctionReturn(0);
}

/* -friction_law_<G>: a law of the table */
PetscErrorCode SSStarGroupLawRead(SSStarScene scene, SSStarContactGroup *cg, const char option[])
{
  char      name[64] = "", known[256];
  PetscBool set;

  PetscFunctionBegin;
  PetscCall(PetscOptionsGetString(NULL, NULL, option, name, sizeof(name), &set));
  PetscCall(SSStarLawGetIndex(name, &cg->law));
  if (cg->law < 0) PetscCall(JoinLaws(NULL, ", ", known, sizeof(known)));
  PetscCheck(cg->law >= 0, scene->comm, PETSC_ERR_ARG_UNKNOWN_TYPE, "Unknown option %s for %s: the friction laws are %s", name, option, known);
  cg->lawSet = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* -<parameter>_<G>: its values, checked by the parameter's kind (a number >= 0, or a nonzero direction) */
PetscErrorCode SSStarGroupLawReadParameter(SSStarScene scene, SSStarContactGroup *cg, const char parameter[], const char option[])
{
  SSStarLawParameterKind kind;
  SSStarGroupParameter  *gp;
  const char            *description;
  PetscInt               size, got;
  PetscBool              set;

  PetscFunctionBegin;
  PetscCall(SSStarLawGetParameterInfo(parameter, &kind, &size, &description, NULL, NULL, NULL));
  PetscCall(PetscRealloc(sizeof(SSStarGroupParameter) * (cg->nparams + 1), &cg->params));
  gp = &cg->params[cg->nparams++];
  PetscCall(PetscMemzero(gp, sizeof(*gp)));
  PetscCall(PetscStrncpy(gp->name, parameter, sizeof(gp->name)));
  gp->size = got = size;
  PetscCall(PetscOptionsGetRealArray(NULL, NULL, option, gp->value, &got, &set));
  if (kind == SSSTAR_LAW_DIRECTION) {
    PetscCheck(got == 3, scene->comm, PETSC_ERR_ARG_WRONG, "Option %s needs 3 comma-separated values x,y,z (got %" PetscInt_FMT ")", option, got);
    for (PetscInt k = 0; k < 3; k++) PetscCheck(!PetscIsInfOrNanReal(gp->value[k]), scene->comm, PETSC_ERR_ARG_OUTOFRANGE, "Option %s: value %" PetscInt_FMT " is not a finite number (%g)", option, k + 1, (double)gp->value[k]);
    PetscCheck(gp->value[0] != 0 || gp->value[1] != 0 || gp->value[2] != 0, scene->comm, PETSC_ERR_ARG_OUTOFRANGE, "Option %s 0,0,0: the %s must be a nonzero vector (global axes)", option, description);
  } else {
    PetscCheck(got == 1, scene->comm, PETSC_ERR_ARG_WRONG, "Option %s needs one number (got %" PetscInt_FMT ")", option, got);
    PetscCheck(gp->value[0] >= 0 && !PetscIsInfOrNanReal(gp->value[0]), scene->comm, PETSC_ERR_ARG_OUTOFRANGE, "Option %s %g: the %s must be a number >= 0%s", option, (double)gp->value[0], description, kind == SSSTAR_LAW_FORCE ? " (a force per contact node)" : "");
  }
  PetscFunctionReturn(0);
}

/* Contradictory and incomplete entries: a parameter the group's law does not have, one it needs without a default */
PetscErrorCode SSStarGroupLawCheck(SSStarScene scene, const SSStarContactGroup *cg)
{
  const char        *law;
  PetscInt           nparams;
  const char *const *params;
  char               owners[256];

  PetscFunctionBegin;
  PetscCall(SSStarLawGetInfo(cg->law, &law, NULL, &nparams, &params));
  for (PetscInt k = 0; k < cg->nparams; k++) {
    PetscBool   has;
    const char *description;

    PetscCall(SSStarLawHasParameter(cg->law, cg->params[k].name, &has));
    if (has) continue;
    PetscCall(SSStarLawGetParameterInfo(cg->params[k].name, NULL, NULL, &description, NULL, NULL, NULL));
    PetscCall(JoinLaws(cg->params[k].name, " or ", owners, sizeof(owners)));
    SETERRQ(scene->comm, PETSC_ERR_ARG_WRONG, "Options -%s_%s and -friction_law_%s %s contradict each other: the %s is a parameter of the law %s", cg->params[k].name, cg->name, cg->name, law, description, owners);
  }
  for (PetscInt p = 0; p < nparams; p++) {
    PetscBool   hasDefault;
    const char *description;

    PetscCall(SSStarLawGetParameterInfo(params[p], NULL, NULL, &description, NULL, &hasDefault, NULL));
    PetscCheck(hasDefault || FindGiven(cg, params[p]), scene->comm, PETSC_ERR_ARG_WRONG, "Option -friction_law_%s %s needs -%s_%s (the %s)", cg->name, law, params[p], cg->name, description);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarGroupLawDestroy(SSStarContactGroup *cg)
{
  PetscFunctionBegin;
  PetscCall(PetscFree(cg->params));
  cg->nparams = 0;
  PetscFunctionReturn(0);
}

/* The options -help lists for the laws of the groups, from the table */
PetscErrorCode SSStarGroupLawHelp(char text[], size_t len)
{
  PetscInt           nparams;
  const char *const *params;
  char               line[512], laws[256];

  PetscFunctionBegin;
  PetscCall(JoinLaws(NULL, " or ", laws, sizeof(laws)));
  PetscCall(PetscSNPrintf(text, len, "  -friction_law_<G> <coulomb>: the friction law of G: %s\n", laws));
  PetscCall(SSStarLawGetParameterNames(&nparams, &params));
  for (PetscInt p = 0; p < nparams; p++) {
    SSStarLawParameterKind kind;
    const char            *description, *symbol;
    PetscBool              hasDefault;

    PetscCall(SSStarLawGetParameterInfo(params[p], &kind, NULL, &description, &symbol, &hasDefault, NULL));
    PetscCall(JoinLaws(params[p], " or ", laws, sizeof(laws)));
    PetscCall(PetscSNPrintf(line, sizeof(line), "  -%s_<G> <%s>: the %s of G%s (law %s; %s%s)\n", params[p], kind == SSSTAR_LAW_DIRECTION ? "x,y,z" : symbol, description, kind == SSSTAR_LAW_DIRECTION ? " in global axes" : kind == SSSTAR_LAW_FORCE ? ", a force per contact node" : "", laws, hasDefault ? "default: the solver's, -snes_ssstar_" : "required", hasDefault ? params[p] : ""));
    PetscCall(PetscStrlcat(text, line, len));
  }
  PetscFunctionReturn(0);
}

/* ", friction coulomb, phi = 0.5": the group's law and the values of its parameters (or where they come from) */
PetscErrorCode SSStarGroupLawView(const SSStarContactGroup *cg, PetscViewer viewer)
{
  const char        *law;
  PetscInt           nparams;
  const char *const *params;

  PetscFunctionBegin;
  PetscCall(SSStarLawGetInfo(cg->law, &law, NULL, &nparams, &params));
  PetscCall(PetscViewerASCIIPrintf(viewer, ", friction %s", law));
  for (PetscInt p = 0; p < nparams; p++) {
    const SSStarGroupParameter *gp = FindGiven(cg, params[p]);
    const char                 *symbol;

    PetscCall(SSStarLawGetParameterInfo(params[p], NULL, NULL, NULL, &symbol, NULL, NULL));
    if (!gp) PetscCall(PetscViewerASCIIPrintf(viewer, ", %s of the solver (-snes_ssstar_%s)", symbol, params[p]));
    else if (gp->size == 1) PetscCall(PetscViewerASCIIPrintf(viewer, ", %s = %g", symbol, (double)gp->value[0]));
    else PetscCall(PetscViewerASCIIPrintf(viewer, ", %s = (%g, %g, %g)", symbol, (double)gp->value[0], (double)gp->value[1], (double)gp->value[2]));
  }
  PetscFunctionReturn(0);
}

/*
   The laws of the contact nodes and their parameters to the solver: one law for every node (SNESSSStarSetFrictionLaw())
   or one per node (SNESSSStarSetNodeFrictionLaws()), and every parameter a group gives as one value per node
   (SNESSSStarSetNodeLawParameter()), SSSTAR_NOT_GIVEN at the nodes of the groups without it: they keep the solver's
   value, whenever it is set
*/
PetscErrorCode SSStarSceneSetContactLaws(SSStarScene scene, SNES snes)
{
  PetscBool          anyLaw = PETSC_FALSE, oneLaw = PETSC_TRUE;
  PetscInt           nparams;
  const char *const *params;
  const char        *law;

  PetscFunctionBegin;
  for (PetscInt g = 0; g < scene->nContact; g++) {
    anyLaw = (PetscBool)(anyLaw || scene->contact[g].lawSet);
    oneLaw = (PetscBool)(oneLaw && scene->contact[g].law == scene->contact[0].law);
  }
  PetscCall(SSStarLawGetInfo(scene->contact[0].law, &law, NULL, NULL, NULL));
  if (anyLaw && oneLaw) PetscCall(SNESSSStarSetFrictionLaw(snes, law));
  else if (!oneLaw) {
    PetscInt *laws;

    PetscCall(PetscMalloc1(scene->n, &laws));
    for (PetscInt i = 0; i < scene->n; i++) laws[i] = scene->contact[scene->group[i]].law;
    PetscCall(SNESSSStarSetNodeFrictionLaws(snes, scene->n, laws));
    PetscCall(PetscFree(laws));
  }
  PetscCall(SSStarLawGetParameterNames(&nparams, &params));
  for (PetscInt p = 0; p < nparams; p++) {
    PetscBool  given = PETSC_FALSE;
    PetscInt   size;
    PetscReal *values;
    Vec        v;

    for (PetscInt g = 0; g < scene->nContact; g++) given = (PetscBool)(given || FindGiven(&scene->contact[g], params[p]));
    if (!given) continue;
    PetscCall(SSStarLawGetParameterSize(params[p], &size));
    PetscCall(PetscMalloc1(size * scene->n + 1, &values));
    for (PetscInt i = 0; i < scene->n; i++) {
      const SSStarGroupParameter *gp = FindGiven(&scene->contact[scene->group[i]], params[p]);

      for (PetscInt k = 0; k < size; k++) values[size * i + k] = gp ? gp->value[k] : SSSTAR_NOT_GIVEN;
    }
    PetscCall(SSStarSceneNodeVec(scene, size, values, &v));
    PetscCall(SNESSSStarSetNodeLawParameter(snes, params[p], v));
    PetscCall(VecDestroy(&v));
    PetscCall(PetscFree(values));
  }
  PetscFunctionReturn(0);
}
