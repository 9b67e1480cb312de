/*
   The mesh cache: a gmsh mesh in a flat HDF5 file that every rank reads a slice of, so that no rank ever holds the
   whole mesh and nobody interpolates it serially (PETSc 3.18's gmsh and HDF5 DMPlex readers both load on rank 0).

   Written once per .msh (by rank 0 through the gmsh C API: the one-time serial step, like meshing itself), beside it
   (FILE.msh.h5) or, where that directory is not writable, in the temporary directory; rebuilt when the .msh's size or
   modification time differ from those it recorded. Content:

     /vertices     N x 3   the nodes by ascending gmsh node tag (the file order of the output)
     /cells        C x 4   the linear tetrahedra, vertex indices
     /cell_groups  C       bit v set: the cell is in the v-th volume group
     /faces_<k>    F_k x 3 the triangles of the k-th surface group, vertex indices
     /groups       G       names (fixed-length strings), with the attributes dims (2 or 3) and tags (gmsh's)

   Read: rank r takes the cells [r C/p, (r+1) C/p) and the vertices [r N/p, (r+1) N/p), DMPlex builds the distributed
   mesh from them (DMPlexCreateFromCellListParallelPetsc, not interpolated), ssstar adds the faces (no edges: nothing
   uses them, and DMPlexInterpolate's faces and edges were most of the read's time at scale), the volume groups label
   the local cells, and the surface groups' triangles find their faces through a hash of their vertices (each triangle
   and each local boundary face meet on the rank their vertex triple hashes to).
*/
#include "../sceneimpl.h"
#include <petscsf.h>
#include <hdf5.h>
#include "../../sys/gmshlib.h"
#include <sys/stat.h>
#include <stdio.h>
#include <unistd.h>

#define SSSTAR_CACHE_VERSION 1
#define SSSTAR_CACHE_NAME_LEN 128
#if PETSC_SIZEOF_INT == 8
  #define H5T_NATIVE_PETSCINT H5T_NATIVE_LLONG
#else
  #define H5T_NATIVE_PETSCINT (sizeof(PetscInt) == 8 ? H5T_NATIVE_LLONG : H5T_NATIVE_INT)
#endif

#define PetscCallH5(call) \
  do { \
    if ((call) < 0) SETERRQ(PETSC_COMM_SELF, PETSC_ERR_LIB, "HDF5 failed in %s", #call); \
  } while (0)

/* The identity of a .msh file: size and modification time (0, 0 if it cannot be read) */
static void FileStamp(const char file[], long long stamp[2])
{
  struct stat st;

  stamp[0] = stamp[1] = 0;
  if (stat(file, &st)) return;
  stamp[0] = (long long)st.st_size;
  stamp[1] = (long long)st.st_mtime;
}

static PetscErrorCode WriteDataset(hid_t file, const char name[], hid_t type, int rank, const hsize_t dims[], const void *data)
{
  hid_t space, set;

  PetscFunctionBegin;
  space = H5Screate_simple(rank, dims, NULL);
  PetscCheck(space >= 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "HDF5: cannot create the dataspace of %s", name);
  set = H5Dcreate2(file, name, type == H5T_NATIVE_DOUBLE ? H5T_IEEE_F64LE : H5T_STD_I64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  PetscCheck(set >= 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "HDF5: cannot create the dataset %s", name);
  if (dims[0] > 0) PetscCallH5(H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data));
  PetscCallH5(H5Dclose(set));
  PetscCallH5(H5Sclose(space));
  PetscFunctionReturn(0);
}

static PetscErrorCode WriteAttribute(hid_t object, const char name[], hid_t type, hsize_t n, const void *data)
{
  hid_t space, attr;

  PetscFunctionBegin;
  space = H5Screate_simple(1, &n, NULL);
  attr  = H5Acreate2(object, name, type == H5T_NATIVE_DOUBLE ? H5T_IEEE_F64LE : H5T_STD_I64LE, space, H5P_DEFAULT, H5P_DEFAULT);
  PetscCheck(attr >= 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "HDF5: cannot create the attribute %s", name);
  PetscCallH5(H5Awrite(attr, type, data));
  PetscCallH5(H5Aclose(attr));
  PetscCallH5(H5Sclose(space));
  PetscFunctionReturn(0);
}

/* The position of node tag t among the sorted tags (they are unique) */
static PetscInt NodeIndex(const size_t sorted[], size_t n, size_t t)
{
  size_t lo = 0, hi = n;

  while (lo < hi) {
    const size_t mid = (lo + hi) / 2;

    if (sorted[mid] < t) lo = mid + 1;
    else hi = mid;
  }
  return lo < n && sorted[lo] == t ? (PetscInt)lo : -1;
}

static int CompareSize(const void *a, const void *b)
{
  const size_t x = *(const size_t *)a, y = *(const size_t *)b;

  return x < y ? -1 : x > y;
}

/* The elements of type (4: linear tetrahedra, 2: triangles) of the entities of a physical group, as vertex indices */
static void GroupElements(int dim, int tag, int type, const size_t sortedNodes[], size_t nnodes, long long **out, size_t *nout, int *ierr)
{
  int   *entities = NULL;
  size_t nentities = 0, per = type == 4 ? 4 : 3, cap = 0;

  *out  = NULL;
  *nout = 0;
  gmshModelGetEntitiesForPhysicalGroup(dim, tag, &entities, &nentities, ierr);
  for (size_t e = 0; !*ierr && e < nentities; e++) {
    size_t *etags = NULL, ne = 0, *nodes = NULL, nn = 0;

    gmshModelMeshGetElementsByType(type, &etags, &ne, &nodes, &nn, entities[e], 0, 1, ierr);
    if (!*ierr && *nout + ne > cap) {
      cap  = 2 * (*nout + ne);
      *out = (long long *)realloc(*out, cap * per * sizeof(long long));
    }
    for (size_t k = 0; !*ierr && k < nn; k++) (*out)[*nout * per + k] = NodeIndex(sortedNodes, nnodes, nodes[k]);
    *nout += ne;
    gmshFree(etags);
    gmshFree(nodes);
  }
  gmshFree(entities);
}

/*
   Rank 0: writes the cache of the mesh in gmsh's current model to a temporary name, renamed to cache when complete.
   *failure: 0, or 1 (gmsh cannot give the mesh), 2 (cannot write the cache), 3 (a volume element that is not a
   linear tetrahedron).
*/
static PetscErrorCode WriteCacheOfModel(const char cache[], const long long stamp[2], int *failure)
{
  char       tmp[PETSC_MAX_PATH_LEN];
  size_t    *nodeTags = NULL, nn = 0, nc3 = 0, np = 0, *sorted = NULL, *byTag = NULL, ncells = 0, ndimTags = 0, ng = 0;
  double    *coord = NULL, *param = NULL, *vertices = NULL;
  long long *cells = NULL, *cellGroups = NULL, *dims = NULL, *tags = NULL;
  int       *dimTags = NULL, ierr = 0, nvol = 0;
  char      *names = NULL;
  hid_t      file = -1;

  PetscFunctionBegin;
  *failure = 0;
  gmshModelMeshGetNodes(&nodeTags, &nn, &coord, &nc3, &param, &np, -1, -1, 0, 0, &ierr);
  if (ierr) {
    *failure = 1;
    PetscFunctionReturn(0);
  }
  /* the vertices by ascending node tag */
  PetscCall(PetscMalloc2(nn, &sorted, 3 * nn, &vertices));
  for (size_t i = 0; i < nn; i++) sorted[i] = nodeTags[i];
  qsort(sorted, nn, sizeof(size_t), CompareSize);
  for (size_t i = 0; i < nn; i++) {
    const PetscInt k = NodeIndex(sorted, nn, nodeTags[i]);

    for (int d = 0; d < 3; d++) vertices[3 * k + d] = coord[3 * i + d];
  }
  /* every linear tetrahedron, and (element tag, position) pairs sorted by tag, to find a group's cells */
  {
    size_t *etags = NULL, ne = 0, *enodes = NULL, nen = 0, ntypes = 0;
    int    *types = NULL;

    gmshModelMeshGetElementTypes(&types, &ntypes, 3, -1, &ierr);
    for (size_t t = 0; !ierr && t < ntypes; t++)
      if (types[t] != 4) *failure = 3;
    gmshFree(types);
    if (!ierr) gmshModelMeshGetElementsByType(4, &etags, &ne, &enodes, &nen, -1, 0, 1, &ierr);
    ncells = ne;
    PetscCall(PetscMalloc3(4 * ne, &cells, ne, &cellGroups, 2 * ne, &byTag));
    for (size_t k = 0; k < nen; k++) cells[k] = NodeIndex(sorted, nn, enodes[k]);
    for (size_t k = 0; k < ne; k++) {
      byTag[2 * k]     = etags[k];
      byTag[2 * k + 1] = k;
      cellGroups[k]    = 0;
    }
    qsort(byTag, ne, 2 * sizeof(size_t), CompareSize);
    gmshFree(etags);
    gmshFree(enodes);
  }
  /* the physical groups of dimension 2 and 3 */
  if (!ierr) gmshModelGetPhysicalGroups(&dimTags, &ndimTags, -1, &ierr);
  ndimTags /= 2;
  PetscCall(PetscCalloc3(ndimTags * SSSTAR_CACHE_NAME_LEN, &names, ndimTags, &dims, ndimTags, &tags));
  for (size_t g = 0; !ierr && g < ndimTags; g++) {
    char *name = NULL;

    if (dimTags[2 * g] < 2) continue;
    gmshModelGetPhysicalName(dimTags[2 * g], dimTags[2 * g + 1], &name, &ierr);
    if (!ierr) PetscCall(PetscStrncpy(names + ng * SSSTAR_CACHE_NAME_LEN, name, SSSTAR_CACHE_NAME_LEN));
    gmshFree(name);
    dims[ng]   = dimTags[2 * g];
    tags[ng++] = dimTags[2 * g + 1];
  }
  PetscCall(PetscSNPrintf(tmp, sizeof(tmp), "%s.%d.tmp", cache, (int)getpid()));
  if (!ierr && !*failure) {
    file = H5Fcreate(tmp, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    if (file < 0) *failure = 2;
  }
  for (size_t g = 0; !ierr && !*failure && g < ng; g++) {
    if (dims[g] == 3) { /* a bit per volume group */
      int   *entities = NULL;
      size_t nentities = 0;

      gmshModelGetEntitiesForPhysicalGroup(3, (int)tags[g], &entities, &nentities, &ierr);
      for (size_t e = 0; !ierr && e < nentities; e++) {
        size_t *etags = NULL, ne = 0, *enodes = NULL, nen = 0;

        gmshModelMeshGetElementsByType(4, &etags, &ne, &enodes, &nen, entities[e], 0, 1, &ierr);
        for (size_t k = 0; k < ne; k++) {
          size_t key[2] = {etags[k], 0}, *hit = (size_t *)bsearch(key, byTag, ncells, 2 * sizeof(size_t), CompareSize);

          if (hit) cellGroups[hit[1]] |= 1LL << nvol;
        }
        gmshFree(etags);
        gmshFree(enodes);
      }
      gmshFree(entities);
      nvol++;
    } else {
      long long *tri = NULL;
      size_t     ntri = 0;
      hsize_t    fdims[2];
      char       set[64];

      GroupElements(2, (int)tags[g], 2, sorted, nn, &tri, &ntri, &ierr);
      fdims[0] = ntri;
      fdims[1] = 3;
      PetscCall(PetscSNPrintf(set, sizeof(set), "faces_%d", (int)g));
      if (!ierr) PetscCall(WriteDataset(file, set, H5T_NATIVE_LLONG, 2, fdims, tri));
      free(tri);
    }
  }
  if (ierr) *failure = 1;
  if (!*failure) {
    hsize_t   vd[2] = {nn, 3}, cd[2] = {ncells, 4}, gd[1] = {ncells}, ngh = ng;
    hid_t     strtype, space, set;
    long long meta[4] = {SSSTAR_CACHE_VERSION, stamp[0], stamp[1], (long long)ng};

    PetscCall(WriteDataset(file, "vertices", H5T_NATIVE_DOUBLE, 2, vd, vertices));
    PetscCall(WriteDataset(file, "cells", H5T_NATIVE_LLONG, 2, cd, cells));
    PetscCall(WriteDataset(file, "cell_groups", H5T_NATIVE_LLONG, 1, gd, cellGroups));
    strtype = H5Tcopy(H5T_C_S1);
    PetscCallH5(H5Tset_size(strtype, SSSTAR_CACHE_NAME_LEN));
    space = H5Screate_simple(1, &ngh, NULL);
    set   = H5Dcreate2(file, "groups", strtype, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (ng) PetscCallH5(H5Dwrite(set, strtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, names));
    if (ng) PetscCall(WriteAttribute(set, "dims", H5T_NATIVE_LLONG, ng, dims));
    if (ng) PetscCall(WriteAttribute(set, "tags", H5T_NATIVE_LLONG, ng, tags));
    PetscCall(WriteAttribute(set, "meta", H5T_NATIVE_LLONG, 4, meta));
    PetscCallH5(H5Dclose(set));
    PetscCallH5(H5Sclose(space));
    PetscCallH5(H5Tclose(strtype));
  }
  if (file >= 0) PetscCallH5(H5Fclose(file));
  if (!*failure && rename(tmp, cache)) *failure = 2;
  if (*failure) unlink(tmp);
  PetscCall(PetscFree3(names, dims, tags));
  PetscCall(PetscFree3(cells, cellGroups, byTag));
  PetscCall(PetscFree2(sorted, vertices));
  gmshFree(nodeTags);
  gmshFree(coord);
  gmshFree(param);
  gmshFree(dimTags);
  PetscFunctionReturn(0);
}

/* Rank 0: reads msh with gmsh and writes its cache (WriteCacheOfModel(); *failure 1 also when gmsh cannot read msh) */
static PetscErrorCode WriteCache(const char msh[], const char cache[], const long long stamp[2], int *failure)
{
  int ierr = 0;

  PetscFunctionBegin;
  *failure = 1;
  if (SSStarGmshLoad()) PetscFunctionReturn(0);
  gmshInitialize(0, NULL, 0, &ierr);
  if (!ierr) gmshOptionSetNumber("General.Verbosity", 0, &ierr);
  if (!ierr) gmshOpen(msh, &ierr);
  if (!ierr) PetscCall(WriteCacheOfModel(cache, stamp, failure));
  gmshFinalize(&ierr);
  PetscFunctionReturn(0);
}

/* The cache of msh: FILE.msh.h5 beside it when that directory is writable, else one in the temporary directory */
static PetscErrorCode CacheName(const char msh[], char cache[], size_t len)
{
  char        dir[PETSC_MAX_PATH_LEN], abs[PETSC_MAX_PATH_LEN];
  const char *slash;
  unsigned    hash = 5381;

  PetscFunctionBegin;
  PetscCall(PetscStrncpy(dir, msh, sizeof(dir)));
  PetscCall(PetscStrrchr(msh, '/', (char **)&slash));
  if (slash != msh) dir[slash - msh - 1] = 0;
  else PetscCall(PetscStrncpy(dir, ".", sizeof(dir)));
  if (!access(dir, W_OK)) {
    PetscCall(PetscSNPrintf(cache, len, "%s.h5", msh));
    PetscFunctionReturn(0);
  }
  if (!realpath(msh, abs)) PetscCall(PetscStrncpy(abs, msh, sizeof(abs)));
  for (const char *c = abs; *c; c++) hash = 33 * hash + (unsigned char)*c;
  PetscCall(PetscSNPrintf(cache, len, "%s/ssstar-mesh-%08x.h5", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp", hash));
  PetscFunctionReturn(0);
}

/* Whether cache exists, is of this version and was made from msh as it is now (rank 0) */
static PetscBool CacheCurrent(const char cache[], const long long stamp[2])
{
  long long meta[4] = {0, 0, 0, 0};
  hid_t     file, set, attr;
  herr_t    ok = -1;

  if (access(cache, R_OK)) return PETSC_FALSE;
  H5E_BEGIN_TRY
  {
    file = H5Fopen(cache, H5F_ACC_RDONLY, H5P_DEFAULT);
    if (file >= 0) {
      set = H5Dopen2(file, "groups", H5P_DEFAULT);
      if (set >= 0) {
        attr = H5Aopen(set, "meta", H5P_DEFAULT);
        if (attr >= 0) {
          ok = H5Aread(attr, H5T_NATIVE_LLONG, meta);
          H5Aclose(attr);
        }
        H5Dclose(set);
      }
      H5Fclose(file);
    }
  }
  H5E_END_TRY;
  return (PetscBool)(ok >= 0 && meta[0] == SSSTAR_CACHE_VERSION && meta[1] == stamp[0] && meta[2] == stamp[1]);
}

/*
   Rank 0, right after gmsh wrote msh from its current model: the cache of msh from that model, so that the first read
   of msh does not parse it again (a failure here is left to SSStarMeshLoadCached(), which writes the cache itself)
*/
PetscErrorCode SSStarMeshCacheFromModel(const char msh[])
{
  char      cache[PETSC_MAX_PATH_LEN];
  long long stamp[2];
  int       failure;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(SSSTAR_MeshCache, 0, 0, 0, 0));
  PetscCall(CacheName(msh, cache, sizeof(cache)));
  FileStamp(msh, stamp);
  PetscCall(WriteCacheOfModel(cache, stamp, &failure));
  PetscCall(PetscLogEventEnd(SSSTAR_MeshCache, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* rows [start, start + count) of a dataset of cols columns into buf */
static PetscErrorCode ReadRows(hid_t file, const char name[], hid_t memtype, hsize_t start, hsize_t count, hsize_t cols, void *buf)
{
  hid_t   set, fspace, mspace;
  hsize_t off[2] = {start, 0}, cnt[2] = {count, cols};
  int     rank;

  PetscFunctionBegin;
  if (!count) PetscFunctionReturn(0);
  set = H5Dopen2(file, name, H5P_DEFAULT);
  PetscCheck(set >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "The mesh cache has no dataset %s", name);
  fspace = H5Dget_space(set);
  rank   = H5Sget_simple_extent_ndims(fspace);
  PetscCallH5(H5Sselect_hyperslab(fspace, H5S_SELECT_SET, off, NULL, cnt, NULL));
  mspace = H5Screate_simple(rank, cnt, NULL);
  PetscCallH5(H5Dread(set, memtype, mspace, fspace, H5P_DEFAULT, buf));
  PetscCallH5(H5Sclose(mspace));
  PetscCallH5(H5Sclose(fspace));
  PetscCallH5(H5Dclose(set));
  PetscFunctionReturn(0);
}

static PetscErrorCode DatasetRows(hid_t file, const char name[], PetscInt *rows)
{
  hid_t   set, space;
  hsize_t dims[2] = {0, 0};

  PetscFunctionBegin;
  set = H5Dopen2(file, name, H5P_DEFAULT);
  PetscCheck(set >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "The mesh cache has no dataset %s", name);
  space = H5Dget_space(set);
  PetscCallH5(H5Sget_simple_extent_dims(space, dims, NULL));
  *rows = (PetscInt)dims[0];
  PetscCallH5(H5Sclose(space));
  PetscCallH5(H5Dclose(set));
  PetscFunctionReturn(0);
}

typedef struct {
  PetscInt n;
  char (*names)[SSSTAR_CACHE_NAME_LEN];
  long long *dims, *tags;
} CacheGroups;

static PetscErrorCode ReadGroups(hid_t file, CacheGroups *g)
{
  hid_t     set, strtype, attr;
  long long meta[4];

  PetscFunctionBegin;
  set = H5Dopen2(file, "groups", H5P_DEFAULT);
  PetscCheck(set >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "The mesh cache has no groups");
  attr = H5Aopen(set, "meta", H5P_DEFAULT);
  PetscCallH5(H5Aread(attr, H5T_NATIVE_LLONG, meta));
  PetscCallH5(H5Aclose(attr));
  g->n = (PetscInt)meta[3];
  PetscCall(PetscCalloc3(g->n, &g->names, g->n, &g->dims, g->n, &g->tags));
  if (g->n) {
    strtype = H5Tcopy(H5T_C_S1);
    PetscCallH5(H5Tset_size(strtype, SSSTAR_CACHE_NAME_LEN));
    PetscCallH5(H5Dread(set, strtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, g->names));
    PetscCallH5(H5Tclose(strtype));
    attr = H5Aopen(set, "dims", H5P_DEFAULT);
    PetscCallH5(H5Aread(attr, H5T_NATIVE_LLONG, g->dims));
    PetscCallH5(H5Aclose(attr));
    attr = H5Aopen(set, "tags", H5P_DEFAULT);
    PetscCallH5(H5Aread(attr, H5T_NATIVE_LLONG, g->tags));
    PetscCallH5(H5Aclose(attr));
  }
  PetscCallH5(H5Dclose(set));
  PetscFunctionReturn(0);
}

/* The groups the scene uses exist in the mesh and are of the kind the option needs (the same verdict on every rank) */
static PetscErrorCode CheckGroups(MPI_Comm comm, const char file[], const CacheGroups *g, PetscInt n, const SSStarGroupUse uses[])
{
  char        available[1024] = "";
  const char *kinds[]         = {"surface or volume", "surface", "volume"};

  PetscFunctionBegin;
  for (PetscInt k = 0; k < g->n; k++) {
    if (available[0]) PetscCall(PetscStrlcat(available, ", ", sizeof(available)));
    PetscCall(PetscStrlcat(available, g->names[k], sizeof(available)));
  }
  for (PetscInt u = 0; u < n; u++) {
    PetscInt  k;
    PetscBool same = PETSC_FALSE;

    for (k = 0; k < g->n && !same; k++) PetscCall(PetscStrcmp(uses[u].group, g->names[k], &same));
    PetscCheck(same, comm, PETSC_ERR_ARG_WRONG, "Mesh %s has no physical group named \"%s\" (option %s); its groups: %s", file, uses[u].group, uses[u].option, available[0] ? available : "none");
    k--;
    PetscCheck(uses[u].kind == SSSTAR_GROUP_ANY || (uses[u].kind == SSSTAR_GROUP_SURFACE && g->dims[k] == 2) || (uses[u].kind == SSSTAR_GROUP_VOLUME && g->dims[k] == 3), comm, PETSC_ERR_ARG_WRONG, "Physical group \"%s\" of mesh %s is not a %s group, as option %s needs", uses[u].group, file, kinds[uses[u].kind], uses[u].option);
  }
  PetscFunctionReturn(0);
}

/*
   Matches triangles (sorted vertex triples, fourth entry -1 - group) with this rank's faces of support 1 (the
   boundary, and faces on a partition boundary) or, when interior, of support 2: both meet on the rank their triple
   hashes to, which sends (face, group) back to the face's rank to be labelled. On return tri[] holds the triangles that
   matched no face (on their home rank).
*/
static PetscErrorCode MatchFaces(MPI_Comm comm, DM dm, const CacheGroups *g, const PetscInt gvertex[], PetscBool interior, PetscInt *ntri, PetscInt **tri)
{
  PetscMPIInt size, rank, *dest;
  PetscInt    fStart, fEnd, vStart, vEnd, nface = 0, *rec, nrecv, *recv, nback = 0, *back, nret, *ret, nleft = 0;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(DMPlexGetHeightStratum(dm, 1, &fStart, &fEnd));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(PetscMalloc2(fEnd - fStart + *ntri + 1, &dest, 4 * (fEnd - fStart + *ntri) + 1, &rec));
  /* a face record carries its rank and local number in the fourth entry: rank + size * face */
  for (PetscInt f = fStart; f < fEnd; f++) {
    PetscInt *closure = NULL, ncl, support, k = 0;

    PetscCall(DMPlexGetSupportSize(dm, f, &support));
    if (support != (interior ? 2 : 1)) continue;
    PetscCall(DMPlexGetTransitiveClosure(dm, f, PETSC_TRUE, &ncl, &closure));
    for (PetscInt i = 0; i < 2 * ncl; i += 2)
      if (closure[i] >= vStart && closure[i] < vEnd && k < 3) rec[4 * nface + k++] = gvertex[closure[i] - vStart];
    PetscCall(DMPlexRestoreTransitiveClosure(dm, f, PETSC_TRUE, &ncl, &closure));
    SSStarTripleSort(&rec[4 * nface]);
    rec[4 * nface + 3] = rank + (PetscInt)size * f;
    dest[nface]        = SSStarTripleHomeRank(rec + 4 * nface, size);
    nface++;
  }
  for (PetscInt i = 0; i < *ntri; i++) {
    PetscCall(PetscArraycpy(rec + 4 * (nface + i), *tri + 4 * i, 4));
    dest[nface + i] = SSStarTripleHomeRank(rec + 4 * (nface + i), size);
  }
  PetscCall(SSStarTripleExchange(comm, nface + *ntri, dest, rec, &nrecv, &recv));
  PetscCall(PetscFree2(dest, rec));
  /* at home: records sorted by triple; each triangle sends (face, group) to the ranks of its faces */
  qsort(recv, nrecv, 4 * sizeof(PetscInt), SSStarTripleCompare);
  PetscCall(PetscFree(*tri));
  PetscCall(PetscMalloc2(nrecv + 1, &dest, 4 * nrecv + 1, &back));
  PetscCall(PetscMalloc1(4 * nrecv + 1, tri));
  for (PetscInt i = 0; i < nrecv; i++) {
    PetscBool found = PETSC_FALSE;
    PetscInt  lo = i, hi = i;

    if (recv[4 * i + 3] >= 0) continue; /* a face */
    while (lo > 0 && !SSStarTripleCompare(recv + 4 * (lo - 1), recv + 4 * i)) lo--;
    while (hi + 1 < nrecv && !SSStarTripleCompare(recv + 4 * (hi + 1), recv + 4 * i)) hi++;
    for (PetscInt j = lo; j <= hi; j++)
      if (recv[4 * j + 3] >= 0) {
        dest[nback]         = (PetscMPIInt)(recv[4 * j + 3] % size);
        back[4 * nback]     = recv[4 * j + 3] / size;
        back[4 * nback + 1] = -1 - recv[4 * i + 3];
        nback++;
        found = PETSC_TRUE;
      }
    if (!found) PetscCall(PetscArraycpy(*tri + 4 * nleft++, recv + 4 * i, 4));
  }
  *ntri = nleft;
  PetscCall(PetscFree(recv));
  PetscCall(SSStarTripleExchange(comm, nback, dest, back, &nret, &ret));
  PetscCall(PetscFree2(dest, back));
  for (PetscInt i = 0; i < nret; i++) PetscCall(DMSetLabelValue(dm, g->names[ret[4 * i + 1]], ret[4 * i], (PetscInt)g->tags[ret[4 * i + 1]]));
  PetscCall(PetscFree(ret));
  PetscFunctionReturn(0);
}

/* This rank's slice of each surface group's triangles: 3 vertices (sorted) and -1 - group each */
static PetscErrorCode ReadTriangles(MPI_Comm comm, hid_t file, const CacheGroups *g, PetscInt *ntri, PetscInt **tri)
{
  PetscMPIInt rank, size;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  *ntri = 0;
  for (PetscInt k = 0; k < g->n; k++) {
    char     set[64];
    PetscInt rows;

    if (g->dims[k] != 2) continue;
    PetscCall(PetscSNPrintf(set, sizeof(set), "faces_%d", (int)k));
    PetscCall(DatasetRows(file, set, &rows));
    *ntri += SSStarSliceStart(rank + 1, rows, size) - SSStarSliceStart(rank, rows, size);
  }
  PetscCall(PetscMalloc1(4 * *ntri + 1, tri));
  *ntri = 0;
  for (PetscInt k = 0; k < g->n; k++) {
    char     set[64];
    PetscInt rows, lo, cnt, *v;

    if (g->dims[k] != 2) continue;
    PetscCall(PetscSNPrintf(set, sizeof(set), "faces_%d", (int)k));
    PetscCall(DatasetRows(file, set, &rows));
    lo  = SSStarSliceStart(rank, rows, size);
    cnt = SSStarSliceStart(rank + 1, rows, size) - lo;
    PetscCall(PetscMalloc1(3 * cnt + 1, &v));
    PetscCall(ReadRows(file, set, H5T_NATIVE_PETSCINT, lo, cnt, 3, v));
    for (PetscInt t = 0; t < cnt; t++) {
      for (int c = 0; c < 3; c++) (*tri)[4 * *ntri + c] = v[3 * t + c];
      SSStarTripleSort(&(*tri)[4 * *ntri]);
      (*tri)[4 * (*ntri)++ + 3] = -1 - k;
    }
    PetscCall(PetscFree(v));
  }
  PetscFunctionReturn(0);
}

/*
   Labels the faces of the surface groups from this rank's triangles (taken): boundary faces first, then interior faces
   (a group on an interface between volumes) for the triangles left. A triangle that is no face of the tetrahedra is
   an error naming its group.
*/
static PetscErrorCode LabelFaces(MPI_Comm comm, const char msh[], const CacheGroups *g, DM dm, const PetscInt gvertex[], PetscInt ntri, PetscInt *tri)
{
  PetscInt left, unmatched = 0;

  PetscFunctionBegin;
  PetscCall(MatchFaces(comm, dm, g, gvertex, PETSC_FALSE, &ntri, &tri));
  PetscCall(MPIU_Allreduce(&ntri, &left, 1, MPIU_INT, MPI_SUM, comm));
  if (left) PetscCall(MatchFaces(comm, dm, g, gvertex, PETSC_TRUE, &ntri, &tri));
  if (ntri) unmatched = 1 - 1 - tri[3];
  PetscCall(PetscFree(tri));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &unmatched, 1, MPIU_INT, MPI_MAX, comm));
  PetscCheck(!unmatched, comm, PETSC_ERR_ARG_WRONG, "Mesh %s: a triangle of physical group \"%s\" is not a face of the mesh's tetrahedra", msh, g->names[unmatched - 1]);
  PetscFunctionReturn(0);
}

/*
   The file index of every local vertex: vertexSF's leaves are the local vertices in order, its roots each rank's slice
   of the vertices (rank r holds [r N/p, (r + 1) N/p))
*/
static PetscErrorCode GlobalVertexNumbers(MPI_Comm comm, PetscSF vsf, PetscInt NV, PetscInt **gv)
{
  PetscInt           nleaves;
  const PetscInt    *ilocal;
  const PetscSFNode *iremote;
  PetscMPIInt        size;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(PetscSFGetGraph(vsf, NULL, &nleaves, &ilocal, &iremote));
  PetscCall(PetscMalloc1(nleaves + 1, gv));
  for (PetscInt l = 0; l < nleaves; l++) {
    const PetscMPIInt r = (PetscMPIInt)iremote[l].rank;

    (*gv)[ilocal ? ilocal[l] : l] = r * (NV / size) + PetscMin(r, NV % size) + iremote[l].index;
  }
  PetscFunctionReturn(0);
}

/*
   The node count after refine refinements of a mesh of NV vertices and NC tetrahedra, before the work: each adds a
   vertex per edge, and a mesh of tetrahedra has about NV + NC edges (Euler: V - E + F - C = 1 with F about 2 C)
*/
static PetscReal RefinedNodes(PetscInt NV, PetscInt NC, PetscInt refine)
{
  PetscReal v = NV, c = NC;

  for (PetscInt k = 0; k < refine; k++) {
    v += v + c;
    c *= 8;
  }
  return v;
}

/*
   SSStarMeshLoadCached - the distributed DMPlex of a gmsh mesh (cells, faces, vertices; no edges) through its cache (written first when
   missing or out of date), refined refine times in parallel (meshrefine.c), with a label per physical group (named
   after it, values its tag; the groups the scene uses completed with the closure of their faces and cells) and tags:
   each local vertex's index in the file's node order (of a refined mesh: the file's nodes, then the new ones, each
   refinement's in the order of their edges). Every rank reads its slice; none holds the whole mesh.
*/
PetscErrorCode SSStarMeshLoadCached(MPI_Comm comm, const char msh[], PetscInt n, const SSStarGroupUse uses[], PetscInt refine, DM *dm, Vec *tags)
{
  char             cache[PETSC_MAX_PATH_LEN];
  long long        stamp[2];
  PetscMPIInt      rank, size;
  int              failure = 0;
  hid_t            plist, file;
  CacheGroups      groups;
  PetscInt         NC, *vadj = NULL;
  SSStarMeshSlices m;
  PetscSF          vsf;
  PetscScalar     *ta;
  DM               dm0;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(CacheName(msh, cache, sizeof(cache)));
  PetscCall(PetscLogEventBegin(SSSTAR_MeshCache, 0, 0, 0, 0));
  if (rank == 0) {
    FileStamp(msh, stamp);
    if (!CacheCurrent(cache, stamp)) PetscCall(WriteCache(msh, cache, stamp, &failure));
  }
  PetscCallMPI(MPI_Bcast(&failure, 1, MPI_INT, 0, comm));
  PetscCall(PetscLogEventEnd(SSSTAR_MeshCache, 0, 0, 0, 0));
  PetscCheck(failure != 1, comm, PETSC_ERR_FILE_UNEXPECTED, "Cannot read the mesh file %s (gmsh could not; is it a complete gmsh file?)", msh);
  PetscCheck(failure != 2, comm, PETSC_ERR_FILE_WRITE, "Cannot write the mesh cache %s of %s", cache, msh);
  PetscCheck(failure != 3, comm, PETSC_ERR_SUP, "The mesh file %s has volume elements that are not linear tetrahedra: ssstar's FEM is P1 on tetrahedra", msh);

  plist = H5Pcreate(H5P_FILE_ACCESS);
  PetscCallH5(H5Pset_fapl_mpio(plist, comm, MPI_INFO_NULL));
  file = H5Fopen(cache, H5F_ACC_RDONLY, plist);
  PetscCallH5(H5Pclose(plist));
  PetscCheck(file >= 0, comm, PETSC_ERR_FILE_OPEN, "Cannot open the mesh cache %s of %s", cache, msh);
  PetscCall(PetscLogEventBegin(SSSTAR_MeshBuild, 0, 0, 0, 0));
  PetscCall(ReadGroups(file, &groups));
  PetscCall(CheckGroups(comm, msh, &groups, n, uses));
  PetscCall(DatasetRows(file, "cells", &NC));
  PetscCall(DatasetRows(file, "vertices", &m.NV));
  PetscCheck(NC > 0, comm, PETSC_ERR_ARG_WRONG, "The mesh file %s has no tetrahedra", msh);
  if (refine > 0) {
    char what[PETSC_MAX_PATH_LEN + 64];

    PetscCall(PetscSNPrintf(what, sizeof(what), "%s refined %" PetscInt_FMT " times (-dm_refine)", msh, refine));
    PetscCall(SSStarCheckMemory(comm, RefinedNodes(m.NV, NC, refine), what));
  }
  m.nc = SSStarSliceStart(rank + 1, NC, size) - SSStarSliceStart(rank, NC, size);
  m.v0 = SSStarSliceStart(rank, m.NV, size);
  m.nv = SSStarSliceStart(rank + 1, m.NV, size) - m.v0;
  PetscCall(PetscMalloc2(4 * m.nc + 1, &m.cells, m.nc + 1, &m.cellGroups));
  PetscCall(PetscMalloc1(3 * m.nv + 1, &m.coords));
  PetscCall(ReadRows(file, "cells", H5T_NATIVE_PETSCINT, SSStarSliceStart(rank, NC, size), m.nc, 4, m.cells));
  PetscCall(ReadRows(file, "vertices", H5T_NATIVE_DOUBLE, m.v0, m.nv, 3, m.coords));
  PetscCall(ReadRows(file, "cell_groups", H5T_NATIVE_LLONG, SSStarSliceStart(rank, NC, size), m.nc, 1, m.cellGroups));
  PetscCall(ReadTriangles(comm, file, &groups, &m.ntri, &m.tri));
  PetscCallH5(H5Fclose(file));
  for (PetscInt k = 0; k < refine; k++) PetscCall(SSStarMeshRefine(comm, &m));
  for (PetscInt c = 0; c < m.nc; c++) PetscCall(DMPlexInvertCell(DM_POLYTOPE_TETRAHEDRON, &m.cells[4 * c])); /* gmsh's orientation to DMPlex's */
  PetscCall(DMPlexCreateFromCellListParallelPetsc(comm, 3, m.nc, m.nv, m.NV, 4, PETSC_FALSE, m.cells, 3, m.coords, &vsf, NULL, &dm0));
  PetscCall(GlobalVertexNumbers(comm, vsf, m.NV, &vadj)); /* (3.18 writes its verticesAdj through a NULL pointer) */
  PetscCall(PetscSFDestroy(&vsf));
  PetscCall(PetscFree(m.coords));
  PetscCall(PetscLogEventBegin(SSSTAR_MeshFaces, 0, 0, 0, 0));
  PetscCall(SSStarMeshAddFaces(dm0, vadj, dm));
  PetscCall(PetscLogEventEnd(SSSTAR_MeshFaces, 0, 0, 0, 0));
  PetscCall(DMDestroy(&dm0));
  PetscCall(PetscLogEventEnd(SSSTAR_MeshBuild, 0, 0, 0, 0));

  /* the volume groups on the local cells, the surface groups on their faces */
  PetscCall(PetscLogEventBegin(SSSTAR_MeshLabel, 0, 0, 0, 0));
  for (PetscInt k = 0, bit = 0; k < groups.n; k++) {
    PetscCall(DMCreateLabel(*dm, groups.names[k]));
    if (groups.dims[k] != 3) continue;
    for (PetscInt c = 0; c < m.nc; c++)
      if (m.cellGroups[c] & (1LL << bit)) PetscCall(DMSetLabelValue(*dm, groups.names[k], c, (PetscInt)groups.tags[k]));
    bit++;
  }
  PetscCall(PetscFree2(m.cells, m.cellGroups));
  PetscCall(LabelFaces(comm, msh, &groups, *dm, vadj, m.ntri, m.tri));
  for (PetscInt u = 0; u < n; u++) {
    DMLabel label;

    PetscCall(DMGetLabel(*dm, uses[u].group, &label));
    PetscCall(DMPlexLabelComplete(*dm, label));
  }
  PetscCall(PetscLogEventEnd(SSSTAR_MeshLabel, 0, 0, 0, 0));
  /* tags: the file index of each local vertex */
  {
    PetscInt vStart, vEnd;

    PetscCall(DMPlexGetDepthStratum(*dm, 0, &vStart, &vEnd));
    PetscCall(VecCreateSeq(PETSC_COMM_SELF, vEnd - vStart, tags));
    PetscCall(VecGetArrayWrite(*tags, &ta));
    for (PetscInt v = 0; v < vEnd - vStart; v++) ta[v] = vadj[v];
    PetscCall(VecRestoreArrayWrite(*tags, &ta));
  }
  PetscCall(PetscFree(vadj));
  PetscCall(PetscFree3(groups.names, groups.dims, groups.tags));
  PetscFunctionReturn(0);
}
