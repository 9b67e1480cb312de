/*
   A scene's load path (docs/load-paths.md, docs/derivation.md section 10): its loads as histories of a pseudo-time t
   (-traction_<G>, -gravity), its rigid obstacles' translations (-obstacle_<G>_motion), and the steps t_1 < t_2 < ...
   solved one after the other with incremental friction. Each step hands the solver the offsets (10.4) of its contact
   nodes, computed from what the accepted step before left (the slip w_t^(k-1), the obstacles' translations d^(k-1)),
   and records, once solved, the kinematics of (10.9): the slip increment, the slip path and the energy friction
   dissipated at every node.
*/
#include "../sceneimpl.h"

/* Every history of the scene (tractions, gravity, motions, prescribed displacements) into list (NULL: count them) */
static PetscInt Histories(SSStarScene scene, SSStarHistory list[])
{
  PetscInt n = 0;

  for (PetscInt d = 0; d < scene->nDisplacements; d++, n++)
    if (list) list[n] = scene->displacements[d].history;
  for (PetscInt t = 0; t < scene->nTractions; t++, n++)
    if (list) list[n] = scene->tractions[t].history;
  if (scene->hasGravity) {
    if (list) list[n] = scene->gravityHistory;
    n++;
  }
  for (PetscInt g = 0; g < scene->nContact; g++)
    if (scene->contact[g].motion) {
      if (list) list[n] = scene->contact[g].motion;
      n++;
    }
  return n;
}

/*@C
   SSStarSceneGetKnots - the times of the knots of every history of the scene (tractions, gravity, obstacle motions,
   prescribed displacements), sorted, each once: the default steps of its load path

   Not Collective

   Input Parameter:
.  scene - the scene, after SSStarSceneSetFromOptions()

   Output Parameters:
+  n     - the number of knots (0 when every load is a constant)
-  times - the times, increasing (free with PetscFree())

   Level: intermediate

.seealso: `SSStarSceneHasPath()`, `SSStarHistoryParseSteps()`, `SSStarSceneSetStep()`
@*/
PetscErrorCode SSStarSceneGetKnots(SSStarScene scene, PetscInt *n, PetscReal *times[])
{
  SSStarHistory *list;
  PetscInt       count = Histories(scene, NULL);

  PetscFunctionBegin;
  PetscCall(PetscMalloc1(count + 1, &list));
  (void)Histories(scene, list);
  PetscCall(SSStarHistoryMergeKnots(count, list, n, times));
  PetscCall(PetscFree(list));
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneHasPath - whether the scene describes a load path: a history with knots, or a moving obstacle

   Not Collective

   Input Parameter:
.  scene - the scene, after SSStarSceneSetFromOptions()

   Output Parameter:
.  path - PETSC_TRUE for a load path; then its steps are solved with SSStarSceneSetStep() (incremental friction)

   Notes:
   A moving obstacle makes a path even with a constant translation: its single step is solved with the offsets of the
   displaced obstacle (SSStarSceneSetStep()).

   Level: intermediate

.seealso: `SSStarSceneGetKnots()`, `SSStarSceneSetStep()`
@*/
PetscErrorCode SSStarSceneHasPath(SSStarScene scene, PetscBool *path)
{
  PetscInt   n;
  PetscReal *times;

  PetscFunctionBegin;
  PetscCall(SSStarSceneGetKnots(scene, &n, &times));
  PetscCall(PetscFree(times));
  *path = (PetscBool)(n > 0);
  for (PetscInt g = 0; g < scene->nContact; g++)
    if (scene->contact[g].motion) *path = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneAssembleLoad - the load b of the scene at the time t of its histories (tractions and gravity evaluated
   at t; a constant load at any t)

   Collective

   Input Parameters:
+  scene - the scene, after SSStarSceneSetUp()
-  t     - the time

   Output Parameter:
.  b - the load (a global vector of the scene's DM, e.g. the one given to SNESSSStarSetLinearProblem())

   Notes:
   A surface and a volume loop, far cheaper than a solve: K is assembled once (SSStarSceneAssemble()), the load of
   each step here.

   Level: intermediate

.seealso: `SSStarSceneAssemble()`, `SSStarSceneSetStep()`, `SSStarSceneGetLoadResultant()`
@*/
PetscErrorCode SSStarSceneAssembleLoad(SSStarScene scene, PetscReal t, Vec b)
{
  PetscFunctionBegin;
  PetscCall(SSStarAssembleLoad(scene, t, b));
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneGetLoadResultant - the resultant of a load vector of the scene: the sum of its nodal forces (global axes)

   Collective

   Input Parameters:
+  scene - the scene
-  b     - a load (a global vector of the scene's DM); with prescribed displacements, the load the scene assembled last
           (SSStarSceneAssembleLoad()) or a multiple of it

   Output Parameter:
.  resultant - the sum over the dofs that are not held of their x, y and z forces (tractions, gravity)

   Notes:
   With prescribed displacements (-displacement_<G>) b holds their lifting too (docs/derivation.md section 15): the
   resultant is then that of the tractions and gravity the scene recorded when it assembled b, times b's factor.

   Level: intermediate

.seealso: `SSStarSceneAssembleLoad()`
@*/
PetscErrorCode SSStarSceneGetLoadResultant(SSStarScene scene, Vec b, PetscReal resultant[3])
{
  const PetscScalar *a;
  PetscInt           n;

  PetscFunctionBegin;
  resultant[0] = resultant[1] = resultant[2] = 0;
  if (scene->nDisplacements) {
    PetscReal alpha;

    PetscCall(SSStarSceneLoadFactor(scene, b, &alpha));
    for (PetscInt k = 0; k < 3; k++) resultant[k] = alpha * scene->loadFree[k];
    PetscFunctionReturn(0);
  }
  PetscCall(VecGetLocalSize(b, &n));
  PetscCall(VecGetArrayRead(b, &a));
  for (PetscInt i = 0; i < n; i++) resultant[i % 3] += PetscRealPart(a[i]); /* every free node has its 3 dofs */
  PetscCall(VecRestoreArrayRead(b, &a));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, resultant, 3, MPIU_REAL, MPIU_SUM, scene->comm));
  PetscFunctionReturn(0);
}

/* The per-node arrays of the path, zero (the reference configuration), at the first step */
static PetscErrorCode PathArrays(SSStarScene scene)
{
  PetscFunctionBegin;
  if (scene->slipPrev) PetscFunctionReturn(0);
  PetscCall(PetscCalloc4(2 * scene->n + 1, &scene->slipPrev, 2 * scene->n + 1, &scene->slipIncrement, scene->n + 1, &scene->slipPath, scene->n + 1, &scene->dissipation));
  PetscCall(VecCreateMPI(scene->comm, 3 * scene->n, PETSC_DETERMINE, &scene->offsets));
  if (scene->sliding == SSSTAR_SLIDING_LARGE) { /* the configuration of the first step: the reference */
    PetscCall(DMCreateGlobalVector(scene->dm, &scene->uAccepted));
    PetscCall(VecZeroEntries(scene->uAccepted));
  }
  PetscFunctionReturn(0);
}

/* The offsets of the step (docs/derivation.md (10.4)) from the gaps, frames and slips of its linearization, to the SNES */
static PetscErrorCode SetOffsets(SSStarScene scene, SNES snes)
{
  PetscScalar *oa;

  PetscFunctionBegin;
  PetscCall(VecGetArrayWrite(scene->offsets, &oa));
  for (PetscInt i = 0; i < scene->n; i++) {
    const SSStarContactGroup *cg = &scene->contact[scene->group[i]];
    const PetscReal          *R  = &scene->frame[9 * i];
    PetscReal                 Rd[3] = {0, 0, 0};

    if (cg->motion)
      for (PetscInt k = 0; k < 3; k++) Rd[k] = SSStarDot3(&R[3 * k], cg->d);
    oa[3 * i]     = -scene->slipPrev[2 * i] - Rd[0];
    oa[3 * i + 1] = -scene->slipPrev[2 * i + 1] - Rd[1];
    oa[3 * i + 2] = scene->gap[i] - Rd[2];
  }
  PetscCall(VecRestoreArrayWrite(scene->offsets, &oa));
  PetscCall(SNESSSStarSetContactOffsets(snes, scene->offsets));
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneCheckSteps - checks the steps of a load path before any is solved: the motions of its obstacles at every
   step (SSStarSceneSetStep() checks its own step again)

   Collective

   Input Parameters:
+  scene - the scene, after SSStarSceneSetUp()
.  n     - the number of steps
-  times - their times

   Notes:
   A moved ball, cylinder or mesh obstacle is refused at the first step where its first-order gap g - n.d is off the
   exact gap (the node's distance to the translated obstacle) by more than -small_sliding_tol times |d| at a node
   within |d| of it, with an error naming the obstacle, the step and the error; a plane never is.

   Level: intermediate

.seealso: `SSStarSceneSetStep()`, `SSStarHistoryParseSteps()`
@*/
PetscErrorCode SSStarSceneCheckSteps(SSStarScene scene, PetscInt n, const PetscReal times[])
{
  PetscFunctionBegin;
  for (PetscInt k = 0; k < n; k++) PetscCall(SSStarSceneCheckSmallSliding(scene, k + 1, times[k]));
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneSetStep - sets up the step of a load path to the time t: each moving obstacle's translation d at t and
   the offsets of the contact nodes (docs/derivation.md (10.4)), handed to the SNES (SNESSSStarSetContactOffsets())

   Collective

   Input Parameters:
+  scene - the scene, after SSStarSceneSetContact(snes)
.  snes  - its ssstar SNES
-  t     - the time of the step

   Notes:
   The step starts from the last step accepted by SSStarSceneAcceptStep() (the reference configuration before the
   first): a node against an obstacle gets o = (-w_t^(k-1) - R_t d, g - n.d), a slave node of a contact pair
   o = (-w_t^(k-1), g), w_t^(k-1) its slip after that step. So a node that sticks keeps its position relative to its
   obstacle (or master surface), a sliding one is resisted against the direction of its increment. Solve the step
   from the previous solution with the load at t (SSStarSceneAssembleLoad()); a step that fails may be set again at
   another time.

   With large sliding (-sliding large, the default) the contact is measured again at the current configuration, the
   reference displaced by the last accepted solution, against the obstacles at their translations of the step: gaps,
   normals, frames and a pair's master faces there (the search asked at the current positions), B declared to the SNES
   again (a rigid obstacle's reduction is kept; a pair's new masters reduce K again), g and w_t^(k-1) taken at that
   configuration (docs/derivation.md section 13). With small sliding (-sliding small) every step keeps the reference
   configuration: the normal offset g - n.d is exact for a plane and first order in |d| for a ball, cylinder or mesh,
   and a step where it is off the exact gap by more than -small_sliding_tol times |d| at a node within |d| of the
   obstacle is refused with an error that names the obstacle, the step (its row in the file's /steps) and the error.

   Level: intermediate

.seealso: `SSStarSceneAcceptStep()`, `SSStarSceneAssembleLoad()`, `SNESSSStarSetContactOffsets()`, `SSStarSceneCheckSteps()`, `SSStarSceneCheckStep()`
@*/
PetscErrorCode SSStarSceneSetStep(SSStarScene scene, SNES snes, PetscReal t)
{
  PetscFunctionBegin;
  PetscCall(PathArrays(scene));
  scene->stepTime = t;
  for (PetscInt g = 0; g < scene->nContact; g++) {
    SSStarContactGroup *cg = &scene->contact[g];

    if (cg->motion) PetscCall(SSStarHistoryEvaluate(cg->motion, t, cg->d));
  }
  PetscCall(SSStarSceneCheckSmallSliding(scene, scene->accepted + 1, t));
  if (scene->sliding == SSSTAR_SLIDING_LARGE) PetscCall(SSStarSceneMeasureContact(scene, snes));
  PetscCall(SetOffsets(scene, snes));
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneCheckStep - with large sliding, after a converged solve of the step set by SSStarSceneSetStep(): the
   contact measured at the solution against the one the step was linearized at (docs/derivation.md (13.5))

   Collective

   Input Parameters:
+  scene - the scene
.  snes  - its ssstar SNES, after the solve
-  u     - the solution

   Output Parameters:
+  consistent - whether the contact at u agrees with the step's linearization within -sliding_tol: accept the step
-  again      - when it does not: the step is now linearized at u; solve it again from u and check again (after
                -sliding_max_it linearizations without agreement, consistent and again are both PETSC_FALSE: the
                step is too large, cut it)

   Notes:
   The geometric error is the largest exact gap at u of a node touching there, or penetration of one that is not,
   against -sliding_tol (1e-3) times the largest normal displacement of a touching node. With small sliding, and on
   a static problem, the step is always consistent.

   Level: intermediate

.seealso: `SSStarSceneSetStep()`, `SSStarSceneAcceptStep()`
@*/
PetscErrorCode SSStarSceneCheckStep(SSStarScene scene, SNES snes, Vec u, PetscBool *consistent, PetscBool *again)
{
  PetscReal error, scale;

  PetscFunctionBegin;
  *consistent = PETSC_TRUE;
  *again      = PETSC_FALSE;
  if (scene->sliding != SSSTAR_SLIDING_LARGE || !scene->nContact) PetscFunctionReturn(0);
  PetscCall(SSStarSceneRelinearizeContact(scene, snes, u, consistent, &error, &scale));
  PetscCall(PetscInfo(NULL, "Step at t = %g, linearization %" PetscInt_FMT ": geometric error %g of the normal displacements %g\n", (double)scene->stepTime, scene->relinearizations, (double)error, (double)scale));
  if (*consistent) PetscFunctionReturn(0);
  *again = (PetscBool)(scene->relinearizations < scene->slidingMaxIt);
  scene->relinearizations++;
  PetscCall(SetOffsets(scene, snes));
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneAcceptStep - records the solution of the step set by SSStarSceneSetStep(): the slip of every contact node
   relative to its obstacle or master surface, its increment in the step, the length of its slip path and the energy
   friction dissipated (docs/derivation.md (10.9)); the next step starts from here

   Collective

   Input Parameters:
+  scene - the scene
.  u     - the solution of the step
-  r     - K u - b, whose contact entries are the contact forces (SNESGetFunction() after the solve)

   Notes:
   The output (SSStarSceneWriteSolution(), SSStarSceneOutputStep()) then holds /contact/slip_increment,
   /contact/slip_path and /contact/dissipation; SSStarSceneGetContactResult() the dissipation of each group.

   Level: intermediate

.seealso: `SSStarSceneSetStep()`, `SSStarSceneOutputStep()`
@*/
PetscErrorCode SSStarSceneAcceptStep(SSStarScene scene, Vec u, Vec r)
{
  PetscReal         *w;
  const PetscScalar *ra;
  Vec                rC;

  PetscFunctionBegin;
  PetscCall(PathArrays(scene));
  PetscCall(PetscMalloc1(3 * scene->n + 1, &w));
  PetscCall(SSStarSceneRelativeDisplacement(scene, u, w));
  PetscCall(VecGetSubVector(r, scene->isC, &rC));
  PetscCall(VecGetArrayRead(rC, &ra));
  for (PetscInt i = 0; i < scene->n; i++) {
    const PetscReal *R = &scene->frame[9 * i];
    PetscReal        ri[3], dw[2];

    for (PetscInt k = 0; k < 3; k++) ri[k] = PetscRealPart(ra[3 * i + k]);
    for (PetscInt k = 0; k < 2; k++) {
      dw[k]                          = w[3 * i + k] - scene->slipPrev[2 * i + k];
      scene->slipIncrement[2 * i + k] = dw[k];
      scene->slipPrev[2 * i + k]      = w[3 * i + k];
      scene->dissipation[i] -= SSStarDot3(&R[3 * k], ri) * dw[k]; /* -r_t . dw_t, r_t = R_t r */
    }
    scene->slipPath[i] += PetscSqrtReal(dw[0] * dw[0] + dw[1] * dw[1]);
  }
  PetscCall(VecRestoreArrayRead(rC, &ra));
  PetscCall(VecRestoreSubVector(r, scene->isC, &rC));
  PetscCall(PetscFree(w));
  for (PetscInt g = 0; g < scene->nContact; g++) PetscCall(PetscArraycpy(scene->contact[g].dPrev, scene->contact[g].d, 3));
  if (scene->uAccepted) PetscCall(VecCopy(u, scene->uAccepted)); /* large sliding: the next step's configuration */
  scene->lastLinearization = PETSC_TRUE;
  scene->stepped = PETSC_TRUE;
  scene->accepted++;
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneGetContactGroupCount - the number of contact groups (-contact)

   Not Collective

   Input Parameter:
.  scene - the scene, after SSStarSceneSetFromOptions()

   Output Parameter:
.  n - the number of contact groups

   Level: intermediate

.seealso: `SSStarSceneGetMotion()`, `SSStarSceneGetContactResult()`
@*/
PetscErrorCode SSStarSceneGetContactGroupCount(SSStarScene scene, PetscInt *n)
{
  PetscFunctionBegin;
  *n = scene->nContact;
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneGetMotion - the name of contact group g and the translation of its rigid obstacle in the step set last
   (SSStarSceneSetStep())

   Not Collective

   Input Parameters:
+  scene - the scene
-  g     - the contact group, 0 .. SSStarSceneGetContactGroupCount() - 1, in the order of -contact

   Output Parameters:
+  name   - its name, or pass NULL
.  d      - its obstacle's translation (0 before the first step, or without -obstacle_<G>_motion), or pass NULL
-  moving - whether the group has a motion (-obstacle_<G>_motion), or pass NULL

   Level: intermediate

.seealso: `SSStarSceneSetStep()`, `SSStarSceneGetContactGroupCount()`
@*/
PetscErrorCode SSStarSceneGetMotion(SSStarScene scene, PetscInt g, const char *name[], PetscReal d[3], PetscBool *moving)
{
  PetscFunctionBegin;
  PetscCheck(g >= 0 && g < scene->nContact, scene->comm, PETSC_ERR_ARG_OUTOFRANGE, "Contact group %" PetscInt_FMT ": the scene has %" PetscInt_FMT, g, scene->nContact);
  if (name) *name = scene->contact[g].name;
  if (d) PetscCall(PetscArraycpy(d, scene->contact[g].d, 3));
  if (moving) *moving = (PetscBool)(scene->contact[g].motion != NULL);
  PetscFunctionReturn(0);
}

/* Whether a group of the mesh has cells (a volume group) on some rank */
static PetscErrorCode IsVolumeGroup(SSStarScene scene, const char name[], PetscBool *volume)
{
  DMLabel  label;
  PetscInt cStart, cEnd;

  PetscFunctionBegin;
  *volume = PETSC_FALSE;
  PetscCall(DMGetLabel(scene->dm, name, &label));
  PetscCall(DMPlexGetHeightStratum(scene->dm, 0, &cStart, &cEnd));
  for (PetscInt c = cStart; c < cEnd && label && !*volume; c++) {
    PetscInt value;

    PetscCall(DMLabelGetValue(label, c, &value));
    *volume = (PetscBool)(value >= 0);
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, volume, 1, MPIU_BOOL, MPI_LOR, scene->comm));
  PetscFunctionReturn(0);
}

/* The surface groups the output follows (scene->surfaces): the traction, spring, contact and prescribed-displacement
   surface groups, each once */
PetscErrorCode SSStarSceneFollowSurfaces(SSStarScene scene)
{
  const SSStarGroupValues *lists[2] = {scene->tractions, scene->springs};
  const PetscInt           sizes[2] = {scene->nTractions, scene->nSprings};
  PetscInt                 max      = scene->nTractions + scene->nSprings + scene->nContact + scene->nDisplacements;

  PetscFunctionBegin;
  if (scene->surfaces) PetscFunctionReturn(0);
  PetscCall(PetscCalloc3(max + 1, &scene->surfaces, max + 1, &scene->surfaceWeights, max + 1, &scene->surfaceAreas));
  for (PetscInt k = 0; k < max; k++) {
    const PetscInt  nc   = sizes[0] + sizes[1] + scene->nContact;
    const char     *name = k < sizes[0] ? lists[0][k].name : k < sizes[0] + sizes[1] ? lists[1][k - sizes[0]].name : k < nc ? scene->contact[k - sizes[0] - sizes[1]].name : scene->displacements[k - nc].name;
    PetscBool       seen = PETSC_FALSE, volume = PETSC_FALSE;
    const PetscReal unit[3] = {1, 1, 1};
    Vec             local;

    for (PetscInt j = 0; j < scene->nSurfaces && !seen; j++) PetscCall(PetscStrcmp(name, scene->surfaces[j], &seen));
    if (k >= nc && !seen) PetscCall(IsVolumeGroup(scene, name, &volume));
    if (seen || volume) continue;
    PetscCall(PetscStrallocpy(name, &scene->surfaces[scene->nSurfaces]));
    PetscCall(DMCreateGlobalVector(scene->dm, &scene->surfaceWeights[scene->nSurfaces]));
    PetscCall(DMGetLocalVector(scene->dm, &local));
    PetscCall(VecZeroEntries(local));
    PetscCall(SSStarAddTraction(scene->dm, name, unit, local));
    PetscCall(VecZeroEntries(scene->surfaceWeights[scene->nSurfaces]));
    PetscCall(DMLocalToGlobal(scene->dm, local, ADD_VALUES, scene->surfaceWeights[scene->nSurfaces]));
    PetscCall(DMRestoreLocalVector(scene->dm, &local));
    PetscCall(SSStarGroupArea(scene->dm, name, &scene->surfaceAreas[scene->nSurfaces]));
    scene->nSurfaces++;
  }
  PetscFunctionReturn(0);
}

/*
   The mean displacement of each followed surface (3 per surface, in the order of scene->surfaces), weighted by the
   consistent load of a uniform traction: the work of a uniform traction t on it is (t area) . mean. Held nodes count
   with u = 0.
*/
PetscErrorCode SSStarSceneSurfaceDisplacements(SSStarScene scene, Vec u, PetscReal mean[])
{
  PetscFunctionBegin;
  PetscCall(SSStarSceneFollowSurfaces(scene));
  for (PetscInt s = 0; s < scene->nSurfaces; s++) {
    const PetscScalar *wa, *ua;
    PetscInt           n;

    mean[3 * s] = mean[3 * s + 1] = mean[3 * s + 2] = 0;
    PetscCall(VecGetLocalSize(u, &n));
    PetscCall(VecGetArrayRead(scene->surfaceWeights[s], &wa));
    PetscCall(VecGetArrayRead(u, &ua));
    for (PetscInt i = 0; i < n; i++) mean[3 * s + i % 3] += PetscRealPart(wa[i] * ua[i]);
    PetscCall(VecRestoreArrayRead(u, &ua));
    PetscCall(VecRestoreArrayRead(scene->surfaceWeights[s], &wa));
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, mean, 3 * scene->nSurfaces, MPIU_REAL, MPIU_SUM, scene->comm));
  for (PetscInt s = 0; s < scene->nSurfaces; s++)
    for (PetscInt k = 0; k < 3; k++) mean[3 * s + k] = scene->surfaceAreas[s] > 0 ? mean[3 * s + k] / scene->surfaceAreas[s] : 0;
  PetscFunctionReturn(0);
}

/* Frees what the path and the followed surfaces hold */
PetscErrorCode SSStarScenePathDestroy(SSStarScene scene)
{
  PetscFunctionBegin;
  PetscCall(PetscFree4(scene->slipPrev, scene->slipIncrement, scene->slipPath, scene->dissipation));
  PetscCall(VecDestroy(&scene->offsets));
  PetscCall(VecDestroy(&scene->uAccepted));
  for (PetscInt s = 0; s < scene->nSurfaces; s++) {
    PetscCall(PetscFree(scene->surfaces[s]));
    PetscCall(VecDestroy(&scene->surfaceWeights[s]));
  }
  PetscCall(PetscFree3(scene->surfaces, scene->surfaceWeights, scene->surfaceAreas));
  scene->nSurfaces = 0;
  PetscFunctionReturn(0);
}
