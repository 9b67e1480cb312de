/* What was simulated (/scene) and how the run went (the attributes of /) */
#include "outputimpl.h"

/* The parameters of the laws the solver used at the group's nodes, as attributes of /scene/contact/<G>: each that has
   one value at every node of the group whose law has it (friction 0.45; friction_direction 1,0,0) */
static PetscErrorCode WriteGroupParameters(SSStarScene scene, PetscInt g, const SSStarNodeFriction *nf, hid_t sub)
{
  PetscFunctionBegin;
  for (PetscInt k = 0; k < nf->nparams; k++) {
    /* range[2c], range[2c + 1]: min and -max of the component c over the nodes; range[6]: 0 once a node has it */
    PetscReal      range[7] = {PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL};
    const PetscInt size = nf->size[k];

    for (PetscInt i = 0; i < scene->n; i++) {
      PetscBool has;

      if (scene->group[i] != g) continue;
      PetscCall(SSStarLawHasParameter(nf->law[i], nf->param[k], &has));
      if (!has) continue;
      range[6] = 0;
      for (PetscInt c = 0; c < size; c++) {
        range[2 * c]     = PetscMin(range[2 * c], nf->value[k][size * i + c]);
        range[2 * c + 1] = PetscMin(range[2 * c + 1], -nf->value[k][size * i + c]);
      }
    }
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, range, 7, MPIU_REAL, MPIU_MIN, scene->comm));
    if (range[6] != 0) continue; /* no node of the group has it */
    {
      PetscBool uniform = PETSC_TRUE;
      PetscReal v[3];

      for (PetscInt c = 0; c < size; c++) {
        uniform = (PetscBool)(uniform && range[2 * c] == -range[2 * c + 1]);
        v[c]    = range[2 * c];
      }
      if (uniform) PetscCall(SSStarH5AttrReals(sub, nf->param[k], size, v));
    }
  }
  PetscFunctionReturn(0);
}

/* An obstacle's attributes (SSStarObstacleWriteAttributes()) on the HDF5 group *ctx */
static PetscErrorCode AttributeReals(void *ctx, const char name[], PetscInt n, const PetscReal v[])
{
  PetscFunctionBegin;
  PetscCall(SSStarH5AttrReals(*(hid_t *)ctx, name, n, v));
  PetscFunctionReturn(0);
}

static PetscErrorCode AttributeInt(void *ctx, const char name[], PetscInt v)
{
  PetscFunctionBegin;
  PetscCall(SSStarH5AttrInt(*(hid_t *)ctx, name, v));
  PetscFunctionReturn(0);
}

static PetscErrorCode AttributeString(void *ctx, const char name[], const char v[])
{
  PetscFunctionBegin;
  PetscCall(SSStarH5AttrString(*(hid_t *)ctx, name, v));
  PetscFunctionReturn(0);
}

/* A load history with knots as the text of its option ("t:x,y,z;..."; nothing for a constant) */
static PetscErrorCode HistoryAttribute(hid_t obj, const char name[], SSStarHistory h)
{
  PetscInt n;
  char     text[4096];

  PetscFunctionBegin;
  PetscCall(SSStarHistoryGetKnots(h, &n, NULL, NULL));
  if (!n) PetscFunctionReturn(0);
  PetscCall(SSStarHistoryDescribe(h, text, sizeof(text)));
  PetscCall(SSStarH5AttrString(obj, name, text));
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarWriteScene(SSStarScene scene, hid_t file, const SSStarNodeFriction *nf)
{
  hid_t group, sub;
  char  path[PETSC_MAX_PATH_LEN], list[4096];

  PetscFunctionBegin;
  PetscCall(SSStarH5GroupOpen(file, "/scene", &group));
  PetscCall(SSStarH5AttrString(group, "mesh", scene->mesh));
  PetscCall(SSStarH5AttrInt(group, "nodes", scene->nodesGlobal));
  PetscCall(SSStarH5AttrInt(group, "cells", scene->cellsGlobal));
  PetscCall(SSStarH5AttrInt(group, "refinements", scene->refine)); /* -dm_refine: the mesh is the file's refined this many times */
  PetscCall(SSStarH5AttrReal(group, "mesh_scale", scene->meshScale));
  if (scene->hasE) PetscCall(SSStarH5AttrReal(group, "E", scene->E));
  if (scene->hasNu) PetscCall(SSStarH5AttrReal(group, "nu", scene->nu));
  if (scene->hasGravity) {
    PetscCall(SSStarH5AttrReals(group, "gravity", 3, scene->gravity));
    PetscCall(SSStarH5AttrReal(group, "density", scene->density));
    PetscCall(HistoryAttribute(group, "gravity_history", scene->gravityHistory));
  }
  PetscCall(SSStarJoinNames(scene->nDirichlet, (const char *const *)scene->dirichlet, list, sizeof(list)));
  PetscCall(SSStarH5AttrString(group, "dirichlet", list));
  list[0] = 0;
  for (PetscInt g = 0; g < scene->nContact; g++) {
    if (g) PetscCall(PetscStrlcat(list, ",", sizeof(list)));
    PetscCall(PetscStrlcat(list, scene->contact[g].name, sizeof(list)));
  }
  PetscCall(SSStarH5AttrString(group, "contact", list));
  PetscCallH5(H5Gclose(group));
  for (PetscInt m = 0; m < scene->nMaterials; m++) {
    PetscCall(PetscSNPrintf(path, sizeof(path), "/scene/material/%s", scene->materials[m].name));
    PetscCall(SSStarH5GroupOpen(file, path, &sub));
    PetscCall(SSStarH5AttrReal(sub, "E", scene->materials[m].value[0]));
    PetscCall(SSStarH5AttrReal(sub, "nu", scene->materials[m].value[1]));
    PetscCallH5(H5Gclose(sub));
  }
  for (PetscInt t = 0; t < scene->nTractions; t++) {
    PetscCall(PetscSNPrintf(path, sizeof(path), "/scene/traction/%s", scene->tractions[t].name));
    PetscCall(SSStarH5GroupOpen(file, path, &sub));
    PetscCall(SSStarH5AttrReals(sub, "traction", 3, scene->tractions[t].value));
    PetscCall(HistoryAttribute(sub, "history", scene->tractions[t].history));
    PetscCallH5(H5Gclose(sub));
  }
  for (PetscInt d = 0; d < scene->nDisplacements; d++) { /* "free,free,-0.01" or the knots "0:free,free,0;1:..." */
    const SSStarPrescribed *p = &scene->displacements[d];
    PetscInt                free[3];
    char                    text[4096];

    for (PetscInt k = 0; k < 3; k++) free[k] = (p->free >> k) & 1;
    PetscCall(PetscSNPrintf(path, sizeof(path), "/scene/displacement/%s", p->name));
    PetscCall(SSStarH5GroupOpen(file, path, &sub));
    PetscCall(SSStarPrescribedText(p, text, sizeof(text)));
    PetscCall(SSStarH5AttrString(sub, "displacement", strncmp(text, "history ", 8) ? text : text + 8));
    PetscCall(SSStarH5AttrInts(sub, "free", 3, free));
    PetscCallH5(H5Gclose(sub));
  }
  for (PetscInt s = 0; s < scene->nSprings; s++) {
    PetscCall(PetscSNPrintf(path, sizeof(path), "/scene/spring/%s", scene->springs[s].name));
    PetscCall(SSStarH5GroupOpen(file, path, &sub));
    PetscCall(SSStarH5AttrReal(sub, "k", scene->springs[s].value[0]));
    PetscCallH5(H5Gclose(sub));
  }
  for (PetscInt g = 0; g < scene->nContact; g++) {
    const SSStarContactGroup *cg = &scene->contact[g];
    PetscInt                 *laws, nlaws, law = -1;
    const char               *name = "mixed";

    PetscCall(SSStarLawGetNames(&nlaws, NULL));
    PetscCall(PetscCalloc1(nlaws, &laws));
    for (PetscInt i = 0; i < scene->n; i++)
      if (scene->group[i] == g) laws[nf->law[i]]++;
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, laws, nlaws, MPIU_INT, MPI_SUM, scene->comm));
    for (PetscInt k = 0; k < nlaws; k++)
      if (laws[k] == cg->nodes) law = k;
    PetscCall(PetscFree(laws));
    if (law >= 0) PetscCall(SSStarLawGetInfo(law, &name, NULL, NULL, NULL));
    PetscCall(PetscSNPrintf(path, sizeof(path), "/scene/contact/%s", cg->name));
    PetscCall(SSStarH5GroupOpen(file, path, &sub));
    PetscCall(SSStarH5AttrString(sub, "law", name));
    PetscCall(WriteGroupParameters(scene, g, nf, sub));
    if (cg->master[0]) { /* a contact pair: its master surface and discretization, no obstacle */
      PetscCall(SSStarH5AttrString(sub, "master", cg->master));
      PetscCall(SSStarH5AttrString(sub, "discretization", SSStarPairDiscretizations[scene->pairMethod]));
    } else {
      SSStarAttributeWriter writer = {&sub, AttributeReals, AttributeInt, AttributeString};
      char                  text[PETSC_MAX_PATH_LEN + 128];

      PetscCall(SSStarObstacleDescribe(cg->obstacle, text, sizeof(text)));
      PetscCall(SSStarH5AttrString(sub, "obstacle", text));
      PetscCall(SSStarObstacleWriteAttributes(cg->obstacle, &writer));
      if (cg->motion) PetscCall(HistoryAttribute(sub, "motion", cg->motion));
    }
    PetscCall(SSStarH5AttrInt(sub, "nodes", cg->nodes));
    PetscCall(SSStarH5AttrReal(sub, "gap_min", cg->gapMin));
    PetscCall(SSStarH5AttrReal(sub, "gap_max", cg->gapMax));
    PetscCallH5(H5Gclose(sub));
  }
  PetscFunctionReturn(0);
}

/* The command line as one string, each argument quoted when the shell would need it (rank 0's, on every rank) */
static PetscErrorCode CommandLine(MPI_Comm comm, char **line)
{
  int         argc;
  char      **argv;
  size_t      len = 1;
  PetscMPIInt rank;
  int         n;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(PetscGetArgs(&argc, &argv));
  for (int i = 0; i < argc; i++) len += strlen(argv[i]) + 3;
  n = (int)len;
  PetscCallMPI(MPI_Bcast(&n, 1, MPI_INT, 0, comm));
  PetscCall(PetscCalloc1(n, line));
  if (!rank)
    for (int i = 0; i < argc; i++) {
      const PetscBool quote = (PetscBool)(!argv[i][0] || strpbrk(argv[i], " \t\"'$*?;&|<>()") != NULL);

      if (i) PetscCall(PetscStrlcat(*line, " ", n));
      if (quote) PetscCall(PetscStrlcat(*line, "'", n));
      PetscCall(PetscStrlcat(*line, argv[i], n));
      if (quote) PetscCall(PetscStrlcat(*line, "'", n));
    }
  PetscCallMPI(MPI_Bcast(*line, n, MPI_CHAR, 0, comm));
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarWriteRun(SSStarScene scene, hid_t file, SNES snes)
{
  hid_t               root;
  char                version[64], *line, names[256];
  PetscInt            major, minor, subminor, release, its, maxit, maxf;
  PetscReal           norm, atol, rtol, stol;
  PetscMPIInt         size;
  SNESConvergedReason reason;
  SNESType            type;
  PetscBool           isssstar;

  PetscFunctionBegin;
  root = H5Gopen2(file, "/", H5P_DEFAULT);
  PetscCheck(root >= 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "HDF5 cannot open the root group");
  PetscCall(PetscSNPrintf(version, sizeof(version), "%d.%d.%d", SSSTAR_VERSION_MAJOR, SSSTAR_VERSION_MINOR, SSSTAR_VERSION_SUBMINOR));
  PetscCall(SSStarH5AttrString(root, "ssstar_version", version));
  PetscCall(PetscGetVersionNumber(&major, &minor, &subminor, &release));
  PetscCall(PetscSNPrintf(version, sizeof(version), "%" PetscInt_FMT ".%" PetscInt_FMT ".%" PetscInt_FMT, major, minor, subminor));
  PetscCall(SSStarH5AttrString(root, "petsc_version", version));
  PetscCall(CommandLine(scene->comm, &line));
  PetscCall(SSStarH5AttrString(root, "command_line", line));
  PetscCall(PetscFree(line));
  PetscCallMPI(MPI_Comm_size(scene->comm, &size));
  PetscCall(SSStarH5AttrInt(root, "ranks", size));

  PetscCall(SNESGetType(snes, &type));
  PetscCall(SNESGetConvergedReason(snes, &reason));
  PetscCall(SNESGetIterationNumber(snes, &its));
  PetscCall(SNESGetFunctionNorm(snes, &norm));
  PetscCall(SNESGetTolerances(snes, &atol, &rtol, &stol, &maxit, &maxf));
  PetscCall(SSStarH5AttrString(root, "snes_type", type ? type : ""));
  PetscCall(SSStarH5AttrString(root, "converged_reason", SNESConvergedReasons[reason]));
  PetscCall(SSStarH5AttrInt(root, "converged_reason_code", (PetscInt)reason));
  PetscCall(SSStarH5AttrInt(root, "iterations", its));
  PetscCall(SSStarH5AttrReal(root, "residual_norm", norm));
  PetscCall(SSStarH5AttrReal(root, "rtol", rtol));
  PetscCall(SSStarH5AttrReal(root, "atol", atol));
  PetscCall(SSStarH5AttrInt(root, "max_it", maxit));
  PetscCall(PetscObjectTypeCompare((PetscObject)snes, SNESSSSTAR, &isssstar));
  if (isssstar) {
    SSStarReason        sub;
    PetscReal           tol, gamma, law, lawtol, lawU, lawF;
    PetscInt            counts[SSSTAR_NUM_STATES];
    SSStarReductionType rtype;

    PetscCall(SNESSSStarGetReason(snes, &sub));
    PetscCall(SNESSSStarGetTolerance(snes, &tol));
    PetscCall(SNESSSStarGetStates(snes, NULL, counts));
    PetscCall(SNESSSStarGetScaling(snes, &gamma));
    PetscCall(SNESSSStarGetReductionType(snes, &rtype));
    PetscCall(SSStarH5AttrString(root, "sub_reason", SSStarReasons[sub]));
    PetscCall(SSStarH5AttrReal(root, "tolerance", tol));
    PetscCall(SNESSSStarGetLawResidual(snes, &law, &lawtol, &lawU, &lawF));
    PetscCall(SSStarH5AttrReal(root, "law_residual", law));
    PetscCall(SSStarH5AttrReal(root, "law_tolerance", lawtol));
    PetscCall(SSStarH5AttrReal(root, "law_displacement_scale", lawU));
    PetscCall(SSStarH5AttrReal(root, "law_force_scale", lawF));
    PetscCall(SSStarH5AttrReal(root, "scaling", gamma));
    PetscCall(SSStarH5AttrString(root, "reduction", rtype));
    PetscCall(SSStarH5AttrInts(root, "state_counts", SSSTAR_NUM_STATES, counts));
    PetscCall(SSStarJoinNames(SSSTAR_NUM_STATES, SSStarStateNames, names, sizeof(names)));
    PetscCall(SSStarH5AttrString(root, "state_names", names));
  }
  PetscCallH5(H5Gclose(root));
  PetscFunctionReturn(0);
}
