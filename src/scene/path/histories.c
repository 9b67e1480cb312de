/*
   A scene's histories changed after it was described: a program's own load path decides the next load or obstacle
   position from the steps solved so far (the Python module's Scene.set()), through the same options' values.
*/
#include "../sceneimpl.h"

/* The history of -traction_<G>, -gravity or -obstacle_<G>_motion, to be replaced; the value at its last knot, if any
   (-displacement_<G>: SSStarSceneSetHistory()) */
static PetscErrorCode FindHistory(SSStarScene scene, const char option[], SSStarHistory **history, PetscReal **last)
{
  PetscBool match;
  size_t    len;

  PetscFunctionBegin;
  *history = NULL;
  *last    = NULL;
  PetscCall(PetscStrcmp(option, "-gravity", &match));
  if (match) {
    PetscCheck(scene->hasGravity, scene->comm, PETSC_ERR_ARG_WRONG, "Option %s: the scene has no gravity (give -gravity and -density when it is made)", option);
    *history = &scene->gravityHistory;
    *last    = scene->gravity;
    PetscFunctionReturn(0);
  }
  PetscCall(PetscStrncmp(option, "-traction_", 10, &match));
  if (match) {
    for (PetscInt t = 0; t < scene->nTractions && !*history; t++) {
      PetscCall(PetscStrcmp(option + 10, scene->tractions[t].name, &match));
      if (match) {
        *history = &scene->tractions[t].history;
        *last    = scene->tractions[t].value;
      }
    }
    PetscCheck(*history, scene->comm, PETSC_ERR_ARG_WRONG, "Option %s: the scene has no traction on %s (give it when the scene is made, 0,0,0 if need be)", option, option + 10);
    PetscFunctionReturn(0);
  }
  PetscCall(PetscStrlen(option, &len));
  PetscCall(PetscStrncmp(option, "-obstacle_", 10, &match));
  if (match && len > 17 && !strcmp(option + len - 7, "_motion"))
    for (PetscInt g = 0; g < scene->nContact && !*history; g++) {
      size_t glen;

      PetscCall(PetscStrlen(scene->contact[g].name, &glen));
      if (glen == len - 17 && !strncmp(option + 10, scene->contact[g].name, glen)) {
        PetscCheck(scene->contact[g].motion, scene->comm, PETSC_ERR_ARG_WRONG, "Option %s: the obstacle of %s has no motion (give -obstacle_%s_motion when the scene is made, 0,0,0 if need be)", option, scene->contact[g].name, scene->contact[g].name);
        *history = &scene->contact[g].motion;
      }
    }
  PetscCheck(*history, scene->comm, PETSC_ERR_ARG_WRONG, "Option %s: not a history of the scene (-traction_<G>, -gravity, -obstacle_<G>_motion, -displacement_<G>)", option);
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneSetHistory - changes a load or an obstacle's motion of the scene: gives one of its history options a new
   value, as the option would (docs/guide/load-paths.md), between the steps of a load path

   Collective

   Input Parameters:
+  scene  - the scene, after SSStarSceneSetFromOptions()
.  option - the option: -traction_<G> (a traction the scene has), -gravity (if the scene has gravity),
            -obstacle_<G>_motion (a motion the scene has) or -displacement_<G> (a prescribed displacement the scene
            has, with the same components free)
-  value  - its new value: a constant x,y,z, or a history t:x,y,z;t:x,y,z;... (linear between the knots, constant
            outside)

   Notes:
   The next step (SSStarSceneAssembleLoad(), SSStarSceneSetStep()) takes the new value at its time; the steps solved
   keep what they were solved with. So a program's own loop decides the next load or obstacle position from the steps
   before (the Python module's Scene.set()). The scene's description (SSStarSceneView(), /scene of the output) shows
   the new value. Loads and motions the scene does not have are refused: the columns of the table of the steps are
   fixed when the scene is made.

   Level: intermediate

.seealso: `SSStarSceneSetStep()`, `SSStarSceneAssembleLoad()`, `SSStarSceneGetKnots()`, `SSStarHistoryCreateFromString()`
@*/
PetscErrorCode SSStarSceneSetHistory(SSStarScene scene, const char option[], const char value[])
{
  SSStarHistory *history, h;
  PetscReal     *last;

  PetscFunctionBegin;
  PetscCheck(option && value, scene->comm, PETSC_ERR_ARG_NULL, "SSStarSceneSetHistory(): give the option and its value");
  for (PetscInt d = 0; d < scene->nDisplacements; d++) { /* a prescribed displacement: the same components free */
    SSStarPrescribed *p = &scene->displacements[d], q = {"", NULL, 0};
    char              name[SSSTAR_GROUP_NAME_LEN + 16];
    PetscBool         match;

    PetscCall(PetscSNPrintf(name, sizeof(name), "-displacement_%s", p->name));
    PetscCall(PetscStrcmp(option, name, &match));
    if (!match) continue;
    PetscCall(SSStarPrescribedRead(scene, option, p->name, value, &q));
    if (q.free != p->free) {
      PetscCall(SSStarHistoryDestroy(&q.history));
      SETERRQ(scene->comm, PETSC_ERR_ARG_WRONG, "Option %s %s: the free components of a prescribed displacement are fixed when the scene is made (K holds them)", option, value);
    }
    PetscCall(SSStarHistoryDestroy(&p->history));
    p->history = q.history;
    PetscFunctionReturn(0);
  }
  PetscCall(FindHistory(scene, option, &history, &last));
  PetscCall(SSStarHistoryCreateFromString(scene->comm, option, value, 3, &h));
  PetscCall(SSStarHistoryDestroy(history));
  *history = h;
  if (last) PetscCall(SSStarSceneLastValue(h, last));
  PetscFunctionReturn(0);
}
