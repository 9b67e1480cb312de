/* Memory before work: an estimate of what a mesh of N nodes needs, against what the machine has. */
#include <ssstarscene.h>
#include "../../sys/meminfo.h"

/*
   Measured with the prism (resident memory after the assembly, one rank, the progress lines of examples/prism): reading
   and distributing the mesh (faces, no edges), the assembly of K and the load take 6.0 kB per node at level 16 (0.42 GB
   for 70 785 nodes); SSSTAR_MESH_BYTES is below that: what every path needs at least. A lower bound on purpose: the
   factors of K and the dense P of the dense route are left to the reduction, which checks its own estimate (after
   MUMPS's analysis) against the same limit, and auto takes the whole-body path where P does not fit (src/reduction).
   The whole run on the whole body peaked at 9.3 kB per node on one rank at level 32 (5.1 GB), 16.9 kB on two (4.6 GB
   each). The 30 kB of the mesh with edges (DMPlexInterpolate) refused level 40, which fits.
*/
#define SSSTAR_MESH_BYTES 5000.0

/* The memory the ranks of comm can use: -snes_ssstar_memory_limit (GB per rank) times the ranks, or MemAvailable
   summed over the machines */
static PetscErrorCode MemoryLimit(MPI_Comm comm, PetscReal *limit, PetscReal *perRank)
{
  MPI_Comm    node;
  PetscMPIInt noderank, size;
  PetscLogDouble mine = 0;
  PetscBool   set;

  PetscFunctionBegin;
  *perRank = 0;
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-snes_ssstar_memory_limit", perRank, &set));
  PetscCheck(*perRank >= 0 && !PetscIsInfOrNanReal(*perRank), comm, PETSC_ERR_ARG_OUTOFRANGE, "-snes_ssstar_memory_limit %g: the limit must be > 0 GB (or 0 for the available memory)", (double)*perRank);
  if (*perRank > 0) {
    PetscCallMPI(MPI_Comm_size(comm, &size));
    *limit = *perRank * 1e9 * size;
    PetscFunctionReturn(0);
  }
  PetscCallMPI(MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node));
  PetscCallMPI(MPI_Comm_rank(node, &noderank));
  PetscCallMPI(MPI_Comm_free(&node));
  if (noderank == 0) PetscCall(SSStarMemAvailable(&mine));
  PetscCall(MPIU_Allreduce(&mine, limit, 1, MPIU_REAL, MPIU_SUM, comm));
  PetscFunctionReturn(0);
}

/*@C
   SSStarCheckMemory - refuses, before the work, a problem whose estimated memory exceeds what the machine has

   Collective

   Input Parameters:
+  comm    - the ranks that will share the work
.  nodes   - mesh nodes (estimated or counted)
-  what    - what the count comes from, for the message (e.g. "-level 400 of meshes/prism.geo")

   Options Database Key:
.  -snes_ssstar_memory_limit <0> - GB per rank instead of MemAvailable

   Notes:
   The limit is MemAvailable of /proc/meminfo (summed over the machines of comm) or -snes_ssstar_memory_limit <GB per rank>
   times the ranks of comm. The estimate covers the mesh and the assembly, which every path needs; the factorization of K
   and the dense P are checked later, by the reduction.

   Level: intermediate

.seealso: `SSStarMeshGenerate()`, `SNESSSStarSetMemoryLimit()`
@*/
PetscErrorCode SSStarCheckMemory(MPI_Comm comm, PetscReal nodes, const char what[])
{
  PetscReal estimate = SSSTAR_MESH_BYTES * nodes, limit, perRank;

  PetscFunctionBegin;
  PetscCall(MemoryLimit(comm, &limit, &perRank));
  if (limit <= 0) PetscFunctionReturn(0); /* no /proc/meminfo: nothing to compare with */
  if (estimate > limit) {
    char source[128];

    if (perRank > 0) PetscCall(PetscSNPrintf(source, sizeof(source), "of -snes_ssstar_memory_limit (%g GB per rank)", (double)perRank));
    else PetscCall(PetscSNPrintf(source, sizeof(source), "available on this machine (MemAvailable)"));
    SETERRQ(comm, PETSC_ERR_MEM, "%s: %.4g nodes need at least %.3g GB for the mesh and the assembly (the solver's own memory comes on top), more than the %.3g GB %s; refused before the work", what, (double)nodes, (double)(estimate / 1e9), (double)(limit / 1e9), source);
  }
  PetscFunctionReturn(0);
}
