/*
   HDF5 output of a scene's solution, the same file on any number of ranks (docs/guide/output.md):

     /geometry/vertices, /fields/displacement  every mesh vertex in the mesh file's node order (fileorder.c)
     /viz/topology/cells                       the tetrahedra by their vertices' file numbers, in a canonical order
     /fields/strain, stress, von_mises         per tetrahedron in that order; /fields/stress_nodal per vertex (stress.c)
     /groups/<G>/reaction                      the force of each held group (-dirichlet, -displacement_<G>) on the body
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

/*
   An attribute of a grid: at its nodes or cells, a scalar (cols 0), a vector (3) or a symmetric tensor (6: our
   columns xx, yy, zz, yz, xz, xy joined in XDMF's Tensor6 order xx, xy, xz, yy, yz, zz, so that VTK's reader, and
   ParaView, make the full tensor of each point with its components where they belong)
*/
static PetscErrorCode XDMFAttribute(FILE *fp, const char base[], const char name[], const char path[], PetscInt rows, PetscInt cols, PetscBool isInt, PetscBool cell)
{
  const char *center = cell ? "Cell" : "Node";
  char        dims[64];

  PetscFunctionBegin;
  if (cols == 6) {
    const PetscInt xdmf[6] = {0, 5, 4, 1, 3, 2}; /* our column of each Tensor6 component */

    PetscCall(PetscFPrintf(PETSC_COMM_SELF, fp, "   <Attribute Name=\"%s\" AttributeType=\"Tensor6\" Center=\"%s\">\n    <DataItem ItemType=\"Function\" Function=\"JOIN($0, $1, $2, $3, $4, $5)\" Dimensions=\"%" PetscInt_FMT " 6\">\n", name, center, rows));
    for (PetscInt k = 0; k < 6; k++)
      PetscCall(PetscFPrintf(PETSC_COMM_SELF, fp, "     <DataItem ItemType=\"HyperSlab\" Dimensions=\"%" PetscInt_FMT " 1\" Type=\"HyperSlab\">\n      <DataItem Dimensions=\"3 2\" Format=\"XML\">0 %" PetscInt_FMT " 1 1 %" PetscInt_FMT " 1</DataItem>\n      <DataItem Dimensions=\"%" PetscInt_FMT " 6\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:%s</DataItem>\n     </DataItem>\n", rows, xdmf[k], rows, rows, base, path));
    PetscCall(PetscFPrintf(PETSC_COMM_SELF, fp, "    </DataItem>\n   </Attribute>\n"));
    PetscFunctionReturn(0);
  }
  if (cols) PetscCall(PetscSNPrintf(dims, sizeof(dims), "%" PetscInt_FMT " %" PetscInt_FMT, rows, cols));
  else PetscCall(PetscSNPrintf(dims, sizeof(dims), "%" PetscInt_FMT, rows));
  PetscCall(PetscFPrintf(PETSC_COMM_SELF, fp, "   <Attribute Name=\"%s\" AttributeType=\"%s\" Center=\"%s\">\n    <DataItem Dimensions=\"%s\" NumberType=\"%s\" Precision=\"%d\" Format=\"HDF\">%s:%s</DataItem>\n   </Attribute>\n", name, cols ? "Vector" : "Scalar", center, dims, isInt ? "Int" : "Float", isInt ? 4 : 8, base, path));
  PetscFunctionReturn(0);
}

/* The grid "mesh" at one state: the tetrahedra with the fields of <prefix>/fields: the displacement and the recovered
   stress at the nodes, the strain, stress and von Mises stress of the cells */
static PetscErrorCode XDMFMeshGrid(SSStarScene scene, FILE *fp, const char base[], const char prefix[], const char time[])
{
  const PetscInt N = scene->nodesGlobal, C = scene->cellsGlobal;
  char           path[PETSC_MAX_PATH_LEN];

  PetscFunctionBegin;
  PetscCall(PetscFPrintf(PETSC_COMM_SELF, fp,
                         "  <Grid Name=\"mesh\" GridType=\"Uniform\">\n%s"
                         "   <Topology TopologyType=\"Tetrahedron\" NumberOfElements=\"%" PetscInt_FMT "\">\n"
                         "    <DataItem Dimensions=\"%" PetscInt_FMT " 4\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">%s:/viz/topology/cells</DataItem>\n"
                         "   </Topology>\n"
                         "   <Geometry GeometryType=\"XYZ\">\n"
                         "    <DataItem Dimensions=\"%" PetscInt_FMT " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/geometry/vertices</DataItem>\n"
                         "   </Geometry>\n",
                         time, C, C, base, N, base));
  {
    const char    *names[] = {"displacement", "stress_nodal", "strain", "stress", "von_mises"};
    const PetscInt cols[]  = {3, 6, 6, 6, 0};

    for (size_t k = 0; k < PETSC_STATIC_ARRAY_LENGTH(names); k++) {
      PetscCall(PetscSNPrintf(path, sizeof(path), "%s/fields/%s", prefix, names[k]));
      PetscCall(XDMFAttribute(fp, base, names[k], path, k < 2 ? N : C, cols[k], PETSC_FALSE, (PetscBool)(k >= 2)));
    }
  }
  PetscCall(PetscFPrintf(PETSC_COMM_SELF, fp, "  </Grid>\n"));
  PetscFunctionReturn(0);
}

/* The grid "contact" at one state: the contact faces' triangles with the point fields at <prefix>/contact_faces */
static PetscErrorCode XDMFContactGrid(FILE *fp, const char base[], const char prefix[], const char time[], PetscInt q, PetscInt ntriangles)
{
  const char    *names[] = {"state", "pressure", "tangential_traction", "slip", "gap", "displacement"};
  const PetscInt cols[]  = {0, 0, 3, 3, 0, 3};
  char           path[PETSC_MAX_PATH_LEN];

  PetscFunctionBegin;
  PetscCall(PetscFPrintf(PETSC_COMM_SELF, fp,
                         "  <Grid Name=\"contact\" GridType=\"Uniform\">\n%s"
                         "   <Topology TopologyType=\"Triangle\" NumberOfElements=\"%" PetscInt_FMT "\">\n"
                         "    <DataItem Dimensions=\"%" PetscInt_FMT " 3\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">%s:/contact_faces/triangles</DataItem>\n"
                         "   </Topology>\n"
                         "   <Geometry GeometryType=\"XYZ\">\n"
                         "    <DataItem Dimensions=\"%" PetscInt_FMT " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/contact_faces/vertices</DataItem>\n"
                         "   </Geometry>\n",
                         time, ntriangles, ntriangles, base, q, base));
  for (size_t k = 0; k < PETSC_STATIC_ARRAY_LENGTH(names); k++) {
    PetscCall(PetscSNPrintf(path, sizeof(path), "%s/contact_faces/%s", prefix, names[k]));
    PetscCall(XDMFAttribute(fp, base, names[k], path, q, cols[k], (PetscBool)(k == 0), PETSC_FALSE));
  }
  PetscCall(PetscFPrintf(PETSC_COMM_SELF, fp, "  </Grid>\n"));
  PetscFunctionReturn(0);
}

/*
   Writes xmf (rank 0): the grid "mesh" (tetrahedra, displacement) and, with contact, the grid "contact" (the contact
   faces' triangles with the state, pressure, tangential traction, slip, gap and displacement of their vertices), both
   naming the HDF5 file h5 without its folder (they sit side by side). Along a load path (nsteps > 0 at the times
   times) each is a temporal collection of one grid per step (/steps/<k>), which ParaView animates.
*/
static PetscErrorCode WriteXDMF(SSStarScene scene, const char h5[], const char xmf[], PetscInt nfaceVertices, PetscInt ntriangles, PetscInt nsteps, const PetscReal times[])
{
  PetscMPIInt rank;
  const char *base;
  FILE       *fp;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(scene->comm, &rank));
  if (rank) PetscFunctionReturn(0);
  base = strrchr(h5, '/');
  base = base ? base + 1 : h5;
  PetscCall(PetscFOpen(PETSC_COMM_SELF, xmf, "w", &fp));
  PetscCall(PetscFPrintf(PETSC_COMM_SELF, fp, "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"2.0\">\n <Domain>\n"));
  for (PetscInt grid = 0; grid < (scene->nContact ? 2 : 1); grid++) {
    if (nsteps) PetscCall(PetscFPrintf(PETSC_COMM_SELF, fp, "  <Grid Name=\"%s\" GridType=\"Collection\" CollectionType=\"Temporal\">\n", grid ? "contact" : "mesh"));
    for (PetscInt k = 0; k < PetscMax(nsteps, 1); k++) {
      char prefix[64] = "", time[96] = "";

      if (nsteps) {
        PetscCall(PetscSNPrintf(prefix, sizeof(prefix), "/steps/%" PetscInt_FMT, k));
        PetscCall(PetscSNPrintf(time, sizeof(time), "   <Time Value=\"%.17g\"/>\n", (double)times[k]));
      }
      if (grid) PetscCall(XDMFContactGrid(fp, base, prefix, time, nfaceVertices, ntriangles));
      else PetscCall(XDMFMeshGrid(scene, fp, base, prefix, time));
    }
    if (nsteps) PetscCall(PetscFPrintf(PETSC_COMM_SELF, fp, "  </Grid>\n"));
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

/* A temporary file beside file: file.<pid>.tmp (the same name on every rank) */
static PetscErrorCode TemporaryNames(SSStarScene scene, SSStarSceneOutput out, const char file[])
{
  int pid = (int)getpid();

  PetscFunctionBegin;
  PetscCallMPI(MPI_Bcast(&pid, 1, MPI_INT, 0, scene->comm));
  PetscCall(PetscStrncpy(out->final, file, sizeof(out->final)));
  PetscCall(XDMFName(file, out->xmf, sizeof(out->xmf)));
  PetscCall(PetscSNPrintf(out->tmpH5, sizeof(out->tmpH5), "%s.%d.tmp", file, pid));
  PetscCall(PetscSNPrintf(out->tmpXmf, sizeof(out->tmpXmf), "%s.%d.tmp", out->xmf, pid));
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneOutputBegin - opens the output file of a load path, written step by step (SSStarSceneOutputStep()) and
   completed by SSStarSceneOutputEnd()

   Collective

   Input Parameters:
+  scene - the scene, after SSStarSceneSetUp()
-  file  - the HDF5 file (an XDMF file is written beside it: x.h5 -> x.xmf)

   Notes:
   The file is written to a temporary name and renamed by SSStarSceneOutputEnd(): a run that stops before leaves no
   file of that name. Memory holds one step's fields at a time.

   Level: intermediate

.seealso: `SSStarSceneOutputStep()`, `SSStarSceneOutputEnd()`, `SSStarSceneWriteSolution()`
@*/
PetscErrorCode SSStarSceneOutputBegin(SSStarScene scene, const char file[])
{
  SSStarSceneOutput out;

  PetscFunctionBegin;
  PetscCheck(!scene->output, scene->comm, PETSC_ERR_ARG_WRONGSTATE, "SSStarSceneOutputBegin: the scene is writing %s already", scene->output->final);
  PetscCall(SSStarCheckOutputFile(scene->comm, file));
  PetscCall(PetscNew(&out));
  PetscCall(TemporaryNames(scene, out, file));
  out->failedStep = -1;
  PetscCall(SSStarSceneGetStepColumns(scene, NULL, &out->ncols));
  PetscCall(PetscViewerHDF5Open(scene->comm, out->tmpH5, FILE_MODE_WRITE, &out->viewer));
  PetscCall(PetscViewerHDF5GetFileId(out->viewer, &out->file));
  scene->output = out;
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneOutputStep - appends a step of a load path to the file opened by SSStarSceneOutputBegin(): its fields
   (/steps/<k>/fields/displacement, /steps/<k>/contact/..., /steps/<k>/contact_faces/...) and its row of the table
   /steps (time, iterations, reason, residual_norm, cuts, load, normal_force, tangential_force, area, sliding,
   sticking, separated, dissipation, law_residual, law_displacement_scale, law_force_scale, motion/<G>,
   groups/<G>/displacement)

   Collective

   Input Parameters:
+  scene - the scene, after SSStarSceneSetStep() and the step's solve (and SSStarSceneAcceptStep() if it converged)
.  snes  - the SNES that solved the step
.  u     - the step's solution (or the last iterate of a step that failed)
-  cuts  - how many times the step was halved before it converged (a caller's count; 0 without step cutting)

   Notes:
   k counts the steps written, from 0; the row is SSStarSceneGetStepRow()'s. The first step written whose solve did
   not converge is where the path failed: SSStarSceneOutputEnd() writes its row and time as the attributes
   failed_step and failed_time of "/".

   Level: intermediate

.seealso: `SSStarSceneOutputBegin()`, `SSStarSceneOutputEnd()`, `SSStarSceneSetStep()`, `SSStarSceneAcceptStep()`, `SSStarSceneGetStepRow()`
@*/
PetscErrorCode SSStarSceneOutputStep(SSStarScene scene, SNES snes, Vec u, PetscInt cuts)
{
  SSStarSceneOutput  out = scene->output;
  char               prefix[64];
  Vec                r;
  const SSStarState *states = NULL;
  PetscBool          isssstar;
  PetscInt           nv, nt;
  hid_t              group;

  PetscFunctionBegin;
  PetscCheck(out, scene->comm, PETSC_ERR_ARG_WRONGSTATE, "SSStarSceneOutputStep: call SSStarSceneOutputBegin() first");
  PetscCall(PetscLogEventBegin(SSSTAR_Output, 0, 0, 0, 0));
  if (out->nsteps == out->maxSteps) {
    out->maxSteps = PetscMax(16, 2 * out->maxSteps);
    PetscCall(PetscRealloc(sizeof(PetscReal) * out->maxSteps * out->ncols, &out->table));
  }
  PetscCall(SSStarSceneGetStepRow(scene, snes, u, cuts, &out->table[out->nsteps * out->ncols]));
  PetscCall(PetscSNPrintf(prefix, sizeof(prefix), "/steps/%" PetscInt_FMT, out->nsteps));
  PetscCall(SSStarH5GroupOpen(out->file, prefix, &group));
  PetscCall(SSStarH5AttrReal(group, "time", scene->stepTime));
  PetscCallH5(H5Gclose(group));
  PetscCall(SSStarWriteDisplacement(scene, out->file, prefix, u));
  PetscCall(SSStarWriteStresses(scene, out->file, prefix, u));
  if (scene->nContact) {
    PetscCall(PetscObjectTypeCompare((PetscObject)snes, SNESSSSTAR, &isssstar));
    if (isssstar) PetscCall(SNESSSStarGetStates(snes, &states, NULL));
    PetscCall(SNESGetFunction(snes, &r, NULL, NULL));
    PetscCall(SSStarWriteContact(scene, out->file, prefix, u, r, states, NULL));
    PetscCall(SSStarWriteContactFaces(scene, out->file, prefix, PETSC_FALSE, u, r, states, &nv, &nt));
  }
  { /* the first step written that did not converge: where the path failed */
    SNESConvergedReason reason;

    PetscCall(SNESGetConvergedReason(snes, &reason));
    if (reason <= 0 && out->failedStep < 0) {
      out->failedStep = out->nsteps;
      out->failedTime = scene->stepTime;
    }
  }
  out->nsteps++;
  PetscCall(PetscLogEventEnd(SSSTAR_Output, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* The table /steps: each column of SSStarSceneGetStepColumn() as /steps/<name> (rank 0 writes the rows) */
static PetscErrorCode WriteStepTable(SSStarScene scene, SSStarSceneOutput out)
{
  PetscMPIInt rank;
  PetscInt    first = 0, n, ncolumns;
  PetscReal  *column;
  PetscInt   *ints;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(scene->comm, &rank));
  n = rank ? 0 : out->nsteps;
  PetscCall(PetscMalloc2(3 * out->nsteps + 1, &column, out->nsteps + 1, &ints));
  PetscCall(SSStarSceneGetStepColumns(scene, &ncolumns, NULL));
  for (PetscInt c = 0; c < ncolumns; c++) {
    char      name[PETSC_MAX_PATH_LEN], path[PETSC_MAX_PATH_LEN + 8], *slash;
    PetscInt  width;
    PetscBool integer;
    hid_t     group;

    PetscCall(SSStarSceneGetStepColumn(scene, c, sizeof(name), name, &width, &integer));
    PetscCall(PetscSNPrintf(path, sizeof(path), "/steps/%s", name));
    slash = strrchr(path, '/');
    *slash = 0; /* its group: /steps, /steps/motion, /steps/groups/<G> */
    PetscCall(SSStarH5GroupOpen(out->file, path, &group));
    PetscCallH5(H5Gclose(group));
    *slash = '/';
    for (PetscInt k = 0; k < out->nsteps; k++)
      for (PetscInt j = 0; j < width; j++) column[width * k + j] = out->table[out->ncols * k + first + j];
    for (PetscInt k = 0; k < out->nsteps; k++) ints[k] = (PetscInt)column[k]; /* the integer columns have width 1 */
    PetscCall(SSStarH5WriteRows(scene->comm, out->file, path, n, width > 1 ? width : 0, integer ? NULL : column, integer ? ints : NULL));
    first += width;
  }
  PetscCall(PetscFree2(column, ints));
  PetscFunctionReturn(0);
}

/* /groups/<G>/reaction of every held group: the force its prescription exerts on the body at u (3, rank 0 writes) */
static PetscErrorCode WriteReactions(SSStarScene scene, hid_t file, SNES snes, Vec u)
{
  PetscInt           nheld;
  const char *const *names;
  PetscReal         *reaction;
  PetscMPIInt        rank;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(scene->comm, &rank));
  PetscCall(SSStarSceneGetHeldGroups(scene, &nheld, &names));
  PetscCall(PetscMalloc1(3 * nheld + 1, &reaction));
  PetscCall(SSStarSceneGetReactions(scene, snes, u, reaction));
  for (PetscInt h = 0; h < nheld; h++) {
    char  path[PETSC_MAX_PATH_LEN];
    hid_t group;

    PetscCall(PetscSNPrintf(path, sizeof(path), "/groups/%s", names[h]));
    PetscCall(SSStarH5GroupOpen(file, path, &group));
    PetscCallH5(H5Gclose(group));
    PetscCall(PetscStrlcat(path, "/reaction", sizeof(path)));
    PetscCall(SSStarH5WriteRows(scene->comm, file, path, rank ? 0 : 3, 0, &reaction[3 * h], NULL));
  }
  PetscCall(PetscFree(reaction));
  PetscFunctionReturn(0);
}

/* The top level (the state u with what the SNES did), the table of the steps, the caller's extra, into the open file */
static PetscErrorCode WriteTopLevel(SSStarScene scene, SSStarSceneOutput out, SNES snes, Vec u, PetscErrorCode (*extra)(PetscViewer, void *), void *ctx, PetscInt *nfaceVertices, PetscInt *ntriangles)
{
  Vec                r      = NULL;
  const SSStarState *states = NULL;
  PetscBool          isssstar;
  SSStarNodeFriction nf;
  hid_t              group;

  PetscFunctionBegin;
  PetscCall(SSStarWriteMesh(scene, out->file, u));
  PetscCall(SSStarWriteStresses(scene, out->file, "", u));
  PetscCall(WriteReactions(scene, out->file, snes, u));
  PetscCall(SSStarWriteRun(scene, out->file, snes));
  {
    PetscInt *laws; /* the groups' laws, for an SNES that is no ssstar */

    PetscCall(PetscMalloc1(scene->n + 1, &laws));
    for (PetscInt i = 0; i < scene->n; i++) laws[i] = scene->contact[scene->group[i]].law;
    PetscCall(SSStarNodeFrictionGet(scene->comm, snes, scene->n, laws, &nf));
    PetscCall(PetscFree(laws));
  }
  PetscCall(SSStarWriteScene(scene, out->file, &nf));
  if (scene->nContact) {
    PetscCall(PetscObjectTypeCompare((PetscObject)snes, SNESSSSTAR, &isssstar));
    if (isssstar) PetscCall(SNESSSStarGetStates(snes, &states, NULL));
    PetscCall(SNESGetFunction(snes, &r, NULL, NULL)); /* K u - b: the contact forces at the contact dofs */
    PetscCall(SSStarWriteContact(scene, out->file, "", u, r, states, &nf));
    PetscCall(SSStarWriteContactFaces(scene, out->file, "", PETSC_TRUE, u, r, states, nfaceVertices, ntriangles));
  }
  PetscCall(SSStarNodeFrictionDestroy(&nf));
  if (out->nsteps) {
    PetscCall(SSStarH5GroupOpen(out->file, "/steps", &group));
    PetscCall(SSStarH5AttrInt(group, "count", out->nsteps));
    PetscCallH5(H5Gclose(group));
    PetscCall(WriteStepTable(scene, out));
  }
  if (out->failedStep >= 0) { /* the path stopped there */
    PetscCall(PetscViewerHDF5WriteAttribute(out->viewer, "/", "failed_step", PETSC_INT, &out->failedStep));
    PetscCall(PetscViewerHDF5WriteAttribute(out->viewer, "/", "failed_time", PETSC_REAL, &out->failedTime));
  }
  if (extra) PetscCall((*extra)(out->viewer, ctx));
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneOutputEnd - completes the file opened by SSStarSceneOutputBegin(): the top-level datasets and
   attributes of the state u (those of SSStarSceneWriteSolution(), docs/guide/output.md), the table of the steps, the
   caller's datasets, and the XDMF file (temporal collections of the steps when there are steps); then renames both
   files to their names

   Collective

   Input Parameters:
+  scene - the scene
.  snes  - the SNES of the last solve
.  u     - the last state (the last step's solution, or the iterate of the step that failed)
.  extra - NULL, or a function adding the caller's datasets to the open file
-  ctx   - its context

   Level: intermediate

.seealso: `SSStarSceneOutputBegin()`, `SSStarSceneOutputStep()`, `SSStarSceneWriteSolution()`
@*/
PetscErrorCode SSStarSceneOutputEnd(SSStarScene scene, SNES snes, Vec u, PetscErrorCode (*extra)(PetscViewer, void *), void *ctx)
{
  SSStarSceneOutput out = scene->output;
  PetscMPIInt       rank, failure = 0;
  PetscInt          nfaceVertices = 0, ntriangles = 0;
  PetscReal        *times;
  PetscErrorCode    ierr;
  PetscLogDouble    t;
  char              line[2 * PETSC_MAX_PATH_LEN + 32];

  PetscFunctionBegin;
  PetscCheck(out, scene->comm, PETSC_ERR_ARG_WRONGSTATE, "SSStarSceneOutputEnd: call SSStarSceneOutputBegin() first");
  PetscCall(PetscLogEventBegin(SSSTAR_Output, 0, 0, 0, 0));
  PetscCall(PetscTime(&t));
  PetscCallMPI(MPI_Comm_rank(scene->comm, &rank));
  scene->output = NULL;
  PetscCall(PetscMalloc1(out->nsteps + 1, &times));
  for (PetscInt k = 0; k < out->nsteps; k++) times[k] = out->table[out->ncols * k];
  ierr = WriteTopLevel(scene, out, snes, u, extra, ctx, &nfaceVertices, &ntriangles);
  if (!ierr) ierr = PetscViewerDestroy(&out->viewer);
  if (!ierr) ierr = WriteXDMF(scene, out->final, out->tmpXmf, nfaceVertices, ntriangles, out->nsteps, times);
  if (rank == 0) {
    if (ierr) {
      (void)remove(out->tmpH5);
      (void)remove(out->tmpXmf);
    } else failure = rename(out->tmpH5, out->final) || rename(out->tmpXmf, out->xmf);
  }
  PetscCall(PetscFree(times));
  if (out->viewer) PetscCall(PetscViewerDestroy(&out->viewer));
  PetscCallMPI(MPI_Bcast(&failure, 1, MPI_INT, 0, scene->comm));
  PetscCheck(!failure, scene->comm, PETSC_ERR_FILE_WRITE, "Cannot rename the written files to %s and %s", out->final, out->xmf);
  if (!ierr) {
    PetscCall(PetscSNPrintf(line, sizeof(line), "output: wrote %s and %s", out->final, out->xmf));
    PetscCall(SSStarSceneProgress(scene, &t, line));
  }
  PetscCall(PetscFree(out->table));
  PetscCall(PetscFree(out));
  PetscCall(ierr);
  PetscCall(PetscLogEventEnd(SSSTAR_Output, 0, 0, 0, 0));
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
   friction_2, friction_direction: 0 where a node's law has no such parameter), state, group (a contact pair named
   slave->master), and at the solution final_gap, pressure, traction, slip against the plane or the master surface;
   after a step of a load path slip_increment, slip_path, dissipation), the contact faces with their point fields
   (/contact_faces: vertices, triangles, state, pressure, tangential_traction, slip, gap, displacement), the scene
   (/scene: mesh, material, loads, contact groups with their laws) and, as attributes of /, the run: ssstar_version,
   petsc_version, command_line, ranks, snes_type, converged_reason, converged_reason_code, iterations, residual_norm
   (||z|| for ssstar), rtol, atol, max_it and, for ssstar, sub_reason, tolerance, scaling, reduction, state_counts,
   state_names. docs/guide/output.md lists them all. It is SSStarSceneOutputBegin() and SSStarSceneOutputEnd() without steps.

   Both files are written to temporary names and renamed when complete: a failure leaves no file behind.

   Level: beginner

.seealso: `SSStarSceneSetContact()`, `SNESSSStarGetStates()`, `SSStarWriteNodeFriction()`, `SSStarCheckOutputFile()`,
          `SSStarSceneOutputBegin()`
@*/
PetscErrorCode SSStarSceneWriteSolution(SSStarScene scene, SNES snes, const char file[], Vec u, PetscErrorCode (*extra)(PetscViewer, void *), void *ctx)
{
  PetscFunctionBegin;
  PetscCall(SSStarSceneOutputBegin(scene, file));
  PetscCall(SSStarSceneOutputEnd(scene, snes, u, extra, ctx));
  PetscFunctionReturn(0);
}
