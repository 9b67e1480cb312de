/*
   The scene's description from the options database (docs/guide/scenes.md): the body, its material, supports, loads and
   contact groups, each option checked where it is read, with errors that name the option; the groups the options
   name, for the checks against the mesh; the refusal of unread options with the scene's own among the known ones.
*/
#include "sceneimpl.h"
#include "../sys/names.h"

#define SSSTAR_MAX_LIST 64 /* groups in one -dirichlet or -contact list */

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

/* The options that carry a group name: -<prefix><G>, and -<parameter>_<G> for every parameter of the friction laws */
typedef enum {
  OPT_MATERIAL,
  OPT_TRACTION,
  OPT_SPRING,
  OPT_OBSTACLE,
  OPT_FRICTION_LAW,
  OPT_CONTACT_PAIR,
  OPT_DISPLACEMENT,
  OPT_LAW_PARAMETER
} GroupOption;
static const char *const GroupOptionPrefix[OPT_LAW_PARAMETER] = {"-material_", "-traction_", "-spring_", "-obstacle_", "-friction_law_", "-contact_pair_", "-displacement_"};

static PetscBool IsContactGroup(SSStarScene scene, const char name[])
{
  for (PetscInt g = 0; g < scene->nContact; g++) {
    PetscBool same;

    if (!PetscStrcmp(name, scene->contact[g].name, &same) && same) return PETSC_TRUE;
  }
  return PETSC_FALSE;
}

/*
   Which group option token is, and where its group starts: the longest prefix it starts with, unless that one leaves
   no contact group and a shorter one does (-friction_1_top: the friction_1 of the group top, or with no contact group
   top the friction of a group 1_top; -friction_law_top: the law of top, not the friction of law_top)
*/
static PetscErrorCode MatchGroupOption(SSStarScene scene, const char token[], GroupOption *kind, size_t *prefixLen, PetscBool *found)
{
  PetscInt           nparams;
  const char *const *params;
  size_t             best = 0, bestContact = 0;
  GroupOption        bestKind = OPT_MATERIAL, bestContactKind = OPT_MATERIAL;

  PetscFunctionBegin;
  PetscCall(SSStarLawGetParameterNames(&nparams, &params));
  for (PetscInt k = 0; k < OPT_LAW_PARAMETER + nparams; k++) {
    const GroupOption option = k < OPT_LAW_PARAMETER ? (GroupOption)k : OPT_LAW_PARAMETER;
    char              prefix[80];
    size_t            len;
    PetscBool         match;

    if (k < OPT_LAW_PARAMETER) PetscCall(PetscStrncpy(prefix, GroupOptionPrefix[k], sizeof(prefix)));
    else PetscCall(PetscSNPrintf(prefix, sizeof(prefix), "-%s_", params[k - OPT_LAW_PARAMETER]));
    PetscCall(PetscStrlen(prefix, &len));
    PetscCall(PetscStrncmp(token, prefix, len, &match));
    if (!match || !token[len]) continue;
    if (len > best) {
      best     = len;
      bestKind = option;
    }
    if (option >= OPT_OBSTACLE && option != OPT_DISPLACEMENT && len > bestContact && IsContactGroup(scene, token + len)) {
      bestContact     = len;
      bestContactKind = option;
    }
  }
  *found = (PetscBool)(best > 0);
  if (bestKind >= OPT_OBSTACLE && bestKind != OPT_DISPLACEMENT && bestContact && !IsContactGroup(scene, token + best)) {
    best     = bestContact;
    bestKind = bestContactKind;
  }
  *kind      = bestKind;
  *prefixLen = best;
  PetscFunctionReturn(0);
}

/* Calls found(scene, kind, group, option) for every option of the database with a group prefix */
static PetscErrorCode ForEachGroupOption(SSStarScene scene, PetscErrorCode (*found)(SSStarScene, GroupOption, const char[], const char[]))
{
  char *all, *token, *save = NULL;

  PetscFunctionBegin;
  PetscCall(PetscOptionsGetAll(NULL, &all));
  for (token = strtok_r(all, " ", &save); token; token = strtok_r(NULL, " ", &save)) {
    GroupOption kind  = OPT_MATERIAL;
    size_t      len   = 0, glen;
    PetscBool   match = PETSC_FALSE;

    PetscCall(MatchGroupOption(scene, token, &kind, &len, &match));
    if (!match) continue;
    PetscCall(PetscStrlen(token + len, &glen));
    PetscCheck(glen < SSSTAR_GROUP_NAME_LEN, scene->comm, PETSC_ERR_ARG_WRONG, "Option %s: the group name is longer than %d characters", token, SSSTAR_GROUP_NAME_LEN - 1);
    PetscCall(found(scene, kind, token + len, token));
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
  if (kind == OPT_DISPLACEMENT) scene->nDisplacements++;
  PetscFunctionReturn(0);
}

/* The contact group named group, or NULL */
static PetscErrorCode FindContactGroup(SSStarScene scene, const char group[], SSStarContactGroup **cg)
{
  PetscBool same;

  PetscFunctionBegin;
  *cg = NULL;
  for (PetscInt g = 0; g < scene->nContact && !*cg; g++) {
    PetscCall(PetscStrcmp(group, scene->contact[g].name, &same));
    if (same) *cg = &scene->contact[g];
  }
  PetscFunctionReturn(0);
}

/* The contact group G of a -obstacle_G, -friction_law_G, -<parameter>_G or -contact_pair_G (which must be in -contact);
   an unknown one is refused with the nearest contact group */
static PetscErrorCode ContactGroup(SSStarScene scene, const char group[], const char option[], SSStarContactGroup **cg)
{
  PetscInt best = PETSC_MAX_INT, nearest = -1;

  PetscFunctionBegin;
  PetscCall(FindContactGroup(scene, group, cg));
  if (*cg) PetscFunctionReturn(0);
  for (PetscInt g = 0; g < scene->nContact; g++) {
    const PetscInt d = SSStarNameDistance(group, strlen(group), scene->contact[g].name, strlen(scene->contact[g].name));

    if (d < best) {
      best    = d;
      nearest = g;
    }
  }
  PetscCheck(nearest >= 0, scene->comm, PETSC_ERR_ARG_WRONG, "Option %s: \"%s\" is not a contact group (there is no -contact)", option, group);
  SETERRQ(scene->comm, PETSC_ERR_ARG_WRONG, "Option %s: \"%s\" is not a contact group (not in -contact; the nearest contact group is \"%s\")", option, group, scene->contact[nearest].name);
}

/* The group name G of a rest "G_motion" of -obstacle_G_motion (empty: no such rest) */
static PetscErrorCode MotionStem(const char rest[], char stem[], size_t size)
{
  const char suffix[] = "_motion";
  size_t     len;

  PetscFunctionBegin;
  stem[0] = 0;
  PetscCall(PetscStrlen(rest, &len));
  if (len <= sizeof(suffix) - 1 || strcmp(rest + len - (sizeof(suffix) - 1), suffix)) PetscFunctionReturn(0);
  PetscCall(PetscStrncpy(stem, rest, PetscMin(size, len - (sizeof(suffix) - 1) + 1)));
  PetscFunctionReturn(0);
}

/* The value of a history at its last knot (a constant's value) */
PetscErrorCode SSStarSceneLastValue(SSStarHistory h, PetscReal value[3])
{
  PetscInt         n;
  const PetscReal *times;

  PetscFunctionBegin;
  PetscCall(SSStarHistoryGetKnots(h, &n, &times, NULL));
  PetscCall(SSStarHistoryEvaluate(h, n ? times[n - 1] : 0, value));
  PetscFunctionReturn(0);
}

static PetscErrorCode ReadGroupOption(SSStarScene scene, GroupOption kind, const char group[], const char option[])
{
  SSStarContactGroup *cg;
  SSStarGroupValues  *gv;
  PetscBool           set;

  PetscFunctionBegin;
  switch (kind) {
  case OPT_MATERIAL:
  case OPT_SPRING:
    gv = kind == OPT_MATERIAL ? &scene->materials[scene->nMaterials++] : &scene->springs[scene->nSprings++];
    PetscCall(PetscStrncpy(gv->name, group, sizeof(gv->name)));
    PetscCall(GetFiniteArray(scene->comm, option, kind == OPT_MATERIAL ? 2 : 1, kind == OPT_MATERIAL ? "E,nu" : "k", gv->value, &set));
    PetscCheck(kind != OPT_SPRING || gv->value[0] > 0, scene->comm, PETSC_ERR_ARG_OUTOFRANGE, "Option %s %g: the spring stiffness must be positive", option, (double)gv->value[0]);
    break;
  case OPT_TRACTION: /* a load history, or a constant */
    gv = &scene->tractions[scene->nTractions++];
    PetscCall(PetscStrncpy(gv->name, group, sizeof(gv->name)));
    PetscCall(SSStarHistoryCreateFromOptions(scene->comm, NULL, option, 3, &gv->history, &set));
    PetscCall(SSStarSceneLastValue(gv->history, gv->value));
    break;
  case OPT_OBSTACLE: {
    char spec[PETSC_MAX_PATH_LEN + 8] = "";

    char stem[SSSTAR_GROUP_NAME_LEN];

    PetscCall(FindContactGroup(scene, group, &cg));
    PetscCall(MotionStem(group, stem, sizeof(stem)));
    if (!cg && stem[0]) { /* -obstacle_<G>_motion: a translation history (a group named "x_motion" is looked up first) */
      PetscCall(ContactGroup(scene, stem, option, &cg));
      PetscCall(SSStarHistoryDestroy(&cg->motion));
      PetscCall(SSStarHistoryCreateFromOptions(scene->comm, NULL, option, 3, &cg->motion, &set));
      break;
    }
    PetscCall(ContactGroup(scene, group, option, &cg));
    PetscCall(PetscOptionsGetString(NULL, NULL, option, spec, sizeof(spec), &set));
    PetscCall(SSStarObstacleDestroy(&cg->obstacle));
    PetscCall(SSStarObstacleCreateFromString(scene->comm, option, spec, &cg->obstacle)); /* obstacle.c */
  } break;
  case OPT_FRICTION_LAW:
    PetscCall(ContactGroup(scene, group, option, &cg));
    PetscCall(SSStarGroupLawRead(scene, cg, option)); /* grouplaws.c */
    break;
  case OPT_LAW_PARAMETER: {
    char   parameter[64];
    size_t len, glen;

    PetscCall(ContactGroup(scene, group, option, &cg));
    PetscCall(PetscStrlen(option, &len));
    PetscCall(PetscStrlen(group, &glen));
    PetscCall(PetscStrncpy(parameter, option + 1, PetscMin(sizeof(parameter), len - glen - 1))); /* -<parameter>_<G> */
    PetscCall(SSStarGroupLawReadParameter(scene, cg, parameter, option));
  } break;
  case OPT_CONTACT_PAIR:
    PetscCall(ContactGroup(scene, group, option, &cg));
    PetscCall(SSStarPairsReadOption(scene, cg, option));
    break;
  case OPT_DISPLACEMENT: { /* prescribed displacements: numbers or free, constant or a history (prescribed.c) */
    const char *value;

    PetscCall(PetscOptionsFindPair(NULL, NULL, option, &value, &set));
    PetscCall(SSStarPrescribedRead(scene, option, group, value, &scene->displacements[scene->nDisplacements++]));
  } break;
  default:
    break;
  }
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

/* The options -help lists for the groups (read below by name, so PetscOptions* does not list them itself); those of
   the obstacles and the friction laws come from their registries (GroupHelp()) */
static const char SceneGroupHelp[] = "\
  -dirichlet <G1,G2,...>: groups held fixed (u = 0)\n\
  -material_<G> <E,nu>: material of volume group G\n\
  -displacement_<G> <x,y,z>: prescribed displacement of surface or volume group G (global axes), each component a\n\
      number or free (free,free,-0.01: only u_z prescribed); a constant or a history t:x,y,z;... (a component free\n\
      in one knot is free in all); its reaction force is in the output (docs/guide/displacements-and-stresses.md)\n\
  -traction_<G> <x,y,z>: traction on surface group G (global axes): a constant, or a load history of knots\n\
      t:x,y,z separated by ';' (\"0:0,0,0;1:0,0,-1\"), linear between them (docs/load-paths.md)\n\
  -spring_<G> <k>: soft elastic support of surface group G, k per unit area in every direction\n\
  -gravity <gx,gy,gz>: gravity, with -density (only when given); a constant or a history t:gx,gy,gz;...\n\
  -contact <G1,G2,...>: the contact groups (without -contact: no contact at all)\n\
  -obstacle_<G>_motion <t:x,y,z;...>: the translation history of G's rigid obstacle (indentation, sliding); with\n\
      histories or -steps the scene is a load path with incremental friction (docs/load-paths.md)\n\
  -contact_pair_<G> <H>: contact group G (slave) meets surface group H (master) of another body\n\
  -pair_discretization <node_to_surface>: of every pair: node_to_surface or dual_mortar (Wohlmuth's dual multipliers)\n";

/* The group options of -help: the fixed ones, -obstacle_<G> with the registered shapes, the friction laws' */
static PetscErrorCode GroupHelp(char text[], size_t len)
{
  char line[1024];

  PetscFunctionBegin;
  PetscCall(PetscStrncpy(text, SceneGroupHelp, len));
  PetscCall(SSStarObstacleHelp(line, sizeof(line)));
  PetscCall(PetscStrlcat(text, line, len));
  PetscCall(SSStarGroupLawHelp(line, sizeof(line)));
  PetscCall(PetscStrlcat(text, line, len));
  PetscFunctionReturn(0);
}

/* The options the scene reads (for SSStarSceneCheckOptionsUsed(): -mesh ... by PetscOptions*, the groups' by name) */
static const char SceneOptionNames[] = "-mesh -geo -level -mesh_cache -dm_refine -nested_levels -mesh_scale -E -nu -density -sliding -sliding_tol -sliding_max_it -small_sliding_tol";

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

.seealso: `SSStarCheckOptionsUsed()`, `SSStarSceneSetFromOptions()`, `SSStarSceneCheckOptionsUsedOf()`
@*/
PetscErrorCode SSStarSceneCheckOptionsUsed(SSStarScene scene, const char help[], SNES snes)
{
  char        groups[8192];
  const char *known[4] = {help ? help : "", SceneOptionNames, groups, NULL};

  PetscFunctionBegin;
  PetscCall(GroupHelp(groups, sizeof(groups)));
  PetscCall(SSStarCheckOptionsUsed(scene->comm, known, snes));
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneCheckOptionsUsedOf - SSStarSceneCheckOptionsUsed() for the options a program gave its scene: refuses
   those of them that neither the program, nor the scene, nor its solver has read, naming the nearest known option;
   the other options of the database keep PETSc's behaviour

   Collective

   Input Parameters:
+  scene - the scene, after SSStarSceneSetFromOptions()
.  n     - the number of options given
.  names - their names, without the dash (the Python module's scene: its keywords and its options file)
.  help  - the program's help text (its options as "-name"), or NULL
-  snes  - the program's SNES after SNESSetFromOptions(), or NULL

   Level: intermediate

.seealso: `SSStarSceneCheckOptionsUsed()`, `SSStarCheckOptionsUsedOf()`
@*/
PetscErrorCode SSStarSceneCheckOptionsUsedOf(SSStarScene scene, PetscInt n, const char *const names[], const char help[], SNES snes)
{
  char        groups[8192];
  const char *known[4] = {help ? help : "", SceneOptionNames, groups, NULL};

  PetscFunctionBegin;
  PetscCall(GroupHelp(groups, sizeof(groups)));
  PetscCall(SSStarCheckOptionsUsedOf(scene->comm, n, names, known, snes));
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneSetFromOptions - reads the scene from the options database (docs/guide/scenes.md), with errors that name the
   option for unknown, contradictory or incomplete entries

   Collective

   Input Parameter:
.  scene - the scene

   Options Database Keys:
+  -mesh <file.msh> - the body, a gmsh mesh
.  -geo <file.geo> - or a geometry meshed at -level
.  -level <L> - the level of -geo
.  -mesh_cache <folder> - where the meshes of -geo are made and kept (SSStarMeshCacheFile(); default $XDG_CACHE_HOME/ssstar, else ~/.cache/ssstar)
.  -ssstar_progress_ranks - the progress lines give rank 0's memory and the least rank's beside the largest one's
.  -nested_levels <auto> - solve this many coarser meshes first (SSStarSceneSolveNested()): 0 none, auto by the size
.  -dm_refine <0> - refine the mesh this many times in parallel (each tetrahedron 1:8, the groups carried), as PETSc's option of the name does
.  -mesh_scale <1> - multiply the coordinates by this
.  -E <E> - Young's modulus of the cells without -material_<G>
.  -nu <nu> - Poisson's ratio of those cells
.  -material_<G> <E,nu> - the material of volume group G
.  -dirichlet <G1,G2> - groups held fixed
.  -displacement_<G> <x,y,z> - the prescribed displacement of surface or volume group G: each component a number or free, a constant or a history t:x,y,z;...
.  -traction_<G> <x,y,z> - traction on surface group G: a constant, or a history t:x,y,z;... (docs/load-paths.md)
.  -spring_<G> <k> - soft support of surface group G
.  -gravity <gx,gy,gz> - gravity, with -density: a constant, or a history t:gx,gy,gz;...
.  -density <rho> - the mass density
.  -contact <G1,G2> - the contact groups
.  -obstacle_<G> <px,py,pz,nx,ny,nz> - the rigid obstacle of G: plane:px,py,pz,nx,ny,nz (or the six numbers), sphere:cx,cy,cz,R, cylinder:px,py,pz,ax,ay,az,R or mesh:FILE.msh
.  -obstacle_<G>_motion <t:x,y,z;...> - the translation history of G's obstacle
.  -sliding <large> - where a load path measures the contact: large (at the current configuration of each step) or small (at the reference)
.  -sliding_tol <1e-3> - large sliding: a step is solved again, linearized at its solution, while the contact measured there is off by more than this times the normal displacements
.  -sliding_max_it <4> - large sliding: such linearizations of a step before it is cut
.  -small_sliding_tol <0.01> - small sliding: a step whose motion makes the first-order gap of a moved obstacle wrong by more than this times |d| is refused
.  -friction_law_<G> <coulomb> - a law of the table: none, tresca, coulomb or orthotropic
.  -<parameter>_<G> <value> - every parameter of the laws (SSStarLawGetParameterNames()): -friction_<G> (the Coulomb
   coefficient of G; default the solver's), -slip_bound_<G> (the Tresca bound), -friction_1_<G>, -friction_2_<G>,
   -friction_direction_<G> x,y,z (orthotropic)
.  -contact_pair_<G> <H> - G meets the surface group H of another body
-  -pair_discretization <node_to_surface> - node_to_surface or dual_mortar

   Notes:
   With -help it lists the scene's options and reads no further (no check, no group): a program prints its options
   with -help and stops, with or without a scene.

   A group option is matched by its longest prefix: -friction_1_top is the friction_1 of the group top, unless top is
   no contact group and 1_top is (then it is the friction of 1_top). A parameter the group's law does not have is
   refused naming both options; one the law needs that has no default (tresca's slip_bound, the orthotropic law's) is
   required.

   Level: beginner

.seealso: `SSStarSceneCreate()`, `SSStarSceneSetUp()`, `SSStarSceneView()`
@*/
PetscErrorCode SSStarSceneSetFromOptions(SSStarScene scene)
{
  MPI_Comm  comm = scene->comm;
  PetscBool hasMesh, hasGeo, hasLevel, hasDensity, help;
  char    **contact;
  char      option[SSSTAR_GROUP_NAME_LEN + 16];

  PetscFunctionBegin;
  PetscOptionsBegin(comm, NULL, "Scene: the body, its loads and its contact groups", "ssstar");
  PetscCall(PetscOptionsString("-mesh", "gmsh mesh file", NULL, scene->mesh, scene->mesh, sizeof(scene->mesh), &hasMesh));
  PetscCall(PetscOptionsString("-geo", "gmsh geometry meshed at -level", NULL, scene->geo, scene->geo, sizeof(scene->geo), &hasGeo));
  PetscCall(PetscOptionsInt("-level", "Mesh level of -geo (the number L of the .geo)", NULL, scene->level, &scene->level, &hasLevel));
  PetscCall(PetscOptionsString("-mesh_cache", "Folder of the meshes made from -geo (default $XDG_CACHE_HOME/ssstar, else ~/.cache/ssstar)", "SSStarMeshCacheFile", scene->meshCache, scene->meshCache, sizeof(scene->meshCache), NULL));
  {
    char      nested[32] = "auto";
    PetscBool set, isauto;

    PetscCall(PetscOptionsString("-nested_levels", "Coarser meshes solved first, each the start of the next (0: none; auto: by the problem's size)", "SSStarSceneSolveNested", nested, nested, sizeof(nested), &set));
    PetscCall(PetscStrcmp(nested, "auto", &isauto));
    if (set && !isauto) {
      char *end;

      scene->nested = (PetscInt)strtol(nested, &end, 10);
      PetscCheck(*nested && !*end && scene->nested >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-nested_levels %s: give auto or a number >= 0 of coarser meshes", nested);
    } else scene->nested = -1;
  }
  PetscCall(PetscOptionsInt("-dm_refine", "Refine the mesh this many times in parallel (each tetrahedron 1:8)", NULL, scene->refine, &scene->refine, NULL));
  PetscCall(PetscOptionsReal("-mesh_scale", "Multiply the mesh coordinates by this", NULL, scene->meshScale, &scene->meshScale, NULL));
  PetscCall(PetscOptionsReal("-E", "Young's modulus of the cells without -material_<G>", NULL, scene->E, &scene->E, &scene->hasE));
  PetscCall(PetscOptionsReal("-nu", "Poisson ratio of the cells without -material_<G>", NULL, scene->nu, &scene->nu, &scene->hasNu));
  PetscCall(PetscOptionsReal("-density", "Mass density (with -gravity)", NULL, scene->density, &scene->density, &hasDensity));
  {
    PetscInt sliding = (PetscInt)scene->sliding;

    PetscCall(PetscOptionsEList("-sliding", "Where a load path measures the contact: large (at the current configuration of each step) or small (at the reference)", NULL, SSStarSlidings, 2, SSStarSlidings[sliding], &sliding, NULL));
    scene->sliding = (SSStarSliding)sliding;
  }
  PetscCall(PetscOptionsReal("-sliding_tol", "Large sliding: a step is solved again, linearized at its solution, while the contact measured there is off by more than this times the normal displacements", NULL, scene->slidingTol, &scene->slidingTol, NULL));
  PetscCall(PetscOptionsInt("-sliding_max_it", "Large sliding: linearizations of a step at its solution before it is cut", NULL, scene->slidingMaxIt, &scene->slidingMaxIt, NULL));
  PetscCall(PetscOptionsReal("-small_sliding_tol", "Small sliding: a moved ball, cylinder or mesh obstacle is refused at a step where its first-order gap g - n.d is off the exact gap by more than this times |d|", NULL, scene->smallSlidingTol, &scene->smallSlidingTol, NULL));
  PetscCall(PetscOptionsBool("-ssstar_progress", "A line as each phase ends: mesh, contact nodes, assembly, the solver's set-up and Newton steps, output", "SSStarSceneSetProgress", scene->progress, &scene->progress, NULL));
  {
    PetscBool ranks = PETSC_FALSE; /* read where the lines are printed (SSStarMemoryText) */

    PetscCall(PetscOptionsBool("-ssstar_progress_ranks", "The progress lines' memory of rank 0 and of the least rank too, beside the largest one's", "SSStarSceneSetProgress", ranks, &ranks, NULL));
  }
  if (PetscOptionsObject->printhelp && PetscOptionsObject->count == 1) {
    char groups[8192];

    PetscCall(GroupHelp(groups, sizeof(groups)));
    PetscCall((*PetscHelpPrintf)(comm, "%s", groups));
  }
  PetscOptionsEnd();
  PetscCall(PetscOptionsHasHelp(NULL, &help));
  if (help) PetscFunctionReturn(0); /* the options are listed: the drivers stop here, with or without a scene */
  PetscCheck(!(hasMesh && hasGeo), comm, PETSC_ERR_ARG_WRONG, "Options -mesh and -geo contradict each other: give one body");
  PetscCheck(hasMesh || hasGeo, comm, PETSC_ERR_ARG_WRONG, "No body: give -mesh file.msh, or -geo file.geo with -level L");
  PetscCheck(!(hasMesh && hasLevel), comm, PETSC_ERR_ARG_WRONG, "Options -mesh and -level contradict each other: -level is for -geo");
  PetscCheck(!hasGeo || hasLevel, comm, PETSC_ERR_ARG_WRONG, "Option -geo %s needs -level L", scene->geo);
  PetscCheck(!hasGeo || scene->level >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "-level %" PetscInt_FMT ": the mesh level must be >= 1", scene->level);
  PetscCheck(scene->refine >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-dm_refine %" PetscInt_FMT ": the number of refinements must be >= 0", scene->refine);
  PetscCheck(!scene->hasE || (scene->E > 0 && !PetscIsInfOrNanReal(scene->E)), comm, PETSC_ERR_ARG_OUTOFRANGE, "-E %g: Young's modulus must be a positive number", (double)scene->E);
  PetscCheck(!scene->hasNu || (scene->nu > -1 && scene->nu < 0.5), comm, PETSC_ERR_ARG_OUTOFRANGE, "-nu %g: Poisson's ratio must be in (-1, 0.5)", (double)scene->nu);
  PetscCheck(scene->slidingTol > 0 && !PetscIsInfOrNanReal(scene->slidingTol), comm, PETSC_ERR_ARG_OUTOFRANGE, "-sliding_tol %g: must be a positive number", (double)scene->slidingTol);
  PetscCheck(scene->slidingMaxIt >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-sliding_max_it %" PetscInt_FMT ": must be >= 0", scene->slidingMaxIt);
  PetscCheck(scene->smallSlidingTol > 0 && !PetscIsInfOrNanReal(scene->smallSlidingTol), comm, PETSC_ERR_ARG_OUTOFRANGE, "-small_sliding_tol %g: must be a positive number", (double)scene->smallSlidingTol);

  PetscCall(SSStarHistoryCreateFromOptions(comm, NULL, "-gravity", 3, &scene->gravityHistory, &scene->hasGravity));
  if (scene->hasGravity) PetscCall(SSStarSceneLastValue(scene->gravityHistory, scene->gravity));
  PetscCheck(scene->hasGravity == hasDensity, comm, PETSC_ERR_ARG_WRONG, "Incomplete body force: %s needs %s", scene->hasGravity ? "-gravity" : "-density", scene->hasGravity ? "-density" : "-gravity");
  PetscCheck(!hasDensity || (scene->density >= 0 && !PetscIsInfOrNanReal(scene->density)), comm, PETSC_ERR_ARG_OUTOFRANGE, "-density %g: the density must be a number >= 0", (double)scene->density);

  PetscCall(GetGroupList(comm, "-dirichlet", &scene->nDirichlet, &scene->dirichlet));
  PetscCall(GetGroupList(comm, "-contact", &scene->nContact, &contact));
  PetscCall(PetscCalloc1(scene->nContact, &scene->contact));
  for (PetscInt g = 0; g < scene->nContact; g++) {
    SSStarContactGroup *cg = &scene->contact[g];

    PetscCall(PetscStrncpy(cg->name, contact[g], sizeof(cg->name)));
    PetscCall(PetscFree(contact[g]));
    PetscCall(SSStarObstacleCreateDefault(&cg->obstacle)); /* the plane z = 0 */
    PetscCall(SSStarLawGetIndex(SSSTARLAWCOULOMB, &cg->law));
    PetscCall(CheckNotHeld(scene, cg->name, "-contact"));
  }
  PetscCall(PetscFree(contact));

  /* the options -<prefix><G>: count, then read */
  PetscCall(SSStarPrescribedDestroy(scene));
  scene->nMaterials = scene->nTractions = scene->nSprings = 0;
  PetscCall(ForEachGroupOption(scene, CountGroupOption));
  PetscCall(PetscFree3(scene->materials, scene->tractions, scene->springs));
  PetscCall(PetscCalloc3(scene->nMaterials, &scene->materials, scene->nTractions, &scene->tractions, scene->nSprings, &scene->springs));
  PetscCall(PetscCalloc1(scene->nDisplacements + 1, &scene->displacements));
  scene->nMaterials = scene->nTractions = scene->nSprings = scene->nPairs = scene->nDisplacements = 0;
  PetscCall(ForEachGroupOption(scene, ReadGroupOption));
  PetscCall(SSStarPairsCheckOptions(scene));
  for (PetscInt t = 0; t < scene->nTractions; t++) {
    PetscCall(PetscSNPrintf(option, sizeof(option), "-traction_%s", scene->tractions[t].name));
    PetscCall(CheckNotHeld(scene, scene->tractions[t].name, option));
  }
  for (PetscInt d = 0; d < scene->nDisplacements; d++) {
    PetscCall(PetscSNPrintf(option, sizeof(option), "-displacement_%s", scene->displacements[d].name));
    PetscCall(CheckNotHeld(scene, scene->displacements[d].name, option));
  }
  for (PetscInt g = 0; g < scene->nContact; g++) {
    const SSStarContactGroup *cg = &scene->contact[g];

    PetscCall(SSStarGroupLawCheck(scene, &scene->contact[g]));
    PetscCheck(!cg->motion || !cg->master[0], comm, PETSC_ERR_ARG_WRONG, "Options -obstacle_%s_motion and -contact_pair_%s contradict each other: a pair's master surface moves with its body (load that body)", cg->name, cg->name);
  }
  PetscFunctionReturn(0);
}

/* SSStarSceneGroupUses - every group an option names, with the kind of group the option needs (for the mesh checks) */
PetscErrorCode SSStarSceneGroupUses(SSStarScene scene, PetscInt *n, SSStarGroupUse **uses, char ***options)
{
  PetscInt total = scene->nDirichlet + scene->nContact + scene->nMaterials + scene->nTractions + scene->nSprings + scene->nPairs + scene->nDisplacements, k = 0;

  PetscFunctionBegin;
  PetscCall(PetscMalloc1(total, uses));
  PetscCall(PetscCalloc1(total, options));
  for (PetscInt g = 0; g < scene->nDirichlet; g++, k++) {
    (*uses)[k].group = scene->dirichlet[g];
    (*uses)[k].kind  = SSSTAR_GROUP_ANY;
    PetscCall(PetscStrallocpy("-dirichlet", &(*options)[k]));
  }
  for (PetscInt g = 0; g < scene->nDisplacements; g++, k++) {
    char option[SSSTAR_GROUP_NAME_LEN + 16];

    (*uses)[k].group = scene->displacements[g].name;
    (*uses)[k].kind  = SSSTAR_GROUP_ANY;
    PetscCall(PetscSNPrintf(option, sizeof(option), "-displacement_%s", scene->displacements[g].name));
    PetscCall(PetscStrallocpy(option, &(*options)[k]));
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
