/*
   What the contact nodes of a scene carry at a solution u (r = K u - b, whose contact entries are the contact forces):
   their states, contact area and forces per group, and their kinematics (the gap and slip against the obstacle or the
   master surface, through the contact operator B) and tractions, for the views and the output.
*/
#include "../sceneimpl.h"

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
.  res - the nodes per kind of state, the area of the nodes in contact, the normal force, the force, its tangential part
         and, on a load path, the energy friction dissipated since its start (SSStarSceneAcceptStep())

   Level: intermediate

.seealso: `SSStarSceneContactView()`, `SNESSSStarGetStates()`
@*/
PetscErrorCode SSStarSceneGetContactResult(SSStarScene scene, PetscInt g, Vec r, const SSStarState states[], SSStarContactResult *res)
{
  Vec                rC;
  const PetscScalar *ra;
  PetscReal          sums[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0}; /* area, normal force, force, tangential force, dissipation */
  PetscInt           counts[4] = {0, 0, 0, 0};

  PetscFunctionBegin;
  PetscCall(VecGetSubVector(r, scene->isC, &rC));
  PetscCall(VecGetArrayRead(rC, &ra));
  for (PetscInt i = 0; i < scene->n; i++) {
    const SSStarState s  = states[i];
    PetscReal         rn = 0;
    PetscBool         touching;

    if (g >= 0 && scene->group[i] != g) continue;
    counts[0]++;
    if (s == SSSTAR_STATE_L || s == SSSTAR_STATE_LS) counts[1]++;
    else if (s == SSSTAR_STATE_M1 || s == SSSTAR_STATE_M2) counts[2]++;
    else counts[3]++;
    touching = (PetscBool)(s != SSSTAR_STATE_L && s != SSSTAR_STATE_LS);
    if (touching) sums[0] += scene->area[i];
    for (PetscInt k = 0; k < 3; k++) {
      rn += PetscRealPart(ra[3 * i + k]) * scene->normal[3 * i + k];
      sums[2 + k] += PetscRealPart(ra[3 * i + k]);
    }
    sums[1] += rn;
    for (PetscInt k = 0; k < 3; k++) sums[5 + k] += PetscRealPart(ra[3 * i + k]) - rn * scene->normal[3 * i + k];
    if (scene->stepped) sums[8] += scene->dissipation[i];
  }
  PetscCall(VecRestoreArrayRead(rC, &ra));
  PetscCall(VecRestoreSubVector(r, scene->isC, &rC));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, sums, 9, MPIU_REAL, MPIU_SUM, scene->comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, counts, 4, MPIU_INT, MPI_SUM, scene->comm));
  res->nodes        = counts[0];
  res->separated    = counts[1];
  res->sliding      = counts[2];
  res->sticking     = counts[3];
  res->area         = sums[0];
  res->normal_force = sums[1];
  for (PetscInt k = 0; k < 3; k++) {
    res->force[k]            = sums[2 + k];
    res->tangential_force[k] = sums[5 + k];
  }
  res->dissipation = sums[8];
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

/*
   The contact kinematics and tractions of every contact node at the solution u (r = K u - b), for /contact: gap (the
   normal gap w_n at the solution), pressure (r.n / area), traction (the tangential traction, global axes, 3 per node)
   and slip (the tangential relative displacement w_t: the slave node against the master surface, or against the
   rigid obstacle where it is in the step set last; global axes, 3 per node), in the order of the contact nodes.
*/
PetscErrorCode SSStarSceneContactKinematics(SSStarScene scene, Vec u, Vec r, PetscReal gap[], PetscReal pressure[], PetscReal traction[], PetscReal slip[])
{
  const PetscInt     n = scene->n;
  const PetscScalar *ra;
  PetscReal         *wa;
  Vec                rC;

  PetscFunctionBegin;
  PetscCall(PetscMalloc1(3 * n + 1, &wa));
  PetscCall(SSStarSceneRelativeDisplacement(scene, u, wa));
  PetscCall(VecGetSubVector(r, scene->isC, &rC));
  PetscCall(VecGetArrayRead(rC, &ra));
  for (PetscInt i = 0; i < n; i++) {
    const PetscReal *nn = &scene->normal[3 * i];
    const PetscReal *R  = &scene->frame[9 * i];
    PetscReal        rn = 0, d[3], dn = 0;

    for (PetscInt k = 0; k < 3; k++) d[k] = R[k] * wa[3 * i] + R[3 + k] * wa[3 * i + 1] + R[6 + k] * wa[3 * i + 2]; /* R^T w: global axes */
    for (PetscInt k = 0; k < 3; k++) {
      rn += PetscRealPart(ra[3 * i + k]) * nn[k];
      dn += d[k] * nn[k];
    }
    gap[i]      = dn + scene->gap[i];
    pressure[i] = scene->area[i] > 0 ? rn / scene->area[i] : 0;
    for (PetscInt k = 0; k < 3; k++) {
      traction[3 * i + k] = scene->area[i] > 0 ? (PetscRealPart(ra[3 * i + k]) - rn * nn[k]) / scene->area[i] : 0;
      slip[3 * i + k]     = d[k] - dn * nn[k];
    }
  }
  PetscCall(VecRestoreArrayRead(rC, &ra));
  PetscCall(VecRestoreSubVector(r, scene->isC, &rC));
  PetscCall(PetscFree(wa));
  PetscFunctionReturn(0);
}

/*
   w - g e3 of every contact node at u, in its frame (3 per node): B u, less R d_i for a node whose obstacle's point it
   faces has moved by d_i in the step set last (docs/derivation.md (10.1), (16.3)); w_t is the slip relative to the
   obstacle or master surface
*/
PetscErrorCode SSStarSceneRelativeDisplacement(SSStarScene scene, Vec u, PetscReal w[])
{
  const PetscScalar *wa;
  Vec                Bu;

  PetscFunctionBegin;
  PetscCall(MatCreateVecs(scene->B, NULL, &Bu));
  PetscCall(MatMult(scene->B, u, Bu));
  PetscCall(VecGetArrayRead(Bu, &wa));
  for (PetscInt i = 0; i < scene->n; i++) {
    PetscReal d[3];

    SSStarSceneObstacleDisplacement(scene, i, &scene->contact[scene->group[i]].motion.now, d);
    for (PetscInt k = 0; k < 3; k++) w[3 * i + k] = PetscRealPart(wa[3 * i + k]) - SSStarDot3(&scene->frame[9 * i + 3 * k], d);
  }
  PetscCall(VecRestoreArrayRead(Bu, &wa));
  PetscCall(VecDestroy(&Bu));
  PetscFunctionReturn(0);
}
