/* FMI 2.0 layer (co-simulation here, Model Exchange in fmi2_me_functions.c): each fmi2* function translates its arguments onto one runtime
 * call (which checks the call order); it never touches the instance's fields. */
#include <string.h>

#include "fmi2Functions.h"
#include "derivatives.h"
#include "do_step.h"
#include "instance.h"
#include "logging.h"
#include "state.h"
#include "values.h"

#define INST ((fmu_instance *)c)
/* The runtime's statuses are numbered as fmi2Status. */
#define CALL(expression) return (fmi2Status)(expression)

static void log_fmi2(const void *callbacks, void *environment, const char *instance_name,
                     fmu_status status, const char *category, const char *message) {
    (void)environment;
    const fmi2CallbackFunctions *f = (const fmi2CallbackFunctions *)callbacks;
    if (f && f->logger)
        f->logger(f->componentEnvironment, instance_name, (fmi2Status)status, category, message);
}

static fmi2Status unsupported(fmi2Component c, const char *function) {
    if (c) fmu_log(INST, FMU_ERROR, LOG_ERROR, "%s is not supported by this FMU", function);
    return fmi2Error;
}

const char *fmi2GetTypesPlatform(void) { return fmi2TypesPlatform; }
const char *fmi2GetVersion(void) { return fmi2Version; }

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean loggingOn, size_t n,
                               const fmi2String categories[]) {
    CALL(fmu_set_debug_logging(INST, loggingOn, n, categories));
}

fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String guid,
                              fmi2String resourceLocation, const fmi2CallbackFunctions *functions,
                              fmi2Boolean visible, fmi2Boolean loggingOn) {
    (void)resourceLocation; /* the unit needs no resources */
    (void)visible;
    const char *problem = NULL;
    if (fmuType != (FMU_MODEL_EXCHANGE ? fmi2ModelExchange : fmi2CoSimulation))
        problem = FMU_MODEL_EXCHANGE ? "this FMU supports model exchange only"
                                     : "this FMU supports co-simulation only";
    else if (!guid || strcmp(guid, FMU_GUID) != 0) problem = "the GUID does not match " FMU_GUID;
    if (problem) {
        if (functions && functions->logger)
            functions->logger(functions->componentEnvironment, instanceName, fmi2Error,
                              "logStatusError", problem);
        return NULL;
    }
    return fmu_instantiate(instanceName, FMU_VERSION_2, log_fmi2, functions, NULL, loggingOn);
}

void fmi2FreeInstance(fmi2Component c) { fmu_free(INST); }

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean toleranceDefined, fmi2Real tolerance,
                               fmi2Real startTime, fmi2Boolean stopTimeDefined, fmi2Real stopTime) {
    (void)toleranceDefined;
    (void)tolerance;
    (void)stopTimeDefined;
    (void)stopTime;
    CALL(fmu_setup_experiment(INST, startTime));
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c) {
    CALL(fmu_enter_initialization(INST, 0, 0.0));
}
fmi2Status fmi2ExitInitializationMode(fmi2Component c) { CALL(fmu_exit_initialization(INST)); }
fmi2Status fmi2Terminate(fmi2Component c) { CALL(fmu_terminate(INST)); }
fmi2Status fmi2Reset(fmi2Component c) { CALL(fmu_reset(INST)); }

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                       fmi2Real value[]) {
    CALL(fmu_get_real(INST, vr, nvr, value));
}
fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          fmi2Integer value[]) {
    CALL(fmu_get_integer(INST, vr, nvr, value));
}
fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                       const fmi2Real value[]) {
    CALL(fmu_set_real(INST, vr, nvr, value));
}
fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          const fmi2Integer value[]) {
    CALL(fmu_set_integer(INST, vr, nvr, value));
}

/* Types without variables: only the empty call succeeds. */
#define NO_VARIABLES(Name, Type)                                                                 \
    fmi2Status fmi2Get##Name(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,         \
                             Type value[]) {                                                     \
        (void)vr;                                                                                \
        (void)value;                                                                             \
        return nvr == 0 ? fmi2OK                                                                 \
                        : unsupported(c, "fmi2Get" #Name " (there are no " #Name " variables)"); \
    }                                                                                            \
    fmi2Status fmi2Set##Name(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,         \
                             const Type value[]) {                                               \
        (void)vr;                                                                                \
        (void)value;                                                                             \
        return nvr == 0 ? fmi2OK                                                                 \
                        : unsupported(c, "fmi2Set" #Name " (there are no " #Name " variables)"); \
    }
NO_VARIABLES(Boolean, fmi2Boolean)
fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                         fmi2String value[]) {
    CALL(fmu_get_string(INST, vr, nvr, value));
}
fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                         const fmi2String value[]) {
    CALL(fmu_set_string(INST, vr, nvr, value));
}

fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate *state) {
    CALL(fmu_get_state(INST, (fmu_snapshot **)state));
}
fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate state) {
    CALL(fmu_set_state(INST, (const fmu_snapshot *)state));
}
fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate *state) {
    CALL(fmu_free_state(INST, (fmu_snapshot **)state));
}
fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate state, size_t *size) {
    CALL(fmu_serialized_size(INST, (const fmu_snapshot *)state, size));
}
fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate state, fmi2Byte bytes[],
                                 size_t size) {
    CALL(fmu_serialize_state(INST, (const fmu_snapshot *)state, (unsigned char *)bytes, size));
}
fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte bytes[], size_t size,
                                   fmi2FMUstate *state) {
    CALL(fmu_deserialize_state(INST, (const unsigned char *)bytes, size, (fmu_snapshot **)state));
}

fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference vUnknown[],
                                        size_t nUnknown, const fmi2ValueReference vKnown[],
                                        size_t nKnown, const fmi2Real dvKnown[],
                                        fmi2Real dvUnknown[]) {
    CALL(fmu_get_directional_derivative(INST, vUnknown, nUnknown, vKnown, nKnown, dvKnown,
                                        dvUnknown, "fmi2GetDirectionalDerivative"));
}

/* ---- model exchange: fmi2_me_functions.c ---- */

/* ---- co-simulation ---- */
fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                       const fmi2Integer order[], const fmi2Real value[]) {
    CALL(fmu_set_input_derivatives(INST, vr, nvr, order, value));
}

fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                        const fmi2Integer order[], fmi2Real value[]) {
    (void)vr;
    (void)nvr;
    (void)order;
    (void)value;
    return unsupported(c, "fmi2GetRealOutputDerivatives (maxOutputDerivativeOrder = 0)");
}

fmi2Status fmi2DoStep(fmi2Component c, fmi2Real currentCommunicationPoint,
                      fmi2Real communicationStepSize,
                      fmi2Boolean noSetFMUStatePriorToCurrentPoint) {
    (void)noSetFMUStatePriorToCurrentPoint;
    CALL(fmu_do_step(INST, currentCommunicationPoint, communicationStepSize));
}

fmi2Status fmi2CancelStep(fmi2Component c) { return unsupported(c, "fmi2CancelStep"); }

fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind s, fmi2Status *value) {
    if (s != fmi2DoStepStatus) return unsupported(c, "fmi2GetStatus for this status kind");
    int status = 0;
    const fmu_status r = fmu_get_step_status(INST, value ? &status : NULL);
    if (r == FMU_OK) *value = (fmi2Status)status;
    CALL(r);
}

fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real *value) {
    if (s != fmi2LastSuccessfulTime)
        return unsupported(c, "fmi2GetRealStatus for this status kind");
    CALL(fmu_get_last_successful_time(INST, value));
}

fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind s, fmi2Integer *value) {
    (void)s;
    (void)value;
    return unsupported(c, "fmi2GetIntegerStatus");
}

fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean *value) {
    if (s != fmi2Terminated) return unsupported(c, "fmi2GetBooleanStatus for this status kind");
    int status = 0; /* the unit never asks to terminate; the call order is still checked */
    const fmu_status r = fmu_get_step_status(INST, value ? &status : NULL);
    if (r == FMU_OK) *value = fmi2False;
    CALL(r);
}

fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind s, fmi2String *value) {
    (void)s;
    (void)value;
    return unsupported(c, "fmi2GetStringStatus");
}
