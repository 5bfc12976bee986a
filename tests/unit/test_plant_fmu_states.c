/*
 * Serialised FMU states of the plant, corrupted at random (thousands, FMI 2 and FMI 3): a
 * deserialisation either refuses the state with a message, or the state is set and the unit
 * steps normally from it (OK or Warning), with leg lengths the closed form of its pose and states
 * it saves again accepted. A state of a terminated unit is one (it steps only after Reset), and
 * one whose max_internal_steps was lowered may run out of them: both say so.
 */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "plant_fmu_unit.h"
#include "stewart/stewart.h"
#include "test_support.h"
#include "unity.h"

#define FIRST_PARAM 210 /* the geometry and masses: value references 210..259 */
#define LAST_PARAM 259
#define TRIALS 1500 /* per FMI version */

void setUp(void) {}
void tearDown(void) {}

/* Corrupts the bytes at random: a double anywhere (8-byte aligned from the start of the values,
 * or in the plant's data at the end), an int32 (mode, flags, options, statistics), or a byte. */
static void corrupt(uint64_t *rng, unsigned char *bytes, size_t n, size_t plant_bytes) {
    const uint64_t r = test_random(rng);
    const size_t values = 16; /* magic and the size of the values */
    switch (r % 4) {
        case 0:
        case 1: {
            const size_t at = r % 4 == 0 ? values + 8 * ((r >> 8) % ((n - values - 8) / 8))
                                         : n - plant_bytes + 8 * ((r >> 8) % (plant_bytes / 8));
            double v;
            memcpy(&v, bytes + at, sizeof v);
            v = corrupted_value(rng, v);
            memcpy(bytes + at, &v, sizeof v);
            return;
        }
        case 2: {
            static const int32_t small[] = {-1, 0, 1, 2, 3, 4, 8, 16, 1000000, INT32_MAX};
            const size_t at = values + 4 * ((r >> 8) % ((n - values - 4) / 4));
            const int32_t v = small[(r >> 40) % (sizeof small / sizeof small[0])];
            memcpy(bytes + at, &v, sizeof v);
            return;
        }
        default: bytes[values + (r >> 8) % (n - values)] ^= (unsigned char)(1 + (r >> 40) % 255);
    }
}

static int get_state(unit *u, void **s) {
    return u->v3 ? (int)fmi3GetFMUState(u->c, s) : (int)fmi2GetFMUstate(u->c, s);
}
static int set_state(unit *u, void *s) {
    return u->v3 ? (int)fmi3SetFMUState(u->c, s) : (int)fmi2SetFMUstate(u->c, s);
}
static void free_state(unit *u, void **s) {
    if (u->v3) fmi3FreeFMUState(u->c, s);
    else fmi2FreeFMUstate(u->c, s);
}
static size_t serialise(unit *u, void *s, unsigned char *bytes, size_t capacity) {
    size_t n = 0;
    const int ok = u->v3 ? fmi3SerializedFMUStateSize(u->c, s, &n) == fmi3OK && n <= capacity &&
                               fmi3SerializeFMUState(u->c, s, bytes, n) == fmi3OK
                         : fmi2SerializedFMUstateSize(u->c, s, &n) == fmi2OK && n <= capacity &&
                               fmi2SerializeFMUstate(u->c, s, (fmi2Byte *)bytes, n) == fmi2OK;
    TEST_ASSERT_TRUE_MESSAGE(ok, u->log.last);
    return n;
}
static int deserialise(unit *u, const unsigned char *bytes, size_t n, void **s) {
    return u->v3 ? (int)fmi3DeserializeFMUState(u->c, bytes, n, s)
                 : (int)fmi2DeSerializeFMUstate(u->c, (const fmi2Byte *)bytes, n, s);
}
static double get_real(unit *u, unsigned vr) {
    double v = NAN;
    if (u->v3) fmi3GetFloat64(u->c, &vr, 1, &v, 1);
    else fmi2GetReal(u->c, &vr, 1, &v);
    return v;
}
static int32_t get_int(unit *u, unsigned vr) {
    int32_t v = -1;
    if (u->v3) fmi3GetInt32(u->c, &vr, 1, &v, 1);
    else fmi2GetInteger(u->c, &vr, 1, &v);
    return v;
}

/* Reset, initialise at 0 and step once: the unit is usable again. */
static int recovers(unit *u, const double force[6]) {
    double last;
    const int init =
        u->v3 ? fmi3Reset(u->c) == fmi3OK &&
                    fmi3EnterInitializationMode(u->c, fmi3False, 0, 0, fmi3False, 0) == fmi3OK &&
                    fmi3ExitInitializationMode(u->c) == fmi3OK
              : fmi2Reset(u->c) == fmi2OK &&
                    fmi2SetupExperiment(u->c, fmi2False, 0, 0, fmi2False, 0) == fmi2OK &&
                    fmi2EnterInitializationMode(u->c) == fmi2OK &&
                    fmi2ExitInitializationMode(u->c) == fmi2OK;
    return init && set_forces(u, force) == 0 && do_step_status(u, 0, STEP, &last) == 0;
}

/* Why the unit, just set to a deserialised state, does not step normally, or NULL. */
static const char *steps_normally(unit *u, const double force[6], const double params_now[],
                                  const double base_params[], const stewart_params *defaults) {
    const double t = get_real(u, VR_time);
    if (set_forces(u, force) != 0) return "the forces are refused";
    for (int i = 0; i < 5; ++i) {
        double last;
        const int s = do_step_status(u, t + i * STEP, STEP, &last);
        if (s == fmi2Error && strstr(u->log.last, "is not allowed in")) /* e.g. terminated */
            return recovers(u, force) ? NULL : "no recovery by Reset";
        if (s == fmi2Discard && strstr(u->log.last, "TOO_MUCH_WORK") &&
            get_int(u, VR_max_internal_steps) < 10000)
            return NULL; /* max_internal_steps lowered: the unit says so */
        if (s != fmi2OK && s != fmi2Warning) return u->log.last;
    }
    snapshot out;
    if (!read_outputs(u, &out)) return "outputs cannot be read";
    for (int i = 0; i < N_REALS; ++i)
        if (!isfinite(out.real[i])) return "an output is not finite";
    if (!memcmp(params_now, base_params, (LAST_PARAM - FIRST_PARAM + 1) * sizeof(double))) {
        stewart_pose p = {{0}, {0}, {0}};
        memcpy(p.q, out.real, sizeof p.q);
        for (int k = 0; k < 6; ++k) {
            const double expected = closed_form_length(defaults, &p, k);
            if (!(fabs(out.real[12 + k] - expected) <= 1e-9 * fmax(1.0, expected)))
                return "a leg length is not the closed form of the output pose";
        }
    }
    /* what it saves now is a state it accepts */
    void *again = NULL, *back = NULL;
    static unsigned char bytes[1 << 16];
    if (get_state(u, &again) != 0) return "GetFMUState refused";
    const size_t n = serialise(u, again, bytes, sizeof bytes);
    const int s = deserialise(u, bytes, n, &back);
    free_state(u, &again);
    free_state(u, &back);
    return s == 0 ? NULL : u->log.last;
}

static void random_corrupt_states(int v3) {
    stewart_params defaults;
    stewart_params_default(&defaults);
    double force[6];
    static_forces(STEWART_FULL, force);
    for (int k = 0; k < 6; ++k) force[k] *= 1.01; /* the platform moves */
    unit u;
    const unsigned start_vr[3] = {VR_x_dot0, VR_roll_dot0, VR_yaw_dot0};
    const double start[3] = {0.01, 0.1, -0.2};
    TEST_ASSERT_TRUE_MESSAGE(unit_open_at(&u, v3, STEWART_FULL, force, 2.0, 3, start_vr, start),
                             u.log.last);
    double last;
    for (int i = 0; i < 10; ++i)
        TEST_ASSERT_EQUAL_MESSAGE(fmi2OK, do_step(&u, 2.0 + i * STEP, STEP, &last), u.log.last);
    void *state = NULL;
    TEST_ASSERT_EQUAL(0, get_state(&u, &state));
    static unsigned char base[1 << 16], bytes[1 << 16];
    const size_t n = serialise(&u, state, base, sizeof base);
    /* the plant's saved bytes at the end: a header (3 unsigned) and 25 doubles */
    const size_t plant_bytes = 3 * sizeof(unsigned) + 25 * sizeof(double);
    double base_params[LAST_PARAM - FIRST_PARAM + 1], params_now[LAST_PARAM - FIRST_PARAM + 1];
    for (unsigned vr = FIRST_PARAM; vr <= LAST_PARAM; ++vr)
        base_params[vr - FIRST_PARAM] = get_real(&u, vr);
    uint64_t rng = 0xD1B54A32D192ED03ULL + (uint64_t)v3;
    int refused = 0, accepted = 0, failures = 0;
    for (int trial = 0; trial < TRIALS; ++trial) {
        memcpy(bytes, base, n);
        const int edits = 1 + (int)(test_random(&rng) % 2);
        for (int e = 0; e < edits; ++e) corrupt(&rng, bytes, n, plant_bytes);
        void *other = NULL;
        u.log.last[0] = '\0';
        if (deserialise(&u, bytes, n, &other) != 0) {
            ++refused;
            TEST_ASSERT_NOT_NULL_MESSAGE(strstr(u.log.last, "DeserializeFMUState"), u.log.last);
            TEST_ASSERT_EQUAL(0, set_state(&u, state)); /* the unit is untouched and usable */
            continue;
        }
        ++accepted;
        const char *why = NULL;
        if (set_state(&u, other) != 0) why = "a state it accepted cannot be set";
        for (unsigned vr = FIRST_PARAM; vr <= LAST_PARAM; ++vr)
            params_now[vr - FIRST_PARAM] = get_real(&u, vr);
        if (!why) why = steps_normally(&u, force, params_now, base_params, &defaults);
        free_state(&u, &other);
        if (why) {
            ++failures;
            if (failures <= 10) {
                size_t first = 0;
                while (first < n && bytes[first] == base[first]) ++first;
                printf("FMI %d trial %d (first changed byte %zu of %zu): accepted, then: %s\n",
                       v3 ? 3 : 2, trial, first, n, why);
            }
        }
        if (set_state(&u, state) != 0)
            TEST_ASSERT_TRUE(recovers(&u, force) && set_state(&u, state) == 0);
    }
    printf("FMI %d, random corrupt FMU states: %d refused, %d accepted, %d failures\n", v3 ? 3 : 2,
           refused, accepted, failures);
    free_state(&u, &state);
    unit_free(&u);
    TEST_ASSERT_EQUAL_INT(0, failures);
    TEST_ASSERT_TRUE(refused > 0 && accepted > 0);
}

static void test_random_corrupt_states_fmi2(void) { random_corrupt_states(0); }
static void test_random_corrupt_states_fmi3(void) { random_corrupt_states(1); }

/* The state of a unit opened with the platform moving and base_radius = `radius` after 10 steps,
 * serialised into bytes (its size returned); the unit stays open. */
static size_t moving_state(unit *u, int v3, double radius, unsigned char *bytes, size_t capacity) {
    double force[6], last;
    static_forces(STEWART_FULL, force);
    for (int k = 0; k < 6; ++k) force[k] *= 1.01;
    const unsigned vr[3] = {VR_base_radius, VR_x_dot0, VR_roll_dot0};
    const double value[3] = {radius, 0.01, 0.1};
    TEST_ASSERT_TRUE_MESSAGE(unit_open_at(u, v3, STEWART_FULL, force, 0.0, 3, vr, value),
                             u->log.last);
    for (int i = 0; i < 10; ++i)
        TEST_ASSERT_EQUAL_MESSAGE(fmi2OK, do_step(u, i * STEP, STEP, &last), u->log.last);
    void *state = NULL;
    TEST_ASSERT_EQUAL(0, get_state(u, &state));
    const size_t n = serialise(u, state, bytes, capacity);
    free_state(u, &state);
    return n;
}

/* Deserialises into a state and frees it: the status; the unit's last message says why. */
static int deserialise_status(unit *u, const unsigned char *bytes, size_t n) {
    void *s = NULL;
    u->log.last[0] = '\0';
    const int status = deserialise(u, bytes, n, &s);
    if (s) free_state(u, &s);
    return status;
}

/* A state with the unit's own parameters is checked on the unit's model (no model is built), one
 * with other parameters on a model of its own. Both give the same verdict and reason for every
 * corruption: the state of `own` (base_radius 0.5 m) corrupted at random is deserialised by `own`
 * and by `other` (base_radius 0.52 m, so a model is built). A state whose plant moved under
 * another base radius is accepted (its leg lengths are right for its own geometry, not the
 * unit's), and refused once its radius is patched to the unit's: the parameters checked are the
 * state's. */
static void test_state_check_on_own_model_same_verdict(void) {
    for (int v3 = 0; v3 < 2; ++v3) {
        unit own, other;
        static unsigned char base[1 << 16], bytes[1 << 16], base_other[1 << 16];
        const size_t n = moving_state(&own, v3, 0.5, base, sizeof base);
        const size_t n_other = moving_state(&other, v3, 0.52, base_other, sizeof base_other);
        TEST_ASSERT_EQUAL(n, n_other);
        const size_t plant_bytes = 3 * sizeof(unsigned) + 25 * sizeof(double);
        /* unchanged: accepted by both */
        TEST_ASSERT_EQUAL_MESSAGE(0, deserialise_status(&own, base, n), own.log.last);
        TEST_ASSERT_EQUAL_MESSAGE(0, deserialise_status(&other, base, n), other.log.last);
        /* named corruptions on the fast path: an output off by one ulp, a non-unit quaternion */
        const size_t x_at = 16 + VR_x * sizeof(double);
        double x;
        memcpy(bytes, base, n);
        memcpy(&x, bytes + x_at, sizeof x);
        x = nextafter(x, INFINITY);
        memcpy(bytes + x_at, &x, sizeof x);
        TEST_ASSERT_EQUAL(fmi2Error, deserialise_status(&own, bytes, n));
        TEST_ASSERT_NOT_NULL_MESSAGE(strstr(own.log.last, "output x = "), own.log.last);
        memcpy(bytes, base, n);
        const size_t q0_at = n - plant_bytes + 3 * sizeof(unsigned) + 4 * sizeof(double);
        const double q0 = 0.5; /* the first quaternion component: the norm is no longer 1 */
        memcpy(bytes + q0_at, &q0, sizeof q0);
        TEST_ASSERT_EQUAL(fmi2Error, deserialise_status(&own, bytes, n));
        TEST_ASSERT_NOT_NULL_MESSAGE(strstr(own.log.last, "quaternion norm"), own.log.last);
        /* random corruptions: the same verdict and reason on both paths */
        uint64_t rng = 0x9E3779B97F4A7C15ULL + (uint64_t)v3;
        int refused = 0, accepted = 0;
        static char reason[sizeof own.log.last];
        for (int trial = 0; trial < 300; ++trial) {
            memcpy(bytes, base, n);
            corrupt(&rng, bytes, n, plant_bytes);
            const int fast = deserialise_status(&own, bytes, n);
            memcpy(reason, own.log.last, sizeof reason);
            const int full = deserialise_status(&other, bytes, n);
            TEST_ASSERT_EQUAL_MESSAGE(full, fast, reason);
            TEST_ASSERT_EQUAL_STRING(other.log.last, reason);
            if (fast == 0) ++accepted;
            else ++refused;
        }
        TEST_ASSERT_TRUE(refused > 0 && accepted > 0);
        /* another radius: its own state is accepted, with the unit's radius patched in refused */
        TEST_ASSERT_EQUAL_MESSAGE(0, deserialise_status(&own, base_other, n), own.log.last);
        memcpy(bytes, base_other, n);
        const double radius = 0.5;
        memcpy(bytes + 16 + VR_base_radius * sizeof(double), &radius, sizeof radius);
        TEST_ASSERT_EQUAL(fmi2Error, deserialise_status(&own, bytes, n));
        TEST_ASSERT_NOT_NULL_MESSAGE(strstr(own.log.last, "is not the plant's"), own.log.last);
        unit_free(&own);
        unit_free(&other);
    }
}

/* The unit's model replaced (Reset, another base radius, initialised again): states with the new
 * radius are checked on the new model and accepted, corrupt ones refused, states with the old
 * radius still accepted (a checking plant kept from the old model would refuse them, and under
 * ASan be a use after free). */
static void test_state_check_follows_new_parameters(void) {
    unit u;
    static unsigned char before[1 << 16], after[1 << 16];
    const size_t n = moving_state(&u, 0, 0.5, before, sizeof before);
    TEST_ASSERT_EQUAL_MESSAGE(0, deserialise_status(&u, before, n), u.log.last);
    unit_free(&u);
    unit other;
    const size_t n_after = moving_state(&other, 0, 0.52, after, sizeof after);
    TEST_ASSERT_EQUAL_MESSAGE(0, deserialise_status(&other, before, n), other.log.last);
    TEST_ASSERT_EQUAL_MESSAGE(0, deserialise_status(&other, after, n_after), other.log.last);
    TEST_ASSERT_EQUAL(fmi2OK, fmi2Reset(other.c));
    const unsigned vr = VR_base_radius;
    const double radius = 0.5;
    TEST_ASSERT_EQUAL(fmi2OK, fmi2SetReal(other.c, &vr, 1, &radius));
    TEST_ASSERT_EQUAL(fmi2OK, fmi2SetupExperiment(other.c, fmi2False, 0, 0, fmi2False, 0));
    TEST_ASSERT_EQUAL(fmi2OK, fmi2EnterInitializationMode(other.c));
    TEST_ASSERT_EQUAL(fmi2OK, fmi2ExitInitializationMode(other.c));
    TEST_ASSERT_EQUAL_MESSAGE(0, deserialise_status(&other, before, n), other.log.last);
    TEST_ASSERT_EQUAL_MESSAGE(0, deserialise_status(&other, after, n_after), other.log.last);
    const size_t x_at = 16 + VR_x * sizeof(double);
    const double x = 1.0;
    memcpy(before + x_at, &x, sizeof x);
    TEST_ASSERT_EQUAL(fmi2Error, deserialise_status(&other, before, n));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(other.log.last, "output x = "), other.log.last);
    unit_free(&other);
}

/* After a Discard for a non-finite FMI 2 force derivative, the derivatives are cleared: a retry
 * that sets only the forces again is accepted (the forces held over the step). */
static void test_bad_force_derivative_cleared_after_discard(void) {
    double force[6], last;
    static_forces(STEWART_FULL, force);
    unit u;
    unit_start(&u, 0, STEWART_FULL, force);
    const double rate[6] = {0, NAN, 0, 0, 0, 0};
    TEST_ASSERT_EQUAL(fmi2OK, set_force_rates(&u, rate));
    TEST_ASSERT_EQUAL(fmi2Discard, do_step(&u, 0, STEP, &last));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(u.log.last, "cleared"), u.log.last);
    TEST_ASSERT_EQUAL(fmi2OK, set_forces(&u, force));
    TEST_ASSERT_EQUAL_MESSAGE(fmi2OK, do_step(&u, 0, STEP, &last), u.log.last);
    TEST_ASSERT_EQUAL_DOUBLE(STEP, last);
    unit_free(&u);
}

/* A state whose gravity is 1e300 m/s2 makes no plant: deserialisation refuses it naming the field
 * and its magnitude ("out of memory checking the plant data" before); an absolute tolerance no plant can use is an
 * Error at initialisation naming it ("invalid parameter: ARKODE failed ..." before). */
static void test_messages_name_the_cause(void) {
    for (int v3 = 0; v3 < 2; ++v3) {
        double force[6], last;
        static_forces(STEWART_FULL, force);
        unit u;
        unit_start(&u, v3, STEWART_FULL, force);
        TEST_ASSERT_EQUAL(fmi2OK, do_step(&u, 0, STEP, &last));
        void *state = NULL, *other = NULL;
        TEST_ASSERT_EQUAL(0, get_state(&u, &state));
        static unsigned char bytes[1 << 16];
        const size_t n = serialise(&u, state, bytes, sizeof bytes);
        const double gravity = -1e300;
        memcpy(bytes + 16 + VR_gravity_3 * sizeof(double), &gravity, sizeof gravity);
        TEST_ASSERT_EQUAL(fmi2Error, deserialise(&u, bytes, n, &other));
        TEST_ASSERT_NOT_NULL_MESSAGE(strstr(u.log.last,
                                            "gravity[3] = -1e+300 m/s2 is beyond any machine"),
                                     u.log.last);
        free_state(&u, &state);
        unit_free(&u);
        const unsigned vr = VR_absolute_tolerance;
        const double tiny = 1e-300;
        TEST_ASSERT_FALSE(unit_open_at(&u, v3, STEWART_FULL, force, 0.0, 1, &vr, &tiny));
        TEST_ASSERT_NOT_NULL_MESSAGE(strstr(u.log.last, "absolute_tolerance = 1e-300 must be >="),
                                     u.log.last);
        unit_free(&u);
    }
}

/* A non-finite FMI 2 start time is an Error at SetupExperiment naming it (it was accepted, and an
 * FMU state taken then gave the time back as NaN with status OK: fuzz_fmu's campaign of issue 23);
 * the runtime's check, shared by every unit. */
static void test_non_finite_start_time_refused(void) {
    double force[6];
    static_forces(STEWART_FULL, force);
    unit u;
    unit_start(&u, 0, STEWART_FULL, force);
    TEST_ASSERT_EQUAL(fmi2OK, fmi2Reset(u.c));
    TEST_ASSERT_EQUAL(fmi2Error, fmi2SetupExperiment(u.c, fmi2False, 0, NAN, fmi2False, 0));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(u.log.last, "startTime = nan must be finite"), u.log.last);
    TEST_ASSERT_EQUAL(fmi2Error, fmi2SetupExperiment(u.c, fmi2False, 0, -INFINITY, fmi2False, 0));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(u.log.last, "startTime = -inf must be finite"), u.log.last);
    unit_free(&u);
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_random_corrupt_states_fmi2);
    RUN_TEST(test_random_corrupt_states_fmi3);
    RUN_TEST(test_bad_force_derivative_cleared_after_discard);
    RUN_TEST(test_messages_name_the_cause);
    RUN_TEST(test_non_finite_start_time_refused);
    RUN_TEST(test_state_check_on_own_model_same_verdict);
    RUN_TEST(test_state_check_follows_new_parameters);
    return UNITY_END();
}
