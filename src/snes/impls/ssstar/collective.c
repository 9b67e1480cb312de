/* Checks that end every rank: a local condition raised on every rank with the message of the first rank that failed */
#include <ssstar.h>

/*@C
   SSStarCheckAllRanks - raises on every rank of comm the error of a check that failed on some rank

   Collective

   Input Parameters:
+  comm    - the communicator of the collective call
.  code    - the PETSc error code to raise
-  message - what the check of this rank found wrong, or NULL or "" when it passed

   Notes:
   Every rank calls it after its local checks; if some rank's message is not empty, every rank raises code with the
   message of the lowest such rank (its rank appended when comm has several), so that no rank is left waiting in a
   collective call while another stopped. The entries of ssstar check their input this way.

   Level: developer

.seealso: `SNESSSStarSetContactNodes()`
@*/
PetscErrorCode SSStarCheckAllRanks(MPI_Comm comm, PetscErrorCode code, const char message[])
{
  PetscMPIInt rank, size, mine, first;
  char        buf[1024] = "";

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  mine = message && message[0] ? rank : size;
  PetscCallMPI(MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm));
  if (first == size) PetscFunctionReturn(0);
  if (rank == first) PetscCall(PetscStrncpy(buf, message, sizeof(buf)));
  PetscCallMPI(MPI_Bcast(buf, sizeof(buf), MPI_CHAR, first, comm));
  if (size == 1) SETERRQ(comm, code, "%s", buf);
  SETERRQ(comm, code, "%s [found on rank %d]", buf, first);
}
