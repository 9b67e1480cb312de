/* HDF5 output: the displacement on the mesh (PETSc's visualization layout + an XDMF file) and the group /contact. */
#include <ssstarcontact.h>
#include <petscviewerhdf5.h>

/* A vector with all its entries on rank 0 (so that the HDF5 dataset is in file order) */
static PetscErrorCode WriteRankZeroVec(PetscViewer viewer, const char name[], PetscInt n, PetscInt bs, const PetscReal a[])
{
  Vec          v;
  PetscScalar *va;

  PetscFunctionBegin;
  PetscCall(VecCreateMPI(PetscObjectComm((PetscObject)viewer), n * bs, PETSC_DETERMINE, &v));
  PetscCall(VecSetBlockSize(v, bs));
  PetscCall(PetscObjectSetName((PetscObject)v, name));
  PetscCall(VecGetArrayWrite(v, &va));
  for (PetscInt i = 0; i < n * bs; i++) va[i] = a[i];
  PetscCall(VecRestoreArrayWrite(v, &va));
  PetscCall(VecView(v, viewer));
  PetscCall(VecDestroy(&v));
  PetscFunctionReturn(0);
}

/* Gathers nloc blocks of bs reals from every rank on rank 0, in the order given by perm there. */
static PetscErrorCode GatherBlocks(MPI_Comm comm, PetscInt nloc, PetscInt bs, const PetscReal loc[], const PetscInt perm[], PetscInt n, PetscReal out[])
{
  PetscMPIInt size, rank, cnt, *counts = NULL, *displs = NULL;
  PetscReal  *all = NULL;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(PetscMPIIntCast(nloc * bs, &cnt));
  if (rank == 0) PetscCall(PetscMalloc3(size, &counts, size, &displs, n * bs, &all));
  PetscCallMPI(MPI_Gather(&cnt, 1, MPI_INT, counts, 1, MPI_INT, 0, comm));
  if (rank == 0) {
    displs[0] = 0;
    for (PetscMPIInt r = 1; r < size; r++) displs[r] = displs[r - 1] + counts[r - 1];
  }
  PetscCallMPI(MPI_Gatherv(loc, cnt, MPIU_REAL, all, counts, displs, MPIU_REAL, 0, comm));
  if (rank == 0) {
    for (PetscInt i = 0; i < n; i++)
      for (PetscInt k = 0; k < bs; k++) out[i * bs + k] = all[perm[i] * bs + k];
    PetscCall(PetscFree3(counts, displs, all));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode WriteXDMF(DM dm, const char h5[])
{
  MPI_Comm    comm = PetscObjectComm((PetscObject)dm);
  PetscInt    cStart, cEnd, ncells, nverts, nloc;
  Vec         coordinates;
  PetscMPIInt rank;
  char        xmf[PETSC_MAX_PATH_LEN];
  const char *base;
  FILE       *fp;
  size_t      len;

  PetscFunctionBegin;
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  nloc = cEnd - cStart;
  PetscCall(MPIU_Allreduce(&nloc, &ncells, 1, MPIU_INT, MPI_SUM, comm));
  PetscCall(DMGetCoordinates(dm, &coordinates));
  PetscCall(VecGetSize(coordinates, &nverts));
  nverts /= 3;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(PetscStrlen(h5, &len));
  PetscCall(PetscStrncpy(xmf, h5, sizeof(xmf)));
  if (len > 3 && !strcmp(h5 + len - 3, ".h5")) xmf[len - 3] = 0;
  PetscCall(PetscStrlcat(xmf, ".xmf", sizeof(xmf)));
  base = strrchr(h5, '/');
  base = base ? base + 1 : h5;
  if (rank == 0) {
    PetscCall(PetscFOpen(PETSC_COMM_SELF, xmf, "w", &fp));
    PetscCall(PetscFPrintf(PETSC_COMM_SELF, fp,
                           "<?xml version=\"1.0\" ?>\n"
                           "<Xdmf Version=\"2.0\">\n"
                           " <Domain>\n"
                           "  <Grid Name=\"mesh\" GridType=\"Uniform\">\n"
                           "   <Topology TopologyType=\"Tetrahedron\" NumberOfElements=\"%" PetscInt_FMT "\">\n"
                           "    <DataItem Dimensions=\"%" PetscInt_FMT " 4\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">%s:/viz/topology/cells</DataItem>\n"
                           "   </Topology>\n"
                           "   <Geometry GeometryType=\"XYZ\">\n"
                           "    <DataItem Dimensions=\"%" PetscInt_FMT " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/geometry/vertices</DataItem>\n"
                           "   </Geometry>\n"
                           "   <Attribute Name=\"displacement\" AttributeType=\"Vector\" Center=\"Node\">\n"
                           "    <DataItem Dimensions=\"%" PetscInt_FMT " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/fields/displacement</DataItem>\n"
                           "   </Attribute>\n"
                           "  </Grid>\n"
                           " </Domain>\n"
                           "</Xdmf>\n",
                           ncells, ncells, base, nverts, base, nverts, base));
    PetscCall(PetscFClose(PETSC_COMM_SELF, fp));
  }
  PetscFunctionReturn(0);
}

/*@C
   SSStarWriteSolution - writes file.h5 (and file.xmf for ParaView): the displacement u on the mesh, and the group
   /contact with coordinates (p x 3), displacement (p x 3), reaction (p x 3) and state (p) of the contact nodes in
   file order
@*/
PetscErrorCode SSStarWriteSolution(const char file[], DM dm, Vec u, const SSStarContactNodes *cn, Vec uC, Vec rC, const PetscInt states[])
{
  MPI_Comm           comm = PetscObjectComm((PetscObject)dm);
  PetscViewer        viewer;
  PetscMPIInt        rank;
  PetscInt           p, nloc = cn->n, *tags = NULL, *perm = NULL;
  PetscReal         *buf = NULL, *locstate, *out;
  const PetscScalar *ua, *ra;
  PetscReal         *ul, *rl;
  const PetscReal   *blocks[4];
  const char        *names[4] = {"coordinates", "displacement", "reaction", "state"};
  const PetscInt     bs[4]    = {3, 3, 3, 1};

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(PetscObjectSetName((PetscObject)u, "displacement"));
  PetscCall(PetscViewerHDF5Open(comm, file, FILE_MODE_WRITE, &viewer));
  PetscCall(PetscViewerPushFormat(viewer, PETSC_VIEWER_HDF5_VIZ));
  PetscCall(DMView(dm, viewer));
  PetscCall(VecView(u, viewer));
  PetscCall(PetscViewerPopFormat(viewer));

  /* the contact nodes in file order, on rank 0 */
  PetscCall(MPIU_Allreduce(&nloc, &p, 1, MPIU_INT, MPI_SUM, comm));
  if (rank == 0) PetscCall(PetscMalloc3(p, &tags, p, &perm, 3 * p, &buf));
  {
    PetscMPIInt size, cnt, *counts = NULL, *displs = NULL;
    PetscCallMPI(MPI_Comm_size(comm, &size));
    PetscCall(PetscMPIIntCast(nloc, &cnt));
    if (rank == 0) PetscCall(PetscMalloc2(size, &counts, size, &displs));
    PetscCallMPI(MPI_Gather(&cnt, 1, MPI_INT, counts, 1, MPI_INT, 0, comm));
    if (rank == 0) {
      displs[0] = 0;
      for (PetscMPIInt r = 1; r < size; r++) displs[r] = displs[r - 1] + counts[r - 1];
    }
    PetscCallMPI(MPI_Gatherv(cn->tag, cnt, MPIU_INT, tags, counts, displs, MPIU_INT, 0, comm));
    if (rank == 0) {
      for (PetscInt i = 0; i < p; i++) perm[i] = i;
      PetscCall(PetscSortIntWithPermutation(p, tags, perm));
      PetscCall(PetscFree2(counts, displs));
    }
  }
  PetscCall(PetscMalloc3(3 * nloc, &ul, 3 * nloc, &rl, nloc, &locstate));
  PetscCall(VecGetArrayRead(uC, &ua));
  PetscCall(VecGetArrayRead(rC, &ra));
  for (PetscInt i = 0; i < 3 * nloc; i++) {
    ul[i] = PetscRealPart(ua[i]);
    rl[i] = PetscRealPart(ra[i]);
  }
  PetscCall(VecRestoreArrayRead(rC, &ra));
  PetscCall(VecRestoreArrayRead(uC, &ua));
  for (PetscInt i = 0; i < nloc; i++) locstate[i] = (PetscReal)states[i];
  blocks[0] = cn->coords;
  blocks[1] = ul;
  blocks[2] = rl;
  blocks[3] = locstate;

  PetscCall(PetscViewerHDF5PushGroup(viewer, "/contact"));
  for (PetscInt k = 0; k < 4; k++) {
    out = buf;
    PetscCall(GatherBlocks(comm, nloc, bs[k], blocks[k], perm, p, out));
    if (k < 3) PetscCall(WriteRankZeroVec(viewer, names[k], rank ? 0 : p, bs[k], out));
    else {
      PetscInt *st = NULL;
      IS        is;

      if (rank == 0) {
        PetscCall(PetscMalloc1(p, &st));
        for (PetscInt i = 0; i < p; i++) st[i] = (PetscInt)out[i];
      }
      PetscCall(ISCreateGeneral(comm, rank ? 0 : p, st, PETSC_OWN_POINTER, &is));
      PetscCall(PetscObjectSetName((PetscObject)is, names[k]));
      PetscCall(ISView(is, viewer));
      PetscCall(ISDestroy(&is));
    }
  }
  PetscCall(PetscViewerHDF5PopGroup(viewer));
  PetscCall(PetscViewerDestroy(&viewer));
  PetscCall(PetscFree3(ul, rl, locstate));
  if (rank == 0) PetscCall(PetscFree3(tags, perm, buf));
  PetscCall(WriteXDMF(dm, file));
  PetscFunctionReturn(0);
}
