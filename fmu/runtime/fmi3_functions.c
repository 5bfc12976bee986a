/* FMI 3.0 layer (co-simulation here, Model Exchange in fmi3_me_functions.c): each fmi3* function translates its arguments onto one runtime
 * call (which checks the call order); it never touches the instance's fields. */
#include <string.h>

#include "fmi3Functions.h"
#include "derivatives.h"
#include "do_step.h"
#include "instance.h"
#include "logging.h"
#include "state.h"
#include "values.h"

#define INST ((fmu_instance *)instance)
/* The runtime's statuses are numbered as fmi3Status. */
#define CALL(expression) return (fmi3Status)(expression)

static void log_fmi3(const void *callbacks, void *environment, const char *instance_name,
                     fmu_status status, const char *category, const char *message) {
    (void)instance_name;
    fmi3LogMessageCallback cb = (fmi3LogMessageCallback)(uintptr_t)callbacks;
    if (cb) cb(environment, (fmi3Status)status, category, message);
}

static fmi3Status unsupported(fmi3Instance instance, const char *function) {
    if (instance) fmu_log(INST, FMU_ERROR, LOG_ERROR, "%s is not supported by this FMU", function);
    return fmi3Error;
}

const char *fmi3GetVersion(void) { return fmi3Version; }

fmi3Status fmi3SetDebugLogging(fmi3Instance instance, fmi3Boolean loggingOn, size_t nCategories,
                               const fmi3String categories[]) {
    CALL(fmu_set_debug_logging(INST, loggingOn, nCategories, categories));
}

/* A new instance if the token matches and the interface is the unit's, else NULL after telling
 * the logger why. */
static fmi3Instance instantiate(fmi3String instanceName, fmi3String instantiationToken,
                                int model_exchange, fmi3Boolean loggingOn,
                                fmi3InstanceEnvironment instanceEnvironment,
                                fmi3LogMessageCallback logMessage, const char *problem) {
    if (!problem && model_exchange != FMU_MODEL_EXCHANGE)
        problem = FMU_MODEL_EXCHANGE ? "this FMU supports model exchange only"
                                     : "this FMU supports co-simulation only";
    if (!problem && (!instantiationToken || strcmp(instantiationToken, FMU_GUID) != 0))
        problem = "the instantiationToken does not match " FMU_GUID;
    if (problem) {
        if (logMessage) logMessage(instanceEnvironment, fmi3Error, "logStatusError", problem);
        return NULL;
    }
    return fmu_instantiate(instanceName, FMU_VERSION_3, log_fmi3,
                           (const void *)(uintptr_t)logMessage, instanceEnvironment, loggingOn);
}

fmi3Instance fmi3InstantiateModelExchange(fmi3String instanceName, fmi3String instantiationToken,
                                          fmi3String resourcePath, fmi3Boolean visible,
                                          fmi3Boolean loggingOn,
                                          fmi3InstanceEnvironment instanceEnvironment,
                                          fmi3LogMessageCallback logMessage) {
    (void)resourcePath; /* the unit needs no resources */
    (void)visible;
    return instantiate(instanceName, instantiationToken, 1, loggingOn, instanceEnvironment,
                       logMessage, NULL);
}

fmi3Instance fmi3InstantiateCoSimulation(
    fmi3String instanceName, fmi3String instantiationToken, fmi3String resourcePath,
    fmi3Boolean visible, fmi3Boolean loggingOn, fmi3Boolean eventModeUsed,
    fmi3Boolean earlyReturnAllowed, const fmi3ValueReference requiredIntermediateVariables[],
    size_t nRequiredIntermediateVariables, fmi3InstanceEnvironment instanceEnvironment,
    fmi3LogMessageCallback logMessage, fmi3IntermediateUpdateCallback intermediateUpdate) {
    (void)resourcePath; /* the unit needs no resources */
    (void)visible;
    (void)earlyReturnAllowed;
    (void)requiredIntermediateVariables;
    (void)nRequiredIntermediateVariables;
    (void)intermediateUpdate;
    return instantiate(instanceName, instantiationToken, 0, loggingOn, instanceEnvironment,
                       logMessage,
                       eventModeUsed && !FMU_MODEL_EXCHANGE
                           ? "this FMU has no event mode (hasEventMode = false)"
                           : NULL);
}

fmi3Instance fmi3InstantiateScheduledExecution(
    fmi3String instanceName, fmi3String instantiationToken, fmi3String resourcePath,
    fmi3Boolean visible, fmi3Boolean loggingOn, fmi3InstanceEnvironment instanceEnvironment,
    fmi3LogMessageCallback logMessage, fmi3ClockUpdateCallback clockUpdate,
    fmi3LockPreemptionCallback lockPreemption, fmi3UnlockPreemptionCallback unlockPreemption) {
    (void)instanceName;
    (void)instantiationToken;
    (void)resourcePath;
    (void)visible;
    (void)loggingOn;
    (void)clockUpdate;
    (void)lockPreemption;
    (void)unlockPreemption;
    if (logMessage)
        logMessage(instanceEnvironment, fmi3Error, "logStatusError",
                   "this FMU supports co-simulation only");
    return NULL;
}

void fmi3FreeInstance(fmi3Instance instance) { fmu_free(INST); }

fmi3Status fmi3EnterInitializationMode(fmi3Instance instance, fmi3Boolean toleranceDefined,
                                       fmi3Float64 tolerance, fmi3Float64 startTime,
                                       fmi3Boolean stopTimeDefined, fmi3Float64 stopTime) {
    (void)toleranceDefined;
    (void)tolerance;
    (void)stopTimeDefined;
    (void)stopTime;
    CALL(fmu_enter_initialization(INST, 1, startTime));
}

fmi3Status fmi3ExitInitializationMode(fmi3Instance instance) {
    CALL(fmu_exit_initialization(INST));
}

fmi3Status fmi3Terminate(fmi3Instance instance) { CALL(fmu_terminate(INST)); }
fmi3Status fmi3Reset(fmi3Instance instance) { CALL(fmu_reset(INST)); }

static fmi3Status check_counts(fmi3Instance instance, const char *f, size_t nvr, size_t nv) {
    if (nvr == nv) return fmi3OK;
    if (instance)
        fmu_log(INST, FMU_ERROR, LOG_ERROR,
                "%s: nValues = %zu must equal nValueReferences = %zu "
                "(all variables are scalars)",
                f, nv, nvr);
    return fmi3Error;
}

fmi3Status fmi3GetFloat64(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,
                          fmi3Float64 values[], size_t nValues) {
    if (check_counts(instance, "fmi3GetFloat64", nvr, nValues) != fmi3OK) return fmi3Error;
    CALL(fmu_get_real(INST, vr, nvr, values));
}

fmi3Status fmi3GetInt32(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,
                        fmi3Int32 values[], size_t nValues) {
    if (check_counts(instance, "fmi3GetInt32", nvr, nValues) != fmi3OK) return fmi3Error;
    CALL(fmu_get_integer(INST, vr, nvr, values));
}

fmi3Status fmi3SetFloat64(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,
                          const fmi3Float64 values[], size_t nValues) {
    if (check_counts(instance, "fmi3SetFloat64", nvr, nValues) != fmi3OK) return fmi3Error;
    CALL(fmu_set_real(INST, vr, nvr, values));
}

fmi3Status fmi3SetInt32(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,
                        const fmi3Int32 values[], size_t nValues) {
    if (check_counts(instance, "fmi3SetInt32", nvr, nValues) != fmi3OK) return fmi3Error;
    CALL(fmu_set_integer(INST, vr, nvr, values));
}

/* Types without variables: only the empty call succeeds. */
#define NO_VARIABLES_GET(Name, Type)                                                              \
    fmi3Status fmi3Get##Name(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,    \
                             Type values[], size_t nValues) {                                     \
        (void)vr;                                                                                 \
        (void)values;                                                                             \
        (void)nValues;                                                                            \
        return nvr == 0 ? fmi3OK : unsupported(instance, "fmi3Get" #Name " (no such variables)"); \
    }
#define NO_VARIABLES_SET(Name, Type)                                                              \
    fmi3Status fmi3Set##Name(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,    \
                             const Type values[], size_t nValues) {                               \
        (void)vr;                                                                                 \
        (void)values;                                                                             \
        (void)nValues;                                                                            \
        return nvr == 0 ? fmi3OK : unsupported(instance, "fmi3Set" #Name " (no such variables)"); \
    }
#define NO_VARIABLES(Name, Type) NO_VARIABLES_GET(Name, Type) NO_VARIABLES_SET(Name, Type)
NO_VARIABLES(Float32, fmi3Float32)
NO_VARIABLES(Int8, fmi3Int8)
NO_VARIABLES(UInt8, fmi3UInt8)
NO_VARIABLES(Int16, fmi3Int16)
NO_VARIABLES(UInt16, fmi3UInt16)
NO_VARIABLES(UInt32, fmi3UInt32)
NO_VARIABLES(Int64, fmi3Int64)
NO_VARIABLES(UInt64, fmi3UInt64)
NO_VARIABLES(Boolean, fmi3Boolean)

fmi3Status fmi3GetString(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,
                         fmi3String values[], size_t nValues) {
    if (check_counts(instance, "fmi3GetString", nvr, nValues) != fmi3OK) return fmi3Error;
    CALL(fmu_get_string(INST, vr, nvr, values));
}
fmi3Status fmi3SetString(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,
                         const fmi3String values[], size_t nValues) {
    if (check_counts(instance, "fmi3SetString", nvr, nValues) != fmi3OK) return fmi3Error;
    CALL(fmu_set_string(INST, vr, nvr, values));
}

fmi3Status fmi3GetBinary(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,
                         size_t valueSizes[], fmi3Binary values[], size_t nValues) {
    (void)vr;
    (void)valueSizes;
    (void)values;
    (void)nValues;
    return nvr == 0 ? fmi3OK : unsupported(instance, "fmi3GetBinary (no such variables)");
}
fmi3Status fmi3SetBinary(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,
                         const size_t valueSizes[], const fmi3Binary values[], size_t nValues) {
    (void)vr;
    (void)valueSizes;
    (void)values;
    (void)nValues;
    return nvr == 0 ? fmi3OK : unsupported(instance, "fmi3SetBinary (no such variables)");
}
fmi3Status fmi3GetClock(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,
                        fmi3Clock values[]) {
    (void)vr;
    (void)values;
    return nvr == 0 ? fmi3OK : unsupported(instance, "fmi3GetClock (no clocks)");
}
fmi3Status fmi3SetClock(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,
                        const fmi3Clock values[]) {
    (void)vr;
    (void)values;
    return nvr == 0 ? fmi3OK : unsupported(instance, "fmi3SetClock (no clocks)");
}

fmi3Status fmi3GetNumberOfVariableDependencies(fmi3Instance instance, fmi3ValueReference vr,
                                               size_t *nDependencies) {
    (void)vr;
    (void)nDependencies;
    return unsupported(instance, "fmi3GetNumberOfVariableDependencies");
}
fmi3Status fmi3GetVariableDependencies(fmi3Instance instance, fmi3ValueReference dependent,
                                       size_t elementIndicesOfDependent[],
                                       fmi3ValueReference independents[],
                                       size_t elementIndicesOfIndependents[],
                                       fmi3DependencyKind dependencyKinds[], size_t nDependencies) {
    (void)dependent;
    (void)elementIndicesOfDependent;
    (void)independents;
    (void)elementIndicesOfIndependents;
    (void)dependencyKinds;
    (void)nDependencies;
    return unsupported(instance, "fmi3GetVariableDependencies");
}

fmi3Status fmi3GetFMUState(fmi3Instance instance, fmi3FMUState *FMUState) {
    CALL(fmu_get_state(INST, (fmu_snapshot **)FMUState));
}
fmi3Status fmi3SetFMUState(fmi3Instance instance, fmi3FMUState FMUState) {
    CALL(fmu_set_state(INST, (const fmu_snapshot *)FMUState));
}
fmi3Status fmi3FreeFMUState(fmi3Instance instance, fmi3FMUState *FMUState) {
    CALL(fmu_free_state(INST, (fmu_snapshot **)FMUState));
}
fmi3Status fmi3SerializedFMUStateSize(fmi3Instance instance, fmi3FMUState FMUState, size_t *size) {
    CALL(fmu_serialized_size(INST, (const fmu_snapshot *)FMUState, size));
}
fmi3Status fmi3SerializeFMUState(fmi3Instance instance, fmi3FMUState FMUState,
                                 fmi3Byte serializedState[], size_t size) {
    CALL(fmu_serialize_state(INST, (const fmu_snapshot *)FMUState, serializedState, size));
}
fmi3Status fmi3DeserializeFMUState(fmi3Instance instance, const fmi3Byte serializedState[],
                                   size_t size, fmi3FMUState *FMUState) {
    CALL(fmu_deserialize_state(INST, serializedState, size, (fmu_snapshot **)FMUState));
}

/* FMI 3 gives the sizes of the seed and sensitivity arrays again: they must be the counts of
 * what the call seeds (seed_of) and what it gives a sensitivity of (sensitivity_of); no array
 * variables here. 0 after an Error message. */
static int derivative_counts_ok(fmi3Instance instance, const char *function, size_t nSeed,
                                size_t n_seeded, const char *seed_of, size_t nSensitivity,
                                size_t n_sensitive, const char *sensitivity_of) {
    if (!instance || (nSeed == n_seeded && nSensitivity == n_sensitive)) return 1;
    fmu_log(INST, FMU_ERROR, LOG_ERROR,
            "%s: nSeed = %zu must equal %s = %zu and nSensitivity = %zu %s = %zu", function, nSeed,
            seed_of, n_seeded, nSensitivity, sensitivity_of, n_sensitive);
    return 0;
}

fmi3Status fmi3GetDirectionalDerivative(fmi3Instance instance, const fmi3ValueReference unknowns[],
                                        size_t nUnknowns, const fmi3ValueReference knowns[],
                                        size_t nKnowns, const fmi3Float64 seed[], size_t nSeed,
                                        fmi3Float64 sensitivity[], size_t nSensitivity) {
    /* one seed per known and one sensitivity per unknown */
    if (!derivative_counts_ok(instance, "fmi3GetDirectionalDerivative", nSeed, nKnowns, "nKnowns",
                              nSensitivity, nUnknowns, "nUnknowns"))
        return fmi3Error;
    CALL(fmu_get_directional_derivative(INST, unknowns, nUnknowns, knowns, nKnowns, seed,
                                        sensitivity, "fmi3GetDirectionalDerivative"));
}
fmi3Status fmi3GetAdjointDerivative(fmi3Instance instance, const fmi3ValueReference unknowns[],
                                    size_t nUnknowns, const fmi3ValueReference knowns[],
                                    size_t nKnowns, const fmi3Float64 seed[], size_t nSeed,
                                    fmi3Float64 sensitivity[], size_t nSensitivity) {
    /* the adjoint: one seed per unknown and one sensitivity per known */
    if (!derivative_counts_ok(instance, "fmi3GetAdjointDerivative", nSeed, nUnknowns, "nUnknowns",
                              nSensitivity, nKnowns, "nKnowns"))
        return fmi3Error;
    CALL(fmu_get_adjoint_derivative(INST, unknowns, nUnknowns, knowns, nKnowns, seed, sensitivity,
                                    "fmi3GetAdjointDerivative"));
}

fmi3Status fmi3EnterConfigurationMode(fmi3Instance instance) {
    return unsupported(instance, "fmi3EnterConfigurationMode");
}
fmi3Status fmi3ExitConfigurationMode(fmi3Instance instance) {
    return unsupported(instance, "fmi3ExitConfigurationMode");
}
fmi3Status fmi3GetIntervalDecimal(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,
                                  fmi3Float64 intervals[], fmi3IntervalQualifier qualifiers[]) {
    (void)vr;
    (void)nvr;
    (void)intervals;
    (void)qualifiers;
    return unsupported(instance, "fmi3GetIntervalDecimal");
}
fmi3Status fmi3GetIntervalFraction(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,
                                   fmi3UInt64 counters[], fmi3UInt64 resolutions[],
                                   fmi3IntervalQualifier qualifiers[]) {
    (void)vr;
    (void)nvr;
    (void)counters;
    (void)resolutions;
    (void)qualifiers;
    return unsupported(instance, "fmi3GetIntervalFraction");
}
fmi3Status fmi3GetShiftDecimal(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,
                               fmi3Float64 shifts[]) {
    (void)vr;
    (void)nvr;
    (void)shifts;
    return unsupported(instance, "fmi3GetShiftDecimal");
}
fmi3Status fmi3GetShiftFraction(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,
                                fmi3UInt64 counters[], fmi3UInt64 resolutions[]) {
    (void)vr;
    (void)nvr;
    (void)counters;
    (void)resolutions;
    return unsupported(instance, "fmi3GetShiftFraction");
}
fmi3Status fmi3SetIntervalDecimal(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,
                                  const fmi3Float64 intervals[]) {
    (void)vr;
    (void)nvr;
    (void)intervals;
    return unsupported(instance, "fmi3SetIntervalDecimal");
}
fmi3Status fmi3SetIntervalFraction(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,
                                   const fmi3UInt64 counters[], const fmi3UInt64 resolutions[]) {
    (void)vr;
    (void)nvr;
    (void)counters;
    (void)resolutions;
    return unsupported(instance, "fmi3SetIntervalFraction");
}
fmi3Status fmi3SetShiftDecimal(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,
                               const fmi3Float64 shifts[]) {
    (void)vr;
    (void)nvr;
    (void)shifts;
    return unsupported(instance, "fmi3SetShiftDecimal");
}
fmi3Status fmi3SetShiftFraction(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,
                                const fmi3UInt64 counters[], const fmi3UInt64 resolutions[]) {
    (void)vr;
    (void)nvr;
    (void)counters;
    (void)resolutions;
    return unsupported(instance, "fmi3SetShiftFraction");
}
fmi3Status fmi3EvaluateDiscreteStates(fmi3Instance instance) {
    return unsupported(instance, "fmi3EvaluateDiscreteStates");
}
/* Model Exchange (and event mode): fmi3_me_functions.c */

fmi3Status fmi3EnterStepMode(fmi3Instance instance) {
    return unsupported(instance, "fmi3EnterStepMode (no event mode)");
}
fmi3Status fmi3GetOutputDerivatives(fmi3Instance instance, const fmi3ValueReference vr[],
                                    size_t nvr, const fmi3Int32 orders[], fmi3Float64 values[],
                                    size_t nValues) {
    (void)vr;
    (void)nvr;
    (void)orders;
    (void)values;
    (void)nValues;
    return unsupported(instance, "fmi3GetOutputDerivatives (maxOutputDerivativeOrder = 0)");
}

/* fmi3DoStep but its usual call (flags written): the runtime's checks. Its arguments are
 * fmi3DoStep's own, in the same registers, so that the jump to it moves none (noclone: the
 * compiler may not drop the unused ones and move the rest). */
#if defined(__GNUC__)
__attribute__((noinline, noclone, cold))
#endif
static fmi3Status do_step_otherwise(fmi3Instance instance, fmi3Float64 currentCommunicationPoint,
                                    fmi3Float64 communicationStepSize,
                                    fmi3Boolean noSetFMUStatePriorToCurrentPoint,
                                    fmi3Boolean *eventHandlingNeeded,
                                    fmi3Boolean *terminateSimulation, fmi3Boolean *earlyReturn,
                                    fmi3Float64 *lastSuccessfulTime) {
    (void)noSetFMUStatePriorToCurrentPoint;
    (void)eventHandlingNeeded;
    (void)terminateSimulation;
    (void)earlyReturn;
    CALL(fmu_do_step_reporting_otherwise(INST, currentCommunicationPoint, communicationStepSize,
                                         lastSuccessfulTime));
}

fmi3Status fmi3DoStep(fmi3Instance instance, fmi3Float64 currentCommunicationPoint,
                      fmi3Float64 communicationStepSize,
                      fmi3Boolean noSetFMUStatePriorToCurrentPoint,
                      fmi3Boolean *eventHandlingNeeded, fmi3Boolean *terminateSimulation,
                      fmi3Boolean *earlyReturn, fmi3Float64 *lastSuccessfulTime) {
    if (eventHandlingNeeded) *eventHandlingNeeded = fmi3False;
    if (terminateSimulation) *terminateSimulation = fmi3False;
    if (earlyReturn) *earlyReturn = fmi3False;
    if (lastSuccessfulTime &&
        fmu_usual_call(INST, currentCommunicationPoint, communicationStepSize))
        CALL(fmu_usual_step_reporting(INST, currentCommunicationPoint, communicationStepSize,
                                      lastSuccessfulTime));
    return do_step_otherwise(instance, currentCommunicationPoint, communicationStepSize,
                             noSetFMUStatePriorToCurrentPoint, eventHandlingNeeded,
                             terminateSimulation, earlyReturn, lastSuccessfulTime);
}

fmi3Status fmi3ActivateModelPartition(fmi3Instance instance, fmi3ValueReference clockReference,
                                      fmi3Float64 activationTime) {
    (void)clockReference;
    (void)activationTime;
    return unsupported(instance, "fmi3ActivateModelPartition");
}
