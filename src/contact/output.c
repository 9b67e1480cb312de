/*
   HDF5 output of a scene's solution, the same file on any number of ranks (README "Output"):

     /geometry/vertices, /fields/displacement  every mesh vertex in the mesh file's node order
     /viz/topology/cells                       the tetrahedra by their vertices' file numbers, in a canonical order
     /contact/...                              per contact node, in file order (coordinates, u, r, plane, friction, state)
     /contact_faces/...                        the contact faces' triangles and the point fields ParaView colours them by
     /scene/...                                what was simulated: mesh, material, loads, contact groups
     attributes of /                           how: versions, command line, reason, iterations, ||z||, tolerance

   and the XDMF file beside it with two grids, the mesh and the contact faces.
*/
#include "sceneimpl.h"
#include <unistd.h>
#include <petscsf.h>
#include <petscviewerhdf5.h>

#define PetscCallH5(call) \
  do { \
    if ((call) < 0) SETERRQ(PETSC_COMM_SELF, PETSC_ERR_LIB, "HDF5 failed: %s", #call); \
  } while (0)

/* ------------------------------------------------------------------------------------------------------------------
   HDF5 pieces. Groups and attributes are metadata: every rank calls with the same arguments. Datasets are written by
   rows, each rank its own consecutive rows (in rank order).
   ------------------------------------------------------------------------------------------------------------------ */

/* Opens the group path of file, creating the missing groups on the way */
static PetscErrorCode GroupOpen(hid_t file, const char path[], hid_t *group)
{
  char  part[PETSC_MAX_PATH_LEN], *save = NULL;
  hid_t parent = file, child = -1;

  PetscFunctionBegin;
  PetscCall(PetscStrncpy(part, path, sizeof(part)));
  for (char *name = strtok_r(part, "/", &save); name; name = strtok_r(NULL, "/", &save)) {
    htri_t exists = H5Lexists(parent, name, H5P_DEFAULT);

    PetscCheck(exists >= 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "HDF5 cannot look up the group %s of %s", name, path);
    child = exists ? H5Gopen2(parent, name, H5P_DEFAULT) : H5Gcreate2(parent, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    PetscCheck(child >= 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "HDF5 cannot open or create the group %s of %s", name, path);
    if (parent != file) PetscCallH5(H5Gclose(parent));
    parent = child;
  }
  *group = parent == file ? H5Gopen2(file, "/", H5P_DEFAULT) : parent;
  PetscFunctionReturn(0);
}

/* A string attribute (variable length: h5py reads it as str) */
static PetscErrorCode AttrString(hid_t obj, const char name[], const char value[])
{
  hid_t type, space, attr;

  PetscFunctionBegin;
  type = H5Tcopy(H5T_C_S1);
  PetscCallH5(H5Tset_size(type, H5T_VARIABLE));
  PetscCallH5(H5Tset_cset(type, H5T_CSET_UTF8));
  space = H5Screate(H5S_SCALAR);
  attr  = H5Acreate2(obj, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
  PetscCheck(attr >= 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "HDF5 cannot create the attribute %s", name);
  PetscCallH5(H5Awrite(attr, type, &value));
  PetscCallH5(H5Aclose(attr));
  PetscCallH5(H5Sclose(space));
  PetscCallH5(H5Tclose(type));
  PetscFunctionReturn(0);
}

/* A real (n = 1: scalar) or an array of n reals */
static PetscErrorCode AttrReals(hid_t obj, const char name[], PetscInt n, const PetscReal v[])
{
  hid_t   space, attr;
  hsize_t dim = (hsize_t)n;
  double  w[8];

  PetscFunctionBegin;
  PetscCheck(n >= 1 && n <= 8, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Attribute %s: %" PetscInt_FMT " values", name, n);
  for (PetscInt k = 0; k < n; k++) w[k] = (double)v[k];
  space = n == 1 ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &dim, NULL);
  attr  = H5Acreate2(obj, name, H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT);
  PetscCheck(attr >= 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "HDF5 cannot create the attribute %s", name);
  PetscCallH5(H5Awrite(attr, H5T_NATIVE_DOUBLE, w));
  PetscCallH5(H5Aclose(attr));
  PetscCallH5(H5Sclose(space));
  PetscFunctionReturn(0);
}

static PetscErrorCode AttrReal(hid_t obj, const char name[], PetscReal v)
{
  PetscFunctionBegin;
  PetscCall(AttrReals(obj, name, 1, &v));
  PetscFunctionReturn(0);
}

/* An integer (n = 1: scalar) or an array of n integers */
static PetscErrorCode AttrInts(hid_t obj, const char name[], PetscInt n, const PetscInt v[])
{
  hid_t     space, attr;
  hsize_t   dim = (hsize_t)n;
  long long w[SSSTAR_NUM_STATES + 1];

  PetscFunctionBegin;
  PetscCheck(n >= 1 && n <= SSSTAR_NUM_STATES + 1, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Attribute %s: %" PetscInt_FMT " values", name, n);
  for (PetscInt k = 0; k < n; k++) w[k] = (long long)v[k];
  space = n == 1 ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &dim, NULL);
  attr  = H5Acreate2(obj, name, H5T_STD_I64LE, space, H5P_DEFAULT, H5P_DEFAULT);
  PetscCheck(attr >= 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "HDF5 cannot create the attribute %s", name);
  PetscCallH5(H5Awrite(attr, H5T_NATIVE_LLONG, w));
  PetscCallH5(H5Aclose(attr));
  PetscCallH5(H5Sclose(space));
  PetscFunctionReturn(0);
}

static PetscErrorCode AttrInt(hid_t obj, const char name[], PetscInt v)
{
  PetscFunctionBegin;
  PetscCall(AttrInts(obj, name, 1, &v));
  PetscFunctionReturn(0);
}

/*
   The dataset path of rows x cols (cols = 0: a 1-d dataset of rows) from the rows of every rank: this rank's nloc rows
   follow those of the lower ranks. reals or ints holds them (the other is NULL). Collective.
*/
static PetscErrorCode WriteRows(MPI_Comm comm, hid_t file, const char path[], PetscInt nloc, PetscInt cols, const PetscReal reals[], const PetscInt ints[])
{
  PetscInt start = 0, total, width = cols ? cols : 1;
  hsize_t  dims[2], offset[2] = {0, 0}, count[2];
  hid_t    filespace, memspace, set, plist;
  void    *buf;
  int      rank = cols ? 2 : 1;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Exscan(&nloc, &start, 1, MPIU_INT, MPI_SUM, comm));
  PetscCall(MPIU_Allreduce(&nloc, &total, 1, MPIU_INT, MPI_SUM, comm));
  {
    PetscMPIInt r;

    PetscCallMPI(MPI_Comm_rank(comm, &r));
    if (!r) start = 0; /* MPI_Exscan leaves rank 0's result undefined */
  }
  dims[0]   = (hsize_t)total;
  dims[1]   = (hsize_t)width;
  offset[0] = (hsize_t)start;
  count[0]  = (hsize_t)nloc;
  count[1]  = (hsize_t)width;
  filespace = H5Screate_simple(rank, dims, NULL);
  set       = H5Dcreate2(file, path, reals ? H5T_IEEE_F64LE : H5T_STD_I32LE, filespace, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  PetscCheck(set >= 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "HDF5 cannot create the dataset %s", path);
  memspace = H5Screate_simple(rank, count, NULL);
  if (nloc) PetscCallH5(H5Sselect_hyperslab(filespace, H5S_SELECT_SET, offset, NULL, count, NULL));
  else {
    PetscCallH5(H5Sselect_none(filespace));
    PetscCallH5(H5Sselect_none(memspace));
  }
  if (reals) {
    double *w;

    PetscCall(PetscMalloc1(nloc * width + 1, &w));
    for (PetscInt i = 0; i < nloc * width; i++) w[i] = (double)reals[i];
    buf = w;
  } else {
    int *w;

    PetscCall(PetscMalloc1(nloc * width + 1, &w));
    for (PetscInt i = 0; i < nloc * width; i++) w[i] = (int)ints[i];
    buf = w;
  }
  plist = H5Pcreate(H5P_DATASET_XFER);
#if defined(H5_HAVE_PARALLEL)
  PetscCallH5(H5Pset_dxpl_mpio(plist, H5FD_MPIO_COLLECTIVE));
#endif
  PetscCallH5(H5Dwrite(set, reals ? H5T_NATIVE_DOUBLE : H5T_NATIVE_INT, memspace, filespace, plist, buf));
  PetscCall(PetscFree(buf));
  PetscCallH5(H5Pclose(plist));
  PetscCallH5(H5Sclose(memspace));
  PetscCallH5(H5Sclose(filespace));
  PetscCallH5(H5Dclose(set));
  PetscFunctionReturn(0);
}

/* An attribute on an existing dataset or group */
static PetscErrorCode ObjectAttrString(hid_t file, const char path[], const char name[], const char value[])
{
  hid_t obj;

  PetscFunctionBegin;
  obj = H5Oopen(file, path, H5P_DEFAULT);
  PetscCheck(obj >= 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "HDF5 cannot open %s", path);
  PetscCall(AttrString(obj, name, value));
  PetscCallH5(H5Oclose(obj));
  PetscFunctionReturn(0);
}

/* "a,b,c" from the first n names */
static PetscErrorCode JoinNames(PetscInt n, const char *const names[], char out[], size_t len)
{
  PetscFunctionBegin;
  out[0] = 0;
  for (PetscInt k = 0; k < n; k++) {
    if (k) PetscCall(PetscStrlcat(out, ",", len));
    PetscCall(PetscStrlcat(out, names[k], len));
  }
  PetscFunctionReturn(0);
}

/* ------------------------------------------------------------------------------------------------------------------
   The mesh in file order: vertex v of the file is row v of /geometry/vertices and /fields/displacement, on any number
   of ranks. Each rank writes the rows [start_r, start_r + n_r) of an even split of the N vertices; a vertex goes from
   the rank that owns it (the root of DMPlex's point SF) to the rank of its row.
   ------------------------------------------------------------------------------------------------------------------ */

/* ghost[p - pStart]: point p is a leaf of the point SF (another rank owns it) */
static PetscErrorCode GhostPoints(DM dm, PetscBool **ghost)
{
  PetscSF         sf;
  PetscInt        pStart, pEnd, nleaves;
  const PetscInt *ilocal;

  PetscFunctionBegin;
  PetscCall(DMPlexGetChart(dm, &pStart, &pEnd));
  PetscCall(PetscCalloc1(pEnd - pStart + 1, ghost));
  PetscCall(DMGetPointSF(dm, &sf));
  PetscCall(PetscSFGetGraph(sf, NULL, &nleaves, &ilocal, NULL));
  for (PetscInt i = 0; i < (nleaves > 0 ? nleaves : 0); i++) (*ghost)[(ilocal ? ilocal[i] : i) - pStart] = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* The even split of N rows over the ranks: rank r has rows [ranges[r], ranges[r + 1]) */
static PetscErrorCode EvenRanges(MPI_Comm comm, PetscInt N, PetscInt **ranges)
{
  PetscMPIInt size;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(PetscMalloc1(size + 1, ranges));
  for (PetscMPIInt r = 0; r <= size; r++) (*ranges)[r] = r * (N / size) + PetscMin(r, N % size);
  PetscFunctionReturn(0);
}

/*
   A field of bs values per mesh vertex (local vector local with its section sec) in file order: nat holds this rank's
   rows of the even split
*/
static PetscErrorCode VertexFieldInFileOrder(SSStarScene scene, const PetscBool ghost[], PetscInt bs, Vec local, PetscSection sec, Vec *nat)
{
  PetscInt           pStart, vStart, vEnd, *ranges;
  PetscMPIInt        rank;
  const PetscScalar *la, *ta;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(scene->comm, &rank));
  PetscCall(EvenRanges(scene->comm, scene->nodesGlobal, &ranges));
  PetscCall(VecCreateMPI(scene->comm, bs * (ranges[rank + 1] - ranges[rank]), bs * scene->nodesGlobal, nat));
  PetscCall(VecSetBlockSize(*nat, bs));
  PetscCall(PetscFree(ranges));
  PetscCall(DMPlexGetChart(scene->dm, &pStart, NULL));
  PetscCall(DMPlexGetDepthStratum(scene->dm, 0, &vStart, &vEnd));
  PetscCall(VecGetArrayRead(local, &la));
  PetscCall(VecGetArrayRead(scene->tags, &ta));
  for (PetscInt v = vStart; v < vEnd; v++) {
    PetscInt off, row = (PetscInt)PetscRealPart(ta[v - vStart]);

    if (ghost[v - pStart]) continue;
    PetscCall(PetscSectionGetOffset(sec, v, &off));
    PetscCall(VecSetValuesBlocked(*nat, 1, &row, &la[off], INSERT_VALUES));
  }
  PetscCall(VecRestoreArrayRead(scene->tags, &ta));
  PetscCall(VecRestoreArrayRead(local, &la));
  PetscCall(VecAssemblyBegin(*nat));
  PetscCall(VecAssemblyEnd(*nat));
  PetscFunctionReturn(0);
}

static PetscErrorCode WriteVec(hid_t file, const char path[], PetscInt cols, Vec v)
{
  const PetscScalar *a;
  PetscReal         *w;
  PetscInt           n;

  PetscFunctionBegin;
  PetscCall(VecGetLocalSize(v, &n));
  PetscCall(PetscMalloc1(n + 1, &w));
  PetscCall(VecGetArrayRead(v, &a));
  for (PetscInt i = 0; i < n; i++) w[i] = PetscRealPart(a[i]);
  PetscCall(VecRestoreArrayRead(v, &a));
  PetscCall(WriteRows(PetscObjectComm((PetscObject)v), file, path, n / (cols ? cols : 1), cols, w, NULL));
  PetscCall(PetscFree(w));
  PetscFunctionReturn(0);
}

/* The vertices of a tetrahedron, reordered by an even permutation (orientation kept) so that the smallest comes first
   and the smallest of the other three second: the same cell gives the same row whatever the mesh's numbering */
static void CanonicalTetrahedron(PetscInt c[4])
{
  PetscInt m = 0, t[4], k = 1;

  for (PetscInt i = 1; i < 4; i++)
    if (c[i] < c[m]) m = i;
  switch (m) { /* double transpositions bring the smallest to the front */
  case 0:
    t[0] = c[0], t[1] = c[1], t[2] = c[2], t[3] = c[3];
    break;
  case 1:
    t[0] = c[1], t[1] = c[0], t[2] = c[3], t[3] = c[2];
    break;
  case 2:
    t[0] = c[2], t[1] = c[3], t[2] = c[0], t[3] = c[1];
    break;
  default:
    t[0] = c[3], t[1] = c[2], t[2] = c[1], t[3] = c[0];
  }
  for (PetscInt i = 2; i < 4; i++)
    if (t[i] < t[k]) k = i;
  c[0] = t[0]; /* a rotation of the last three brings the smallest of them second */
  c[1] = t[k];
  c[2] = t[k == 3 ? 1 : k + 1];
  c[3] = t[k == 1 ? 3 : k - 1];
}

/* Rows of cols vertex numbers, compared by their sorted entries */
static int CompareRows(const void *a, const void *b, void *ctx)
{
  const PetscInt cols = *(const PetscInt *)ctx;
  PetscInt       x[4], y[4];

  for (PetscInt k = 0; k < cols; k++) {
    x[k] = ((const PetscInt *)a)[k];
    y[k] = ((const PetscInt *)b)[k];
  }
  PetscSortInt(cols, x);
  PetscSortInt(cols, y);
  for (PetscInt k = 0; k < cols; k++)
    if (x[k] != y[k]) return x[k] < y[k] ? -1 : 1;
  return 0;
}

/*
   The tetrahedra of the mesh as rows of 4 file vertex numbers, canonical and sorted: each cell goes to the rank whose
   even-split vertex range holds its smallest vertex, which sorts its cells; the ranks' rows in rank order are sorted.
*/
static PetscErrorCode CellsInFileOrder(SSStarScene scene, const PetscBool ghost[], PetscInt *nout, PetscInt **out)
{
  MPI_Comm           comm = scene->comm;
  PetscMPIInt        size, *scount, *sdispl, *rcount, *rdispl;
  PetscInt           pStart, cStart, cEnd, vStart, vEnd, ncells = 0, *rows, *ranges, *sorted, cols = 4, nrecv = 0;
  const PetscScalar *ta, *xa;
  DM                 cdm;
  PetscSection       csec;
  Vec                coordinates;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(EvenRanges(comm, scene->nodesGlobal, &ranges));
  PetscCall(DMPlexGetChart(scene->dm, &pStart, NULL));
  PetscCall(DMPlexGetHeightStratum(scene->dm, 0, &cStart, &cEnd));
  PetscCall(DMPlexGetDepthStratum(scene->dm, 0, &vStart, &vEnd));
  PetscCall(PetscMalloc1(4 * (cEnd - cStart) + 1, &rows));
  PetscCall(DMGetCoordinatesLocal(scene->dm, &coordinates));
  PetscCall(DMGetCoordinateDM(scene->dm, &cdm));
  PetscCall(DMGetLocalSection(cdm, &csec));
  PetscCall(VecGetArrayRead(coordinates, &xa));
  PetscCall(VecGetArrayRead(scene->tags, &ta));
  for (PetscInt c = cStart; c < cEnd; c++) {
    PetscInt  v[4], *row = &rows[4 * ncells];
    PetscReal x[4][3], e[3][3], volume;

    if (ghost[c - pStart]) continue;
    PetscCall(SSStarMeshCellVertices(scene->dm, c, v));
    for (PetscInt i = 0; i < 4; i++) {
      PetscInt off;

      PetscCall(PetscSectionGetOffset(csec, v[i], &off));
      for (PetscInt k = 0; k < 3; k++) x[i][k] = PetscRealPart(xa[off + k]);
      row[i] = (PetscInt)PetscRealPart(ta[v[i] - vStart]);
    }
    /* VTK's (and XDMF's) orientation: (x1 - x0) x (x2 - x0) . (x3 - x0) > 0 */
    for (PetscInt i = 0; i < 3; i++)
      for (PetscInt k = 0; k < 3; k++) e[i][k] = x[i + 1][k] - x[0][k];
    volume = (e[0][1] * e[1][2] - e[0][2] * e[1][1]) * e[2][0] + (e[0][2] * e[1][0] - e[0][0] * e[1][2]) * e[2][1] + (e[0][0] * e[1][1] - e[0][1] * e[1][0]) * e[2][2];
    if (volume < 0) {
      const PetscInt t = row[2];

      row[2] = row[3];
      row[3] = t;
    }
    CanonicalTetrahedron(row);
    ncells++;
  }
  PetscCall(VecRestoreArrayRead(scene->tags, &ta));
  PetscCall(VecRestoreArrayRead(coordinates, &xa));
  /* rows to the rank of their smallest vertex (rows[4 i]): sort by destination first */
  PetscCall(PetscCalloc4(size, &scount, size + 1, &sdispl, size, &rcount, size + 1, &rdispl));
  {
    PetscInt *dest, *perm, *tmp;

    PetscCall(PetscMalloc3(ncells + 1, &dest, ncells + 1, &perm, 4 * ncells + 1, &tmp));
    for (PetscInt i = 0; i < ncells; i++) {
      PetscInt r = 0;

      while (r + 1 < size && ranges[r + 1] <= rows[4 * i]) r++; /* the range [ranges[r], ranges[r + 1]) holding it */
      dest[i] = r;
      perm[i] = i;
      scount[r] += 4;
    }
    PetscCall(PetscSortIntWithArray(ncells, dest, perm));
    for (PetscInt i = 0; i < ncells; i++)
      for (PetscInt k = 0; k < 4; k++) tmp[4 * i + k] = rows[4 * perm[i] + k];
    PetscCall(PetscArraycpy(rows, tmp, 4 * ncells));
    PetscCall(PetscFree3(dest, perm, tmp));
  }
  PetscCallMPI(MPI_Alltoall(scount, 1, MPI_INT, rcount, 1, MPI_INT, comm));
  for (PetscMPIInt r = 0; r < size; r++) {
    sdispl[r + 1] = sdispl[r] + scount[r];
    rdispl[r + 1] = rdispl[r] + rcount[r];
  }
  nrecv = rdispl[size] / 4;
  PetscCall(PetscMalloc1(4 * nrecv + 1, &sorted));
  PetscCallMPI(MPI_Alltoallv(rows, scount, sdispl, MPIU_INT, sorted, rcount, rdispl, MPIU_INT, comm));
  if (nrecv > 1) PetscCall(PetscTimSort(nrecv, sorted, 4 * sizeof(PetscInt), CompareRows, &cols));
  PetscCall(PetscFree4(scount, sdispl, rcount, rdispl));
  PetscCall(PetscFree(rows));
  PetscCall(PetscFree(ranges));
  *nout = nrecv;
  *out  = sorted;
  PetscFunctionReturn(0);
}

static PetscErrorCode WriteMesh(SSStarScene scene, hid_t file, Vec u)
{
  DM           cdm;
  PetscSection csec, sec;
  Vec          coordinates, ul, nat;
  PetscBool   *ghost;
  PetscInt     ncells, *cells;
  hid_t        group;

  PetscFunctionBegin;
  PetscCall(GhostPoints(scene->dm, &ghost));
  PetscCall(GroupOpen(file, "/geometry", &group));
  PetscCallH5(H5Gclose(group));
  PetscCall(DMGetCoordinatesLocal(scene->dm, &coordinates));
  PetscCall(DMGetCoordinateDM(scene->dm, &cdm));
  PetscCall(DMGetLocalSection(cdm, &csec));
  PetscCall(VertexFieldInFileOrder(scene, ghost, 3, coordinates, csec, &nat));
  PetscCall(WriteVec(file, "/geometry/vertices", 3, nat));
  PetscCall(VecDestroy(&nat));

  /* the displacement with the held dofs (0: DMGlobalToLocal leaves the constrained dofs as they are) */
  PetscCall(GroupOpen(file, "/fields", &group));
  PetscCallH5(H5Gclose(group));
  PetscCall(DMGetLocalSection(scene->dm, &sec));
  PetscCall(DMGetLocalVector(scene->dm, &ul));
  PetscCall(VecZeroEntries(ul));
  PetscCall(DMGlobalToLocal(scene->dm, u, INSERT_VALUES, ul));
  PetscCall(VertexFieldInFileOrder(scene, ghost, 3, ul, sec, &nat));
  PetscCall(DMRestoreLocalVector(scene->dm, &ul));
  PetscCall(WriteVec(file, "/fields/displacement", 3, nat));
  PetscCall(VecDestroy(&nat));

  PetscCall(CellsInFileOrder(scene, ghost, &ncells, &cells));
  PetscCall(GroupOpen(file, "/viz/topology", &group));
  PetscCallH5(H5Gclose(group));
  PetscCall(WriteRows(scene->comm, file, "/viz/topology/cells", ncells, 4, NULL, cells));
  {
    hid_t set = H5Dopen2(file, "/viz/topology/cells", H5P_DEFAULT);

    PetscCall(AttrInt(set, "cell_dim", 3)); /* what PETSc's petsc_gen_xdmf.py reads */
    PetscCall(AttrInt(set, "cell_corners", 4));
    PetscCallH5(H5Dclose(set));
  }
  PetscCall(PetscFree(cells));
  PetscCall(PetscFree(ghost));
  PetscFunctionReturn(0);
}

/* ------------------------------------------------------------------------------------------------------------------
   Per-node fields gathered on rank 0 in file order (the contact nodes, the contact faces' vertices: few)
   ------------------------------------------------------------------------------------------------------------------ */

/* Position of each of the n local keys (file vertex numbers) among the sorted keys of all ranks; *p: their number */
static PetscErrorCode FileOrder(MPI_Comm comm, PetscInt n, const PetscInt key[], PetscInt *p, PetscInt **all, PetscInt pos[])
{
  IS              local, gathered;
  const PetscInt *keys;

  PetscFunctionBegin;
  PetscCall(ISCreateGeneral(comm, n, key, PETSC_USE_POINTER, &local));
  PetscCall(ISAllGather(local, &gathered));
  PetscCall(ISGetLocalSize(gathered, p));
  PetscCall(ISGetIndices(gathered, &keys));
  PetscCall(PetscMalloc1(*p + 1, all));
  PetscCall(PetscArraycpy(*all, keys, *p));
  PetscCall(ISRestoreIndices(gathered, &keys));
  PetscCall(PetscSortInt(*p, *all));
  for (PetscInt i = 0; i < n; i++) PetscCall(PetscFindInt(key[i], *p, *all, &pos[i]));
  PetscCall(ISDestroy(&gathered));
  PetscCall(ISDestroy(&local));
  PetscFunctionReturn(0);
}

/* The dataset path (p rows of bs values, bs = 1: 1-d) from the n local nodes at positions pos; integers if asInt */
static PetscErrorCode WriteNodeField(MPI_Comm comm, hid_t file, const char path[], PetscInt p, PetscInt n, const PetscInt pos[], PetscInt bs, const PetscReal values[], PetscBool asInt)
{
  PetscMPIInt        rank;
  Vec                v;
  const PetscScalar *a;
  PetscReal         *w;
  PetscInt          *iw;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(VecCreateMPI(comm, rank ? 0 : p * bs, p * bs, &v));
  for (PetscInt i = 0; i < n; i++)
    for (PetscInt k = 0; k < bs; k++) PetscCall(VecSetValue(v, pos[i] * bs + k, values[i * bs + k], INSERT_VALUES));
  PetscCall(VecAssemblyBegin(v));
  PetscCall(VecAssemblyEnd(v));
  PetscCall(PetscMalloc2(rank ? 1 : p * bs + 1, &w, rank ? 1 : p * bs + 1, &iw));
  PetscCall(VecGetArrayRead(v, &a));
  for (PetscInt i = 0; i < (rank ? 0 : p * bs); i++) {
    w[i]  = PetscRealPart(a[i]);
    iw[i] = (PetscInt)PetscRealPart(a[i]);
  }
  PetscCall(VecRestoreArrayRead(v, &a));
  PetscCall(WriteRows(comm, file, path, rank ? 0 : p, bs > 1 ? bs : 0, asInt ? NULL : w, asInt ? iw : NULL));
  PetscCall(PetscFree2(w, iw));
  PetscCall(VecDestroy(&v));
  PetscFunctionReturn(0);
}

/* What the solver used at each contact node: law, coefficient, bound (from the SNES when it is an ssstar) */
typedef struct {
  PetscBool          known; /* the SNES is an ssstar: the laws below are the solver's */
  SSStarFrictionLaw *law;
  PetscReal         *phi, *bound;
} NodeFriction;

static PetscErrorCode NodeFrictionGet(SSStarScene scene, SNES snes, NodeFriction *nf)
{
  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)snes, SNESSSSTAR, &nf->known));
  PetscCall(PetscMalloc3(scene->n + 1, &nf->law, scene->n + 1, &nf->phi, scene->n + 1, &nf->bound));
  if (nf->known) PetscCall(SNESSSStarGetNodeFriction(snes, scene->n, nf->law, nf->phi, nf->bound));
  else
    for (PetscInt i = 0; i < scene->n; i++) { /* the scene's own description */
      const SSStarContactGroup *cg = &scene->contact[scene->group[i]];

      nf->law[i]   = cg->law;
      nf->phi[i]   = cg->phi;
      nf->bound[i] = cg->bound;
    }
  for (PetscInt i = 0; i < scene->n; i++) {
    if (nf->law[i] != SSSTAR_FRICTION_COULOMB) nf->phi[i] = 0;
    if (nf->law[i] != SSSTAR_FRICTION_TRESCA) nf->bound[i] = 0;
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode NodeFrictionDestroy(NodeFriction *nf)
{
  PetscFunctionBegin;
  PetscCall(PetscFree3(nf->law, nf->phi, nf->bound));
  PetscFunctionReturn(0);
}

/* The datasets of /contact: per contact node, in the order of the mesh file */
static PetscErrorCode WriteContact(SSStarScene scene, hid_t file, Vec u, Vec r, const SSStarState states[], const NodeFriction *nf)
{
  MPI_Comm           comm = scene->comm;
  PetscInt           p, n = scene->n, *pos, *all;
  PetscReal         *ul, *rl, *sl, *gl, *ll;
  const PetscScalar *ua, *ra;
  Vec                uC, rC;
  char               names[1024];
  hid_t              group;

  PetscFunctionBegin;
  PetscCall(PetscMalloc5(n + 1, &pos, 3 * n + 1, &ul, 3 * n + 1, &rl, n + 1, &sl, n + 1, &gl));
  PetscCall(PetscMalloc1(n + 1, &ll));
  PetscCall(FileOrder(comm, n, scene->tag, &p, &all, pos));
  PetscCall(PetscFree(all));
  PetscCall(VecGetSubVector(u, scene->isC, &uC));
  PetscCall(VecGetSubVector(r, scene->isC, &rC));
  PetscCall(VecGetArrayRead(uC, &ua));
  PetscCall(VecGetArrayRead(rC, &ra));
  for (PetscInt i = 0; i < 3 * n; i++) {
    ul[i] = PetscRealPart(ua[i]);
    rl[i] = PetscRealPart(ra[i]);
  }
  PetscCall(VecRestoreArrayRead(rC, &ra));
  PetscCall(VecRestoreArrayRead(uC, &ua));
  PetscCall(VecRestoreSubVector(r, scene->isC, &rC));
  PetscCall(VecRestoreSubVector(u, scene->isC, &uC));
  PetscCall(GroupOpen(file, "/contact", &group));
  PetscCallH5(H5Gclose(group));
  {
    const char      *vnames[] = {"/contact/coordinates", "/contact/displacement", "/contact/reaction", "/contact/normal", "/contact/gap", "/contact/area", "/contact/friction", "/contact/slip_bound"};
    const PetscReal *values[] = {scene->coords, ul, rl, scene->normal, scene->gap, scene->area, nf->phi, nf->bound};
    const PetscInt   bs[]     = {3, 3, 3, 3, 1, 1, 1, 1};

    for (size_t k = 0; k < PETSC_STATIC_ARRAY_LENGTH(vnames); k++) {
      if (k >= 6 && !nf->known) continue; /* the friction the solver used, if it is an ssstar */
      PetscCall(WriteNodeField(comm, file, vnames[k], p, n, pos, bs[k], values[k], PETSC_FALSE));
    }
  }
  for (PetscInt i = 0; i < n; i++) {
    sl[i] = states ? (PetscReal)states[i] : -1;
    gl[i] = (PetscReal)scene->group[i];
    ll[i] = (PetscReal)nf->law[i];
  }
  PetscCall(WriteNodeField(comm, file, "/contact/state", p, n, pos, 1, sl, PETSC_TRUE));
  PetscCall(JoinNames(SSSTAR_NUM_STATES, SSStarStateNames, names, sizeof(names)));
  PetscCall(ObjectAttrString(file, "/contact/state", "names", names));
  PetscCall(WriteNodeField(comm, file, "/contact/group", p, n, pos, 1, gl, PETSC_TRUE));
  names[0] = 0;
  for (PetscInt g = 0; g < scene->nContact; g++) {
    if (g) PetscCall(PetscStrlcat(names, ",", sizeof(names)));
    PetscCall(PetscStrlcat(names, scene->contact[g].name, sizeof(names)));
    if (scene->contact[g].master[0]) { /* a pair: slave->master */
      PetscCall(PetscStrlcat(names, "->", sizeof(names)));
      PetscCall(PetscStrlcat(names, scene->contact[g].master, sizeof(names)));
    }
  }
  PetscCall(ObjectAttrString(file, "/contact/group", "names", names));
  { /* at the solution: the gap, pressure, tangential traction and slip (against the plane or the master surface) */
    PetscReal *kin[4];

    PetscCall(PetscMalloc4(n + 1, &kin[0], n + 1, &kin[1], 3 * n + 1, &kin[2], 3 * n + 1, &kin[3]));
    PetscCall(SSStarSceneContactKinematics(scene, u, r, kin[0], kin[1], kin[2], kin[3]));
    PetscCall(WriteNodeField(comm, file, "/contact/final_gap", p, n, pos, 1, kin[0], PETSC_FALSE));
    PetscCall(WriteNodeField(comm, file, "/contact/pressure", p, n, pos, 1, kin[1], PETSC_FALSE));
    PetscCall(WriteNodeField(comm, file, "/contact/traction", p, n, pos, 3, kin[2], PETSC_FALSE));
    PetscCall(WriteNodeField(comm, file, "/contact/slip", p, n, pos, 3, kin[3], PETSC_FALSE));
    PetscCall(PetscFree4(kin[0], kin[1], kin[2], kin[3]));
  }
  PetscCall(WriteNodeField(comm, file, "/contact/friction_law", p, n, pos, 1, ll, PETSC_TRUE));
  PetscCall(JoinNames(3, SSStarFrictionLaws, names, sizeof(names)));
  PetscCall(ObjectAttrString(file, "/contact/friction_law", "names", names));
  PetscCall(PetscFree5(pos, ul, rl, sl, gl));
  PetscCall(PetscFree(ll));
  PetscFunctionReturn(0);
}

/* ------------------------------------------------------------------------------------------------------------------
   The contact faces: the triangles of the contact groups on the vertices of those faces (the contact nodes and the
   held vertices among them), with the point fields ParaView colours them by
   ------------------------------------------------------------------------------------------------------------------ */

static PetscReal Dot3(const PetscReal a[3], const PetscReal b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* The first contact group whose label holds point q, or -1 */
static PetscErrorCode PointGroup(SSStarScene scene, const DMLabel labels[], PetscInt q, PetscInt *g)
{
  PetscFunctionBegin;
  *g = -1;
  for (PetscInt k = 0; k < scene->nContact && *g < 0; k++) {
    PetscInt value;

    PetscCall(DMLabelGetValue(labels[k], q, &value));
    if (value >= 0) *g = k;
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode WriteContactFaces(SSStarScene scene, hid_t file, Vec u, Vec r, const SSStarState states[], PetscInt *nvertices, PetscInt *ntriangles)
{
  MPI_Comm           comm = scene->comm;
  DM                 dm   = scene->dm, cdm;
  DMLabel           *labels;
  PetscSection       csec;
  Vec                coordinates, uC, rC;
  PetscBool         *ghost;
  PetscInt           pStart, vStart, vEnd, fStart, fEnd, nq = 0, q, *tag, *pos, *all, ntri = 0, *tri, c = 0;
  PetscReal         *x, *du, *st, *pr, *tt, *sl, *gp, *kin[4];
  const PetscScalar *ta, *xa, *ua, *ra;
  PetscMPIInt        rank, size;
  hid_t              group;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(GhostPoints(dm, &ghost));
  PetscCall(PetscMalloc1(scene->nContact, &labels));
  for (PetscInt g = 0; g < scene->nContact; g++) PetscCall(DMGetLabel(dm, scene->contact[g].name, &labels[g]));
  PetscCall(DMPlexGetChart(dm, &pStart, NULL));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(DMPlexGetHeightStratum(dm, 1, &fStart, &fEnd));
  PetscCall(DMGetCoordinatesLocal(dm, &coordinates));
  PetscCall(DMGetCoordinateDM(dm, &cdm));
  PetscCall(DMGetLocalSection(cdm, &csec));
  PetscCall(VecGetArrayRead(scene->tags, &ta));
  PetscCall(VecGetArrayRead(coordinates, &xa));
  PetscCall(VecGetSubVector(u, scene->isC, &uC));
  PetscCall(VecGetSubVector(r, scene->isC, &rC));
  PetscCall(VecGetArrayRead(uC, &ua));
  PetscCall(VecGetArrayRead(rC, &ra));

  /* the owned vertices of the contact faces; the contact nodes among them come in the scene's order (vertex order) */
  PetscCall(PetscMalloc2(vEnd - vStart + 1, &tag, vEnd - vStart + 1, &pos));
  PetscCall(PetscMalloc5(3 * (vEnd - vStart) + 1, &x, 3 * (vEnd - vStart) + 1, &du, vEnd - vStart + 1, &st, vEnd - vStart + 1, &pr, 3 * (vEnd - vStart) + 1, &tt));
  PetscCall(PetscMalloc2(3 * (vEnd - vStart) + 1, &sl, vEnd - vStart + 1, &gp));
  PetscCall(PetscMalloc4(scene->n + 1, &kin[0], scene->n + 1, &kin[1], 3 * scene->n + 1, &kin[2], 3 * scene->n + 1, &kin[3]));
  PetscCall(SSStarSceneContactKinematics(scene, u, r, kin[0], kin[1], kin[2], kin[3])); /* gap and slip: against a plane or a master surface */
  for (PetscInt v = vStart; v < vEnd; v++) {
    PetscInt  g, off;
    PetscReal xv[3];

    if (ghost[v - pStart]) continue;
    PetscCall(PointGroup(scene, labels, v, &g));
    if (g < 0) continue;
    PetscCall(PetscSectionGetOffset(csec, v, &off));
    for (PetscInt k = 0; k < 3; k++) xv[k] = PetscRealPart(xa[off + k]);
    tag[nq] = (PetscInt)PetscRealPart(ta[v - vStart]);
    for (PetscInt k = 0; k < 3; k++) x[3 * nq + k] = xv[k];
    if (c < scene->n && scene->tag[c] == tag[nq]) { /* contact node c */
      const PetscReal *n = &scene->normal[3 * c], ui[3] = {PetscRealPart(ua[3 * c]), PetscRealPart(ua[3 * c + 1]), PetscRealPart(ua[3 * c + 2])};
      const PetscReal  ri[3] = {PetscRealPart(ra[3 * c]), PetscRealPart(ra[3 * c + 1]), PetscRealPart(ra[3 * c + 2])};
      const PetscReal  rn = Dot3(ri, n), area = scene->area[c] > 0 ? scene->area[c] : 1;

      st[nq] = states ? (PetscReal)states[c] : -1;
      pr[nq] = rn / area;
      gp[nq] = kin[0][c]; /* for a plane, gap + u.n */
      for (PetscInt k = 0; k < 3; k++) {
        du[3 * nq + k] = ui[k];
        tt[3 * nq + k] = (ri[k] - rn * n[k]) / area;
        sl[3 * nq + k] = kin[3][3 * c + k]; /* for a plane, u - (u.n) n */
      }
      c++;
    } else { /* held fixed (Dirichlet) */
      PetscReal n[3];

      st[nq] = -1;
      pr[nq] = 0;
      PetscCall(SSStarObstacleGap(&scene->contact[g].obstacle, xv, 0, &gp[nq], n));
      for (PetscInt k = 0; k < 3; k++) du[3 * nq + k] = tt[3 * nq + k] = sl[3 * nq + k] = 0;
    }
    nq++;
  }
  PetscCheck(c == scene->n, PETSC_COMM_SELF, PETSC_ERR_PLIB, "%" PetscInt_FMT " of the %" PetscInt_FMT " contact nodes found on the contact faces", c, scene->n);
  PetscCall(PetscFree4(kin[0], kin[1], kin[2], kin[3]));
  PetscCall(FileOrder(comm, nq, tag, &q, &all, pos));

  /* the owned contact faces, as rows of 3 positions among the face vertices, their normal out of the body */
  PetscCall(PetscMalloc1(3 * (fEnd - fStart) + 1, &tri));
  for (PetscInt f = fStart; f < fEnd; f++) {
    PetscInt *closure = NULL, nclosure, nv = 0, g, verts[3];
    PetscReal xv[3][3], e1[3], e2[3], nrm[3];

    if (ghost[f - pStart]) continue;
    PetscCall(PointGroup(scene, labels, f, &g));
    if (g < 0) continue;
    PetscCall(DMPlexGetTransitiveClosure(dm, f, PETSC_TRUE, &nclosure, &closure));
    for (PetscInt i = 0; i < nclosure; i++) {
      const PetscInt pt = closure[2 * i];

      if (pt >= vStart && pt < vEnd && nv < 3) {
        PetscInt off;

        PetscCall(PetscSectionGetOffset(csec, pt, &off));
        for (PetscInt k = 0; k < 3; k++) xv[nv][k] = PetscRealPart(xa[off + k]);
        verts[nv++] = (PetscInt)PetscRealPart(ta[pt - vStart]);
      }
    }
    PetscCall(DMPlexRestoreTransitiveClosure(dm, f, PETSC_TRUE, &nclosure, &closure));
    PetscCheck(nv == 3, PETSC_COMM_SELF, PETSC_ERR_SUP, "Face %" PetscInt_FMT " of contact group %s has %" PetscInt_FMT " vertices, not 3", f, scene->contact[g].name, nv);
    for (PetscInt k = 0; k < 3; k++) {
      e1[k] = xv[1][k] - xv[0][k];
      e2[k] = xv[2][k] - xv[0][k];
    }
    nrm[0] = e1[1] * e2[2] - e1[2] * e2[1];
    nrm[1] = e1[2] * e2[0] - e1[0] * e2[2];
    nrm[2] = e1[0] * e2[1] - e1[1] * e2[0];
    {
      PetscReal centre[3], gap, n[3];

      for (PetscInt k = 0; k < 3; k++) centre[k] = (xv[0][k] + xv[1][k] + xv[2][k]) / 3;
      PetscCall(SSStarObstacleGap(&scene->contact[g].obstacle, centre, 0, &gap, n));
      for (PetscInt k = 0; k < 3; k++) e1[k] = n[k];
    }
    if (Dot3(nrm, e1) > 0) { /* the obstacle's normal (at the face's centre) points into the body; the face's out of it */
      const PetscInt t = verts[1];

      verts[1] = verts[2];
      verts[2] = t;
    }
    for (PetscInt k = 0; k < 3; k++) {
      PetscInt at;

      PetscCall(PetscFindInt(verts[k], q, all, &at));
      PetscCheck(at >= 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Vertex %" PetscInt_FMT " of a contact face is not among the contact faces' vertices", verts[k]);
      tri[3 * ntri + k] = at;
    }
    ntri++;
  }
  PetscCall(VecRestoreArrayRead(rC, &ra));
  PetscCall(VecRestoreArrayRead(uC, &ua));
  PetscCall(VecRestoreSubVector(r, scene->isC, &rC));
  PetscCall(VecRestoreSubVector(u, scene->isC, &uC));
  PetscCall(VecRestoreArrayRead(coordinates, &xa));
  PetscCall(VecRestoreArrayRead(scene->tags, &ta));

  PetscCall(GroupOpen(file, "/contact_faces", &group));
  PetscCallH5(H5Gclose(group));
  {
    const char      *vnames[] = {"/contact_faces/vertices", "/contact_faces/displacement", "/contact_faces/pressure", "/contact_faces/tangential_traction", "/contact_faces/slip", "/contact_faces/gap"};
    const PetscReal *values[] = {x, du, pr, tt, sl, gp};
    const PetscInt   bs[]     = {3, 3, 1, 3, 3, 1};

    for (size_t k = 0; k < PETSC_STATIC_ARRAY_LENGTH(vnames); k++) PetscCall(WriteNodeField(comm, file, vnames[k], q, nq, pos, bs[k], values[k], PETSC_FALSE));
    PetscCall(WriteNodeField(comm, file, "/contact_faces/state", q, nq, pos, 1, st, PETSC_TRUE));
  }
  /* the triangles: on rank 0, each rotated to start at its smallest vertex, sorted */
  {
    PetscMPIInt *counts, *displs, nsend = (PetscMPIInt)(3 * ntri);
    PetscInt    *alltri = NULL, total = 0, three = 3;

    PetscCall(PetscCalloc2(size, &counts, size + 1, &displs));
    PetscCallMPI(MPI_Gather(&nsend, 1, MPI_INT, counts, 1, MPI_INT, 0, comm));
    for (PetscMPIInt i = 0; i < size; i++) displs[i + 1] = displs[i] + counts[i];
    if (!rank) total = displs[size] / 3;
    PetscCall(PetscMalloc1(3 * total + 1, &alltri));
    PetscCallMPI(MPI_Gatherv(tri, nsend, MPIU_INT, alltri, counts, displs, MPIU_INT, 0, comm));
    for (PetscInt t = 0; t < total; t++) {
      PetscInt *row = &alltri[3 * t], m = row[1] < row[0] ? (row[2] < row[1] ? 2 : 1) : (row[2] < row[0] ? 2 : 0), rot[3];

      for (PetscInt k = 0; k < 3; k++) rot[k] = row[(m + k) % 3];
      for (PetscInt k = 0; k < 3; k++) row[k] = rot[k];
    }
    if (total > 1) PetscCall(PetscTimSort(total, alltri, 3 * sizeof(PetscInt), CompareRows, &three));
    PetscCall(WriteRows(comm, file, "/contact_faces/triangles", total, 3, NULL, alltri));
    PetscCallMPI(MPI_Bcast(&total, 1, MPIU_INT, 0, comm));
    *ntriangles = total;
    PetscCall(PetscFree(alltri));
    PetscCall(PetscFree2(counts, displs));
  }
  {
    char names[256];

    PetscCall(JoinNames(SSSTAR_NUM_STATES, SSStarStateNames, names, sizeof(names)));
    PetscCall(ObjectAttrString(file, "/contact_faces/state", "names", names));
  }
  *nvertices = q;
  PetscCall(PetscFree(tri));
  PetscCall(PetscFree(all));
  PetscCall(PetscFree2(sl, gp));
  PetscCall(PetscFree5(x, du, st, pr, tt));
  PetscCall(PetscFree2(tag, pos));
  PetscCall(PetscFree(labels));
  PetscCall(PetscFree(ghost));
  PetscFunctionReturn(0);
}

/* ------------------------------------------------------------------------------------------------------------------
   What was simulated (/scene) and how the run went (the attributes of /)
   ------------------------------------------------------------------------------------------------------------------ */

static PetscErrorCode WriteScene(SSStarScene scene, hid_t file, const NodeFriction *nf)
{
  hid_t group, sub;
  char  path[PETSC_MAX_PATH_LEN], list[4096];

  PetscFunctionBegin;
  PetscCall(GroupOpen(file, "/scene", &group));
  PetscCall(AttrString(group, "mesh", scene->mesh));
  PetscCall(AttrInt(group, "nodes", scene->nodesGlobal));
  PetscCall(AttrInt(group, "cells", scene->cellsGlobal));
  PetscCall(AttrReal(group, "mesh_scale", scene->meshScale));
  if (scene->hasE) PetscCall(AttrReal(group, "E", scene->E));
  if (scene->hasNu) PetscCall(AttrReal(group, "nu", scene->nu));
  if (scene->hasGravity) {
    PetscCall(AttrReals(group, "gravity", 3, scene->gravity));
    PetscCall(AttrReal(group, "density", scene->density));
  }
  PetscCall(JoinNames(scene->nDirichlet, (const char *const *)scene->dirichlet, list, sizeof(list)));
  PetscCall(AttrString(group, "dirichlet", list));
  list[0] = 0;
  for (PetscInt g = 0; g < scene->nContact; g++) {
    if (g) PetscCall(PetscStrlcat(list, ",", sizeof(list)));
    PetscCall(PetscStrlcat(list, scene->contact[g].name, sizeof(list)));
  }
  PetscCall(AttrString(group, "contact", list));
  PetscCallH5(H5Gclose(group));
  for (PetscInt m = 0; m < scene->nMaterials; m++) {
    PetscCall(PetscSNPrintf(path, sizeof(path), "/scene/material/%s", scene->materials[m].name));
    PetscCall(GroupOpen(file, path, &sub));
    PetscCall(AttrReal(sub, "E", scene->materials[m].value[0]));
    PetscCall(AttrReal(sub, "nu", scene->materials[m].value[1]));
    PetscCallH5(H5Gclose(sub));
  }
  for (PetscInt t = 0; t < scene->nTractions; t++) {
    PetscCall(PetscSNPrintf(path, sizeof(path), "/scene/traction/%s", scene->tractions[t].name));
    PetscCall(GroupOpen(file, path, &sub));
    PetscCall(AttrReals(sub, "traction", 3, scene->tractions[t].value));
    PetscCallH5(H5Gclose(sub));
  }
  for (PetscInt s = 0; s < scene->nSprings; s++) {
    PetscCall(PetscSNPrintf(path, sizeof(path), "/scene/spring/%s", scene->springs[s].name));
    PetscCall(GroupOpen(file, path, &sub));
    PetscCall(AttrReal(sub, "k", scene->springs[s].value[0]));
    PetscCallH5(H5Gclose(sub));
  }
  for (PetscInt g = 0; g < scene->nContact; g++) {
    const SSStarContactGroup *cg = &scene->contact[g];
    PetscInt                  laws[3] = {0, 0, 0}, law = -1;
    PetscReal                 range[4] = {PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL}; /* min phi, -max phi, min s, -max s */

    for (PetscInt i = 0; i < scene->n; i++) {
      if (scene->group[i] != g) continue;
      laws[nf->law[i]]++;
      if (nf->law[i] == SSSTAR_FRICTION_COULOMB) {
        range[0] = PetscMin(range[0], nf->phi[i]);
        range[1] = PetscMin(range[1], -nf->phi[i]);
      }
      if (nf->law[i] == SSSTAR_FRICTION_TRESCA) {
        range[2] = PetscMin(range[2], nf->bound[i]);
        range[3] = PetscMin(range[3], -nf->bound[i]);
      }
    }
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, laws, 3, MPIU_INT, MPI_SUM, scene->comm));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, range, 4, MPIU_REAL, MPIU_MIN, scene->comm));
    for (PetscInt k = 0; k < 3; k++)
      if (laws[k] == cg->nodes) law = k;
    PetscCall(PetscSNPrintf(path, sizeof(path), "/scene/contact/%s", cg->name));
    PetscCall(GroupOpen(file, path, &sub));
    PetscCall(AttrString(sub, "law", law >= 0 ? SSStarFrictionLaws[law] : "mixed"));
    if (nf->known && laws[SSSTAR_FRICTION_COULOMB] && range[0] == -range[1]) PetscCall(AttrReal(sub, "friction", range[0]));
    if (nf->known && laws[SSSTAR_FRICTION_TRESCA] && range[2] == -range[3]) PetscCall(AttrReal(sub, "slip_bound", range[2]));
    if (cg->master[0]) { /* a contact pair: its master surface and discretization, no obstacle */
      PetscCall(AttrString(sub, "master", cg->master));
      PetscCall(AttrString(sub, "discretization", SSStarPairDiscretizations[scene->pairMethod]));
    } else {
      const SSStarObstacle *ob = &cg->obstacle;
      char                  text[PETSC_MAX_PATH_LEN + 128];

      PetscCall(SSStarObstacleDescribe(ob, text, sizeof(text)));
      PetscCall(AttrString(sub, "obstacle", text));
      if (ob->type == SSSTAR_OBSTACLE_PLANE || ob->type == SSSTAR_OBSTACLE_CYLINDER) PetscCall(AttrReals(sub, "point", 3, ob->point));
      if (ob->type == SSSTAR_OBSTACLE_PLANE) PetscCall(AttrReals(sub, "normal", 3, ob->dir));
      if (ob->type == SSSTAR_OBSTACLE_CYLINDER) PetscCall(AttrReals(sub, "axis", 3, ob->dir));
      if (ob->type == SSSTAR_OBSTACLE_SPHERE) PetscCall(AttrReals(sub, "centre", 3, ob->point));
      if (ob->type == SSSTAR_OBSTACLE_SPHERE || ob->type == SSSTAR_OBSTACLE_CYLINDER) PetscCall(AttrReal(sub, "radius", ob->radius));
      if (ob->type == SSSTAR_OBSTACLE_MESH) PetscCall(AttrString(sub, "file", ob->file));
      if (ob->type == SSSTAR_OBSTACLE_MESH) PetscCall(AttrInt(sub, "triangles", ob->nt));
    }
    PetscCall(AttrInt(sub, "nodes", cg->nodes));
    PetscCall(AttrReal(sub, "gap_min", cg->gapMin));
    PetscCall(AttrReal(sub, "gap_max", cg->gapMax));
    PetscCallH5(H5Gclose(sub));
  }
  PetscFunctionReturn(0);
}

/* The command line as one string, each argument quoted when the shell would need it (rank 0's, on every rank) */
static PetscErrorCode CommandLine(MPI_Comm comm, char **line)
{
  int         argc;
  char      **argv;
  size_t      len = 1;
  PetscMPIInt rank;
  int         n;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(PetscGetArgs(&argc, &argv));
  for (int i = 0; i < argc; i++) len += strlen(argv[i]) + 3;
  n = (int)len;
  PetscCallMPI(MPI_Bcast(&n, 1, MPI_INT, 0, comm));
  PetscCall(PetscCalloc1(n, line));
  if (!rank)
    for (int i = 0; i < argc; i++) {
      const PetscBool quote = (PetscBool)(!argv[i][0] || strpbrk(argv[i], " \t\"'$*?;&|<>()") != NULL);

      if (i) PetscCall(PetscStrlcat(*line, " ", n));
      if (quote) PetscCall(PetscStrlcat(*line, "'", n));
      PetscCall(PetscStrlcat(*line, argv[i], n));
      if (quote) PetscCall(PetscStrlcat(*line, "'", n));
    }
  PetscCallMPI(MPI_Bcast(*line, n, MPI_CHAR, 0, comm));
  PetscFunctionReturn(0);
}

static PetscErrorCode WriteRun(SSStarScene scene, hid_t file, SNES snes)
{
  hid_t               root;
  char                version[64], *line, names[256];
  PetscInt            major, minor, subminor, release, its, maxit, maxf;
  PetscReal           norm, atol, rtol, stol;
  PetscMPIInt         size;
  SNESConvergedReason reason;
  SNESType            type;
  PetscBool           isssstar;

  PetscFunctionBegin;
  root = H5Gopen2(file, "/", H5P_DEFAULT);
  PetscCheck(root >= 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "HDF5 cannot open the root group");
  PetscCall(PetscSNPrintf(version, sizeof(version), "%d.%d.%d", SSSTAR_VERSION_MAJOR, SSSTAR_VERSION_MINOR, SSSTAR_VERSION_SUBMINOR));
  PetscCall(AttrString(root, "ssstar_version", version));
  PetscCall(PetscGetVersionNumber(&major, &minor, &subminor, &release));
  PetscCall(PetscSNPrintf(version, sizeof(version), "%" PetscInt_FMT ".%" PetscInt_FMT ".%" PetscInt_FMT, major, minor, subminor));
  PetscCall(AttrString(root, "petsc_version", version));
  PetscCall(CommandLine(scene->comm, &line));
  PetscCall(AttrString(root, "command_line", line));
  PetscCall(PetscFree(line));
  PetscCallMPI(MPI_Comm_size(scene->comm, &size));
  PetscCall(AttrInt(root, "ranks", size));

  PetscCall(SNESGetType(snes, &type));
  PetscCall(SNESGetConvergedReason(snes, &reason));
  PetscCall(SNESGetIterationNumber(snes, &its));
  PetscCall(SNESGetFunctionNorm(snes, &norm));
  PetscCall(SNESGetTolerances(snes, &atol, &rtol, &stol, &maxit, &maxf));
  PetscCall(AttrString(root, "snes_type", type ? type : ""));
  PetscCall(AttrString(root, "converged_reason", SNESConvergedReasons[reason]));
  PetscCall(AttrInt(root, "converged_reason_code", (PetscInt)reason));
  PetscCall(AttrInt(root, "iterations", its));
  PetscCall(AttrReal(root, "residual_norm", norm));
  PetscCall(AttrReal(root, "rtol", rtol));
  PetscCall(AttrReal(root, "atol", atol));
  PetscCall(AttrInt(root, "max_it", maxit));
  PetscCall(PetscObjectTypeCompare((PetscObject)snes, SNESSSSTAR, &isssstar));
  if (isssstar) {
    SSStarReason        sub;
    PetscReal           tol, gamma;
    PetscInt            counts[SSSTAR_NUM_STATES];
    SSStarReductionType rtype;

    PetscCall(SNESSSStarGetReason(snes, &sub));
    PetscCall(SNESSSStarGetTolerance(snes, &tol));
    PetscCall(SNESSSStarGetStates(snes, NULL, counts));
    PetscCall(SNESSSStarGetScaling(snes, &gamma));
    PetscCall(SNESSSStarGetReductionType(snes, &rtype));
    PetscCall(AttrString(root, "sub_reason", SSStarReasons[sub]));
    PetscCall(AttrReal(root, "tolerance", tol));
    PetscCall(AttrReal(root, "scaling", gamma));
    PetscCall(AttrString(root, "reduction", SSStarReductionTypes[rtype]));
    PetscCall(AttrInts(root, "state_counts", SSSTAR_NUM_STATES, counts));
    PetscCall(JoinNames(SSSTAR_NUM_STATES, SSStarStateNames, names, sizeof(names)));
    PetscCall(AttrString(root, "state_names", names));
  }
  PetscCallH5(H5Gclose(root));
  PetscFunctionReturn(0);
}

/* ------------------------------------------------------------------------------------------------------------------
   Files
   ------------------------------------------------------------------------------------------------------------------ */

/* The XDMF file beside an HDF5 file: x.h5 -> x.xmf */
static PetscErrorCode XDMFName(const char h5[], char xmf[], size_t size)
{
  size_t len;

  PetscFunctionBegin;
  PetscCall(PetscStrlen(h5, &len));
  PetscCall(PetscStrncpy(xmf, h5, size));
  if (len > 3 && !strcmp(h5 + len - 3, ".h5")) xmf[len - 3] = 0;
  PetscCall(PetscStrlcat(xmf, ".xmf", size));
  PetscFunctionReturn(0);
}

static PetscErrorCode XDMFAttribute(FILE *fp, const char base[], const char name[], const char path[], PetscInt rows, PetscInt cols, PetscBool isInt)
{
  char dims[64];

  PetscFunctionBegin;
  if (cols) PetscCall(PetscSNPrintf(dims, sizeof(dims), "%" PetscInt_FMT " %" PetscInt_FMT, rows, cols));
  else PetscCall(PetscSNPrintf(dims, sizeof(dims), "%" PetscInt_FMT, rows));
  PetscCall(PetscFPrintf(PETSC_COMM_SELF, fp, "   <Attribute Name=\"%s\" AttributeType=\"%s\" Center=\"Node\">\n    <DataItem Dimensions=\"%s\" NumberType=\"%s\" Precision=\"%d\" Format=\"HDF\">%s:%s</DataItem>\n   </Attribute>\n", name, cols ? "Vector" : "Scalar", dims, isInt ? "Int" : "Float", isInt ? 4 : 8, base, path));
  PetscFunctionReturn(0);
}

/*
   Writes xmf (rank 0): the grid "mesh" (tetrahedra, displacement) and, with contact, the grid "contact" (the contact
   faces' triangles with the state, pressure, tangential traction, slip, gap and displacement of their vertices), both
   naming the HDF5 file h5 without its folder (they sit side by side)
*/
static PetscErrorCode WriteXDMF(SSStarScene scene, const char h5[], const char xmf[], PetscInt nfaceVertices, PetscInt ntriangles)
{
  PetscMPIInt rank;
  const char *base;
  FILE       *fp;
  const PetscInt N = scene->nodesGlobal, C = scene->cellsGlobal;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(scene->comm, &rank));
  if (rank) PetscFunctionReturn(0);
  base = strrchr(h5, '/');
  base = base ? base + 1 : h5;
  PetscCall(PetscFOpen(PETSC_COMM_SELF, xmf, "w", &fp));
  PetscCall(PetscFPrintf(PETSC_COMM_SELF, fp, "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"2.0\">\n <Domain>\n"));
  PetscCall(PetscFPrintf(PETSC_COMM_SELF, fp,
                         "  <Grid Name=\"mesh\" GridType=\"Uniform\">\n"
                         "   <Topology TopologyType=\"Tetrahedron\" NumberOfElements=\"%" PetscInt_FMT "\">\n"
                         "    <DataItem Dimensions=\"%" PetscInt_FMT " 4\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">%s:/viz/topology/cells</DataItem>\n"
                         "   </Topology>\n"
                         "   <Geometry GeometryType=\"XYZ\">\n"
                         "    <DataItem Dimensions=\"%" PetscInt_FMT " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/geometry/vertices</DataItem>\n"
                         "   </Geometry>\n",
                         C, C, base, N, base));
  PetscCall(XDMFAttribute(fp, base, "displacement", "/fields/displacement", N, 3, PETSC_FALSE));
  PetscCall(PetscFPrintf(PETSC_COMM_SELF, fp, "  </Grid>\n"));
  if (scene->nContact) {
    const PetscInt q = nfaceVertices;

    PetscCall(PetscFPrintf(PETSC_COMM_SELF, fp,
                           "  <Grid Name=\"contact\" GridType=\"Uniform\">\n"
                           "   <Topology TopologyType=\"Triangle\" NumberOfElements=\"%" PetscInt_FMT "\">\n"
                           "    <DataItem Dimensions=\"%" PetscInt_FMT " 3\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">%s:/contact_faces/triangles</DataItem>\n"
                           "   </Topology>\n"
                           "   <Geometry GeometryType=\"XYZ\">\n"
                           "    <DataItem Dimensions=\"%" PetscInt_FMT " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/contact_faces/vertices</DataItem>\n"
                           "   </Geometry>\n",
                           ntriangles, ntriangles, base, q, base));
    PetscCall(XDMFAttribute(fp, base, "state", "/contact_faces/state", q, 0, PETSC_TRUE));
    PetscCall(XDMFAttribute(fp, base, "pressure", "/contact_faces/pressure", q, 0, PETSC_FALSE));
    PetscCall(XDMFAttribute(fp, base, "tangential_traction", "/contact_faces/tangential_traction", q, 3, PETSC_FALSE));
    PetscCall(XDMFAttribute(fp, base, "slip", "/contact_faces/slip", q, 3, PETSC_FALSE));
    PetscCall(XDMFAttribute(fp, base, "gap", "/contact_faces/gap", q, 0, PETSC_FALSE));
    PetscCall(XDMFAttribute(fp, base, "displacement", "/contact_faces/displacement", q, 3, PETSC_FALSE));
    PetscCall(PetscFPrintf(PETSC_COMM_SELF, fp, "  </Grid>\n"));
  }
  PetscCall(PetscFPrintf(PETSC_COMM_SELF, fp, " </Domain>\n</Xdmf>\n"));
  PetscCall(PetscFClose(PETSC_COMM_SELF, fp));
  PetscFunctionReturn(0);
}

/*@C
   SSStarCheckOutputFile - errors out, naming the file, when file cannot be created (its folder is missing or read-only)

   Collective

   Input Parameters:
+  comm - the ranks that will write the file
-  file - the file name

   Notes:
   The drivers call it before any work, so that a run does not end, after its solve, on a file it cannot write.

   Level: beginner

.seealso: `SSStarSceneWriteSolution()`
@*/
PetscErrorCode SSStarCheckOutputFile(MPI_Comm comm, const char file[])
{
  char      dir[PETSC_MAX_PATH_LEN];
  char     *slash;
  PetscBool ok;

  PetscFunctionBegin;
  PetscCall(PetscStrncpy(dir, file, sizeof(dir)));
  slash = strrchr(dir, '/');
  if (slash) *slash = 0;
  else PetscCall(PetscStrncpy(dir, ".", sizeof(dir)));
  PetscCall(PetscTestDirectory(dir[0] ? dir : "/", 'w', &ok));
  PetscCheck(ok, comm, PETSC_ERR_FILE_OPEN, "Cannot write %s: %s is not a writable folder", file, dir[0] ? dir : "/");
  PetscFunctionReturn(0);
}

/* Everything into the temporary files h5 and xmf, xmf naming the HDF5 file final */
static PetscErrorCode WriteFiles(SSStarScene scene, SNES snes, const char h5[], const char xmf[], const char final[], Vec u, PetscErrorCode (*extra)(PetscViewer, void *), void *ctx)
{
  PetscViewer        viewer;
  hid_t              file;
  Vec                r     = NULL;
  const SSStarState *states = NULL;
  PetscBool          isssstar;
  PetscInt           nfaceVertices = 0, ntriangles = 0;
  NodeFriction       nf;

  PetscFunctionBegin;
  PetscCall(PetscViewerHDF5Open(scene->comm, h5, FILE_MODE_WRITE, &viewer));
  PetscCall(PetscViewerHDF5GetFileId(viewer, &file));
  PetscCall(WriteMesh(scene, file, u));
  PetscCall(WriteRun(scene, file, snes));
  PetscCall(NodeFrictionGet(scene, snes, &nf));
  PetscCall(WriteScene(scene, file, &nf));
  if (scene->nContact) {
    PetscCall(PetscObjectTypeCompare((PetscObject)snes, SNESSSSTAR, &isssstar));
    if (isssstar) PetscCall(SNESSSStarGetStates(snes, &states, NULL));
    PetscCall(SNESGetFunction(snes, &r, NULL, NULL)); /* K u - b: the contact forces at the contact dofs */
    PetscCall(WriteContact(scene, file, u, r, states, &nf));
    PetscCall(WriteContactFaces(scene, file, u, r, states, &nfaceVertices, &ntriangles));
  }
  PetscCall(NodeFrictionDestroy(&nf));
  if (extra) PetscCall((*extra)(viewer, ctx));
  PetscCall(PetscViewerDestroy(&viewer));
  PetscCall(WriteXDMF(scene, final, xmf, nfaceVertices, ntriangles));
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneWriteSolution - writes the solution of a scene and what it was (HDF5), with the XDMF file beside it
   (x.h5 -> x.xmf) that ParaView opens

   Collective

   Input Parameters:
+  scene - the scene
.  snes  - the SNES that solved it (an ssstar, or any SNES for a scene without contact), after SNESSolve()
.  file  - the HDF5 file
.  u     - the displacement (a global vector of the scene's DM)
.  extra - NULL, or a function adding the caller's datasets to the open file
-  ctx   - its context

   Notes:
   The file is the same on any number of ranks: the vertices in the mesh file's node order (/geometry/vertices,
   /fields/displacement with the held nodes), the tetrahedra by their vertices' numbers in a canonical order
   (/viz/topology/cells), the contact nodes in file order (/contact: coordinates, displacement, reaction K u - b,
   normal, gap, area, friction_law, friction, slip_bound, state, group (a contact pair named slave->master), and at the
   solution final_gap, pressure, traction, slip against the plane or the master surface), the contact faces with their point fields
   (/contact_faces: vertices, triangles, state, pressure, tangential_traction, slip, gap, displacement), the scene
   (/scene: mesh, material, loads, contact groups with their laws) and, as attributes of /, the run: ssstar_version,
   petsc_version, command_line, ranks, snes_type, converged_reason, converged_reason_code, iterations, residual_norm
   (||z|| for ssstar), rtol, atol, max_it and, for ssstar, sub_reason, tolerance, scaling, reduction, state_counts,
   state_names. README "Output" lists them all.

   Both files are written to temporary names and renamed when complete: a failure leaves no file behind.

   Level: beginner

.seealso: `SSStarSceneSetContact()`, `SNESSSStarGetStates()`, `SNESSSStarGetNodeFriction()`, `SSStarCheckOutputFile()`
@*/
PetscErrorCode SSStarSceneWriteSolution(SSStarScene scene, SNES snes, const char file[], Vec u, PetscErrorCode (*extra)(PetscViewer, void *), void *ctx)
{
  char           xmf[PETSC_MAX_PATH_LEN], tmpH5[PETSC_MAX_PATH_LEN], tmpXmf[PETSC_MAX_PATH_LEN];
  int            pid = (int)getpid();
  PetscMPIInt    rank, failure = 0;
  PetscErrorCode ierr;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(SSSTAR_Output, 0, 0, 0, 0));
  PetscCall(SSStarCheckOutputFile(scene->comm, file));
  PetscCallMPI(MPI_Comm_rank(scene->comm, &rank));
  PetscCallMPI(MPI_Bcast(&pid, 1, MPI_INT, 0, scene->comm));
  PetscCall(XDMFName(file, xmf, sizeof(xmf)));
  PetscCall(PetscSNPrintf(tmpH5, sizeof(tmpH5), "%s.%d.tmp", file, pid));
  PetscCall(PetscSNPrintf(tmpXmf, sizeof(tmpXmf), "%s.%d.tmp", xmf, pid));
  ierr = WriteFiles(scene, snes, tmpH5, tmpXmf, file, u, extra, ctx);
  if (rank == 0) {
    if (ierr) {
      (void)remove(tmpH5);
      (void)remove(tmpXmf);
    } else failure = rename(tmpH5, file) || rename(tmpXmf, xmf);
  }
  PetscCall(ierr);
  PetscCallMPI(MPI_Bcast(&failure, 1, MPI_INT, 0, scene->comm));
  PetscCheck(!failure, scene->comm, PETSC_ERR_FILE_WRITE, "Cannot rename the written files to %s and %s", file, xmf);
  PetscCall(PetscLogEventEnd(SSSTAR_Output, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}
