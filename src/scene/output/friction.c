/*
   What the solver used at each contact node, as the output files write it: the law (/contact/friction_law, its index in
   the table of laws, with the table's names as the attribute names) and one dataset per parameter of the laws in use
   (/contact/<parameter>: friction, slip_bound, friction_1, friction_2, friction_direction, ...), 0 where the node's
   law has no such parameter. Read from the table, so that a new law needs nothing here. The scenes' files
   (contact.c, metadata.c) and examples/generic (SSStarWriteNodeFriction()) write them alike.
*/
#include "outputimpl.h"

/*
   The laws of the n local nodes (the solver's when snes is an ssstar, else the caller's laws[]) and, for an ssstar,
   the values of the parameters of the laws in use on any rank. Collective.
*/
PetscErrorCode SSStarNodeFrictionGet(MPI_Comm comm, SNES snes, PetscInt n, const PetscInt laws[], SSStarNodeFriction *nf)
{
  PetscInt           nlaws, nparams;
  const char *const *params;
  PetscBool         *used;

  PetscFunctionBegin;
  PetscCall(PetscMemzero(nf, sizeof(*nf)));
  PetscCall(PetscObjectTypeCompare((PetscObject)snes, SNESSSSTAR, &nf->known));
  nf->n = n;
  PetscCall(PetscMalloc1(n + 1, &nf->law));
  if (nf->known) PetscCall(SNESSSStarGetNodeFrictionLaws(snes, n, nf->law));
  else PetscCall(PetscArraycpy(nf->law, laws, n));
  if (!nf->known) PetscFunctionReturn(0); /* the laws the scene describes; no values of the solver's */
  PetscCall(SSStarLawGetNames(&nlaws, NULL));
  PetscCall(PetscCalloc1(nlaws, &used));
  for (PetscInt i = 0; i < n; i++) used[nf->law[i]] = PETSC_TRUE;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, used, nlaws, MPIU_BOOL, MPI_LOR, comm));
  PetscCall(SSStarLawGetParameterNames(&nparams, &params));
  PetscCall(PetscMalloc3(nparams, &nf->param, nparams, &nf->size, nparams, &nf->value));
  for (PetscInt p = 0; p < nparams; p++) {
    PetscBool inUse = PETSC_FALSE;

    for (PetscInt l = 0; l < nlaws && !inUse; l++) {
      PetscBool has;

      PetscCall(SSStarLawHasParameter(l, params[p], &has));
      inUse = (PetscBool)(used[l] && has);
    }
    if (!inUse) continue;
    nf->param[nf->nparams] = params[p];
    PetscCall(SSStarLawGetParameterSize(params[p], &nf->size[nf->nparams]));
    PetscCall(PetscMalloc1(nf->size[nf->nparams] * n + 1, &nf->value[nf->nparams]));
    PetscCall(SNESSSStarGetNodeLawParameter(snes, params[p], n, nf->value[nf->nparams])); /* 0 where the law has none */
    nf->nparams++;
  }
  PetscCall(PetscFree(used));
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarNodeFrictionDestroy(SSStarNodeFriction *nf)
{
  PetscFunctionBegin;
  for (PetscInt p = 0; p < nf->nparams; p++) PetscCall(PetscFree(nf->value[p]));
  PetscCall(PetscFree3(nf->param, nf->size, nf->value));
  PetscCall(PetscFree(nf->law));
  nf->nparams = 0;
  PetscFunctionReturn(0);
}

/* group/friction_law and group/<parameter>, row pos[i] of p for the local node i */
PetscErrorCode SSStarNodeFrictionWrite(MPI_Comm comm, hid_t file, const char group[], const SSStarNodeFriction *nf, PetscInt p, const PetscInt pos[])
{
  char               path[PETSC_MAX_PATH_LEN], names[1024];
  PetscReal         *codes;
  PetscInt           nlaws;
  const char *const *laws;
  hid_t              g;

  PetscFunctionBegin;
  PetscCall(SSStarH5GroupOpen(file, group, &g));
  PetscCallH5(H5Gclose(g));
  PetscCall(PetscMalloc1(nf->n + 1, &codes));
  for (PetscInt i = 0; i < nf->n; i++) codes[i] = (PetscReal)nf->law[i];
  PetscCall(PetscSNPrintf(path, sizeof(path), "%s/friction_law", group));
  PetscCall(SSStarWriteNodeField(comm, file, path, p, nf->n, pos, 1, codes, PETSC_TRUE));
  PetscCall(PetscFree(codes));
  PetscCall(SSStarLawGetNames(&nlaws, &laws));
  PetscCall(SSStarJoinNames(nlaws, laws, names, sizeof(names)));
  PetscCall(SSStarH5ObjectAttrString(file, path, "names", names));
  for (PetscInt k = 0; k < nf->nparams; k++) {
    PetscCall(PetscSNPrintf(path, sizeof(path), "%s/%s", group, nf->param[k]));
    PetscCall(SSStarWriteNodeField(comm, file, path, p, nf->n, pos, nf->size[k], nf->value[k], PETSC_FALSE));
  }
  PetscFunctionReturn(0);
}

/*@C
   SSStarWriteNodeFriction - writes the friction law the solver used at each contact node and the values of the
   parameters of the laws in use into an HDF5 file, as the scenes' files have them

   Collective

   Input Parameters:
+  snes   - an ssstar SNES after SNESSetUp() or SNESSolve()
.  viewer - an HDF5 viewer open for writing
-  group  - the HDF5 group of the datasets, e.g. "/contact"

   Notes:
   group/friction_law (integers: the index of each node's law in the table of laws, SSStarLawGetNames(); the attribute
   names lists the table) and group/<parameter> for every parameter of the laws in use (SSStarLawGetParameterNames():
   friction, slip_bound, friction_1, friction_2, friction_direction, ...; one value per node, 3 for a direction in
   global axes), 0 where the node's law has no such parameter. Rows in the order the nodes were declared, rank after
   rank. tests/check_solution.py reads them.

   Level: intermediate

.seealso: `SNESSSStarGetNodeFrictionLaws()`, `SNESSSStarGetNodeLawParameter()`, `SSStarSceneWriteSolution()`
@*/
PetscErrorCode SSStarWriteNodeFriction(SNES snes, PetscViewer viewer, const char group[])
{
  MPI_Comm           comm = PetscObjectComm((PetscObject)snes);
  SSStarNodeFriction nf;
  PetscInt           n, start = 0, p, *pos;
  PetscMPIInt        rank;
  hid_t              file;
  PetscBool          isssstar;

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)snes, SNESSSSTAR, &isssstar));
  PetscCheck(isssstar, comm, PETSC_ERR_ARG_WRONG, "SSStarWriteNodeFriction: the SNES is not of type ssstar");
  PetscCall(SNESSSStarGetContactNodes(snes, &n, NULL, NULL, NULL));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Exscan(&n, &start, 1, MPIU_INT, MPI_SUM, comm));
  if (!rank) start = 0; /* MPI_Exscan leaves rank 0's undefined */
  PetscCall(MPIU_Allreduce(&n, &p, 1, MPIU_INT, MPI_SUM, comm));
  PetscCall(PetscMalloc1(n + 1, &pos));
  for (PetscInt i = 0; i < n; i++) pos[i] = start + i;
  PetscCall(SSStarNodeFrictionGet(comm, snes, n, NULL, &nf));
  PetscCall(PetscViewerHDF5GetFileId(viewer, &file));
  PetscCall(SSStarNodeFrictionWrite(comm, file, group, &nf, p, pos));
  PetscCall(SSStarNodeFrictionDestroy(&nf));
  PetscCall(PetscFree(pos));
  PetscFunctionReturn(0);
}
