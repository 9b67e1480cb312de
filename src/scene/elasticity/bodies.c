/*
   The bodies of a scene: the connected components of its mesh (cells sharing a vertex), each named by the smallest file
   index of its nodes. Each body must be held by a -dirichlet or -spring_<G> group: one held by contact alone has rigid-body
   motions nothing resists (K singular) and is refused, named by its volume groups. Contact pairs (pairs.c) are between
   two bodies.
*/
#include "../sceneimpl.h"
#include <petscsf.h>

#define SSSTAR_MAX_VOLUME_GROUPS 62 /* bits of the body's volume-group mask */

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

/*
   The bodies: connected components of the mesh (cells sharing a vertex), each named by the smallest file index of
   its nodes; scene->body[v] for every local vertex. Each body must touch a -dirichlet or -spring_<G> group, or its
   rigid-body motions are held by contact alone (K singular): refused, naming the body.
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
  PetscMPIInt        size, *counts, *displs, total = 0;
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

  /* per local component: (body, held, volume groups), merged over the ranks */
  PetscCall(HoldingLabels(scene, &nhold, &hold));
  PetscCall(PetscCalloc1(3 * (vEnd - vStart) + 3, &loc));
  for (PetscInt v = 0; v < vEnd - vStart; v++) setMin[v] = -1; /* the entry of each local set */
  for (PetscInt v = vStart; v < vEnd; v++) {
    const PetscInt r = Find(parent, v - vStart);
    PetscBool      held = PETSC_FALSE;

    if (setMin[r] < 0) {
      setMin[r]        = nloc++;
      loc[3 * setMin[r]] = comp[v - pStart];
    }
    for (PetscInt g = 0; g < nhold && !held; g++) {
      PetscInt value;

      PetscCall(DMLabelGetValue(hold[g], v, &value));
      held = (PetscBool)(value >= 0);
    }
    if (held) loc[3 * setMin[r] + 1] = 1;
  }
  for (PetscInt c = cStart; c < cEnd; c++) {
    PetscInt v[4], e;

    PetscCall(SSStarMeshCellVertices(dm, c, v));
    e = setMin[Find(parent, v[0] - vStart)];
    for (PetscInt l = 0; l < nvol && e >= 0; l++) {
      PetscInt value;

      PetscCall(DMLabelGetValue(vol[l], c, &value));
      if (value >= 0) loc[3 * e + 2] |= 1LL << l;
    }
  }
  PetscCall(PetscFree(hold));
  PetscCall(PetscMalloc2(size, &counts, size, &displs));
  {
    PetscMPIInt mine = (PetscMPIInt)(3 * nloc);

    PetscCallMPI(MPI_Allgather(&mine, 1, MPI_INT, counts, 1, MPI_INT, scene->comm));
  }
  for (PetscMPIInt r = 0; r < size; r++) {
    displs[r] = total;
    total += counts[r];
  }
  PetscCall(PetscMalloc1(total + 3, &all));
  PetscCallMPI(MPI_Allgatherv(loc, 3 * (PetscMPIInt)nloc, MPI_LONG_LONG, all, counts, displs, MPI_LONG_LONG, scene->comm));
  /* merge: the same body on several ranks */
  scene->nBodies = 0;
  for (PetscMPIInt e = 0; e < total / 3; e++) {
    PetscBool first = PETSC_TRUE;

    for (PetscMPIInt f = 0; f < e && first; f++)
      if (all[3 * f] == all[3 * e]) first = PETSC_FALSE;
    if (!first) continue;
    for (PetscMPIInt f = e + 1; f < total / 3; f++)
      if (all[3 * f] == all[3 * e]) {
        all[3 * e + 1] |= all[3 * f + 1];
        all[3 * e + 2] |= all[3 * f + 2];
      }
    for (PetscMPIInt f = e + 1; f < total / 3; f++) /* the merged verdict in every entry of the body */
      if (all[3 * f] == all[3 * e]) all[3 * f + 1] = all[3 * e + 1];
    scene->nBodies++;
  }
  for (PetscMPIInt e = 0; e < total / 3; e++) {
    char names[1024] = "";

    if (all[3 * e + 1]) continue;
    for (PetscInt l = 0; l < nvol; l++)
      if (all[3 * e + 2] & (1LL << l)) {
        if (names[0]) PetscCall(PetscStrlcat(names, ", ", sizeof(names)));
        PetscCall(PetscStrlcat(names, "\"", sizeof(names)));
        PetscCall(PetscStrlcat(names, volName[l], sizeof(names)));
        PetscCall(PetscStrlcat(names, "\"", sizeof(names)));
      }
    SETERRQ(scene->comm, PETSC_ERR_ARG_WRONG, "The body of volume group %s (the mesh nodes connected to node %lld, 0-based file order; one of %" PetscInt_FMT " bodies) is held only by contact: nothing holds its rigid-body motions. Hold it with -dirichlet or -spring_<G> on one of its groups", names[0] ? names : "(none)", all[3 * e], scene->nBodies);
  }
  PetscCall(PetscFree(all));
  PetscCall(PetscFree2(counts, displs));
  PetscCall(PetscFree(loc));
  PetscCall(PetscFree4(parent, comp, copy, setMin));
  PetscFunctionReturn(0);
}
