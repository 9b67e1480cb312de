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
