/* Memory before work: an estimate of what a mesh of N nodes with p contact nodes needs, against what the machine has. */
#include <ssstarcontact.h>
#include <stdio.h>

/*
   Measured with the prism at levels 6, 10, 12 (peak resident memory, one rank): reading, interpolating and
   distributing the mesh, the COO assembly of K and the load take 28-29 kB per node (MESH_BYTES); MUMPS's Cholesky
   factor of K took 690-730 bytes N^(4/3) more (FACTOR_BYTES; nested-dissection fill of 3D meshes grows as N^(4/3)).
   With contact, three dense 3p x 3p matrices (P, the Newton matrix, its LU factor). A lower bound on purpose: the
   Schur reduction needs more than a Cholesky factor and checks its own estimate after MUMPS's analysis.
*/
#define SSSTAR_MESH_BYTES   30000.0
#define SSSTAR_FACTOR_BYTES 700.0

/* MemAvailable of /proc/meminfo in bytes (0 if unknown) */
static PetscErrorCode MemAvailable(PetscReal *bytes)
{
  FILE  *fp;
  char   line[256];
  double kb;

  PetscFunctionBegin;
  *bytes = 0;
  fp     = fopen("/proc/meminfo", "r");
  if (!fp) PetscFunctionReturn(0);
  while (fgets(line, sizeof(line), fp))
    if (sscanf(line, "MemAvailable: %lf kB", &kb) == 1) *bytes = 1024.0 * kb;
  fclose(fp);
  PetscFunctionReturn(0);
}

/* The memory the ranks of comm can use: -snes_ssstar_memory_limit (GB) or MemAvailable summed over the machines */
static PetscErrorCode MemoryLimit(MPI_Comm comm, PetscReal *limit, PetscBool *fromOption)
{
  MPI_Comm    node;
  PetscMPIInt noderank;
  PetscReal   mine = 0;

  PetscFunctionBegin;
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-snes_ssstar_memory_limit", limit, fromOption));
  if (*fromOption) {
    PetscCheck(*limit > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-snes_ssstar_memory_limit %g: the limit must be positive (in GB)", (double)*limit);
    *limit *= 1e9;
    PetscFunctionReturn(0);
  }
  PetscCallMPI(MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node));
  PetscCallMPI(MPI_Comm_rank(node, &noderank));
  PetscCallMPI(MPI_Comm_free(&node));
  if (noderank == 0) PetscCall(MemAvailable(&mine));
  PetscCall(MPIU_Allreduce(&mine, limit, 1, MPIU_REAL, MPIU_SUM, comm));
  PetscFunctionReturn(0);
}

/*@C
   SSStarCheckMemory - refuses, before the work, a problem whose estimated memory exceeds what the machine has

   Input Parameters:
+  comm    - the ranks that will share the work
.  nodes   - mesh nodes (estimated or counted)
.  contact - contact nodes (0 when not known yet)
-  what    - what the count comes from, for the message (e.g. "-level 400 of meshes/prism.geo")

   Notes:
   The limit is MemAvailable of /proc/meminfo (summed over the machines of comm) or -snes_ssstar_memory_limit <GB>.
@*/
PetscErrorCode SSStarCheckMemory(MPI_Comm comm, PetscReal nodes, PetscReal contact, const char what[])
{
  PetscReal mesh = SSSTAR_MESH_BYTES * nodes, factor = SSSTAR_FACTOR_BYTES * PetscPowReal(nodes, 4.0 / 3.0), dense = 3.0 * 8.0 * (3 * contact) * (3 * contact);
  PetscReal limit, estimate = mesh + factor + dense;
  PetscBool fromOption;

  PetscFunctionBegin;
  PetscCall(MemoryLimit(comm, &limit, &fromOption));
  if (limit <= 0) PetscFunctionReturn(0); /* no /proc/meminfo: nothing to compare with */
  if (estimate > limit) {
    char counts[64];

    if (contact > 0) PetscCall(PetscSNPrintf(counts, sizeof(counts), "%.4g nodes, %.4g contact nodes", (double)nodes, (double)contact));
    else PetscCall(PetscSNPrintf(counts, sizeof(counts), "%.4g nodes", (double)nodes));
    SETERRQ(comm, PETSC_ERR_MEM, "%s: %s need at least %.3g GB (mesh and assembly %.3g GB, factorization of K %.3g GB, dense contact matrices %.3g GB), more than the %.3g GB %s; refused before the work", what, counts, (double)(estimate / 1e9), (double)(mesh / 1e9), (double)(factor / 1e9), (double)(dense / 1e9), (double)(limit / 1e9), fromOption ? "of -snes_ssstar_memory_limit" : "available on this machine (MemAvailable)");
  }
  PetscFunctionReturn(0);
}
