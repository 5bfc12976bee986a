// libFuzzer target over the C API: random parameter edits, options and a sequence of poses, with
// raw doubles (NaN, Inf, huge and tiny values included). Invariants: nothing crashes, and a solve
// that returns STEWART_OK never writes a non-finite output. Built with clang -fsanitize=fuzzer by
// scripts/fuzz.sh; tests/CMakeLists.txt also builds it with a replay main (fuzz_replay.cpp) that
// runs the committed corpus in tests/fuzz/corpus/api under ctest.
//
// Building a model (the 14-body mechanism, its block plan) costs far more than a solve, so models
// are kept across inputs, keyed by their parameters, in a small cache of the harness (the library
// itself has no global state); each input makes its own solver objects, so that it sees the
// same thing as in a fresh process.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>

#include "fuzz_reader.hpp"
#include "stewart/stewart.h"
#include "stewart/stewart_cueing.h"
#include "stewart/stewart_forward.h"
#include "stewart/stewart_linearize.h"
#include "stewart/stewart_plant.h"
#include "stewart/stewart_table.h"

namespace {

void require_finite(const stewart_inverse_output &o) {
    const double *all[] = {
        o.lengths.length, o.lengths.length_rate, o.lengths.length_accel, o.force,   o.motor_angle,
        o.motor_speed,    o.motor_accel,         o.motor_torque,         o.current, o.current_rate,
        o.voltage,        o.electrical_power,    o.motor_power};
    for (const double *g : all)
        for (int k = 0; k < STEWART_LEGS; ++k)
            if (!std::isfinite(g[k])) std::abort();
    if (!std::isfinite(o.condition) || !std::isfinite(o.residual)) std::abort();
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(o.base_force[i]) || !std::isfinite(o.base_torque[i])) std::abort();
}

// A model, kept for inputs with the same parameters.
struct CachedModel {
    stewart_params params;
    stewart_model *model = nullptr;
};

// Bounded: at most kCacheSize models live at once; a new parameter set replaces the oldest entry.
constexpr int kCacheSize = 8;
CachedModel cache[kCacheSize];
int next_victim = 0;

// The cached model for these parameters (built on first use), or null if the parameters are
// refused.
CachedModel *model_for(const stewart_params &params) {
    for (CachedModel &c : cache)
        if (c.model && std::memcmp(&c.params, &params, sizeof params) == 0) return &c;
    char message[STEWART_MESSAGE_SIZE];
    stewart_model *model = stewart_model_create(&params, message, sizeof message);
    if (!model) return nullptr;
    CachedModel &c = cache[next_victim];
    next_victim = (next_victim + 1) % kCacheSize;
    stewart_model_free(c.model);
    c.params = params;
    c.model = model;
    return &c;
}

// The forward API on the same model: raw lengths, rates, accelerations, guesses and options
// (NaN, Inf, huge), tracking or cold, the history copied, saved and loaded. Every call returns a
// known status; a filled result (STEWART_OK, STEWART_ERR_OTHER_BRANCH) is finite.
void fuzz_forward(Reader &in, const stewart_model *model) {
    stewart_forward_options options;
    stewart_forward_options_default(&options);
    const uint8_t choice = in.byte();
    if (choice & 1) options.tolerance = in.value();
    if (choice & 2) options.max_iterations = static_cast<int8_t>(in.byte());
    char message[STEWART_MESSAGE_SIZE];
    stewart_forward *forward = stewart_forward_create(model, &options, message, sizeof message);
    stewart_forward *saved = stewart_forward_create(model, &options, message, sizeof message);
    unsigned char state[1024];
    if (!forward || !saved || stewart_forward_state_size(forward) > sizeof state) {
        stewart_forward_free(saved);
        stewart_forward_free(forward);
        return;  // refused options (the message says which)
    }
    stewart_forward_input input{};
    double time = 0;
    for (int call = 0; call < 16 && in.left > 0; ++call) {
        const uint8_t what = in.byte();
        stewart_lengths &l = input.lengths;
        for (int k = 0; k < 6; ++k) l.length[k] = (what & 1) ? in.value() : 0.55 + in.value() / 10;
        for (int k = 0; k < 6 && (what & 2); ++k) l.length_rate[k] = in.value();
        for (int k = 0; k < 6 && (what & 4); ++k) l.length_accel[k] = in.value();
        for (int k = 0; k < 6 && (what & 8); ++k) input.guess[k] = in.value();
        if (what & 16) stewart_forward_reset(forward);
        time = (what & 32) ? in.value() : time + 1e-3;
        input.time = time;
        input.derivatives = (what & 2) ? ((what & 4) ? 2 : 1) : 0;
        input.use_guess = (what & 8) != 0;
        if (what & 64) {  // a rollback: back to the saved history, or to bytes (maybe broken)
            stewart_forward_save(saved, state, sizeof state);
            if (what & 128) state[in.byte() % stewart_forward_state_size(saved)] ^= in.byte();
            if (stewart_forward_load(forward, state, stewart_forward_state_size(saved)) !=
                STEWART_OK)
                stewart_forward_copy(forward, saved);
        }
        stewart_forward_output r;
        const stewart_status s = stewart_forward_solve(forward, &input, &r);
        stewart_forward_copy(saved, forward);
        if (s > STEWART_OK || s < STEWART_ERR_OTHER_BRANCH) std::abort();
        if (s != STEWART_OK && s != STEWART_ERR_OTHER_BRANCH) continue;
        const double *groups[3] = {r.pose.q, r.pose.q_dot, r.pose.q_ddot};
        for (const double *g : groups)
            for (int i = 0; i < 6; ++i)
                if (!std::isfinite(g[i])) std::abort();
        if (!std::isfinite(r.residual) || !std::isfinite(r.condition) || !std::isfinite(r.jump))
            std::abort();
    }
    stewart_forward_free(saved);
    stewart_forward_free(forward);
}

// The plant (forward dynamics) on the same model: random options, start states, forces (NaN, Inf,
// huge), step sizes (zero, negative, huge), output and reaction queries, and saved states with
// corrupted values loaded back. Every call returns a known status, a filled output is finite,
// and a saved state loaded back unchanged gives the same outputs bit for bit. The work of one
// input is bounded: at most kPlantCalls calls and kPlantMaxInternalSteps integrator steps per
// communication step (the options may ask for fewer, never for more).
constexpr int kPlantCalls = 8;
constexpr long kPlantMaxInternalSteps = 20;
// The doubles of a plant output (time to base_torque) and of the 13 bodies.
constexpr size_t kOutputDoubles = offsetof(stewart_plant_output, warnings) / sizeof(double);
constexpr size_t kBodyDoubles = sizeof(stewart_plant_body[STEWART_PLANT_BODIES]) / sizeof(double);

bool known_status(stewart_status s) { return s <= STEWART_OK && s >= STEWART_ERR_OTHER_BRANCH; }

void require_finite_values(const double *values, size_t count) {
    for (size_t i = 0; i < count; ++i)
        if (!std::isfinite(values[i])) std::abort();
}

void require_message(const stewart_plant *plant) {
    if (!std::memchr(stewart_plant_message(plant), '\0', STEWART_MESSAGE_SIZE)) std::abort();
}

// The outputs at the current state; finite whenever the status is OK.
stewart_status checked_output(const stewart_plant *plant, const double *force,
                              stewart_plant_output &out) {
    const stewart_status s = stewart_plant_output_get(plant, force, &out);
    if (!known_status(s)) std::abort();
    if (s == STEWART_OK) require_finite_values(&out.time, kOutputDoubles);
    return s;
}

void fuzz_plant(Reader &in, const stewart_model *model) {
    stewart_plant_options options;
    stewart_plant_options_default(&options);
    const uint8_t choice = in.byte();
    options.fidelity = (choice & 1) ? STEWART_FULL : STEWART_MASSLESS;
    if (choice & 2) options.fidelity = static_cast<int8_t>(in.byte());  // mostly invalid
    options.method = (choice >> 2) % 5;                                 // 4 is invalid
    if (choice & 0x20) options.relative_tolerance = in.value();
    if (choice & 0x40) options.absolute_tolerance = in.value();
    options.max_internal_steps = (choice & 0x80)
                                     ? static_cast<int8_t>(in.byte()) % kPlantMaxInternalSteps
                                     : kPlantMaxInternalSteps;
    char message[STEWART_MESSAGE_SIZE];
    stewart_plant *plant = stewart_plant_create(model, &options, message, sizeof message);
    if (!plant) {  // refused options (or a singular home pose): a message says why
        if (!std::memchr(message, '\0', sizeof message) || message[0] == '\0') std::abort();
        return;
    }
    const size_t state_size = stewart_plant_state_size(plant);
    unsigned char saved[1024];
    double force[STEWART_LEGS];
    stewart_plant_input step{};
    if (state_size > sizeof saved) std::abort();
    const double home_height = stewart_model_params(model)->home_height;
    for (int call = 0; call < kPlantCalls && in.left > 0; ++call) {
        const uint8_t what = in.byte();
        stewart_status s = STEWART_OK;
        stewart_plant_output out;
        switch (what % 6) {
            case 0: {  // a start state near home, or raw values
                double pose[6], rate[6];
                for (int i = 0; i < 6; ++i) {
                    pose[i] =
                        (what & 8) ? in.value() : (i == 2 ? home_height : 0) + in.value() / 20;
                    rate[i] = (what & 16) ? in.value() : 0;
                }
                s = stewart_plant_set_state(plant, (what & 32) ? in.value() : 0, pose, rate);
                break;
            }
            case 1:
            case 2: {  // a step: raw or moderate forces and step size, linear or Hermite profile
                for (int k = 0; k < STEWART_LEGS; ++k) {
                    step.force_start[k] = (what & 8) ? in.value() : 200 + 100 * in.value();
                    step.force_end[k] = (what & 16) ? in.value() : step.force_start[k];
                    step.force_rate_start[k] = in.value();
                    step.force_rate_end[k] = in.value();
                }
                step.h = (what & 32) ? in.value() : 1e-3;
                step.derivatives = (what & 64) ? 1 : 0;
                s = stewart_plant_step(plant, &step, &out);
                if (s == STEWART_OK) require_finite_values(&out.time, kOutputDoubles);
                if (s == STEWART_OK && checked_output(plant, nullptr, out) != STEWART_OK)
                    std::abort();
                stewart_plant_statistics stats;
                stewart_plant_statistics_get(plant, &stats);
                if (stats.steps < 0 || stats.steps > kPlantMaxInternalSteps) std::abort();
                break;
            }
            case 3: {  // outputs and reactions under other forces, and the bodies
                for (int k = 0; k < STEWART_LEGS; ++k) force[k] = in.value();
                const double *f = (what & 8) ? force : nullptr;
                s = checked_output(plant, f, out);
                stewart_plant_reactions reactions;
                const stewart_status r = stewart_plant_reactions_get(plant, f, &reactions);
                if (!known_status(r)) std::abort();
                if (r == STEWART_OK)
                    require_finite_values(&reactions.base_cardan_force[0][0],
                                          sizeof reactions / sizeof(double));
                stewart_plant_body bodies[STEWART_PLANT_BODIES];
                const stewart_status b = stewart_plant_bodies(plant, bodies);
                if (!known_status(b)) std::abort();
                if (b == STEWART_OK) require_finite_values(bodies[0].position, kBodyDoubles);
                break;
            }
            case 4: {  // save, load back unchanged: the same outputs bit for bit
                stewart_plant_output before, after;
                const bool had_output = checked_output(plant, nullptr, before) == STEWART_OK;
                if (stewart_plant_save(plant, saved, state_size) != STEWART_OK) std::abort();
                if (stewart_plant_load(plant, saved, state_size) != STEWART_OK) std::abort();
                stewart_plant *copy =
                    stewart_plant_create(model, &options, message, sizeof message);
                if (!copy || stewart_plant_copy(copy, plant) != STEWART_OK) std::abort();
                stewart_plant_free(copy);
                const size_t bytes = kOutputDoubles * sizeof(double);
                if (had_output && (checked_output(plant, nullptr, after) != STEWART_OK ||
                                   std::memcmp(&before.time, &after.time, bytes) != 0))
                    std::abort();
                break;
            }
            case 5: {  // save, corrupt values (or the size), load: refused or a usable state
                if (stewart_plant_save(plant, saved, state_size) != STEWART_OK) std::abort();
                const int edits = 1 + (what >> 3) % 4;
                const size_t doubles = state_size / sizeof(double);  // the header's bytes aside
                for (int e = 0; e < edits; ++e) {
                    const double value = in.value();
                    std::memcpy(saved + state_size - sizeof(double) * (1 + in.byte() % doubles),
                                &value, sizeof value);
                }
                const size_t count = (what & 0x80) ? state_size - 1 + in.byte() % 3 : state_size;
                s = stewart_plant_load(plant, saved, count);
                if (s != STEWART_OK && s != STEWART_ERR_ARGUMENT) std::abort();
                if (s == STEWART_OK) checked_output(plant, nullptr, out);
                break;
            }
        }
        if (!known_status(s)) std::abort();
        require_message(plant);
    }
    stewart_plant_free(plant);
}

// Linearisation on the same model: raw or moderate poses, rates, accelerations and forces (NaN,
// Inf, huge); a known status, a filled result finite, a message always terminated.
void fuzz_linearize(Reader &in, const stewart_model *model) {
    stewart_linearize_options options;
    stewart_linearize_options_default(&options);
    options.fidelity = in.byte() % 4;  // 0 and 3 are refused
    char message[STEWART_MESSAGE_SIZE];
    stewart_linearize *l = stewart_linearize_create(model, &options, message, sizeof message);
    if (!l) return;
    for (int call = 0; call < 8 && in.left > 0; ++call) {
        const uint8_t what = in.byte();
        stewart_linearize_input input{};
        const double home[6] = {0, 0, 0.5, 0, 0, 0};
        for (int i = 0; i < 6; ++i) {
            input.pose.q[i] = (what & 1) ? in.value() : home[i] + in.value() / 100;
            input.pose.q_dot[i] = (what & 2) ? in.value() : 0;
            input.pose.q_ddot[i] = (what & 4) ? in.value() : 0;
            input.force[i] = (what & 8) ? in.value() : 300;
        }
        stewart_status s;
        if (what & 16) {
            stewart_linearize_inverse_output out;
            s = stewart_linearize_inverse(l, &input.pose, &out);
            if (s == STEWART_OK)
                for (size_t i = 0; i < sizeof out.jacobian / sizeof(double); ++i)
                    if (!std::isfinite((&out.jacobian[0][0])[i])) std::abort();
        } else {
            stewart_linearize_output out;
            s = stewart_linearize_plant(l, &input, &out);
            if (s == STEWART_OK)
                for (size_t i = 0; i < sizeof out.A / sizeof(double); ++i)
                    if (!std::isfinite((&out.A[0][0])[i])) std::abort();
        }
        if (s > STEWART_OK || s < STEWART_ERR_OTHER_BRANCH) std::abort();
        if (!std::memchr(stewart_linearize_message(l), '\0', STEWART_MESSAGE_SIZE)) std::abort();
    }
    stewart_linearize_free(l);
}


// The cueing unit on the same model: raw options (some out of range: refused), raw or moderate
// vehicle inputs and steps (NaN, Inf, huge), save and load. A known status; a step that returns
// STEWART_OK gives finite outputs and a pose within every limit of the machine.
void fuzz_cueing(Reader &in, const stewart_model *model) {
    stewart_cueing_options options;
    stewart_cueing_options_default(&options);
    const uint8_t edits = in.byte();
    for (int e = 0; e < edits % 4; ++e) {
        const int i = in.byte() % stewart_cueing_option_count();
        stewart_cueing_option_set(&options, i, in.value(), nullptr, 0);
    }
    char message[STEWART_MESSAGE_SIZE];
    stewart_cueing *c = stewart_cueing_create(model, &options, message, sizeof message);
    if (!c) return;
    stewart_limits_options lo;
    stewart_limits_options_default(&lo);
    lo.warn_condition = options.warn_condition;
    stewart_limits *limits = stewart_limits_create(model, &lo, message, sizeof message);
    unsigned char state[4096];
    const size_t size = stewart_cueing_state_size(c);
    for (int call = 0; limits && call < 16 && in.left > 0; ++call) {
        const uint8_t what = in.byte();
        stewart_cueing_input input{};
        input.dt = (what & 1) ? in.value() : 1e-3 * (in.byte() % 50);
        for (int i = 0; i < 3; ++i) {
            input.specific_force[i] =
                (what & 2) ? in.value() : in.value() / 1e3 + (i == 2 ? 9.81 : 0);
            input.angular_velocity[i] = (what & 4) ? in.value() : in.value() / 1e3;
        }
        if ((what & 8) && size <= sizeof state) {
            if (stewart_cueing_save(c, state, size) != STEWART_OK) std::abort();
            if (what & 16) state[in.byte() % size] ^= in.byte();
            stewart_cueing_load(c, state, size);  // corrupted bytes: refused or a usable state
        }
        stewart_cueing_output out;
        const stewart_status s = stewart_cueing_step(c, &input, &out);
        if (s != STEWART_OK && s != STEWART_ERR_ARGUMENT) std::abort();
        if (s != STEWART_OK) continue;
        require_finite_values(out.pose.q, 6);
        require_finite_values(out.pose.q_dot, 6);
        require_finite_values(out.pose.q_ddot, 6);
        stewart_limits_input check{};
        std::memcpy(check.q, out.pose.q, sizeof check.q);
        stewart_limits_output verdict;
        if (stewart_limits_check(limits, &check, &verdict) != STEWART_OK ||
            verdict.first != STEWART_LIMIT_NONE)
            std::abort();
    }
    stewart_limits_free(limits);
    stewart_cueing_free(c);
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *bytes, size_t size) {
    Reader in{bytes, size};
    stewart_params params;
    stewart_params_default(&params);
    uint8_t edits = 0;
    in.take(&edits, 1);
    for (int e = 0; e < edits % 8; ++e) {
        uint8_t field = 0;
        double value = 0;
        if (!in.take(&field, 1) || !in.take(&value, sizeof value)) break;
        reinterpret_cast<double *>(&params)[field % (sizeof params / sizeof(double))] = value;
    }
    stewart_inverse_options options;
    stewart_inverse_options_default(&options);
    uint8_t choice = 0;
    in.take(&choice, 1);
    options.fidelity = choice % 4;  // 3 is invalid on purpose
    options.modified_newton = (choice >> 2) & 1;
    if (choice & 0x80) in.take(&options.tolerance, sizeof options.tolerance);

    CachedModel *c = model_for(params);
    if (!c) return 0;
    char message[STEWART_MESSAGE_SIZE];
    stewart_inverse *inverse = stewart_inverse_create(c->model, &options, message, sizeof message);
    stewart_inverse *saved = stewart_inverse_create(c->model, &options, message, sizeof message);
    stewart_inverse_input pose;
    stewart_inverse_output out;
    while (inverse && saved && in.take(&pose.pose, sizeof pose.pose)) {
        if (stewart_inverse_solve(inverse, &pose, &out) == STEWART_OK) require_finite(out);
        stewart_inverse_copy(saved, inverse);
    }
    stewart_inverse_free(saved);
    stewart_inverse_free(inverse);
    Reader again{bytes, size};  // the pose loop takes every byte: read them again
    fuzz_forward(again, c->model);
    Reader plant_bytes{bytes, size};
    fuzz_plant(plant_bytes, c->model);
    Reader linearize_bytes{bytes, size};
    fuzz_linearize(linearize_bytes, c->model);
    Reader cueing_bytes{bytes, size};
    fuzz_cueing(cueing_bytes, c->model);
    return 0;
}
