// libFuzzer target over the plant FMU's set/step/get sequence (fmu/models/plant on fmu/runtime,
// both FMI layers, linked in statically), driven through the fmi2* or the fmi3* functions (flag
// bit 5) with random calls and values: forces (NaN, Inf, huge, near the static ones), FMI 2 force
// derivatives of any order, parameters and integrator options, step sizes and start times, FMU
// states rolled back and serialised (corrupted), calls out of sequence.
//
// Invariants: nothing crashes or trips a sanitizer; every call returns OK, Warning, Discard or
// Error (fuzz_fmu_unit.hpp); every Real output read back with status OK is finite; status is
// 0, 1 or 3; an accepted step ends at t + h (lastSuccessfulTime), a discarded one sets status 3
// and leaves the unit at the step's start t, which is its time to the rounding of a clock; a
// rolled-back FMU state gives back the same outputs bit for bit; every log message is a
// NUL-terminated string.
//
// Bounded work per input: max_internal_steps is set to 1..32 (byte 1) before every
// initialisation, and a DoStep is only called while the integrator steps it may take
// (max_internal_steps, read back: a SetInteger or a deserialised state may have changed it) fit in
// a budget of kStepBudget internal steps per input.
//
// Built with clang -fsanitize=fuzzer by scripts/fuzz.sh; tests/CMakeLists.txt also builds it with
// the replay main (fuzz_replay.cpp) that runs tests/fuzz/corpus/plant_fmu under ctest
// (fuzz_plant_fmu_corpus). Input layout (tests/fuzz/fuzz_seeds.py --plant writes seeds): byte 0
// flags (bit 0: logging on; bit 1: initialise at once with fidelity 1 + bit 2 and method =
// bits 3-4; bit 5: FMI 3 instead of FMI 2), byte 1 max_internal_steps (1 + byte % 32), then
// operations: 1 opcode byte and its arguments.
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "fuzz_fmu_unit.hpp"
#include "fuzz_plant_unit.hpp"

namespace {

constexpr int kStepBudget = 256;  // integrator steps per input (a few ms under the sanitizers)

// The unit's time, or NaN where it cannot be read.
double unit_time(Unit &u) {
    const unsigned vr = VR_time;
    double t = NAN;
    if (u.get_real(&vr, 1, &t) != 0) return NAN;
    return t;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *bytes, size_t size) {
    tables();
    compute_static_forces();
    Reader in{bytes, size};
    const uint8_t flags = in.byte();
    const int32_t step_cap = 1 + in.byte() % 32;
    Unit &u = unit_for((flags & 32) != 0, (flags & 1) != 0);
    const unsigned cap_vr = VR_max_internal_steps;
    auto set_cap = [&] { u.set_int(&cap_vr, 1, &step_cap); };
    double t = 0;
    set_cap();
    u.setup(0.0);
    if (flags & 2) {
        const unsigned vrs[2] = {VR_fidelity, VR_method};
        const int32_t values[2] = {1 + ((flags >> 2) & 1), (flags >> 3) & 3};
        u.set_int(vrs, 2, values);
        set_cap();
        u.setup(0.0);
        u.enter_init(0.0);
        u.exit_init();
    }
    int budget = kStepBudget;
    StateProbe probe;
    int ops = 0;
    while (in.left > 0 && ++ops < 512) {
        const uint8_t op = in.byte() % 14;
        if (shared_operation(op, u, in, probe, t, 5, check_outputs, set_cap) ||
            plant_operation(op, u, in))
            continue;  // 0, 1, 2, 4, 6..11, 13
        switch (op) {
            case 3: {  // DoStep from the current time (or from a raw t), any step size
                const uint8_t how = in.byte();
                const double h = in.value();
                const double t0 = (how & 1) ? in.value() : t;
                int32_t cap = 0;
                if (u.get_int(&cap_vr, 1, &cap) != 0 || cap < 0 || cap > budget) break;
                budget -= cap;
                const double before = unit_time(u);
                double last = 0;
                const int s = u.do_step(t0, h, &last);
                if (!std::isfinite(last)) std::abort();
                if (s == 0 || s == 1) {
                    if (last != t0 + h) std::abort();  // an accepted step ends at t + h
                    t = t0 + h;
                } else if (s == 2) {  // refused: status 3, the unit at the master's t0
                    const unsigned vr_status = VR_status;
                    int32_t status = 0;
                    // The unit follows the master's clock (fmu/runtime/instance.c): t0 may be a
                    // rounding off its time, never more (a gap is an Error, not a Discard).
                    if (last != t0) std::abort();
                    const double rounding =
                        32 * DBL_EPSILON * std::fmax(std::fabs(t0), std::fabs(before));
                    if (std::isfinite(before) && std::fabs(t0 - before) > rounding) std::abort();
                    if (u.get_int(&vr_status, 1, &status) == 0 && status != 3) std::abort();
                }
                break;
            }
            case 5: {  // SetRealInputDerivatives (FMI 2), any variable and order
                const unsigned vr = in.byte() % 8;
                const int order = in.byte() % 3;
                u.input_derivative(vr, order, 1e3 * in.value());
                break;
            }
            case 12: random_debug_logging(u, in.byte()); break;
        }
    }
    check_outputs(u);
    probe.free(u);
    return 0;
}
