/*
   A scene from the options: the body (gmsh mesh), its material, supports and loads, and its contact groups, each with
   a rigid obstacle (a plane, ball, cylinder or triangle mesh: obstacle.c) and a friction law. Only what the options
   name is built: no contact group, no contact nodes; no -gravity, no body force.
*/
#include "sceneimpl.h"

#define SSSTAR_MAX_LIST 64 /* groups in one -dirichlet or -contact list */

/*@C
   SSStarSceneCreate - an empty scene; SSStarSceneSetFromOptions() describes it, SSStarSceneSetUp() builds it

   Collective

   Input Parameter:
.  comm - the ranks that share the scene

   Output Parameter:
.  scene - the scene

   Level: beginner

.seealso: `SSStarSceneSetFromOptions()`, `SSStarSceneSetUp()`, `SSStarSceneDestroy()`
@*/
PetscErrorCode SSStarSceneCreate(MPI_Comm comm, SSStarScene *scene)
{
  PetscFunctionBegin;
  PetscCall(PetscNew(scene));
  (*scene)->comm      = comm;
  (*scene)->meshScale = 1.0;
  (*scene)->level     = -1;
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneDestroy - frees the scene, its mesh and contact nodes

   Collective

   Input Parameter:
.  scene - the scene (set to NULL)

   Level: beginner

.seealso: `SSStarSceneCreate()`
@*/
PetscErrorCode SSStarSceneDestroy(SSStarScene *scene)
{
  SSStarScene s = *scene;

  PetscFunctionBegin;
  if (!s) PetscFunctionReturn(0);
  for (PetscInt g = 0; g < s->nDirichlet; g++) PetscCall(PetscFree(s->dirichlet[g]));
  PetscCall(PetscFree(s->dirichlet));
  PetscCall(PetscFree3(s->materials, s->tractions, s->springs));
  for (PetscInt g = 0; g < s->nContact; g++) PetscCall(SSStarObstacleReset(&s->contact[g].obstacle));
  PetscCall(PetscFree(s->contact));
  PetscCall(PetscFree4(s->tag, s->group, s->coords, s->normal));
  PetscCall(PetscFree2(s->gap, s->area));
  PetscCall(ISDestroy(&s->isC));
  PetscCall(PetscFree(s->body));
  PetscCall(PetscFree2(s->frame, s->weight));
  PetscCall(MatDestroy(&s->B));
  PetscCall(VecDestroy(&s->tags));
  PetscCall(DMDestroy(&s->dm));
  PetscCall(PetscFree(*scene));
  PetscFunctionReturn(0);
}

/* A real array option of exactly n finite values (or not given) */
static PetscErrorCode GetFiniteArray(MPI_Comm comm, const char option[], PetscInt n, const char form[], PetscReal v[], PetscBool *set)
{
  PetscInt got = n;

  PetscFunctionBegin;
  PetscCall(PetscOptionsGetRealArray(NULL, NULL, option, v, &got, set));
  if (!*set) PetscFunctionReturn(0);
  PetscCheck(got == n, comm, PETSC_ERR_ARG_WRONG, "Option %s needs %" PetscInt_FMT " comma-separated values %s (got %" PetscInt_FMT ")", option, n, form, got);
  for (PetscInt k = 0; k < n; k++) PetscCheck(!PetscIsInfOrNanReal(v[k]), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option %s: value %" PetscInt_FMT " is not a finite number (%g)", option, k + 1, (double)v[k]);
  PetscFunctionReturn(0);
}

/* A list of group names (-dirichlet, -contact); each name once */
static PetscErrorCode GetGroupList(MPI_Comm comm, const char option[], PetscInt *n, char ***names)
{
  char     *list[SSSTAR_MAX_LIST];
  PetscInt  max = SSSTAR_MAX_LIST;
  PetscBool set, same;

  PetscFunctionBegin;
  *n     = 0;
  *names = NULL;
  PetscCall(PetscOptionsGetStringArray(NULL, NULL, option, list, &max, &set));
  if (!set) PetscFunctionReturn(0);
  PetscCall(PetscMalloc1(max, names));
  for (PetscInt i = 0; i < max; i++) {
    size_t len;

    PetscCall(PetscStrlen(list[i], &len));
    PetscCheck(len > 0 && len < SSSTAR_GROUP_NAME_LEN, comm, PETSC_ERR_ARG_WRONG, "Option %s: group name %" PetscInt_FMT " is empty or longer than %d characters", option, i + 1, SSSTAR_GROUP_NAME_LEN - 1);
    for (PetscInt j = 0; j < i; j++) {
      PetscCall(PetscStrcmp(list[i], list[j], &same));
      PetscCheck(!same, comm, PETSC_ERR_ARG_WRONG, "Option %s names the group \"%s\" twice", option, list[i]);
    }
    (*names)[i] = list[i];
  }
  *n = max;
  PetscFunctionReturn(0);
}

static PetscErrorCode FindName(const char name[], PetscInt n, char *const names[], PetscInt *index)
{
  PetscBool same;

  PetscFunctionBegin;
  *index = -1;
  for (PetscInt i = 0; i < n && *index < 0; i++) {
    PetscCall(PetscStrcmp(name, names[i], &same));
    if (same) *index = i;
  }
  PetscFunctionReturn(0);
}

/* The options that carry a group name: -<prefix><G> */
typedef enum {
  OPT_MATERIAL,
  OPT_TRACTION,
  OPT_SPRING,
  OPT_OBSTACLE,
  OPT_FRICTION_LAW,
  OPT_FRICTION,
  OPT_SLIP_BOUND,
  OPT_CONTACT_PAIR,
  OPT_COUNT
} GroupOption;
/* friction_law_ before friction_: the longer prefix is tried first */
static const char *const GroupOptionPrefix[OPT_COUNT] = {"-material_", "-traction_", "-spring_", "-obstacle_", "-friction_law_", "-friction_", "-slip_bound_", "-contact_pair_"};

/* Calls found(scene, kind, group, option) for every option of the database with a group prefix */
static PetscErrorCode ForEachGroupOption(SSStarScene scene, PetscErrorCode (*found)(SSStarScene, GroupOption, const char[], const char[]))
{
  char  *all, *token, *save = NULL;

  PetscFunctionBegin;
  PetscCall(PetscOptionsGetAll(NULL, &all));
  for (token = strtok_r(all, " ", &save); token; token = strtok_r(NULL, " ", &save)) {
    for (PetscInt k = 0; k < OPT_COUNT; k++) {
      size_t    len;
      PetscBool match;

      PetscCall(PetscStrlen(GroupOptionPrefix[k], &len));
      PetscCall(PetscStrncmp(token, GroupOptionPrefix[k], len, &match));
      if (!match) continue;
      if (token[len]) {
        size_t glen;

        PetscCall(PetscStrlen(token + len, &glen));
        PetscCheck(glen < SSSTAR_GROUP_NAME_LEN, scene->comm, PETSC_ERR_ARG_WRONG, "Option %s: the group name is longer than %d characters", token, SSSTAR_GROUP_NAME_LEN - 1);
        PetscCall(found(scene, (GroupOption)k, token + len, token));
      }
      break;
    }
  }
  PetscCall(PetscFree(all));
  PetscFunctionReturn(0);
}

static PetscErrorCode CountGroupOption(SSStarScene scene, GroupOption kind, const char group[], const char option[])
{
  PetscFunctionBegin;
  if (kind == OPT_MATERIAL) scene->nMaterials++;
  if (kind == OPT_TRACTION) scene->nTractions++;
  if (kind == OPT_SPRING) scene->nSprings++;
  PetscFunctionReturn(0);
}

/* The contact group G of a -obstacle_G, -friction_law_G, -friction_G or -slip_bound_G (which must be in -contact) */
static PetscErrorCode ContactGroup(SSStarScene scene, const char group[], const char option[], SSStarContactGroup **cg)
{
  PetscBool same;

  PetscFunctionBegin;
  *cg = NULL;
  for (PetscInt g = 0; g < scene->nContact && !*cg; g++) {
    PetscCall(PetscStrcmp(group, scene->contact[g].name, &same));
    if (same) *cg = &scene->contact[g];
  }
  PetscCheck(*cg, scene->comm, PETSC_ERR_ARG_WRONG, "Option %s: \"%s\" is not a contact group (not in -contact)", option, group);
  PetscFunctionReturn(0);
}

static PetscErrorCode ReadGroupOption(SSStarScene scene, GroupOption kind, const char group[], const char option[])
{
  SSStarContactGroup *cg;
  SSStarGroupValues  *gv;
  PetscBool           set;
  PetscInt            nlaws;
  const char *const  *laws;
  char                name[64], known[256] = "";

  PetscFunctionBegin;
  switch (kind) {
  case OPT_MATERIAL:
  case OPT_TRACTION:
  case OPT_SPRING:
    gv = kind == OPT_MATERIAL ? &scene->materials[scene->nMaterials++] : kind == OPT_TRACTION ? &scene->tractions[scene->nTractions++] : &scene->springs[scene->nSprings++];
    PetscCall(PetscStrncpy(gv->name, group, sizeof(gv->name)));
    PetscCall(GetFiniteArray(scene->comm, option, kind == OPT_MATERIAL ? 2 : kind == OPT_TRACTION ? 3 : 1, kind == OPT_MATERIAL ? "E,nu" : kind == OPT_TRACTION ? "x,y,z" : "k", gv->value, &set));
    PetscCheck(kind != OPT_SPRING || gv->value[0] > 0, scene->comm, PETSC_ERR_ARG_OUTOFRANGE, "Option %s %g: the spring stiffness must be positive", option, (double)gv->value[0]);
    break;
  case OPT_OBSTACLE: {
    char spec[PETSC_MAX_PATH_LEN + 8] = "";

    PetscCall(ContactGroup(scene, group, option, &cg));
    PetscCall(PetscOptionsGetString(NULL, NULL, option, spec, sizeof(spec), &set));
    PetscCall(SSStarObstacleSetFromString(scene->comm, option, spec, &cg->obstacle)); /* obstacle.c */
  } break;
  case OPT_FRICTION_LAW:
    PetscCall(ContactGroup(scene, group, option, &cg));
    PetscCall(PetscOptionsGetString(NULL, NULL, option, name, sizeof(name), &set));
    PetscCall(SSStarLawGetIndex(name, &cg->law));
    PetscCall(SSStarLawGetNames(&nlaws, &laws));
    for (PetscInt l = 0; l < nlaws && cg->law < 0; l++) { /* the message names the laws of the table */
      PetscCall(PetscStrlcat(known, l ? ", " : "", sizeof(known)));
      PetscCall(PetscStrlcat(known, laws[l], sizeof(known)));
    }
    PetscCheck(cg->law >= 0, scene->comm, PETSC_ERR_ARG_UNKNOWN_TYPE, "Unknown option %s for %s: the friction laws are %s", name, option, known);
    cg->lawSet = PETSC_TRUE;
    break;
  case OPT_FRICTION:
    PetscCall(ContactGroup(scene, group, option, &cg));
    PetscCall(PetscOptionsGetReal(NULL, NULL, option, &cg->phi, &set));
    PetscCheck(cg->phi >= 0 && !PetscIsInfOrNanReal(cg->phi), scene->comm, PETSC_ERR_ARG_OUTOFRANGE, "Option %s %g: the friction coefficient must be a number >= 0", option, (double)cg->phi);
    cg->phiSet = PETSC_TRUE;
    break;
  case OPT_SLIP_BOUND:
    PetscCall(ContactGroup(scene, group, option, &cg));
    PetscCall(PetscOptionsGetReal(NULL, NULL, option, &cg->bound, &set));
    PetscCheck(cg->bound >= 0 && !PetscIsInfOrNanReal(cg->bound), scene->comm, PETSC_ERR_ARG_OUTOFRANGE, "Option %s %g: the slip bound must be a number >= 0 (a force per contact node)", option, (double)cg->bound);
    cg->boundSet = PETSC_TRUE;
    break;
  case OPT_CONTACT_PAIR:
    PetscCall(ContactGroup(scene, group, option, &cg));
    PetscCall(SSStarPairsReadOption(scene, cg, option));
    break;
  default:
    break;
  }
  PetscFunctionReturn(0);
}

/* Contradictory and incomplete entries of a contact group */
static PetscErrorCode CheckContactGroup(SSStarScene scene, const SSStarContactGroup *cg)
{
  const char *law;
  PetscBool   friction, bound;

  PetscFunctionBegin;
  PetscCall(SSStarLawGetInfo(cg->law, &law, NULL, NULL, NULL));
  PetscCall(SSStarLawHasParameter(cg->law, "friction", &friction));
  PetscCall(SSStarLawHasParameter(cg->law, "slip_bound", &bound));
  PetscCheck(!cg->phiSet || friction, scene->comm, PETSC_ERR_ARG_WRONG, "Options -friction_%s and -friction_law_%s %s contradict each other: a friction coefficient is for the coulomb law", cg->name, cg->name, law);
  PetscCheck(!cg->boundSet || bound, scene->comm, PETSC_ERR_ARG_WRONG, "Options -slip_bound_%s and -friction_law_%s %s contradict each other: a slip bound is for the tresca law", cg->name, cg->name, law);
  PetscCheck(cg->boundSet || !bound, scene->comm, PETSC_ERR_ARG_WRONG, "Option -friction_law_%s tresca needs -slip_bound_%s (the Tresca bound, a force per contact node)", cg->name, cg->name);
  PetscFunctionReturn(0);
}

/* A group listed by two options that exclude each other */
static PetscErrorCode CheckNotHeld(SSStarScene scene, const char group[], const char option[])
{
  PetscInt d;

  PetscFunctionBegin;
  PetscCall(FindName(group, scene->nDirichlet, scene->dirichlet, &d));
  PetscCheck(d < 0, scene->comm, PETSC_ERR_ARG_WRONG, "Options %s and -dirichlet contradict each other: the group \"%s\" is held fixed", option, group);
  PetscFunctionReturn(0);
}

/* The options -help lists for the groups (read below by name, so PetscOptions* does not list them itself) */
static const char SceneGroupHelp[] = "\
  -dirichlet <G1,G2,...>: groups held fixed (u = 0)\n\
  -material_<G> <E,nu>: material of volume group G\n\
  -traction_<G> <x,y,z>: constant traction on surface group G (global axes)\n\
  -spring_<G> <k>: soft elastic support of surface group G, k per unit area in every direction\n\
  -gravity <gx,gy,gz>: gravity, with -density (only when given)\n\
  -contact <G1,G2,...>: the contact groups (without -contact: no contact at all)\n\
  -obstacle_<G> <0,0,0,0,0,1>: the rigid obstacle of G: plane:px,py,pz,nx,ny,nz (or the six numbers: a point and\n\
      the normal into the body), sphere:cx,cy,cz,R (a ball touched from outside), cylinder:px,py,pz,ax,ay,az,R\n\
      (infinite, axis through p along a) or mesh:FILE.msh (a rigid body bounded by gmsh triangles, normals out of it)\n\
  -friction_law_<G> <coulomb>: none, tresca or coulomb\n\
  -friction_<G> <phi>: Coulomb coefficient of G (default: the solver's, -snes_ssstar_friction)\n\
  -slip_bound_<G> <s>: Tresca slip bound of G, a force per contact node\n\
  -contact_pair_<G> <H>: contact group G (slave) meets surface group H (master) of another body\n\
  -pair_discretization <node_to_surface>: of every pair: node_to_surface or dual_mortar (Wohlmuth's dual multipliers)\n";

/* The options the scene reads (for SSStarSceneCheckOptionsUsed(): -mesh ... by PetscOptions*, the groups' by name) */
static const char SceneOptionNames[] = "-mesh -geo -level -mesh_scale -E -nu -density";

/*@C
   SSStarSceneCheckOptionsUsed - refuses, before any work, an option that neither the program, nor the scene, nor its
   solver has read (SSStarCheckOptionsUsed()), naming the nearest option among the program's (its help text), the
   scene's and the solver's

   Collective

   Input Parameters:
+  scene - the scene, after SSStarSceneSetFromOptions()
.  help  - the program's help text (its options as "-name"), or NULL
-  snes  - the program's SNES after SNESSetFromOptions(), or NULL

   Level: intermediate

.seealso: `SSStarCheckOptionsUsed()`, `SSStarSceneSetFromOptions()`
@*/
PetscErrorCode SSStarSceneCheckOptionsUsed(SSStarScene scene, const char help[], SNES snes)
{
  const char *known[4] = {help ? help : "", SceneOptionNames, SceneGroupHelp, NULL};

  PetscFunctionBegin;
  PetscCall(SSStarCheckOptionsUsed(scene->comm, known, snes));
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneSetFromOptions - reads the scene from the options database (README "Scenes"), with errors that name the
   option for unknown, contradictory or incomplete entries

   Collective

   Input Parameter:
.  scene - the scene

   Options Database Keys:
+  -mesh <file.msh> - the body, a gmsh mesh
.  -geo <file.geo> - or a geometry meshed at -level
.  -level <L> - the level of -geo
.  -mesh_scale <1> - multiply the coordinates by this
.  -E <E> - Young's modulus of the cells without -material_<G>
.  -nu <nu> - Poisson's ratio of those cells
.  -material_<G> <E,nu> - the material of volume group G
.  -dirichlet <G1,G2> - groups held fixed
.  -traction_<G> <x,y,z> - traction on surface group G
.  -spring_<G> <k> - soft support of surface group G
.  -gravity <gx,gy,gz> - gravity, with -density
.  -density <rho> - the mass density
.  -contact <G1,G2> - the contact groups
.  -obstacle_<G> <px,py,pz,nx,ny,nz> - the rigid obstacle of G: plane:px,py,pz,nx,ny,nz (or the six numbers), sphere:cx,cy,cz,R, cylinder:px,py,pz,ax,ay,az,R or mesh:FILE.msh
.  -friction_law_<G> <coulomb> - none, tresca or coulomb
.  -friction_<G> <phi> - the Coulomb coefficient of G
-  -slip_bound_<G> <s> - the Tresca bound of G

   Level: beginner

.seealso: `SSStarSceneCreate()`, `SSStarSceneSetUp()`, `SSStarSceneView()`
@*/
PetscErrorCode SSStarSceneSetFromOptions(SSStarScene scene)
{
  MPI_Comm  comm = scene->comm;
  PetscBool hasMesh, hasGeo, hasLevel, hasDensity;
  char    **contact;
  char      option[SSSTAR_GROUP_NAME_LEN + 16];

  PetscFunctionBegin;
  PetscOptionsBegin(comm, NULL, "Scene: the body, its loads and its contact groups", "ssstar");
  PetscCall(PetscOptionsString("-mesh", "gmsh mesh file", NULL, scene->mesh, scene->mesh, sizeof(scene->mesh), &hasMesh));
  PetscCall(PetscOptionsString("-geo", "gmsh geometry meshed at -level", NULL, scene->geo, scene->geo, sizeof(scene->geo), &hasGeo));
  PetscCall(PetscOptionsInt("-level", "Mesh level of -geo (the number L of the .geo)", NULL, scene->level, &scene->level, &hasLevel));
  PetscCall(PetscOptionsReal("-mesh_scale", "Multiply the mesh coordinates by this", NULL, scene->meshScale, &scene->meshScale, NULL));
  PetscCall(PetscOptionsReal("-E", "Young's modulus of the cells without -material_<G>", NULL, scene->E, &scene->E, &scene->hasE));
  PetscCall(PetscOptionsReal("-nu", "Poisson ratio of the cells without -material_<G>", NULL, scene->nu, &scene->nu, &scene->hasNu));
  PetscCall(PetscOptionsReal("-density", "Mass density (with -gravity)", NULL, scene->density, &scene->density, &hasDensity));
  if (PetscOptionsObject->printhelp && PetscOptionsObject->count == 1) PetscCall((*PetscHelpPrintf)(comm, "%s", SceneGroupHelp));
  PetscOptionsEnd();
  PetscCheck(!(hasMesh && hasGeo), comm, PETSC_ERR_ARG_WRONG, "Options -mesh and -geo contradict each other: give one body");
  PetscCheck(hasMesh || hasGeo, comm, PETSC_ERR_ARG_WRONG, "No body: give -mesh file.msh, or -geo file.geo with -level L");
  PetscCheck(!(hasMesh && hasLevel), comm, PETSC_ERR_ARG_WRONG, "Options -mesh and -level contradict each other: -level is for -geo");
  PetscCheck(!hasGeo || hasLevel, comm, PETSC_ERR_ARG_WRONG, "Option -geo %s needs -level L", scene->geo);
  PetscCheck(!hasGeo || scene->level >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "-level %" PetscInt_FMT ": the mesh level must be >= 1", scene->level);
  PetscCheck(!scene->hasE || (scene->E > 0 && !PetscIsInfOrNanReal(scene->E)), comm, PETSC_ERR_ARG_OUTOFRANGE, "-E %g: Young's modulus must be a positive number", (double)scene->E);
  PetscCheck(!scene->hasNu || (scene->nu > -1 && scene->nu < 0.5), comm, PETSC_ERR_ARG_OUTOFRANGE, "-nu %g: Poisson's ratio must be in (-1, 0.5)", (double)scene->nu);

  PetscCall(GetFiniteArray(comm, "-gravity", 3, "gx,gy,gz", scene->gravity, &scene->hasGravity));
  PetscCheck(scene->hasGravity == hasDensity, comm, PETSC_ERR_ARG_WRONG, "Incomplete body force: %s needs %s", scene->hasGravity ? "-gravity" : "-density", scene->hasGravity ? "-density" : "-gravity");
  PetscCheck(!hasDensity || (scene->density >= 0 && !PetscIsInfOrNanReal(scene->density)), comm, PETSC_ERR_ARG_OUTOFRANGE, "-density %g: the density must be a number >= 0", (double)scene->density);

  PetscCall(GetGroupList(comm, "-dirichlet", &scene->nDirichlet, &scene->dirichlet));
  PetscCall(GetGroupList(comm, "-contact", &scene->nContact, &contact));
  PetscCall(PetscCalloc1(scene->nContact, &scene->contact));
  for (PetscInt g = 0; g < scene->nContact; g++) {
    SSStarContactGroup *cg = &scene->contact[g];

    PetscCall(PetscStrncpy(cg->name, contact[g], sizeof(cg->name)));
    PetscCall(PetscFree(contact[g]));
    PetscCall(SSStarObstacleReset(&cg->obstacle)); /* the default: the plane z = 0 */
    PetscCall(SSStarLawGetIndex(SSSTARLAWCOULOMB, &cg->law));
    PetscCall(CheckNotHeld(scene, cg->name, "-contact"));
  }
  PetscCall(PetscFree(contact));

  /* the options -<prefix><G>: count, then read */
  scene->nMaterials = scene->nTractions = scene->nSprings = 0;
  PetscCall(ForEachGroupOption(scene, CountGroupOption));
  PetscCall(PetscFree3(scene->materials, scene->tractions, scene->springs));
  PetscCall(PetscCalloc3(scene->nMaterials, &scene->materials, scene->nTractions, &scene->tractions, scene->nSprings, &scene->springs));
  scene->nMaterials = scene->nTractions = scene->nSprings = scene->nPairs = 0;
  PetscCall(ForEachGroupOption(scene, ReadGroupOption));
  PetscCall(SSStarPairsCheckOptions(scene));
  for (PetscInt t = 0; t < scene->nTractions; t++) {
    PetscCall(PetscSNPrintf(option, sizeof(option), "-traction_%s", scene->tractions[t].name));
    PetscCall(CheckNotHeld(scene, scene->tractions[t].name, option));
  }
  for (PetscInt g = 0; g < scene->nContact; g++) PetscCall(CheckContactGroup(scene, &scene->contact[g]));
  PetscFunctionReturn(0);
}

/* Every group an option names, with the kind of group the option needs */
static PetscErrorCode GroupUses(SSStarScene scene, PetscInt *n, SSStarGroupUse **uses, char ***options)
{
  PetscInt total = scene->nDirichlet + scene->nContact + scene->nMaterials + scene->nTractions + scene->nSprings + scene->nPairs, k = 0;

  PetscFunctionBegin;
  PetscCall(PetscMalloc1(total, uses));
  PetscCall(PetscCalloc1(total, options));
  for (PetscInt g = 0; g < scene->nDirichlet; g++, k++) {
    (*uses)[k].group = scene->dirichlet[g];
    (*uses)[k].kind  = SSSTAR_GROUP_ANY;
    PetscCall(PetscStrallocpy("-dirichlet", &(*options)[k]));
  }
  for (PetscInt g = 0; g < scene->nContact; g++, k++) {
    (*uses)[k].group = scene->contact[g].name;
    (*uses)[k].kind  = SSSTAR_GROUP_SURFACE;
    PetscCall(PetscStrallocpy("-contact", &(*options)[k]));
  }
  for (PetscInt g = 0; g < scene->nContact; g++) {
    char option[SSSTAR_GROUP_NAME_LEN + 16];

    if (!scene->contact[g].master[0]) continue;
    (*uses)[k].group = scene->contact[g].master;
    (*uses)[k].kind  = SSSTAR_GROUP_SURFACE;
    PetscCall(PetscSNPrintf(option, sizeof(option), "-contact_pair_%s", scene->contact[g].name));
    PetscCall(PetscStrallocpy(option, &(*options)[k++]));
  }
  {
    const SSStarGroupValues *lists[3] = {scene->materials, scene->tractions, scene->springs};
    const PetscInt           sizes[3] = {scene->nMaterials, scene->nTractions, scene->nSprings};
    const char              *names[3] = {"-material_", "-traction_", "-spring_"};

    for (PetscInt l = 0; l < 3; l++)
      for (PetscInt g = 0; g < sizes[l]; g++, k++) {
        char option[SSSTAR_GROUP_NAME_LEN + 16];

        (*uses)[k].group = lists[l][g].name;
        (*uses)[k].kind  = l == 0 ? SSSTAR_GROUP_VOLUME : SSSTAR_GROUP_SURFACE;
        PetscCall(PetscSNPrintf(option, sizeof(option), "%s%s", names[l], lists[l][g].name));
        PetscCall(PetscStrallocpy(option, &(*options)[k]));
      }
  }
  for (PetscInt i = 0; i < total; i++) (*uses)[i].option = (*options)[i];
  *n = total;
  PetscFunctionReturn(0);
}

/* The mesh file of -geo at -level: meshes/prism.geo at level 6 -> meshes/prism_L6.msh */
static PetscErrorCode MeshFileOfLevel(SSStarScene scene)
{
  size_t len;

  PetscFunctionBegin;
  PetscCall(PetscStrlen(scene->geo, &len));
  PetscCheck(len > 4 && !strcmp(scene->geo + len - 4, ".geo"), scene->comm, PETSC_ERR_ARG_WRONG, "-geo %s: expected a .geo file", scene->geo);
  PetscCall(PetscSNPrintf(scene->mesh, sizeof(scene->mesh), "%.*s_L%" PetscInt_FMT ".msh", (int)(len - 4), scene->geo, scene->level));
  PetscFunctionReturn(0);
}

/* Tributary area of every local vertex on the contact groups (a third of each adjacent face), in the x-dofs of a global vector */
static PetscErrorCode ContactAreas(SSStarScene scene, Vec *areas)
{
  const PetscReal unit[3] = {1, 0, 0};
  Vec             loc;

  PetscFunctionBegin;
  PetscCall(DMGetLocalVector(scene->dm, &loc));
  PetscCall(VecZeroEntries(loc));
  for (PetscInt g = 0; g < scene->nContact; g++) PetscCall(SSStarAddTraction(scene->dm, scene->contact[g].name, unit, loc));
  PetscCall(DMCreateGlobalVector(scene->dm, areas));
  PetscCall(VecZeroEntries(*areas));
  PetscCall(DMLocalToGlobal(scene->dm, loc, ADD_VALUES, *areas));
  PetscCall(DMRestoreLocalVector(scene->dm, &loc));
  PetscFunctionReturn(0);
}

/* Whether the obstacles of two contact groups give the node at x the same gap and normal */
static PetscErrorCode SameObstacleAt(const SSStarContactGroup *a, const SSStarContactGroup *b, const PetscReal x[3], PetscReal tol, PetscBool *same)
{
  PetscReal ga, gb, na[3], nb[3];

  PetscFunctionBegin;
  PetscCall(SSStarObstacleGap(&a->obstacle, x, tol, &ga, na));
  PetscCall(SSStarObstacleGap(&b->obstacle, x, tol, &gb, nb));
  *same = (PetscBool)(PetscAbsReal(na[0] - nb[0]) + PetscAbsReal(na[1] - nb[1]) + PetscAbsReal(na[2] - nb[2]) <= 1e-12 && PetscAbsReal(ga - gb) <= tol);
  PetscFunctionReturn(0);
}

/* A node an error is about: the owner's data reach every rank (the lowest file index wins) */
typedef struct {
  PetscInt  tag, group, other;
  PetscReal x[3], gap;
} BadNode;

static PetscErrorCode ShareBadNode(MPI_Comm comm, BadNode *bad, PetscBool *found)
{
  PetscInt  tag = bad->tag >= 0 ? bad->tag : PETSC_MAX_INT, first;
  PetscReal data[7];

  PetscFunctionBegin;
  PetscCall(MPIU_Allreduce(&tag, &first, 1, MPIU_INT, MPI_MIN, comm));
  *found = (PetscBool)(first != PETSC_MAX_INT);
  if (!*found) PetscFunctionReturn(0);
  for (PetscInt k = 0; k < 7; k++) data[k] = 0;
  if (tag == first) {
    data[0] = (PetscReal)bad->group;
    data[1] = (PetscReal)bad->other;
    data[2] = bad->x[0];
    data[3] = bad->x[1];
    data[4] = bad->x[2];
    data[5] = bad->gap;
    data[6] = 1;
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, data, 7, MPIU_REAL, MPIU_SUM, comm));
  bad->tag   = first;
  bad->group = (PetscInt)(data[0] / data[6]);
  bad->other = (PetscInt)(data[1] / data[6]);
  for (PetscInt k = 0; k < 3; k++) bad->x[k] = data[2 + k] / data[6];
  bad->gap = data[5] / data[6];
  PetscFunctionReturn(0);
}

/*
   The owned contact nodes: vertices of the contact groups that are not held fixed, each with the obstacle of its group
   (the first listed in -contact when it is in two groups whose obstacles agree at the node), its normal and initial
   gap there (SSStarObstacleGap, obstacle.c) and its tributary area.
*/
static PetscErrorCode CreateContactNodes(SSStarScene scene)
{
  DM                 dm = scene->dm, cdm;
  DMLabel           *labels;
  PetscSection       sec, gsec, csec;
  PetscInt           vStart, vEnd, n = 0, *dofs, rstart;
  Vec                coordinates, areas;
  const PetscScalar *ta, *xa, *aa;
  PetscReal          gmin[3], gmax[3], tol;
  BadNode            inside = {-1, -1, -1, {0, 0, 0}, 0}, twice = {-1, -1, -1, {0, 0, 0}, 0};
  PetscBool          found;

  PetscFunctionBegin;
  PetscCall(DMGetBoundingBox(dm, gmin, gmax));
  /* "inside the obstacle by more than round-off": relative to the size of the body and the distance to the obstacles */
  tol = 0;
  for (PetscInt k = 0; k < 3; k++) tol += PetscSqr(gmax[k] - gmin[k]);
  tol = 1e-10 * PetscSqrtReal(tol);
  PetscCall(ContactAreas(scene, &areas));
  PetscCall(PetscMalloc1(scene->nContact, &labels));
  for (PetscInt g = 0; g < scene->nContact; g++) PetscCall(DMGetLabel(dm, scene->contact[g].name, &labels[g]));
  PetscCall(DMGetLocalSection(dm, &sec));
  PetscCall(DMGetGlobalSection(dm, &gsec));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(DMGetCoordinatesLocal(dm, &coordinates));
  PetscCall(DMGetCoordinateDM(dm, &cdm));
  PetscCall(DMGetLocalSection(cdm, &csec));
  PetscCall(PetscMalloc4(vEnd - vStart, &scene->tag, vEnd - vStart, &scene->group, 3 * (vEnd - vStart), &scene->coords, 3 * (vEnd - vStart), &scene->normal));
  PetscCall(PetscMalloc2(vEnd - vStart, &scene->gap, vEnd - vStart, &scene->area));
  PetscCall(PetscMalloc1(3 * (vEnd - vStart), &dofs));
  PetscCall(VecGetArrayRead(scene->tags, &ta));
  PetscCall(VecGetArrayRead(coordinates, &xa));
  PetscCall(VecGetArrayRead(areas, &aa));
  PetscCall(VecGetOwnershipRange(areas, &rstart, NULL));
  for (PetscInt g = 0; g < scene->nContact; g++) scene->contact[g].nodes = 0;
  /* vertices in point order have increasing global offsets, so the dofs are sorted */
  for (PetscInt v = vStart; v < vEnd; v++) {
    PetscInt  off, ncon, coff, group = -1;
    PetscReal x[3], normal[3];
    PetscBool same;

    PetscCall(PetscSectionGetOffset(gsec, v, &off));
    PetscCall(PetscSectionGetConstraintDof(sec, v, &ncon));
    if (off < 0 || ncon) continue; /* not owned, or held fixed */
    PetscCall(PetscSectionGetOffset(csec, v, &coff));
    for (PetscInt k = 0; k < 3; k++) x[k] = PetscRealPart(xa[coff + k]);
    for (PetscInt g = 0; g < scene->nContact; g++) {
      PetscInt value;

      PetscCall(DMLabelGetValue(labels[g], v, &value));
      if (value < 0) continue;
      if (group < 0) {
        group = g;
        continue;
      }
      PetscCall(SameObstacleAt(&scene->contact[group], &scene->contact[g], x, tol, &same));
      if (!same && twice.tag < 0) {
        twice.tag   = (PetscInt)PetscRealPart(ta[v - vStart]);
        twice.group = group;
        twice.other = g;
        PetscCall(PetscArraycpy(twice.x, x, 3));
      }
    }
    if (group < 0) continue;
    scene->tag[n]   = (PetscInt)PetscRealPart(ta[v - vStart]);
    scene->group[n] = group;
    if (scene->contact[group].master[0]) { /* a pair's gap and normal: SSStarPairsSetUp() */
      scene->gap[n] = 0.0;
      normal[0] = normal[1] = 0.0;
      normal[2] = 1.0;
    } else PetscCall(SSStarObstacleGap(&scene->contact[group].obstacle, x, tol, &scene->gap[n], normal));
    scene->area[n]  = PetscRealPart(aa[off - rstart]); /* in the x-dof */
    if (scene->gap[n] < -tol && inside.tag < 0) {
      inside.tag   = scene->tag[n];
      inside.group = group;
      inside.gap   = scene->gap[n];
      PetscCall(PetscArraycpy(inside.x, x, 3));
    }
    if (PetscAbsReal(scene->gap[n]) <= tol) scene->gap[n] = 0.0; /* on the obstacle up to round-off: touching */
    for (PetscInt k = 0; k < 3; k++) {
      scene->coords[3 * n + k] = x[k];
      scene->normal[3 * n + k] = normal[k];
      dofs[3 * n + k]          = off + k;
    }
    scene->contact[group].nodes++;
    n++;
  }
  PetscCall(VecRestoreArrayRead(areas, &aa));
  PetscCall(VecRestoreArrayRead(coordinates, &xa));
  PetscCall(VecRestoreArrayRead(scene->tags, &ta));
  PetscCall(VecDestroy(&areas));
  PetscCall(PetscFree(labels));
  scene->n = n;
  PetscCall(ISCreateGeneral(scene->comm, 3 * n, dofs, PETSC_OWN_POINTER, &scene->isC));

  PetscCall(ShareBadNode(scene->comm, &twice, &found));
  PetscCheck(!found, scene->comm, PETSC_ERR_ARG_WRONG, "Mesh node %" PetscInt_FMT " (0-based, file order) at (%g, %g, %g) is in the contact groups \"%s\" and \"%s\" whose obstacles (-obstacle_%s, -obstacle_%s) differ at this node: a node touches one obstacle", twice.tag, (double)twice.x[0], (double)twice.x[1], (double)twice.x[2], scene->contact[twice.group].name, scene->contact[twice.other].name, scene->contact[twice.group].name, scene->contact[twice.other].name);
  PetscCall(ShareBadNode(scene->comm, &inside, &found));
  PetscCheck(!found, scene->comm, PETSC_ERR_ARG_OUTOFRANGE, "Mesh node %" PetscInt_FMT " (0-based, file order) of contact group \"%s\" at (%g, %g, %g) starts %g inside the obstacle of -obstacle_%s (%s)", inside.tag, scene->contact[inside.group].name, (double)inside.x[0], (double)inside.x[1], (double)inside.x[2], (double)-inside.gap, scene->contact[inside.group].name, SSStarObstacleInsideHint(&scene->contact[inside.group].obstacle));
  for (PetscInt g = 0; g < scene->nContact; g++) {
    SSStarContactGroup *cg = &scene->contact[g];
    PetscReal           range[2] = {PETSC_MAX_REAL, PETSC_MAX_REAL};

    for (PetscInt i = 0; i < n; i++)
      if (scene->group[i] == g) {
        range[0] = PetscMin(range[0], scene->gap[i]);
        range[1] = PetscMin(range[1], -scene->gap[i]);
      }
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, range, 2, MPIU_REAL, MPIU_MIN, scene->comm));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &cg->nodes, 1, MPIU_INT, MPI_SUM, scene->comm));
    cg->gapMin = range[0];
    cg->gapMax = -range[1];
    PetscCheck(cg->nodes > 0, scene->comm, PETSC_ERR_ARG_WRONG, "Contact group \"%s\" (option -contact) has no nodes once the nodes held fixed (-dirichlet) are removed", cg->name);
  }
  PetscCall(MPIU_Allreduce(&n, &scene->nGlobal, 1, MPIU_INT, MPI_SUM, scene->comm));
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneSetUp - builds the scene: meshes -geo at -level (or reads -mesh), checks the groups the options name,
   distributes the mesh, sets the dofs (u = 0 on the -dirichlet groups), finds the bodies (connected parts of the
   mesh; one that no -dirichlet or -spring_<G> group holds is refused, named by its volume groups), the contact nodes
   and the contact pairs' operator (-contact_pair_<G>)

   Collective

   Input Parameter:
.  scene - the scene, after SSStarSceneSetFromOptions()

   Notes:
   Refuses, before each costly step, a problem too large for the machine's memory (SSStarCheckMemory()).

   Level: beginner

.seealso: `SSStarSceneSetFromOptions()`, `SSStarSceneAssemble()`, `SSStarSceneSetContact()`
@*/
PetscErrorCode SSStarSceneSetUp(SSStarScene scene)
{
  SSStarGroupUse *uses;
  char          **options;
  PetscInt        nuses = 0, cells;
  Vec             coordinates;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(SSSTAR_Mesh, 0, 0, 0, 0));
  if (scene->geo[0]) {
    PetscCall(MeshFileOfLevel(scene));
    PetscCall(SSStarMeshGenerate(scene->comm, scene->geo, scene->level, scene->mesh));
  }
  PetscCall(SSStarMeshFileNodes(scene->comm, scene->mesh, &scene->nodesGlobal));
  PetscCall(SSStarCheckMemory(scene->comm, (PetscReal)scene->nodesGlobal, scene->mesh));
  PetscCall(GroupUses(scene, &nuses, &uses, &options));
  PetscCall(SSStarMeshLoad(scene->comm, scene->mesh, nuses, uses, &scene->dm, &scene->tags));
  for (PetscInt k = 0; k < nuses; k++) PetscCall(PetscFree(options[k]));
  PetscCall(PetscFree(options));
  PetscCall(PetscFree(uses));
  PetscCall(SSStarMeshScale(scene->dm, scene->meshScale));
  PetscCall(SSStarMeshCreateSection(scene->dm, scene->nDirichlet, scene->dirichlet));
  PetscCall(DMGetCoordinates(scene->dm, &coordinates));
  PetscCall(VecGetSize(coordinates, &scene->nodesGlobal));
  scene->nodesGlobal /= 3;
  {
    PetscInt cStart, cEnd;

    PetscCall(DMPlexGetHeightStratum(scene->dm, 0, &cStart, &cEnd));
    cells = cEnd - cStart;
    PetscCall(MPIU_Allreduce(&cells, &scene->cellsGlobal, 1, MPIU_INT, MPI_SUM, scene->comm));
  }
  PetscCall(SSStarSceneFindBodies(scene));
  PetscCall(CreateContactNodes(scene));
  PetscCall(SSStarPairsSetUp(scene));
  PetscCall(PetscLogEventEnd(SSSTAR_Mesh, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneGetDM - the distributed mesh of the scene, with its displacement section

   Not Collective

   Input Parameter:
.  scene - the scene, after SSStarSceneSetUp()

   Output Parameter:
.  dm - the DMPlex (owned by the scene); DMCreateGlobalVector() gives the displacement vectors

   Level: beginner

.seealso: `SSStarSceneSetUp()`, `SSStarSceneAssemble()`
@*/
PetscErrorCode SSStarSceneGetDM(SSStarScene scene, DM *dm)
{
  PetscFunctionBegin;
  *dm = scene->dm;
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneGetSizes - the number of mesh nodes and of contact nodes (global)

   Not Collective

   Input Parameter:
.  scene - the scene, after SSStarSceneSetUp()

   Output Parameters:
+  nodes   - the mesh nodes, or pass NULL
-  contact - the contact nodes, or pass NULL

   Level: beginner

.seealso: `SSStarSceneGetContactNodes()`
@*/
PetscErrorCode SSStarSceneGetSizes(SSStarScene scene, PetscInt *nodes, PetscInt *contact)
{
  PetscFunctionBegin;
  if (nodes) *nodes = scene->nodesGlobal;
  if (contact) *contact = scene->nGlobal;
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneAssemble - the stiffness K (SPD, with the springs) and the load b (tractions, gravity) of the scene

   Collective

   Input Parameter:
.  scene - the scene, after SSStarSceneSetUp()

   Output Parameters:
+  K - the stiffness (the caller destroys it); the rigid-body modes are its near-null space
-  b - the load (the caller destroys it)

   Level: beginner

.seealso: `SSStarSceneSetContact()`, `SSStarSceneGetDM()`
@*/
PetscErrorCode SSStarSceneAssemble(SSStarScene scene, Mat *K, Vec *b)
{
  PetscFunctionBegin;
  PetscCall(SSStarAssembleElasticity(scene, K, b));
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneHasContact - whether the scene names contact groups (-contact); without, one linear solve is all there is
   to do

   Not Collective

   Input Parameter:
.  scene - the scene

   Output Parameter:
.  has - PETSC_TRUE with contact groups

   Level: beginner

.seealso: `SSStarSceneSetContact()`
@*/
PetscErrorCode SSStarSceneHasContact(SSStarScene scene, PetscBool *has)
{
  PetscFunctionBegin;
  *has = (PetscBool)(scene->nContact > 0);
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneGetContactDofs - the global x, y, z dofs of the owned contact nodes

   Not Collective

   Input Parameter:
.  scene - the scene, after SSStarSceneSetUp()

   Output Parameter:
.  dofs - 3 per node, in the order of the states SNESSSStarGetStates() returns for this scene (owned by the scene)

   Level: intermediate

.seealso: `SSStarSceneGetContactNodes()`, `SSStarSceneSetContact()`
@*/
PetscErrorCode SSStarSceneGetContactDofs(SSStarScene scene, IS *dofs)
{
  PetscFunctionBegin;
  *dofs = scene->isC;
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneGetContactNodes - the owned contact nodes, in the order of SSStarSceneGetContactDofs()

   Not Collective

   Input Parameter:
.  scene - the scene, after SSStarSceneSetUp()

   Output Parameters:
+  n       - their number, or pass NULL
.  coords  - their coordinates, 3 per node, or pass NULL
.  normals - the normals of their obstacles at them (out of the obstacle, into the body), 3 per node, or pass NULL
.  gaps    - their initial gaps, 1 per node, or pass NULL
-  areas   - their tributary areas (a third of their adjacent contact faces), 1 per node, or pass NULL

   Notes:
   The arrays belong to the scene.

   Level: intermediate

.seealso: `SSStarSceneGetContactDofs()`, `SSStarSceneGetContactResult()`
@*/
PetscErrorCode SSStarSceneGetContactNodes(SSStarScene scene, PetscInt *n, const PetscReal *coords[], const PetscReal *normals[], const PetscReal *gaps[], const PetscReal *areas[])
{
  PetscFunctionBegin;
  if (n) *n = scene->n;
  if (coords) *coords = scene->coords;
  if (normals) *normals = scene->normal;
  if (gaps) *gaps = scene->gap;
  if (areas) *areas = scene->area;
  PetscFunctionReturn(0);
}

/* A per-node Vec of the owned contact nodes */
static PetscErrorCode NodeVec(SSStarScene scene, PetscInt bs, const PetscReal values[], Vec *v)
{
  PetscScalar *a;

  PetscFunctionBegin;
  PetscCall(VecCreateMPI(scene->comm, bs * scene->n, PETSC_DETERMINE, v));
  PetscCall(VecGetArrayWrite(*v, &a));
  for (PetscInt i = 0; i < bs * scene->n; i++) a[i] = values[i];
  PetscCall(VecRestoreArrayWrite(*v, &a));
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneSetContact - declares the contact nodes of the scene to an "ssstar" SNES: their dofs, the normals of
   their obstacles at them, their initial gaps, and the friction laws of their groups; with contact pairs
   (-contact_pair_<G>), the contact operator B of every contact node instead (SNESSSStarSetContactOperator(): a pair's
   slave node against the master surface, node-to-surface or dual mortar, -pair_discretization)

   Collective

   Input Parameters:
+  scene - the scene, after SSStarSceneSetUp(), with contact groups
-  snes  - an SNES of type ssstar

   Notes:
   A group's -friction_<G> gives its nodes their own coefficient; the nodes of Coulomb groups without one keep the
   solver's (SNESSSStarSetFriction(), -snes_ssstar_friction), whether it is set before or after this call (their
   entries are PETSC_DEFAULT in SNESSSStarSetNodeLawParameter()). One law for all groups is set with
   SNESSSStarSetFrictionLaw(), several with SNESSSStarSetNodeFrictionLaws().

   Level: beginner

.seealso: `SNESSSStarSetContactNodes()`, `SSStarSceneWriteSolution()`
@*/
PetscErrorCode SSStarSceneSetContact(SSStarScene scene, SNES snes)
{
  Vec         normals, gaps = NULL, v;
  PetscBool   anyGap = PETSC_FALSE, anyPhi = PETSC_FALSE, anyBound = PETSC_FALSE, anyLaw = PETSC_FALSE, oneLaw = PETSC_TRUE, bound;
  PetscReal  *values;
  const char *law;

  PetscFunctionBegin;
  PetscCheck(scene->nContact > 0, scene->comm, PETSC_ERR_ARG_WRONGSTATE, "The scene has no contact group (-contact): solve K u = b without ssstar");
  for (PetscInt i = 0; i < scene->n; i++)
    if (scene->gap[i] != 0) anyGap = PETSC_TRUE;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &anyGap, 1, MPIU_BOOL, MPI_LOR, scene->comm));
  for (PetscInt g = 0; g < scene->nContact; g++) {
    anyPhi   = (PetscBool)(anyPhi || scene->contact[g].phiSet);
    PetscCall(SSStarLawHasParameter(scene->contact[g].law, "slip_bound", &bound));
    anyBound = (PetscBool)(anyBound || bound);
    anyLaw   = (PetscBool)(anyLaw || scene->contact[g].lawSet);
    oneLaw   = (PetscBool)(oneLaw && scene->contact[g].law == scene->contact[0].law);
  }
  PetscCall(NodeVec(scene, 3, scene->normal, &normals));
  if (anyGap) PetscCall(NodeVec(scene, 1, scene->gap, &gaps));
  if (scene->B) PetscCall(SNESSSStarSetContactOperator(snes, scene->isC, scene->B, gaps)); /* contact pairs */
  else PetscCall(SNESSSStarSetContactNodes(snes, scene->isC, normals, gaps));
  PetscCall(VecDestroy(&normals));
  PetscCall(VecDestroy(&gaps));

  PetscCall(SSStarLawGetInfo(scene->contact[0].law, &law, NULL, NULL, NULL));
  if (anyLaw && oneLaw) PetscCall(SNESSSStarSetFrictionLaw(snes, law));
  else if (!oneLaw) {
    PetscInt *laws;

    PetscCall(PetscMalloc1(scene->n, &laws));
    for (PetscInt i = 0; i < scene->n; i++) laws[i] = scene->contact[scene->group[i]].law;
    PetscCall(SNESSSStarSetNodeFrictionLaws(snes, scene->n, laws));
    PetscCall(PetscFree(laws));
  }
  PetscCall(PetscMalloc1(scene->n, &values));
  if (anyPhi) { /* the groups without -friction_<G> keep the solver's coefficient, whenever it is set */
    for (PetscInt i = 0; i < scene->n; i++) values[i] = scene->contact[scene->group[i]].phiSet ? scene->contact[scene->group[i]].phi : (PetscReal)PETSC_DEFAULT;
    PetscCall(NodeVec(scene, 1, values, &v));
    PetscCall(SNESSSStarSetNodeLawParameter(snes, "friction", v));
    PetscCall(VecDestroy(&v));
  }
  if (anyBound) {
    for (PetscInt i = 0; i < scene->n; i++) values[i] = scene->contact[scene->group[i]].boundSet ? scene->contact[scene->group[i]].bound : 0.0;
    PetscCall(NodeVec(scene, 1, values, &v));
    PetscCall(SNESSSStarSetNodeLawParameter(snes, "slip_bound", v));
    PetscCall(VecDestroy(&v));
  }
  PetscCall(PetscFree(values));
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneView - what the scene simulates: the body, its material, supports and loads, its contact groups, and
   the line "active effects"

   Collective

   Input Parameters:
+  scene  - the scene
-  viewer - an ASCII viewer

   Level: beginner

.seealso: `SSStarSceneContactView()`, `SSStarSceneSetFromOptions()`
@*/
PetscErrorCode SSStarSceneView(SSStarScene scene, PetscViewer viewer)
{
  char effects[512] = "elasticity";

  PetscFunctionBegin;
  PetscCall(PetscViewerASCIIPrintf(viewer, "Scene: mesh %s, %" PetscInt_FMT " nodes, %" PetscInt_FMT " tetrahedra\n", scene->mesh, scene->nodesGlobal, scene->cellsGlobal));
  PetscCall(PetscViewerASCIIPushTab(viewer));
  if (scene->hasE && scene->hasNu) PetscCall(PetscViewerASCIIPrintf(viewer, "material: E = %g, nu = %g\n", (double)scene->E, (double)scene->nu));
  for (PetscInt m = 0; m < scene->nMaterials; m++) PetscCall(PetscViewerASCIIPrintf(viewer, "material of %s: E = %g, nu = %g\n", scene->materials[m].name, (double)scene->materials[m].value[0], (double)scene->materials[m].value[1]));
  for (PetscInt g = 0; g < scene->nDirichlet; g++) PetscCall(PetscViewerASCIIPrintf(viewer, "held fixed: %s\n", scene->dirichlet[g]));
  for (PetscInt s = 0; s < scene->nSprings; s++) PetscCall(PetscViewerASCIIPrintf(viewer, "spring on %s: k = %g per unit area, every direction\n", scene->springs[s].name, (double)scene->springs[s].value[0]));
  for (PetscInt t = 0; t < scene->nTractions; t++) PetscCall(PetscViewerASCIIPrintf(viewer, "traction on %s: (%g, %g, %g)\n", scene->tractions[t].name, (double)scene->tractions[t].value[0], (double)scene->tractions[t].value[1], (double)scene->tractions[t].value[2]));
  if (scene->hasGravity) PetscCall(PetscViewerASCIIPrintf(viewer, "gravity: (%g, %g, %g), density %g\n", (double)scene->gravity[0], (double)scene->gravity[1], (double)scene->gravity[2], (double)scene->density));
  for (PetscInt g = 0; g < scene->nContact; g++) {
    const SSStarContactGroup *cg = &scene->contact[g];
    char                      obstacle[PETSC_MAX_PATH_LEN + 128];
    const char               *law;
    PetscBool                 friction, bound;

    PetscCall(SSStarLawGetInfo(cg->law, &law, NULL, NULL, NULL));
    PetscCall(SSStarLawHasParameter(cg->law, "friction", &friction));
    PetscCall(SSStarLawHasParameter(cg->law, "slip_bound", &bound));
    if (cg->master[0]) PetscCall(PetscViewerASCIIPrintf(viewer, "contact pair %s -> %s: %" PetscInt_FMT " slave nodes of %s against the master surface %s of another body (%s), initial gaps %g .. %g, friction %s", cg->name, cg->master, cg->nodes, cg->name, cg->master, scene->pairMethod == SSSTAR_PAIR_DUAL_MORTAR ? "dual mortar" : "node-to-surface", (double)cg->gapMin, (double)cg->gapMax, law));
    else {
      PetscCall(SSStarObstacleDescribe(&cg->obstacle, obstacle, sizeof(obstacle)));
      PetscCall(PetscViewerASCIIPrintf(viewer, "contact group %s: %" PetscInt_FMT " nodes, %s, initial gaps %g .. %g, friction %s", cg->name, cg->nodes, obstacle, (double)cg->gapMin, (double)cg->gapMax, law));
    }
    PetscCall(PetscViewerASCIIUseTabs(viewer, PETSC_FALSE));
    if (friction && cg->phiSet) PetscCall(PetscViewerASCIIPrintf(viewer, ", phi = %g", (double)cg->phi));
    if (friction && !cg->phiSet) PetscCall(PetscViewerASCIIPrintf(viewer, ", phi of the solver (-snes_ssstar_friction)"));
    if (bound) PetscCall(PetscViewerASCIIPrintf(viewer, ", slip bound %g per node", (double)cg->bound));
    PetscCall(PetscViewerASCIIPrintf(viewer, "\n"));
    PetscCall(PetscViewerASCIIUseTabs(viewer, PETSC_TRUE));
  }
  if (scene->nBodies > 1) PetscCall(PetscViewerASCIIPrintf(viewer, "bodies: %" PetscInt_FMT " (connected parts of the mesh)\n", scene->nBodies));
  if (scene->nPairs && scene->pairMethod == SSSTAR_PAIR_DUAL_MORTAR) PetscCall(PetscViewerASCIIPrintf(viewer, "dual mortar: %" PetscInt_FMT " slave nodes not covered by their master surface keep node-to-surface\n", scene->pairFallback));
  if (scene->nSprings) PetscCall(PetscStrlcat(effects, ", springs", sizeof(effects)));
  if (scene->nTractions) PetscCall(PetscStrlcat(effects, ", tractions", sizeof(effects)));
  if (scene->hasGravity) PetscCall(PetscStrlcat(effects, ", gravity", sizeof(effects)));
  if (scene->nContact) {
    PetscInt nlaws;

    PetscCall(PetscStrlcat(effects, ", contact (non-penetration)", sizeof(effects)));
    if (scene->nPairs) PetscCall(PetscStrlcat(effects, scene->pairMethod == SSSTAR_PAIR_DUAL_MORTAR ? ", contact pairs (dual mortar)" : ", contact pairs (node-to-surface)", sizeof(effects)));
    PetscCall(SSStarLawGetNames(&nlaws, NULL));
    for (PetscInt l = 0; l < nlaws; l++) { /* the effects of the laws in use, in the table's order */
      PetscBool   used = PETSC_FALSE;
      const char *effect;

      for (PetscInt g = 0; g < scene->nContact; g++) used = (PetscBool)(used || scene->contact[g].law == l);
      PetscCall(SSStarLawGetInfo(l, NULL, &effect, NULL, NULL));
      if (used && effect) {
        PetscCall(PetscStrlcat(effects, ", ", sizeof(effects)));
        PetscCall(PetscStrlcat(effects, effect, sizeof(effects)));
      }
    }
  } else PetscCall(PetscStrlcat(effects, "; no contact: one linear solve", sizeof(effects)));
  PetscCall(PetscViewerASCIIPrintf(viewer, "active effects: %s\n", effects));
  PetscCall(PetscViewerASCIIPopTab(viewer));
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneGetContactResult - counts, contact area and forces of the contact nodes of group g (-1: of all groups)
   at a solution

   Collective

   Input Parameters:
+  scene  - the scene
.  g      - the contact group (in the order of -contact), or -1
.  r      - K u - b, whose contact entries are the contact forces (SNESGetFunction() after the solve)
-  states - the states of the owned contact nodes (SNESSSStarGetStates())

   Output Parameter:
.  res - the nodes per kind of state, the area of the nodes in contact, the normal force and the force

   Level: intermediate

.seealso: `SSStarSceneContactView()`, `SNESSSStarGetStates()`
@*/
PetscErrorCode SSStarSceneGetContactResult(SSStarScene scene, PetscInt g, Vec r, const SSStarState states[], SSStarContactResult *res)
{
  Vec                rC;
  const PetscScalar *ra;
  PetscReal          sums[5] = {0, 0, 0, 0, 0};
  PetscInt           counts[4] = {0, 0, 0, 0};

  PetscFunctionBegin;
  PetscCall(VecGetSubVector(r, scene->isC, &rC));
  PetscCall(VecGetArrayRead(rC, &ra));
  for (PetscInt i = 0; i < scene->n; i++) {
    const SSStarState s = states[i];
    PetscBool         touching;

    if (g >= 0 && scene->group[i] != g) continue;
    counts[0]++;
    if (s == SSSTAR_STATE_L || s == SSSTAR_STATE_LS) counts[1]++;
    else if (s == SSSTAR_STATE_M1 || s == SSSTAR_STATE_M2) counts[2]++;
    else counts[3]++;
    touching = (PetscBool)(s != SSSTAR_STATE_L && s != SSSTAR_STATE_LS);
    if (touching) sums[0] += scene->area[i];
    for (PetscInt k = 0; k < 3; k++) {
      sums[1] += PetscRealPart(ra[3 * i + k]) * scene->normal[3 * i + k];
      sums[2 + k] += PetscRealPart(ra[3 * i + k]);
    }
  }
  PetscCall(VecRestoreArrayRead(rC, &ra));
  PetscCall(VecRestoreSubVector(r, scene->isC, &rC));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, sums, 5, MPIU_REAL, MPIU_SUM, scene->comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, counts, 4, MPIU_INT, MPI_SUM, scene->comm));
  res->nodes        = counts[0];
  res->separated    = counts[1];
  res->sliding      = counts[2];
  res->sticking     = counts[3];
  res->area         = sums[0];
  res->normal_force = sums[1];
  for (PetscInt k = 0; k < 3; k++) res->force[k] = sums[2 + k];
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneContactView - one line per contact group: states, contact area, forces

   Collective

   Input Parameters:
+  scene  - the scene
.  r      - K u - b (SNESGetFunction() after the solve)
.  states - the states of the owned contact nodes (SNESSSStarGetStates())
-  viewer - an ASCII viewer

   Level: beginner

.seealso: `SSStarSceneGetContactResult()`, `SSStarSceneView()`
@*/
PetscErrorCode SSStarSceneContactView(SSStarScene scene, Vec r, const SSStarState states[], PetscViewer viewer)
{
  PetscFunctionBegin;
  for (PetscInt g = 0; g < scene->nContact; g++) {
    SSStarContactResult res;

    PetscCall(SSStarSceneGetContactResult(scene, g, r, states, &res));
    PetscCall(PetscViewerASCIIPrintf(viewer, "contact group %s: %" PetscInt_FMT " nodes, %" PetscInt_FMT " separated, %" PetscInt_FMT " sliding, %" PetscInt_FMT " sticking; contact area %.6g; normal force %.6g; force (%.6g, %.6g, %.6g)\n", scene->contact[g].name, res.nodes, res.separated, res.sliding, res.sticking, (double)res.area, (double)res.normal_force, (double)res.force[0], (double)res.force[1], (double)res.force[2]));
  }
  PetscFunctionReturn(0);
}
