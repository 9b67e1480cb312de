/* HDF5 output: the displacement on the mesh (PETSc's visualization layout + an XDMF file) and the group /contact. */
#include <ssstarcontact.h>
#include <petscviewerhdf5.h>

/*
   A field of the contact nodes (bs values per node) as a vector held whole by rank 0 in file order, so that
   the HDF5 dataset does not depend on the partition; pos[] is the file-order position of each local node.
*/
static PetscErrorCode ContactFieldCreate(MPI_Comm comm, PetscInt p, PetscInt nloc, const PetscInt pos[], PetscInt bs, const PetscReal values[], const char name[], Vec *v)
{
  PetscMPIInt rank;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(VecCreateMPI(comm, rank ? 0 : p * bs, p * bs, v));
  PetscCall(VecSetBlockSize(*v, bs));
  PetscCall(PetscObjectSetName((PetscObject)*v, name));
  for (PetscInt i = 0; i < nloc; i++)
    for (PetscInt k = 0; k < bs; k++) PetscCall(VecSetValue(*v, pos[i] * bs + k, values[i * bs + k], INSERT_VALUES));
  PetscCall(VecAssemblyBegin(*v));
  PetscCall(VecAssemblyEnd(*v));
  PetscFunctionReturn(0);
}

/* Position of each local contact node in the file order of all contact nodes */
static PetscErrorCode ContactFileOrder(MPI_Comm comm, const SSStarContactNodes *cn, PetscInt *p, PetscInt pos[])
{
  IS              local, all;
  const PetscInt *tags;
  PetscInt       *sorted;

  PetscFunctionBegin;
  PetscCall(ISCreateGeneral(comm, cn->n, cn->tag, PETSC_USE_POINTER, &local));
  PetscCall(ISAllGather(local, &all));
  PetscCall(ISGetLocalSize(all, p));
  PetscCall(ISGetIndices(all, &tags));
  PetscCall(PetscMalloc1(*p, &sorted));
  PetscCall(PetscArraycpy(sorted, tags, *p));
  PetscCall(ISRestoreIndices(all, &tags));
  PetscCall(PetscSortInt(*p, sorted));
  for (PetscInt i = 0; i < cn->n; i++) PetscCall(PetscFindInt(cn->tag[i], *p, sorted, &pos[i]));
  PetscCall(PetscFree(sorted));
  PetscCall(ISDestroy(&all));
  PetscCall(ISDestroy(&local));
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

/* /contact/state: a one-dimensional integer dataset of p entries, from a field held by rank 0 */
static PetscErrorCode WriteStates(PetscViewer viewer, Vec field)
{
  MPI_Comm           comm = PetscObjectComm((PetscObject)viewer);
  hid_t              file, group, filespace, memspace, dset;
  hsize_t            p, m;
  PetscInt           N, n;
  int               *st;
  const PetscScalar *fa;
  herr_t             status;

  PetscFunctionBegin;
  PetscCall(VecGetSize(field, &N));
  PetscCall(VecGetLocalSize(field, &n));
  p = (hsize_t)N;
  m = (hsize_t)n;
  PetscCall(PetscMalloc1(n, &st));
  PetscCall(VecGetArrayRead(field, &fa));
  for (PetscInt i = 0; i < n; i++) st[i] = (int)PetscRealPart(fa[i]);
  PetscCall(VecRestoreArrayRead(field, &fa));
  PetscCall(PetscViewerHDF5OpenGroup(viewer, NULL, &file, &group));
  filespace = H5Screate_simple(1, &p, NULL);
  memspace  = H5Screate_simple(1, &m, NULL);
  dset      = H5Dcreate2(group, "state", H5T_NATIVE_INT, filespace, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  PetscCheck(filespace >= 0 && memspace >= 0 && dset >= 0, comm, PETSC_ERR_LIB, "HDF5 could not create the dataset /contact/state");
  if (!n) {
    H5Sselect_none(filespace);
    H5Sselect_none(memspace);
  }
  status = H5Dwrite(dset, H5T_NATIVE_INT, memspace, filespace, H5P_DEFAULT, st);
  PetscCheck(status >= 0, comm, PETSC_ERR_LIB, "HDF5 could not write the dataset /contact/state");
  H5Dclose(dset);
  H5Sclose(memspace);
  H5Sclose(filespace);
  if (group != file) H5Gclose(group);
  PetscCall(PetscFree(st));
  PetscFunctionReturn(0);
}

/*@C
   SSStarCheckOutputFile - errors out, naming the file, when file cannot be created (its folder is missing or read-only)
@*/
PetscErrorCode SSStarCheckOutputFile(MPI_Comm comm, const char file[])
{
  char      dir[PETSC_MAX_PATH_LEN];
  char     *slash;
  PetscBool ok;

  PetscFunctionBegin;
  PetscCall(PetscStrncpy(dir, file, sizeof(dir)));
  slash = strrchr(dir, '/');
  if (slash) *slash = 0;
  else PetscCall(PetscStrncpy(dir, ".", sizeof(dir)));
  PetscCall(PetscTestDirectory(dir[0] ? dir : "/", 'w', &ok));
  PetscCheck(ok, comm, PETSC_ERR_FILE_OPEN, "Cannot write %s: %s is not a writable folder", file, dir[0] ? dir : "/");
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
  PetscInt           p, *pos;
  PetscReal         *ul, *rl, *sl;
  const PetscScalar *ua, *ra;
  Vec                field;

  PetscFunctionBegin;
  PetscCall(SSStarCheckOutputFile(comm, file));
  PetscCall(PetscObjectSetName((PetscObject)u, "displacement"));
  PetscCall(PetscViewerHDF5Open(comm, file, FILE_MODE_WRITE, &viewer));
  PetscCall(PetscViewerPushFormat(viewer, PETSC_VIEWER_HDF5_VIZ));
  PetscCall(DMView(dm, viewer));
  PetscCall(VecView(u, viewer));
  PetscCall(PetscViewerPopFormat(viewer));

  PetscCall(PetscMalloc4(cn->n, &pos, 3 * cn->n, &ul, 3 * cn->n, &rl, cn->n, &sl));
  PetscCall(ContactFileOrder(comm, cn, &p, pos));
  PetscCall(VecGetArrayRead(uC, &ua));
  PetscCall(VecGetArrayRead(rC, &ra));
  for (PetscInt i = 0; i < 3 * cn->n; i++) {
    ul[i] = PetscRealPart(ua[i]);
    rl[i] = PetscRealPart(ra[i]);
  }
  PetscCall(VecRestoreArrayRead(rC, &ra));
  PetscCall(VecRestoreArrayRead(uC, &ua));
  for (PetscInt i = 0; i < cn->n; i++) sl[i] = (PetscReal)states[i];

  PetscCall(PetscViewerHDF5PushGroup(viewer, "/contact"));
  {
    const char      *names[3]  = {"coordinates", "displacement", "reaction"};
    const PetscReal *values[3] = {cn->coords, ul, rl};

    for (PetscInt k = 0; k < 3; k++) {
      PetscCall(ContactFieldCreate(comm, p, cn->n, pos, 3, values[k], names[k], &field));
      PetscCall(VecView(field, viewer));
      PetscCall(VecDestroy(&field));
    }
  }
  PetscCall(ContactFieldCreate(comm, p, cn->n, pos, 1, sl, "state", &field));
  PetscCall(WriteStates(viewer, field));
  PetscCall(VecDestroy(&field));
  PetscCall(PetscViewerHDF5PopGroup(viewer));
  PetscCall(PetscViewerDestroy(&viewer));
  PetscCall(PetscFree4(pos, ul, rl, sl));
  PetscCall(WriteXDMF(dm, file));
  PetscFunctionReturn(0);
}
