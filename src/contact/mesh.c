/* gmsh meshes on DMPlex: generation from a .geo at a level, checks of a mesh file, reading, groups, distribution, dofs. */
#include "sceneimpl.h"
#include <petscsf.h>
#include <stdio.h>
#include <unistd.h>
#include <gmshc.h>

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
   SSStarMeshGenerate - meshes geo (a .geo file read with the number L set to level, such as meshes/prism.geo) with the
   gmsh C API on rank 0 and writes msh (format 4.1)

   Notes:
   A .geo may declare the node count of a level with SetNumber("ssstar/nodes", <formula of L>); the level is then
   refused before meshing when the memory it would need exceeds the machine's (SSStarCheckMemory()).
@*/
PetscErrorCode SSStarMeshGenerate(MPI_Comm comm, const char geo[], PetscInt level, const char msh[])
{
  PetscMPIInt rank, failure = 0;
  PetscBool   exists;
  PetscReal   nodes = 0;
  int         ierr  = 0;

  PetscFunctionBegin;
  PetscCheck(level >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "-level %" PetscInt_FMT ": the mesh level must be >= 1", level);
  PetscCall(PetscTestFile(geo, 'r', &exists));
  PetscCheck(exists, comm, PETSC_ERR_FILE_OPEN, "Cannot read the geometry file %s (option -geo)", geo);
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) {
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
  PetscCallMPI(MPI_Bcast(&failure, 1, MPI_INT, 0, comm));
  PetscCheck(!failure, comm, PETSC_ERR_LIB, "gmsh cannot read %s (option -geo)", geo);
  PetscCallMPI(MPI_Bcast(&nodes, 1, MPIU_REAL, 0, comm));
  if (nodes > 0) {
    char what[PETSC_MAX_PATH_LEN + 64];

    PetscCall(PetscSNPrintf(what, sizeof(what), "-level %" PetscInt_FMT " of %s", level, geo));
    PetscCall(SSStarCheckMemory(comm, nodes, 0, what));
  }
  if (rank == 0) {
    char tmp[PETSC_MAX_PATH_LEN];

    GmshOpen(geo, level, &ierr);
    if (!ierr) gmshModelMeshGenerate(3, &ierr);
    if (!ierr) gmshOptionSetNumber("Mesh.MshFileVersion", 4.1, &ierr);
    /* write, then rename: a concurrent run never reads half a file */
    PetscCall(PetscSNPrintf(tmp, sizeof(tmp), "%s.%d.msh", msh, (int)getpid()));
    if (!ierr) gmshWrite(tmp, &ierr);
    failure = ierr ? 1 : (rename(tmp, msh) ? 2 : 0);
    gmshFinalize(&ierr);
  }
  /* every rank raises the error, so that none waits for rank 0 */
  PetscCallMPI(MPI_Bcast(&failure, 1, MPI_INT, 0, comm));
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

/* DMPlex's own labels, not physical groups */
static PetscBool IsGroupLabel(const char name[])
{
  const char *internal[] = {"depth", "celltype", "marker", "Cell Sets", "Face Sets", "Vertex Sets", "ghost", "vtk"};
  PetscBool   same;

  for (size_t k = 0; k < PETSC_STATIC_ARRAY_LENGTH(internal); k++) {
    PetscStrcmp(name, internal[k], &same);
    if (same) return PETSC_FALSE;
  }
  return PETSC_TRUE;
}

/* Height of the points of a physical group before completion: 0 for a volume group, 1 for a surface group, -1 if mixed */
static PetscErrorCode GroupHeight(DM dm, DMLabel label, PetscInt *height)
{
  IS              values;
  const PetscInt *v;
  PetscInt        nv;

  PetscFunctionBegin;
  *height = -2;
  PetscCall(DMLabelGetValueIS(label, &values));
  PetscCall(ISGetLocalSize(values, &nv));
  PetscCall(ISGetIndices(values, &v));
  for (PetscInt k = 0; k < nv; k++) {
    IS              points;
    const PetscInt *p;
    PetscInt        np;

    PetscCall(DMLabelGetStratumIS(label, v[k], &points));
    if (!points) continue;
    PetscCall(ISGetLocalSize(points, &np));
    PetscCall(ISGetIndices(points, &p));
    for (PetscInt i = 0; i < np; i++) {
      PetscInt h;

      PetscCall(DMPlexGetPointHeight(dm, p[i], &h));
      *height = *height == -2 || *height == h ? h : -1;
    }
    PetscCall(ISRestoreIndices(points, &p));
    PetscCall(ISDestroy(&points));
  }
  PetscCall(ISRestoreIndices(values, &v));
  PetscCall(ISDestroy(&values));
  PetscFunctionReturn(0);
}

/*
   The mesh is read on rank 0: the groups are checked there (present, of the kind the option needs), the verdict and
   the list of the file's groups are broadcast so that every rank raises the same error, and every rank gets the labels.
*/
static PetscErrorCode CheckGroups(DM dm, const char file[], PetscInt n, const SSStarGroupUse uses[])
{
  MPI_Comm    comm = PetscObjectComm((PetscObject)dm);
  PetscMPIInt rank;
  char        available[1024] = "";
  const char *kinds[]         = {"surface or volume", "surface", "volume"};

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) {
    PetscInt nl;

    PetscCall(DMGetNumLabels(dm, &nl));
    for (PetscInt l = 0; l < nl; l++) {
      const char *name;

      PetscCall(DMGetLabelName(dm, l, &name));
      if (!IsGroupLabel(name)) continue;
      if (available[0]) PetscCall(PetscStrlcat(available, ", ", sizeof(available)));
      PetscCall(PetscStrlcat(available, name, sizeof(available)));
    }
  }
  PetscCallMPI(MPI_Bcast(available, sizeof(available), MPI_CHAR, 0, comm));
  for (PetscInt g = 0; g < n; g++) {
    DMLabel     label;
    PetscInt    height = -2;
    PetscMPIInt verdict = 0; /* 0 ok, 1 missing, 2 wrong kind */

    PetscCall(DMGetLabel(dm, uses[g].group, &label));
    if (rank == 0) {
      if (!label || !IsGroupLabel(uses[g].group)) verdict = 1;
      else {
        PetscCall(GroupHeight(dm, label, &height));
        if ((uses[g].kind == SSSTAR_GROUP_SURFACE && height != 1) || (uses[g].kind == SSSTAR_GROUP_VOLUME && height != 0) || (uses[g].kind == SSSTAR_GROUP_ANY && height != 0 && height != 1)) verdict = 2;
      }
    }
    PetscCallMPI(MPI_Bcast(&verdict, 1, MPI_INT, 0, comm));
    PetscCheck(verdict != 1, comm, PETSC_ERR_ARG_WRONG, "Mesh %s has no physical group named \"%s\" (option %s); its groups: %s", file, uses[g].group, uses[g].option, available[0] ? available : "none");
    PetscCheck(verdict != 2, comm, PETSC_ERR_ARG_WRONG, "Physical group \"%s\" of mesh %s is not a %s group, as option %s needs", uses[g].group, file, kinds[uses[g].kind], uses[g].option);
  }
  /* then every rank gets each label once, with the vertices and edges of its faces or cells */
  for (PetscInt g = 0; g < n; g++) {
    DMLabel   label;
    PetscBool seen = PETSC_FALSE;

    for (PetscInt h = 0; h < g && !seen; h++) PetscCall(PetscStrcmp(uses[g].group, uses[h].group, &seen));
    if (seen) continue;
    PetscCall(DMGetLabel(dm, uses[g].group, &label));
    if (!label) {
      PetscCall(DMCreateLabel(dm, uses[g].group));
      PetscCall(DMGetLabel(dm, uses[g].group, &label));
    }
    PetscCall(DMPlexLabelComplete(dm, label));
  }
  PetscFunctionReturn(0);
}

/* One dof per vertex holding the vertex's index in the file, so that distributed runs can restore the file order. */
static PetscErrorCode CreateVertexTags(DM dm, PetscSection *sec, Vec *tags)
{
  PetscInt     pStart, pEnd, vStart, vEnd;
  PetscScalar *a;

  PetscFunctionBegin;
  PetscCall(DMPlexGetChart(dm, &pStart, &pEnd));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(PetscSectionCreate(PetscObjectComm((PetscObject)dm), sec));
  PetscCall(PetscSectionSetChart(*sec, pStart, pEnd));
  for (PetscInt v = vStart; v < vEnd; v++) PetscCall(PetscSectionSetDof(*sec, v, 1));
  PetscCall(PetscSectionSetUp(*sec));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, vEnd - vStart, tags));
  PetscCall(VecGetArrayWrite(*tags, &a));
  for (PetscInt v = vStart; v < vEnd; v++) a[v - vStart] = v - vStart;
  PetscCall(VecRestoreArrayWrite(*tags, &a));
  PetscFunctionReturn(0);
}

/* The distributed tags are laid out by the migrated section; the caller wants them by vertex number. */
static PetscErrorCode TagsInVertexOrder(DM dm, PetscSection sec, Vec migrated, Vec *tags)
{
  PetscInt           vStart, vEnd;
  const PetscScalar *ma;
  PetscScalar       *a;

  PetscFunctionBegin;
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, vEnd - vStart, tags));
  PetscCall(VecGetArrayRead(migrated, &ma));
  PetscCall(VecGetArrayWrite(*tags, &a));
  for (PetscInt v = vStart; v < vEnd; v++) {
    PetscInt off;

    PetscCall(PetscSectionGetOffset(sec, v, &off));
    a[v - vStart] = ma[off];
  }
  PetscCall(VecRestoreArrayWrite(*tags, &a));
  PetscCall(VecRestoreArrayRead(migrated, &ma));
  PetscFunctionReturn(0);
}

/* DMPlexCreateFromFile with its error (a corrupt file) turned into one that names the file */
static PetscErrorCode ReadMesh(MPI_Comm comm, const char file[], DM *dm)
{
  PetscErrorCode ierr;
  PetscBool      set;

  PetscFunctionBegin;
  PetscCall(PetscOptionsHasName(NULL, NULL, "-dm_plex_gmsh_use_regions", &set));
  if (!set) PetscCall(PetscOptionsSetValue(NULL, "-dm_plex_gmsh_use_regions", "true"));
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  ierr = DMPlexCreateFromFile(comm, file, "mesh", PETSC_TRUE, dm);
  PetscCall(PetscPopErrorHandler());
  if (ierr) {
    const char *text;
    char       *specific = NULL;

    PetscCall(PetscErrorMessage(ierr, &text, &specific));
    SETERRQ(comm, PETSC_ERR_FILE_UNEXPECTED, "Cannot read the mesh file %s: %s (is it a complete gmsh file?)", file, specific && specific[0] ? specific : (text ? text : "read error"));
  }
  PetscFunctionReturn(0);
}

/*
   Reads a gmsh mesh, checks the groups the scene uses and distributes it. tags: a local vector (one entry per local
   vertex, in vertex order) with each vertex's index in the file.
*/
PetscErrorCode SSStarMeshLoad(MPI_Comm comm, const char file[], PetscInt n, const SSStarGroupUse uses[], DM *dm, Vec *tags)
{
  DM               dist;
  PetscSF          migration;
  PetscSection     tagSec;
  PetscPartitioner part;

  PetscFunctionBegin;
  PetscCall(ReadMesh(comm, file, dm));
  PetscCall(CheckGroups(*dm, file, n, uses));
  PetscCall(CreateVertexTags(*dm, &tagSec, tags));

  PetscCall(DMPlexGetPartitioner(*dm, &part));
  PetscCall(PetscPartitionerSetFromOptions(part));
  PetscCall(DMPlexDistribute(*dm, 0, &migration, &dist));
  if (dist) {
    PetscSection newSec;
    Vec          newTags;

    PetscCall(PetscSectionCreate(comm, &newSec));
    PetscCall(VecCreate(PETSC_COMM_SELF, &newTags));
    PetscCall(DMPlexDistributeField(*dm, migration, tagSec, *tags, newSec, newTags));
    PetscCall(VecDestroy(tags));
    PetscCall(DMDestroy(dm));
    *dm = dist;
    PetscCall(TagsInVertexOrder(*dm, newSec, newTags, tags));
    PetscCall(PetscSectionDestroy(&newSec));
    PetscCall(VecDestroy(&newTags));
  }
  PetscCall(PetscSFDestroy(&migration));
  PetscCall(PetscSectionDestroy(&tagSec));
  PetscCall(PetscObjectSetName((PetscObject)*dm, "mesh"));
  PetscCall(DMViewFromOptions(*dm, NULL, "-dm_view"));
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
