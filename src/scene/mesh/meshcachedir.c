/* Where meshes made from a .geo are kept: a cache outside the source tree (issue 31), shared by the runs of a user. */
#include "../sceneimpl.h"
#include <errno.h>
#include <stdlib.h>
#include <unistd.h>
#include <sys/stat.h>

/* mkdir -p: every folder of path, each made unless it exists (another run may make it at the same time); 0 on success */
static int MakeFolders(const char path[])
{
  char buf[PETSC_MAX_PATH_LEN];

  if (strlen(path) >= sizeof(buf)) return -1;
  strcpy(buf, path);
  for (char *s = buf + 1; *s; s++) {
    if (*s != '/') continue;
    *s = 0;
    if (mkdir(buf, 0777) && errno != EEXIST) return -1;
    *s = '/';
  }
  if (mkdir(buf, 0777) && errno != EEXIST) return -1;
  return access(buf, W_OK);
}

/* The default cache: $XDG_CACHE_HOME/ssstar, else $HOME/.cache/ssstar, else none (empty) */
static void DefaultCache(char dir[], size_t len)
{
  const char *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");

  dir[0] = 0;
  if (xdg && xdg[0] == '/') snprintf(dir, len, "%s/ssstar", xdg);
  else if (home && home[0]) snprintf(dir, len, "%s/.cache/ssstar", home);
}

/*
   Rank 0: the folder of geo's meshes in the cache, <cache>/<folder of geo>-<hash of its absolute path>, made; empty when
   it cannot be made. A hash of the path keeps apart two .geo files of one name in different folders.
*/
static void GeoFolder(const char cache[], const char geo[], char folder[], size_t len)
{
  char        abs[PETSC_MAX_PATH_LEN], parent[PETSC_MAX_PATH_LEN] = "geo";
  unsigned    hash = 5381;
  const char *slash;

  folder[0] = 0;
  if (!cache[0]) return;
  if (!realpath(geo, abs)) snprintf(abs, sizeof(abs), "%s", geo);
  for (const char *c = abs; *c; c++) hash = 33 * hash + (unsigned char)*c;
  slash = strrchr(abs, '/');
  if (slash && slash > abs) { /* the name of the folder that holds geo */
    const char *start = slash - 1;

    while (start > abs && start[-1] != '/') start--;
    snprintf(parent, sizeof(parent), "%.*s", (int)(slash - start), start);
  }
  snprintf(folder, len, "%s/%s-%08x", cache, parent, hash);
  if (MakeFolders(folder)) folder[0] = 0;
}

/*@C
   SSStarMeshCacheFile - the mesh file a .geo is meshed into at a level (SSStarMeshGenerate()): in the mesh cache, out
   of the source tree, <cache>/<folder of the .geo>-<hash of its path>/<name>_L<level>.msh, e.g.
   ~/.cache/ssstar/meshes-1a2b3c4d/prism_L6.msh for meshes/prism.geo at level 6; its parallel cache (FILE.msh.h5) lies
   beside it

   Collective

   Input Parameters:
+  comm  - the ranks (rank 0 makes the folders)
.  cache - the cache folder (-mesh_cache), or NULL or "" for the default: $XDG_CACHE_HOME/ssstar, else
           ~/.cache/ssstar, else (neither can be made) $TMPDIR/ssstar-<user id> (default TMPDIR /tmp)
.  geo   - the geometry
-  level - its level

   Output Parameter:
.  msh - the mesh file (length PETSC_MAX_PATH_LEN), the same on every rank

   Notes:
   The folders are made as needed; several runs may share the cache at the same time (the mesh and its cache are
   written to temporary names and renamed). A cache given by -mesh_cache that cannot be made is an error naming it.

   Level: intermediate

.seealso: `SSStarMeshGenerate()`, `SSStarSceneSetUp()`
@*/
PetscErrorCode SSStarMeshCacheFile(MPI_Comm comm, const char cache[], const char geo[], PetscInt level, char msh[])
{
  PetscMPIInt rank;
  char        folder[PETSC_MAX_PATH_LEN], dir[PETSC_MAX_PATH_LEN];
  const char *name, *slash;
  size_t      len;
  PetscBool   given = (PetscBool)(cache && cache[0]);

  PetscFunctionBegin;
  PetscCall(PetscStrlen(geo, &len));
  PetscCheck(len > 4 && !strcmp(geo + len - 4, ".geo"), comm, PETSC_ERR_ARG_WRONG, "-geo %s: expected a .geo file", geo);
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  folder[0] = 0;
  if (rank == 0) {
    if (given) PetscCall(PetscStrncpy(dir, cache, sizeof(dir)));
    else DefaultCache(dir, sizeof(dir));
    GeoFolder(dir, geo, folder, sizeof(folder));
    if (!folder[0] && !given) { /* no home to write to: the temporary directory */
      snprintf(dir, sizeof(dir), "%s/ssstar-%d", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp", (int)getuid());
      GeoFolder(dir, geo, folder, sizeof(folder));
    }
  }
  PetscCallMPI(MPI_Bcast(folder, sizeof(folder), MPI_CHAR, 0, comm));
  PetscCheck(folder[0] || !given, comm, PETSC_ERR_FILE_WRITE, "-mesh_cache %s: cannot make the folder or write to it", cache);
  PetscCheck(folder[0], comm, PETSC_ERR_FILE_WRITE, "No mesh cache can be made for -geo %s ($XDG_CACHE_HOME/ssstar, ~/.cache/ssstar, $TMPDIR): give one with -mesh_cache <folder>", geo);
  slash = strrchr(geo, '/');
  name  = slash ? slash + 1 : geo;
  PetscCall(PetscSNPrintf(msh, PETSC_MAX_PATH_LEN, "%s/%.*s_L%" PetscInt_FMT ".msh", folder, (int)strlen(name) - 4, name, level));
  PetscFunctionReturn(0);
}
