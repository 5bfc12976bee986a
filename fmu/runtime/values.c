/* Get and set through the variable table (variables.h); outputs come from the model. */
#include "values.h"

#include <math.h>
#include <string.h>

#include "call_table.h"
#include "logging.h"
#include "model_interface.h"

static fmu_status bad_vr(fmu_instance *inst, const char *what, unsigned vr) {
    fmu_log(inst, FMU_ERROR, LOG_ERROR, "%s: value reference %u is not a variable of that type",
            what, vr);
    return FMU_ERROR;
}

static fmu_status null_arrays(fmu_instance *inst, const char *what) {
    fmu_log(inst, FMU_ERROR, LOG_ERROR,
            "%s: the array of value references or of values is NULL for a nonzero count", what);
    return FMU_ERROR;
}

/* Outputs asked for: the model makes them those of the current inputs. Discard and Warning are
 * reported by the status outputs; the values returned are well defined. */
fmu_status fmu_refresh_outputs(fmu_instance *inst) {
    fmu_values *v = &inst->v;
    if (v->outputs_current || !(v->mode & (MODE_INITIALIZATION | MODES_RUNNING))) return FMU_OK;
    if (v->mode == MODE_INITIALIZATION && fmu_apply_initial_parameters(inst) != FMU_OK)
        return fmu_fail(inst);
    if (model_refresh_outputs(inst) == FMU_ERROR) return fmu_fail(inst);
    return FMU_OK;
}

/* The descriptor of vr if it is a variable of `type`, else NULL after an Error message. */
static const fmu_variable *typed(fmu_instance *inst, const char *what, unsigned vr, fmu_type type) {
    const fmu_variable *var = fmu_variable_by_vr(vr);
    if (!var || var->type != type) {
        bad_vr(inst, what, vr);
        return NULL;
    }
    return var;
}

/* vr, a variable of `type` whose value may be read now: an output brought up to date first (the
 * test that the outputs are current here: most reads need no call). 0 after an Error message. */
static int readable(fmu_instance *inst, const char *what, unsigned vr, fmu_type type) {
    const fmu_variable *var = typed(inst, what, vr, type);
    if (!var) return 0;
    return var->causality != FMU_OUTPUT_VAR || inst->v.outputs_current == 1 ||
           fmu_refresh_outputs(inst) == FMU_OK;
}

/* The checks of a get of n values of `type`: the call allowed now, the arrays given, and every
 * vr a variable of that type whose value may be read (outputs brought up to date). */
static fmu_status readable_all(fmu_instance *inst, const char *what, fmu_type type,
                               const unsigned vr[], size_t n, const void *value) {
    if (fmu_check_call(inst, CALL_GET, what) != FMU_OK) return FMU_ERROR;
    if (n > 0 && (!vr || !value)) return null_arrays(inst, what);
    for (size_t i = 0; i < n; ++i)
        if (!readable(inst, what, vr[i], type)) return FMU_ERROR;
    return FMU_OK;
}

fmu_status fmu_get_real(fmu_instance *inst, const unsigned vr[], size_t n, double value[]) {
    if (readable_all(inst, "GetReal", FMU_REAL, vr, n, value) != FMU_OK) return FMU_ERROR;
    for (size_t i = 0; i < n; ++i) value[i] = inst->v.real[vr[i]];
    return FMU_OK;
}

fmu_status fmu_get_integer(fmu_instance *inst, const unsigned vr[], size_t n, int32_t value[]) {
    if (readable_all(inst, "GetInteger", FMU_INTEGER, vr, n, value) != FMU_OK) return FMU_ERROR;
    for (size_t i = 0; i < n; ++i) value[i] = inst->v.integer[vr[i]];
    return FMU_OK;
}

/* Whether var may be set now: inputs in any mode before Terminate, parameters (fixed) only
 * before the end of initialisation; outputs and time never. */
static int settable_now(const fmu_instance *inst, const fmu_variable *var) {
    return var->causality == FMU_INPUT_VAR ||
           (var->causality == FMU_PARAMETER_VAR &&
            (inst->v.mode & (MODE_INSTANTIATED | MODE_INITIALIZATION)));
}

/* Element i of a set call's values as a double (an Int32 converts exactly). */
static double given(fmu_type type, const void *value, size_t i) {
    return type == FMU_REAL ? ((const double *)value)[i] : ((const int32_t *)value)[i];
}

/* The checks of a set of n values of `type`, all made before any value is written (the call
 * allowed now and the arrays given first): every vr a variable of that type that may be set now,
 * and every value within the variable's declared min and max. A declared range belongs to one
 * variable alone, so the order in which a master sets values cannot make a valid value look out
 * of range: it is refused at the call that gives it, naming it (checks across variables, such as
 * stroke_min < stroke_max, are the model's, at the end of initialisation). */
static fmu_status check_settable(fmu_instance *inst, const char *what, const unsigned vr[],
                                 size_t n, fmu_type type, const void *value) {
    if (fmu_check_call(inst, CALL_SET, what) != FMU_OK) return FMU_ERROR;
    if (n > 0 && (!vr || !value)) return null_arrays(inst, what);
    for (size_t i = 0; i < n; ++i) {
        const fmu_variable *var = typed(inst, what, vr[i], type);
        if (!var) return FMU_ERROR;
        if (!settable_now(inst, var)) {
            fmu_log(inst, FMU_ERROR, LOG_ERROR, "%s: variable %s cannot be set in %s", what,
                    var->name, fmu_mode_name(inst->v.mode));
            return FMU_ERROR;
        }
        if (type == FMU_STRING) continue; /* a path or a name: no range */
        const double x = given(type, value, i);
        if (!fmu_within_range(var, x)) {
            fmu_log(inst, FMU_ERROR, LOG_ERROR,
                    "%s: " FMU_OUT_OF_RANGE_FORMAT " (none of this call's values is set)", what,
                    var->name, x, var->min, var->max);
            return FMU_ERROR;
        }
    }
    return FMU_OK;
}

fmu_status fmu_set_real(fmu_instance *inst, const unsigned vr[], size_t n, const double value[]) {
    if (check_settable(inst, "SetReal", vr, n, FMU_REAL, value) != FMU_OK) return FMU_ERROR;
    int nonfinite = 0;
    for (size_t i = 0; i < n; ++i) {
        inst->v.real[vr[i]] = value[i];
        nonfinite |= !isfinite(value[i]);
    }
    /* checked here, where the values pass anyway, so that a step need not look at every input */
    if (nonfinite) inst->v.inputs_unchecked = 1;
    if (n > 0) inst->v.outputs_current = 0;
    return FMU_OK;
}

fmu_status fmu_set_integer(fmu_instance *inst, const unsigned vr[], size_t n,
                           const int32_t value[]) {
    if (check_settable(inst, "SetInteger", vr, n, FMU_INTEGER, value) != FMU_OK) return FMU_ERROR;
    for (size_t i = 0; i < n; ++i) inst->v.integer[vr[i]] = value[i];
    if (n > 0) inst->v.outputs_current = 0;
    return FMU_OK;
}

fmu_status fmu_get_string(fmu_instance *inst, const unsigned vr[], size_t n, const char *value[]) {
    if (fmu_check_call(inst, CALL_GET, "GetString") != FMU_OK) return FMU_ERROR;
    if (n > 0 && (!vr || !value)) return null_arrays(inst, "GetString");
    for (size_t i = 0; i < n; ++i) {
        if (!typed(inst, "GetString", vr[i], FMU_STRING)) return FMU_ERROR;
#if FMU_STRING_PARAMETERS
        value[i] = model_string(&inst->v, vr[i]);
#endif
    }
    return FMU_OK;
}

fmu_status fmu_set_string(fmu_instance *inst, const unsigned vr[], size_t n,
                          const char *const value[]) {
    if (check_settable(inst, "SetString", vr, n, FMU_STRING, value) != FMU_OK) return FMU_ERROR;
#if FMU_STRING_PARAMETERS
    for (size_t i = 0; i < n; ++i)
        if (!value[i] || strlen(value[i]) >= FMU_STRING_SIZE) {
            fmu_log(inst, FMU_ERROR, LOG_ERROR, "SetString: %s is %s: give at most %d bytes",
                    fmu_variable_by_vr(vr[i])->name, value[i] ? "too long" : "NULL",
                    FMU_STRING_SIZE - 1);
            return FMU_ERROR;
        }
    for (size_t i = 0; i < n; ++i) /* memmove: a master may pass back GetString's own pointer */
        memmove(model_string(&inst->v, vr[i]), value[i], strlen(value[i]) + 1);
    if (n > 0) inst->v.outputs_current = 0;
#endif
    return FMU_OK;
}

fmu_status fmu_set_input_derivatives(fmu_instance *inst, const unsigned vr[], size_t n,
                                     const int order[], const double value[]) {
    if (fmu_check_call(inst, CALL_SET_INPUT_DERIVATIVES, "SetRealInputDerivatives") != FMU_OK)
        return FMU_ERROR;
    if (n > 0 && (!vr || !order || !value)) return null_arrays(inst, "SetRealInputDerivatives");
    const fmu_status s = model_set_input_derivatives(inst, vr, n, order, value);
    if (s == FMU_OK && n > 0) inst->v.outputs_current = 0;
    return s;
}
