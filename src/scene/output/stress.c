/*
   Stresses and strains of the output (docs/derivation.md section 15): the P1 strain of every tetrahedron (constant in
   it), Hooke's stress with the cell's material, the von Mises stress, in the order of /viz/topology/cells; and a
   nodal recovery for smooth pictures, each vertex the volume-weighted mean of the stresses of its cells. Components
   xx, yy, zz, yz, xz, xy (tensor components: the strain's yz is half the engineering shear strain).
*/
#include "outputimpl.h"
#include <petscsf.h>

#define NCELL 13 /* per cell: strain (6), stress (6), von Mises (1) */
#define NNODE 7  /* per vertex: sum of volume times stress (6), sum of volumes */

/*
   SSStarStressFields - at u: NCELL values per local cell (cellValues, by cell from cStart) and the recovered stress,
   6 per local vertex (nodal, by vertex from vStart; the owned vertices' are complete)
*/
PetscErrorCode SSStarStressFields(SSStarScene scene, Vec u, PetscReal **cellValues, PetscScalar **nodal)
{
  DM                 dm = scene->dm;
  PetscSection       sec;
  Vec                uloc;
  const PetscScalar *ua;
  PetscInt           pStart, pEnd;
  PetscReal         *acc;
  PetscMPIInt        size;
  SSStarCells        cells;

  PetscFunctionBegin;
  PetscCall(DMGetLocalSection(dm, &sec));
  PetscCall(DMPlexGetChart(dm, &pStart, &pEnd));
  PetscCall(DMGetLocalVector(dm, &uloc));
  PetscCall(VecZeroEntries(uloc)); /* the -dirichlet dofs: 0 */
  PetscCall(DMGlobalToLocal(dm, u, INSERT_VALUES, uloc));
  PetscCall(VecGetArrayRead(uloc, &ua));
  PetscCall(SSStarCellsBegin(scene, &cells));
  PetscCall(PetscMalloc1(NCELL * (cells.cEnd - cells.cStart) + 1, cellValues));
  PetscCall(PetscCalloc1(NNODE * (pEnd - pStart) + 1, &acc));
  for (PetscInt c = 0; c < cells.cEnd - cells.cStart; c++) {
    const PetscInt *v = &cells.vertices[4 * c];
    PetscReal       x[12], ue[12], vol, *cv = &(*cellValues)[NCELL * c];

    for (PetscInt a = 0; a < 4; a++) {
      PetscInt off;

      PetscCall(PetscSectionGetOffset(sec, cells.vStart + v[a], &off));
      for (PetscInt k = 0; k < 3; k++) ue[3 * a + k] = PetscRealPart(ua[off + k]);
    }
    PetscCall(SSStarCellsGet(&cells, c, x));
    vol = SSStarTetStrain(x, ue, cv);
    SSStarHookeStress(cells.lame[c][0], cells.lame[c][1], cv, cv + 6);
    cv[12] = SSStarVonMises(cv + 6);
    for (PetscInt a = 0; a < 4; a++) {
      PetscReal *va = &acc[NNODE * (cells.vStart + v[a] - pStart)];

      for (PetscInt k = 0; k < 6; k++) va[k] += vol * cv[6 + k];
      va[6] += vol;
    }
  }
  PetscCall(SSStarCellsEnd(&cells));
  PetscCall(VecRestoreArrayRead(uloc, &ua));
  PetscCall(DMRestoreLocalVector(dm, &uloc));
  PetscCallMPI(MPI_Comm_size(scene->comm, &size));
  if (size > 1) { /* a vertex's cells on other ranks: their sums to its owner */
    PetscSF      sf;
    MPI_Datatype unit;

    PetscCall(DMGetPointSF(dm, &sf));
    PetscCallMPI(MPI_Type_contiguous(NNODE, MPIU_REAL, &unit));
    PetscCallMPI(MPI_Type_commit(&unit));
    PetscCall(PetscSFReduceBegin(sf, unit, acc, acc, MPI_SUM));
    PetscCall(PetscSFReduceEnd(sf, unit, acc, acc, MPI_SUM));
    PetscCallMPI(MPI_Type_free(&unit));
  }
  {
    PetscInt vStart, vEnd;

    PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
    PetscCall(PetscMalloc1(6 * (vEnd - vStart) + 1, nodal));
    for (PetscInt v = vStart; v < vEnd; v++) {
      const PetscReal *va = &acc[NNODE * (v - pStart)];

      for (PetscInt k = 0; k < 6; k++) (*nodal)[6 * (v - vStart) + k] = va[6] > 0 ? va[k] / va[6] : 0;
    }
  }
  PetscCall(PetscFree(acc));
  PetscFunctionReturn(0);
}

/* <prefix>/fields/strain, stress (cells x 6), von_mises (cells) and stress_nodal (nodes x 6) at u */
PetscErrorCode SSStarWriteStresses(SSStarScene scene, hid_t file, const char prefix[], Vec u)
{
  PetscReal   *cellValues, *rows, *column;
  PetscScalar *nodal;
  PetscInt     nrows;
  Vec          nat;
  char         path[PETSC_MAX_PATH_LEN];
  const char  *names[3] = {"strain", "stress", "von_mises"};

  PetscFunctionBegin;
  PetscCall(SSStarStressFields(scene, u, &cellValues, &nodal));
  PetscCall(SSStarCellValuesInFileOrder(scene, NCELL, cellValues, &nrows, &rows));
  PetscCall(PetscMalloc1(6 * nrows + 1, &column));
  for (PetscInt f = 0; f < 3; f++) {
    const PetscInt cols = f < 2 ? 6 : 1;

    for (PetscInt i = 0; i < nrows; i++)
      for (PetscInt k = 0; k < cols; k++) column[cols * i + k] = rows[NCELL * i + 6 * f + k];
    PetscCall(PetscSNPrintf(path, sizeof(path), "%s/fields/%s", prefix, names[f]));
    PetscCall(SSStarH5WriteRows(scene->comm, file, path, nrows, f < 2 ? 6 : 0, column, NULL));
  }
  PetscCall(SSStarVertexValuesInFileOrder(scene, 6, nodal, &nat));
  PetscCall(PetscSNPrintf(path, sizeof(path), "%s/fields/stress_nodal", prefix));
  PetscCall(SSStarWriteVec(file, path, 6, nat));
  PetscCall(VecDestroy(&nat));
  PetscCall(PetscFree(column));
  PetscCall(PetscFree(rows));
  PetscCall(PetscFree(nodal));
  PetscCall(PetscFree(cellValues));
  PetscFunctionReturn(0);
}
