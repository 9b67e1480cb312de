/* libgmsh opened on first use (gmshlib.h) */
#define SSSTAR_GMSHLIB_TABLE
#include "gmshlib.h"
#include <dlfcn.h>

SSStarGmshTable SSStarGmsh;

/*
   Opens libgmsh (SSSTAR_GMSH_SONAME, found by configure.py) once and fills SSStarGmsh; returns 0, or 1 after printing
   why it cannot (the callers report it as gmsh's own failure, ierr != 0, on the ranks that called it)
*/
int SSStarGmshLoad(void)
{
  static void *lib = NULL;

  if (lib) return 0;
  lib = dlopen(SSSTAR_GMSH_SONAME, RTLD_NOW | RTLD_LOCAL);
  if (!lib) {
    (void)PetscErrorPrintf("Cannot open the gmsh library %s: %s\n", SSSTAR_GMSH_SONAME, dlerror());
    return 1;
  }
#define SSSTAR_GMSH_SYMBOL(f) \
  if (!(*(void **)&SSStarGmsh.f = dlsym(lib, #f))) { \
    (void)PetscErrorPrintf("The gmsh library %s has no %s\n", SSSTAR_GMSH_SONAME, #f); \
    dlclose(lib); \
    lib = NULL; \
    return 1; \
  }
  SSSTAR_GMSH_FUNCTIONS(SSSTAR_GMSH_SYMBOL)
#undef SSSTAR_GMSH_SYMBOL
  return 0;
}
