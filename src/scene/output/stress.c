/*
   Stresses and strains of the output (docs/derivation.md sections 15 and 18): the P1 strain of every tetrahedron
   (constant in it), Hooke's stress with the cell's material, the von Mises stress, in the order of /viz/topology/cells;
   for a cell of a hyperelastic model the Green-Lagrange strain and the Cauchy stress instead, and in a hyperelastic
   scene every cell's J = det F and first Piola-Kirchhoff stress; and a nodal recovery for smooth pictures, each vertex
   the (reference) volume-weighted mean of the stresses of its cells. Components xx, yy, zz, yz, xz, xy (tensor
   components: the strain's yz is half the engineering shear strain); P row by row.
*/
#include "outputimpl.h"
#include <petscsf.h>

#define NCELL 24 /* per cell: strain (6), stress (6), von Mises (1), J (1), first Piola-Kirchhoff stress (9), model (1) */
#define NNODE 7  /* per vertex: sum of volume times stress (6), sum of volumes */

/* The point SF of dm restricted to its vertices, numbered from vStart on each rank (the nodal sums need no other point) */
static PetscErrorCode VertexSF(DM dm, PetscSF *vertexSF)
{
  PetscSF            sf;
  PetscInt           nroots, nleaves, pStart, pEnd, vStart, vEnd, n = 0, *index, *remoteIndex, *leaves;
  const PetscInt    *ilocal;
  const PetscSFNode *iremote;
  PetscSFNode       *remote;

  PetscFunctionBegin;
  PetscCall(DMGetPointSF(dm, &sf));
  PetscCall(PetscSFGetGraph(sf, &nroots, &nleaves, &ilocal, &iremote));
  PetscCall(DMPlexGetChart(dm, &pStart, &pEnd));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(PetscMalloc2(pEnd - pStart, &index, pEnd - pStart, &remoteIndex));
  for (PetscInt p = pStart; p < pEnd; p++) index[p - pStart] = p >= vStart && p < vEnd ? p - vStart : -1;
  if (nroots >= 0) { /* each leaf vertex learns its root's number on the owner */
    PetscCall(PetscSFBcastBegin(sf, MPIU_INT, index, remoteIndex, MPI_REPLACE));
    PetscCall(PetscSFBcastEnd(sf, MPIU_INT, index, remoteIndex, MPI_REPLACE));
  }
  for (PetscInt l = 0; l < PetscMax(nleaves, 0); l++) {
    const PetscInt p = ilocal ? ilocal[l] : l;

    if (p >= vStart && p < vEnd) n++;
  }
  PetscCall(PetscMalloc1(n + 1, &leaves));
  PetscCall(PetscMalloc1(n + 1, &remote));
  n = 0;
  for (PetscInt l = 0; l < PetscMax(nleaves, 0); l++) {
    const PetscInt p = ilocal ? ilocal[l] : l;

    if (p < vStart || p >= vEnd) continue;
    leaves[n]       = p - vStart;
    remote[n].rank  = iremote[l].rank;
    remote[n].index = remoteIndex[p - pStart];
    n++;
  }
  PetscCall(PetscFree2(index, remoteIndex));
  PetscCall(PetscSFCreate(PetscObjectComm((PetscObject)dm), vertexSF));
  PetscCall(PetscSFSetGraph(*vertexSF, vEnd - vStart, n, leaves, PETSC_OWN_POINTER, remote, PETSC_OWN_POINTER));
  PetscFunctionReturn(0);
}

/* The values of local cell c (from cStart) at the local displacement ua (section sec): all NCELL of them; and its volume */
static PetscErrorCode CellValues(const SSStarCells *cells, PetscSection sec, const PetscScalar ua[], PetscInt c, PetscReal all[NCELL], PetscReal *vol)
{
  PetscReal x[12], ue[12], F[9];

  PetscFunctionBeginHot;
  PetscCall(SSStarCellsGetValues(cells, sec, ua, c, ue));
  PetscCall(SSStarCellsGet(cells, c, x));
  *vol = SSStarTetDeformationGradient(x, ue, F);
  (void)SSStarMaterialStress(cells->model[c], cells->lame[c][0], cells->lame[c][1], F, all + 14);
  if (cells->model[c] == SSSTAR_MATERIAL_LINEAR) { /* small strain: eps, Hooke's sigma (= P) */
    (void)SSStarTetStrain(x, ue, all);
    SSStarHookeStress(cells->lame[c][0], cells->lame[c][1], all, all + 6);
  } else {
    SSStarGreenLagrangeStrain(F, all);
    SSStarCauchyStress(F, all + 14, all + 6);
  }
  all[12] = SSStarVonMises(all + 6);
  all[13] = SSStarDeterminant3(F);
  all[23] = (PetscReal)cells->model[c];
  PetscFunctionReturn(0);
}

/* The recovered stress, 6 per local vertex (nodal, by vertex from vStart; the owned vertices' are complete) */
static PetscErrorCode NodalStress(SSStarScene scene, const SSStarCells *cells, PetscSection sec, const PetscScalar ua[], PetscScalar **nodal)
{
  DM          dm = scene->dm;
  PetscReal  *acc;
  PetscMPIInt size;

  PetscFunctionBegin;
  PetscCall(PetscCalloc1(NNODE * (cells->vEnd - cells->vStart) + 1, &acc)); /* by vertex: not over the whole chart */
  for (PetscInt c = 0; c < cells->cEnd - cells->cStart; c++) {
    const PetscInt *v = &cells->vertices[4 * c];
    PetscReal       all[NCELL], vol;

    PetscCall(CellValues(cells, sec, ua, c, all, &vol));
    for (PetscInt a = 0; a < 4; a++) {
      PetscReal *va = &acc[NNODE * v[a]];

      for (PetscInt k = 0; k < 6; k++) va[k] += vol * all[6 + k];
      va[6] += vol;
    }
  }
  PetscCallMPI(MPI_Comm_size(scene->comm, &size));
  if (size > 1) { /* a vertex's cells on other ranks: their sums to its owner */
    PetscSF      sf;
    MPI_Datatype unit;

    PetscCall(VertexSF(dm, &sf));
    PetscCallMPI(MPI_Type_contiguous(NNODE, MPIU_REAL, &unit));
    PetscCallMPI(MPI_Type_commit(&unit));
    PetscCall(PetscSFReduceBegin(sf, unit, acc, acc, MPI_SUM));
    PetscCall(PetscSFReduceEnd(sf, unit, acc, acc, MPI_SUM));
    PetscCallMPI(MPI_Type_free(&unit));
    PetscCall(PetscSFDestroy(&sf));
  }
  PetscCall(PetscMalloc1(6 * (cells->vEnd - cells->vStart) + 1, nodal));
  for (PetscInt v = 0; v < cells->vEnd - cells->vStart; v++) {
    const PetscReal *va = &acc[NNODE * v];

    for (PetscInt k = 0; k < 6; k++) (*nodal)[6 * v + k] = va[6] > 0 ? va[k] / va[6] : 0;
  }
  PetscCall(PetscFree(acc));
  PetscFunctionReturn(0);
}

/*
   <prefix>/fields/strain, stress (cells x 6), von_mises (cells) and stress_nodal (nodes x 6) at u; a hyperelastic
   scene's J (cells), stress_pk1 (cells x 9) and material_model (cells: the index of SSStarMaterialModels) too. One
   field at a time, computed in the order the cells travel to the ranks that write them (SSStarCellOrderApply()): the
   output holds at most two copies of one field (the prism at level 48: 5.3 M cells a rank)
*/
PetscErrorCode SSStarWriteStresses(SSStarScene scene, hid_t file, const char prefix[], Vec u)
{
  const char    *names[6] = {"strain", "stress", "von_mises", "J", "stress_pk1", "material_model"};
  const PetscInt cols[6] = {6, 6, 1, 1, 9, 1}, first[6] = {0, 6, 12, 13, 14, 23};
  DM             dm = scene->dm;
  PetscSection   sec;
  Vec            uloc, nat;
  const PetscScalar *ua;
  PetscScalar   *nodal;
  SSStarCells    cells;
  SSStarCellOrder plan;
  char           path[PETSC_MAX_PATH_LEN];

  PetscFunctionBegin;
  PetscCall(SSStarCellOrderCreate(scene, &plan, NULL));
  PetscCall(DMGetLocalSection(dm, &sec));
  PetscCall(DMGetLocalVector(dm, &uloc));
  PetscCall(VecZeroEntries(uloc)); /* the -dirichlet dofs: 0 */
  PetscCall(DMGlobalToLocal(dm, u, INSERT_VALUES, uloc));
  PetscCall(VecGetArrayRead(uloc, &ua));
  PetscCall(SSStarCellsBegin(scene, &cells));
  for (PetscInt f = 0; f < (scene->affine ? 3 : 6); f++) {
    PetscReal *send, *rows;
    PetscInt  *codes = NULL;

    PetscCall(PetscMalloc1(cols[f] * plan.nsend + 1, &send));
    for (PetscInt i = 0; i < plan.nsend; i++) {
      PetscReal all[NCELL], vol;

      PetscCall(CellValues(&cells, sec, ua, plan.send[i], all, &vol));
      PetscCall(PetscArraycpy(&send[cols[f] * i], &all[first[f]], cols[f]));
    }
    PetscCall(SSStarCellOrderApply(scene->comm, &plan, cols[f], send, &rows));
    PetscCall(PetscFree(send));
    if (f == 5) {
      PetscCall(PetscMalloc1(plan.nrows + 1, &codes));
      for (PetscInt i = 0; i < plan.nrows; i++) codes[i] = (PetscInt)rows[i];
    }
    PetscCall(PetscSNPrintf(path, sizeof(path), "%s/fields/%s", prefix, names[f]));
    PetscCall(SSStarH5WriteRows(scene->comm, file, path, plan.nrows, cols[f] > 1 ? cols[f] : 0, codes ? NULL : rows, codes));
    PetscCall(PetscFree(codes));
    PetscCall(PetscFree(rows));
  }
  PetscCall(SSStarCellOrderDestroy(&plan));
  PetscCall(NodalStress(scene, &cells, sec, ua, &nodal));
  PetscCall(SSStarCellsEnd(&cells));
  PetscCall(VecRestoreArrayRead(uloc, &ua));
  PetscCall(DMRestoreLocalVector(dm, &uloc));
  PetscCall(SSStarVertexValuesInFileOrder(scene, 6, nodal, &nat));
  PetscCall(PetscFree(nodal));
  PetscCall(PetscSNPrintf(path, sizeof(path), "%s/fields/stress_nodal", prefix));
  PetscCall(SSStarWriteVec(file, path, 6, nat));
  PetscCall(VecDestroy(&nat));
  PetscFunctionReturn(0);
}
