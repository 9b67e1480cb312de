/* gmsh meshes on DMPlex: generation of the prism levels, reading, distribution, dofs and Dirichlet constraints. */
#include <ssstarcontact.h>
#include <petscsf.h>
#include <stdio.h>
#include <unistd.h>
#include <gmshc.h>

/*@C
   SSStarMeshGeneratePrism - meshes geo (a .geo file with a parameter L, such as meshes/prism.geo) at level L
   with the gmsh C API on rank 0 and writes msh (format 2.2)
@*/
PetscErrorCode SSStarMeshGeneratePrism(MPI_Comm comm, const char geo[], PetscInt level, const char msh[])
{
  PetscMPIInt rank, failure = 0;
  PetscBool   exists;

  PetscFunctionBegin;
  PetscCheck(level >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "-level %" PetscInt_FMT ": the mesh level must be >= 1", level);
  PetscCall(PetscTestFile(geo, 'r', &exists));
  PetscCheck(exists, comm, PETSC_ERR_FILE_OPEN, "Cannot read the geometry file %s (option -geo)", geo);
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) {
    char  lvl[32], tmp[PETSC_MAX_PATH_LEN];
    char *argv[] = {(char *)"ssstar", (char *)"-setnumber", (char *)"L", lvl};
    int   ierr   = 0;

    PetscCall(PetscSNPrintf(lvl, sizeof(lvl), "%" PetscInt_FMT, level));
    gmshInitialize(4, argv, 0, &ierr);
    if (!ierr) gmshOptionSetNumber("General.Verbosity", 1, &ierr);
    if (!ierr) gmshOpen(geo, &ierr);
    if (!ierr) gmshModelMeshGenerate(3, &ierr);
    if (!ierr) gmshOptionSetNumber("Mesh.MshFileVersion", 2.2, &ierr);
    /* write, then rename: a concurrent run never reads half a file */
    PetscCall(PetscSNPrintf(tmp, sizeof(tmp), "%s.%d.msh", msh, (int)getpid()));
    if (!ierr) gmshWrite(tmp, &ierr);
    gmshFinalize(&ierr);
    failure = ierr ? 1 : (rename(tmp, msh) ? 2 : 0);
  }
  /* every rank raises the error, so that none waits for rank 0 */
  PetscCallMPI(MPI_Bcast(&failure, 1, MPI_INT, 0, comm));
  PetscCheck(failure != 1, comm, PETSC_ERR_LIB, "gmsh failed to mesh %s at level %" PetscInt_FMT, geo, level);
  PetscCheck(failure != 2, comm, PETSC_ERR_FILE_WRITE, "Cannot write the mesh file %s", msh);
  PetscFunctionReturn(0);
}

/* The mesh is read on rank 0: check the group there, then give every rank the label. */
static PetscErrorCode CheckGroup(DM dm, const char file[], const char group[])
{
  DMLabel     label;
  PetscMPIInt has;

  PetscFunctionBegin;
  PetscCall(DMGetLabel(dm, group, &label));
  has = label ? 1 : 0;
  PetscCallMPI(MPI_Bcast(&has, 1, MPI_INT, 0, PetscObjectComm((PetscObject)dm)));
  PetscCheck(has, PetscObjectComm((PetscObject)dm), PETSC_ERR_ARG_WRONG, "Mesh %s has no physical group named \"%s\" (needs %s, %s, %s, %s)", file, group, SSSTAR_GROUP_DIRICHLET, SSSTAR_GROUP_TOP, SSSTAR_GROUP_RIGHT, SSSTAR_GROUP_CONTACT);
  if (!label) {
    PetscCall(DMCreateLabel(dm, group));
    PetscCall(DMGetLabel(dm, group, &label));
  }
  PetscCall(DMPlexLabelComplete(dm, label));
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

/* 3 dofs (u_x, u_y, u_z) per vertex; the vertices of "dirichlet" are constrained to 0. */
static PetscErrorCode CreateDisplacementSection(DM dm)
{
  PetscSection s;
  DMLabel      dirichlet;
  PetscInt     pStart, pEnd, vStart, vEnd;
  const PetscInt all[3] = {0, 1, 2};

  PetscFunctionBegin;
  PetscCall(DMGetLabel(dm, SSSTAR_GROUP_DIRICHLET, &dirichlet));
  PetscCall(DMPlexGetChart(dm, &pStart, &pEnd));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(PetscSectionCreate(PetscObjectComm((PetscObject)dm), &s));
  PetscCall(PetscSectionSetChart(s, pStart, pEnd));
  for (PetscInt v = vStart; v < vEnd; v++) {
    PetscInt value;

    PetscCall(PetscSectionSetDof(s, v, 3));
    PetscCall(DMLabelGetValue(dirichlet, v, &value));
    if (value >= 0) PetscCall(PetscSectionSetConstraintDof(s, v, 3));
  }
  PetscCall(PetscSectionSetUp(s));
  for (PetscInt v = vStart; v < vEnd; v++) {
    PetscInt ncon;

    PetscCall(PetscSectionGetConstraintDof(s, v, &ncon));
    if (ncon) PetscCall(PetscSectionSetConstraintIndices(s, v, all));
  }
  PetscCall(DMSetLocalSection(dm, s));
  PetscCall(PetscSectionDestroy(&s));
  PetscFunctionReturn(0);
}

/*@C
   SSStarMeshLoad - reads a gmsh mesh with the physical groups dirichlet, top, right and contact, distributes it,
   and sets up the displacement dofs with u = 0 on dirichlet

   Output Parameters:
+  dm   - the distributed mesh with its local section
-  tags - a local vector (one entry per local vertex, in vertex order) with each vertex's index in the file
@*/
PetscErrorCode SSStarMeshLoad(MPI_Comm comm, const char file[], DM *dm, Vec *tags)
{
  PetscBool    exists, set;
  DM           dist;
  PetscSF      migration;
  PetscSection tagSec;
  PetscPartitioner part;
  const char  *groups[] = {SSSTAR_GROUP_DIRICHLET, SSSTAR_GROUP_TOP, SSSTAR_GROUP_RIGHT, SSSTAR_GROUP_CONTACT};

  PetscFunctionBegin;
  PetscCall(PetscTestFile(file, 'r', &exists));
  PetscCheck(exists, comm, PETSC_ERR_FILE_OPEN, "Cannot read the mesh file %s", file);
  PetscCall(PetscOptionsHasName(NULL, NULL, "-dm_plex_gmsh_use_regions", &set));
  if (!set) PetscCall(PetscOptionsSetValue(NULL, "-dm_plex_gmsh_use_regions", "true"));
  PetscCall(DMPlexCreateFromFile(comm, file, "mesh", PETSC_TRUE, dm));
  for (size_t g = 0; g < PETSC_STATIC_ARRAY_LENGTH(groups); g++) PetscCall(CheckGroup(*dm, file, groups[g]));
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
  PetscCall(CreateDisplacementSection(*dm));
  PetscFunctionReturn(0);
}

/*@C
   SSStarMeshScale - multiplies the coordinates of the mesh by s (a change of length unit)
@*/
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

/*@C
   SSStarContactNodesCreate - the owned vertices of "contact" that are not in "dirichlet", with their global dofs
@*/
PetscErrorCode SSStarContactNodesCreate(DM dm, Vec tags, SSStarContactNodes *cn)
{
  DMLabel            contact, dirichlet;
  PetscSection       gsec;
  PetscInt           vStart, vEnd, rstart, rend, n = 0, *dofs;
  Vec                coordinates;
  PetscSection       csec;
  const PetscScalar *ta, *xa;
  DM                 cdm;
  Vec                global;

  PetscFunctionBegin;
  PetscCall(DMGetLabel(dm, SSSTAR_GROUP_CONTACT, &contact));
  PetscCall(DMGetLabel(dm, SSSTAR_GROUP_DIRICHLET, &dirichlet));
  PetscCall(DMGetGlobalSection(dm, &gsec));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(DMGetCoordinatesLocal(dm, &coordinates));
  PetscCall(DMGetCoordinateDM(dm, &cdm));
  PetscCall(DMGetLocalSection(cdm, &csec));
  PetscCall(PetscMalloc2(vEnd - vStart, &cn->tag, 3 * (vEnd - vStart), &cn->coords));
  PetscCall(PetscMalloc1(3 * (vEnd - vStart), &dofs));
  PetscCall(VecGetArrayRead(tags, &ta));
  PetscCall(VecGetArrayRead(coordinates, &xa));
  /* vertices in point order have increasing global offsets, so isC is sorted */
  for (PetscInt v = vStart; v < vEnd; v++) {
    PetscInt inC, inD, off, coff;

    PetscCall(DMLabelGetValue(contact, v, &inC));
    PetscCall(DMLabelGetValue(dirichlet, v, &inD));
    PetscCall(PetscSectionGetOffset(gsec, v, &off));
    if (inC < 0 || inD >= 0 || off < 0) continue;
    PetscCall(PetscSectionGetOffset(csec, v, &coff));
    cn->tag[n] = (PetscInt)PetscRealPart(ta[v - vStart]);
    for (PetscInt k = 0; k < 3; k++) {
      cn->coords[3 * n + k] = PetscRealPart(xa[coff + k]);
      dofs[3 * n + k]       = off + k;
    }
    n++;
  }
  PetscCall(VecRestoreArrayRead(coordinates, &xa));
  PetscCall(VecRestoreArrayRead(tags, &ta));
  cn->n = n;
  PetscCall(ISCreateGeneral(PetscObjectComm((PetscObject)dm), 3 * n, dofs, PETSC_OWN_POINTER, &cn->isC));
  PetscCall(DMGetGlobalVector(dm, &global));
  PetscCall(VecGetOwnershipRange(global, &rstart, &rend));
  PetscCall(DMRestoreGlobalVector(dm, &global));
  PetscCall(ISComplement(cn->isC, rstart, rend, &cn->isI));
  PetscFunctionReturn(0);
}

/*@C
   SSStarContactNodesDestroy - frees the arrays and index sets of the contact nodes
@*/
PetscErrorCode SSStarContactNodesDestroy(SSStarContactNodes *cn)
{
  PetscFunctionBegin;
  PetscCall(PetscFree2(cn->tag, cn->coords));
  PetscCall(ISDestroy(&cn->isC));
  PetscCall(ISDestroy(&cn->isI));
  cn->n = 0;
  PetscFunctionReturn(0);
}
