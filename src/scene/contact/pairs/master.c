/*
   The master surface of a contact pair (-contact_pair_<G> H): the faces of the group H as triangles in a search over the
   ranks, each kept where its cell is, carrying its normal out of the master body and its vertices' x-dofs
   (SSSTAR_MASTER_DATA), which node-to-surface (pairs.c) and the dual mortar (mortar.c) ask.
*/
#include "master.h"

/*
   SSStarMasterSearchCreate - the master faces of pair g owned here, in a search over the ranks (no rank gathers them
   all): their vertices, keys (their vertices' file indices, sorted: of equally close triangles the first in this order
   wins, on any number of ranks) and data (the normal out of the master body, the x-dofs), at the reference
   configuration or displaced by u (a global displacement, or NULL); the bodies the master faces are on, over all ranks
*/
PetscErrorCode SSStarMasterSearchCreate(SSStarScene scene, PetscInt g, Vec u, SSStarSearch *search, PetscInt *nbodies, PetscInt **bodies)
{
  SSStarFaces   faces;
  DMLabel       label;
  PetscInt      n = 0, *key, *body;
  PetscReal    *x, *data;
  PetscMPIInt   size, mine, *counts, *displs, total = 0;
  SSStarBadNode held = {-1, -1, -1, {0, 0, 0}, 0};
  PetscBool     found;

  PetscFunctionBegin;
  PetscCall(SSStarFacesBegin(scene, u, &faces));
  PetscCall(DMGetLabel(scene->dm, scene->contact[g].master, &label));
  PetscCall(PetscMalloc4(9 * (faces.fEnd - faces.fStart) + 1, &x, 3 * (faces.fEnd - faces.fStart) + 1, &key, SSSTAR_MASTER_DATA * (faces.fEnd - faces.fStart) + 1, &data, faces.fEnd - faces.fStart + 1, &body));
  for (PetscInt f = faces.fStart; f < faces.fEnd; f++) {
    PetscInt  value, dof[3], vertex;
    PetscReal area;

    PetscCall(DMLabelGetValue(label, f, &value));
    if (value < 0 || faces.leaf[f]) continue;
    PetscCall(SSStarFaceTriangle(&faces, f, &x[9 * n], dof, &key[3 * n], &vertex, &data[SSSTAR_MASTER_DATA * n], &area));
    if (held.tag < 0) { /* a prescribed component (-displacement_<G>) on the master surface: refused below */
      PetscInt *closure = NULL, nc;

      PetscCall(DMPlexGetTransitiveClosure(scene->dm, f, PETSC_TRUE, &nc, &closure));
      for (PetscInt k = 0; k < nc && held.tag < 0; k++) {
        const PetscInt v = closure[2 * k] - faces.vStart;

        if (v < 0 || v >= faces.vEnd - faces.vStart) continue;
        for (PetscInt c = 0; c < 3 && held.tag < 0; c++)
          if (SSStarHeldIdentityRow(scene, v, c)) {
            held.tag   = (PetscInt)PetscRealPart(faces.ta[v]);
            held.other = scene->heldBy[3 * v + c];
          }
      }
      PetscCall(DMPlexRestoreTransitiveClosure(scene->dm, f, PETSC_TRUE, &nc, &closure));
    }
    PetscCall(PetscSortInt(3, &key[3 * n]));
    for (PetscInt k = 0; k < 3; k++) data[SSSTAR_MASTER_DATA * n + 3 + k] = (PetscReal)dof[k];
    body[n++] = scene->body[vertex - faces.vStart];
  }
  PetscCall(SSStarFacesEnd(&faces));
  PetscCall(SSStarSceneShareBadNode(scene->comm, &held, &found));
  if (found) {
    char option[SSSTAR_GROUP_NAME_LEN + 16];

    PetscCall(PetscFree4(x, key, data, body));
    PetscCall(SSStarHeldName(scene, held.other, option, sizeof(option)));
    SETERRQ(scene->comm, PETSC_ERR_SUP, "Mesh node %" PetscInt_FMT " (0-based, file order) of the master surface %s of contact pair %s has a displacement prescribed by %s: a pair's master nodes may not be prescribed (prescribe a face of that body away from its master surface)", held.tag, scene->contact[g].master, scene->contact[g].name, option);
  }
  PetscCall(SSStarSearchCreate(scene->comm, n, x, key, SSSTAR_MASTER_DATA, data, search));
  PetscCall(PetscSortRemoveDupsInt(&n, body));
  PetscCallMPI(MPI_Comm_size(scene->comm, &size));
  PetscCall(PetscMalloc2(size, &counts, size, &displs));
  mine = (PetscMPIInt)n;
  PetscCallMPI(MPI_Allgather(&mine, 1, MPI_INT, counts, 1, MPI_INT, scene->comm));
  for (PetscMPIInt r = 0; r < size; r++) {
    displs[r] = total;
    total += counts[r];
  }
  PetscCall(PetscMalloc1(total + 1, bodies));
  PetscCallMPI(MPI_Allgatherv(body, mine, MPIU_INT, *bodies, counts, displs, MPIU_INT, scene->comm));
  *nbodies = total;
  PetscCall(PetscSortRemoveDupsInt(nbodies, *bodies));
  PetscCall(PetscFree2(counts, displs));
  PetscCall(PetscFree4(x, key, data, body));
  PetscFunctionReturn(0);
}
