/* HDF5 output: the displacement on the mesh (PETSc's visualization layout + an XDMF file) and the group /contact. */
#include "sceneimpl.h"
#include <unistd.h>
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
static PetscErrorCode ContactFileOrder(MPI_Comm comm, PetscInt n, const PetscInt tag[], PetscInt *p, PetscInt pos[])
{
  IS              local, all;
  const PetscInt *tags;
  PetscInt       *sorted;

  PetscFunctionBegin;
  PetscCall(ISCreateGeneral(comm, n, tag, PETSC_USE_POINTER, &local));
  PetscCall(ISAllGather(local, &all));
  PetscCall(ISGetLocalSize(all, p));
  PetscCall(ISGetIndices(all, &tags));
  PetscCall(PetscMalloc1(*p, &sorted));
  PetscCall(PetscArraycpy(sorted, tags, *p));
  PetscCall(ISRestoreIndices(all, &tags));
  PetscCall(PetscSortInt(*p, sorted));
  for (PetscInt i = 0; i < n; i++) PetscCall(PetscFindInt(tag[i], *p, sorted, &pos[i]));
  PetscCall(PetscFree(sorted));
  PetscCall(ISDestroy(&all));
  PetscCall(ISDestroy(&local));
  PetscFunctionReturn(0);
}

/* The XDMF file beside an HDF5 file: x.h5 -> x.xmf */
static PetscErrorCode XDMFName(const char h5[], char xmf[], size_t size)
{
  size_t len;

  PetscFunctionBegin;
  PetscCall(PetscStrlen(h5, &len));
  PetscCall(PetscStrncpy(xmf, h5, size));
  if (len > 3 && !strcmp(h5 + len - 3, ".h5")) xmf[len - 3] = 0;
  PetscCall(PetscStrlcat(xmf, ".xmf", size));
  PetscFunctionReturn(0);
}

/* Writes xmf, which opens the mesh and displacement of the HDF5 file h5 (named without its folder: they sit side by side) */
static PetscErrorCode WriteXDMF(DM dm, const char h5[], const char xmf[])
{
  MPI_Comm    comm = PetscObjectComm((PetscObject)dm);
  PetscInt    cStart, cEnd, ncells, nverts, nloc;
  Vec         coordinates;
  PetscMPIInt rank;
  const char *base;
  FILE       *fp;

  PetscFunctionBegin;
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  nloc = cEnd - cStart;
  PetscCall(MPIU_Allreduce(&nloc, &ncells, 1, MPIU_INT, MPI_SUM, comm));
  PetscCall(DMGetCoordinates(dm, &coordinates));
  PetscCall(VecGetSize(coordinates, &nverts));
  nverts /= 3;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
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

/* An integer dataset (/contact/state, /contact/group) of p entries, from a field held by rank 0 */
static PetscErrorCode WriteIntField(PetscViewer viewer, const char name[], Vec field)
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
  dset      = H5Dcreate2(group, name, H5T_NATIVE_INT, filespace, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  PetscCheck(filespace >= 0 && memspace >= 0 && dset >= 0, comm, PETSC_ERR_LIB, "HDF5 could not create the dataset /contact/%s", name);
  if (!n) {
    H5Sselect_none(filespace);
    H5Sselect_none(memspace);
  }
  status = H5Dwrite(dset, H5T_NATIVE_INT, memspace, filespace, H5P_DEFAULT, st);
  PetscCheck(status >= 0, comm, PETSC_ERR_LIB, "HDF5 could not write the dataset /contact/%s", name);
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

/* The datasets of /contact: per contact node, in the order of the mesh file */
static PetscErrorCode WriteContact(SSStarScene scene, PetscViewer viewer, Vec u, Vec r, const SSStarState states[])
{
  MPI_Comm           comm = scene->comm;
  PetscInt           p, n = scene->n, *pos;
  PetscReal         *ul, *rl, *sl, *gl;
  const PetscScalar *ua, *ra;
  Vec                field, uC, rC;
  char               names[1024] = "";

  PetscFunctionBegin;
  PetscCall(PetscMalloc5(n, &pos, 3 * n, &ul, 3 * n, &rl, n, &sl, n, &gl));
  PetscCall(ContactFileOrder(comm, n, scene->tag, &p, pos));
  PetscCall(VecGetSubVector(u, scene->isC, &uC));
  PetscCall(VecGetSubVector(r, scene->isC, &rC));
  PetscCall(VecGetArrayRead(uC, &ua));
  PetscCall(VecGetArrayRead(rC, &ra));
  for (PetscInt i = 0; i < 3 * n; i++) {
    ul[i] = PetscRealPart(ua[i]);
    rl[i] = PetscRealPart(ra[i]);
  }
  PetscCall(VecRestoreArrayRead(rC, &ra));
  PetscCall(VecRestoreArrayRead(uC, &ua));
  PetscCall(VecRestoreSubVector(r, scene->isC, &rC));
  PetscCall(VecRestoreSubVector(u, scene->isC, &uC));
  PetscCall(PetscViewerHDF5PushGroup(viewer, "/contact"));
  {
    const char      *vnames[7]  = {"coordinates", "displacement", "reaction", "normal", "gap", "area", NULL};
    const PetscReal *values[7]  = {scene->coords, ul, rl, scene->normal, scene->gap, scene->area, NULL};
    const PetscInt   bs[7]      = {3, 3, 3, 3, 1, 1, 0};

    for (PetscInt k = 0; vnames[k]; k++) {
      PetscCall(ContactFieldCreate(comm, p, n, pos, bs[k], values[k], vnames[k], &field));
      PetscCall(VecView(field, viewer));
      PetscCall(VecDestroy(&field));
    }
  }
  for (PetscInt i = 0; i < n; i++) {
    sl[i] = states ? (PetscReal)states[i] : -1;
    gl[i] = (PetscReal)scene->group[i];
  }
  PetscCall(ContactFieldCreate(comm, p, n, pos, 1, sl, "state", &field));
  PetscCall(WriteIntField(viewer, "state", field));
  PetscCall(VecDestroy(&field));
  PetscCall(ContactFieldCreate(comm, p, n, pos, 1, gl, "group", &field));
  PetscCall(WriteIntField(viewer, "group", field));
  PetscCall(VecDestroy(&field));
  for (PetscInt g = 0; g < scene->nContact; g++) {
    if (g) PetscCall(PetscStrlcat(names, ",", sizeof(names)));
    PetscCall(PetscStrlcat(names, scene->contact[g].name, sizeof(names)));
  }
  PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/contact/group", "names", PETSC_STRING, names));
  PetscCall(PetscViewerHDF5PopGroup(viewer));
  PetscCall(PetscFree5(pos, ul, rl, sl, gl));
  PetscFunctionReturn(0);
}

/* Everything into the temporary files h5 and xmf, xmf naming the HDF5 file final */
static PetscErrorCode WriteFiles(SSStarScene scene, const char h5[], const char xmf[], const char final[], Vec u, Vec r, const SSStarState states[], PetscErrorCode (*extra)(PetscViewer, void *), void *ctx)
{
  PetscViewer viewer;

  PetscFunctionBegin;
  PetscCall(PetscObjectSetName((PetscObject)u, "displacement"));
  PetscCall(PetscViewerHDF5Open(scene->comm, h5, FILE_MODE_WRITE, &viewer));
  PetscCall(PetscViewerPushFormat(viewer, PETSC_VIEWER_HDF5_VIZ));
  PetscCall(DMView(scene->dm, viewer));
  PetscCall(VecView(u, viewer));
  PetscCall(PetscViewerPopFormat(viewer));
  if (scene->nContact) PetscCall(WriteContact(scene, viewer, u, r, states));
  if (extra) PetscCall((*extra)(viewer, ctx));
  PetscCall(PetscViewerDestroy(&viewer));
  PetscCall(WriteXDMF(scene->dm, final, xmf));
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneWriteSolution - writes file (HDF5) and the XDMF file beside it (x.h5 -> x.xmf, for ParaView): the
   displacement u on the mesh and, with contact, the group /contact of the contact nodes in file order: coordinates,
   displacement, reaction (global axes, p x 3), normal (p x 3), gap, area (p), state and group (p, integers)

   Input Parameters:
+  scene  - the scene
.  file   - the HDF5 file
.  u      - the displacement (a global vector of the scene's DM)
.  r      - K u - b (the contact forces at the contact dofs), or NULL without contact
.  states - the states of the owned contact nodes, or NULL (written as -1)
.  extra  - NULL, or a function adding the caller's datasets to the open file
-  ctx    - its context

   Notes:
   Both files are written to temporary names and renamed when complete: a failure leaves no file behind.
@*/
PetscErrorCode SSStarSceneWriteSolution(SSStarScene scene, const char file[], Vec u, Vec r, const SSStarState states[], PetscErrorCode (*extra)(PetscViewer, void *), void *ctx)
{
  char           xmf[PETSC_MAX_PATH_LEN], tmpH5[PETSC_MAX_PATH_LEN], tmpXmf[PETSC_MAX_PATH_LEN];
  int            pid = (int)getpid();
  PetscMPIInt    rank, failure = 0;
  PetscErrorCode ierr;

  PetscFunctionBegin;
  PetscCheck(!scene->nContact || r, scene->comm, PETSC_ERR_ARG_NULL, "SSStarSceneWriteSolution: a scene with contact needs the contact forces r");
  PetscCall(PetscLogEventBegin(SSSTAR_Output, 0, 0, 0, 0));
  PetscCall(SSStarCheckOutputFile(scene->comm, file));
  PetscCallMPI(MPI_Comm_rank(scene->comm, &rank));
  PetscCallMPI(MPI_Bcast(&pid, 1, MPI_INT, 0, scene->comm));
  PetscCall(XDMFName(file, xmf, sizeof(xmf)));
  PetscCall(PetscSNPrintf(tmpH5, sizeof(tmpH5), "%s.%d.tmp", file, pid));
  PetscCall(PetscSNPrintf(tmpXmf, sizeof(tmpXmf), "%s.%d.tmp", xmf, pid));
  ierr = WriteFiles(scene, tmpH5, tmpXmf, file, u, r, states, extra, ctx);
  if (rank == 0) {
    if (ierr) {
      (void)remove(tmpH5);
      (void)remove(tmpXmf);
    } else failure = rename(tmpH5, file) || rename(tmpXmf, xmf);
  }
  PetscCall(ierr);
  PetscCallMPI(MPI_Bcast(&failure, 1, MPI_INT, 0, scene->comm));
  PetscCheck(!failure, scene->comm, PETSC_ERR_FILE_WRITE, "Cannot rename the written files to %s and %s", file, xmf);
  PetscCall(PetscLogEventEnd(SSSTAR_Output, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}
