/*
   libgmsh, opened when a run first needs it (SSStarGmshLoad()) instead of linked: it brings 70 shared libraries whose
   loading cost every process about half a second, also the runs that read their mesh from the cache and never mesh.
   The gmsh C API's names below call through the table SSStarGmshLoad() fills; call it before the first of them.
*/
#ifndef SSSTAR_GMSHLIB_H
#define SSSTAR_GMSHLIB_H
#include <petscsys.h>
#include <gmshc.h>

#define SSSTAR_GMSH_FUNCTIONS(X) \
  X(gmshInitialize) \
  X(gmshFinalize) \
  X(gmshOpen) \
  X(gmshWrite) \
  X(gmshFree) \
  X(gmshOptionSetNumber) \
  X(gmshOnelabGetNumber) \
  X(gmshModelGetPhysicalGroups) \
  X(gmshModelGetPhysicalName) \
  X(gmshModelGetEntitiesForPhysicalGroup) \
  X(gmshModelMeshGenerate) \
  X(gmshModelMeshGetNodes) \
  X(gmshModelMeshGetElementTypes) \
  X(gmshModelMeshGetElementsByType)

#define SSSTAR_GMSH_POINTER(f) __typeof__(f) *f;
typedef struct {
  SSSTAR_GMSH_FUNCTIONS(SSSTAR_GMSH_POINTER)
} SSStarGmshTable;
#undef SSSTAR_GMSH_POINTER

PETSC_INTERN SSStarGmshTable SSStarGmsh;
PETSC_INTERN int             SSStarGmshLoad(void);

#if !defined(SSSTAR_GMSHLIB_TABLE) /* gmshlib.c fills the table by these names */
#define gmshInitialize                       SSStarGmsh.gmshInitialize
#define gmshFinalize                         SSStarGmsh.gmshFinalize
#define gmshOpen                             SSStarGmsh.gmshOpen
#define gmshWrite                            SSStarGmsh.gmshWrite
#define gmshFree                             SSStarGmsh.gmshFree
#define gmshOptionSetNumber                  SSStarGmsh.gmshOptionSetNumber
#define gmshOnelabGetNumber                  SSStarGmsh.gmshOnelabGetNumber
#define gmshModelGetPhysicalGroups           SSStarGmsh.gmshModelGetPhysicalGroups
#define gmshModelGetPhysicalName             SSStarGmsh.gmshModelGetPhysicalName
#define gmshModelGetEntitiesForPhysicalGroup SSStarGmsh.gmshModelGetEntitiesForPhysicalGroup
#define gmshModelMeshGenerate                SSStarGmsh.gmshModelMeshGenerate
#define gmshModelMeshGetNodes                SSStarGmsh.gmshModelMeshGetNodes
#define gmshModelMeshGetElementTypes         SSStarGmsh.gmshModelMeshGetElementTypes
#define gmshModelMeshGetElementsByType       SSStarGmsh.gmshModelMeshGetElementsByType
#endif
#endif
