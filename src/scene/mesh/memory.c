/* Memory before work: an estimate of what a mesh of N nodes needs, against what the machine has. */
#include "../sceneimpl.h"
#include "../../sys/meminfo.h"

/*
   The peak of the largest of size ranks over nodes mesh nodes (3 dofs each) from what each holds before the mesh (base),
   with smoothed aggregation or plain (sys/meminfo.h)
*/
PetscLogDouble SSStarPeakFrom(PetscMPIInt size, PetscReal nodes, PetscLogDouble base, PetscBool plain)
{
  return base + (SSSTAR_BODY_BYTES(size) + SSSTAR_SOLVE_BYTES(size, plain)) * 3 * nodes / size;
}

/* The same on the dense route, with contactNodes contact nodes: the mesh to the output, MUMPS's factors of K with the
   Schur block, P and the Newton step's dense matrices (sys/meminfo.h) */
PetscLogDouble SSStarPeakDenseFrom(PetscMPIInt size, PetscReal nodes, PetscReal contactNodes, PetscLogDouble base)
{
  return base + SSSTAR_BODY_BYTES(size) * 3 * nodes / size + SSSTAR_DENSE_BYTES(size, 3 * nodes, 3 * contactNodes);
}

/* Whether the whole body's multigrid will aggregate plainly by the size of K, dofs (-snes_ssstar_plain_aggregation_dofs,
   SNESSSStarSetPlainAggregationDofs()), unless -pc_gamg_agg_nsmooths chooses */
PetscErrorCode SSStarPlainAggregationBySize(PetscReal dofs, PetscBool *plain)
{
  PetscInt  from = SSSTAR_PLAIN_AGGREGATION_DOFS, nsmooths = 1;
  PetscBool set;

  PetscFunctionBegin;
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-pc_gamg_agg_nsmooths", &nsmooths, &set));
  if (set) {
    *plain = (PetscBool)(nsmooths == 0);
    PetscFunctionReturn(0);
  }
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-snes_ssstar_plain_aggregation_dofs", &from, NULL));
  *plain = (PetscBool)(from >= 0 && dofs >= from);
  PetscFunctionReturn(0);
}

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

/* The additional bytes of all the ranks and the peak of the largest from what each holds before the mesh (base); whether they fit */
static PetscErrorCode Estimate(MPI_Comm comm, PetscReal nodes, PetscBool plain, PetscLogDouble base, PetscLogDouble *peak, PetscLogDouble *extra, PetscBool *fits)
{
  PetscMPIInt size;
  PetscReal   limit, perRank;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  *peak  = SSStarPeakFrom(size, nodes, base, plain);
  *extra = (*peak - base) * size;
  PetscCall(MemoryLimit(comm, &limit, &perRank));
  *fits = (PetscBool)(limit <= 0 || (perRank > 0 ? *peak <= perRank * 1e9 : *extra <= limit)); /* no /proc/meminfo: nothing to compare with */
  PetscFunctionReturn(0);
}

/*
   The whole body's estimate from what each rank held before the mesh (base): the peak of the largest rank with the
   multigrid's aggregation (plain: by K's size, or where the smoothed one's peak does not fit), whether the smoothed
   one's peak fits (the verdict the solver follows, SNESSSStarSetSmoothedAggregationFits()), the bytes all ranks add
   and whether the peak fits
*/
PetscErrorCode SSStarEstimateWholeBody(MPI_Comm comm, PetscReal nodes, PetscLogDouble base, PetscLogDouble *peak, PetscBool *plain, PetscBool *smoothedFits, PetscLogDouble *extra, PetscBool *fits)
{
  PetscBool bySize, smoothed;

  PetscFunctionBegin;
  PetscCall(SSStarPlainAggregationBySize(3 * nodes, &bySize));
  PetscCall(Estimate(comm, nodes, PETSC_FALSE, base, peak, extra, &smoothed));
  *plain = (PetscBool)(bySize || !smoothed);
  if (smoothedFits) *smoothedFits = smoothed;
  PetscCall(Estimate(comm, nodes, *plain, base, peak, extra, fits));
  PetscFunctionReturn(0);
}

/*@C
   SSStarEstimateMemory - the peak memory a run over a mesh of nodes nodes is expected to reach on the largest of the
   ranks of comm: what that rank holds now (before the mesh) and its share of the mesh, the assembly and the solve, on
   the whole body (with the multigrid the solver will take) and on the dense route (a Schur complement P of the
   contactNodes contact nodes)

   Collective

   Input Parameters:
+  comm         - the ranks that will share the work
.  nodes        - mesh nodes (estimated or counted)
-  contactNodes - contact nodes (0 if not known: the dense route's estimate is then the whole body's without P)

   Output Parameters:
+  peak  - bytes at the peak on the largest rank, on the whole body
.  dense - bytes at the peak on the largest rank, on the dense route (MUMPS's factors of K with the Schur block of the
           3 contactNodes contact dofs, P and the Newton step's dense matrices: 4 matrices of P's size on one rank,
           the factorization's about N^(4/3)), or pass NULL
-  plain - PETSC_TRUE when the multigrid will aggregate plainly: K has at least -snes_ssstar_plain_aggregation_dofs dofs,
           or the smoothed aggregation's peak would not fit (a scene's solver follows this verdict of its estimate:
           SSStarSceneSetContact()), or pass NULL

   Notes:
   Measured per dof with bench/memory.py on the prism, one rank and several (docs/guide/large-problems.md, "Where the
   memory goes"), and on the dense route with bench/auto.py (docs/guide/choosing-a-route.md); the limit is
   -snes_ssstar_memory_limit or MemAvailable (SSStarCheckMemory()). auto takes the dense route only where it costs
   less time and fits.

   Level: intermediate

.seealso: `SSStarCheckMemory()`, `SSStarMemoryGetUsage()`
@*/
PetscErrorCode SSStarEstimateMemory(MPI_Comm comm, PetscReal nodes, PetscReal contactNodes, PetscLogDouble *peak, PetscLogDouble *dense, PetscBool *plain)
{
  PetscLogDouble extra, now;
  PetscBool      fits, isPlain;
  PetscMPIInt    size;

  PetscFunctionBegin;
  PetscCall(SSStarMemoryGetUsage(comm, &now, NULL));
  PetscCall(SSStarEstimateWholeBody(comm, nodes, now, peak, &isPlain, NULL, &extra, &fits));
  if (plain) *plain = isPlain;
  if (dense) {
    PetscCallMPI(MPI_Comm_size(comm, &size));
    *dense = SSStarPeakDenseFrom(size, nodes, contactNodes, now);
  }
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
   The estimate (SSStarEstimateMemory()) is the whole run's peak on the whole body: the mesh, the assembly and the
   solve (the path auto takes for all but small problems), with smoothed aggregation where it fits and plain
   aggregation where only that does. The limit is MemAvailable of /proc/meminfo (summed over the machines of comm;
   what the ranks add must fit) or -snes_ssstar_memory_limit <GB per rank> (the peak of each rank must fit). The dense
   route's factors of K and its dense P are checked again by the reduction.

   Level: intermediate

.seealso: `SSStarEstimateMemory()`, `SSStarMeshGenerate()`, `SNESSSStarSetMemoryLimit()`
@*/
PetscErrorCode SSStarCheckMemory(MPI_Comm comm, PetscReal nodes, const char what[])
{
  PetscReal      limit, perRank;
  PetscLogDouble peak, extra, now;
  PetscMPIInt    size;
  PetscBool      fits, plain;
  char           source[160];

  PetscFunctionBegin;
  PetscCall(SSStarMemoryGetUsage(comm, &now, NULL));
  PetscCall(SSStarEstimateWholeBody(comm, nodes, now, &peak, &plain, NULL, &extra, &fits));
  if (fits) PetscFunctionReturn(0);
  PetscCall(MemoryLimit(comm, &limit, &perRank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  if (perRank > 0) PetscCall(PetscSNPrintf(source, sizeof(source), "more than the %.3g GB of -snes_ssstar_memory_limit (per rank)", (double)perRank));
  else PetscCall(PetscSNPrintf(source, sizeof(source), "and the %d rank%s would add %.3g GB, more than the %.3g GB available on this machine (MemAvailable)", size, size > 1 ? "s" : "", (double)(extra / 1e9), (double)(limit / 1e9)));
  SETERRQ(comm, PETSC_ERR_MEM, "%s: %.4g nodes need an estimated %.3g GB per rank at the peak of the run (mesh, assembly and the solve on the whole body, with the multigrid's plain aggregation), %s; refused before the work", what, (double)nodes, (double)(peak / 1e9), source);
}
