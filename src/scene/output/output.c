/*
   HDF5 output of a scene's solution, the same file on any number of ranks (README "Output"):

     /geometry/vertices, /fields/displacement  every mesh vertex in the mesh file's node order (fileorder.c)
     /viz/topology/cells                       the tetrahedra by their vertices' file numbers, in a canonical order
     /contact/...                              per contact node, in file order (contact.c)
     /contact_faces/...                        the contact faces' triangles and the point fields ParaView colours them by
     /scene/...                                what was simulated: mesh, material, loads, contact groups (metadata.c)
     attributes of /                           how: versions, command line, reason, iterations, ||z||, tolerance

   and the XDMF file beside it with two grids, the mesh and the contact faces; both written to temporary names and
   renamed when complete.
*/
#include "outputimpl.h"
#include <unistd.h>

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

static PetscErrorCode XDMFAttribute(FILE *fp, const char base[], const char name[], const char path[], PetscInt rows, PetscInt cols, PetscBool isInt)
{
  char dims[64];

  PetscFunctionBegin;
  if (cols) PetscCall(PetscSNPrintf(dims, sizeof(dims), "%" PetscInt_FMT " %" PetscInt_FMT, rows, cols));
  else PetscCall(PetscSNPrintf(dims, sizeof(dims), "%" PetscInt_FMT, rows));
  PetscCall(PetscFPrintf(PETSC_COMM_SELF, fp, "   <Attribute Name=\"%s\" AttributeType=\"%s\" Center=\"Node\">\n    <DataItem Dimensions=\"%s\" NumberType=\"%s\" Precision=\"%d\" Format=\"HDF\">%s:%s</DataItem>\n   </Attribute>\n", name, cols ? "Vector" : "Scalar", dims, isInt ? "Int" : "Float", isInt ? 4 : 8, base, path));
  PetscFunctionReturn(0);
}

/*
   Writes xmf (rank 0): the grid "mesh" (tetrahedra, displacement) and, with contact, the grid "contact" (the contact
   faces' triangles with the state, pressure, tangential traction, slip, gap and displacement of their vertices), both
   naming the HDF5 file h5 without its folder (they sit side by side)
*/
static PetscErrorCode WriteXDMF(SSStarScene scene, const char h5[], const char xmf[], PetscInt nfaceVertices, PetscInt ntriangles)
{
  PetscMPIInt rank;
  const char *base;
  FILE       *fp;
  const PetscInt N = scene->nodesGlobal, C = scene->cellsGlobal;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(scene->comm, &rank));
  if (rank) PetscFunctionReturn(0);
  base = strrchr(h5, '/');
  base = base ? base + 1 : h5;
  PetscCall(PetscFOpen(PETSC_COMM_SELF, xmf, "w", &fp));
  PetscCall(PetscFPrintf(PETSC_COMM_SELF, fp, "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"2.0\">\n <Domain>\n"));
  PetscCall(PetscFPrintf(PETSC_COMM_SELF, fp,
                         "  <Grid Name=\"mesh\" GridType=\"Uniform\">\n"
                         "   <Topology TopologyType=\"Tetrahedron\" NumberOfElements=\"%" PetscInt_FMT "\">\n"
                         "    <DataItem Dimensions=\"%" PetscInt_FMT " 4\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">%s:/viz/topology/cells</DataItem>\n"
                         "   </Topology>\n"
                         "   <Geometry GeometryType=\"XYZ\">\n"
                         "    <DataItem Dimensions=\"%" PetscInt_FMT " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/geometry/vertices</DataItem>\n"
                         "   </Geometry>\n",
                         C, C, base, N, base));
  PetscCall(XDMFAttribute(fp, base, "displacement", "/fields/displacement", N, 3, PETSC_FALSE));
  PetscCall(PetscFPrintf(PETSC_COMM_SELF, fp, "  </Grid>\n"));
  if (scene->nContact) {
    const PetscInt q = nfaceVertices;

    PetscCall(PetscFPrintf(PETSC_COMM_SELF, fp,
                           "  <Grid Name=\"contact\" GridType=\"Uniform\">\n"
                           "   <Topology TopologyType=\"Triangle\" NumberOfElements=\"%" PetscInt_FMT "\">\n"
                           "    <DataItem Dimensions=\"%" PetscInt_FMT " 3\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">%s:/contact_faces/triangles</DataItem>\n"
                           "   </Topology>\n"
                           "   <Geometry GeometryType=\"XYZ\">\n"
                           "    <DataItem Dimensions=\"%" PetscInt_FMT " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/contact_faces/vertices</DataItem>\n"
                           "   </Geometry>\n",
                           ntriangles, ntriangles, base, q, base));
    PetscCall(XDMFAttribute(fp, base, "state", "/contact_faces/state", q, 0, PETSC_TRUE));
    PetscCall(XDMFAttribute(fp, base, "pressure", "/contact_faces/pressure", q, 0, PETSC_FALSE));
    PetscCall(XDMFAttribute(fp, base, "tangential_traction", "/contact_faces/tangential_traction", q, 3, PETSC_FALSE));
    PetscCall(XDMFAttribute(fp, base, "slip", "/contact_faces/slip", q, 3, PETSC_FALSE));
    PetscCall(XDMFAttribute(fp, base, "gap", "/contact_faces/gap", q, 0, PETSC_FALSE));
    PetscCall(XDMFAttribute(fp, base, "displacement", "/contact_faces/displacement", q, 3, PETSC_FALSE));
    PetscCall(PetscFPrintf(PETSC_COMM_SELF, fp, "  </Grid>\n"));
  }
  PetscCall(PetscFPrintf(PETSC_COMM_SELF, fp, " </Domain>\n</Xdmf>\n"));
  PetscCall(PetscFClose(PETSC_COMM_SELF, fp));
  PetscFunctionReturn(0);
}

/*@C
   SSStarCheckOutputFile - errors out, naming the file, when file cannot be created (its folder is missing or read-only)

   Collective

   Input Parameters:
+  comm - the ranks that will write the file
-  file - the file name

   Notes:
   The drivers call it before any work, so that a run does not end, after its solve, on a file it cannot write.

   Level: beginner

.seealso: `SSStarSceneWriteSolution()`
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

/* Everything into the temporary files h5 and xmf, xmf naming the HDF5 file final */
static PetscErrorCode WriteFiles(SSStarScene scene, SNES snes, const char h5[], const char xmf[], const char final[], Vec u, PetscErrorCode (*extra)(PetscViewer, void *), void *ctx)
{
  PetscViewer        viewer;
  hid_t              file;
  Vec                r     = NULL;
  const SSStarState *states = NULL;
  PetscBool          isssstar;
  PetscInt           nfaceVertices = 0, ntriangles = 0;
  SSStarNodeFriction nf;

  PetscFunctionBegin;
  PetscCall(PetscViewerHDF5Open(scene->comm, h5, FILE_MODE_WRITE, &viewer));
  PetscCall(PetscViewerHDF5GetFileId(viewer, &file));
  PetscCall(SSStarWriteMesh(scene, file, u));
  PetscCall(SSStarWriteRun(scene, file, snes));
  {
    PetscInt *laws; /* the groups' laws, for an SNES that is no ssstar */

    PetscCall(PetscMalloc1(scene->n + 1, &laws));
    for (PetscInt i = 0; i < scene->n; i++) laws[i] = scene->contact[scene->group[i]].law;
    PetscCall(SSStarNodeFrictionGet(scene->comm, snes, scene->n, laws, &nf));
    PetscCall(PetscFree(laws));
  }
  PetscCall(SSStarWriteScene(scene, file, &nf));
  if (scene->nContact) {
    PetscCall(PetscObjectTypeCompare((PetscObject)snes, SNESSSSTAR, &isssstar));
    if (isssstar) PetscCall(SNESSSStarGetStates(snes, &states, NULL));
    PetscCall(SNESGetFunction(snes, &r, NULL, NULL)); /* K u - b: the contact forces at the contact dofs */
    PetscCall(SSStarWriteContact(scene, file, u, r, states, &nf));
    PetscCall(SSStarWriteContactFaces(scene, file, u, r, states, &nfaceVertices, &ntriangles));
  }
  PetscCall(SSStarNodeFrictionDestroy(&nf));
  if (extra) PetscCall((*extra)(viewer, ctx));
  PetscCall(PetscViewerDestroy(&viewer));
  PetscCall(WriteXDMF(scene, final, xmf, nfaceVertices, ntriangles));
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneWriteSolution - writes the solution of a scene and what it was (HDF5), with the XDMF file beside it
   (x.h5 -> x.xmf) that ParaView opens

   Collective

   Input Parameters:
+  scene - the scene
.  snes  - the SNES that solved it (an ssstar, or any SNES for a scene without contact), after SNESSolve()
.  file  - the HDF5 file
.  u     - the displacement (a global vector of the scene's DM)
.  extra - NULL, or a function adding the caller's datasets to the open file
-  ctx   - its context

   Notes:
   The file is the same on any number of ranks: the vertices in the mesh file's node order (/geometry/vertices,
   /fields/displacement with the held nodes), the tetrahedra by their vertices' numbers in a canonical order
   (/viz/topology/cells), the contact nodes in file order (/contact: coordinates, displacement, reaction K u - b,
   normal, gap, area, friction_law and one dataset per parameter of the laws in use (friction, slip_bound, friction_1,
   friction_2, friction_direction: 0 where a node's law has no such parameter), state, group (a contact pair named slave->master), and at the
   solution final_gap, pressure, traction, slip against the plane or the master surface), the contact faces with their point fields
   (/contact_faces: vertices, triangles, state, pressure, tangential_traction, slip, gap, displacement), the scene
   (/scene: mesh, material, loads, contact groups with their laws) and, as attributes of /, the run: ssstar_version,
   petsc_version, command_line, ranks, snes_type, converged_reason, converged_reason_code, iterations, residual_norm
   (||z|| for ssstar), rtol, atol, max_it and, for ssstar, sub_reason, tolerance, scaling, reduction, state_counts,
   state_names. README "Output" lists them all.

   Both files are written to temporary names and renamed when complete: a failure leaves no file behind.

   Level: beginner

.seealso: `SSStarSceneSetContact()`, `SNESSSStarGetStates()`, `SSStarWriteNodeFriction()`, `SSStarCheckOutputFile()`
@*/
PetscErrorCode SSStarSceneWriteSolution(SSStarScene scene, SNES snes, const char file[], Vec u, PetscErrorCode (*extra)(PetscViewer, void *), void *ctx)
{
  char           xmf[PETSC_MAX_PATH_LEN], tmpH5[PETSC_MAX_PATH_LEN], tmpXmf[PETSC_MAX_PATH_LEN];
  int            pid = (int)getpid();
  PetscMPIInt    rank, failure = 0;
  PetscErrorCode ierr;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(SSSTAR_Output, 0, 0, 0, 0));
  PetscCall(SSStarCheckOutputFile(scene->comm, file));
  PetscCallMPI(MPI_Comm_rank(scene->comm, &rank));
  PetscCallMPI(MPI_Bcast(&pid, 1, MPI_INT, 0, scene->comm));
  PetscCall(XDMFName(file, xmf, sizeof(xmf)));
  PetscCall(PetscSNPrintf(tmpH5, sizeof(tmpH5), "%s.%d.tmp", file, pid));
  PetscCall(PetscSNPrintf(tmpXmf, sizeof(tmpXmf), "%s.%d.tmp", xmf, pid));
  ierr = WriteFiles(scene, snes, tmpH5, tmpXmf, file, u, extra, ctx);
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
