/*
   The bodies of a scene: the connected components of its mesh (cells sharing a vertex), each named by the smallest file
   index of its nodes. A body is held by a -dirichlet or -spring_<G> group, by prescribed displacements
   (-displacement_<G>), or by contact alone: a contact group of its own against a rigid obstacle, or a contact pair with
   a body held so (the pairs chain them). A body no -dirichlet or -spring_<G> holds floats: its rigid-body motions that
   its prescribed displacements leave free are K's null space (modes.c), which the solver needs (docs/derivation.md
   sections 14, 15). A body nothing can hold (no such group, no such pair) is refused, named by its volume groups. Contact
   pairs (pairs.c) are between two bodies.
*/
#include "../sceneimpl.h"
#include <petscsf.h>

#define SSSTAR_MAX_VOLUME_GROUPS 62 /* bits of the body's volume-group mask */
#define SSSTAR_MAX_CONTACT_MASK  63 /* bits of the body's contact-group masks */
/* per body: its number, held (-dirichlet, -spring_<G>), volume groups, contact groups, master surfaces of pairs on
   it (bit g: the master of contact group g), held through contact (set after the merge), prescribed displacements */
#define SSSTAR_BODY_INFO 7

/* union-find with path halving */
static PetscInt Find(PetscInt parent[], PetscInt v)
{
  while (parent[v] != v) {
    parent[v] = parent[parent[v]];
    v         = parent[v];
  }
  return v;
}

/* The labels of the groups that hold a body: -dirichlet and -spring_<G> */
static PetscErrorCode HoldingLabels(SSStarScene scene, PetscInt *n, DMLabel **labels)
{
  PetscFunctionBegin;
  PetscCall(PetscMalloc1(scene->nDirichlet + scene->nSprings + 1, labels));
  *n = 0;
  for (PetscInt g = 0; g < scene->nDirichlet; g++) PetscCall(DMGetLabel(scene->dm, scene->dirichlet[g], &(*labels)[(*n)++]));
  for (PetscInt g = 0; g < scene->nSprings; g++) PetscCall(DMGetLabel(scene->dm, scene->springs[g].name, &(*labels)[(*n)++]));
  PetscFunctionReturn(0);
}

/* The labels of the contact groups and of their pairs' master surfaces (NULL for an obstacle) */
static PetscErrorCode ContactLabels(SSStarScene scene, DMLabel **slave, DMLabel **master)
{
  PetscFunctionBegin;
  PetscCheck(scene->nContact <= SSSTAR_MAX_CONTACT_MASK, scene->comm, PETSC_ERR_SUP, "-contact: at most %d contact groups", SSSTAR_MAX_CONTACT_MASK);
  PetscCall(PetscCalloc2(scene->nContact + 1, slave, scene->nContact + 1, master));
  for (PetscInt g = 0; g < scene->nContact; g++) {
    PetscCall(DMGetLabel(scene->dm, scene->contact[g].name, &(*slave)[g]));
    if (scene->contact[g].master[0]) PetscCall(DMGetLabel(scene->dm, scene->contact[g].master, &(*master)[g]));
  }
  PetscFunctionReturn(0);
}

/* "volume group \"a\", \"b\" (the mesh nodes connected to node 12, 0-based file order)" of a merged entry */
static PetscErrorCode BodyName(const long long a[], PetscInt nvol, const char *volName[], char name[], size_t len)
{
  char names[1024] = "";

  PetscFunctionBegin;
  for (PetscInt l = 0; l < nvol; l++)
    if (a[2] & (1LL << l)) {
      if (names[0]) PetscCall(PetscStrlcat(names, ", ", sizeof(names)));
      PetscCall(PetscStrlcat(names, "\"", sizeof(names)));
      PetscCall(PetscStrlcat(names, volName[l], sizeof(names)));
      PetscCall(PetscStrlcat(names, "\"", sizeof(names)));
    }
  PetscCall(PetscSNPrintf(name, len, "volume group %s (the mesh nodes connected to node %lld, 0-based file order)", names[0] ? names : "(none)", a[0]));
  PetscFunctionReturn(0);
}

/*
   Which bodies contact can hold (entry field 5): held ones, those with a contact group against an obstacle, and, through
   every contact pair, the bodies of its slave group and of its master surface together once one of them is
*/
static PetscErrorCode HeldThroughContact(SSStarScene scene, PetscMPIInt nent, long long all[])
{
  long long obstacles = 0;
  PetscBool changed   = PETSC_TRUE;

  PetscFunctionBegin;
  for (PetscInt g = 0; g < scene->nContact; g++)
    if (!scene->contact[g].master[0]) obstacles |= 1LL << g;
  for (PetscMPIInt e = 0; e < nent; e++) {
    long long *a = &all[SSSTAR_BODY_INFO * e];

    a[5] = a[0] >= 0 && (a[1] || a[6] || (a[3] & obstacles));
  }
  while (changed) {
    changed = PETSC_FALSE;
    for (PetscInt g = 0; g < scene->nContact; g++) {
      const long long bit = 1LL << g;
      PetscBool       one = PETSC_FALSE;

      if (obstacles & bit) continue;
      for (PetscMPIInt e = 0; e < nent; e++) {
        const long long *a = &all[SSSTAR_BODY_INFO * e];

        if (a[0] >= 0 && a[5] && ((a[3] | a[4]) & bit)) one = PETSC_TRUE;
      }
      for (PetscMPIInt e = 0; e < nent && one; e++) {
        long long *a = &all[SSSTAR_BODY_INFO * e];

        if (a[0] >= 0 && !a[5] && ((a[3] | a[4]) & bit)) {
          a[5]    = 1;
          changed = PETSC_TRUE;
        }
      }
    }
  }
  PetscFunctionReturn(0);
}

/* Refuses a body nothing can hold (the first in file order); those held by contact alone are the floating bodies */
static PetscErrorCode RecordFloating(SSStarScene scene, PetscMPIInt nent, const long long all[], PetscInt nvol, const char *volName[])
{
  char             name[1280];
  const long long *loose = NULL;

  PetscFunctionBegin;
  for (PetscMPIInt e = 0; e < nent; e++) {
    const long long *a = &all[SSSTAR_BODY_INFO * e];

    if (a[0] >= 0 && !a[5] && (!loose || a[0] < loose[0])) loose = a;
  }
  if (loose) {
    PetscCall(BodyName(loose, nvol, volName, name, sizeof(name)));
    SETERRQ(scene->comm, PETSC_ERR_ARG_WRONG, "The body of %s, one of %" PetscInt_FMT " bodies, is held by nothing: no -dirichlet, -displacement_<G> or -spring_<G> group, no contact group against an obstacle (-contact), no contact pair with a body held so. Hold it by one of them", name, scene->nBodies);
  }
  PetscCall(SSStarSceneDestroyFloating(scene));
  for (PetscMPIInt e = 0; e < nent; e++) scene->nFloating += all[SSSTAR_BODY_INFO * e] >= 0 && !all[SSSTAR_BODY_INFO * e + 1];
  PetscCall(PetscMalloc2(scene->nFloating, &scene->floating, scene->nFloating, &scene->floatingName));
  scene->nFloating = 0;
  for (PetscMPIInt e = 0; e < nent; e++) {
    const long long *a = &all[SSSTAR_BODY_INFO * e];

    if (a[0] < 0 || a[1]) continue;
    PetscCall(BodyName(a, nvol, volName, name, sizeof(name)));
    scene->floating[scene->nFloating] = (PetscInt)a[0];
    PetscCall(PetscStrallocpy(name, &scene->floatingName[scene->nFloating++]));
  }
  PetscFunctionReturn(0);
}

/* Frees the floating bodies' record */
PetscErrorCode SSStarSceneDestroyFloating(SSStarScene scene)
{
  PetscFunctionBegin;
  for (PetscInt k = 0; k < scene->nFloating; k++) PetscCall(PetscFree(scene->floatingName[k]));
  PetscCall(PetscFree2(scene->floating, scene->floatingName));
  scene->nFloating = 0;
  PetscFunctionReturn(0);
}

/*
   The bodies: connected components of the mesh (cells sharing a vertex), each named by the smallest file index of
   its nodes; scene->body[v] for every local vertex. A body no -dirichlet, -spring_<G> or contact can hold is refused,
   naming it; those held by contact alone are recorded as floating.
*/
PetscErrorCode SSStarSceneFindBodies(SSStarScene scene)
{
  DM                 dm = scene->dm;
  PetscSF            sf;
  PetscInt           pStart, pEnd, vStart, vEnd, cStart, cEnd, nroots, nhold = 0, nlabels, nvol = 0, nloc = 0;
  PetscInt          *parent, *comp, *copy, *setMin;
  DMLabel           *hold, vol[SSSTAR_MAX_VOLUME_GROUPS];
  const char        *volName[SSSTAR_MAX_VOLUME_GROUPS];
  long long         *loc, *all;
  PetscMPIInt        size, *counts, *displs, total = 0, nent;
  DMLabel           *slave, *master;
  const PetscScalar *ta;
  PetscBool          changed = PETSC_TRUE;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(scene->comm, &size));
  PetscCall(DMPlexGetChart(dm, &pStart, &pEnd));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  PetscCall(PetscMalloc4(vEnd - vStart, &parent, pEnd - pStart, &comp, pEnd - pStart, &copy, vEnd - vStart, &setMin));
  for (PetscInt v = 0; v < vEnd - vStart; v++) parent[v] = v;
  for (PetscInt c = cStart; c < cEnd; c++) {
    PetscInt v[4], first;

    PetscCall(SSStarMeshCellVertices(dm, c, v));
    first = Find(parent, v[0] - vStart);
    for (PetscInt k = 1; k < 4; k++) parent[Find(parent, v[k] - vStart)] = first;
  }
  PetscCall(VecGetArrayRead(scene->tags, &ta));
  for (PetscInt p = 0; p < pEnd - pStart; p++) comp[p] = PETSC_MAX_INT;
  for (PetscInt v = vStart; v < vEnd; v++) comp[v - pStart] = (PetscInt)PetscRealPart(ta[v - vStart]);
  PetscCall(VecRestoreArrayRead(scene->tags, &ta));
  /* the smallest index of each local component, then across the ranks through the shared vertices, until stable */
  PetscCall(DMGetPointSF(dm, &sf));
  PetscCall(PetscSFGetGraph(sf, &nroots, NULL, NULL, NULL));
  while (changed) {
    changed = PETSC_FALSE;
    for (PetscInt v = 0; v < vEnd - vStart; v++) setMin[v] = PETSC_MAX_INT;
    for (PetscInt v = 0; v < vEnd - vStart; v++) {
      const PetscInt r = Find(parent, v);

      setMin[r] = PetscMin(setMin[r], comp[v + vStart - pStart]);
    }
    for (PetscInt v = 0; v < vEnd - vStart; v++) {
      const PetscInt m = setMin[Find(parent, v)];

      if (comp[v + vStart - pStart] != m) changed = PETSC_TRUE;
      comp[v + vStart - pStart] = m;
    }
    if (size > 1 && nroots >= 0) {
      PetscCall(PetscArraycpy(copy, comp, pEnd - pStart));
      PetscCall(PetscSFReduceBegin(sf, MPIU_INT, copy, comp, MPI_MIN));
      PetscCall(PetscSFReduceEnd(sf, MPIU_INT, copy, comp, MPI_MIN));
      PetscCall(PetscArraycpy(copy, comp, pEnd - pStart));
      PetscCall(PetscSFBcastBegin(sf, MPIU_INT, copy, comp, MPI_REPLACE));
      PetscCall(PetscSFBcastEnd(sf, MPIU_INT, copy, comp, MPI_REPLACE));
      for (PetscInt v = vStart; v < vEnd && !changed; v++)
        if (comp[v - pStart] != copy[v - pStart]) changed = PETSC_TRUE;
    }
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &changed, 1, MPIU_BOOL, MPI_LOR, scene->comm));
  }
  PetscCall(PetscFree(scene->body));
  PetscCall(PetscMalloc1(vEnd - vStart, &scene->body));
  for (PetscInt v = vStart; v < vEnd; v++) scene->body[v - vStart] = comp[v - pStart];

  /* the volume groups (labels on cells somewhere), to name the bodies */
  PetscCall(DMGetNumLabels(dm, &nlabels));
  for (PetscInt l = 0; l < nlabels; l++) {
    const char *name;
    DMLabel     label;
    PetscBool   cells = PETSC_FALSE, skip;

    PetscCall(DMGetLabelName(dm, l, &name));
    PetscCall(PetscStrcmp(name, "depth", &skip));
    if (!skip) PetscCall(PetscStrcmp(name, "celltype", &skip));
    if (!skip) {
      PetscCall(DMGetLabel(dm, name, &label));
      for (PetscInt c = cStart; c < cEnd && !cells; c++) {
        PetscInt value;

        PetscCall(DMLabelGetValue(label, c, &value));
        cells = (PetscBool)(value >= 0);
      }
    }
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &cells, 1, MPIU_BOOL, MPI_LOR, scene->comm));
    if (cells && nvol < SSSTAR_MAX_VOLUME_GROUPS) {
      volName[nvol] = name;
      PetscCall(DMGetLabel(dm, name, &vol[nvol++]));
    }
  }

  /* per local component: (body, held, volume groups, contact groups, master surfaces), merged over the ranks */
  PetscCall(HoldingLabels(scene, &nhold, &hold));
  PetscCall(ContactLabels(scene, &slave, &master));
  PetscCall(PetscCalloc1(SSSTAR_BODY_INFO * (vEnd - vStart) + SSSTAR_BODY_INFO, &loc));
  for (PetscInt v = 0; v < vEnd - vStart; v++) setMin[v] = -1; /* the entry of each local set */
  for (PetscInt v = vStart; v < vEnd; v++) {
    const PetscInt r = Find(parent, v - vStart);
    PetscBool      held = PETSC_FALSE;
    long long     *e;

    if (setMin[r] < 0) {
      setMin[r]                         = nloc++;
      loc[SSSTAR_BODY_INFO * setMin[r]] = comp[v - pStart];
    }
    e = &loc[SSSTAR_BODY_INFO * setMin[r]];
    for (PetscInt g = 0; g < nhold && !held; g++) {
      PetscInt value;

      PetscCall(DMLabelGetValue(hold[g], v, &value));
      held = (PetscBool)(value >= 0);
    }
    if (held) e[1] = 1;
    if (scene->heldBy[3 * (v - vStart)] >= 0 || scene->heldBy[3 * (v - vStart) + 1] >= 0 || scene->heldBy[3 * (v - vStart) + 2] >= 0) e[6] = 1;
    for (PetscInt g = 0; g < scene->nContact; g++) {
      PetscInt value;

      PetscCall(DMLabelGetValue(slave[g], v, &value));
      if (value >= 0) e[3] |= 1LL << g;
      if (!master[g]) continue;
      PetscCall(DMLabelGetValue(master[g], v, &value));
      if (value >= 0) e[4] |= 1LL << g;
    }
  }
  for (PetscInt c = cStart; c < cEnd; c++) {
    PetscInt v[4], e;

    PetscCall(SSStarMeshCellVertices(dm, c, v));
    e = setMin[Find(parent, v[0] - vStart)];
    for (PetscInt l = 0; l < nvol && e >= 0; l++) {
      PetscInt value;

      PetscCall(DMLabelGetValue(vol[l], c, &value));
      if (value >= 0) loc[SSSTAR_BODY_INFO * e + 2] |= 1LL << l;
    }
  }
  PetscCall(PetscFree(hold));
  PetscCall(PetscFree2(slave, master));
  PetscCall(PetscMalloc2(size, &counts, size, &displs));
  {
    PetscMPIInt mine = (PetscMPIInt)(SSSTAR_BODY_INFO * nloc);

    PetscCallMPI(MPI_Allgather(&mine, 1, MPI_INT, counts, 1, MPI_INT, scene->comm));
  }
  for (PetscMPIInt r = 0; r < size; r++) {
    displs[r] = total;
    total += counts[r];
  }
  PetscCall(PetscMalloc1(total + SSSTAR_BODY_INFO, &all));
  PetscCallMPI(MPI_Allgatherv(loc, SSSTAR_BODY_INFO * (PetscMPIInt)nloc, MPI_LONG_LONG, all, counts, displs, MPI_LONG_LONG, scene->comm));
  /* merge: the same body on several ranks, into its first entry (the others' body set to -1) */
  nent           = total / SSSTAR_BODY_INFO;
  scene->nBodies = 0;
  for (PetscMPIInt e = 0; e < nent; e++) {
    long long *a = &all[SSSTAR_BODY_INFO * e];

    if (a[0] < 0) continue;
    for (PetscMPIInt f = e + 1; f < nent; f++) {
      long long *b = &all[SSSTAR_BODY_INFO * f];

      if (b[0] != a[0]) continue;
      for (PetscInt k = 1; k < SSSTAR_BODY_INFO; k++) a[k] |= b[k];
      b[0] = -1;
    }
    scene->nBodies++;
  }
  PetscCall(HeldThroughContact(scene, nent, all));
  PetscCall(RecordFloating(scene, nent, all, nvol, volName));
  PetscCall(PetscFree(all));
  PetscCall(PetscFree2(counts, displs));
  PetscCall(PetscFree(loc));
  PetscCall(PetscFree4(parent, comp, copy, setMin));
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneViewNoEquilibrium - after a solve that found no equilibrium (SSSTAR_REASON_NO_EQUILIBRIUM), one line: the
   floating body of the scene that goes away, the direction it slides in and the load its contacts cannot balance;
   nothing after any other solve

   Collective

   Input Parameters:
+  scene  - the scene
.  snes   - the SNES of its solve
-  viewer - an ASCII viewer

   Level: intermediate

.seealso: `SNESSSStarGetUnbalancedMotion()`, `SNESSSStarGetReason()`
@*/
PetscErrorCode SSStarSceneViewNoEquilibrium(SSStarScene scene, SNES snes, PetscViewer viewer)
{
  SSStarReason       reason;
  Vec                motion, mloc;
  PetscReal          direction[3], unbalanced, *share;
  PetscSection       sec;
  PetscInt           vStart, vEnd, moving = 0;
  const PetscScalar *ma;
  PetscBool          isssstar;

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)snes, SNESSSSTAR, &isssstar));
  if (!isssstar) PetscFunctionReturn(0);
  PetscCall(SNESSSStarGetReason(snes, &reason));
  if (reason != SSSTAR_REASON_NO_EQUILIBRIUM) PetscFunctionReturn(0);
  PetscCall(SNESSSStarGetUnbalancedMotion(snes, &motion, NULL, direction, &unbalanced));
  /* the floating body whose nodes the motion moves most */
  PetscCall(PetscCalloc1(scene->nFloating + 1, &share));
  PetscCall(DMGetLocalVector(scene->dm, &mloc));
  PetscCall(DMGlobalToLocal(scene->dm, motion, INSERT_VALUES, mloc));
  PetscCall(DMGetLocalSection(scene->dm, &sec));
  PetscCall(DMPlexGetDepthStratum(scene->dm, 0, &vStart, &vEnd));
  PetscCall(VecGetArrayRead(mloc, &ma));
  for (PetscInt v = vStart; v < vEnd; v++) {
    PetscInt dof, off;

    PetscCall(PetscSectionGetDof(sec, v, &dof));
    PetscCall(PetscSectionGetOffset(sec, v, &off));
    for (PetscInt b = 0; b < scene->nFloating; b++)
      if (scene->body[v - vStart] == scene->floating[b])
        for (PetscInt k = 0; k < dof; k++) share[b] += PetscRealPart(ma[off + k] * ma[off + k]);
  }
  PetscCall(VecRestoreArrayRead(mloc, &ma));
  PetscCall(DMRestoreLocalVector(scene->dm, &mloc));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, share, scene->nFloating, MPIU_REAL, MPIU_SUM, scene->comm));
  for (PetscInt b = 1; b < scene->nFloating; b++)
    if (share[b] > share[moving]) moving = b;
  PetscCall(PetscFree(share));
  if (scene->nFloating)
    PetscCall(PetscViewerASCIIPrintf(viewer, "no equilibrium: the body of %s slides away along (%.4g, %.4g, %.4g): no contact forces its friction allows balance its load (%.3g of the load on its rigid-body motions is unbalanced)\n", scene->floatingName[moving], (double)direction[0], (double)direction[1], (double)direction[2], (double)unbalanced));
  PetscFunctionReturn(0);
}
