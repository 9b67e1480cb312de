/*
   The law "none": frictionless contact, Q(u) = {0} x N_R+(u3) (docs/derivation.md section 0): no tangential force, the
   tangential step leaves v = u_t - c_t as it is, and every node in strong contact slides.
*/
#include "lawimpl.h"

static void Tangential_None(const SSStarFriction *fr, PetscReal rn, const PetscReal v[2], PetscReal d[2])
{
  d[0] = v[0];
  d[1] = v[1];
}

static PetscReal Margin_None(const SSStarFriction *fr, const PetscReal b[3])
{
  return -PetscSqrtReal(b[0] * b[0] + b[1] * b[1]); /* the friction set is {0} */
}

static void Sliding_None(const SSStarFriction *fr, const PetscReal d[3], const PetscReal b[3], PetscReal W[4], PetscReal k[2])
{
  SSStarIsotropicSliding(0.0, 0.0, d, W, k);
}

static PetscBool Frictionless_None(const SSStarFriction *fr)
{
  return PETSC_TRUE;
}

static void Cone_None(const SSStarFriction *fr, PetscReal D[4])
{
  D[0] = D[1] = D[2] = D[3] = 0;
}

PetscErrorCode SSStarLawCreate_None(SSStarLaw law)
{
  PetscFunctionBegin;
  law->label            = "frictionless";
  law->effect           = NULL;
  law->nparams          = 0;
  law->coupled          = PETSC_FALSE;
  law->separate         = PETSC_FALSE;
  law->ops.tangential   = Tangential_None;
  law->ops.margin       = Margin_None;
  law->ops.sliding      = Sliding_None;
  law->ops.frictionless = Frictionless_None;
  law->ops.cone         = Cone_None;
  PetscFunctionReturn(0);
}
