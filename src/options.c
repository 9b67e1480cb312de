/*
   What ssstar's programs promise a scripted user (docs/guide/scripting.md): an option that nobody
   read is refused before any work, naming it and the nearest option the program knows; a solve that did not converge
   ends with the exit status SSSTAR_EXIT_NOT_CONVERGED, and the file it writes says so.
*/
#include <ctype.h>
#include <stdlib.h>
#include <strings.h>
#include <unistd.h>
#include <petsc/private/petscimpl.h>
#include <ssstar.h>
#include <petscviewerhdf5.h>
#include "sys/names.h"

/*
   Options PETSc reads only while the work runs (objects created then: the reduction's MUMPS, the mesh, the viewers,
   the Newton step's GMRES, the factorizations), after the solve (views, reasons) or at PetscFinalize(). Prefixes,
   without the dash; none of them is checked before the work.
*/
static const char *const LateOptions[] = {"snes_view", "snes_converged_reason", "ksp_view", "ksp_converged_reason", "pc_view", "mat_", "vec_view", "dm_", "petscpartitioner_", "viewer_", "log", "options_left", "options_view", "memory_view", "malloc_", "objects_dump", "snes_ssstar_newton_ksp_", "schur_", "interior_", "initial_mat_", "pc_factor_", "pc_mg_", "mg_", "matmatmult_", "matptap_", "matproduct_"};

/* The prefix of the scratch SNES whose -help text lists the options of a SNES of the same types */
#define SSSTAR_KNOWN_PREFIX "ssstar_known_"

static PetscBool IsLate(const char name[])
{
  for (size_t k = 0; k < PETSC_STATIC_ARRAY_LENGTH(LateOptions); k++)
    if (!strncasecmp(name, LateOptions[k], strlen(LateOptions[k]))) return PETSC_TRUE;
  return PETSC_FALSE;
}

/* A growing list of option names (without the dash); "<G>" at the end marks a name followed by a group name */
typedef struct {
  PetscInt n, max;
  char   **names;
} NameList;

static PetscErrorCode NameListAdd(NameList *list, const char name[], size_t len)
{
  PetscFunctionBegin;
  for (PetscInt i = 0; i < list->n; i++)
    if (strlen(list->names[i]) == len && !strncasecmp(list->names[i], name, len)) PetscFunctionReturn(0);
  if (list->n == list->max) {
    list->max = PetscMax(64, 2 * list->max);
    PetscCall(PetscRealloc(list->max * sizeof(char *), &list->names));
  }
  PetscCall(PetscMalloc1(len + 1, &list->names[list->n]));
  PetscCall(PetscStrncpy(list->names[list->n], name, len + 1));
  list->n++;
  PetscFunctionReturn(0);
}

static PetscErrorCode NameListDestroy(NameList *list)
{
  PetscFunctionBegin;
  for (PetscInt i = 0; i < list->n; i++) PetscCall(PetscFree(list->names[i]));
  PetscCall(PetscFree(list->names));
  list->n = list->max = 0;
  PetscFunctionReturn(0);
}

static PetscBool IsNameChar(char c)
{
  return (PetscBool)(isalnum((unsigned char)c) || c == '_');
}

/* Every option named in text: "-name", "-name_<G>" (a template); with prefix, "-<prefix>name" counts as "-name" */
static PetscErrorCode AddNamesOfText(NameList *list, const char text[], const char prefix[])
{
  const size_t plen = prefix ? strlen(prefix) : 0;

  PetscFunctionBegin;
  for (const char *s = text; s && *s; s++) {
    const char *start;
    size_t      len;

    if (*s != '-' || (s > text && (IsNameChar(s[-1]) || s[-1] == '-')) || !isalpha((unsigned char)s[1])) continue;
    start = s + 1;
    if (plen && !strncmp(start, prefix, plen)) start += plen;
    for (s = start; IsNameChar(*s); s++) {}
    len = (size_t)(s - start);
    if (!strncmp(s, "<G>", 3) && len && start[len - 1] == '_') len += 3; /* -friction_<G> */
    else if (len && start[len - 1] == '_') {                             /* -snes_ssstar_*: no name */
      s--;
      continue;
    }
    if (len) PetscCall(NameListAdd(list, start, len));
    s--;
  }
  PetscFunctionReturn(0);
}

/* The options of the database that were read */
static PetscErrorCode AddUsedNames(NameList *list)
{
  char *all, *token, *save = NULL;

  PetscFunctionBegin;
  PetscCall(PetscOptionsGetAll(NULL, &all));
  for (token = strtok_r(all, " ", &save); token; token = strtok_r(NULL, " ", &save)) {
    PetscBool used;

    if (token[0] != '-' || !isalpha((unsigned char)token[1])) continue;
    PetscCall(PetscOptionsUsed(NULL, token + 1, &used));
    if (used) PetscCall(NameListAdd(list, token + 1, strlen(token + 1)));
  }
  PetscCall(PetscFree(all));
  PetscFunctionReturn(0);
}

/* The -help text a SNES of the types of snes (and of its KSP and PC) prints, collected instead of printed */
static char  *helpText    = NULL;
static size_t helpTextLen = 0, helpTextMax = 0;
static PetscErrorCode (*vfprintfSaved)(FILE *, const char[], va_list);

static PetscErrorCode CollectText(const char format[], va_list args)
{
  char   line[4096];
  size_t len;

  PetscFunctionBegin;
  PetscCall(PetscVSNPrintf(line, sizeof(line), format, &len, args));
  len = strlen(line);
  if (helpTextLen + len + 1 > helpTextMax) {
    helpTextMax = PetscMax(2 * helpTextMax, helpTextLen + len + 1 + 65536);
    PetscCall(PetscRealloc(helpTextMax, &helpText));
  }
  PetscCall(PetscMemcpy(helpText + helpTextLen, line, len + 1));
  helpTextLen += len;
  PetscFunctionReturn(0);
}

/* PetscHelpPrintf() while collecting */
static PetscErrorCode CollectHelp(MPI_Comm comm, const char format[], ...)
{
  va_list args;

  PetscFunctionBegin;
  va_start(args, format);
  PetscCall(CollectText(format, args));
  va_end(args);
  PetscFunctionReturn(0);
}

/* PetscVFPrintf() while collecting: the lists of types go to stdout directly */
static PetscErrorCode CollectStdout(FILE *fd, const char format[], va_list args)
{
  PetscFunctionBegin;
  if (fd == PETSC_STDOUT || fd == stdout) PetscCall(CollectText(format, args));
  else PetscCall((*vfprintfSaved)(fd, format, args));
  PetscFunctionReturn(0);
}

static PetscErrorCode AddNamesOfSNES(NameList *list, SNES snes)
{
  SNES      scratch;
  KSP       ksp, kspScratch;
  PC        pc, pcScratch;
  SNESType  stype;
  KSPType   ktype;
  PCType    ptype;
  PetscBool hadHelp;
  PetscErrorCode (*print)(MPI_Comm, const char[], ...) = PetscHelpPrintf;

  PetscFunctionBegin;
  PetscCall(SNESGetType(snes, &stype));
  PetscCall(SNESGetKSP(snes, &ksp));
  PetscCall(KSPGetType(ksp, &ktype));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCGetType(pc, &ptype));
  PetscCall(SNESCreate(PetscObjectComm((PetscObject)snes), &scratch));
  PetscCall(SNESSetOptionsPrefix(scratch, SSSTAR_KNOWN_PREFIX));
  if (stype) PetscCall(SNESSetType(scratch, stype));
  PetscCall(SNESGetKSP(scratch, &kspScratch));
  if (ktype) PetscCall(KSPSetType(kspScratch, ktype));
  PetscCall(KSPGetPC(kspScratch, &pcScratch));
  if (ptype) PetscCall(PCSetType(pcScratch, ptype));
  PetscCall(PetscOptionsHasHelp(NULL, &hadHelp));
  if (!hadHelp) PetscCall(PetscOptionsSetValue(NULL, "-help", NULL));
  helpTextLen     = 0;
  vfprintfSaved   = PetscVFPrintf;
  PetscHelpPrintf = CollectHelp;
  PetscVFPrintf   = CollectStdout;
  PetscCall(SNESSetFromOptions(scratch));
  PetscHelpPrintf = print;
  PetscVFPrintf   = vfprintfSaved;
  if (!hadHelp) PetscCall(PetscOptionsClearValue(NULL, "-help"));
  PetscCall(SNESDestroy(&scratch));
  if (helpText) PetscCall(AddNamesOfText(list, helpText, SSSTAR_KNOWN_PREFIX));
  PetscCall(PetscFree(helpText));
  helpTextLen = helpTextMax = 0;
  PetscFunctionReturn(0);
}

/*
   The known option nearest to name: by edit distance (a template -x_<G> matches -x_ followed by any group name: the
   name's own, after one of its underscores); else a known option that ends with _name (-friction:
   -snes_ssstar_friction). Empty when none is near.
*/
static PetscErrorCode Nearest(const NameList *known, const char name[], char nearest[], size_t size)
{
  const size_t len = strlen(name);
  PetscInt     best = PETSC_MAX_INT;
  size_t       bestSuffix = 0;

  PetscFunctionBegin;
  nearest[0] = 0;
  for (PetscInt i = 0; i < known->n; i++) {
    const char  *k    = known->names[i];
    const size_t klen = strlen(k);

    if (klen > 3 && !strcmp(k + klen - 3, "<G>")) {
      for (size_t split = 1; split < len; split++) {
        PetscInt d;

        if (name[split - 1] != '_') continue; /* the group name follows an underscore */
        d = SSStarNameDistance(name, split, k, klen - 3);
        if (d < best) {
          best = d;
          PetscCall(PetscSNPrintf(nearest, size, "-%.*s%s", (int)(klen - 3), k, name + split));
        }
      }
    } else {
      const PetscInt d = SSStarNameDistance(name, len, k, klen);

      if (d < best) {
        best = d;
        PetscCall(PetscSNPrintf(nearest, size, "-%s", k));
      }
    }
  }
  if (best <= PetscMax(2, (PetscInt)len / 4)) PetscFunctionReturn(0);
  nearest[0] = 0;
  for (PetscInt i = 0; i < known->n; i++) {
    const char  *k    = known->names[i];
    const size_t klen = strlen(k);

    if (klen > len && k[klen - len - 1] == '_' && !strcasecmp(k + klen - len, name) && (!bestSuffix || klen < bestSuffix)) {
      bestSuffix = klen;
      PetscCall(PetscSNPrintf(nearest, size, "-%s", k));
    }
  }
  PetscFunctionReturn(0);
}

/* The options no rank read: rank 0's unread options that are unread on every rank too */
static PetscErrorCode UnreadOptions(MPI_Comm comm, NameList *unread)
{
  PetscMPIInt rank;
  PetscInt    len = 0;
  char       *list = NULL, *token, *save = NULL;
  PetscBool  *left;
  NameList    all = {0, 0, NULL};

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (!rank) {
    PetscInt nleft;
    char   **names, **values;

    PetscCall(PetscOptionsLeftGet(NULL, &nleft, &names, &values));
    for (PetscInt i = 0; i < nleft; i++) len += (PetscInt)strlen(names[i]) + 1;
    PetscCall(PetscCalloc1(len + 1, &list));
    len = 0;
    for (PetscInt i = 0; i < nleft; i++)
      if (!IsLate(names[i])) {
        const size_t l = strlen(names[i]);

        PetscCall(PetscMemcpy(list + len, names[i], l));
        list[len + l] = ' ';
        len += (PetscInt)l + 1;
      }
    PetscCall(PetscOptionsLeftRestore(NULL, &nleft, &names, &values));
  }
  PetscCallMPI(MPI_Bcast(&len, 1, MPIU_INT, 0, comm));
  if (rank) PetscCall(PetscCalloc1(len + 1, &list));
  PetscCallMPI(MPI_Bcast(list, (PetscMPIInt)len + 1, MPI_CHAR, 0, comm));
  for (token = strtok_r(list, " ", &save); token; token = strtok_r(NULL, " ", &save)) PetscCall(NameListAdd(&all, token, strlen(token)));
  PetscCall(PetscFree(list));
  PetscCall(PetscMalloc1(all.n, &left));
  for (PetscInt i = 0; i < all.n; i++) {
    PetscBool used;

    PetscCall(PetscOptionsUsed(NULL, all.names[i], &used));
    left[i] = (PetscBool)!used;
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, left, all.n, MPIU_BOOL, MPI_LAND, comm));
  for (PetscInt i = 0; i < all.n; i++)
    if (left[i]) PetscCall(NameListAdd(unread, all.names[i], strlen(all.names[i])));
  PetscCall(PetscFree(left));
  PetscCall(NameListDestroy(&all));
  PetscFunctionReturn(0);
}

/* The options of names (without the dash) that no rank has read */
static PetscErrorCode UnreadOptionsOf(MPI_Comm comm, PetscInt n, const char *const names[], NameList *unread)
{
  PetscBool *left;

  PetscFunctionBegin;
  PetscCall(PetscMalloc1(n + 1, &left));
  for (PetscInt i = 0; i < n; i++) {
    PetscBool used;

    PetscCall(PetscOptionsUsed(NULL, names[i], &used));
    left[i] = (PetscBool)(!used && !IsLate(names[i]));
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, left, n, MPIU_BOOL, MPI_LAND, comm));
  for (PetscInt i = 0; i < n; i++)
    if (left[i]) PetscCall(NameListAdd(unread, names[i], strlen(names[i])));
  PetscCall(PetscFree(left));
  PetscFunctionReturn(0);
}

/* Refuses the unread options, each with the nearest option known (known texts, the used options, the SNES's) */
static PetscErrorCode RefuseUnread(MPI_Comm comm, NameList *unread, const char *const known[], SNES snes)
{
  NameList names = {0, 0, NULL};
  char     message[4096] = "", nearest[PETSC_MAX_PATH_LEN];
  PetscInt n;

  PetscFunctionBegin;
  if (!unread->n) PetscFunctionReturn(0);
  for (PetscInt k = 0; known && known[k]; k++) PetscCall(AddNamesOfText(&names, known[k], NULL));
  PetscCall(AddUsedNames(&names));
  if (snes) PetscCall(AddNamesOfSNES(&names, snes));
  for (PetscInt i = 0; i < unread->n; i++) {
    char one[2 * PETSC_MAX_PATH_LEN];

    PetscCall(Nearest(&names, unread->names[i], nearest, sizeof(nearest)));
    if (nearest[0]) PetscCall(PetscSNPrintf(one, sizeof(one), "%s-%s (nearest known option: %s)", i ? ", " : "", unread->names[i], nearest));
    else PetscCall(PetscSNPrintf(one, sizeof(one), "%s-%s (no known option is near it)", i ? ", " : "", unread->names[i]));
    if (strlen(message) + strlen(one) < sizeof(message)) PetscCall(PetscMemcpy(message + strlen(message), one, strlen(one) + 1));
  }
  n = unread->n;
  PetscCall(NameListDestroy(&names));
  PetscCall(NameListDestroy(unread));
  SETERRQ(comm, PETSC_ERR_USER_INPUT, "Unknown option%s %s: nothing was done; -help lists the options", n > 1 ? "s" : "", message);
}

/*@C
   SSStarCheckOptionsUsed - refuses the options of the database that nothing has read, naming each with the nearest
   option the program knows; for a program that has read all its options and set up its solver from them, before
   its work (the check of ssstar's example programs)

   Collective

   Input Parameters:
+  comm  - the communicator of the program
.  known - NULL, or a NULL-terminated list of texts that name the program's options as "-name" (its help text);
           "-name_<G>" names the options -name_ followed by any group name
-  snes  - NULL, or the program's SNES after SNESSetFromOptions(): the options of a SNES, KSP and PC of its types
           count as known too

   Notes:
   An option that PETSc reads only during the work, after the solve or at PetscFinalize() is not refused here:
   -snes_view*, -snes_converged_reason, -ksp_view, -ksp_converged_reason, -pc_view, -vec_view, -log*, -options_left,
   -options_view, -memory_view, -malloc_*, -objects_dump, and the prefixes -mat_, -dm_, -petscpartitioner_, -viewer_,
   -pc_factor_, -pc_mg_, -mg_, -matmatmult_, -matptap_, -matproduct_, -schur_, -interior_, -initial_mat_,
   -snes_ssstar_newton_ksp_. PETSc's -options_left
   lists at PetscFinalize() those left unread.

   The error (PETSC_ERR_USER_INPUT) reads "Unknown option -levle (nearest known option: -level): nothing was done;
   -help lists the options". The options read by every rank count as read.

   Level: intermediate

.seealso: `SSStarCheckOptionsUsedOf()`, `PetscOptionsLeftGet()`, `PetscOptionsUsed()`
@*/
PetscErrorCode SSStarCheckOptionsUsed(MPI_Comm comm, const char *const known[], SNES snes)
{
  NameList unread = {0, 0, NULL};

  PetscFunctionBegin;
  if (snes) PetscValidHeaderSpecific(snes, SNES_CLASSID, 3);
  PetscCall(UnreadOptions(comm, &unread));
  PetscCall(RefuseUnread(comm, &unread, known, snes));
  PetscCall(NameListDestroy(&unread));
  PetscFunctionReturn(0);
}

/*@C
   SSStarCheckOptionsUsedOf - refuses those of the given options that nothing has read, naming each with the nearest
   option the program knows: SSStarCheckOptionsUsed() for a program's own list of options (the keywords of a Python
   scene), the rest of the database left to PETSc's behaviour

   Collective

   Input Parameters:
+  comm  - the communicator of the program
.  n     - the number of options
.  names - their names, without the dash
.  known - NULL, or a NULL-terminated list of texts that name the program's options as "-name" (its help text);
           "-name_<G>" names the options -name_ followed by any group name
-  snes  - NULL, or the program's SNES after SNESSetFromOptions(): the options of a SNES, KSP and PC of its types
           count as known too

   Notes:
   As SSStarCheckOptionsUsed(), options PETSc reads only during the work, after the solve or at PetscFinalize() are
   not refused (-snes_view, -log_view, -mat_*, ...).

   Level: intermediate

.seealso: `SSStarCheckOptionsUsed()`, `SSStarSceneCheckOptionsUsedOf()`
@*/
PetscErrorCode SSStarCheckOptionsUsedOf(MPI_Comm comm, PetscInt n, const char *const names[], const char *const known[], SNES snes)
{
  NameList unread = {0, 0, NULL};

  PetscFunctionBegin;
  if (snes) PetscValidHeaderSpecific(snes, SNES_CLASSID, 5);
  PetscCall(UnreadOptionsOf(comm, n, names, &unread));
  PetscCall(RefuseUnread(comm, &unread, known, snes));
  PetscCall(NameListDestroy(&unread));
  PetscFunctionReturn(0);
}

/*@C
   SSStarWriteOutcome - writes how the last SNESSolve() of snes ended as attributes of the root group "/" of an HDF5
   file: converged_reason (a string, SNESConvergedReasons[], e.g. CONVERGED_FNORM_RELATIVE or DIVERGED_MAX_IT),
   residual_norm (the last function norm: ||z|| for ssstar) and iterations

   Collective

   Input Parameters:
+  snes   - the SNES after SNESSolve()
-  viewer - an HDF5 viewer open for writing

   Notes:
   ssstar's programs write these into every solution file, so that a file written by a solve that did not converge
   says so; such a solve ends the program with the exit status SSSTAR_EXIT_NOT_CONVERGED.

   Level: intermediate

.seealso: `SNESGetConvergedReason()`, `SNESGetFunctionNorm()`, `SSStarSceneWriteSolution()`
@*/
PetscErrorCode SSStarWriteOutcome(SNES snes, PetscViewer viewer)
{
  SNESConvergedReason reason;
  PetscReal           norm;
  PetscInt            its;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscValidHeaderSpecific(viewer, PETSC_VIEWER_CLASSID, 2);
  PetscCall(SNESGetConvergedReason(snes, &reason));
  PetscCall(SNESGetFunctionNorm(snes, &norm));
  PetscCall(SNESGetIterationNumber(snes, &its));
  PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "converged_reason", PETSC_STRING, SNESConvergedReasons[reason]));
  PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "residual_norm", PETSC_REAL, &norm));
  PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "iterations", PETSC_INT, &its));
  PetscFunctionReturn(0);
}

/*
   How an error ends a program of ours (SSStarPushErrorHandler()): one line, the program's name and the message; PETSc's
   report (its version, configuration and calls) after it only with a debugging option; and the way out of main():
   every rank that raised the error exits with its code, and if a rank did not raise it (it is still working, or
   waits in a collective call), the job is aborted so that no rank is left waiting.
*/
static PetscErrorCode (*SSStarErrorReport)(MPI_Comm, int, const char *, const char *, PetscErrorCode, PetscErrorType, const char *, void *) = NULL;
static MPI_Comm SSStarErrorComm = MPI_COMM_NULL; /* a copy of PETSC_COMM_WORLD where the ranks meet on their way out */
#define SSSTAR_ERROR_WAIT 2.0 /* seconds a rank waits for the others to raise the error too */

/* Leaves main(): MPI_Finalize() and the error code if every rank raised an error, else MPI_Abort() of the job */
static void SSStarErrorExit(PetscErrorCode n)
{
  MPI_Request request;
  int         done = 0;
  double      start = MPI_Wtime();

  fflush(stdout);
  fflush(stderr);
  if (MPI_Ibarrier(SSStarErrorComm, &request) == MPI_SUCCESS)
    while (!done && MPI_Wtime() - start < SSSTAR_ERROR_WAIT) {
      if (MPI_Test(&request, &done, MPI_STATUS_IGNORE) != MPI_SUCCESS) break;
      if (!done) usleep(1000);
    }
  if (!done) MPI_Abort(MPI_COMM_WORLD, (int)n);
  MPI_Finalize();
  exit((int)n);
}

/* PETSc's words for a value its options parser could not read ("Input string abc has no numeric value"), with what the value should be */
static const struct {
  const char *before, *after, *expected;
} ValueErrors[] = {
  {"Input string ", " has no numeric value", "a number"},
  {"Input string ", " has no integer value", "an integer"},
  {"Unknown logical value: ", "", "true or false"},
};

/* Whether value (an option's value in the database) is bad, or holds bad as one of its comma-separated entries (an array option) */
static PetscBool ValueHolds(const char value[], const char bad[])
{
  const size_t n = strlen(bad);

  for (const char *s = value; s && *s; s = strchr(s, ',') ? strchr(s, ',') + 1 : NULL)
    if (!strncmp(s, bad, n) && (s[n] == 0 || s[n] == ',')) return PETSC_TRUE;
  return PETSC_FALSE;
}

/*@C
   SSStarOptionsNameBadValue - the message of an error of PETSc's options parser with the option named: PETSc names
   the value it cannot read, not the option (-snes_rtol abc: "Input string abc has no numeric value"); the options of
   the database whose value (or an entry of whose comma-separated list) is that one are named instead, "Option
   -snes_rtol abc: abc is not a number", for every real, integer and logical option of ours and of PETSc's, whenever
   it is read

   Not Collective

   Input Parameters:
+  message - the message of an error (PetscErrorMessage())
-  len     - the size of named

   Output Parameter:
.  named - the message naming the option; empty when message is no such error or no option of the database has the
           value

   Notes:
   ssstar's programs print it in place of PETSc's message (SSStarPushErrorHandler()), and so does the Python module.

   Level: developer

.seealso: `SSStarPushErrorHandler()`, `SSStarCheckOptionsUsed()`
@*/
PetscErrorCode SSStarOptionsNameBadValue(const char message[], char named[], size_t len)
{
  char        bad[256] = "", *all = NULL, *token, *save = NULL, *name = NULL;
  const char *expected = NULL;
  size_t      used     = 0;

  PetscFunctionBegin;
  named[0] = 0;
  for (size_t k = 0; message && k < PETSC_STATIC_ARRAY_LENGTH(ValueErrors) && !expected; k++) {
    const size_t lb = strlen(ValueErrors[k].before);
    const char  *end;

    if (strncmp(message, ValueErrors[k].before, lb)) continue;
    end = ValueErrors[k].after[0] ? strstr(message + lb, ValueErrors[k].after) : message + strlen(message);
    if (!end || end == message + lb || (size_t)(end - message - lb) >= sizeof(bad)) continue;
    PetscCall(PetscSNPrintf(bad, sizeof(bad), "%.*s", (int)(end - message - lb), message + lb));
    expected = ValueErrors[k].expected;
  }
  if (!expected) PetscFunctionReturn(0);
  PetscCall(PetscOptionsGetAll(NULL, &all));
  for (token = strtok_r(all, " ", &save); token; token = strtok_r(NULL, " ", &save)) {
    if (token[0] == '-' && isalpha((unsigned char)token[1])) { /* a name; its value, if any, follows */
      name = token;
      continue;
    }
    if (!name || !ValueHolds(token, bad)) continue;
    used += (size_t)snprintf(named + used, used < len ? len - used : 0, "%s%s %s", used ? " or " : "Option ", name, token);
    name = NULL;
  }
  if (used && used < len) snprintf(named + used, len - used, ": %s is not %s", bad, expected);
  else named[0] = 0;
  PetscCall(PetscFree(all));
  PetscFunctionReturn(0);
}

static PetscErrorCode SSStarErrorHandler(MPI_Comm comm, int line, const char *fun, const char *file, PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx)
{
  if (p == PETSC_ERROR_INITIAL) {
    PetscMPIInt rank = 0, size = 1, world = 0, worldSize = 1;
    char        name[PETSC_MAX_PATH_LEN] = "";
    const char *text = mess;

    if (comm != MPI_COMM_NULL) {
      MPI_Comm_rank(comm, &rank);
      MPI_Comm_size(comm, &size);
    }
    MPI_Comm_rank(MPI_COMM_WORLD, &world);
    MPI_Comm_size(MPI_COMM_WORLD, &worldSize);
    if (!text || !text[0] || !strcmp(text, " ")) (void)PetscErrorMessage(n, &text, NULL); /* no message of its own: PETSc's words for the code */
    else {
      static char named[1024];

      if (SSStarOptionsNameBadValue(text, named, sizeof(named))) named[0] = 0;
      if (named[0]) text = named;
    }
    (void)PetscGetProgramName(name, sizeof(name));
    if (size == 1 && worldSize > 1) fprintf(stderr, "%s, rank %d: %s\n", name, (int)world, text ? text : "error"); /* a rank's own error */
    else if (!rank) fprintf(stderr, "%s: %s\n", name, text ? text : "error");
    fflush(stderr);
  }
  if (SSStarErrorReport) (void)(*SSStarErrorReport)(comm, line, fun, file, n, p, mess, ctx);
  if (fun && !strcmp(fun, "main")) SSStarErrorExit(n); /* the error leaves the program */
  return n;
}

/* Restores the handler before ours (PetscFinalize()) */
static PetscErrorCode SSStarPopErrorHandler(void)
{
  PetscFunctionBegin;
  PetscCall(PetscPopErrorHandler());
  if (SSStarErrorComm != MPI_COMM_NULL) PetscCallMPI(MPI_Comm_free(&SSStarErrorComm));
  PetscFunctionReturn(0);
}

/*@C
   SSStarPushErrorHandler - makes an error end the program as users of a command expect: one line with the program's
   name and the message, and the exit status; PETSc's report of it (its version, configuration and calls) only with a
   debugging option; and no rank left waiting when another one failed

   Collective on PETSC_COMM_WORLD

   Options Database Keys:
+  -ssstar_traceback - print PETSc's report after ssstar's line (PetscTraceBackErrorHandler()); so does -info
.  -on_error_abort - PETSc's report, then abort() (a core file, for a debugger)
-  -on_error_attach_debugger - PETSc's report, then a debugger

   Notes:
   ssstar's programs call it after PetscInitialize(); PetscFinalize() (or PetscPopErrorHandler()) restores the handler
   before it.

   When an error leaves main(), the ranks that raised it wait up to 2 seconds for each other: if all of them did, each
   exits with the error code; if one did not (it goes on working, or waits in a collective call for the rank that
   failed), MPI_Abort() ends the job with the error code, so that an error on one rank ends every rank promptly.

   Level: intermediate

.seealso: `PetscPushErrorHandler()`, `PetscTraceBackErrorHandler()`, `SSStarCheckOptionsUsed()`
@*/
PetscErrorCode SSStarPushErrorHandler(void)
{
  PetscBool traceback = PETSC_FALSE, info, abort, debugger;

  PetscFunctionBegin;
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "Error reports", NULL);
  PetscCall(PetscOptionsBool("-ssstar_traceback", "Print PETSc's report of an error (version, configuration, calls) after ssstar's line", "SSStarPushErrorHandler", traceback, &traceback, NULL));
  PetscOptionsEnd();
  PetscCall(PetscOptionsHasName(NULL, NULL, "-info", &info));
  PetscCall(PetscOptionsHasName(NULL, NULL, "-on_error_abort", &abort));
  PetscCall(PetscOptionsHasName(NULL, NULL, "-on_error_attach_debugger", &debugger));
  SSStarErrorReport = NULL;
  if (traceback || info) SSStarErrorReport = PetscTraceBackErrorHandler;
  if (debugger) SSStarErrorReport = PetscAttachDebuggerErrorHandler;
  if (abort) SSStarErrorReport = PetscAbortErrorHandler;
  if (SSStarErrorComm == MPI_COMM_NULL) PetscCallMPI(MPI_Comm_dup(PETSC_COMM_WORLD, &SSStarErrorComm));
  PetscCall(PetscPushErrorHandler(SSStarErrorHandler, NULL));
  PetscCall(PetscRegisterFinalize(SSStarPopErrorHandler));
  PetscFunctionReturn(0);
}
