/* gmsh meshes on DMPlex: generation from a .geo at a level, checks of a mesh file, reading, groups, distribution, dofs. */
#include "../sceneimpl.h"
#include <petscsf.h>
#include <stdio.h>
#include <unistd.h>
#include <sys/stat.h>
#if defined(__GLIBC__)
  #include <malloc.h>
#endif
#include "../../sys/gmshlib.h"

/* gmsh session on rank 0 with geo read at the level (the number L set before reading) */
static void GmshOpen(const char geo[], PetscInt level, int *ierr)
{
  char  lvl[32];
  char *argv[] = {(char *)"ssstar", (char *)"-setnumber", (char *)"L", lvl};

  snprintf(lvl, sizeof(lvl), "%" PetscInt_FMT, level);
  gmshInitialize(4, argv, 0, ierr);
  if (!*ierr) gmshOptionSetNumber("General.Verbosity", 1, ierr);
  if (!*ierr) gmshOpen(geo, ierr);
}

/*@C
   SSStarMeshGenerate - meshes a .geo file at a level with the gmsh C API on rank 0 and writes the mesh file

   Collective

   Input Parameters:
+  comm  - the ranks
.  geo   - the geometry, read with the number L set to level (such as meshes/prism.geo)
.  level - the level, >= 1
-  msh   - the mesh file to write (binary format 4.1; written to a temporary name and renamed)

   Notes:
   A .geo may declare the node count of a level with SetNumber("ssstar/nodes", <formula of L>); the level is then
   refused before meshing when the memory it would need exceeds the machine's (SSStarCheckMemory()).

   A mesh file newer than the geometry is the geometry's mesh already: it is kept (gmsh meshes the whole body on one
   process; at level 40 of the prism that took a few seconds and a rank-0 peak of several GB, every run), and the gmsh
   library is not even opened (the scene checks the memory by the mesh file's node count, SSStarMeshFileNodes()).

   Level: intermediate

.seealso: `SSStarMeshFileNodes()`, `SSStarSceneSetUp()`
@*/
PetscErrorCode SSStarMeshGenerate(MPI_Comm comm, const char geo[], PetscInt level, const char msh[])
{
  PetscMPIInt rank, failure = 0, current = 0;
  PetscBool   exists;
  PetscReal   nodes = 0;
  int         ierr  = 0;

  PetscFunctionBegin;
  PetscCheck(level >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "-level %" PetscInt_FMT ": the mesh level must be >= 1", level);
  PetscCall(PetscTestFile(geo, 'r', &exists));
  PetscCheck(exists, comm, PETSC_ERR_FILE_OPEN, "Cannot read the geometry file %s (option -geo)", geo);
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) { /* a mesh file made from the geometry as it is now: kept, and gmsh not even loaded */
    struct stat g, m;

    current = (PetscMPIInt)(!stat(geo, &g) && !stat(msh, &m) && (m.st_mtim.tv_sec > g.st_mtim.tv_sec || (m.st_mtim.tv_sec == g.st_mtim.tv_sec && m.st_mtim.tv_nsec >= g.st_mtim.tv_nsec)));
  }
  PetscCallMPI(MPI_Bcast(&current, 1, MPI_INT, 0, comm));
  if (current) PetscFunctionReturn(0);
  if (rank == 0) {
    ierr = SSStarGmshLoad();
    failure = ierr ? 3 : 0;
    if (!ierr) {
      GmshOpen(geo, level, &ierr);
      if (!ierr) {
        double *value = NULL;
        size_t  n     = 0;

        gmshOnelabGetNumber("ssstar/nodes", &value, &n, &ierr);
        if (!ierr && n == 1) nodes = value[0];
        gmshFree(value);
      }
      failure = ierr ? 1 : 0;
      gmshFinalize(&ierr);
    }
  }
  PetscCallMPI(MPI_Bcast(&failure, 1, MPI_INT, 0, comm));
  PetscCheck(failure != 3, comm, PETSC_ERR_LIB, "Cannot open the gmsh library %s to mesh %s (option -geo)", SSSTAR_GMSH_SONAME, geo);
  PetscCheck(!failure, comm, PETSC_ERR_LIB, "gmsh cannot read %s (option -geo)", geo);
  PetscCallMPI(MPI_Bcast(&nodes, 1, MPIU_REAL, 0, comm));
  if (nodes > 0) {
    char what[PETSC_MAX_PATH_LEN + 64];

    PetscCall(PetscSNPrintf(what, sizeof(what), "-level %" PetscInt_FMT " of %s", level, geo));
    PetscCall(SSStarCheckMemory(comm, nodes, what));
  }
  PetscCall(PetscLogEventBegin(SSSTAR_MeshGmsh, 0, 0, 0, 0));
  if (rank == 0) {
    char tmp[PETSC_MAX_PATH_LEN];

    GmshOpen(geo, level, &ierr);
    if (!ierr) gmshModelMeshGenerate(3, &ierr);
    if (!ierr) gmshOptionSetNumber("Mesh.MshFileVersion", 4.1, &ierr);
    if (!ierr) gmshOptionSetNumber("Mesh.Binary", 1, &ierr); /* a third of the text's time to write and read, and exact */
    /* write, then rename: a concurrent run never reads half a file */
    PetscCall(PetscSNPrintf(tmp, sizeof(tmp), "%s.%d.msh", msh, (int)getpid()));
    if (!ierr) gmshWrite(tmp, &ierr);
    failure = ierr ? 1 : (rename(tmp, msh) ? 2 : 0);
    if (!failure) PetscCall(SSStarMeshCacheFromModel(msh));
    gmshFinalize(&ierr);
#if defined(__GLIBC__)
    /* the heap gmsh freed back to the system: else it stays resident through the run, and the memory estimate, which
       starts from what the rank holds, counted it (level 14 meshed in the run: 0.452 GB estimated, 0.341 from the cache) */
    malloc_trim(0);
#endif
  }
  /* every rank raises the error, so that none waits for rank 0 */
  PetscCallMPI(MPI_Bcast(&failure, 1, MPI_INT, 0, comm));
  PetscCall(PetscLogEventEnd(SSSTAR_MeshGmsh, 0, 0, 0, 0));
  PetscCheck(failure != 1, comm, PETSC_ERR_LIB, "gmsh failed to mesh %s at level %" PetscInt_FMT, geo, level);
  PetscCheck(failure != 2, comm, PETSC_ERR_FILE_WRITE, "Cannot write the mesh file %s", msh);
  PetscFunctionReturn(0);
}

typedef enum {
  MESH_FILE_OK,
  MESH_FILE_MISSING,
  MESH_FILE_EMPTY,
  MESH_FILE_NOT_GMSH,
  MESH_FILE_VERSION,
  MESH_FILE_NO_NODES,
  MESH_FILE_TAGS
} MeshFileStatus;

/* The dimension of a gmsh element type (0 for the types a scene does not use) */
static int ElementDimension(int type)
{
  switch (type) {
  case 2:
  case 3:
  case 9:
  case 10:
    return 2;
  case 4:
  case 5:
  case 6:
  case 7:
  case 11:
    return 3;
  default:
    return 0;
  }
}

/*
   PETSc 3.18 reads both tags of an msh 2.2 element (physical, elementary) as physical groups: an element whose
   elementary tag is the tag of another physical group of its dimension would land in that group too. Finds the first
   such element of an ASCII msh 2.2 file (elementary tag *tag, dimension *dim); *tag = -1 when there is none.
*/
static void FindTagCollision(FILE *fp, int *dim, int *tag)
{
  char line[1024];
  int  phys[2][4096], nphys[2] = {0, 0};

  *tag = -1;
  while (fgets(line, sizeof(line), fp)) {
    if (!strncmp(line, "$PhysicalNames", 14)) {
      int n = 0;

      if (!fgets(line, sizeof(line), fp) || sscanf(line, "%d", &n) != 1) return;
      for (int i = 0; i < n && fgets(line, sizeof(line), fp); i++) {
        int d, t;

        if (sscanf(line, "%d %d", &d, &t) == 2 && d >= 2 && d <= 3 && nphys[d - 2] < 4096) phys[d - 2][nphys[d - 2]++] = t;
      }
    }
    if (!strncmp(line, "$Elements", 9)) {
      long n = 0;

      if (!fgets(line, sizeof(line), fp) || sscanf(line, "%ld", &n) != 1) return;
      for (long e = 0; e < n && fgets(line, sizeof(line), fp); e++) {
        int id, type, ntags, physical, elementary, d;

        if (sscanf(line, "%d %d %d %d %d", &id, &type, &ntags, &physical, &elementary) != 5 || ntags < 2 || elementary == physical) continue;
        d = ElementDimension(type);
        if (!d) continue;
        for (int i = 0; i < nphys[d - 2]; i++)
          if (phys[d - 2][i] == elementary) {
            *dim = d;
            *tag = elementary;
            return;
          }
      }
      return;
    }
  }
}

/* The node count from the header of the $Nodes section (msh 2.2 and 4.1, ASCII or binary), and the tag check of msh 2.2 */
static MeshFileStatus ReadNodeCount(const char file[], double *version, PetscInt *nodes, int *dim, int *tag)
{
  FILE          *fp = fopen(file, "rb");
  char           line[1024];
  int            binary = 0, size = 0;
  MeshFileStatus status = MESH_FILE_NO_NODES;

  *nodes = 0;
  if (!fp) return MESH_FILE_MISSING;
  if (!fgets(line, sizeof(line), fp)) status = MESH_FILE_EMPTY;
  else if (strncmp(line, "$MeshFormat", 11)) status = MESH_FILE_NOT_GMSH;
  else if (!fgets(line, sizeof(line), fp) || sscanf(line, "%lf %d %d", version, &binary, &size) != 3 || (*version != 2.2 && (*version < 4.0 || *version >= 5.0))) status = MESH_FILE_VERSION;
  else {
    while (fgets(line, sizeof(line), fp)) {
      if (strncmp(line, "$Nodes", 6)) continue;
      if (*version >= 4.0 && binary) {
        size_t header[2];

        if (fread(header, sizeof(size_t), 2, fp) == 2) *nodes = (PetscInt)header[1];
      } else if (fgets(line, sizeof(line), fp)) {
        long long blocks, count;

        if (*version >= 4.0 && sscanf(line, "%lld %lld", &blocks, &count) == 2) *nodes = (PetscInt)count;
        else if (*version < 4.0 && sscanf(line, "%lld", &count) == 1) *nodes = (PetscInt)count;
      }
      if (*nodes > 0) status = MESH_FILE_OK;
      break;
    }
  }
  if (status == MESH_FILE_OK && *version < 4.0 && !binary) {
    rewind(fp);
    FindTagCollision(fp, dim, tag);
    if (*tag >= 0) status = MESH_FILE_TAGS;
  }
  fclose(fp);
  return status;
}

/*@C
   SSStarMeshFileNodes - the number of nodes of a gmsh mesh file from its header, with an error naming the file when
   it is missing, empty, not a gmsh mesh, without nodes, or an msh 2.2 file whose elementary tags PETSc would take for
   physical groups

   Collective

   Input Parameters:
+  comm - the ranks (rank 0 reads the file)
-  file - the gmsh mesh (format 2.2 or 4.x)

   Output Parameter:
.  nodes - its node count, on every rank

   Level: intermediate

.seealso: `SSStarMeshGenerate()`, `SSStarCheckMemory()`
@*/
PetscErrorCode SSStarMeshFileNodes(MPI_Comm comm, const char file[], PetscInt *nodes)
{
  PetscMPIInt rank;
  int         status = MESH_FILE_OK, tagdim[2] = {0, -1};
  double      version = 0;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) status = (int)ReadNodeCount(file, &version, nodes, &tagdim[0], &tagdim[1]);
  PetscCallMPI(MPI_Bcast(tagdim, 2, MPI_INT, 0, comm));
  PetscCallMPI(MPI_Bcast(&status, 1, MPI_INT, 0, comm));
  PetscCallMPI(MPI_Bcast(nodes, 1, MPIU_INT, 0, comm));
  PetscCallMPI(MPI_Bcast(&version, 1, MPI_DOUBLE, 0, comm));
  PetscCheck(status != MESH_FILE_MISSING, comm, PETSC_ERR_FILE_OPEN, "Cannot read the mesh file %s", file);
  PetscCheck(status != MESH_FILE_EMPTY, comm, PETSC_ERR_FILE_UNEXPECTED, "The mesh file %s is empty", file);
  PetscCheck(status != MESH_FILE_NOT_GMSH, comm, PETSC_ERR_FILE_UNEXPECTED, "The mesh file %s is not a gmsh mesh (it does not start with $MeshFormat)", file);
  PetscCheck(status != MESH_FILE_VERSION, comm, PETSC_ERR_FILE_UNEXPECTED, "The mesh file %s is not in gmsh format 2.2 or 4.x", file);
  PetscCheck(status != MESH_FILE_NO_NODES, comm, PETSC_ERR_FILE_UNEXPECTED, "The mesh file %s has no nodes (no readable $Nodes section)", file);
  PetscCheck(status != MESH_FILE_TAGS, comm, PETSC_ERR_FILE_UNEXPECTED, "The msh 2.2 file %s has elements of dimension %d whose elementary tag %d is the tag of a physical group: PETSc would put them in that group too. Write it as msh 4.1 (gmsh -format msh41) or number the physical groups apart", file, tagdim[0], tagdim[1]);
  PetscFunctionReturn(0);
}

/*
   Reads a gmsh mesh through its cache (meshcache.c: every rank reads its slice, the mesh is built with its faces in
   parallel), checks the groups the scene uses. tags: a local vector (one entry per local vertex, in vertex order) with
   each vertex's index in the file's node order.
*/
PetscErrorCode SSStarMeshLoad(MPI_Comm comm, const char file[], PetscInt n, const SSStarGroupUse uses[], PetscInt refine, DM *dm, Vec *tags)
{
  PetscFunctionBegin;
  PetscCall(SSStarMeshLoadCached(comm, file, n, uses, refine, dm, tags));
  PetscCall(PetscObjectSetName((PetscObject)*dm, "mesh"));
  PetscCall(DMViewFromOptions(*dm, NULL, "-dm_view"));
  PetscFunctionReturn(0);
}

/*
   The four vertices of tetrahedron c, through the cones of two of its faces (the mesh has cells, faces and vertices:
   meshcache.c). DMPlexGetTransitiveClosure() looks up the cell type of every point of the closure in a label, which
   made every pass over the cells several times slower.
*/
PetscErrorCode SSStarMeshCellVertices(DM dm, PetscInt c, PetscInt v[4])
{
  const PetscInt *faces, *a, *b;
  PetscInt        n, na;

  PetscFunctionBeginHot;
  PetscCall(DMPlexGetConeSize(dm, c, &n));
  PetscCall(DMPlexGetCone(dm, c, &faces));
  PetscCheck(n == 4, PETSC_COMM_SELF, PETSC_ERR_SUP, "Cell %" PetscInt_FMT " is not a linear tetrahedron", c);
  PetscCall(DMPlexGetConeSize(dm, faces[0], &na));
  PetscCheck(na == 3, PETSC_COMM_SELF, PETSC_ERR_SUP, "Cell %" PetscInt_FMT " is not a tetrahedron of triangles on vertices", c);
  PetscCall(DMPlexGetCone(dm, faces[0], &a));
  PetscCall(DMPlexGetCone(dm, faces[1], &b));
  for (PetscInt k = 0; k < 3; k++) v[k] = a[k];
  for (PetscInt k = 0; k < 3; k++)
    if (b[k] != a[0] && b[k] != a[1] && b[k] != a[2]) v[3] = b[k];
  PetscFunctionReturn(0);
}

/* 3 dofs (u_x, u_y, u_z) per vertex; the vertices of the Dirichlet groups are constrained to 0. */
PetscErrorCode SSStarMeshCreateSection(DM dm, PetscInt n, char *const groups[])
{
  PetscSection   s;
  DMLabel       *labels;
  PetscInt       pStart, pEnd, vStart, vEnd;
  const PetscInt all[3] = {0, 1, 2};

  PetscFunctionBegin;
  PetscCall(PetscMalloc1(n, &labels));
  for (PetscInt g = 0; g < n; g++) PetscCall(DMGetLabel(dm, groups[g], &labels[g]));
  PetscCall(DMPlexGetChart(dm, &pStart, &pEnd));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(PetscSectionCreate(PetscObjectComm((PetscObject)dm), &s));
  PetscCall(PetscSectionSetChart(s, pStart, pEnd));
  for (PetscInt v = vStart; v < vEnd; v++) {
    PetscCall(PetscSectionSetDof(s, v, 3));
    for (PetscInt g = 0; g < n; g++) {
      PetscInt value;

      PetscCall(DMLabelGetValue(labels[g], v, &value));
      if (value >= 0) {
        PetscCall(PetscSectionSetConstraintDof(s, v, 3));
        break;
      }
    }
  }
  PetscCall(PetscSectionSetUp(s));
  for (PetscInt v = vStart; v < vEnd; v++) {
    PetscInt ncon;

    PetscCall(PetscSectionGetConstraintDof(s, v, &ncon));
    if (ncon) PetscCall(PetscSectionSetConstraintIndices(s, v, all));
  }
  PetscCall(DMSetLocalSection(dm, s));
  PetscCall(PetscSectionDestroy(&s));
  PetscCall(PetscFree(labels));
  PetscFunctionReturn(0);
}

/* Multiplies the coordinates of the mesh by s (a change of length unit, -mesh_scale) */
PetscErrorCode SSStarMeshScale(DM dm, PetscReal s)
{
  Vec coordinates;

  PetscFunctionBegin;
  PetscCheck(s > 0 && !PetscIsInfOrNanReal(s), PetscObjectComm((PetscObject)dm), PETSC_ERR_ARG_OUTOFRANGE, "-mesh_scale %g: the scale must be a positive number", (double)s);
  if (s == 1.0) PetscFunctionReturn(0);
  PetscCall(DMGetCoordinates(dm, &coordinates));
  PetscCall(VecScale(coordinates, s));
  PetscCall(DMSetCoordinates(dm, coordinates));
  PetscFunctionReturn(0);
}
