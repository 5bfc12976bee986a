/*
 * Writes a model's modelDescription.xml for FMI 2.0 or 3.0 from its variable table (variables.h,
 * generated from the model's variables.def) and its config.h. Start values are what the model's
 * model_start_values writes (for the inverse model: the C library's defaults), printed with 17
 * significant digits. Compiled once per model, linked with that model's objects.
 *
 * usage: gen_model_description 2|3 OUT.xml
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "instance.h"
#include "model_interface.h"
#include "variables.h"

/* A Model Exchange unit's states and their derivatives (runtime/model_exchange.h). */
#ifndef FMU_N_STATES
#define FMU_N_STATES 0
#define FMU_STATE_VR(i) 0u
#define FMU_DERIVATIVE_VR(i) 0u
#endif

/* A model's config.h may name the outputs that no input reaches within a step (outputs of the
 * state): FMU_OUTPUT_WITHOUT_FEEDTHROUGH(vr). They are listed among the Outputs with no
 * dependencies, so that a master sees that loops through them are not algebraic; every other
 * output depends on every input (no dependencies attribute). */
/* A model's config.h sets FMU_PROVIDES_DIRECTIONAL_DERIVATIVE 1 if it defines
 * model_directional_derivative (model_interface.h), and may say which inputs each output depends
 * on: FMU_OUTPUT_DEPENDS_ON(output_vr, input_vr), listed as the output's dependencies. */
#ifndef FMU_PROVIDES_DIRECTIONAL_DERIVATIVE
#define FMU_PROVIDES_DIRECTIONAL_DERIVATIVE 0
#endif

#ifndef FMU_OUTPUT_WITHOUT_FEEDTHROUGH
#define FMU_OUTPUT_WITHOUT_FEEDTHROUGH(vr) 0
#endif

static FILE *out;
static int version;

/* The FMI 2 index of a variable (1-based position in ModelVariables, where FMI 2 leaves out the
 * independent variable), or 0. */
static size_t fmi2_index(unsigned vr) {
    size_t index = 0;
    for (size_t i = 0; i < fmu_n_variables; ++i) {
        if (fmu_variables[i].causality == FMU_INDEPENDENT_VAR) continue;
        ++index;
        if (fmu_variables[i].vr == vr) return index;
    }
    return 0;
}

/* How a variable is referred to in this version: FMI 2 index, FMI 3 value reference. */
static size_t reference(unsigned vr) { return version == 2 ? fmi2_index(vr) : vr; }

/* The state whose derivative vr is, or -1. */
static int state_of_derivative(unsigned vr) {
    for (int i = 0; i < FMU_N_STATES; ++i)
        if (FMU_DERIVATIVE_VR(i) == vr) return i;
    return -1;
}

/* The state vr is, or -1. */
static int state_index(unsigned vr) {
    for (int i = 0; i < FMU_N_STATES; ++i)
        if (FMU_STATE_VR(i) == vr) return i;
    return -1;
}

#ifdef FMU_ME_DEPENDS_ON
/* A Model Exchange unit's config.h may say which states and inputs each output and state
 * derivative depends on: FMU_ME_DEPENDS_ON(unknown_vr, known_vr). The dependencies attribute of
 * unknown vr, the knowns in the order of ModelVariables. */
static const char *listed_dependencies(unsigned vr, char *buf, size_t size) {
    size_t used = (size_t)snprintf(buf, size, " dependencies=\"");
    int first = 1;
    for (size_t i = 0; i < fmu_n_variables && used < size; ++i) {
        const unsigned known = fmu_variables[i].vr;
        if (fmu_variables[i].causality != FMU_INPUT_VAR && state_index(known) < 0) continue;
        if (!(FMU_ME_DEPENDS_ON(vr, known))) continue;
        used += (size_t)snprintf(buf + used, size - used, first ? "%zu" : " %zu", reference(known));
        first = 0;
    }
    if (used < size) snprintf(buf + used, size - used, "\"");
    return buf;
}
#endif

/* The dependencies attribute of an output or derivative, or "" (none written: it may depend on
 * every known). Co-simulation: an output of the state depends on no input (dependencies="").
 * Model Exchange: an output that is a state depends on itself, another output of the state on
 * the states; a derivative that is a state (x' = x_dot) on that state. */
static const char *dependencies(unsigned vr, int is_derivative, char *buf, size_t size) {
#ifdef FMU_ME_DEPENDS_ON
    if (FMU_MODEL_EXCHANGE) return listed_dependencies(vr, buf, size);
#endif
    if (!FMU_MODEL_EXCHANGE) return FMU_OUTPUT_WITHOUT_FEEDTHROUGH(vr) ? " dependencies=\"\"" : "";
    if (state_index(vr) >= 0) {
        snprintf(buf, size, " dependencies=\"%zu\"", reference(vr));
        return buf;
    }
    if (is_derivative || !FMU_OUTPUT_WITHOUT_FEEDTHROUGH(vr)) return "";
    size_t used = (size_t)snprintf(buf, size, " dependencies=\"");
    for (int i = 0; i < FMU_N_STATES && used < size; ++i)
        used += (size_t)snprintf(buf + used, size - used, i ? " %zu" : "%zu",
                                 reference(FMU_STATE_VR(i)));
    if (used < size) snprintf(buf + used, size - used, "\"");
    return buf;
}

#ifdef FMU_OUTPUT_DEPENDS_ON
/* dependencies="..." of an output: the inputs FMU_OUTPUT_DEPENDS_ON names, by index (FMI 2,
 * 1-based position in ModelVariables) or value reference (FMI 3). */
static void output_dependencies(unsigned output_vr) {
    fputs(" dependencies=\"", out);
    size_t index = 0;
    int first = 1;
    for (size_t i = 0; i < fmu_n_variables; ++i) {
        if (version == 2 && fmu_variables[i].causality == FMU_INDEPENDENT_VAR) continue;
        ++index;
        if (fmu_variables[i].causality != FMU_INPUT_VAR) continue;
        const unsigned in = fmu_variables[i].vr;
        if (!(FMU_OUTPUT_DEPENDS_ON(output_vr, in))) continue;
        if (version == 2) fprintf(out, first ? "%zu" : " %zu", index);
        else fprintf(out, first ? "%u" : " %u", in);
        first = 0;
    }
    fputc('"', out);
}
#endif

static void attr(const char *name, const char *value) {
    if (!value || !*value) return;
    fprintf(out, " %s=\"", name);
    for (const char *c = value; *c; ++c) switch (*c) {
            case '<': fputs("&lt;", out); break;
            case '>': fputs("&gt;", out); break;
            case '&': fputs("&amp;", out); break;
            case '"': fputs("&quot;", out); break;
            default: fputc(*c, out);
        }
    fputc('"', out);
}

static void attr_double(const char *name, double v) {
    char b[40];
    snprintf(b, sizeof b, "%.17g", v);
    attr(name, b);
}

static void attr_int(const char *name, long v) {
    char b[24];
    snprintf(b, sizeof b, "%ld", v);
    attr(name, b);
}

/* The attributes every variable has, in both versions. */
static void common_attributes(unsigned vr, const char *name, const char *causality,
                              const char *variability, const char *initial,
                              const char *description) {
    attr("name", name);
    attr_int("valueReference", vr);
    attr("description", description);
    attr("causality", causality);
    attr("variability", variability);
    attr("initial", initial);
}

/* The attributes of the value: unit, range, start. start_kind: 0 none, 1 real, 2 integer. */
static void value_attributes(const char *unit, const char *display_unit, int has_range, long min,
                             long max, int start_kind, double start, unsigned vr) {
    const int state = state_of_derivative(vr);
    if (state >= 0) attr_int("derivative", (long)reference(FMU_STATE_VR(state)));
    attr("unit", unit);
    attr("displayUnit", display_unit);
    if (has_range) {
        attr_int("min", min);
        attr_int("max", max);
    }
    if (start_kind == 1) attr_double("start", start);
    if (start_kind == 2) attr_int("start", (long)start);
}

/* One variable: FMI 2 nests the value's element in ScalarVariable, FMI 3 names the type. */
static void variable(unsigned vr, const char *name, int is_real, const char *causality,
                     const char *variability, const char *initial, int start_kind, double start,
                     const char *unit, const char *display_unit, int has_range, long min, long max,
                     const char *description) {
    if (unit && !strcmp(unit, "1")) unit = NULL;
    if (version == 2) {
        fputs("    <ScalarVariable", out);
        common_attributes(vr, name, causality, variability, initial, description);
        fputs(">\n      <", out);
        fputs(is_real ? "Real" : "Integer", out);
        value_attributes(unit, display_unit, has_range, min, max, start_kind, start, vr);
        fputs("/>\n    </ScalarVariable>\n", out);
    } else {
        fputs("    <", out);
        fputs(is_real ? "Float64" : "Int32", out);
        common_attributes(vr, name, causality, variability, initial, description);
        value_attributes(unit, display_unit, has_range, min, max, start_kind, start, vr);
        fputs("/>\n", out);
    }
}

static const struct {
    const char *name;
    const char *base;
} kUnits[] = {
    {"1/s", "s=\"-1\""},
    {"1/s2", "s=\"-2\""},
    {"A", "A=\"1\""},
    {"A/s", "s=\"-1\" A=\"1\""},
    {"H", "kg=\"1\" m=\"2\" s=\"-2\" A=\"-2\""},
    {"kg", "kg=\"1\""},
    {"kg.m2", "kg=\"1\" m=\"2\""},
    {"m", "m=\"1\""},
    {"m/s", "m=\"1\" s=\"-1\""},
    {"m/s2", "m=\"1\" s=\"-2\""},
    {"m/s3", "m=\"1\" s=\"-3\""},
    {"N", "kg=\"1\" m=\"1\" s=\"-2\""},
    {"N.m", "kg=\"1\" m=\"2\" s=\"-2\""},
    {"N/m", "kg=\"1\" s=\"-2\""},
    {"N.s/m", "kg=\"1\" s=\"-1\""},
    {"N.m/A", "kg=\"1\" m=\"2\" s=\"-2\" A=\"-1\""},
    {"N.m.s/rad", "kg=\"1\" m=\"2\" s=\"-1\" rad=\"-1\""},
    {"Ohm", "kg=\"1\" m=\"2\" s=\"-3\" A=\"-2\""},
    {"rad", "rad=\"1\""},
    {"rad/s", "rad=\"1\" s=\"-1\""},
    {"rad/s2", "rad=\"1\" s=\"-2\""},
    {"s", "s=\"1\""},
    {"V", "kg=\"1\" m=\"2\" s=\"-3\" A=\"-1\""},
    {"W", "kg=\"1\" m=\"2\" s=\"-3\""},
};
enum { N_UNITS = sizeof kUnits / sizeof kUnits[0] };

/* Index of a unit in kUnits, or -1. */
static int unit_index(const char *unit) {
    for (int u = 0; u < N_UNITS; ++u)
        if (!strcmp(kUnits[u].name, unit)) return u;
    return -1;
}

/* A String parameter, empty at the start (the model's start values hold no strings). */
static void string_parameter(const fmu_variable *var) {
    if (version == 2) {
        fputs("    <ScalarVariable", out);
        common_attributes(var->vr, var->name, "parameter", "fixed", "exact", var->description);
        fputs(">\n      <String start=\"\"/>\n    </ScalarVariable>\n", out);
    } else {
        fputs("    <String", out);
        common_attributes(var->vr, var->name, "parameter", "fixed", "exact", var->description);
        fputs(">\n      <Start value=\"\"/>\n    </String>\n", out);
    }
}

/* One variable of the table, with its start value from the model's start values. FMI 3 requires
 * the independent variable; FMI 2 does not, and FMI Library (libcosim) rejects an FMI 2
 * independent variable without a start value, so FMI 2 leaves it out. */
static void table_variable(const fmu_variable *var, const fmu_values *start) {
    if (var->type == FMU_STRING) {
        string_parameter(var);
        return;
    }
    const int is_real = var->type == FMU_REAL;
    const double start_value = is_real ? start->real[var->vr] : start->integer[var->vr];
    switch (var->causality) {
        case FMU_INPUT_VAR:
            /* angles are entered in degrees by people, in radians by programs */
            variable(var->vr, var->name, is_real, "input", "continuous", NULL, is_real ? 1 : 2,
                     start_value, var->unit, strcmp(var->unit, "rad") ? var->display_unit : "deg",
                     var->has_range, var->min, var->max, var->description);
            break;
        case FMU_OUTPUT_VAR:
            variable(var->vr, var->name, is_real, "output", is_real ? "continuous" : "discrete",
                     "calculated", 0, 0, var->unit, var->display_unit, var->has_range, var->min,
                     var->max, var->description);
            break;
        case FMU_PARAMETER_VAR:
            variable(var->vr, var->name, is_real, "parameter", "fixed", "exact", is_real ? 1 : 2,
                     start_value, var->unit, var->display_unit, var->has_range, var->min, var->max,
                     var->description);
            break;
        case FMU_INDEPENDENT_VAR:
            if (version == 3)
                variable(var->vr, var->name, is_real, "independent", "continuous", NULL, 0, 0,
                         var->unit, NULL, 0, 0, 0, var->description);
            break;
    }
}

/* Marks in used[] the units the variables use; 0, or 1 with a message if one is not in kUnits
 * (every unit the variables use must be known, and only those are listed). */
static int mark_used_units(int used[N_UNITS]) {
    for (size_t i = 0; i < fmu_n_variables; ++i) {
        const char *unit = fmu_variables[i].unit;
        if (!*unit || !strcmp(unit, "1")) continue;
        const int u = unit_index(unit);
        if (u < 0) {
            fprintf(stderr, "gen_model_description: %s has unit '%s', which is not in kUnits\n",
                    fmu_variables[i].name, unit);
            return 1;
        }
        used[u] = 1;
    }
    return 0;
}

/* The XML declaration and the fmiModelDescription element's attributes. */
static void write_header(void) {
    fputs("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n", out);
    fputs("<!-- Generated by fmu/runtime/gen_model_description.c from " FMU_VARIABLES_SOURCE
          ": do not edit. -->\n",
          out);
    fputs("<fmiModelDescription", out);
    attr("fmiVersion", version == 2 ? "2.0" : "3.0");
    attr("modelName", FMU_MODEL_IDENTIFIER);
    attr(version == 2 ? "guid" : "instantiationToken", FMU_GUID);
    attr("description", FMU_MODEL_DESCRIPTION_TEXT);
    attr("generationTool", FMU_MODEL_IDENTIFIER " gen_model_description");
    attr("variableNamingConvention", "structured");
    if (version == 2) attr("numberOfEventIndicators", "0");
    fputs(">\n", out);
}

/* The ModelExchange or CoSimulation element: the interface and its capabilities. */
static void write_interface(void) {
#if FMU_MODEL_EXCHANGE
    fputs("  <ModelExchange", out);
    attr("modelIdentifier", FMU_MODEL_IDENTIFIER);
    attr(version == 2 ? "completedIntegratorStepNotNeeded" : "needsCompletedIntegratorStep",
         version == 2 ? "true" : "false");
    attr(version == 2 ? "canGetAndSetFMUstate" : "canGetAndSetFMUState", "true");
    attr(version == 2 ? "canSerializeFMUstate" : "canSerializeFMUState", "true");
    if (version == 2) attr("canNotUseMemoryManagementFunctions", "true");
    if (FMU_PROVIDES_DIRECTIONAL_DERIVATIVE) {
        attr(version == 2 ? "providesDirectionalDerivative" : "providesDirectionalDerivatives",
             "true");
        if (version == 3) attr("providesAdjointDerivatives", "true");
    }
#else
    fputs("  <CoSimulation", out);
    attr("modelIdentifier", FMU_MODEL_IDENTIFIER);
    attr("canHandleVariableCommunicationStepSize", "true");
    if (version == 2) {
        attr("canInterpolateInputs", FMU_CAN_INTERPOLATE_INPUTS ? "true" : "false");
        attr("maxOutputDerivativeOrder", "0");
        attr("canGetAndSetFMUstate", "true");
        attr("canSerializeFMUstate", "true");
        attr("canNotUseMemoryManagementFunctions", "true");
        if (FMU_PROVIDES_DIRECTIONAL_DERIVATIVE) attr("providesDirectionalDerivative", "true");
    } else {
        attr("canGetAndSetFMUState", "true");
        attr("canSerializeFMUState", "true");
        if (FMU_PROVIDES_DIRECTIONAL_DERIVATIVE) {
            attr("providesDirectionalDerivatives", "true");
            attr("providesAdjointDerivatives", "true");
        }
        attr("hasEventMode", "false");
    }
#endif
    fputs("/>\n", out);
}

/* The definitions of the units in used[] (rad with its display unit deg). */
static void write_unit_definitions(const int used[N_UNITS]) {
    fputs("  <UnitDefinitions>\n", out);
    for (int u = 0; u < N_UNITS; ++u) {
        if (!used[u]) continue;
        fprintf(out, "    <Unit name=\"%s\">\n      <BaseUnit %s/>\n", kUnits[u].name,
                kUnits[u].base);
        if (!strcmp(kUnits[u].name, "rad"))
            fputs("      <DisplayUnit name=\"deg\" factor=\"57.295779513082323\"/>\n", out);
        fputs("    </Unit>\n", out);
    }
    fputs("  </UnitDefinitions>\n", out);
}

/* The log categories and the default experiment. */
static void write_log_categories(void) {
    fputs("  <LogCategories>\n", out);
    for (int c = 0; c < FMU_N_LOG_CATEGORIES; ++c) {
        fputs("    <Category", out);
        attr("name", fmu_log_category_names[c]);
        attr("description", fmu_log_category_descriptions[c]);
        fputs("/>\n", out);
    }
    fputs("  </LogCategories>\n", out);
    fputs("  <DefaultExperiment " FMU_DEFAULT_EXPERIMENT "/>\n", out);
}

/* Outputs, the state derivatives (Model Exchange), then the initial unknowns (the outputs,
 * which include the derivatives); by index (FMI 2, 1-based position in ModelVariables) or
 * value reference (FMI 3). */
static void write_model_structure(void) {
    fputs("  <ModelStructure>\n", out);
    static const char *const kFmi2Lists[3] = {"Outputs", "Derivatives", "InitialUnknowns"};
    static const char *const kFmi3Elements[3] = {"Output", "ContinuousStateDerivative",
                                                 "InitialUnknown"};
    for (int pass = 0; pass < 3; ++pass) {
        if (pass == 1 && !FMU_N_STATES) continue;
        if (version == 2) fprintf(out, "    <%s>\n", kFmi2Lists[pass]);
        for (size_t i = 0; i < fmu_n_variables; ++i) {
            const unsigned vr = fmu_variables[i].vr;
            if (fmu_variables[i].causality != FMU_OUTPUT_VAR) continue;
            if (pass == 1 && state_of_derivative(vr) < 0) continue;
            char buf[512];
            const char *deps = pass == 2 ? "" : dependencies(vr, pass == 1, buf, sizeof buf);
            if (version == 2) fprintf(out, "      <Unknown index=\"%zu\"%s", fmi2_index(vr), deps);
            else fprintf(out, "    <%s valueReference=\"%u\"%s", kFmi3Elements[pass], vr, deps);
#ifdef FMU_OUTPUT_DEPENDS_ON
            if (pass == 0) output_dependencies(vr);
#endif
            fputs("/>\n", out);
        }
        if (version == 2) fprintf(out, "    </%s>\n", kFmi2Lists[pass]);
    }
    fputs("  </ModelStructure>\n", out);
}

/* 0, or 1 with a message if a start value lies outside its variable's declared range (the
 * runtime refuses such a value when it is set: a unit must start within its own description). */
static int check_start_ranges(const fmu_values *start) {
    for (size_t i = 0; i < fmu_n_variables; ++i) {
        const fmu_variable *var = &fmu_variables[i];
        const double x = var->type == FMU_REAL ? start->real[var->vr] : start->integer[var->vr];
        if (var->causality == FMU_OUTPUT_VAR || fmu_within_range(var, x)) continue;
        fprintf(stderr, "gen_model_description: start value of " FMU_OUT_OF_RANGE_FORMAT "\n",
                var->name, x, var->min, var->max);
        return 1;
    }
    return 0;
}

int main(int argc, char **argv) {
    if (argc != 3 || (strcmp(argv[1], "2") && strcmp(argv[1], "3"))) {
        fprintf(stderr, "usage: gen_model_description 2|3 OUT.xml\n");
        return 2;
    }
    version = atoi(argv[1]);
    int used[N_UNITS] = {0};
    if (mark_used_units(used)) return 1;
    static fmu_values start; /* large: not on the stack */
    model_start_values(&start);
    if (check_start_ranges(&start)) return 1;
    out = fopen(argv[2], "w");
    if (!out) {
        fprintf(stderr, "gen_model_description: cannot write %s\n", argv[2]);
        return 1;
    }
    write_header();
    write_interface();
    write_unit_definitions(used);
    write_log_categories();
    fputs("  <ModelVariables>\n", out);
    for (size_t i = 0; i < fmu_n_variables; ++i) table_variable(&fmu_variables[i], &start);
    fputs("  </ModelVariables>\n", out);
    write_model_structure();
    fputs("</fmiModelDescription>\n", out);
    if (fclose(out) != 0) {
        fprintf(stderr, "gen_model_description: error writing %s\n", argv[2]);
        return 1;
    }
    return 0;
}
