// libFuzzer target over the Model Exchange plant (fmu/models/plant_me on fmu/runtime, both FMI
// layers, linked in statically), driven through the fmi2* or the fmi3* functions (flag bit 5) as a
// master that integrates it would drive it, and as a broken one would: SetTime, SetContinuousStates
// (any value, near home or wild, wrong counts), GetDerivatives, event mode and back, completed
// integrator steps, forces and parameters, a few explicit Euler steps, FMU states rolled back and
// serialised (corrupted), calls out of sequence.
//
// Invariants: nothing crashes or trips a sanitizer; every call returns OK, Warning, Discard or
// Error (fuzz_fmu_unit.hpp); derivatives, states and Real outputs read back with status OK are
// finite; status is 0, 1 or 3; a Discarded SetContinuousStates changes no state; a rolled-back
// FMU state gives back the same outputs bit for bit; every log message is a NUL-terminated string.
//
// Built with clang -fsanitize=fuzzer by scripts/fuzz.sh (target `me`); tests/CMakeLists.txt also
// builds it with the replay main (fuzz_replay.cpp) that runs tests/fuzz/corpus/plant_me_fmu under
// ctest (fuzz_plant_me_fmu_corpus). Input layout (tests/fuzz/fuzz_seeds.py --me writes seeds):
// byte 0 flags (bit 0: logging on; bit 1: initialise at once with fidelity 1 + bit 2; bit 5:
// FMI 3 instead of FMI 2), then operations: 1 opcode byte and its arguments.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "fuzz_fmu_unit.hpp"
#include "fuzz_plant_unit.hpp"

namespace {

constexpr size_t kStates = 12;  // x .. yaw, x_dot .. yaw_dot (plant_me/config.h)

// The Model Exchange calls on either layer; each returns a known status.
int get_states(Unit &u, double *x, size_t n) {
    return known(u.v3 ? (int)fmi3GetContinuousStates(u.c, x, n)
                      : (int)fmi2GetContinuousStates(u.c, x, n));
}
int set_states(Unit &u, const double *x, size_t n) {
    return known(u.v3 ? (int)fmi3SetContinuousStates(u.c, x, n)
                      : (int)fmi2SetContinuousStates(u.c, x, n));
}
int get_derivatives(Unit &u, double *dx, size_t n) {
    return known(u.v3 ? (int)fmi3GetContinuousStateDerivatives(u.c, dx, n)
                      : (int)fmi2GetDerivatives(u.c, dx, n));
}
int set_time(Unit &u, double t) {
    return known(u.v3 ? (int)fmi3SetTime(u.c, t) : (int)fmi2SetTime(u.c, t));
}
int completed_step(Unit &u) {
    if (u.v3) {
        fmi3Boolean event = fmi3True, terminate = fmi3True;
        const int s = known(fmi3CompletedIntegratorStep(u.c, fmi3True, &event, &terminate));
        if (s == 0 && (event || terminate)) std::abort();  // no events in this unit
        return s;
    }
    fmi2Boolean event = fmi2True, terminate = fmi2True;
    const int s = known(fmi2CompletedIntegratorStep(u.c, fmi2True, &event, &terminate));
    if (s == 0 && (event || terminate)) std::abort();
    return s;
}
// Event mode and its calls (selector b): enter, update the discrete states, leave, and the
// nominals and event indicators (the unit has none: n = 1 must be an Error).
void event_call(Unit &u, uint8_t b) {
    double values[kStates + 1];
    const size_t n = (b >> 3) & 1;
    switch (b % 6) {
        case 0: known(u.v3 ? (int)fmi3EnterEventMode(u.c) : (int)fmi2EnterEventMode(u.c)); break;
        case 1:
            if (u.v3) {
                fmi3Boolean f[5];
                double next = 0;
                known(fmi3UpdateDiscreteStates(u.c, &f[0], &f[1], &f[2], &f[3], &f[4], &next));
            } else {
                fmi2EventInfo info;
                known(fmi2NewDiscreteStates(u.c, &info));
            }
            break;
        case 2:
            known(u.v3 ? (int)fmi3EnterContinuousTimeMode(u.c)
                       : (int)fmi2EnterContinuousTimeMode(u.c));
            break;
        case 3: completed_step(u); break;
        case 4: {
            const int s =
                known(u.v3 ? (int)fmi3GetNominalsOfContinuousStates(u.c, values, kStates)
                           : (int)fmi2GetNominalsOfContinuousStates(u.c, values, kStates));
            if (s == 0)
                for (size_t i = 0; i < kStates; ++i)
                    if (!(values[i] > 0) || !std::isfinite(values[i])) std::abort();
            break;
        }
        case 5:
            if ((u.v3 ? (int)fmi3GetEventIndicators(u.c, values, n)
                      : (int)fmi2GetEventIndicators(u.c, values, n)) == 0 &&
                n != 0)
                std::abort();
            break;
    }
}

// Derivatives read back with status OK (or Warning) are finite.
int checked_derivatives(Unit &u, double *dx) {
    const int s = get_derivatives(u, dx, kStates);
    if (s <= 1)
        for (size_t i = 0; i < kStates; ++i)
            if (!std::isfinite(dx[i])) std::abort();
    return s;
}

// SetContinuousStates of the unit's states (read back; home if they cannot be) changed as the
// input says: one state to any value, or all by small relative offsets; a wrong count sometimes.
// A Discarded or refused call changes no state.
void change_states(Unit &u, Reader &in) {
    double x[kStates], before[kStates];
    const bool readable = get_states(u, x, kStates) == 0;
    if (!readable) {
        std::memset(x, 0, sizeof x);
        x[2] = 0.5;
    }
    std::memcpy(before, x, sizeof x);
    const uint8_t how = in.byte();
    if (how & 1) {
        x[(how >> 1) % kStates] = in.value();
    } else {
        for (size_t i = 0; i < kStates; ++i) {
            int8_t offset = 0;
            in.take(&offset, 1);
            x[i] += offset / 1000.0;
        }
    }
    const size_t n = (how & 0x80) && (how & 0x40) ? kStates - 1 : kStates;
    const int s = set_states(u, x, n);
    if (s >= 2 && readable) {
        double after[kStates];
        if (get_states(u, after, kStates) == 0 && std::memcmp(after, before, sizeof after) != 0)
            std::abort();
    }
}

// Explicit Euler over `count` steps of h: GetDerivatives, SetTime, SetContinuousStates,
// CompletedIntegratorStep, as a fixed-step master does; stops at the first refusal.
void euler(Unit &u, double &t, int count, double h) {
    for (int k = 0; k < count; ++k) {
        double x[kStates], dx[kStates];
        if (get_states(u, x, kStates) != 0 || checked_derivatives(u, dx) > 1) return;
        for (size_t i = 0; i < kStates; ++i) x[i] += h * dx[i];
        if (set_time(u, t + h) != 0) return;
        t += h;
        if (set_states(u, x, kStates) != 0 || completed_step(u) != 0) return;
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *bytes, size_t size) {
    tables();
    compute_static_forces();
    Reader in{bytes, size};
    const uint8_t flags = in.byte();
    Unit &u = unit_for((flags & 32) != 0, (flags & 1) != 0);
    double t = 0;
    u.setup(0.0);
    if (flags & 2) {
        const unsigned vr = VR_fidelity;
        const int32_t fidelity = 1 + ((flags >> 2) & 1);
        u.set_int(&vr, 1, &fidelity);
        u.setup(0.0);
        u.enter_init(0.0);
        u.exit_init();
    }
    StateProbe probe;
    int ops = 0;
    while (in.left > 0 && ++ops < 512) {
        const uint8_t op = in.byte() % 16;
        if (shared_operation(op, u, in, probe, t, 4, check_outputs, [] {}) ||
            plant_operation(op, u, in))
            continue;  // 0, 1, 2, 4, 6..11, 13
        switch (op) {
            case 3: {  // SetTime: any value, or the current time plus one
                const double v = in.value();
                if (set_time(u, (flags & 16) ? t + v : v) == 0) t = (flags & 16) ? t + v : v;
                break;
            }
            case 5: change_states(u, in); break;
            case 12: event_call(u, in.byte()); break;
            case 14: {  // a few explicit Euler steps (1 .. 16) of any size
                const int count = 1 + in.byte() % 16;
                euler(u, t, count, in.value());
                break;
            }
            case 15: {
                double dx[kStates];
                checked_derivatives(u, dx);
                random_debug_logging(u, in.byte());
                break;
            }
        }
    }
    check_outputs(u);
    probe.free(u);
    return 0;
}
