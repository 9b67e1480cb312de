/*
   The contact nodes and faces in the output: /contact (per contact node, in file order: what was declared, what the
   solver used, the state and the kinematics at the solution) and /contact_faces (the contact groups' triangles with
   the point fields ParaView colours them by).
*/
#include "outputimpl.h"

/* "<prefix>/contact/<name>" */
static PetscErrorCode ContactPath(const char prefix[], const char name[], char path[], size_t len)
{
  PetscFunctionBegin;
  PetscCall(PetscSNPrintf(path, len, "%s/contact/%s", prefix, name));
  PetscFunctionReturn(0);
}

/*
   The datasets of <prefix>/contact: per contact node, in the order of the mesh file (fields.c computes their values).
   With nf, what was declared too (the top level); without, the solution's fields alone (a step of a load path, prefix
   /steps/<k>). After a step of a load path was accepted, its slip increment, slip path and dissipation.
*/
PetscErrorCode SSStarWriteContact(SSStarScene scene, hid_t file, const char prefix[], Vec u, Vec r, const SSStarState states[], const SSStarNodeFriction *nf)
{
  MPI_Comm   comm = scene->comm;
  PetscInt   p, n = scene->n, *pos, *all;
  PetscReal *values;
  char       names[1024], path[PETSC_MAX_PATH_LEN];
  hid_t      group;

  PetscFunctionBegin;
  PetscCall(PetscMalloc2(n + 1, &pos, 3 * n + 1, &values));
  PetscCall(SSStarFileOrder(comm, n, scene->tag, &p, &all, pos));
  PetscCall(PetscFree(all));
  PetscCall(ContactPath(prefix, "", path, sizeof(path)));
  PetscCall(SSStarH5GroupOpen(file, path, &group));
  PetscCallH5(H5Gclose(group));
  for (const SSStarContactField *f = SSStarContactFields; f->name; f++) {
    if ((f->kind == SSSTAR_FIELD_SCENE && !nf) || (f->kind == SSSTAR_FIELD_PATH && !scene->stepped)) continue;
    PetscCall(SSStarContactFieldValues(scene, f, u, r, states, values));
    PetscCall(ContactPath(prefix, f->name, path, sizeof(path)));
    PetscCall(SSStarWriteNodeField(comm, file, path, p, n, pos, f->bs, values, f->integer));
  }
  PetscCall(ContactPath(prefix, "state", path, sizeof(path)));
  PetscCall(SSStarJoinNames(SSSTAR_NUM_STATES, SSStarStateNames, names, sizeof(names)));
  PetscCall(SSStarH5ObjectAttrString(file, path, "names", names));
  if (nf) {
    PetscCall(SSStarNodeFrictionWrite(comm, file, "/contact", nf, p, pos)); /* friction_law and the laws' parameters */
    names[0] = 0;
    for (PetscInt g = 0; g < scene->nContact; g++) {
      if (g) PetscCall(PetscStrlcat(names, ",", sizeof(names)));
      PetscCall(PetscStrlcat(names, scene->contact[g].name, sizeof(names)));
      if (scene->contact[g].master[0]) { /* a pair: slave->master */
        PetscCall(PetscStrlcat(names, "->", sizeof(names)));
        PetscCall(PetscStrlcat(names, scene->contact[g].master, sizeof(names)));
      }
    }
    PetscCall(SSStarH5ObjectAttrString(file, "/contact/group", "names", names));
  }
  PetscCall(PetscFree2(pos, values));
  PetscFunctionReturn(0);
}

/* ------------------------------------------------------------------------------------------------------------------
   The contact faces: the triangles of the contact groups on the vertices of those faces (the contact nodes and the
   held vertices among them), with the point fields ParaView colours them by
   ------------------------------------------------------------------------------------------------------------------ */

/* The first contact group whose label holds point q, or -1 */
static PetscErrorCode PointGroup(SSStarScene scene, const DMLabel labels[], PetscInt q, PetscInt *g)
{
  PetscFunctionBegin;
  *g = -1;
  for (PetscInt k = 0; k < scene->nContact && *g < 0; k++) {
    PetscInt value;

    PetscCall(DMLabelGetValue(labels[k], q, &value));
    if (value >= 0) *g = k;
  }
  PetscFunctionReturn(0);
}

/* <prefix>/contact_faces: the point fields, and with geometry the vertices and triangles (the top level) */
PetscErrorCode SSStarWriteContactFaces(SSStarScene scene, hid_t file, const char prefix[], PetscBool geometry, Vec u, Vec r, const SSStarState states[], PetscInt *nvertices, PetscInt *ntriangles)
{
  MPI_Comm           comm = scene->comm;
  DM                 dm   = scene->dm, cdm;
  DMLabel           *labels;
  PetscSection       csec;
  Vec                coordinates, uC, rC;
  PetscBool         *ghost;
  PetscInt           pStart, vStart, vEnd, fStart, fEnd, nq = 0, q, *tag, *pos, *all, ntri = 0, *tri, c = 0, *held, *faceGroup;
  PetscReal         *x, *du, *st, *pr, *tt, *sl, *gp, *kin[4], *normal, *faceNormal, *centre;
  const PetscScalar *ta, *xa, *ua, *ra;
  PetscMPIInt        rank, size;
  hid_t              group;
  char               path[PETSC_MAX_PATH_LEN];

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(SSStarGhostPoints(dm, &ghost));
  PetscCall(PetscMalloc1(scene->nContact, &labels));
  for (PetscInt g = 0; g < scene->nContact; g++) PetscCall(DMGetLabel(dm, scene->contact[g].name, &labels[g]));
  PetscCall(DMPlexGetChart(dm, &pStart, NULL));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(DMPlexGetHeightStratum(dm, 1, &fStart, &fEnd));
  PetscCall(DMGetCoordinatesLocal(dm, &coordinates));
  PetscCall(DMGetCoordinateDM(dm, &cdm));
  PetscCall(DMGetLocalSection(cdm, &csec));
  PetscCall(VecGetArrayRead(scene->tags, &ta));
  PetscCall(VecGetArrayRead(coordinates, &xa));
  PetscCall(VecGetSubVector(u, scene->isC, &uC));
  PetscCall(VecGetSubVector(r, scene->isC, &rC));
  PetscCall(VecGetArrayRead(uC, &ua));
  PetscCall(VecGetArrayRead(rC, &ra));

  /* the owned vertices of the contact faces; the contact nodes among them come in the scene's order (vertex order) */
  PetscCall(PetscMalloc2(vEnd - vStart + 1, &tag, vEnd - vStart + 1, &pos));
  PetscCall(PetscMalloc5(3 * (vEnd - vStart) + 1, &x, 3 * (vEnd - vStart) + 1, &du, vEnd - vStart + 1, &st, vEnd - vStart + 1, &pr, 3 * (vEnd - vStart) + 1, &tt));
  PetscCall(PetscMalloc2(3 * (vEnd - vStart) + 1, &sl, vEnd - vStart + 1, &gp));
  PetscCall(PetscMalloc2(vEnd - vStart + 1, &held, 3 * (vEnd - vStart) + 1, &normal));
  PetscCall(PetscMalloc4(scene->n + 1, &kin[0], scene->n + 1, &kin[1], 3 * scene->n + 1, &kin[2], 3 * scene->n + 1, &kin[3]));
  PetscCall(SSStarSceneContactKinematics(scene, u, r, kin[0], kin[1], kin[2], kin[3])); /* gap and slip: against a plane or a master surface */
  for (PetscInt v = vStart; v < vEnd; v++) {
    PetscInt  g, off;
    PetscReal xv[3];

    if (ghost[v - pStart]) continue;
    PetscCall(PointGroup(scene, labels, v, &g));
    if (g < 0) continue;
    PetscCall(PetscSectionGetOffset(csec, v, &off));
    for (PetscInt k = 0; k < 3; k++) xv[k] = PetscRealPart(xa[off + k]);
    tag[nq] = (PetscInt)PetscRealPart(ta[v - vStart]);
    for (PetscInt k = 0; k < 3; k++) x[3 * nq + k] = xv[k];
    if (c < scene->n && scene->tag[c] == tag[nq]) { /* contact node c */
      const PetscReal *n = &scene->normal[3 * c], ui[3] = {PetscRealPart(ua[3 * c]), PetscRealPart(ua[3 * c + 1]), PetscRealPart(ua[3 * c + 2])};
      const PetscReal  ri[3] = {PetscRealPart(ra[3 * c]), PetscRealPart(ra[3 * c + 1]), PetscRealPart(ra[3 * c + 2])};
      const PetscReal  rn = SSStarDot3(ri, n), area = scene->area[c] > 0 ? scene->area[c] : 1;

      st[nq] = states ? (PetscReal)states[c] : -1;
      pr[nq] = rn / area;
      gp[nq] = kin[0][c]; /* for a plane, gap + u.n */
      for (PetscInt k = 0; k < 3; k++) {
        du[3 * nq + k] = ui[k];
        tt[3 * nq + k] = (ri[k] - rn * n[k]) / area;
        sl[3 * nq + k] = kin[3][3 * c + k]; /* for a plane, u - (u.n) n */
      }
      c++;
      held[nq] = -1;
    } else { /* held fixed (Dirichlet): its gap to the obstacle, below */
      st[nq]   = -1;
      pr[nq]   = 0;
      held[nq] = g;
      for (PetscInt k = 0; k < 3; k++) du[3 * nq + k] = tt[3 * nq + k] = sl[3 * nq + k] = 0;
    }
    nq++;
  }
  PetscCall(SSStarSceneObstacleGaps(scene, nq, held, x, NULL, 0, gp, normal)); /* a held vertex against its obstacle where it is */
  PetscCall(PetscFree2(held, normal));
  PetscCheck(c == scene->n, PETSC_COMM_SELF, PETSC_ERR_PLIB, "%" PetscInt_FMT " of the %" PetscInt_FMT " contact nodes found on the contact faces", c, scene->n);
  PetscCall(PetscFree4(kin[0], kin[1], kin[2], kin[3]));
  PetscCall(SSStarFileOrder(comm, nq, tag, &q, &all, pos));

  /* the owned contact faces, as rows of 3 positions among the face vertices, their normal out of the body */
  PetscCall(PetscMalloc1(3 * (fEnd - fStart) + 1, &tri));
  PetscCall(PetscMalloc3(fEnd - fStart + 1, &faceGroup, 3 * (fEnd - fStart) + 1, &faceNormal, 3 * (fEnd - fStart) + 1, &centre));
  for (PetscInt f = fStart; f < fEnd; f++) { /* each face's vertices (file indices), normal and centre */
    PetscInt *closure = NULL, nclosure, nv = 0, g, *verts = &tri[3 * ntri];
    PetscReal xv[3][3], e1[3], e2[3];

    if (ghost[f - pStart]) continue;
    PetscCall(PointGroup(scene, labels, f, &g));
    if (g < 0) continue;
    PetscCall(DMPlexGetTransitiveClosure(dm, f, PETSC_TRUE, &nclosure, &closure));
    for (PetscInt i = 0; i < nclosure; i++) {
      const PetscInt pt = closure[2 * i];

      if (pt >= vStart && pt < vEnd && nv < 3) {
        PetscInt off;

        PetscCall(PetscSectionGetOffset(csec, pt, &off));
        for (PetscInt k = 0; k < 3; k++) xv[nv][k] = PetscRealPart(xa[off + k]);
        verts[nv++] = (PetscInt)PetscRealPart(ta[pt - vStart]);
      }
    }
    PetscCall(DMPlexRestoreTransitiveClosure(dm, f, PETSC_TRUE, &nclosure, &closure));
    PetscCheck(nv == 3, PETSC_COMM_SELF, PETSC_ERR_SUP, "Face %" PetscInt_FMT " of contact group %s has %" PetscInt_FMT " vertices, not 3", f, scene->contact[g].name, nv);
    for (PetscInt k = 0; k < 3; k++) {
      e1[k]                = xv[1][k] - xv[0][k];
      e2[k]                = xv[2][k] - xv[0][k];
      centre[3 * ntri + k] = (xv[0][k] + xv[1][k] + xv[2][k]) / 3;
    }
    SSStarCross3(e1, e2, &faceNormal[3 * ntri]);
    faceGroup[ntri++] = g;
  }
  { /* the obstacle's normal (at the face's centre; the faces and the obstacle where their options put them) points into
       the body; the face's out of it */
    PetscReal       *gap, *n;
    SSStarPlacement *rest;

    PetscCall(PetscMalloc3(ntri + 1, &gap, 3 * ntri + 1, &n, scene->nContact, &rest));
    for (PetscInt g = 0; g < scene->nContact; g++) SSStarPlacementIdentity(&rest[g]);
    PetscCall(SSStarSceneObstacleGaps(scene, ntri, faceGroup, centre, rest, 0, gap, n));
    for (PetscInt t = 0; t < ntri; t++) {
      PetscInt *verts = &tri[3 * t];

      if (SSStarDot3(&faceNormal[3 * t], &n[3 * t]) > 0) {
        const PetscInt v = verts[1];

        verts[1] = verts[2];
        verts[2] = v;
      }
      for (PetscInt k = 0; k < 3; k++) {
        PetscInt at;

        PetscCall(PetscFindInt(verts[k], q, all, &at));
        PetscCheck(at >= 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Vertex %" PetscInt_FMT " of a contact face is not among the contact faces' vertices", verts[k]);
        verts[k] = at;
      }
    }
    PetscCall(PetscFree3(gap, n, rest));
  }
  PetscCall(PetscFree3(faceGroup, faceNormal, centre));
  PetscCall(VecRestoreArrayRead(rC, &ra));
  PetscCall(VecRestoreArrayRead(uC, &ua));
  PetscCall(VecRestoreSubVector(r, scene->isC, &rC));
  PetscCall(VecRestoreSubVector(u, scene->isC, &uC));
  PetscCall(VecRestoreArrayRead(coordinates, &xa));
  PetscCall(VecRestoreArrayRead(scene->tags, &ta));

  PetscCall(PetscSNPrintf(path, sizeof(path), "%s/contact_faces", prefix));
  PetscCall(SSStarH5GroupOpen(file, path, &group));
  PetscCallH5(H5Gclose(group));
  {
    const char      *vnames[] = {"vertices", "displacement", "pressure", "tangential_traction", "slip", "gap"};
    const PetscReal *values[] = {x, du, pr, tt, sl, gp};
    const PetscInt   bs[]     = {3, 3, 1, 3, 3, 1};

    for (size_t k = geometry ? 0 : 1; k < PETSC_STATIC_ARRAY_LENGTH(vnames); k++) {
      PetscCall(PetscSNPrintf(path, sizeof(path), "%s/contact_faces/%s", prefix, vnames[k]));
      PetscCall(SSStarWriteNodeField(comm, file, path, q, nq, pos, bs[k], values[k], PETSC_FALSE));
    }
    PetscCall(PetscSNPrintf(path, sizeof(path), "%s/contact_faces/state", prefix));
    PetscCall(SSStarWriteNodeField(comm, file, path, q, nq, pos, 1, st, PETSC_TRUE));
  }
  /* the triangles: on rank 0, each rotated to start at its smallest vertex, sorted */
  {
    PetscMPIInt *counts, *displs, nsend = (PetscMPIInt)(3 * ntri);
    PetscInt    *alltri = NULL, total = 0, three = 3;

    PetscCall(PetscCalloc2(size, &counts, size + 1, &displs));
    PetscCallMPI(MPI_Gather(&nsend, 1, MPI_INT, counts, 1, MPI_INT, 0, comm));
    for (PetscMPIInt i = 0; i < size; i++) displs[i + 1] = displs[i] + counts[i];
    if (!rank) total = displs[size] / 3;
    PetscCall(PetscMalloc1(3 * total + 1, &alltri));
    PetscCallMPI(MPI_Gatherv(tri, nsend, MPIU_INT, alltri, counts, displs, MPIU_INT, 0, comm));
    for (PetscInt t = 0; t < total; t++) {
      PetscInt *row = &alltri[3 * t], m = row[1] < row[0] ? (row[2] < row[1] ? 2 : 1) : (row[2] < row[0] ? 2 : 0), rot[3];

      for (PetscInt k = 0; k < 3; k++) rot[k] = row[(m + k) % 3];
      for (PetscInt k = 0; k < 3; k++) row[k] = rot[k];
    }
    if (total > 1) PetscCall(PetscTimSort(total, alltri, 3 * sizeof(PetscInt), SSStarCompareRows, &three));
    if (geometry) PetscCall(SSStarH5WriteRows(comm, file, "/contact_faces/triangles", total, 3, NULL, alltri));
    PetscCallMPI(MPI_Bcast(&total, 1, MPIU_INT, 0, comm));
    *ntriangles = total;
    PetscCall(PetscFree(alltri));
    PetscCall(PetscFree2(counts, displs));
  }
  {
    char names[256];

    PetscCall(SSStarJoinNames(SSSTAR_NUM_STATES, SSStarStateNames, names, sizeof(names)));
    PetscCall(PetscSNPrintf(path, sizeof(path), "%s/contact_faces/state", prefix));
    PetscCall(SSStarH5ObjectAttrString(file, path, "names", names));
  }
  *nvertices = q;
  PetscCall(PetscFree(tri));
  PetscCall(PetscFree(all));
  PetscCall(PetscFree2(sl, gp));
  PetscCall(PetscFree5(x, du, st, pr, tt));
  PetscCall(PetscFree2(tag, pos));
  PetscCall(PetscFree(labels));
  PetscCall(PetscFree(ghost));
  PetscFunctionReturn(0);
}
