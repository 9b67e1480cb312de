/*
   The output's fields in memory (SSStarSceneGetField()): the datasets of the file -- the mesh's vertices and the
   displacement (in file order by fileorder.c), and the fields of the contact nodes (/contact/<name>: their values are
   computed here, for the file (contact.c) and for a program alike) -- every row in the order of the file, the whole
   field on every rank.
*/
#include "outputimpl.h"

/* The datasets of /contact, in the order the file has them */
const SSStarContactField SSStarContactFields[] = {
  {"displacement", 3, PETSC_FALSE, SSSTAR_FIELD_STATE},
  {"reaction", 3, PETSC_FALSE, SSSTAR_FIELD_STATE},
  {"coordinates", 3, PETSC_FALSE, SSSTAR_FIELD_SCENE},
  {"normal", 3, PETSC_FALSE, SSSTAR_FIELD_FRAME},
  {"gap", 1, PETSC_FALSE, SSSTAR_FIELD_SCENE},
  {"area", 1, PETSC_FALSE, SSSTAR_FIELD_SCENE},
  {"state", 1, PETSC_TRUE, SSSTAR_FIELD_STATE},
  {"final_gap", 1, PETSC_FALSE, SSSTAR_FIELD_STATE},
  {"pressure", 1, PETSC_FALSE, SSSTAR_FIELD_STATE},
  {"traction", 3, PETSC_FALSE, SSSTAR_FIELD_STATE},
  {"slip", 3, PETSC_FALSE, SSSTAR_FIELD_STATE},
  {"slip_increment", 3, PETSC_FALSE, SSSTAR_FIELD_PATH},
  {"slip_path", 1, PETSC_FALSE, SSSTAR_FIELD_PATH},
  {"dissipation", 1, PETSC_FALSE, SSSTAR_FIELD_PATH},
  {"group", 1, PETSC_TRUE, SSSTAR_FIELD_SCENE},
  {NULL, 0, PETSC_FALSE, SSSTAR_FIELD_SCENE}
};

/* The contact entries of a global vector (u or r = K u - b), 3 per contact node */
static PetscErrorCode ContactEntries(SSStarScene scene, Vec v, PetscReal values[])
{
  const PetscScalar *a;
  Vec                vC;

  PetscFunctionBegin;
  PetscCall(VecGetSubVector(v, scene->isC, &vC));
  PetscCall(VecGetArrayRead(vC, &a));
  for (PetscInt i = 0; i < 3 * scene->n; i++) values[i] = PetscRealPart(a[i]);
  PetscCall(VecRestoreArrayRead(vC, &a));
  PetscCall(VecRestoreSubVector(v, scene->isC, &vC));
  PetscFunctionReturn(0);
}

/* One of the kinematic fields at the solution (final_gap, pressure, traction, slip: results.c) */
static PetscErrorCode Kinematics(SSStarScene scene, const char name[], Vec u, Vec r, PetscReal values[])
{
  const char *const names[4] = {"final_gap", "pressure", "traction", "slip"};
  const PetscInt    n        = scene->n;
  PetscReal        *kin[4];

  PetscFunctionBegin;
  PetscCall(PetscMalloc4(n + 1, &kin[0], n + 1, &kin[1], 3 * n + 1, &kin[2], 3 * n + 1, &kin[3]));
  PetscCall(SSStarSceneContactKinematics(scene, u, r, kin[0], kin[1], kin[2], kin[3]));
  for (PetscInt k = 0; k < 4; k++) {
    PetscBool same;

    PetscCall(PetscStrcmp(name, names[k], &same));
    if (same) PetscCall(PetscArraycpy(values, kin[k], (k < 2 ? 1 : 3) * n));
  }
  PetscCall(PetscFree4(kin[0], kin[1], kin[2], kin[3]));
  PetscFunctionReturn(0);
}

/*
   The values of a field of /contact at the owned contact nodes (field->bs per node, in the scene's order): the scene's
   (coordinates, gap of the reference configuration, area, group; normal: of the frames of the last step), at the state u with r = K u - b and the solver's states (displacement,
   reaction, state: -1 without states, final_gap, pressure, traction, slip), or of the load path after its last
   accepted step (slip_increment in global axes, slip_path, dissipation)
*/
PetscErrorCode SSStarContactFieldValues(SSStarScene scene, const SSStarContactField *field, Vec u, Vec r, const SSStarState states[], PetscReal values[])
{
  const char    *name = field->name;
  const PetscInt n    = scene->n;
  PetscBool      is[8];

  PetscFunctionBegin;
  PetscCheck(field->kind != SSSTAR_FIELD_STATE || (u && r), scene->comm, PETSC_ERR_ARG_WRONGSTATE, "The field /contact/%s is one of a solution: give the displacement and the SNES that solved it", name);
  PetscCheck(field->kind != SSSTAR_FIELD_PATH || scene->stepped, scene->comm, PETSC_ERR_ARG_WRONGSTATE, "The field /contact/%s is one of a load path: no step was accepted (SSStarSceneAcceptStep())", name);
  PetscCall(PetscStrcmp(name, "displacement", &is[0]));
  PetscCall(PetscStrcmp(name, "reaction", &is[1]));
  PetscCall(PetscStrcmp(name, "state", &is[2]));
  PetscCall(PetscStrcmp(name, "group", &is[3]));
  PetscCall(PetscStrcmp(name, "slip_increment", &is[4]));
  PetscCall(PetscStrcmp(name, "coordinates", &is[5]));
  PetscCall(PetscStrcmp(name, "normal", &is[6]));
  if (is[0] || is[1]) PetscCall(ContactEntries(scene, is[0] ? u : r, values));
  else if (is[2] || is[3])
    for (PetscInt i = 0; i < n; i++) values[i] = is[3] ? (PetscReal)scene->group[i] : states ? (PetscReal)states[i] : -1;
  else if (is[4])
    for (PetscInt i = 0; i < n; i++) {
      const PetscReal *R = &scene->frame[9 * i];

      for (PetscInt k = 0; k < 3; k++) values[3 * i + k] = R[k] * scene->slipIncrement[2 * i] + R[3 + k] * scene->slipIncrement[2 * i + 1]; /* R_t^T dw_t */
    }
  else if (is[5] || is[6]) PetscCall(PetscArraycpy(values, is[5] ? scene->coords : scene->normal, 3 * n));
  else {
    const char *const names[4]  = {"gap", "area", "slip_path", "dissipation"};
    const PetscReal  *arrays[4] = {scene->gapInitial, scene->area, scene->slipPath, scene->dissipation};
    PetscBool         found     = PETSC_FALSE;

    for (PetscInt k = 0; k < 4 && !found; k++) {
      PetscCall(PetscStrcmp(name, names[k], &found));
      if (found) PetscCall(PetscArraycpy(values, arrays[k], n));
    }
    if (!found) PetscCall(Kinematics(scene, name, u, r, values));
  }
  PetscFunctionReturn(0);
}

/* A sequential vector of n values in blocks of bs */
static PetscErrorCode SequentialVec(PetscInt n, PetscInt bs, Vec *v)
{
  PetscFunctionBegin;
  PetscCall(VecCreate(PETSC_COMM_SELF, v));
  PetscCall(VecSetSizes(*v, n, n));
  PetscCall(VecSetBlockSize(*v, bs));
  PetscCall(VecSetType(*v, VECSEQ));
  PetscFunctionReturn(0);
}

/* A field of /contact, every contact node in file order on every rank */
static PetscErrorCode ContactField(SSStarScene scene, const SSStarContactField *field, Vec u, Vec r, const SSStarState states[], Vec *v)
{
  const PetscInt bs = field->bs;
  PetscInt       p, *pos, *all;
  PetscReal     *local, *w;
  PetscScalar   *a;

  PetscFunctionBegin;
  PetscCall(PetscMalloc2(scene->n + 1, &pos, 3 * scene->n + 1, &local));
  PetscCall(SSStarContactFieldValues(scene, field, u, r, states, local));
  PetscCall(SSStarFileOrder(scene->comm, scene->n, scene->tag, &p, &all, pos));
  PetscCall(PetscCalloc1(bs * p + 1, &w));
  for (PetscInt i = 0; i < scene->n; i++) PetscCall(PetscArraycpy(&w[bs * pos[i]], &local[bs * i], bs));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, w, bs * p, MPIU_REAL, MPIU_SUM, scene->comm)); /* one rank holds each row */
  PetscCall(SequentialVec(bs * p, bs, v));
  PetscCall(VecGetArrayWrite(*v, &a));
  for (PetscInt i = 0; i < bs * p; i++) a[i] = w[i];
  PetscCall(VecRestoreArrayWrite(*v, &a));
  PetscCall(PetscFree(w));
  PetscCall(PetscFree(all));
  PetscCall(PetscFree2(pos, local));
  PetscFunctionReturn(0);
}

/* The vertices (u NULL) or the displacement u, every vertex in file order on every rank */
static PetscErrorCode VertexField(SSStarScene scene, Vec u, Vec *v)
{
  Vec        nat, all;
  VecScatter scatter;

  PetscFunctionBegin;
  PetscCall(SSStarVertexFieldInFileOrder(scene, u, &nat));
  PetscCall(VecScatterCreateToAll(nat, &scatter, &all));
  PetscCall(SequentialVec(3 * scene->nodesGlobal, 3, v));
  PetscCall(VecScatterBegin(scatter, nat, *v, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(scatter, nat, *v, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterDestroy(&scatter));
  PetscCall(VecDestroy(&all));
  PetscCall(VecDestroy(&nat));
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneGetField - a dataset of the output file as the scene holds it at a state: the values of every row in the
   order of the file (the mesh file's node order), the whole field on every rank

   Collective

   Input Parameters:
+  scene - the scene, after SSStarSceneSetUp() (and SSStarSceneSetContact() for the fields of the contact nodes)
.  snes  - the SNES that solved u (its states and its function K u - b), or NULL for the fields of the scene alone
.  u     - the displacement (a global vector of the scene's DM), or NULL for the fields of the scene alone
-  name  - the dataset: /geometry/vertices, /fields/displacement, or /contact/<field> with <field> one of
           coordinates, normal, gap, area, group (the scene's), displacement, reaction, state, final_gap, pressure,
           traction, slip (at the state u), slip_increment, slip_path, dissipation (of a load path, after
           SSStarSceneAcceptStep()); the leading / may be left out

   Output Parameter:
.  field - a sequential vector (PETSC_COMM_SELF) of rows x cols values, cols (1 or 3) its block size, row k of the
           dataset at entries k cols .. k cols + cols - 1; the caller destroys it

   Notes:
   The values are those the output file holds (SSStarSceneWriteSolution(), SSStarSceneOutputStep(),
   docs/guide/output.md): the same functions compute them. Integer datasets (state, group) come as reals. Every rank gets the
   whole field: /fields/displacement costs 3 reals per mesh node on every rank.

   Level: intermediate

.seealso: `SSStarSceneWriteSolution()`, `SSStarSceneOutputStep()`, `SSStarSceneGetStepRow()`, `SSStarSceneGetContactNodes()`
@*/
PetscErrorCode SSStarSceneGetField(SSStarScene scene, SNES snes, Vec u, const char name[], Vec *field)
{
  const char *path = name && name[0] == '/' ? name + 1 : name;
  PetscBool   vertices, displacement, contact;

  PetscFunctionBegin;
  PetscCheck(name && field, scene->comm, PETSC_ERR_ARG_NULL, "SSStarSceneGetField(): give the name of the field and where to put it");
  PetscCheck(scene->dm, scene->comm, PETSC_ERR_ARG_WRONGSTATE, "SSStarSceneGetField(): set the scene up first (SSStarSceneSetUp())");
  PetscCall(PetscStrcmp(path, "geometry/vertices", &vertices));
  PetscCall(PetscStrcmp(path, "fields/displacement", &displacement));
  PetscCall(PetscStrncmp(path, "contact/", 8, &contact));
  PetscCheck(!displacement || u, scene->comm, PETSC_ERR_ARG_NULL, "The field %s needs the displacement u", name);
  if (vertices || displacement) {
    PetscCall(VertexField(scene, displacement ? u : NULL, field));
    PetscFunctionReturn(0);
  }
  if (contact)
    for (const SSStarContactField *f = SSStarContactFields; f->name; f++) {
      PetscBool          same;
      Vec                r      = NULL;
      const SSStarState *states = NULL;

      PetscCall(PetscStrcmp(path + 8, f->name, &same));
      if (!same) continue;
      PetscCheck(scene->nContact, scene->comm, PETSC_ERR_ARG_WRONGSTATE, "The field %s: the scene has no contact groups", name);
      if (f->kind == SSSTAR_FIELD_STATE) {
        PetscBool isssstar;

        PetscCheck(snes && u, scene->comm, PETSC_ERR_ARG_NULL, "The field %s is one of a solution: give the displacement and the SNES that solved it", name);
        PetscCall(SNESGetFunction(snes, &r, NULL, NULL));
        PetscCall(PetscObjectTypeCompare((PetscObject)snes, SNESSSSTAR, &isssstar));
        if (isssstar) PetscCall(SNESSSStarGetStates(snes, &states, NULL));
      }
      PetscCall(ContactField(scene, f, u, r, states, field));
      PetscFunctionReturn(0);
    }
  SETERRQ(scene->comm, PETSC_ERR_ARG_UNKNOWN_TYPE, "Unknown field %s: /geometry/vertices, /fields/displacement or /contact/<field> (docs/guide/output.md)", name);
}
