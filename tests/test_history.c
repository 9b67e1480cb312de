static const char help[] = "Load histories (include/ssstarhistory.h) against hand-computed cases and every refusal.\n";

/* Requirement: a history option's value "t:x,y,z;..." (or a plain vector, a constant) is parsed into its knots and
   evaluated piecewise linearly, constant before the first and after the last knot, exactly a knot's value at its
   time; spaces, exponents, negative times, one component and a single knot are accepted, and a value of any length;
   the knots of several histories merge into the default steps (equal times once); -steps gives a count N (the first
   knot and N equal steps to the last; a single value, refused unless a whole number >= 1) or a list of two or more
   times; every malformed value is refused with a message naming the
   option and the knot or time, and leaves nothing allocated (the suite runs this with -malloc_dump). Tolerance: exact
   where the arithmetic is (knot values, merged times), 1e-15 relative otherwise. */
#include <ssstarhistory.h>

static int  failures = 0;
static char lastError[1024];

static void Expect(PetscBool ok, const char what[], const char detail[])
{
  if (!ok) {
    failures++;
    PetscPrintf(PETSC_COMM_SELF, "FAIL %s: %s\n", what, detail);
  }
}

static PetscBool Close(PetscInt n, const PetscReal a[], const PetscReal b[], PetscReal tol)
{
  for (PetscInt i = 0; i < n; i++)
    if (!(PetscAbsReal(a[i] - b[i]) <= tol * (1 + PetscAbsReal(b[i])))) return PETSC_FALSE; /* NaN fails */
  return PETSC_TRUE;
}

/* Keeps the message of the error being raised, and returns its code (no printing, no abort) */
static PetscErrorCode CaptureError(MPI_Comm comm, int line, const char *func, const char *file, PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx)
{
  if (p == PETSC_ERROR_INITIAL) PetscStrncpy(lastError, mess ? mess : "", sizeof(lastError));
  return n;
}

/* The value at t of the history of text, against the hand-computed one */
static PetscErrorCode ExpectValue(SSStarHistory h, const char text[], PetscReal t, PetscInt ncomp, const PetscReal expected[], PetscReal tol)
{
  PetscReal v[3];
  char      what[256];

  PetscFunctionBeginUser;
  PetscCall(SSStarHistoryEvaluate(h, t, v));
  PetscCall(PetscSNPrintf(what, sizeof(what), "\"%s\" at t = %g", text, (double)t));
  Expect(Close(ncomp, v, expected, tol), what, "wrong value");
  PetscFunctionReturn(0);
}

static PetscErrorCode Accepted(void)
{
  const char   *steps = "0:0,0,0;1:0,0,-1;2:0.8,0,-1;3:0,0,-1";
  SSStarHistory h;
  PetscInt      n;
  const PetscReal *times, *values;
  char          text[128];

  PetscFunctionBeginUser;
  /* the example: press, shear, release; constant outside [0, 3]; exact at the knots */
  PetscCall(SSStarHistoryCreateFromString(PETSC_COMM_SELF, "-traction_top", steps, 3, &h));
  PetscCall(SSStarHistoryGetKnots(h, &n, &times, &values));
  {
    const PetscReal t[4] = {0, 1, 2, 3}, v[12] = {0, 0, 0, 0, 0, -1, 0.8, 0, -1, 0, 0, -1};

    Expect((PetscBool)(n == 4 && Close(4, times, t, 0) && Close(12, values, v, 0)), "knots of the issue's example", steps);
  }
  {
    const PetscReal at[8] = {-1, 0, 0.5, 1, 1.5, 2.25, 3, 10};
    const PetscReal v[24] = {0, 0, 0, 0, 0, 0, 0, 0, -0.5, 0, 0, -1, 0.4, 0, -1, 0.6, 0, -1, 0, 0, -1, 0, 0, -1};

    for (PetscInt k = 0; k < 8; k++) PetscCall(ExpectValue(h, steps, at[k], 3, &v[3 * k], k == 2 || k == 4 || k == 5 ? 1e-15 : 0.0));
  }
  PetscCall(SSStarHistoryDescribe(h, text, sizeof(text)));
  Expect((PetscBool)!strcmp(text, steps), "described in its own syntax", text);
  PetscCall(SSStarHistoryDescribe(h, text, 10));
  Expect((PetscBool)!strcmp(text, "0:0,0,..."), "a description that does not fit ends in ...", text);
  PetscCall(SSStarHistoryDestroy(&h));
  Expect((PetscBool)(h == NULL), "destroy sets NULL", "");

  /* a plain vector: a constant without knots */
  PetscCall(SSStarHistoryCreateFromString(PETSC_COMM_SELF, "-traction_x", "-200,30,200", 3, &h));
  PetscCall(SSStarHistoryGetKnots(h, &n, NULL, NULL));
  Expect((PetscBool)(n == 0), "a plain vector has no knots", "-200,30,200");
  {
    const PetscReal v[3] = {-200, 30, 200};

    PetscCall(ExpectValue(h, "-200,30,200", -5, 3, v, 0));
    PetscCall(ExpectValue(h, "-200,30,200", 7, 3, v, 0));
  }
  PetscCall(SSStarHistoryDescribe(h, text, sizeof(text)));
  Expect((PetscBool)!strcmp(text, "-200,30,200"), "a constant described", text);
  PetscCall(SSStarHistoryDestroy(&h));

  /* spaces around numbers and separators */
  PetscCall(SSStarHistoryCreateFromString(PETSC_COMM_SELF, "-traction_top", " 0 : 1 , 2 , 3 ; 2: 4,5,6 ", 3, &h));
  {
    const PetscReal v[3] = {2.5, 3.5, 4.5};

    PetscCall(ExpectValue(h, "spaced", 1, 3, v, 1e-15));
  }
  PetscCall(SSStarHistoryDestroy(&h));

  /* negative times, exponents */
  PetscCall(SSStarHistoryCreateFromString(PETSC_COMM_SELF, "-obstacle_top_motion", "-1:1e-3,0,0;0.5:-2E-3,0,0", 3, &h));
  {
    const PetscReal v[3] = {-0.5e-3, 0, 0};

    PetscCall(ExpectValue(h, "-1:1e-3,0,0;0.5:-2E-3,0,0", -0.25, 3, v, 1e-15));
  }
  PetscCall(SSStarHistoryDestroy(&h));

  /* one component; a single knot is a constant with a time */
  PetscCall(SSStarHistoryCreateFromString(PETSC_COMM_SELF, "-scale", "0:0;2:4", 1, &h));
  {
    const PetscReal v[1] = {1};

    PetscCall(ExpectValue(h, "0:0;2:4", 0.5, 1, v, 1e-15));
  }
  PetscCall(SSStarHistoryDestroy(&h));
  PetscCall(SSStarHistoryCreateFromString(PETSC_COMM_SELF, "-traction_top", "1:0,0,-1", 3, &h));
  PetscCall(SSStarHistoryGetKnots(h, &n, &times, NULL));
  Expect((PetscBool)(n == 1 && times[0] == 1), "a single knot", "1:0,0,-1");
  {
    const PetscReal v[3] = {0, 0, -1};

    PetscCall(ExpectValue(h, "1:0,0,-1", 0, 3, v, 0));
    PetscCall(ExpectValue(h, "1:0,0,-1", 5, 3, v, 0));
  }
  PetscCall(SSStarHistoryDestroy(&h));
  PetscFunctionReturn(0);
}

/* The options database: given or not, marked as used, a value longer than any option buffer */
static PetscErrorCode FromOptions(void)
{
  SSStarHistory h;
  PetscBool     set;
  PetscInt      n, unused[2];
  char         *longValue;
  size_t        len = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsSetValue(NULL, "-traction_top", "0:0,0,0;1:0,0,-1"));
  PetscCall(PetscOptionsAllUsed(NULL, &unused[0]));
  PetscCall(SSStarHistoryCreateFromOptions(PETSC_COMM_SELF, NULL, "-traction_top", 3, &h, &set));
  PetscCall(PetscOptionsAllUsed(NULL, &unused[1]));
  PetscCall(SSStarHistoryGetKnots(h, &n, NULL, NULL));
  Expect((PetscBool)(set && unused[1] == unused[0] - 1 && n == 2), "-traction_top from the options database, marked as used", "");
  PetscCall(SSStarHistoryDestroy(&h));
  PetscCall(SSStarHistoryCreateFromOptions(PETSC_COMM_SELF, NULL, "-traction_absent", 3, &h, &set));
  Expect((PetscBool)(!set && h == NULL), "an option not given: no history", "");

  /* 1000 knots, about 24 000 characters */
  PetscCall(PetscMalloc1(32 * 1000, &longValue));
  for (PetscInt k = 0; k < 1000; k++) {
    PetscCall(PetscSNPrintf(longValue + len, 32, "%s%d:%d,0,-1", k ? ";" : "", (int)k, (int)(k % 7)));
    PetscCall(PetscStrlen(longValue, &len));
  }
  PetscCall(PetscOptionsSetValue(NULL, "-traction_long", longValue));
  PetscCall(SSStarHistoryCreateFromOptions(PETSC_COMM_SELF, NULL, "-traction_long", 3, &h, &set));
  PetscCall(SSStarHistoryGetKnots(h, &n, NULL, NULL));
  Expect((PetscBool)(set && n == 1000), "a value of 1000 knots", "");
  {
    const PetscReal v[3] = {4.5, 0, -1}; /* knot k at t = k has x = k mod 7: 4 at t = 998, 5 at t = 999 */

    PetscCall(ExpectValue(h, "the long value", 998.5, 3, v, 1e-15));
  }
  PetscCall(SSStarHistoryDestroy(&h));
  PetscCall(PetscFree(longValue));
  PetscFunctionReturn(0);
}

/* Merged knots and -steps */
static PetscErrorCode Steps(void)
{
  SSStarHistory h[3];
  PetscInt      m, n;
  PetscReal    *knots, *times;

  PetscFunctionBeginUser;
  PetscCall(SSStarHistoryCreateFromString(PETSC_COMM_SELF, "-traction_top", "0:0,0,0;1:0,0,-1;2:0.8,0,-1;3:0,0,-1", 3, &h[0]));
  PetscCall(SSStarHistoryCreateFromString(PETSC_COMM_SELF, "-obstacle_base_motion", "0:0,0,0;0.5:0,0,1;1.0:0,0,1;4:1,0,1", 3, &h[1]));
  PetscCall(SSStarHistoryCreateFromString(PETSC_COMM_SELF, "-gravity", "0,0,-9.81", 3, &h[2]));
  PetscCall(SSStarHistoryMergeKnots(3, h, &m, &knots));
  {
    const PetscReal expected[6] = {0, 0.5, 1, 2, 3, 4};

    Expect((PetscBool)(m == 6 && Close(6, knots, expected, 0)), "the knots merged, 1 and 1.0 once, the constant none", "");
  }
  PetscCall(SSStarHistoryParseSteps(PETSC_COMM_SELF, "-steps", NULL, m, knots, &n, &times));
  Expect((PetscBool)(n == m && Close(m, times, knots, 0)), "no -steps: the knots", "");
  PetscCall(PetscFree(times));
  PetscCall(SSStarHistoryParseSteps(PETSC_COMM_SELF, "-steps", "4", m, knots, &n, &times));
  {
    const PetscReal expected[5] = {0, 1, 2, 3, 4};

    Expect((PetscBool)(n == 5 && Close(5, times, expected, 0)), "-steps 4: the first knot and 4 equal steps to the last", "");
  }
  PetscCall(PetscFree(times));
  PetscCall(SSStarHistoryParseSteps(PETSC_COMM_SELF, "-steps", " 3 ", m, knots, &n, &times));
  {
    const PetscReal expected[4] = {0, 4.0 / 3, 8.0 / 3, 4};

    Expect((PetscBool)(n == 4 && Close(4, times, expected, 1e-15) && times[3] == 4), "-steps 3: ends exactly at the last knot", "");
  }
  PetscCall(PetscFree(times));
  PetscCall(SSStarHistoryParseSteps(PETSC_COMM_SELF, "-steps", "0.5,1,2.5,7", m, knots, &n, &times));
  {
    const PetscReal expected[4] = {0.5, 1, 2.5, 7};

    Expect((PetscBool)(n == 4 && Close(4, times, expected, 0)), "-steps as a list of times (7: after the last knot)", "");
  }
  PetscCall(PetscFree(times));
  PetscCall(SSStarHistoryParseSteps(PETSC_COMM_SELF, "-steps", "-1,2", m, knots, &n, &times));
  Expect((PetscBool)(n == 2 && times[0] == -1 && times[1] == 2), "-steps -1,2: times (the first before the first knot)", "");
  PetscCall(PetscFree(times));
  PetscCall(SSStarHistoryParseSteps(PETSC_COMM_SELF, "-steps", NULL, 0, NULL, &n, &times));
  Expect((PetscBool)(n == 0), "no histories, no -steps: no steps (one static solve)", "");
  PetscCall(PetscFree(times));
  PetscCall(PetscFree(knots));
  for (PetscInt k = 0; k < 3; k++) PetscCall(SSStarHistoryDestroy(&h[k]));
  PetscFunctionReturn(0);
}

/* A value refused with a message that contains expected, and no history left behind */
static void Refused(const char text[], PetscInt ncomp, const char expected[])
{
  SSStarHistory  h = NULL;
  PetscErrorCode ierr;

  lastError[0] = 0;
  ierr         = SSStarHistoryCreateFromString(PETSC_COMM_SELF, "-traction_top", text, ncomp, &h);
  Expect((PetscBool)(ierr && !h && strstr(lastError, expected)), text ? text : "(no value)", lastError[0] ? lastError : "accepted");
}

static void RefusedSteps(const char text[], PetscInt nknots, const PetscReal knots[], const char expected[])
{
  PetscInt       n     = -1;
  PetscReal     *times = NULL;
  PetscErrorCode ierr;

  lastError[0] = 0;
  ierr         = SSStarHistoryParseSteps(PETSC_COMM_SELF, "-steps", text, nknots, knots, &n, &times);
  Expect((PetscBool)(ierr && strstr(lastError, expected)), text, lastError[0] ? lastError : "accepted");
  if (!ierr) PetscFree(times);
}

int main(int argc, char **argv)
{
  const PetscReal knots[3] = {0, 1, 2}, nan = (PetscReal)NAN;
  PetscReal       v[3];

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(Accepted());
  PetscCall(FromOptions());
  PetscCall(Steps());

  PetscCall(PetscPushErrorHandler(CaptureError, NULL));
  Refused("", 3, "Option -traction_top has an empty value: give x,y,z, or knots t:x,y,z separated by ';'");
  Refused("   ", 3, "Option -traction_top has an empty value");
  Refused(NULL, 3, "Option -traction_top needs a value: x,y,z, or knots t:x,y,z separated by ';'");
  Refused("1,2", 3, "Option -traction_top: 2 comma-separated values, expected 3 (x,y,z), or knots t:x,y,z separated by ';'");
  Refused("0:0,0", 3, "Option -traction_top: knot 1 \"0:0,0\": 2 values, expected 3 (t:x,y,z)");
  Refused("0:0,0,0;1:0,0,0,0", 3, "knot 2 \"1:0,0,0,0\": 4 values, expected 3 (t:x,y,z)");
  Refused("0:0;1:1,2", 1, "knot 2 \"1:1,2\": 2 values, expected 1 (t:v)");
  Refused("0:0,0,0;1", 3, "Option -traction_top: knot 2 \"1\" has no time: expected t:x,y,z");
  Refused("1,2,3;", 3, "knot 1 \"1,2,3\" has no time");
  Refused("0:0,0,0;;1:0,0,1", 3, "Option -traction_top: knot 2 is empty (two ';' in a row, or one at an end)");
  Refused("0:0,0,0;", 3, "knot 2 is empty");
  Refused("x:0,0,0", 3, "Option -traction_top: knot 1 \"x:0,0,0\": the time \"x\" is not a number");
  Refused(":0,0,0", 3, "the time \"\" is not a number");
  Refused("0:0,a,0", 3, "Option -traction_top: knot 1 \"0:0,a,0\": value 2 \"a\" is not a number");
  Refused("0:0,,0", 3, "value 2 \"\" is not a number");
  Refused("0:0,0,0:1", 3, "value 3 \"0:1\" is not a number");
  Refused("0:0,nan,0", 3, "value 2 \"nan\" is not a finite number");
  Refused("0,0,1e999", 3, "Option -traction_top: value 3 \"1e999\" is not a finite number");
  Refused("inf:0,0,0", 3, "the time \"inf\" is not a finite number");
  Refused("1:0,0,0;1:0,0,1", 3, "Option -traction_top: the times of the knots must increase: knot 2 at t = 1. follows knot 1 at t = 1.");
  Refused("0:0,0,0;2:0,0,0;1:0,0,1", 3, "knot 3 at t = 1. follows knot 2 at t = 2.");
  {
    PetscErrorCode ierr;
    SSStarHistory  h;

    ierr = SSStarHistoryCreateFromString(PETSC_COMM_SELF, "-traction_top", "0:0,0,0;1:1,1,1", 3, &h);
    lastError[0] = 0;
    if (!ierr) ierr = SSStarHistoryEvaluate(h, nan, v);
    Expect((PetscBool)(ierr && strstr(lastError, "is not a finite time")), "evaluation at NaN", lastError);
    SSStarHistoryDestroy(&h);
  }
  RefusedSteps("", 3, knots, "Option -steps has an empty value: give a count N of equal steps, or the times t1,t2,...");
  RefusedSteps("0", 3, knots, "Option -steps 0: needs at least one step");
  RefusedSteps("-3", 3, knots, "Option -steps -3: a count of equal steps is a whole number >= 1 (times are a list of two or more, t1,t2,...)");
  RefusedSteps("2.5", 3, knots, "Option -steps 2.5: a count of equal steps is a whole number >= 1");
  RefusedSteps("2.0", 3, knots, "Option -steps 2.0: a count of equal steps is a whole number >= 1");
  RefusedSteps("x", 3, knots, "Option -steps x: not a number (give a count N of equal steps, or the times t1,t2,...)");
  RefusedSteps("4", 0, NULL, "Option -steps 4: equal steps need load histories that span a time (knots t:x,y,z); no option has one");
  RefusedSteps("4", 1, knots, "they have a single time");
  RefusedSteps("1,x", 3, knots, "Option -steps: time 2 \"x\" is not a number (give a count N of equal steps, or the times t1,t2,...)");
  RefusedSteps("1,,2", 3, knots, "time 2 \"\" is not a number");
  RefusedSteps("1,nan", 3, knots, "Option -steps: time 2 \"nan\" is not a finite number");
  RefusedSteps("1,1", 3, knots, "Option -steps: the times must increase: time 2 (1.) follows time 1 (1.)");
  RefusedSteps("0.5,2,1", 3, knots, "time 3 (1.) follows time 2 (2.)");
  PetscCall(PetscPopErrorHandler());

  PetscCall(PetscPrintf(PETSC_COMM_SELF, "%s: %d failures\n", failures ? "FAILED" : "OK", failures));
  PetscCall(PetscFinalize());
  return failures ? 1 : 0;
}
