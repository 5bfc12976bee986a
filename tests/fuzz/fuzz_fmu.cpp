// libFuzzer target over the FMU's set/step/get sequence: the FMU's code (the runtime, fmu/runtime,
// with the inverse model, fmu/models/inverse, and both FMI layers) is linked in statically and driven
// through the fmi2* or the fmi3* functions (flag bit 5) with random calls and random values (NaN, Inf, huge, tiny and ordinary numbers), random
// step sizes (zero, negative, huge, below the resolution of t) and random call order (the state
// machine must refuse what is out of sequence).
//
// Invariants: nothing crashes or trips a sanitizer; every Real output (and time) read back with
// status OK is finite; status is 0..3; every call returns OK, Warning, Discard or Error
// (fuzz_fmu_unit.hpp); lastSuccessfulTime is finite; a rolled-back FMU state gives
// back the same outputs bit for bit; every log message is a NUL-terminated string.
//
// Built with clang -fsanitize=fuzzer by scripts/fuzz.sh; tests/CMakeLists.txt also builds it with
// a replay main (fuzz_replay.cpp) that runs the committed corpus tests/fuzz/corpus/fmu under ctest.
// Input layout (tests/fuzz/fuzz_seeds.py writes seeds): byte 0 flags (bit 0: logging on, bit 1:
// enter and leave initialisation at once with fidelity = bits 2-3 and derivatives = bit 4, bit 5:
// FMI 3 instead of FMI 2), then operations: 1 opcode byte and its arguments.
//
// Instances live across inputs, one per FMI version and logging flag: each input starts with a
// Reset (and the logging categories set back as instantiation set them), which keeps the
// instance's model when the parameters come back the same, as they do in most inputs. Building
// the 14-body model, not the input, is what costs; an instance that refuses the Reset is freed
// and instantiated afresh.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "fuzz_fmu_unit.hpp"

namespace {

// The inverse unit's status output is 0 to 3.
void check_outputs(Unit &u, std::vector<double> *keep = nullptr) {
    check_real_outputs(u, 0xFu, keep);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *bytes, size_t size) {
    tables();
    Reader in{bytes, size};
    const uint8_t flags = in.byte();
    Unit &u = unit_for((flags & 32) != 0, (flags & 1) != 0);
    double t = 0;
    u.setup(0.0);
    if (flags & 2) {  // initialise at once with fidelity (flags >> 2) & 3 (3 is invalid)
        const unsigned vrs[2] = {VR_fidelity, VR_derivatives};
        const int32_t values[2] = {(flags >> 2) & 3, (flags >> 4) & 1};
        u.set_int(vrs, 2, values);
        u.enter_init(0.0);
        u.exit_init();
    }
    StateProbe probe;
    int ops = 0;
    while (in.left > 0 && ++ops < 512) {
        const uint8_t op = in.byte() % 14;
        if (shared_operation(op, u, in, probe, t, 4, check_outputs, [] {}))
            continue;  // 0, 2, 4, 6..11
        switch (op) {
            case 1: {  // SetReal of a pose input (most useful for coverage)
                const unsigned vr = in.byte() % 18;
                const double v = in.value();
                u.set_real(&vr, 1, &v);
                break;
            }
            case 3: {  // DoStep from the current time (or from a raw t), any step size
                const uint8_t how = in.byte();
                const double h = in.value();
                const double t0 = (how & 1) ? in.value() : t;
                double last = 0;
                const int s = u.do_step(t0, h, &last);
                if (s == 0 || s == 1) t = t0 + h;
                if (!std::isfinite(last)) std::abort();
                break;
            }
            case 5: {  // SetRealInputDerivatives (FMI 2), any order
                const unsigned vr = in.byte() % 20;
                const int order = in.byte() % 4;
                u.input_derivative(vr, order, in.value());
                break;
            }
            case 12: random_debug_logging(u, in.byte()); break;
            case 13: {  // read every Real variable (inputs and parameters may hold what was set)
                std::vector<double> all(reals.size());
                u.get_real(reals.data(), all.size(), all.data());
                check_outputs(u);
                break;
            }
        }
    }
    check_outputs(u);
    probe.free(u);
    return 0;
}
