#ifndef SSSTAROUTPUTIMPL_H
#define SSSTAROUTPUTIMPL_H

/* The output's files share: HDF5 pieces (hdf5.c), the file order (fileorder.c), the contact datasets (contact.c), the
   metadata (metadata.c); output.c writes the files with them */
#include "../sceneimpl.h"
#include <petscviewerhdf5.h>

#define PetscCallH5(call) \
  do { \
    if ((call) < 0) SETERRQ(PETSC_COMM_SELF, PETSC_ERR_LIB, "HDF5 failed: %s", #call); \
  } while (0)

PETSC_INTERN PetscErrorCode SSStarH5GroupOpen(hid_t, const char[], hid_t *);
PETSC_INTERN PetscErrorCode SSStarH5AttrString(hid_t, const char[], const char[]);
PETSC_INTERN PetscErrorCode SSStarH5AttrReals(hid_t, const char[], PetscInt, const PetscReal[]);
PETSC_INTERN PetscErrorCode SSStarH5AttrReal(hid_t, const char[], PetscReal);
PETSC_INTERN PetscErrorCode SSStarH5AttrInts(hid_t, const char[], PetscInt, const PetscInt[]);
PETSC_INTERN PetscErrorCode SSStarH5AttrInt(hid_t, const char[], PetscInt);
PETSC_INTERN PetscErrorCode SSStarH5WriteRows(MPI_Comm, hid_t, const char[], PetscInt, PetscInt, const PetscReal[], const PetscInt[]);
PETSC_INTERN PetscErrorCode SSStarH5ObjectAttrString(hid_t, const char[], const char[], const char[]);
PETSC_INTERN PetscErrorCode SSStarJoinNames(PetscInt, const char *const[], char[], size_t);

PETSC_INTERN PetscErrorCode SSStarGhostPoints(DM, PetscBool **);
PETSC_INTERN int            SSStarCompareRows(const void *, const void *, void *);
PETSC_INTERN PetscErrorCode SSStarWriteMesh(SSStarScene, hid_t, Vec);
PETSC_INTERN PetscErrorCode SSStarWriteDisplacement(SSStarScene, hid_t, const char[], Vec);
PETSC_INTERN PetscErrorCode SSStarWriteVertexField(SSStarScene, hid_t, const char[], const char[], Vec);
PETSC_INTERN PetscErrorCode SSStarVertexFieldInFileOrder(SSStarScene, Vec, Vec *);
PETSC_INTERN PetscErrorCode SSStarVertexValuesInFileOrder(SSStarScene, PetscInt, const PetscScalar[], Vec *);
/* Where the local cells' values go in the file (fileorder.c): rows of /viz/topology/cells and the fields of the cells */
typedef struct {
  PetscInt     nsend;  /* the local cells this rank sends (not ghosts)                         */
  PetscInt    *send;   /* each one's local cell (from cStart), in the order they are sent        */
  PetscMPIInt *scount, *sdispl, *rcount, *rdispl; /* cells to and from each rank                 */
  PetscInt     nrows;  /* this rank's rows of the file                                           */
  PetscInt    *order;  /* the received cell at each of them                                      */
} SSStarCellOrder;
PETSC_INTERN PetscErrorCode SSStarCellOrderCreate(SSStarScene, SSStarCellOrder *, PetscInt **);
PETSC_INTERN PetscErrorCode SSStarCellOrderApply(MPI_Comm, const SSStarCellOrder *, PetscInt, const PetscReal[], PetscReal **);
PETSC_INTERN PetscErrorCode SSStarCellOrderDestroy(SSStarCellOrder *);
PETSC_INTERN PetscErrorCode SSStarWriteVec(hid_t, const char[], PetscInt, Vec);
PETSC_INTERN PetscErrorCode SSStarWriteStresses(SSStarScene, hid_t, const char[], Vec);
PETSC_INTERN PetscErrorCode SSStarFileOrder(MPI_Comm, PetscInt, const PetscInt[], PetscInt *, PetscInt **, PetscInt[]);
PETSC_INTERN PetscErrorCode SSStarWriteNodeField(MPI_Comm, hid_t, const char[], PetscInt, PetscInt, const PetscInt[], PetscInt, const PetscReal[], PetscBool);

/* What the solver used at each contact node (friction.c): the law and the parameters of the laws in use */
typedef struct {
  PetscBool          known;   /* the SNES is an ssstar: the laws and values are the solver's         */
  PetscInt           n;       /* local contact nodes                                                 */
  PetscInt          *law;     /* per node: its index in the table of laws                            */
  PetscInt           nparams; /* the parameters of the laws in use on any rank, in the table's order */
  const char       **param;   /* their names (the table's)                                           */
  PetscInt          *size;    /* their values per node: 1, or 3 for a direction                      */
  PetscReal        **value;   /* size values per node, 0 where the node's law has no such parameter  */
} SSStarNodeFriction;

PETSC_INTERN PetscErrorCode SSStarNodeFrictionGet(MPI_Comm, SNES, PetscInt, const PetscInt[], SSStarNodeFriction *);
PETSC_INTERN PetscErrorCode SSStarNodeFrictionWrite(MPI_Comm, hid_t, const char[], const SSStarNodeFriction *, PetscInt, const PetscInt[]);
PETSC_INTERN PetscErrorCode SSStarNodeFrictionDestroy(SSStarNodeFriction *);
/* The datasets of /contact (fields.c): the scene's, the frames' (the scene's, and each step's on a load path: large
   sliding measures the contact where the bodies are), those of a state (u, r, states), those of a load path's last step */
typedef enum {
  SSSTAR_FIELD_SCENE,
  SSSTAR_FIELD_FRAME,
  SSSTAR_FIELD_STATE,
  SSSTAR_FIELD_PATH
} SSStarFieldKind;
typedef struct {
  const char     *name;
  PetscInt        bs;      /* values per node: 1 or 3 */
  PetscBool       integer; /* written as integers      */
  SSStarFieldKind kind;
} SSStarContactField;
PETSC_INTERN const SSStarContactField SSStarContactFields[]; /* ends with a NULL name */
PETSC_INTERN PetscErrorCode           SSStarContactFieldValues(SSStarScene, const SSStarContactField *, Vec, Vec, const SSStarState[], PetscReal[]);

PETSC_INTERN PetscErrorCode SSStarWriteContact(SSStarScene, hid_t, const char[], Vec, Vec, const SSStarState[], const SSStarNodeFriction *);
PETSC_INTERN PetscErrorCode SSStarWriteContactFaces(SSStarScene, hid_t, const char[], PetscBool, Vec, Vec, const SSStarState[], PetscInt *, PetscInt *);
PETSC_INTERN PetscErrorCode SSStarWriteScene(SSStarScene, hid_t, const SSStarNodeFriction *);
PETSC_INTERN PetscErrorCode SSStarWriteRun(SSStarScene, hid_t, SNES);

/*
   A file written step by step along a load path (output.c: SSStarSceneOutputBegin(), SSStarSceneOutputStep(),
   SSStarSceneOutputEnd()): open on its temporary name, each step's fields written as it comes, the table of the steps
   (one row per step, the columns of SSStarSceneGetStepColumn()) kept on every rank and written at the end with the top level
*/
struct _n_SSStarSceneOutput {
  PetscViewer viewer;
  hid_t       file;
  char        final[PETSC_MAX_PATH_LEN], xmf[PETSC_MAX_PATH_LEN], tmpH5[PETSC_MAX_PATH_LEN], tmpXmf[PETSC_MAX_PATH_LEN];
  PetscInt    nsteps, maxSteps, ncols; /* the table: nsteps rows of ncols (SSStarSceneGetStepRow()) */
  PetscReal  *table;
  PetscInt    failedStep; /* the first step written whose solve did not converge (-1: none): /'s failed_step */
  PetscReal   failedTime; /* its time: /'s failed_time */
};

#endif
