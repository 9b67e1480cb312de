/*
   HDF5 pieces of the output (the same file on any number of ranks). Groups and attributes are metadata: every rank calls
   with the same arguments. Datasets are written by rows, each rank its own consecutive rows (in rank order).
*/
#include "outputimpl.h"

/* Opens the group path of file, creating the missing groups on the way */
PetscErrorCode SSStarH5GroupOpen(hid_t file, const char path[], hid_t *group)
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
PetscErrorCode SSStarH5AttrString(hid_t obj, const char name[], const char value[])
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
PetscErrorCode SSStarH5AttrReals(hid_t obj, const char name[], PetscInt n, const PetscReal v[])
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

PetscErrorCode SSStarH5AttrReal(hid_t obj, const char name[], PetscReal v)
{
  PetscFunctionBegin;
  PetscCall(SSStarH5AttrReals(obj, name, 1, &v));
  PetscFunctionReturn(0);
}

/* An integer (n = 1: scalar) or an array of n integers */
PetscErrorCode SSStarH5AttrInts(hid_t obj, const char name[], PetscInt n, const PetscInt v[])
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

PetscErrorCode SSStarH5AttrInt(hid_t obj, const char name[], PetscInt v)
{
  PetscFunctionBegin;
  PetscCall(SSStarH5AttrInts(obj, name, 1, &v));
  PetscFunctionReturn(0);
}

/*
   The dataset path of rows x cols (cols = 0: a 1-d dataset of rows) from the rows of every rank: this rank's nloc rows
   follow those of the lower ranks. reals or ints holds them (the other is NULL). Collective.
*/
PetscErrorCode SSStarH5WriteRows(MPI_Comm comm, hid_t file, const char path[], PetscInt nloc, PetscInt cols, const PetscReal reals[], const PetscInt ints[])
{
  PetscInt start = 0, total, width = cols ? cols : 1;
  hsize_t  dims[2], offset[2] = {0, 0}, count[2];
  hid_t    filespace, memspace, set, plist;
  void    *buf, *copy = NULL;
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
  if (reals && sizeof(PetscReal) == sizeof(double)) buf = (void *)reals; /* written as it is: no copy beside the field */
  else if (reals) {
    double *w;

    PetscCall(PetscMalloc1(nloc * width + 1, &w));
    for (PetscInt i = 0; i < nloc * width; i++) w[i] = (double)reals[i];
    buf = copy = w;
  } else if (sizeof(PetscInt) == sizeof(int)) buf = (void *)ints;
  else {
    int *w;

    PetscCall(PetscMalloc1(nloc * width + 1, &w));
    for (PetscInt i = 0; i < nloc * width; i++) w[i] = (int)ints[i];
    buf = copy = w;
  }
  plist = H5Pcreate(H5P_DATASET_XFER);
#if defined(H5_HAVE_PARALLEL)
  PetscCallH5(H5Pset_dxpl_mpio(plist, H5FD_MPIO_COLLECTIVE));
#endif
  if (!buf) buf = &start; /* no rows here: HDF5 wants a buffer all the same */
  PetscCallH5(H5Dwrite(set, reals ? H5T_NATIVE_DOUBLE : H5T_NATIVE_INT, memspace, filespace, plist, buf));
  PetscCall(PetscFree(copy));
  PetscCallH5(H5Pclose(plist));
  PetscCallH5(H5Sclose(memspace));
  PetscCallH5(H5Sclose(filespace));
  PetscCallH5(H5Dclose(set));
  PetscFunctionReturn(0);
}

/* An attribute on an existing dataset or group */
PetscErrorCode SSStarH5ObjectAttrString(hid_t file, const char path[], const char name[], const char value[])
{
  hid_t obj;

  PetscFunctionBegin;
  obj = H5Oopen(file, path, H5P_DEFAULT);
  PetscCheck(obj >= 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "HDF5 cannot open %s", path);
  PetscCall(SSStarH5AttrString(obj, name, value));
  PetscCallH5(H5Oclose(obj));
  PetscFunctionReturn(0);
}

/* "a,b,c" from the first n names */
PetscErrorCode SSStarJoinNames(PetscInt n, const char *const names[], char out[], size_t len)
{
  PetscFunctionBegin;
  out[0] = 0;
  for (PetscInt k = 0; k < n; k++) {
    if (k) PetscCall(PetscStrlcat(out, ",", len));
    PetscCall(PetscStrlcat(out, names[k], len));
  }
  PetscFunctionReturn(0);
}
