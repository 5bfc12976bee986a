// libFuzzer target over the FMU's FMI 2 set/step/get sequence: the FMU's model code (fmu/model.c,
// fmu/variables.c, fmu/fmi2_functions.c) is linked in statically and driven through the fmi2*
// functions with random calls and random values (NaN, Inf, huge, tiny and ordinary numbers), random
// step sizes (zero, negative, huge, below the resolution of t) and random call order (the state
// machine must refuse what is out of sequence).
//
// Invariants: nothing crashes or trips a sanitizer; every Real output (and time) read back with
// status OK is finite; status is 0..3; lastSuccessfulTime is finite; a rolled-back FMU state gives
// back the same outputs bit for bit; every log message is a NUL-terminated string.
//
// Built with clang -fsanitize=fuzzer by scripts/fuzz.sh; tests/CMakeLists.txt also builds it with
// a replay main (fuzz_replay.cpp) that runs the committed corpus tests/fuzz/corpus/fmu under ctest.
// Input layout (scripts/fuzz_seeds.py writes seeds): byte 0 flags (bit 0: logging on, bit 1:
// enter and leave initialisation at once with fidelity = bits 2-3 and derivatives = bit 4), then
// operations: 1 opcode byte and its arguments.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "fmi2Functions.h"
#include "variables.h"

namespace {

struct Reader {
    const uint8_t *p;
    size_t left;
    bool take(void *out, size_t n) {
        if (left < n) return false;
        std::memcpy(out, p, n);
        p += n;
        left -= n;
        return true;
    }
    uint8_t byte() {
        uint8_t b = 0;
        take(&b, 1);
        return b;
    }
    // A selector byte, then a value: specials, small decimals or a raw float64.
    double value() {
        static const double kSpecial[] = {
            0.0, 0.5, -0.5, 1.0, -1.0, 0.1, 1e-9, 10.0, M_PI / 2, -M_PI / 2, 1e-15, 1e3,
            1e300, -1e300, HUGE_VAL, -HUGE_VAL, NAN, 2.2250738585072014e-308, 4.9e-324, 1e-3,
            100.0, 0.7, 0.4, 1e10, 1e-300, -0.0, 0.45, 0.55, 1e16, 1e308, 3.0, 0.75};
        const uint8_t sel = byte();
        if (sel < 128) return kSpecial[sel % (sizeof kSpecial / sizeof kSpecial[0])];
        if (sel < 192) {
            int8_t small = 0;
            take(&small, 1);
            return small / 100.0;
        }
        double d = 0;
        take(&d, sizeof d);
        return d;
    }
};

void logger(fmi2ComponentEnvironment, fmi2String name, fmi2Status status, fmi2String category,
            fmi2String message, ...) {
    // Touch every byte: an unterminated or freed string trips AddressSanitizer here.
    volatile size_t n = std::strlen(name ? name : "") + std::strlen(category) + std::strlen(message);
    (void)n;
    if (status < fmi2OK || status > fmi2Pending) std::abort();
}

void *alloc(size_t n, size_t size) { return std::calloc(n, size); }

// Every variable, by kind.
std::vector<fmi2ValueReference> reals, integers, real_outputs;

void tables() {
    if (!reals.empty()) return;
    for (size_t i = 0; i < fmu_n_variables; ++i) {
        const fmu_variable &v = fmu_variables[i];
        (v.type == FMU_REAL ? reals : integers).push_back(v.vr);
        if (v.type == FMU_REAL && (v.causality == FMU_OUTPUT_VAR || v.causality == FMU_INDEPENDENT_VAR))
            real_outputs.push_back(v.vr);
    }
}

void check_outputs(fmi2Component c, std::vector<double> *keep = nullptr) {
    std::vector<double> out(real_outputs.size());
    if (fmi2GetReal(c, real_outputs.data(), out.size(), out.data()) == fmi2OK) {
        for (double d : out)
            if (!std::isfinite(d)) std::abort();
        if (keep) *keep = out;
    }
    const fmi2ValueReference vr_status = VR_status;
    fmi2Integer status = 0;
    if (fmi2GetInteger(c, &vr_status, 1, &status) == fmi2OK && (status < 0 || status > 3))
        std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *bytes, size_t size) {
    tables();
    Reader in{bytes, size};
    const uint8_t flags = in.byte();
    fmi2CallbackFunctions cb = {logger, alloc, std::free, nullptr, nullptr};
    fmi2Component c = fmi2Instantiate("fuzz", fmi2CoSimulation, FMU_GUID, "", &cb, fmi2False,
                                      (flags & 1) ? fmi2True : fmi2False);
    if (!c) std::abort();
    double t = 0;
    fmi2SetupExperiment(c, fmi2False, 0, 0.0, fmi2False, 0);
    if (flags & 2) {  // initialise at once with fidelity (flags >> 2) & 3 (3 is invalid)
        const fmi2ValueReference vrs[2] = {VR_fidelity, VR_derivatives};
        const fmi2Integer values[2] = {(flags >> 2) & 3, (flags >> 4) & 1};
        fmi2SetInteger(c, vrs, 2, values);
        fmi2EnterInitializationMode(c);
        fmi2ExitInitializationMode(c);
    }
    fmi2FMUstate state = nullptr;
    std::vector<double> at_state;
    int ops = 0;
    while (in.left > 0 && ++ops < 512) {
        const uint8_t op = in.byte() % 14;
        switch (op) {
            case 0: {  // SetReal of any Real variable (outputs and time must be refused)
                const fmi2ValueReference vr = reals[in.byte() % reals.size()];
                const double v = in.value();
                fmi2SetReal(c, &vr, 1, &v);
                break;
            }
            case 1: {  // SetReal of a pose input (most useful for coverage)
                const fmi2ValueReference vr = in.byte() % 18;
                const double v = in.value();
                fmi2SetReal(c, &vr, 1, &v);
                break;
            }
            case 2: {  // SetInteger
                const fmi2ValueReference vr = integers[in.byte() % integers.size()];
                int32_t v = 0;
                const uint8_t sel = in.byte();
                if (sel < 200) v = sel % 4;
                else in.take(&v, sizeof v);
                fmi2SetInteger(c, &vr, 1, &v);
                break;
            }
            case 3: {  // DoStep from the current time (or from a raw t), any step size
                const uint8_t how = in.byte();
                const double h = in.value();
                const double t0 = (how & 1) ? in.value() : t;
                const fmi2Status s = fmi2DoStep(c, t0, h, fmi2True);
                if (s == fmi2OK || s == fmi2Warning) t = t0 + h;
                fmi2Real last = 0;
                if (fmi2GetRealStatus(c, fmi2LastSuccessfulTime, &last) == fmi2OK &&
                    !std::isfinite(last))
                    std::abort();
                break;
            }
            case 4:
                check_outputs(c);
                break;
            case 5: {  // SetRealInputDerivatives, any order
                const fmi2ValueReference vr = in.byte() % 20;
                const fmi2Integer order = in.byte() % 4;
                const double v = in.value();
                fmi2SetRealInputDerivatives(c, &vr, 1, &order, &v);
                break;
            }
            case 6:  // FMU state: take one and remember the outputs it holds
                at_state.clear();
                if (fmi2GetFMUstate(c, &state) == fmi2OK) check_outputs(c, &at_state);
                break;
            case 7:  // ... and roll back to it: the same outputs bit for bit
                if (state && fmi2SetFMUstate(c, state) == fmi2OK && !at_state.empty()) {
                    std::vector<double> now;
                    check_outputs(c, &now);
                    if (!now.empty() && std::memcmp(now.data(), at_state.data(),
                                                    now.size() * sizeof(double)) != 0)
                        std::abort();
                }
                break;
            case 8: {  // serialise and deserialise (possibly corrupted)
                if (!state) break;
                size_t n = 0;
                if (fmi2SerializedFMUstateSize(c, state, &n) != fmi2OK) break;
                std::vector<fmi2Byte> buf(n);
                if (fmi2SerializeFMUstate(c, state, buf.data(), n) != fmi2OK) break;
                const uint8_t corrupt = in.byte();
                if (corrupt & 1) buf[in.byte() % n] ^= static_cast<char>(in.byte());
                size_t m = (corrupt & 2) ? n - 1 : n;
                fmi2FMUstate other = nullptr;
                if (fmi2DeSerializeFMUstate(c, buf.data(), m, &other) == fmi2OK) {
                    fmi2SetFMUstate(c, other);
                    check_outputs(c);
                    fmi2FreeFMUstate(c, &other);
                }
                break;
            }
            case 9:
                fmi2Reset(c);
                fmi2SetupExperiment(c, fmi2False, 0, 0.0, fmi2False, 0);
                t = 0;
                break;
            case 10:
                fmi2Terminate(c);
                break;
            case 11:  // initialisation, at a random start time
                t = in.value();
                fmi2SetupExperiment(c, fmi2False, 0, t, fmi2False, 0);
                fmi2EnterInitializationMode(c);
                fmi2ExitInitializationMode(c);
                check_outputs(c);
                break;
            case 12: {
                const char *cats[] = {"logEvents", "logStatusWarning", "logStatusDiscard",
                                      "logStatusError", "noSuchCategory"};
                const uint8_t b = in.byte();
                fmi2SetDebugLogging(c, (b & 1) ? fmi2True : fmi2False, (b >> 1) % 3,
                                    &cats[(b >> 3) % 3]);
                break;
            }
            case 13: {  // read every Real variable (inputs and parameters may hold what was set)
                std::vector<double> all(reals.size());
                fmi2GetReal(c, reals.data(), all.size(), all.data());
                check_outputs(c);
                break;
            }
        }
    }
    check_outputs(c);
    if (state) fmi2FreeFMUstate(c, &state);
    fmi2FreeInstance(c);
    return 0;
}
