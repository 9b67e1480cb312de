/*
   Tables of the output: the table of a load path's steps (/steps/<column>, one row per step: what the step was and
   what it gave), whose columns and rows a program gets too (SSStarSceneGetStepColumn(), SSStarSceneGetStepRow()), and
   a program's own table of named columns (SSStarWriteTable()).
*/
#include "outputimpl.h"

/* The fixed columns of the table of the steps: 1 or 3 values per step, integers or reals */
typedef struct {
  const char *name;
  PetscInt    width;
  PetscBool   integer;
} StepColumn;

static const StepColumn StepColumns[] = {
  {"time", 1, PETSC_FALSE},         {"iterations", 1, PETSC_TRUE},   {"reason", 1, PETSC_TRUE}, {"residual_norm", 1, PETSC_FALSE}, {"cuts", 1, PETSC_TRUE},
  {"load", 3, PETSC_FALSE},         {"normal_force", 1, PETSC_FALSE}, {"tangential_force", 3, PETSC_FALSE}, {"area", 1, PETSC_FALSE},
  {"sliding", 1, PETSC_TRUE},       {"sticking", 1, PETSC_TRUE},     {"separated", 1, PETSC_TRUE}, {"dissipation", 1, PETSC_FALSE},
  {"law_residual", 1, PETSC_FALSE}, {"law_displacement_scale", 1, PETSC_FALSE}, {"law_force_scale", 1, PETSC_FALSE},
};
#define NFIXED ((PetscInt)PETSC_STATIC_ARRAY_LENGTH(StepColumns))

/* The moving obstacles' contact groups (their columns motion/<G> follow the fixed ones, then the surfaces') */
static PetscInt MovingGroups(SSStarScene scene)
{
  PetscInt n = 0;

  for (PetscInt g = 0; g < scene->nContact; g++) n += scene->contact[g].motion ? 1 : 0;
  return n;
}

/*@C
   SSStarSceneGetStepColumns - the columns of the table of a load path's steps (/steps of the output file), whose rows
   SSStarSceneGetStepRow() gives

   Collective

   Input Parameter:
.  scene - the scene, after SSStarSceneSetUp()

   Output Parameters:
+  ncolumns - the number of columns (SSStarSceneGetStepColumn() names each), or pass NULL
-  rowsize  - the values of a row (a column holds 1 or 3), or pass NULL

   Notes:
   The columns are time, iterations, reason, residual_norm, cuts, load (3), normal_force, tangential_force (3), area,
   sliding, sticking, separated, dissipation, law_residual, law_displacement_scale, law_force_scale, then motion/<G>
   (3) for each contact group with a moving obstacle, groups/<G>/displacement (3) for each traction, spring, contact
   and prescribed-displacement surface group and groups/<G>/reaction (3) for each held group, -dirichlet or
   -displacement_<G> (docs/guide/load-paths.md).

   Level: intermediate

.seealso: `SSStarSceneGetStepColumn()`, `SSStarSceneGetStepRow()`, `SSStarSceneOutputStep()`
@*/
PetscErrorCode SSStarSceneGetStepColumns(SSStarScene scene, PetscInt *ncolumns, PetscInt *rowsize)
{
  PetscInt width = 0, nheld;

  PetscFunctionBegin;
  PetscCall(SSStarSceneFollowSurfaces(scene));
  PetscCall(SSStarSceneGetHeldGroups(scene, &nheld, NULL));
  for (PetscInt c = 0; c < NFIXED; c++) width += StepColumns[c].width;
  if (ncolumns) *ncolumns = NFIXED + MovingGroups(scene) + scene->nSurfaces + nheld;
  if (rowsize) *rowsize = width + 3 * (MovingGroups(scene) + scene->nSurfaces + nheld);
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneGetStepColumn - a column of the table of a load path's steps: its name (its dataset in /steps), its width
   and whether it holds integers

   Collective

   Input Parameters:
+  scene - the scene, after SSStarSceneSetUp()
.  c     - the column, 0 .. ncolumns - 1 (SSStarSceneGetStepColumns())
-  len   - the size of name

   Output Parameters:
+  name    - its name: time, ..., dissipation, motion/<G>, groups/<G>/displacement, groups/<G>/reaction
.  width   - its values per row, 1 or 3, or pass NULL
-  integer - whether they are integers (stored as reals in a row), or pass NULL

   Level: intermediate

.seealso: `SSStarSceneGetStepColumns()`, `SSStarSceneGetStepRow()`
@*/
PetscErrorCode SSStarSceneGetStepColumn(SSStarScene scene, PetscInt c, size_t len, char name[], PetscInt *width, PetscBool *integer)
{
  PetscInt ncolumns, moving = MovingGroups(scene);

  PetscFunctionBegin;
  PetscCall(SSStarSceneGetStepColumns(scene, &ncolumns, NULL));
  PetscCheck(c >= 0 && c < ncolumns, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Column %" PetscInt_FMT " of the table of the steps: it has %" PetscInt_FMT, c, ncolumns);
  if (width) *width = c < NFIXED ? StepColumns[c].width : 3;
  if (integer) *integer = c < NFIXED ? StepColumns[c].integer : PETSC_FALSE;
  if (c < NFIXED) PetscCall(PetscStrncpy(name, StepColumns[c].name, len));
  else if (c < NFIXED + moving) {
    PetscInt g = 0;

    for (PetscInt m = -1; g < scene->nContact; g++)
      if (scene->contact[g].motion && ++m == c - NFIXED) break;
    PetscCall(PetscSNPrintf(name, len, "motion/%s", scene->contact[g].name));
  } else if (c < NFIXED + moving + scene->nSurfaces) PetscCall(PetscSNPrintf(name, len, "groups/%s/displacement", scene->surfaces[c - NFIXED - moving]));
  else {
    const char *const *held;

    PetscCall(SSStarSceneGetHeldGroups(scene, NULL, &held));
    PetscCall(PetscSNPrintf(name, len, "groups/%s/reaction", held[c - NFIXED - moving - scene->nSurfaces]));
  }
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneGetStepRow - the row of the table of a load path's steps (/steps of the output file) of the step just
   solved: what the step was and what it gave

   Collective

   Input Parameters:
+  scene - the scene, after SSStarSceneSetStep() and the step's solve (and SSStarSceneAcceptStep() if it converged)
.  snes  - the SNES that solved the step
.  u     - the step's solution (or the last iterate of a step that failed)
-  cuts  - how many times the step was halved before it converged (a caller's count; 0 without step cutting)

   Output Parameter:
.  row - the values of the columns of SSStarSceneGetStepColumns(), rowsize of them (integers as reals), the same on
         every rank

   Notes:
   time is the one of SSStarSceneSetStep(); iterations, reason (SNESConvergedReason) and residual_norm the SNES's;
   load the resultant of the step's load b = -F(0); normal_force, tangential_force, area, sliding, sticking,
   separated and dissipation those of SSStarSceneGetContactResult() for every group; law_residual and its scales
   law_displacement_scale, law_force_scale the solver's (SNESSSStarGetLawResidual(), docs/derivation.md section 12);
   motion/<G> the obstacle's
   translation; groups/<G>/displacement the mean displacement of the group, weighted like a uniform traction's load
   (so that the work of a uniform traction on G is its force times this); groups/<G>/reaction the force the
   prescription of a held group exerts on the body (SSStarSceneGetReactions()). SSStarSceneOutputStep() writes this row.

   Level: intermediate

.seealso: `SSStarSceneGetStepColumns()`, `SSStarSceneOutputStep()`, `SSStarSceneGetContactResult()`
@*/
PetscErrorCode SSStarSceneGetStepRow(SSStarScene scene, SNES snes, Vec u, PetscInt cuts, PetscReal row[])
{
  SSStarContactResult res = {0, 0, 0, 0, 0, 0, {0, 0, 0}, {0, 0, 0}, 0};
  SNESConvergedReason reason;
  PetscInt            its, c = 0, rowsize;
  PetscReal           norm, load[3], law[3] = {0, 0, 0}; /* the law residual and its scales (docs/derivation.md section 12) */
  Vec                 r, zero, b;
  const SSStarState  *states = NULL;
  PetscBool           isssstar;

  PetscFunctionBegin;
  PetscCall(SSStarSceneGetStepColumns(scene, NULL, &rowsize));
  PetscCall(SNESGetConvergedReason(snes, &reason));
  PetscCall(SNESGetIterationNumber(snes, &its));
  PetscCall(SNESGetFunctionNorm(snes, &norm));
  PetscCall(SNESGetFunction(snes, &r, NULL, NULL)); /* K u - b: the contact forces at the contact dofs */
  PetscCall(VecDuplicate(u, &zero));                  /* b = -F(0), the step's load */
  PetscCall(VecDuplicate(u, &b));
  PetscCall(VecZeroEntries(zero));
  PetscCall(SNESComputeFunction(snes, zero, b));
  PetscCall(VecScale(b, -1.0));
  PetscCall(SSStarSceneGetLoadResultant(scene, b, load));
  PetscCall(VecDestroy(&zero));
  PetscCall(VecDestroy(&b));
  PetscCall(PetscObjectTypeCompare((PetscObject)snes, SNESSSSTAR, &isssstar));
  if (scene->nContact && isssstar) {
    PetscCall(SNESSSStarGetStates(snes, &states, NULL));
    PetscCall(SSStarSceneGetContactResult(scene, -1, r, states, &res));
    PetscCall(SNESSSStarGetLawResidual(snes, &law[0], NULL, &law[1], &law[2]));
  }
  row[c++] = scene->stepTime;
  row[c++] = its;
  row[c++] = reason;
  row[c++] = norm;
  row[c++] = cuts;
  for (PetscInt k = 0; k < 3; k++) row[c++] = load[k];
  row[c++] = res.normal_force;
  for (PetscInt k = 0; k < 3; k++) row[c++] = res.tangential_force[k];
  row[c++] = res.area;
  row[c++] = res.sliding;
  row[c++] = res.sticking;
  row[c++] = res.separated;
  row[c++] = res.dissipation;
  for (PetscInt k = 0; k < 3; k++) row[c++] = law[k];
  for (PetscInt g = 0; g < scene->nContact; g++)
    if (scene->contact[g].motion)
      for (PetscInt k = 0; k < 3; k++) row[c++] = scene->contact[g].d[k];
  PetscCall(SSStarSceneSurfaceDisplacements(scene, u, &row[c]));
  c += 3 * scene->nSurfaces;
  PetscCall(SSStarSceneGetReactions(scene, snes, u, &row[c]));
  c += 3 * (scene->nDirichlet + scene->nDisplacements);
  PetscCheck(c == rowsize, PETSC_COMM_SELF, PETSC_ERR_PLIB, "the row of a step has %" PetscInt_FMT " values, not %" PetscInt_FMT, c, rowsize);
  PetscFunctionReturn(0);
}

/*@C
   SSStarWriteTable - writes a table of named columns into an HDF5 file: the dataset group/<name> of each column, its
   values those rank 0 holds

   Collective

   Input Parameters:
+  viewer  - an HDF5 viewer open for writing (the one SSStarSceneWriteSolution() hands its extra function)
.  group   - the group of the columns, e.g. "/load_steps"
.  ncols   - the number of columns
.  names   - their names
.  nrows   - the number of rows (rank 0's; the other ranks' is not used)
-  columns - the columns: columns[k] holds the nrows values of column k (rank 0's; the other ranks may pass NULL)

   Notes:
   examples/contact writes its load steps so (/load_steps/factor, area, normal_force, iterations), as does the Python
   module.

   Level: intermediate

.seealso: `SSStarSceneWriteSolution()`, `SSStarSceneGetStepRow()`
@*/
PetscErrorCode SSStarWriteTable(PetscViewer viewer, const char group[], PetscInt ncols, const char *const names[], PetscInt nrows, const PetscReal *const columns[])
{
  PetscMPIInt rank;
  MPI_Comm    comm = PetscObjectComm((PetscObject)viewer);

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Bcast(&nrows, 1, MPIU_INT, 0, comm));
  PetscCall(PetscViewerHDF5PushGroup(viewer, group));
  for (PetscInt k = 0; k < ncols; k++) {
    Vec v;

    PetscCall(VecCreateMPI(comm, rank ? 0 : nrows, nrows, &v));
    PetscCall(PetscObjectSetName((PetscObject)v, names[k]));
    if (!rank)
      for (PetscInt i = 0; i < nrows; i++) PetscCall(VecSetValue(v, i, columns[k][i], INSERT_VALUES));
    PetscCall(VecAssemblyBegin(v));
    PetscCall(VecAssemblyEnd(v));
    PetscCall(VecView(v, viewer));
    PetscCall(VecDestroy(&v));
  }
  PetscCall(PetscViewerHDF5PopGroup(viewer));
  PetscFunctionReturn(0);
}
