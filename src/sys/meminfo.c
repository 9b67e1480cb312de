/* The memory the machine has for the work */
#include "meminfo.h"
#include <stdio.h>

/* SSStarMemAvailable - MemAvailable of this node from /proc/meminfo, in bytes; 0 when unknown */
PetscErrorCode SSStarMemAvailable(PetscLogDouble *bytes)
{
  FILE  *file = fopen("/proc/meminfo", "r");
  char   line[256];
  double kb;

  PetscFunctionBegin;
  *bytes = 0;
  if (!file) PetscFunctionReturn(0);
  while (fgets(line, sizeof(line), file))
    if (sscanf(line, "MemAvailable: %lf kB", &kb) == 1) *bytes = 1024.0 * kb;
  fclose(file);
  PetscFunctionReturn(0);
}

/* VmRSS and VmHWM of this process from /proc/self/status, in bytes; PETSc's getrusage figure for both when unknown */
static PetscErrorCode ProcessMemory(PetscLogDouble *current, PetscLogDouble *peak)
{
  FILE  *file = fopen("/proc/self/status", "r");
  char   line[256];
  double kb;

  PetscFunctionBegin;
  *current = *peak = 0;
  if (file) {
    while (fgets(line, sizeof(line), file)) {
      if (sscanf(line, "VmRSS: %lf kB", &kb) == 1) *current = 1024.0 * kb;
      if (sscanf(line, "VmHWM: %lf kB", &kb) == 1) *peak = 1024.0 * kb;
    }
    fclose(file);
  }
  if (!*current) PetscCall(PetscMemoryGetCurrentUsage(current));
  if (!*peak) *peak = *current;
  PetscFunctionReturn(0);
}

/*@C
   SSStarMemoryGetUsage - the memory of the largest rank: its resident set now and its peak since the start (Linux's
   VmRSS and VmHWM; they need no -malloc_debug or -memory_view), the maximum over the ranks of comm

   Collective

   Input Parameter:
.  comm - the ranks

   Output Parameters:
+  current - bytes in memory now, on the rank with the most, or pass NULL
-  peak    - the most bytes a rank had in memory at once so far, or pass NULL

   Level: intermediate

.seealso: `SSStarSceneSetProgress()`, `SNESSSStarMonitorProgress()`
@*/
PetscErrorCode SSStarMemoryGetUsage(MPI_Comm comm, PetscLogDouble *current, PetscLogDouble *peak)
{
  PetscLogDouble mine[2];

  PetscFunctionBegin;
  PetscCall(ProcessMemory(&mine[0], &mine[1]));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, mine, 2, MPIU_PETSCLOGDOUBLE, MPI_MAX, comm));
  if (current) *current = mine[0];
  if (peak) *peak = mine[1];
  PetscFunctionReturn(0);
}

/*
   The memory of a progress line: the largest rank's resident set, and with -ssstar_progress_ranks (on several ranks)
   rank 0's and the least one's too, to see whether a phase loads one rank more than the others
*/
PetscErrorCode SSStarMemoryText(MPI_Comm comm, char text[], size_t len)
{
  PetscLogDouble mine[2], most, least, first;
  PetscMPIInt    size;
  PetscBool      ranks = PETSC_FALSE;

  PetscFunctionBegin;
  PetscCall(ProcessMemory(&mine[0], &mine[1]));
  PetscCall(MPIU_Allreduce(&mine[0], &most, 1, MPIU_PETSCLOGDOUBLE, MPI_MAX, comm));
  PetscCall(PetscSNPrintf(text, len, "%.3f GB per rank", most / 1e9));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-ssstar_progress_ranks", &ranks, NULL));
  if (size == 1 || !ranks) PetscFunctionReturn(0);
  PetscCall(MPIU_Allreduce(&mine[0], &least, 1, MPIU_PETSCLOGDOUBLE, MPI_MIN, comm));
  first = mine[0];
  PetscCallMPI(MPI_Bcast(&first, 1, MPIU_PETSCLOGDOUBLE, 0, comm));
  PetscCall(PetscSNPrintf(text + strlen(text), len - strlen(text), " (rank 0: %.3f, least: %.3f)", first / 1e9, least / 1e9));
  PetscFunctionReturn(0);
}
