/*
   What inertia adds to a scene (docs/derivation.md section 16): the mass matrix of P1 tetrahedra, consistent
   (M_ab = rho vol (1 + delta_ab) / 20 per component) or lumped (rho vol / 4 on the diagonal, its row sums), with each
   cell's density (-material_<G> E,nu,rho, else -density), and the initial velocity of the nodes (-initial_velocity,
   -initial_velocity_<G> for the nodes of a volume group).
*/
#include "../sceneimpl.h"

/* The element mass of a tetrahedron of volume vol and density rho, 12 x 12 in 3 x 3 blocks (row-major) */
void SSStarTetMass(PetscReal vol, PetscReal rho, PetscBool lumped, PetscScalar Me[144])
{
  for (PetscInt a = 0; a < 4; a++)
    for (PetscInt b = 0; b < 4; b++)
      for (PetscInt i = 0; i < 3; i++)
        for (PetscInt j = 0; j < 3; j++) {
          PetscReal m = 0;

          if (i == j) m = lumped ? (a == b ? rho * vol / 4 : 0) : rho * vol * (a == b ? 2 : 1) / 20;
          Me[(3 * a + i) * 12 + 3 * b + j] = m;
        }
}

/*
   SSStarAssembleMass - the mass matrix of the scene in K's layout and nonzero pattern (held vertices have no dofs), and
   the check that every cell has a density
*/
PetscErrorCode SSStarAssembleMass(SSStarScene scene, Mat K, PetscBool lumped, Mat *M)
{
  DM                 dm = scene->dm, cdm;
  PetscSection       csec;
  Vec                cloc;
  const PetscScalar *ca;
  PetscInt           cStart, cEnd, vStart, vEnd, *blocks, missing = 0;
  PetscReal         *rho;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(SSSTAR_Assembly, dm, 0, 0, 0));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(PetscMalloc1(cEnd - cStart + 1, &rho));
  PetscCall(SSStarCellMaterials(scene, cStart, cEnd, NULL, NULL, rho));
  for (PetscInt c = cStart; c < cEnd; c++) missing += rho[c - cStart] <= 0;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &missing, 1, MPIU_INT, MPI_SUM, scene->comm));
  if (missing) PetscCall(PetscFree(rho));
  PetscCheck(!missing, scene->comm, PETSC_ERR_ARG_WRONG, "Option -dynamics: %" PetscInt_FMT " cells have no positive density: give -density rho, or -material_<G> E,nu,rho for their volume groups", missing);
  PetscCall(SSStarVertexBlocks(dm, vStart, vEnd, &blocks));
  PetscCall(MatDuplicate(K, MAT_DO_NOT_COPY_VALUES, M)); /* K's pattern holds every cell's couplings */
  PetscCall(MatSetNullSpace(*M, NULL));
  PetscCall(DMGetCoordinateDM(dm, &cdm));
  PetscCall(DMGetLocalSection(cdm, &csec));
  PetscCall(DMGetCoordinatesLocal(dm, &cloc));
  PetscCall(VecGetArrayRead(cloc, &ca));
  for (PetscInt c = cStart; c < cEnd; c++) {
    PetscInt    v[4], b[4];
    PetscReal   x[12], grad[4][3];
    PetscScalar Me[144];

    PetscCall(SSStarMeshCellVertices(dm, c, v));
    for (PetscInt a = 0; a < 4; a++) {
      PetscInt off;

      PetscCall(PetscSectionGetOffset(csec, v[a], &off));
      for (PetscInt k = 0; k < 3; k++) x[3 * a + k] = PetscRealPart(ca[off + k]);
      b[a] = blocks[v[a] - vStart];
    }
    SSStarTetMass(SSStarTetGradients(x, grad), rho[c - cStart], lumped, Me);
    PetscCall(MatSetValuesBlocked(*M, 4, b, 4, b, Me, ADD_VALUES)); /* held vertices (b < 0) drop out */
  }
  PetscCall(VecRestoreArrayRead(cloc, &ca));
  PetscCall(MatAssemblyBegin(*M, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*M, MAT_FINAL_ASSEMBLY));
  PetscCall(MatSetOption(*M, MAT_SPD, PETSC_TRUE));
  PetscCall(PetscFree(blocks));
  PetscCall(PetscFree(rho));
  PetscCall(PetscLogEventEnd(SSSTAR_Assembly, dm, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* The nodes of the volume group: 1 at the local dofs of the vertices of its cells (a local vector), 0 elsewhere */
static PetscErrorCode MarkGroup(DM dm, const char group[], Vec local)
{
  PetscSection sec;
  DMLabel      label;
  PetscScalar *la;
  PetscInt     cStart, cEnd;

  PetscFunctionBegin;
  PetscCall(DMGetLocalSection(dm, &sec));
  PetscCall(DMGetLabel(dm, group, &label));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  PetscCall(VecZeroEntries(local));
  PetscCall(VecGetArray(local, &la));
  for (PetscInt c = cStart; c < cEnd; c++) {
    PetscInt value, verts[4];

    PetscCall(DMLabelGetValue(label, c, &value));
    if (value < 0) continue;
    PetscCall(SSStarMeshCellVertices(dm, c, verts));
    for (PetscInt a = 0; a < 4; a++) {
      PetscInt dof, off;

      PetscCall(PetscSectionGetDof(sec, verts[a], &dof));
      PetscCall(PetscSectionGetOffset(sec, verts[a], &off));
      for (PetscInt k = 0; k < dof; k++) la[off + k] = 1;
    }
  }
  PetscCall(VecRestoreArray(local, &la));
  PetscFunctionReturn(0);
}

/*
   SSStarInitialVelocity - the initial velocity v (a global vector of the scene's DM): -initial_velocity (all) at every
   node that is not held, -initial_velocity_<G> at the nodes of the volume group G (the last group's, in the order of the
   options, where groups share a node; on any number of ranks alike: a node's owner counts every rank's cells of it)
*/
PetscErrorCode SSStarInitialVelocity(SSStarScene scene, const PetscReal all[3], Vec v)
{
  DM           dm = scene->dm;
  Vec          local, mark;
  PetscScalar *va;
  PetscInt     n;

  PetscFunctionBegin;
  PetscCall(VecGetLocalSize(v, &n));
  PetscCall(VecGetArrayWrite(v, &va));
  for (PetscInt i = 0; i < n; i++) va[i] = all[i % 3]; /* every node not held has its 3 dofs, in order */
  PetscCall(VecRestoreArrayWrite(v, &va));
  PetscCall(DMGetLocalVector(dm, &local));
  PetscCall(DMGetGlobalVector(dm, &mark));
  for (PetscInt g = 0; g < scene->nVelocities; g++) {
    const PetscScalar *ma;

    PetscCall(MarkGroup(dm, scene->velocities[g].name, local));
    PetscCall(VecZeroEntries(mark));
    PetscCall(DMLocalToGlobal(dm, local, ADD_VALUES, mark));
    PetscCall(VecGetArrayRead(mark, &ma));
    PetscCall(VecGetArray(v, &va));
    for (PetscInt i = 0; i < n; i++)
      if (PetscRealPart(ma[i]) > 0) va[i] = scene->velocities[g].value[i % 3];
    PetscCall(VecRestoreArray(v, &va));
    PetscCall(VecRestoreArrayRead(mark, &ma));
  }
  PetscCall(DMRestoreGlobalVector(dm, &mark));
  PetscCall(DMRestoreLocalVector(dm, &local));
  PetscFunctionReturn(0);
}
