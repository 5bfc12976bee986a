/* The parameter and option tables (stewart/stewart_table.h): the defaults are the thesis
 * platform's formulas, worked out here again; iteration reaches every field once; ranges refuse
 * by name with all the digits of the value. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "stewart/stewart_table.h"
#include "unity.h"

void setUp(void) {}
void tearDown(void) {}

/* The thesis platform (4.2.8), from its description: 1 m aluminium disc 0.05 m thick, legs of
 * aluminium rods 15 mm x 0.3 m with the centre at mid-length, beta and tau in degrees. */
static void thesis_platform(stewart_params *p) {
    const double pi = 3.14159265358979323846, deg = pi / 180.0, rho = 2700.0;
    const double beta[6] = {0, 30, 120, 150, 240, 270}, tau[6] = {330, 60, 90, 180, 210, 300};
    memset(p, 0, sizeof *p);
    p->base_radius = 0.5;
    p->platform_radius = 0.5;
    for (int k = 0; k < 6; ++k)
        p->base_angle[k] = beta[k] * deg, p->platform_angle[k] = tau[k] * deg;
    p->home_height = 0.5;
    /* geometry 0 (circles); the joints' defaults are the same joints as coordinates, the arms
     * zero (tangential) */
    for (int k = 0; k < 6; ++k) {
        p->base_joint[3 * k] = 0.5 * cos(p->base_angle[k]);
        p->base_joint[3 * k + 1] = 0.5 * sin(p->base_angle[k]);
        p->platform_joint[3 * k] = 0.5 * cos(p->platform_angle[k]);
        p->platform_joint[3 * k + 1] = 0.5 * sin(p->platform_angle[k]);
    }
    p->gravity[2] = -9.81;
    const double R = 0.5, t = 0.05, m_plate = rho * pi * R * R * t;
    p->platform_mass = m_plate;
    p->platform_inertia[0] = p->platform_inertia[1] = m_plate * R * R / 4.0;
    p->platform_inertia[2] = m_plate * R * R / 2.0;
    const double r = 0.0075, l = 0.3, m_rod = rho * pi * r * r * l;
    const double I_across = m_rod * (3.0 * r * r + l * l) / 12.0, I_axis = m_rod * r * r / 2.0;
    p->cylinder_mass = p->piston_mass = m_rod;
    p->cylinder_inertia[0] = p->cylinder_inertia[1] = I_across;
    p->piston_inertia[0] = p->piston_inertia[1] = I_across;
    p->cylinder_inertia[2] = p->piston_inertia[2] = I_axis;
    p->cylinder_com = p->piston_com = l / 2.0;
    for (int k = 0; k < 6; ++k) p->stroke_min[k] = 0.40, p->stroke_max[k] = 0.70;
    /* The limits (docs/limits.md), not the thesis': joints up to 90 degrees from the leg's home
     * direction (the zero neutral axes), legs as thick as the rods. */
    p->base_joint_limit = p->platform_joint_limit = 90.0 * deg;
    p->leg_diameter = 2.0 * r;
    /* no actuator body or rod (the legs are leg_diameter thick), no software position limits */
    for (int i = 0; i < 6; ++i) p->axis_min[i] = -DBL_MAX, p->axis_max[i] = DBL_MAX;
    /* no drive (zero lead); its gear and efficiencies neutral; no leg motion limits */
    for (int k = 0; k < 6; ++k)
        p->gear_ratio[k] = p->screw_efficiency[k] = p->screw_back_efficiency[k] = 1.0;
}

static void test_defaults_are_the_thesis_platform_bit_for_bit(void) {
    stewart_params expected, library, from_table;
    thesis_platform(&expected);
    memset(&library, 0x5a, sizeof library);
    stewart_params_default(&library);
    TEST_ASSERT_EQUAL_MEMORY(&expected, &library, sizeof expected);
    memset(&from_table, 0x5a, sizeof from_table);
    for (int i = 0; i < stewart_param_count(); ++i)
        for (int e = 0; e < stewart_param(i)->count; ++e)
            *stewart_param_element(&from_table, i, e) = stewart_param(i)->defaults[e];
    TEST_ASSERT_EQUAL_MEMORY(&expected, &from_table, sizeof expected);
    /* the payload is absent and the platform's centre of mass at its origin */
    TEST_ASSERT_EQUAL_DOUBLE(0.0, library.payload_mass);
}

/* Element addresses walk stewart_params double by double; ids are consecutive per parameter;
 * names and ids find their element again. */
static void test_iteration_covers_every_field_once(void) {
    stewart_params p;
    const double *next = (const double *)&p;
    for (int i = 0; i < stewart_param_count(); ++i) {
        const stewart_param_info *info = stewart_param(i);
        TEST_ASSERT_TRUE(info->count == 1 || info->count == 3 || info->count == 6 ||
                         info->count == 18);
        for (int e = 0; e < info->count; ++e) {
            const char *unit = stewart_param_element_unit(i, e);
            const char *display = stewart_param_element_display_unit(i, e);
            TEST_ASSERT_TRUE(strcmp(display, "") == 0 ||
                             (strcmp(display, "deg") == 0 && !strcmp(unit, "rad")));
            TEST_ASSERT_EQUAL_PTR(next++, stewart_param_element(&p, i, e));
            char name[48];
            TEST_ASSERT_TRUE(stewart_param_element_name(i, e, name, sizeof name) > 0);
            int found_e = -1;
            TEST_ASSERT_EQUAL_INT_MESSAGE(i, stewart_param_find(name, &found_e), name);
            TEST_ASSERT_EQUAL_INT(e, found_e);
            TEST_ASSERT_EQUAL_INT(i, stewart_param_find_id(info->id + e, &found_e));
            TEST_ASSERT_EQUAL_INT(e, found_e);
        }
        TEST_ASSERT_NULL(stewart_param_element(&p, i, info->count));
    }
    TEST_ASSERT_EQUAL_PTR((const double *)(&p + 1), next);
    TEST_ASSERT_NULL(stewart_param(stewart_param_count()));
    TEST_ASSERT_NULL(stewart_param(-1));
    TEST_ASSERT_EQUAL_INT(-1, stewart_param_find_id(201, NULL));
}

static void test_element_names_and_descriptions(void) {
    char text[160];
    int e;
    const int angle = stewart_param_find("base_angle[2]", &e);
    TEST_ASSERT_EQUAL_INT(1, e);
    stewart_param_element_name(angle, 1, text, sizeof text);
    TEST_ASSERT_EQUAL_STRING("base_angle[2]", text);
    stewart_param_element_description(angle, 1, text, sizeof text);
    TEST_ASSERT_EQUAL_STRING("Angle of the base Cardan centre of leg 2", text);
    stewart_param_element_description(stewart_param_find("gravity[3]", NULL), 2, text, sizeof text);
    TEST_ASSERT_EQUAL_STRING("Gravity, world z", text);
    TEST_ASSERT_EQUAL_INT(-1, stewart_param_element_name(angle, 6, text, sizeof text));
    TEST_ASSERT_EQUAL_STRING("deg", stewart_param(angle)->display_unit);
    TEST_ASSERT_EQUAL_INT(212, stewart_param(angle)->id);
    /* a pose's elements: x, y, z in m, roll, pitch, yaw in rad shown in deg */
    const int tool = stewart_param_find("tool_frame[5]", &e);
    TEST_ASSERT_EQUAL_INT(4, e);
    stewart_param_element_description(tool, 4, text, sizeof text);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(text, "tool frame"), text);
    TEST_ASSERT_EQUAL_STRING(" pitch", text + strlen(text) - 6);
    TEST_ASSERT_EQUAL_STRING("m", stewart_param_element_unit(tool, 2));
    TEST_ASSERT_EQUAL_STRING("", stewart_param_element_display_unit(tool, 2));
    TEST_ASSERT_EQUAL_STRING("rad", stewart_param_element_unit(tool, 3));
    TEST_ASSERT_EQUAL_STRING("deg", stewart_param_element_display_unit(tool, 3));
    TEST_ASSERT_NULL(stewart_param_element_unit(tool, 6));
}

/* Each element is refused just outside its range and accepted just inside, by name. */
static void test_ranges_refuse_by_name(void) {
    char msg[STEWART_MESSAGE_SIZE], name[48];
    for (int i = 0; i < stewart_param_count(); ++i) {
        const stewart_param_info *info = stewart_param(i);
        for (int e = 0; e < info->count; ++e) {
            stewart_param_element_name(i, e, name, sizeof name);
            TEST_ASSERT_EQUAL_INT(STEWART_ERR_PARAMETER,
                                  stewart_param_check_value(i, e, NAN, msg, sizeof msg));
            TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg, name), msg);
            TEST_ASSERT_EQUAL_INT(STEWART_ERR_PARAMETER,
                                  stewart_param_check_value(i, e, INFINITY, msg, sizeof msg));
            const double below = info->min_closed ? nextafter(info->min, -INFINITY) : info->min;
            TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_ERR_PARAMETER,
                                          stewart_param_check_value(i, e, below, msg, sizeof msg),
                                          name);
            const double inside = info->min_closed ? info->min : nextafter(info->min, INFINITY);
            TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK,
                                          stewart_param_check_value(i, e, inside, msg, sizeof msg),
                                          msg);
        }
    }
    /* the value is printed with every digit it needs */
    const int mass = stewart_param_find("payload_mass", NULL);
    stewart_param_check_value(mass, 0, -1e-300, msg, sizeof msg);
    TEST_ASSERT_EQUAL_STRING("payload_mass = -1e-300 kg must be >= 0", msg);
}

/* Issue 15 item 7: (1, 2, 3 + 1 ulp) breaks the triangle inequality by one ulp; the message shows
 * the ulp. */
static void test_refused_inertia_shows_why(void) {
    stewart_params p;
    stewart_params_default(&p);
    p.payload_inertia[0] = 1, p.payload_inertia[1] = 2, p.payload_inertia[2] = nextafter(3.0, 4.0);
    char msg[STEWART_MESSAGE_SIZE];
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_PARAMETER, stewart_params_check(&p, msg, sizeof msg));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg, "(1, 2, 3.0000000000000004)"), msg);
    p.payload_inertia[2] = 3.0;
    TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK, stewart_params_check(&p, msg, sizeof msg), msg);
}

static void test_options_table(void) {
    stewart_inverse_options o, from_table;
    stewart_inverse_options_default(&o);
    memset(&from_table, 0, sizeof from_table);
    char msg[STEWART_MESSAGE_SIZE];
    for (int i = 0; i < stewart_inverse_option_count(); ++i) {
        const stewart_option_info *info = stewart_inverse_option(i);
        TEST_ASSERT_EQUAL_INT(i, stewart_inverse_option_find(info->name));
        TEST_ASSERT_EQUAL_DOUBLE(info->default_value, stewart_inverse_option_get(&o, i));
        TEST_ASSERT_EQUAL_INT_MESSAGE(
            STEWART_OK,
            stewart_inverse_option_set(&from_table, i, info->default_value, msg, sizeof msg), msg);
    }
    /* field by field (the struct has padding) */
    TEST_ASSERT_EQUAL_INT(o.fidelity, from_table.fidelity);
    TEST_ASSERT_EQUAL_DOUBLE(o.tolerance, from_table.tolerance);
    TEST_ASSERT_EQUAL_INT(o.max_iterations, from_table.max_iterations);
    TEST_ASSERT_EQUAL_INT(o.modified_newton, from_table.modified_newton);
    TEST_ASSERT_EQUAL_DOUBLE(o.warn_condition, from_table.warn_condition);
    TEST_ASSERT_EQUAL_DOUBLE(o.singular_condition, from_table.singular_condition);
    /* the documented defaults */
    TEST_ASSERT_EQUAL_INT(STEWART_MASSLESS, o.fidelity);
    TEST_ASSERT_EQUAL_DOUBLE(1e-12, o.tolerance);
    TEST_ASSERT_EQUAL_INT(20, o.max_iterations);
    TEST_ASSERT_EQUAL_INT(0, o.modified_newton);
    TEST_ASSERT_EQUAL_DOUBLE(1e3, o.warn_condition);
    TEST_ASSERT_EQUAL_DOUBLE(1e10, o.singular_condition);
    /* ids are the FMU's value references; 201 (derivatives) is the FMU's own */
    TEST_ASSERT_EQUAL_INT(200, stewart_inverse_option(stewart_inverse_option_find("fidelity"))->id);
    TEST_ASSERT_EQUAL_INT(
        206, stewart_inverse_option(stewart_inverse_option_find("singular_condition"))->id);
    TEST_ASSERT_EQUAL_INT(-1, stewart_inverse_option_find("derivatives"));
    /* integers take whole numbers only, within range; a refusal leaves the options unchanged */
    const int it = stewart_inverse_option_find("max_iterations");
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_PARAMETER,
                          stewart_inverse_option_set(&o, it, 2.5, msg, sizeof msg));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg, "max_iterations = 2.5"), msg);
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_PARAMETER,
                          stewart_inverse_option_set(&o, it, 0, msg, sizeof msg));
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_PARAMETER,
                          stewart_inverse_option_set(&o, it, 3e9, msg, sizeof msg));
    TEST_ASSERT_EQUAL_INT(20, o.max_iterations);
    TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_inverse_option_set(&o, it, 7, msg, sizeof msg));
    TEST_ASSERT_EQUAL_INT(7, o.max_iterations);
    o.warn_condition = 1e11;
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_PARAMETER,
                          stewart_inverse_options_check(&o, msg, sizeof msg));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg, "warn = 1e+11, singular = 1e+10"), msg);
    /* forward kinematics' options keep the same rule across fields, after their ranges */
    stewart_forward_options f;
    stewart_forward_options_default(&f);
    TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_forward_options_check(&f, msg, sizeof msg));
    f.warn_condition = 2 * f.singular_condition;
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_PARAMETER,
                          stewart_forward_options_check(&f, msg, sizeof msg));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg, "warn_condition <= singular_condition"), msg);
    f.tolerance = -1; /* a range is checked before the rule */
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_PARAMETER,
                          stewart_forward_options_check(&f, msg, sizeof msg));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg, "tolerance = -1"), msg);
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT,
                          stewart_forward_options_check(NULL, msg, sizeof msg));
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_defaults_are_the_thesis_platform_bit_for_bit);
    RUN_TEST(test_iteration_covers_every_field_once);
    RUN_TEST(test_element_names_and_descriptions);
    RUN_TEST(test_ranges_refuse_by_name);
    RUN_TEST(test_refused_inertia_shows_why);
    RUN_TEST(test_options_table);
    return UNITY_END();
}
