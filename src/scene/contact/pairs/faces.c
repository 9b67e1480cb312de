/*
   The boundary faces of a scene's mesh as triangles: their vertices, dofs and file indices, and their unit normal out of
   their body (away from the centroid of the cell they bound). Contact pairs take the master faces (pairs.c) and the
   slave faces (mortar.c) from here.
*/
#include "../../sceneimpl.h"
#include <petscsf.h>

/* SSStarFacesBegin - what SSStarFaceTriangle() reads: the sections, the coordinates, the faces owned here */
PetscErrorCode SSStarFacesBegin(SSStarScene scene, SSStarFaces *faces)
{
  DM              cdm;
  PetscSF         sf;
  PetscInt        nleaves;
  const PetscInt *ilocal;

  PetscFunctionBegin;
  faces->dm = scene->dm;
  PetscCall(DMPlexGetHeightStratum(scene->dm, 1, &faces->fStart, &faces->fEnd));
  PetscCall(DMPlexGetDepthStratum(scene->dm, 0, &faces->vStart, &faces->vEnd));
  PetscCall(DMGetGlobalSection(scene->dm, &faces->gsec));
  PetscCall(DMGetCoordinatesLocal(scene->dm, &faces->coordinates));
  PetscCall(DMGetCoordinateDM(scene->dm, &cdm));
  PetscCall(DMGetLocalSection(cdm, &faces->csec));
  PetscCall(DMGetPointSF(scene->dm, &sf));
  PetscCall(PetscCalloc1(faces->fEnd + 1, &faces->leaf));
  PetscCall(PetscSFGetGraph(sf, NULL, &nleaves, &ilocal, NULL));
  for (PetscInt l = 0; l < nleaves; l++) {
    const PetscInt p = ilocal ? ilocal[l] : l;

    if (p < faces->fEnd) faces->leaf[p] = PETSC_TRUE;
  }
  faces->tags = scene->tags;
  PetscCall(VecGetArrayRead(faces->coordinates, &faces->xa));
  PetscCall(VecGetArrayRead(faces->tags, &faces->ta));
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarFacesEnd(SSStarFaces *faces)
{
  PetscFunctionBegin;
  PetscCall(VecRestoreArrayRead(faces->tags, &faces->ta));
  PetscCall(VecRestoreArrayRead(faces->coordinates, &faces->xa));
  PetscCall(PetscFree(faces->leaf));
  PetscFunctionReturn(0);
}

/*
   SSStarFaceTriangle - face f as a triangle: its vertices (x, 9), their global x-dofs (-1: held fixed), their file
   indices, its first vertex point, its unit normal out of its body and its area
*/
PetscErrorCode SSStarFaceTriangle(const SSStarFaces *faces, PetscInt f, PetscReal x[9], PetscInt dof[3], PetscInt tag[3], PetscInt *vertex, PetscReal n[3], PetscReal *area)
{
  DM              dm = faces->dm;
  PetscInt       *closure = NULL, nc, nv = 0, vert[3], ns;
  const PetscInt *support;
  PetscReal       cc[3] = {0, 0, 0}, side = 0;

  PetscFunctionBegin;
  PetscCall(DMPlexGetTransitiveClosure(dm, f, PETSC_TRUE, &nc, &closure));
  for (PetscInt k = 0; k < nc; k++)
    if (closure[2 * k] >= faces->vStart && closure[2 * k] < faces->vEnd && nv < 3) vert[nv++] = closure[2 * k];
  PetscCall(DMPlexRestoreTransitiveClosure(dm, f, PETSC_TRUE, &nc, &closure));
  for (PetscInt k = 0; k < 3; k++) {
    PetscInt off, d, coff;

    PetscCall(PetscSectionGetOffset(faces->csec, vert[k], &coff));
    for (PetscInt c = 0; c < 3; c++) x[3 * k + c] = PetscRealPart(faces->xa[coff + c]);
    PetscCall(PetscSectionGetDof(faces->gsec, vert[k], &d));
    PetscCall(PetscSectionGetOffset(faces->gsec, vert[k], &off));
    if (d < 0) d = -(d + 1);
    if (off < 0) off = -(off + 1);
    dof[k] = d == 3 ? off : -1;
    tag[k] = (PetscInt)PetscRealPart(faces->ta[vert[k] - faces->vStart]);
  }
  *vertex = vert[0];
  /* the cell's centroid: the normal points away from it, out of the body */
  PetscCall(DMPlexGetSupportSize(dm, f, &ns));
  PetscCall(DMPlexGetSupport(dm, f, &support));
  PetscCheck(ns >= 1, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Face %" PetscInt_FMT " has no cell", f);
  PetscCall(DMPlexGetTransitiveClosure(dm, support[0], PETSC_TRUE, &nc, &closure));
  for (PetscInt k = 0; k < nc; k++)
    if (closure[2 * k] >= faces->vStart && closure[2 * k] < faces->vEnd) {
      PetscInt coff;

      PetscCall(PetscSectionGetOffset(faces->csec, closure[2 * k], &coff));
      for (PetscInt c = 0; c < 3; c++) cc[c] += PetscRealPart(faces->xa[coff + c]) / 4;
    }
  PetscCall(DMPlexRestoreTransitiveClosure(dm, support[0], PETSC_TRUE, &nc, &closure));
  *area = SSStarTriangleNormal(&x[0], &x[3], &x[6], n);
  for (PetscInt c = 0; c < 3; c++) side += n[c] * ((x[c] + x[3 + c] + x[6 + c]) / 3 - cc[c]);
  if (side < 0)
    for (PetscInt c = 0; c < 3; c++) n[c] = -n[c];
  PetscFunctionReturn(0);
}
