/*
   The reaction forces of the held groups (-dirichlet, -displacement_<G>): the force each prescription exerts on the
   body, r = K u - b summed over the group's held components in global axes (the convention of /contact/reaction), with
   K the stiffness before the identity rows (every cell's matrix, the springs) and b the tractions and gravity there
   (docs/derivation.md section 15). A cell (or a face) is on one rank: each rank sums its cells' contributions.
*/
#include "../sceneimpl.h"

/*@C
   SSStarSceneGetHeldGroups - the groups that hold nodes: the -dirichlet groups, then the -displacement_<G> groups, in
   the order of the reactions SSStarSceneGetReactions() gives

   Not Collective

   Input Parameter:
.  scene - the scene, after SSStarSceneSetFromOptions()

   Output Parameters:
+  n     - the number of held groups, or pass NULL
-  names - their names (owned by the scene), or pass NULL

   Notes:
   A node held by several groups counts, component by component, in the first of them in this order.

   Level: intermediate

.seealso: `SSStarSceneGetReactions()`
@*/
PetscErrorCode SSStarSceneGetHeldGroups(SSStarScene scene, PetscInt *n, const char *const *names[])
{
  const PetscInt nheld = scene->nDirichlet + scene->nDisplacements;

  PetscFunctionBegin;
  if (n) *n = nheld;
  if (!names) PetscFunctionReturn(0);
  PetscCall(PetscFree(scene->heldNames));
  PetscCall(PetscMalloc1(nheld + 1, &scene->heldNames));
  for (PetscInt h = 0; h < nheld; h++) scene->heldNames[h] = h < scene->nDirichlet ? scene->dirichlet[h] : scene->displacements[h - scene->nDirichlet].name;
  *names = (const char *const *)scene->heldNames;
  PetscFunctionReturn(0);
}

/*
   SSStarSceneLoadFactor - the factor of a load b against the load the scene assembled last (SSStarAssembleLoad()): b is
   that load or a multiple of it (a step of -load_steps); 1 when the last load is zero
*/
PetscErrorCode SSStarSceneLoadFactor(SSStarScene scene, Vec b, PetscReal *alpha)
{
  PetscScalar bl, ll;

  PetscFunctionBegin;
  *alpha = 1;
  if (!scene->lastLoad || !b) PetscFunctionReturn(0);
  PetscCall(VecDot(b, scene->lastLoad, &bl));
  PetscCall(VecDot(scene->lastLoad, scene->lastLoad, &ll));
  if (PetscRealPart(ll) > 0) *alpha = PetscRealPart(bl) / PetscRealPart(ll);
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneGetReactions - the reaction force of every held group at the displacement u: the force its prescription
   exerts on the body, the sum of r = K u - b over its held components (global axes; the convention of
   /contact/reaction), with K the stiffness of the elastic body (and its springs) and b the tractions and gravity

   Collective

   Input Parameters:
+  scene - the scene, after SSStarSceneAssemble()
.  snes  - the SNES that solved u (its load, -F(0), may be a multiple of the scene's: -load_steps), or NULL for the
           load the scene assembled last
-  u     - the displacement (a global vector of the scene's DM)

   Output Parameter:
.  reaction - 3 per held group (SSStarSceneGetHeldGroups()), the same on every rank

   Notes:
   The file's /groups/<G>/reaction and, on a load path, /steps/groups/<G>/reaction. With the contact forces and the
   loads they balance: the sum of the reactions, of the contact forces on obstacles and of the loads (the tractions and
   gravity of every node, held ones included) is zero (docs/derivation.md section 15).

   Level: intermediate

.seealso: `SSStarSceneGetHeldGroups()`, `SSStarSceneGetContactResult()`, `SSStarSceneGetLoadResultant()`
@*/
PetscErrorCode SSStarSceneGetReactions(SSStarScene scene, SNES snes, Vec u, PetscReal reaction[])
{
  const PetscInt     nheld = scene->nDirichlet + scene->nDisplacements;
  DM                 dm    = scene->dm;
  PetscSection       sec;
  Vec                uloc, wloc;
  const PetscScalar *ua;
  PetscReal          alpha = 1;
  SSStarCells        cells;

  PetscFunctionBegin;
  for (PetscInt k = 0; k < 3 * nheld; k++) reaction[k] = 0;
  if (!nheld) PetscFunctionReturn(0);
  if (snes) { /* the load of the solve: -F(0) */
    Vec zero, b;

    PetscCall(VecDuplicate(u, &zero));
    PetscCall(VecDuplicate(u, &b));
    PetscCall(VecZeroEntries(zero));
    PetscCall(SNESComputeFunction(snes, zero, b));
    PetscCall(VecScale(b, -1.0));
    PetscCall(SSStarSceneLoadFactor(scene, b, &alpha));
    PetscCall(VecDestroy(&zero));
    PetscCall(VecDestroy(&b));
  }
  PetscCall(DMGetLocalSection(dm, &sec));
  PetscCall(DMGetLocalVector(dm, &uloc));
  PetscCall(VecZeroEntries(uloc)); /* the -dirichlet dofs: 0 */
  PetscCall(DMGlobalToLocal(dm, u, INSERT_VALUES, uloc));
  PetscCall(VecGetArrayRead(uloc, &ua));
  PetscCall(SSStarCellsBegin(scene, &cells));
  for (PetscInt c = 0; c < cells.cEnd - cells.cStart; c++) { /* K u at the held components of the cell's vertices */
    const PetscInt *v = &cells.vertices[4 * c];
    PetscInt        off[4];
    PetscReal       x[12], ue[12];
    PetscScalar     Ke[144];
    PetscBool       held = PETSC_FALSE;

    for (PetscInt a = 0; a < 4; a++)
      for (PetscInt k = 0; k < 3; k++) held = (PetscBool)(held || scene->heldBy[3 * v[a] + k] >= 0);
    if (!held) continue;
    for (PetscInt a = 0; a < 4; a++) {
      PetscCall(PetscSectionGetOffset(sec, cells.vStart + v[a], &off[a]));
      for (PetscInt k = 0; k < 3; k++) ue[3 * a + k] = PetscRealPart(ua[off[a] + k]);
    }
    PetscCall(SSStarCellsGet(&cells, c, x));
    SSStarTetStiffness(x, cells.lame[c][0], cells.lame[c][1], Ke);
    for (PetscInt a = 0; a < 4; a++)
      for (PetscInt k = 0; k < 3; k++) {
        const PetscInt h = scene->heldBy[3 * v[a] + k];
        PetscReal      f = 0;

        if (h < 0) continue;
        for (PetscInt j = 0; j < 12; j++) f += PetscRealPart(Ke[12 * (3 * a + k) + j]) * ue[j];
        reaction[3 * h + k] += f;
      }
  }
  PetscCall(SSStarCellsEnd(&cells));
  PetscCall(DMGetLocalVector(dm, &wloc)); /* the springs: k area/3 per face vertex, each rank its faces */
  for (PetscInt s = 0; s < scene->nSprings; s++) {
    const PetscReal    k3[3] = {scene->springs[s].value[0], scene->springs[s].value[0], scene->springs[s].value[0]};
    const PetscScalar *wa;
    PetscInt           vStart, vEnd;

    PetscCall(VecZeroEntries(wloc));
    PetscCall(SSStarAddTraction(dm, scene->springs[s].name, k3, wloc));
    PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
    PetscCall(VecGetArrayRead(wloc, &wa));
    for (PetscInt v = vStart; v < vEnd; v++) {
      PetscInt off;

      PetscCall(PetscSectionGetOffset(sec, v, &off));
      for (PetscInt k = 0; k < 3; k++) {
        const PetscInt h = scene->heldBy[3 * (v - vStart) + k];

        if (h >= 0) reaction[3 * h + k] += PetscRealPart(wa[off + k] * ua[off + k]);
      }
    }
    PetscCall(VecRestoreArrayRead(wloc, &wa));
  }
  PetscCall(DMRestoreLocalVector(dm, &wloc));
  PetscCall(VecRestoreArrayRead(uloc, &ua));
  PetscCall(DMRestoreLocalVector(dm, &uloc));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, reaction, 3 * nheld, MPIU_REAL, MPIU_SUM, scene->comm));
  for (PetscInt k = 0; k < 3 * nheld; k++) reaction[k] -= alpha * (scene->loadHeld ? scene->loadHeld[k] : 0);
  PetscFunctionReturn(0);
}
