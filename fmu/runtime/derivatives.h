/* Directional derivatives (fmi2GetDirectionalDerivative, fmi3GetDirectionalDerivative) and their
 * adjoint (fmi3GetAdjointDerivative): the
 * call-order and argument checks, then the model's hook (model_interface.h) if its config.h
 * declares FMU_PROVIDES_DIRECTIONAL_DERIVATIVE; else the call is not supported (Error). */
#ifndef STEWART_FMU_DERIVATIVES_H
#define STEWART_FMU_DERIVATIVES_H

#include <stddef.h>

#include "instance.h"

#ifdef __cplusplus
extern "C" {
#endif

/* sensitivity[i] = sum_j d unknown[i] / d known[j] * seed[j] at the current inputs: every unknown
 * a Real output (a Model Exchange unit's state derivatives are outputs), every known a Real input
 * or a Model Exchange unit's state (else Error naming it). `function` names the caller
 * in messages. */
fmu_status fmu_get_directional_derivative(fmu_instance *inst, const unsigned unknown[],
                                          size_t n_unknown, const unsigned known[], size_t n_known,
                                          const double seed[], double sensitivity[],
                                          const char *function);

/* sensitivity[j] = sum_i seed[i] * d unknown[i] / d known[j] (FMI 3's adjoint: one seed per
 * unknown, one sensitivity per known), from one directional derivative per known; the same
 * checks and messages as fmu_get_directional_derivative. */
fmu_status fmu_get_adjoint_derivative(fmu_instance *inst, const unsigned unknown[],
                                      size_t n_unknown, const unsigned known[], size_t n_known,
                                      const double seed[], double sensitivity[],
                                      const char *function);

#ifdef __cplusplus
}
#endif

#endif
