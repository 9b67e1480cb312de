/*
   The law "coulomb": |r_t| <= phi r_n, r_t = -phi r_n u_t/|u_t| where the node slides (docs/derivation.md section 0):
   the threshold of the tangential step is phi r_n (1.2), a sliding node's W = phi r_n/|d_t| (I - om om^T) with the
   coupling phi om (3.1), and phi = 0 is frictionless.
*/
#include "lawimpl.h"

/* value[0] = phi */

static void Tangential_Coulomb(const SSStarFriction *fr, PetscReal rn, const PetscReal v[2], PetscReal d[2])
{
  SSStarSoftThreshold(fr->value[0] * rn, v, d);
}

static PetscReal Margin_Coulomb(const SSStarFriction *fr, const PetscReal b[3])
{
  return -fr->value[0] * b[2] - PetscSqrtReal(b[0] * b[0] + b[1] * b[1]);
}

static void Sliding_Coulomb(const SSStarFriction *fr, const PetscReal d[3], const PetscReal b[3], PetscReal W[4], PetscReal k[2])
{
  SSStarIsotropicSliding(-fr->value[0] * b[2], fr->value[0], d, W, k);
}

static PetscBool Frictionless_Coulomb(const SSStarFriction *fr)
{
  return (PetscBool)(fr->value[0] == 0.0);
}

static void Cone_Coulomb(const SSStarFriction *fr, PetscReal D[4])
{
  D[0] = D[3] = fr->value[0];
  D[1] = D[2] = 0;
}

PetscErrorCode SSStarLawCreate_Coulomb(SSStarLaw law)
{
  PetscFunctionBegin;
  law->label                 = "Coulomb";
  law->effect                = "Coulomb friction";
  law->nparams               = 1;
  law->params[0].name        = "friction";
  law->params[0].description = "friction coefficient";
  law->params[0].symbol      = "phi";
  law->params[0].kind        = SSSTAR_LAW_COEFFICIENT;
  law->params[0].hasDefault  = PETSC_TRUE;
  law->params[0].defaultValue = 0.3;
  law->coupled               = PETSC_TRUE;
  law->separate              = PETSC_FALSE;
  law->ops.tangential        = Tangential_Coulomb;
  law->ops.margin            = Margin_Coulomb;
  law->ops.sliding           = Sliding_Coulomb;
  law->ops.frictionless      = Frictionless_Coulomb;
  law->ops.cone              = Cone_Coulomb;
  PetscFunctionReturn(0);
}
