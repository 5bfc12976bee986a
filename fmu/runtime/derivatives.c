/* Directional derivatives through the model's hook (derivatives.h). */
#include "derivatives.h"

#include "call_table.h"
#include "logging.h"
#include "model_interface.h"
#include "variables.h"

#ifndef FMU_PROVIDES_DIRECTIONAL_DERIVATIVE
#define FMU_PROVIDES_DIRECTIONAL_DERIVATIVE 0
#endif

#if FMU_PROVIDES_DIRECTIONAL_DERIVATIVE
#if FMU_MODEL_EXCHANGE
/* A Model Exchange unit's knowns are its states too (runtime/model_exchange.h). */
static int is_state(unsigned vr) {
    for (int i = 0; i < FMU_N_STATES; ++i)
        if (FMU_STATE_VR(i) == vr) return 1;
    return 0;
}
#else
static int is_state(unsigned vr) {
    (void)vr;
    return 0;
}
#endif

/* FMU_OK if every vr[i] is a Real variable of the causality (or, with states_too, a state), else
 * Error naming it. */
static fmu_status check_all(fmu_instance *inst, const char *function, const unsigned vr[], size_t n,
                            fmu_causality causality, int states_too, const char *what) {
    for (size_t i = 0; i < n; ++i) {
        const fmu_variable *var = fmu_variable_by_vr(vr[i]);
        if (states_too && var && is_state(vr[i])) continue;
        if (!var || var->type != FMU_REAL || var->causality != causality) {
            fmu_log(inst, FMU_ERROR, LOG_ERROR, "%s: value reference %u (%s) is not a Real %s",
                    function, vr[i], var ? var->name : "no variable", what);
            return FMU_ERROR;
        }
    }
    return FMU_OK;
}
/* The checks both calls share: call order, NULL arrays, each unknown a Real output and each known
 * a Real input (or state); in initialisation mode the outputs are made first. */
static fmu_status check_request(fmu_instance *inst, const unsigned unknown[], size_t n_unknown,
                                const unsigned known[], size_t n_known, const double seed[],
                                size_t n_seed, double sensitivity[], size_t n_sensitivity,
                                const char *function) {
    if (fmu_check_call(inst, CALL_GET_DIRECTIONAL_DERIVATIVE, function) != FMU_OK) return FMU_ERROR;
    if ((n_unknown > 0 && !unknown) || (n_known > 0 && !known) || (n_seed > 0 && !seed) ||
        (n_sensitivity > 0 && !sensitivity)) {
        fmu_log(inst, FMU_ERROR, LOG_ERROR,
                "%s: an array of value references, seeds or sensitivities is NULL for a nonzero "
                "count",
                function);
        return FMU_ERROR;
    }
    if (check_all(inst, function, unknown, n_unknown, FMU_OUTPUT_VAR, 0, "output") != FMU_OK ||
        check_all(inst, function, known, n_known, FMU_INPUT_VAR, FMU_MODEL_EXCHANGE,
                  FMU_MODEL_EXCHANGE ? "input or state" : "input") != FMU_OK)
        return FMU_ERROR;
    /* In initialisation mode the outputs (and what they are made from) may not exist yet. */
    if (inst->v.mode == MODE_INITIALIZATION && fmu_apply_initial_parameters(inst) != FMU_OK)
        return fmu_fail(inst);
    return FMU_OK;
}
#endif

fmu_status fmu_get_directional_derivative(fmu_instance *inst, const unsigned unknown[],
                                          size_t n_unknown, const unsigned known[], size_t n_known,
                                          const double seed[], double sensitivity[],
                                          const char *function) {
#if FMU_PROVIDES_DIRECTIONAL_DERIVATIVE
    const fmu_status checked = check_request(inst, unknown, n_unknown, known, n_known, seed,
                                             n_known, sensitivity, n_unknown, function);
    if (checked != FMU_OK) return checked;
    return model_directional_derivative(inst, unknown, n_unknown, known, n_known, seed, sensitivity,
                                        function);
#else
    (void)unknown;
    (void)n_unknown;
    (void)known;
    (void)n_known;
    (void)seed;
    (void)sensitivity;
    if (inst) fmu_log(inst, FMU_ERROR, LOG_ERROR, "%s is not supported by this FMU", function);
    return FMU_ERROR;
#endif
}

fmu_status fmu_get_adjoint_derivative(fmu_instance *inst, const unsigned unknown[],
                                      size_t n_unknown, const unsigned known[], size_t n_known,
                                      const double seed[], double sensitivity[],
                                      const char *function) {
#if FMU_PROVIDES_DIRECTIONAL_DERIVATIVE
    const fmu_status checked = check_request(inst, unknown, n_unknown, known, n_known, seed,
                                             n_unknown, sensitivity, n_known, function);
    if (checked != FMU_OK) return checked;
    /* Row j of J^T is column j of J: one directional derivative per known, with the unknowns
     * taken in chunks so that no buffer is allocated (a model that keeps its linearisation for
     * the current inputs, as the Model Exchange plant does, makes it once for all of them). */
    enum { CHUNK = 32 };
    double column[CHUNK];
    const double unit_seed = 1.0;
    fmu_status worst = FMU_OK;
    for (size_t j = 0; j < n_known; ++j) {
        double sum = 0.0;
        for (size_t first = 0; first < n_unknown; first += CHUNK) {
            const size_t m = n_unknown - first < CHUNK ? n_unknown - first : CHUNK;
            const fmu_status s = model_directional_derivative(inst, unknown + first, m, &known[j],
                                                              1, &unit_seed, column, function);
            if (s > FMU_WARNING) return s;
            if (s > worst) worst = s;
            for (size_t i = 0; i < m; ++i) sum += seed[first + i] * column[i];
        }
        sensitivity[j] = sum;
    }
    return worst;
#else
    (void)unknown;
    (void)n_unknown;
    (void)known;
    (void)n_known;
    (void)seed;
    (void)sensitivity;
    if (inst) fmu_log(inst, FMU_ERROR, LOG_ERROR, "%s is not supported by this FMU", function);
    return FMU_ERROR;
#endif
}
