/*
   Load histories: piecewise-linear vector functions of the pseudo-time, read from an option's value, and the times a
   load path is solved at (include/ssstarhistory.h; docs/load-paths.md). Self-contained: PETSc's options and
   strings only.
*/
#include <ssstarhistory.h>
#include <ctype.h>
#include <stdlib.h>

struct _n_SSStarHistory {
  PetscInt   ncomp;  /* components of a value                                     */
  PetscInt   nknots; /* 0: a constant                                             */
  PetscReal *times;  /* nknots, strictly increasing                               */
  PetscReal *values; /* ncomp per knot (ncomp for a constant)                     */
};

/* A piece of the option's value: text[0..len) */
typedef struct {
  const char *text;
  size_t      len;
} Piece;

static Piece Trimmed(const char *text, size_t len)
{
  Piece p = {text, len};

  while (p.len && isspace((unsigned char)p.text[0])) {
    p.text++;
    p.len--;
  }
  while (p.len && isspace((unsigned char)p.text[p.len - 1])) p.len--;
  return p;
}

/* The part of p before the first sep (all of p if none), and what follows it in *rest (len 0 and found false if none) */
static Piece Split(Piece p, char sep, Piece *rest, PetscBool *found)
{
  const char *at = (const char *)memchr(p.text, sep, p.len);
  Piece       head = {p.text, at ? (size_t)(at - p.text) : p.len};

  *found = (PetscBool)(at != NULL);
  rest->text = at ? at + 1 : p.text + p.len;
  rest->len  = at ? p.len - head.len - 1 : 0;
  return head;
}

static PetscInt Count(Piece p, char sep)
{
  PetscInt n = 1;

  for (size_t i = 0; i < p.len; i++) n += p.text[i] == sep;
  return n;
}

/* A real number filling the whole (trimmed) piece; NaN and Inf are numbers here (the callers refuse them by name) */
static PetscBool ParseReal(Piece p, PetscReal *x)
{
  char   buf[64], *end;
  Piece  q = Trimmed(p.text, p.len);
  double v;

  *x = 0;
  if (q.len == 0 || q.len >= sizeof(buf)) return PETSC_FALSE;
  memcpy(buf, q.text, q.len);
  buf[q.len] = 0;
  v  = strtod(buf, &end);
  *x = (PetscReal)v;
  return (PetscBool)(end == buf + q.len);
}

/* How a value is written: x,y,z for 3 components, v1,...,vN otherwise */
static void ValueForm(PetscInt ncomp, char form[], size_t len)
{
  if (ncomp == 3) PetscSNPrintf(form, len, "x,y,z");
  else if (ncomp == 1) PetscSNPrintf(form, len, "v");
  else if (ncomp == 2) PetscSNPrintf(form, len, "v1,v2");
  else PetscSNPrintf(form, len, "v1,...,v%d", (int)ncomp);
}

/*
   The ncomp comma-separated finite numbers of piece p into v; knot = 0 for a constant, else the 1-based knot p belongs
   to (whole: its text, for the messages)
*/
static PetscErrorCode ParseValue(MPI_Comm comm, const char option[], PetscInt knot, Piece whole, Piece p, PetscInt ncomp, PetscReal v[])
{
  char      form[32], where[160] = "";
  PetscInt  n = Count(p, ',');
  Piece     rest = p, item;
  PetscBool more;

  PetscFunctionBegin;
  ValueForm(ncomp, form, sizeof(form));
  if (knot) PetscCall(PetscSNPrintf(where, sizeof(where), " knot %" PetscInt_FMT " \"%.*s\":", knot, (int)PetscMin(whole.len, 100), whole.text));
  if (knot) PetscCheck(n == ncomp, comm, PETSC_ERR_ARG_WRONG, "Option %s:%s %" PetscInt_FMT " values, expected %" PetscInt_FMT " (t:%s)", option, where, n, ncomp, form);
  else PetscCheck(n == ncomp, comm, PETSC_ERR_ARG_WRONG, "Option %s: %" PetscInt_FMT " comma-separated values, expected %" PetscInt_FMT " (%s), or knots t:%s separated by ';'", option, n, ncomp, form, form);
  for (PetscInt k = 0; k < ncomp; k++) {
    item = Split(rest, ',', &rest, &more);
    PetscCheck(ParseReal(item, &v[k]), comm, PETSC_ERR_ARG_WRONG, "Option %s:%s value %" PetscInt_FMT " \"%.*s\" is not a number", option, where, k + 1, (int)PetscMin(item.len, 60), item.text);
    PetscCheck(!PetscIsInfOrNanReal(v[k]), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option %s:%s value %" PetscInt_FMT " \"%.*s\" is not a finite number", option, where, k + 1, (int)PetscMin(item.len, 60), item.text);
  }
  PetscFunctionReturn(0);
}

/* The constant or the knots of the (trimmed, nonempty) value into hist */
static PetscErrorCode Parse(MPI_Comm comm, const char option[], Piece all, const char form[], SSStarHistory hist)
{
  const PetscInt ncomp = hist->ncomp;
  Piece          rest = all, knot, head, tail;
  PetscBool      more, timed;

  PetscFunctionBegin;
  if (!memchr(all.text, ':', all.len) && !memchr(all.text, ';', all.len)) {
    PetscCall(PetscMalloc1(ncomp, &hist->values));
    PetscCall(ParseValue(comm, option, 0, all, all, ncomp, hist->values));
    PetscFunctionReturn(0);
  }
  hist->nknots = Count(all, ';');
  PetscCall(PetscMalloc2(hist->nknots, &hist->times, ncomp * hist->nknots, &hist->values));
  for (PetscInt i = 0; i < hist->nknots; i++) {
    knot = Split(rest, ';', &rest, &more);
    knot = Trimmed(knot.text, knot.len);
    PetscCheck(knot.len > 0, comm, PETSC_ERR_ARG_WRONG, "Option %s: knot %" PetscInt_FMT " is empty (two ';' in a row, or one at an end)", option, i + 1);
    head = Split(knot, ':', &tail, &timed);
    PetscCheck(timed, comm, PETSC_ERR_ARG_WRONG, "Option %s: knot %" PetscInt_FMT " \"%.*s\" has no time: expected t:%s", option, i + 1, (int)PetscMin(knot.len, 100), knot.text, form);
    PetscCheck(ParseReal(head, &hist->times[i]), comm, PETSC_ERR_ARG_WRONG, "Option %s: knot %" PetscInt_FMT " \"%.*s\": the time \"%.*s\" is not a number", option, i + 1, (int)PetscMin(knot.len, 100), knot.text, (int)PetscMin(head.len, 60), head.text);
    PetscCheck(!PetscIsInfOrNanReal(hist->times[i]), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option %s: knot %" PetscInt_FMT " \"%.*s\": the time \"%.*s\" is not a finite number", option, i + 1, (int)PetscMin(knot.len, 100), knot.text, (int)PetscMin(head.len, 60), head.text);
    PetscCall(ParseValue(comm, option, i + 1, knot, tail, ncomp, &hist->values[ncomp * i]));
    PetscCheck(i == 0 || hist->times[i] > hist->times[i - 1], comm, PETSC_ERR_ARG_OUTOFRANGE, "Option %s: the times of the knots must increase: knot %" PetscInt_FMT " at t = %g follows knot %" PetscInt_FMT " at t = %g", option, i + 1, (double)hist->times[i], i, (double)hist->times[i - 1]);
  }
  PetscFunctionReturn(0);
}

/*@C
   SSStarHistoryCreateFromString - a load history from the text of an option's value: knots "t:v1,...,vN" separated
   by ';' with strictly increasing times, or a plain vector "v1,...,vN" (a constant)

   Collective

   Input Parameters:
+  comm   - the ranks that share the history (every rank passes the same text)
.  option - the option's name, for the messages (e.g. "-traction_top")
.  text   - the value, e.g. "0:0,0,0;1:0,0,-1;2:0.8,0,-1" or "0,0,-1"
-  ncomp  - the number of components of a value (3 for a traction, a gravity or a translation)

   Output Parameter:
.  h - the history

   Notes:
   Spaces around numbers are ignored. Refused with an error naming the option and the knot (1-based): an empty value or
   knot, a knot without its time, a number that is not one, NaN or Inf, a wrong count of components, times that do not
   increase. Between its knots the history is linear; before the first knot it keeps the first knot's value, after the
   last the last one's (SSStarHistoryEvaluate()).

   Level: intermediate

.seealso: `SSStarHistoryCreateFromOptions()`, `SSStarHistoryEvaluate()`, `SSStarHistoryDestroy()`
@*/
PetscErrorCode SSStarHistoryCreateFromString(MPI_Comm comm, const char option[], const char text[], PetscInt ncomp, SSStarHistory *h)
{
  SSStarHistory  hist;
  Piece          all;
  char           form[32];
  PetscErrorCode ierr;

  PetscFunctionBegin;
  *h = NULL;
  PetscCheck(ncomp >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "SSStarHistoryCreateFromString: %" PetscInt_FMT " components: at least one", ncomp);
  ValueForm(ncomp, form, sizeof(form));
  PetscCheck(text, comm, PETSC_ERR_ARG_WRONG, "Option %s needs a value: %s, or knots t:%s separated by ';'", option, form, form);
  PetscCall(PetscStrlen(text, &all.len));
  all = Trimmed(text, all.len);
  PetscCheck(all.len > 0, comm, PETSC_ERR_ARG_WRONG, "Option %s has an empty value: give %s, or knots t:%s separated by ';'", option, form, form);
  PetscCall(PetscNew(&hist));
  hist->ncomp = ncomp;
  ierr        = Parse(comm, option, all, form, hist);
  if (ierr) { /* a refused value leaves nothing allocated */
    PetscCall(SSStarHistoryDestroy(&hist));
    PetscCall(ierr);
  }
  *h = hist;
  PetscFunctionReturn(0);
}

/*@C
   SSStarHistoryCreateFromOptions - the load history of an option of the database, if it is given

   Collective

   Input Parameters:
+  comm    - the ranks that share the history
.  options - the options database (NULL: the global one)
.  name    - the option, e.g. "-traction_top"
-  ncomp   - the number of components of a value

   Output Parameters:
+  h   - the history (SSStarHistoryCreateFromString()), or NULL when the option is not given
-  set - whether it is given

   Notes:
   The value has no length limit (it is not copied into a buffer).

   Level: intermediate

.seealso: `SSStarHistoryCreateFromString()`, `SSStarHistoryDestroy()`
@*/
PetscErrorCode SSStarHistoryCreateFromOptions(MPI_Comm comm, PetscOptions options, const char name[], PetscInt ncomp, SSStarHistory *h, PetscBool *set)
{
  const char *value;

  PetscFunctionBegin;
  *h = NULL;
  PetscCall(PetscOptionsFindPair(options, NULL, name, &value, set));
  if (*set) PetscCall(SSStarHistoryCreateFromString(comm, name, value, ncomp, h));
  PetscFunctionReturn(0);
}

/*@C
   SSStarHistoryDestroy - frees a history

   Not Collective

   Input Parameter:
.  h - the history (set to NULL; NULL is accepted)

   Level: intermediate

.seealso: `SSStarHistoryCreateFromString()`
@*/
PetscErrorCode SSStarHistoryDestroy(SSStarHistory *h)
{
  PetscFunctionBegin;
  if (!*h) PetscFunctionReturn(0);
  if ((*h)->nknots) PetscCall(PetscFree2((*h)->times, (*h)->values));
  else PetscCall(PetscFree((*h)->values));
  PetscCall(PetscFree(*h));
  PetscFunctionReturn(0);
}

/*@C
   SSStarHistoryEvaluate - the value of a history at the time t

   Not Collective

   Input Parameters:
+  h - the history
-  t - the time

   Output Parameter:
.  value - its ncomp components: linear between two knots, the first knot's value for t before the first knot, the
           last knot's after the last one, the constant of a plain vector at any t; exactly a knot's value at its time

   Level: intermediate

.seealso: `SSStarHistoryCreateFromString()`, `SSStarHistoryGetKnots()`
@*/
PetscErrorCode SSStarHistoryEvaluate(SSStarHistory h, PetscReal t, PetscReal value[])
{
  const PetscInt m = h->ncomp, n = h->nknots;
  PetscInt       lo = 0, hi = n - 1;
  PetscReal      w;

  PetscFunctionBegin;
  PetscCheck(!PetscIsInfOrNanReal(t), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "SSStarHistoryEvaluate: t = %g is not a finite time", (double)t);
  if (n == 0 || t <= h->times[0]) {
    PetscCall(PetscArraycpy(value, h->values, m));
    PetscFunctionReturn(0);
  }
  if (t >= h->times[n - 1]) {
    PetscCall(PetscArraycpy(value, &h->values[m * (n - 1)], m));
    PetscFunctionReturn(0);
  }
  while (hi - lo > 1) { /* times[lo] < t < times[hi] or t == times[lo] */
    const PetscInt mid = (lo + hi) / 2;

    if (h->times[mid] <= t) lo = mid;
    else hi = mid;
  }
  w = (t - h->times[lo]) / (h->times[hi] - h->times[lo]);
  for (PetscInt k = 0; k < m; k++) value[k] = h->values[m * lo + k] + w * (h->values[m * hi + k] - h->values[m * lo + k]);
  PetscFunctionReturn(0);
}

/*@C
   SSStarHistoryGetKnots - the knots of a history

   Not Collective

   Input Parameter:
.  h - the history

   Output Parameters:
+  n      - the number of knots (0 for a constant), or pass NULL
.  times  - their times, increasing, or pass NULL
-  values - their values, ncomp per knot (a constant: its ncomp components), or pass NULL

   Notes:
   The arrays belong to the history.

   Level: intermediate

.seealso: `SSStarHistoryMergeKnots()`, `SSStarHistoryEvaluate()`
@*/
PetscErrorCode SSStarHistoryGetKnots(SSStarHistory h, PetscInt *n, const PetscReal *times[], const PetscReal *values[])
{
  PetscFunctionBegin;
  if (n) *n = h->nknots;
  if (times) *times = h->times;
  if (values) *values = h->values;
  PetscFunctionReturn(0);
}

/*@C
   SSStarHistoryDescribe - a history in the syntax of its option ("0:0,0,0;1:0,0,-1", or "0,0,-1" for a constant),
   numbers with 15 significant digits, for views and output files

   Not Collective

   Input Parameters:
+  h   - the history
-  len - the size of buf

   Output Parameter:
.  buf - the text; ending in "..." when it did not fit

   Level: intermediate

.seealso: `SSStarHistoryCreateFromString()`
@*/
PetscErrorCode SSStarHistoryDescribe(SSStarHistory h, char buf[], size_t len)
{
  const PetscInt nk = PetscMax(h->nknots, 1);
  size_t         need = 0, have;
  char           piece[64];

  PetscFunctionBegin;
  if (!len) PetscFunctionReturn(0);
  buf[0] = 0;
  for (PetscInt i = 0; i < nk; i++) {
    for (PetscInt k = -1; k < h->ncomp; k++) {
      if (k < 0 && !h->nknots) continue;
      if (k < 0) PetscCall(PetscSNPrintf(piece, sizeof(piece), "%s%.15g:", i ? ";" : "", (double)h->times[i]));
      else PetscCall(PetscSNPrintf(piece, sizeof(piece), "%s%.15g", k ? "," : "", (double)h->values[h->ncomp * i + k]));
      PetscCall(PetscStrlen(piece, &have));
      need += have;
      PetscCall(PetscStrlcat(buf, piece, len));
    }
  }
  if (need >= len && len > 3) PetscCall(PetscStrcpy(buf + len - 4, "..."));
  PetscFunctionReturn(0);
}

/*@C
   SSStarHistoryMergeKnots - the times of the knots of several histories, sorted, each once: the default steps of a
   load path

   Not Collective

   Input Parameters:
+  n - the number of histories
-  h - the histories (constants have no knots)

   Output Parameters:
+  m     - the number of distinct times (0 when no history has knots)
-  times - the times, increasing (free with PetscFree())

   Notes:
   Times are merged when they are equal as numbers: "1" in one option and "1.0" in another are one step.

   Level: intermediate

.seealso: `SSStarHistoryParseSteps()`, `SSStarHistoryGetKnots()`
@*/
PetscErrorCode SSStarHistoryMergeKnots(PetscInt n, const SSStarHistory h[], PetscInt *m, PetscReal *times[])
{
  PetscInt total = 0, k = 0;

  PetscFunctionBegin;
  for (PetscInt i = 0; i < n; i++) total += h[i]->nknots;
  PetscCall(PetscMalloc1(total, times));
  for (PetscInt i = 0; i < n; i++)
    for (PetscInt j = 0; j < h[i]->nknots; j++) (*times)[k++] = h[i]->times[j];
  PetscCall(PetscSortReal(total, *times));
  *m = 0;
  for (PetscInt i = 0; i < total; i++)
    if (*m == 0 || (*times)[i] != (*times)[*m - 1]) (*times)[(*m)++] = (*times)[i];
  PetscFunctionReturn(0);
}

/* A count of steps: digits only */
static PetscBool IsCount(Piece p)
{
  if (p.len == 0 || p.len > 9) return PETSC_FALSE;
  for (size_t i = 0; i < p.len; i++)
    if (!isdigit((unsigned char)p.text[i])) return PETSC_FALSE;
  return PETSC_TRUE;
}

/*@C
   SSStarHistoryParseSteps - the times a load path is solved at, from the value of -steps and the knots of its
   histories

   Collective

   Input Parameters:
+  comm   - the ranks that share the load path
.  option - the option's name, for the messages (e.g. "-steps")
.  text   - its value, or NULL when it is not given: then the knots themselves
.  nknots - the number of knots (SSStarHistoryMergeKnots())
-  knots  - the knots, increasing

   Output Parameters:
+  n     - the number of times
-  times - the times, increasing (free with PetscFree())

   Notes:
   A single value is a count N, a whole number >= 1: the first knot and N equal steps to the last one, N + 1 times (the
   first knot's state is a step of its own, so that a load path starts where its histories start); it needs knots
   that span a time. A list of two or more values is the times t1,t2,... (finite, strictly increasing); the
   histories are constant outside their knots, so times before the first or after the last knot hold those knots'
   values. Refused, naming the option: a count that is 0, negative or fractional (-steps -3, -steps 2.5), a count
   without a time span, a time that is not a finite number, times that do not increase, an empty value.

   Level: intermediate

.seealso: `SSStarHistoryMergeKnots()`, `SSStarHistoryCreateFromString()`
@*/
PetscErrorCode SSStarHistoryParseSteps(MPI_Comm comm, const char option[], const char text[], PetscInt nknots, const PetscReal knots[], PetscInt *n, PetscReal *times[])
{
  Piece      all, rest, item;
  PetscBool  more;
  PetscInt   count;
  PetscReal *list;

  PetscFunctionBegin;
  if (!text) {
    *n = nknots;
    PetscCall(PetscMalloc1(nknots, times));
    PetscCall(PetscArraycpy(*times, knots, nknots));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscStrlen(text, &all.len));
  all = Trimmed(text, all.len);
  PetscCheck(all.len > 0, comm, PETSC_ERR_ARG_WRONG, "Option %s has an empty value: give a count N of equal steps, or the times t1,t2,...", option);
  if (IsCount(all)) {
    const PetscInt count = (PetscInt)strtol(all.text, NULL, 10);

    PetscCheck(count >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option %s %" PetscInt_FMT ": needs at least one step", option, count);
    PetscCheck(nknots >= 2, comm, PETSC_ERR_ARG_WRONG, "Option %s %" PetscInt_FMT ": equal steps need load histories that span a time (knots t:x,y,z); %s", option, count, nknots ? "they have a single time" : "no option has one");
    *n = count + 1;
    PetscCall(PetscMalloc1(count + 1, times));
    for (PetscInt k = 0; k < count; k++) (*times)[k] = knots[0] + (knots[nknots - 1] - knots[0]) * k / count;
    (*times)[count] = knots[nknots - 1];
    PetscFunctionReturn(0);
  }
  count = Count(all, ',');
  if (count == 1) { /* one value: a count, which is none of these */
    PetscReal x;

    PetscCheck(ParseReal(all, &x), comm, PETSC_ERR_ARG_WRONG, "Option %s %.*s: not a number (give a count N of equal steps, or the times t1,t2,...)", option, (int)PetscMin(all.len, 60), all.text);
    SETERRQ(comm, PETSC_ERR_ARG_OUTOFRANGE, "Option %s %.*s: a count of equal steps is a whole number >= 1 (times are a list of two or more, t1,t2,...)", option, (int)PetscMin(all.len, 60), all.text);
  }
  PetscCall(PetscMalloc1(count, &list));
  rest = all;
  for (PetscInt k = 0; k < count; k++) {
    PetscBool number, finite, increasing;

    item       = Split(rest, ',', &rest, &more);
    number     = ParseReal(item, &list[k]);
    finite     = (PetscBool)!PetscIsInfOrNanReal(list[k]);
    increasing = (PetscBool)(k == 0 || list[k] > list[k - 1]);
    if (!number || !finite || !increasing) { /* the message after the list is freed */
      const PetscReal t = list[k], before = k ? list[k - 1] : 0;

      PetscCall(PetscFree(list));
      PetscCheck(number, comm, PETSC_ERR_ARG_WRONG, "Option %s: time %" PetscInt_FMT " \"%.*s\" is not a number (give a count N of equal steps, or the times t1,t2,...)", option, k + 1, (int)PetscMin(item.len, 60), item.text);
      PetscCheck(finite, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option %s: time %" PetscInt_FMT " \"%.*s\" is not a finite number", option, k + 1, (int)PetscMin(item.len, 60), item.text);
      SETERRQ(comm, PETSC_ERR_ARG_OUTOFRANGE, "Option %s: the times must increase: time %" PetscInt_FMT " (%g) follows time %" PetscInt_FMT " (%g)", option, k + 1, (double)t, k, (double)before);
    }
  }
  *n     = count;
  *times = list;
  PetscFunctionReturn(0);
}
