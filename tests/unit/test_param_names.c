/* stewart_params_set: every parameter name of the FMU's variable list (fmu/variables.def, the
 * model description's names) reaches the field the FMU maps it to, and only that field; names
 * that are not parameters are refused with a message. */
#include <math.h>
#include <string.h>

#include "stewart/stewart.h"
#include "stewart/stewart_table.h"
#include "unity.h"

void setUp(void) {}
void tearDown(void) {}

static void test_every_fmu_parameter_name_sets_its_field(void) {
    int names = 0;
#define FMU_PARAM(vr, id, name, field, unit, display, desc)                                        \
    {                                                                                              \
        stewart_params by_name, expected;                                                          \
        stewart_params_default(&by_name);                                                          \
        stewart_params_default(&expected);                                                         \
        expected.field = 1000.0 + (vr);                                                            \
        char msg[STEWART_MESSAGE_SIZE];                                                            \
        TEST_ASSERT_EQUAL_INT_MESSAGE(                                                             \
            STEWART_OK, stewart_params_set(&by_name, name, 1000.0 + (vr), msg, sizeof msg), name); \
        TEST_ASSERT_EQUAL_MEMORY_MESSAGE(&expected, &by_name, sizeof expected, name);              \
        ++names;                                                                                   \
    }
#include "variables.def"
    /* every double of stewart_params has an FMU name */
    TEST_ASSERT_EQUAL_INT(sizeof(stewart_params) / sizeof(double), names);
}

/* The library's table ids are the FMU's value references: each FMU parameter's vr finds its name,
 * and each FMU option of the library has the table's id. */
static void test_table_ids_are_the_fmu_value_references(void) {
    char element_name[48];
    int e = -1;
#define FMU_PARAM(vr, fmu_id, fmu_name, field, fmu_unit, display, desc)              \
    {                                                                                \
        const int i = stewart_param_find_id(vr, &e);                                 \
        TEST_ASSERT_TRUE_MESSAGE(i >= 0, fmu_name);                                  \
        stewart_param_element_name(i, e, element_name, sizeof element_name);         \
        TEST_ASSERT_EQUAL_STRING(fmu_name, element_name);                            \
        TEST_ASSERT_EQUAL_STRING(fmu_unit, stewart_param_element_unit(i, e));        \
        TEST_ASSERT_EQUAL_STRING(display, stewart_param_element_display_unit(i, e)); \
    }
#define FMU_OPTION_INT(vr, fmu_id, fmu_name, start, min, max, desc) \
    if (stewart_inverse_option_find(fmu_name) >= 0)                 \
        TEST_ASSERT_EQUAL_INT_MESSAGE(                              \
            vr, stewart_inverse_option(stewart_inverse_option_find(fmu_name))->id, fmu_name);
#define FMU_OPTION_REAL(vr, fmu_id, fmu_name, field, unit, desc) \
    TEST_ASSERT_EQUAL_INT_MESSAGE(                               \
        vr, stewart_inverse_option(stewart_inverse_option_find(fmu_name))->id, fmu_name);
#include "variables.def"
}

static void test_names_that_are_not_parameters(void) {
    const char *bad[] = {"payload_mas",
                         "base_angle",
                         "base_angle[0]",
                         "base_angle[7]",
                         "base_angle[1]x",
                         "base_angle[-1]",
                         "base_angle[4294967298]",
                         "base_angle[ 2]",
                         "base_angle[+2]",
                         "base_angle[01]",
                         "gravity[4]",
                         "payload_mass[1]",
                         "",
                         "gravity[1",
                         "Payload_mass",
                         "fidelity"};
    stewart_params p, untouched;
    stewart_params_default(&p);
    untouched = p;
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        char msg[STEWART_MESSAGE_SIZE] = "";
        TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_ERR_ARGUMENT,
                                      stewart_params_set(&p, bad[i], 1.0, msg, sizeof msg), bad[i]);
        TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg, "no parameter is named"), msg);
        TEST_ASSERT_EQUAL_MEMORY(&untouched, &p, sizeof p);
    }
    char msg[STEWART_MESSAGE_SIZE];
    stewart_params_set(&p, "payload_mas", 1.0, msg, sizeof msg);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg, "the nearest is payload_mass"), msg);
    stewart_params_set(&p, "base_angle[7]", 1.0, msg, sizeof msg);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg, "the nearest is base_angle[1..6]"), msg);
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT,
                          stewart_params_set(NULL, "payload_mass", 1.0, msg, sizeof msg));
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_params_set(&p, NULL, 1.0, msg, sizeof msg));
}

/* The value is checked when the model is built, with the same name in the message. */
static void test_an_invalid_value_is_named_at_model_creation(void) {
    stewart_params p;
    stewart_params_default(&p);
    char msg[STEWART_MESSAGE_SIZE];
    TEST_ASSERT_EQUAL_INT(STEWART_OK,
                          stewart_params_set(&p, "payload_com[2]", INFINITY, msg, sizeof msg));
    TEST_ASSERT_NULL(stewart_model_create(&p, msg, sizeof msg));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg, "payload_com[2]"), msg);
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_every_fmu_parameter_name_sets_its_field);
    RUN_TEST(test_table_ids_are_the_fmu_value_references);
    RUN_TEST(test_names_that_are_not_parameters);
    RUN_TEST(test_an_invalid_value_is_named_at_model_creation);
    return UNITY_END();
}
