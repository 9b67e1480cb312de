/*
   A scene: the body (a gmsh mesh), its material, supports and loads, and its contact groups, each with a contact source
   (a rigid obstacle: obstacle.c; or the master surface of a contact pair: pairs.c) and a friction law. Only what the
   options name is built: no contact group, no contact nodes; no -gravity, no body force. The description comes from
   the options (sceneoptions.c); SSStarSceneSetUp() meshes, finds the bodies (bodies.c) and the contact nodes (nodes.c)
   and builds the contact operator (operator.c).
*/
#include "sceneimpl.h"
#include "../sys/meminfo.h"

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
  (*scene)->smallSlidingTol = 0.01;
  (*scene)->slidingTol      = 1e-3;
  (*scene)->slidingMaxIt    = 4;
  (*scene)->level     = -1;
  (*scene)->nested    = -1;
  (*scene)->affine    = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneSetProgress - whether the scene prints a line as each phase of its work ends (the default of
   -ssstar_progress, which SSStarSceneSetFromOptions() reads): the mesh file, the mesh read and distributed, the contact
   nodes, the assembly, the output file, each with its seconds and the memory of the largest rank; and, through
   SSStarSceneSetContact(), the solver's SNESSSStarMonitorProgress()

   Logically Collective

   Input Parameters:
+  scene    - the scene, before SSStarSceneSetFromOptions()
-  progress - PETSC_TRUE for the lines (the programs of examples/); a library's scene prints none unless asked

   Options Database Key:
.  -ssstar_progress <bool> - the lines

   Level: intermediate

.seealso: `SSStarSceneSetFromOptions()`, `SNESSSStarMonitorProgress()`, `SSStarMemoryGetUsage()`
@*/
PetscErrorCode SSStarSceneSetProgress(SSStarScene scene, PetscBool progress)
{
  PetscFunctionBegin;
  scene->progress = progress;
  PetscFunctionReturn(0);
}

/* With -ssstar_progress, the line of a phase that ended: what it did, the seconds since *t (restarted), the memory of the largest rank */
PetscErrorCode SSStarSceneProgress(SSStarScene scene, PetscLogDouble *t, const char what[])
{
  PetscLogDouble now;
  char           memory[128];

  PetscFunctionBegin;
  if (!scene->progress) PetscFunctionReturn(0);
  PetscCall(PetscTime(&now));
  PetscCall(SSStarMemoryText(scene->comm, memory, sizeof(memory)));
  PetscCall(PetscPrintf(scene->comm, "%s, %.3f s, %s\n", what, now - *t, memory));
  PetscCall(PetscViewerFlush(PETSC_VIEWER_STDOUT_(scene->comm)));
  *t = now;
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
  for (PetscInt t = 0; t < s->nTractions; t++) PetscCall(SSStarHistoryDestroy(&s->tractions[t].history));
  PetscCall(PetscFree4(s->materials, s->tractions, s->springs, s->velocities));
  PetscCall(SSStarDynamicsDestroy(s));
  PetscCall(PetscFree(s->models));
  PetscCall(VecDestroy(&s->problemLoad));
  PetscCall(MatDestroy(&s->Kref));
  PetscCall(KSPDestroy(&s->predictor));
  PetscCall(SSStarHistoryDestroy(&s->gravityHistory));
  PetscCall(SSStarPrescribedDestroy(s));
  PetscCall(PetscFree(s->contactHeld));
  for (PetscInt g = 0; g < s->nContact; g++) {
    PetscCall(SSStarObstacleDestroy(&s->contact[g].obstacle));
    PetscCall(SSStarMotionDestroy(&s->contact[g].motion));
    PetscCall(SSStarGroupLawDestroy(&s->contact[g]));
  }
  PetscCall(SSStarScenePathDestroy(s));
  PetscCall(PetscFree(s->contact));
  PetscCall(PetscFree4(s->tag, s->group, s->coords, s->normal));
  PetscCall(PetscFree2(s->gap, s->area));
  PetscCall(PetscFree(s->gapInitial));
  PetscCall(PetscFree(s->obstaclePoint));
  PetscCall(ISDestroy(&s->isC));
  PetscCall(PetscFree(s->body));
  PetscCall(SSStarSceneDestroyFloating(s));
  PetscCall(PetscFree(s->frame));
  PetscCall(PetscFree3(s->masterStart, s->masterDof, s->masterWeight));
  PetscCall(MatDestroy(&s->B));
  PetscCall(VecDestroy(&s->tags));
  PetscCall(DMDestroy(&s->dm));
  PetscCall(PetscFree(*scene));
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneSetUp - builds the scene: meshes -geo at -level (or reads -mesh), checks the groups the options name,
   distributes the mesh, sets the dofs (u = 0 on the -dirichlet groups; the components -displacement_<G> prescribes,
   refusing a node prescribed twice with different values), finds the bodies (connected parts of the
   mesh; one that no -dirichlet or -spring_<G> group holds is refused, named by its volume groups), the contact nodes
   and the contact operator B (each node's rows from its group's rigid obstacle or contact pair)

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
  PetscLogDouble  t, base, peak, extra;
  PetscBool       plain, fits;
  PetscMPIInt     size;
  char            line[PETSC_MAX_PATH_LEN + 128];

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(SSSTAR_Mesh, 0, 0, 0, 0));
  PetscCall(PetscTime(&t));
  if (scene->geo[0]) {
    PetscCall(SSStarMeshCacheFile(scene->comm, scene->meshCache, scene->geo, scene->level, scene->mesh));
    PetscCall(SSStarMeshGenerate(scene->comm, scene->geo, scene->level, scene->mesh));
  }
  PetscCall(SSStarMeshFileNodes(scene->comm, scene->mesh, &scene->nodesGlobal));
  PetscCall(SSStarMemoryGetUsage(scene->comm, &base, NULL));
  PetscCallMPI(MPI_Comm_size(scene->comm, &size));
  PetscCall(PetscSNPrintf(line, sizeof(line), "mesh: file %s, %" PetscInt_FMT " nodes", scene->mesh, scene->nodesGlobal));
  PetscCall(SSStarSceneProgress(scene, &t, line));
  PetscCall(SSStarCheckMemory(scene->comm, (PetscReal)scene->nodesGlobal, scene->mesh));
  PetscCall(SSStarSceneGroupUses(scene, &nuses, &uses, &options));
  PetscCall(SSStarMeshLoad(scene->comm, scene->mesh, nuses, uses, scene->refine, &scene->dm, &scene->tags));
  for (PetscInt k = 0; k < nuses; k++) PetscCall(PetscFree(options[k]));
  PetscCall(PetscFree(options));
  PetscCall(PetscFree(uses));
  PetscCall(SSStarMeshScale(scene->dm, scene->meshScale));
  PetscCall(SSStarMeshCreateSection(scene->dm, scene->nDirichlet, scene->dirichlet));
  PetscCall(SSStarSceneFindHeld(scene));
  PetscCall(DMGetCoordinates(scene->dm, &coordinates));
  PetscCall(VecGetSize(coordinates, &scene->nodesGlobal));
  scene->nodesGlobal /= 3;
  {
    PetscInt cStart, cEnd;

    PetscCall(DMPlexGetHeightStratum(scene->dm, 0, &cStart, &cEnd));
    cells = cEnd - cStart;
    PetscCall(MPIU_Allreduce(&cells, &scene->cellsGlobal, 1, MPIU_INT, MPI_SUM, scene->comm));
  }
  if (scene->refine) PetscCall(PetscSNPrintf(line, sizeof(line), "mesh: read, refined %" PetscInt_FMT " time%s and distributed over %d rank%s, %" PetscInt_FMT " nodes, %" PetscInt_FMT " cells", scene->refine, scene->refine > 1 ? "s" : "", size, size > 1 ? "s" : "", scene->nodesGlobal, scene->cellsGlobal));
  else PetscCall(PetscSNPrintf(line, sizeof(line), "mesh: read and distributed over %d rank%s, %" PetscInt_FMT " cells", size, size > 1 ? "s" : "", scene->cellsGlobal));
  PetscCall(SSStarSceneProgress(scene, &t, line));
  PetscCall(SSStarSceneFindBodies(scene));
  PetscCall(SSStarSceneFindContactNodes(scene));
  PetscCall(SSStarSceneBuildContactOperator(scene, NULL));
  PetscCall(SSStarSceneCheckPartlyHeld(scene));
  /* the estimates before the work, now that the contact nodes are known: the whole body's, with the aggregation the
     solver will follow (SSStarSceneSetContact()), and the dense route's */
  PetscCall(SSStarEstimateWholeBody(scene->comm, scene->nodesGlobal, base, &peak, &plain, &scene->smoothedFits, &extra, &fits));
  scene->plain = plain;
  PetscCall(PetscSNPrintf(line, sizeof(line), "contact: %" PetscInt_FMT " contact nodes in %" PetscInt_FMT " group%s, estimated peak %.3f GB per rank%s%s", scene->nGlobal, scene->nContact, scene->nContact == 1 ? "" : "s", peak / 1e9, plain ? " (plain aggregation)" : "", scene->nGlobal ? " on the whole body" : ""));
  if (scene->nGlobal) {
    char dense[64];

    PetscCall(PetscSNPrintf(dense, sizeof(dense), ", %.3f GB on the dense route", SSStarPeakDenseFrom(size, scene->nodesGlobal, scene->nGlobal, base) / 1e9));
    PetscCall(PetscStrlcat(line, dense, sizeof(line)));
  }
  PetscCall(SSStarSceneProgress(scene, &t, line));
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
-  b - the load (the caller destroys it); of load histories, their value at the last knot (SSStarSceneAssembleLoad()
       gives it at any time)

   Level: beginner

.seealso: `SSStarSceneSetContact()`, `SSStarSceneGetDM()`
@*/
PetscErrorCode SSStarSceneAssemble(SSStarScene scene, Mat *K, Vec *b)
{
  PetscInt       nknots, n;
  PetscReal     *knots;
  PetscLogDouble t;
  char           line[128];

  PetscFunctionBegin;
  PetscCall(PetscTime(&t));
  PetscCall(SSStarSceneGetKnots(scene, &nknots, &knots));
  PetscCall(SSStarAssembleElasticity(scene, nknots ? knots[nknots - 1] : 0, K, b)); /* the load at the last knot */
  PetscCall(PetscFree(knots));
  PetscCall(MatGetSize(*K, &n, NULL));
  PetscCall(PetscSNPrintf(line, sizeof(line), "assembly: K of %" PetscInt_FMT " dofs and b", n));
  PetscCall(SSStarSceneProgress(scene, &t, line));
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

/* A history as the view shows it: "(x, y, z)" for a constant, else "history t:x,y,z;..." */
static PetscErrorCode HistoryText(SSStarHistory h, char text[], size_t len)
{
  PetscInt         n;
  const PetscReal *v;

  PetscFunctionBegin;
  PetscCall(SSStarHistoryGetKnots(h, &n, NULL, &v));
  if (!n) PetscCall(PetscSNPrintf(text, len, "(%g, %g, %g)", (double)v[0], (double)v[1], (double)v[2]));
  else {
    PetscCall(PetscStrncpy(text, "history ", len));
    PetscCall(SSStarHistoryDescribe(h, text + 8, len - 8));
  }
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
  char effects[512] = "elasticity", text[1024];

  PetscFunctionBegin;
  if (!scene->affine) PetscCall(PetscStrncpy(effects, "hyperelasticity (finite strain; tractions and gravity dead loads)", sizeof(effects)));
  if (scene->refine) PetscCall(PetscViewerASCIIPrintf(viewer, "Scene: mesh %s refined %" PetscInt_FMT " time%s (-dm_refine), %" PetscInt_FMT " nodes, %" PetscInt_FMT " tetrahedra\n", scene->mesh, scene->refine, scene->refine > 1 ? "s" : "", scene->nodesGlobal, scene->cellsGlobal));
  else PetscCall(PetscViewerASCIIPrintf(viewer, "Scene: mesh %s, %" PetscInt_FMT " nodes, %" PetscInt_FMT " tetrahedra\n", scene->mesh, scene->nodesGlobal, scene->cellsGlobal));
  PetscCall(PetscViewerASCIIPushTab(viewer));
  if (scene->hasE && scene->hasNu) PetscCall(PetscViewerASCIIPrintf(viewer, "material: E = %g, nu = %g\n", (double)scene->E, (double)scene->nu));
  if (!scene->affine) PetscCall(PetscViewerASCIIPrintf(viewer, "material model: %s\n", SSStarMaterialModels[scene->model]));
  for (PetscInt m = 0; m < scene->nModels; m++) PetscCall(PetscViewerASCIIPrintf(viewer, "material model of %s: %s\n", scene->models[m].name, SSStarMaterialModels[scene->models[m].model]));
  for (PetscInt m = 0; m < scene->nMaterials; m++) {
    PetscCall(PetscViewerASCIIPrintf(viewer, "material of %s: E = %g, nu = %g", scene->materials[m].name, (double)scene->materials[m].value[0], (double)scene->materials[m].value[1]));
    PetscCall(PetscViewerASCIIUseTabs(viewer, PETSC_FALSE));
    if (scene->materials[m].count > 2) PetscCall(PetscViewerASCIIPrintf(viewer, ", density %g", (double)scene->materials[m].value[2]));
    PetscCall(PetscViewerASCIIPrintf(viewer, "\n"));
    PetscCall(PetscViewerASCIIUseTabs(viewer, PETSC_TRUE));
  }
  for (PetscInt g = 0; g < scene->nVelocities; g++) PetscCall(PetscViewerASCIIPrintf(viewer, "initial velocity of %s: (%g, %g, %g)\n", scene->velocities[g].name, (double)scene->velocities[g].value[0], (double)scene->velocities[g].value[1], (double)scene->velocities[g].value[2]));
  PetscCall(SSStarDynamicsView(scene, viewer));
  for (PetscInt g = 0; g < scene->nDirichlet; g++) PetscCall(PetscViewerASCIIPrintf(viewer, "held fixed: %s\n", scene->dirichlet[g]));
  for (PetscInt g = 0; g < scene->nDisplacements; g++) {
    PetscCall(SSStarPrescribedText(&scene->displacements[g], text, sizeof(text)));
    PetscCall(PetscViewerASCIIPrintf(viewer, "%s of %s: %s\n", scene->displacements[g].rotation ? "rotation" : "displacement", scene->displacements[g].name, text));
  }
  for (PetscInt s = 0; s < scene->nSprings; s++) PetscCall(PetscViewerASCIIPrintf(viewer, "spring on %s: k = %g per unit area, every direction\n", scene->springs[s].name, (double)scene->springs[s].value[0]));
  for (PetscInt t = 0; t < scene->nTractions; t++) {
    PetscCall(HistoryText(scene->tractions[t].history, text, sizeof(text)));
    PetscCall(PetscViewerASCIIPrintf(viewer, "traction on %s: %s\n", scene->tractions[t].name, text));
  }
  if (scene->hasGravity) {
    PetscCall(HistoryText(scene->gravityHistory, text, sizeof(text)));
    PetscCall(PetscViewerASCIIPrintf(viewer, "gravity: %s, density %g\n", text, (double)scene->density));
  }
  for (PetscInt g = 0; g < scene->nContact; g++) {
    const SSStarContactGroup *cg = &scene->contact[g];
    char                      obstacle[PETSC_MAX_PATH_LEN + 128];

    if (cg->master[0]) PetscCall(PetscViewerASCIIPrintf(viewer, "contact pair %s -> %s: %" PetscInt_FMT " slave nodes of %s against the master surface %s of another body (%s), initial gaps %g .. %g", cg->name, cg->master, cg->nodes, cg->name, cg->master, scene->pairMethod == SSSTAR_PAIR_DUAL_MORTAR ? "dual mortar" : "node-to-surface", (double)cg->gapMin, (double)cg->gapMax));
    else {
      PetscCall(SSStarObstacleDescribe(cg->obstacle, obstacle, sizeof(obstacle)));
      PetscCall(PetscViewerASCIIPrintf(viewer, "contact group %s: %" PetscInt_FMT " nodes, %s, initial gaps %g .. %g", cg->name, cg->nodes, obstacle, (double)cg->gapMin, (double)cg->gapMax));
    }
    PetscCall(PetscViewerASCIIUseTabs(viewer, PETSC_FALSE));
    if (cg->motion.translation) {
      PetscCall(HistoryText(cg->motion.translation, text, sizeof(text)));
      PetscCall(PetscViewerASCIIPrintf(viewer, ", moving by %s", text));
    }
    if (cg->motion.rotation) {
      PetscCall(HistoryText(cg->motion.rotation, text, sizeof(text)));
      PetscCall(PetscViewerASCIIPrintf(viewer, ", turning by %s (axis, angle) about (%g, %g, %g)", text, (double)cg->motion.center[0], (double)cg->motion.center[1], (double)cg->motion.center[2]));
    }
    PetscCall(SSStarGroupLawView(cg, viewer)); /* ", friction coulomb, phi = 0.5" */
    PetscCall(PetscViewerASCIIPrintf(viewer, "\n"));
    PetscCall(PetscViewerASCIIUseTabs(viewer, PETSC_TRUE));
  }
  if (scene->nBodies > 1) PetscCall(PetscViewerASCIIPrintf(viewer, "bodies: %" PetscInt_FMT " (connected parts of the mesh)\n", scene->nBodies));
  if (scene->nPairs && scene->pairMethod == SSSTAR_PAIR_DUAL_MORTAR) PetscCall(PetscViewerASCIIPrintf(viewer, "dual mortar: %" PetscInt_FMT " slave nodes not covered by their master surface keep node-to-surface\n", scene->pairFallback));
  if (scene->nSprings) PetscCall(PetscStrlcat(effects, ", springs", sizeof(effects)));
  if (scene->nDisplacements) PetscCall(PetscStrlcat(effects, ", prescribed displacements", sizeof(effects)));
  if (scene->nTractions) PetscCall(PetscStrlcat(effects, ", tractions", sizeof(effects)));
  if (scene->hasGravity) PetscCall(PetscStrlcat(effects, ", gravity", sizeof(effects)));
  {
    PetscBool path; /* histories with knots or moving obstacles */

    PetscCall(SSStarSceneHasPath(scene, &path));
    if (path) PetscCall(PetscStrlcat(effects, scene->nContact && scene->sliding == SSSTAR_SLIDING_LARGE ? ", load path (incremental friction, large sliding)" : ", load path (incremental friction)", sizeof(effects)));
    if (scene->dynamics) PetscCall(PetscStrlcat(effects, ", inertia (time steps)", sizeof(effects)));
  }
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
  } else PetscCall(PetscStrlcat(effects, scene->affine ? "; no contact: one linear solve" : "; no contact: Newton's method", sizeof(effects)));
  PetscCall(PetscViewerASCIIPrintf(viewer, "active effects: %s\n", effects));
  PetscCall(PetscViewerASCIIPopTab(viewer));
  PetscFunctionReturn(0);
}
