/* What the shapes share to read their option's value: numbers, unit vectors (errors name the option) */
#include "obstacleimpl.h"

/* The comma-separated numbers of a value: exactly n finite values */
PetscErrorCode SSStarObstacleParseNumbers(MPI_Comm comm, const char option[], const char spec[], const char numbers[], PetscInt n, const char form[], PetscReal v[])
{
  const char *s   = numbers;
  PetscInt    got = 0;

  PetscFunctionBegin;
  while (*s) {
    char     *end;
    PetscReal value = (PetscReal)strtod(s, &end);

    PetscCheck(end != s && (*end == ',' || !*end), comm, PETSC_ERR_ARG_WRONG, "Option %s %s: \"%s\" is not a list of numbers %s", option, spec, numbers, form);
    PetscCheck(got < n, comm, PETSC_ERR_ARG_WRONG, "Option %s %s needs %" PetscInt_FMT " comma-separated values %s (got more)", option, spec, n, form);
    PetscCheck(!PetscIsInfOrNanReal(value), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option %s %s: value %" PetscInt_FMT " is not a finite number (%g)", option, spec, got + 1, (double)value);
    v[got++] = value;
    s        = *end ? end + 1 : end;
  }
  PetscCheck(got == n, comm, PETSC_ERR_ARG_WRONG, "Option %s %s needs %" PetscInt_FMT " comma-separated values %s (got %" PetscInt_FMT ")", option, spec, n, form, got);
  PetscFunctionReturn(0);
}

/* A unit vector from v (what: its name in the message), refused when zero */
PetscErrorCode SSStarObstacleUnitVector(MPI_Comm comm, const char option[], const char spec[], const char what[], const PetscReal v[3], PetscReal u[3])
{
  const PetscReal len = PetscSqrtReal(SSStarDot3(v, v));

  PetscFunctionBegin;
  PetscCheck(len > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option %s %s: the %s (%g, %g, %g) is zero", option, spec, what, (double)v[0], (double)v[1], (double)v[2]);
  for (PetscInt k = 0; k < 3; k++) u[k] = v[k] / len;
  PetscFunctionReturn(0);
}
