/* FMU state: a snapshot is the instance's plain values plus the bytes of the model's resources
 * (model_save); restoring loads them (model_load). The same bytes are the serialised form. */
#include "state.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "call_table.h"
#include "logging.h"
#include "model_interface.h"

struct fmu_snapshot {
    fmu_values v;
    unsigned char *bytes; /* the model's saved resources (model_save), size bytes */
    size_t size;
    size_t capacity;
};

static int reserve(fmu_snapshot *s, size_t size) {
    if (size <= s->capacity) return 1;
    unsigned char *b = (unsigned char *)realloc(s->bytes, size);
    if (!b) return 0;
    s->bytes = b;
    s->capacity = size;
    return 1;
}

fmu_status fmu_get_state(fmu_instance *inst, fmu_snapshot **state) {
    if (fmu_check_call(inst, CALL_GET_FMU_STATE, "GetFMUState") != FMU_OK) return FMU_ERROR;
    if (!state) {
        fmu_log(inst, FMU_ERROR, LOG_ERROR, "GetFMUState: the pointer to the state is NULL");
        return FMU_ERROR;
    }
    fmu_snapshot *s = *state ? *state : (fmu_snapshot *)calloc(1, sizeof *s);
    const size_t size = model_state_size(inst);
    if (!s || !reserve(s, size)) {
        if (s != *state) free(s);
        fmu_log(inst, FMU_ERROR, LOG_ERROR, "GetFMUState: out of memory");
        return FMU_ERROR;
    }
    if (size && model_save(inst, s->bytes, size) != FMU_OK) {
        if (s != *state) fmu_free_state(inst, &s);
        fmu_log(inst, FMU_ERROR, LOG_ERROR, "GetFMUState: cannot save the model's state");
        return FMU_ERROR;
    }
    s->size = size;
    s->v = inst->v;
    *state = s;
    return FMU_OK;
}

fmu_status fmu_set_state(fmu_instance *inst, const fmu_snapshot *s) {
    if (fmu_check_call(inst, CALL_SET_FMU_STATE, "SetFMUState") != FMU_OK) return FMU_ERROR;
    if (!s) {
        fmu_log(inst, FMU_ERROR, LOG_ERROR, "SetFMUState: the state is NULL");
        return FMU_ERROR;
    }
    const fmu_values before = inst->v;
    inst->v = s->v;
    /* after initialisation the resources for the state's parameters come first (allocation is
     * fine here: this is not a step), then the model loads its bytes into them */
    if ((fmu_after_initialization(&inst->v) && model_apply_parameters(inst) != FMU_OK) ||
        model_load(inst, s->bytes, s->size) != FMU_OK) {
        /* the model said why; its resources may already be those of the state's parameters,
         * so the instance cannot go on from its old values: Error (Reset or another state) */
        inst->v = before;
        return fmu_fail(inst);
    }
    return FMU_OK;
}

fmu_status fmu_free_state(fmu_instance *inst, fmu_snapshot **state) {
    if (fmu_check_call(inst, CALL_FREE_FMU_STATE, "FreeFMUState") != FMU_OK) return FMU_ERROR;
    if (!state || !*state) return FMU_OK;
    free((*state)->bytes);
    free(*state);
    *state = NULL;
    return FMU_OK;
}

/* Serialised form: magic, sizeof(fmu_values), the values, then the size of the model's saved
 * resources and their bytes (0 bytes before the model has built any). */
static const unsigned char kMagic[8] = {'S', 'T', 'W', 'F', 'M', 'U', '0', '3'};
enum { HEADER = sizeof kMagic + sizeof(uint64_t) + sizeof(fmu_values) + sizeof(uint64_t) };

fmu_status fmu_serialized_size(fmu_instance *inst, const fmu_snapshot *s, size_t *size) {
    if (fmu_check_call(inst, CALL_SERIALIZE, "SerializedFMUStateSize") != FMU_OK) return FMU_ERROR;
    if (!s || !size) {
        fmu_log(inst, FMU_ERROR, LOG_ERROR, "SerializedFMUStateSize: the %s is NULL",
                !s ? "state" : "size pointer");
        return FMU_ERROR;
    }
    *size = HEADER + s->size;
    return FMU_OK;
}

fmu_status fmu_serialize_state(fmu_instance *inst, const fmu_snapshot *s, unsigned char *out,
                               size_t size) {
    if (fmu_check_call(inst, CALL_SERIALIZE, "SerializeFMUState") != FMU_OK) return FMU_ERROR;
    if (!s || !out || size < HEADER + s->size) {
        fmu_log(inst, FMU_ERROR, LOG_ERROR, "SerializeFMUState: %s",
                !s     ? "the state is NULL"
                : !out ? "the buffer is NULL"
                       : "the buffer is smaller than SerializedFMUStateSize");
        return FMU_ERROR;
    }
    const uint64_t n = sizeof(fmu_values), data_size = s->size;
    memcpy(out, kMagic, sizeof kMagic);
    memcpy(out + sizeof kMagic, &n, sizeof n);
    memcpy(out + sizeof kMagic + sizeof n, &s->v, sizeof s->v);
    memcpy(out + HEADER - sizeof data_size, &data_size, sizeof data_size);
    if (s->size) memcpy(out + HEADER, s->bytes, s->size);
    return FMU_OK;
}

/* Whether a Real input of v is not finite. */
static int any_nonfinite_input(const fmu_values *v) {
    for (size_t j = 0; j < fmu_n_variables; ++j) {
        const fmu_variable *var = &fmu_variables[j];
        if (var->causality == FMU_INPUT_VAR && var->type == FMU_REAL && !isfinite(v->real[var->vr]))
            return 1;
    }
    return 0;
}

/* Why the runtime's part of deserialised values cannot be a state, or NULL if it can. */
static const char *corrupt_values(const fmu_values *v) {
    const int modes = MODE_INSTANTIATED | MODE_INITIALIZATION | MODE_AFTER_INITIALIZATION |
                      (FMU_MODEL_EXCHANGE ? MODE_CONTINUOUS_TIME : 0) | MODE_TERMINATED;
    if (!(v->mode & modes) || (v->mode & ~modes) || (v->mode & (v->mode - 1)))
        return FMU_MODEL_EXCHANGE
                   ? "mode is not one of instantiated, initialization, event, continuous time, "
                     "terminated"
                   : "mode is not one of instantiated, initialization, step, terminated";
    if ((v->outputs_current & ~1) || (v->has_stepped & ~1) || (v->inputs_unchecked & ~1) ||
        v->last_step_status < FMU_OK || v->last_step_status > FMU_ERROR)
        return "a flag is out of range";
    if (!isfinite(v->time) || !isfinite(v->last_successful_time) || !isfinite(v->last_step_point))
        return "time is not finite";
    if (v->real[fmu_time_vr] != v->time) return "the time variable is not the unit's time";
    if (v->has_stepped && !(v->last_step_point < v->time))
        return "the last step's communication point is not before the current time";
    if ((v->mode & (MODE_INSTANTIATED | MODE_INITIALIZATION)) &&
        (v->has_stepped || v->last_step_point != 0 || v->last_step_status != FMU_OK))
        return "a unit before the end of initialisation has a step behind it";
    return NULL;
}

/* The first parameter or input of v outside its declared range (as a set would refuse it), or
 * NULL. */
static const fmu_variable *outside_declared_range(const fmu_values *v) {
    for (size_t j = 0; j < fmu_n_variables; ++j) {
        const fmu_variable *var = &fmu_variables[j];
        if (var->causality != FMU_INPUT_VAR && var->causality != FMU_PARAMETER_VAR) continue;
        if (!fmu_within_range(var, var->type == FMU_REAL ? v->real[var->vr] : v->integer[var->vr]))
            return var;
    }
    return NULL;
}

fmu_status fmu_deserialize_state(fmu_instance *inst, const unsigned char *in, size_t size,
                                 fmu_snapshot **state) {
    if (fmu_check_call(inst, CALL_SERIALIZE, "DeserializeFMUState") != FMU_OK) return FMU_ERROR;
    uint64_t n = 0, data_size = 0;
    if (in && size >= HEADER) {
        memcpy(&n, in + sizeof kMagic, sizeof n);
        memcpy(&data_size, in + HEADER - sizeof data_size, sizeof data_size);
    }
    if (!in || !state || size < HEADER || memcmp(in, kMagic, sizeof kMagic) ||
        n != sizeof(fmu_values) || data_size != size - HEADER) {
        fmu_log(inst, FMU_ERROR, LOG_ERROR,
                "DeserializeFMUState: %zu bytes are not a state of this FMU", size);
        return FMU_ERROR;
    }
    fmu_values v;
    memcpy(&v, in + sizeof kMagic + sizeof n, sizeof v);
    char why[256];
    const char *corrupt = corrupt_values(&v);
    const fmu_variable *outside = corrupt ? NULL : outside_declared_range(&v);
    if (outside) {
        const double x = outside->type == FMU_REAL ? v.real[outside->vr] : v.integer[outside->vr];
        fmu_log(inst, FMU_ERROR, LOG_ERROR,
                "DeserializeFMUState: corrupt state: " FMU_OUT_OF_RANGE_FORMAT, outside->name, x,
                outside->min, outside->max);
        return FMU_ERROR;
    }
    if (!corrupt) corrupt = model_check_state(inst, &v, in + HEADER, data_size, why, sizeof why);
    if (corrupt) {
        fmu_log(inst, FMU_ERROR, LOG_ERROR, "DeserializeFMUState: corrupt state: %s", corrupt);
        return FMU_ERROR;
    }
    fmu_snapshot *s = *state ? *state : (fmu_snapshot *)calloc(1, sizeof *s);
    if (!s || !reserve(s, data_size)) {
        if (s != *state) free(s);
        fmu_log(inst, FMU_ERROR, LOG_ERROR, "DeserializeFMUState: out of memory");
        return FMU_ERROR;
    }
    s->v = v;
    /* the bytes' claim that every input is finite is not taken on trust */
    if (any_nonfinite_input(&v)) s->v.inputs_unchecked = 1;
    if (data_size) memcpy(s->bytes, in + HEADER, data_size);
    s->size = data_size;
    *state = s;
    return FMU_OK;
}
