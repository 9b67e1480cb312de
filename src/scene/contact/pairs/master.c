/*
   The master surface of a contact pair (-contact_pair_<G> H): the faces of the group H as triangles in a search over the
   ranks, each kept where its cell is, carrying its normal out of the master body and its vertices' x-dofs
   (SSSTAR_MASTER_DATA), which node-to-surface (pairs.c) and the dual mortar (mortar.c) ask.
*/
#include "master.h"

/*
   SSStarMasterSearchCreate - the master faces of pair g owned here, in a search over the ranks (no rank gathers them
   all): their vertices, keys (their vertices' file indices, sorted: of equally close triangles the first in this order
   wins, on any number of ranks) and data (the normal out of the master body, the x-dofs); the bodies the master faces
   are on, over all ranks
*/
PetscErrorCode SSStarMasterSearchCreate(SSStarScene scene, PetscInt g, SSStarSearch *search, PetscInt *nbodies, PetscInt **bodies)
{
  SSStarFaces faces;
  DMLabel     label;
  PetscInt    n = 0, *key, *body;
  PetscReal  *x, *data;
  PetscMPIInt size, mine, *counts, *displs, total = 0;

  PetscFunctionBegin;
  PetscCall(SSStarFacesBegin(scene, &faces));
  PetscCall(DMGetLabel(scene->dm, scene->contact[g].master, &label));
  PetscCall(PetscMalloc4(9 * (faces.fEnd - faces.fStart) + 1, &x, 3 * (faces.fEnd - faces.fStart) + 1, &key, SSSTAR_MASTER_DATA * (faces.fEnd - faces.fStart) + 1, &data, faces.fEnd - faces.fStart + 1, &body));
  for (PetscInt f = faces.fStart; f < faces.fEnd; f++) {
    PetscInt  value, dof[3], vertex;
    PetscReal area;

    PetscCall(DMLabelGetValue(label, f, &value));
    if (value < 0 || faces.leaf[f]) continue;
    PetscCall(SSStarFaceTriangle(&faces, f, &x[9 * n], dof, &key[3 * n], &vertex, &data[SSSTAR_MASTER_DATA * n], &area));
    PetscCall(PetscSortInt(3, &key[3 * n]));
    for (PetscInt k = 0; k < 3; k++) data[SSSTAR_MASTER_DATA * n + 3 + k] = (PetscReal)dof[k];
    body[n++] = scene->body[vertex - faces.vStart];
  }
  PetscCall(SSStarFacesEnd(&faces));
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
