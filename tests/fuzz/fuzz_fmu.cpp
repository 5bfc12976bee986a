// libFuzzer target over the FMU's set/step/get sequence: the FMU's code (the runtime, fmu/runtime,
// with the inverse model, fmu/models/inverse, and both FMI layers) is linked in statically and driven
// through the fmi2* or the fmi3* functions (flag bit 5) with random calls and random values (NaN, Inf, huge, tiny and ordinary numbers), random
// step sizes (zero, negative, huge, below the resolution of t) and random call order (the state
// machine must refuse what is out of sequence).
//
// Invariants: nothing crashes or trips a sanitizer; every Real output (and time) read back with
// status OK is finite; status is 0..3; lastSuccessfulTime is finite; a rolled-back FMU state gives
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

#include "fmi2Functions.h"
#include "fmi3Functions.h"
#include "fuzz_reader.hpp"
#include "variables.h"

namespace {

void logger(fmi2ComponentEnvironment, fmi2String name, fmi2Status status, fmi2String category,
            fmi2String message, ...) {
    // Touch every byte: an unterminated or freed string trips AddressSanitizer here.
    volatile size_t n = std::strlen(name ? name : "") + std::strlen(category) + std::strlen(message);
    (void)n;
    if (status < fmi2OK || status > fmi2Pending) std::abort();
}

void logger3(fmi3InstanceEnvironment, fmi3Status status, fmi3String category,
             fmi3String message) {
    volatile size_t n = std::strlen(category) + std::strlen(message);
    (void)n;
    if (status < fmi3OK || status > fmi3Fatal) std::abort();
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

// One instance behind either FMI layer (statuses have the same numbers in both).
struct Unit {
    bool v3;
    void *c;
    fmi2CallbackFunctions cb2;

    Unit(bool fmi3, bool logging) : v3(fmi3), c(nullptr), cb2{logger, alloc, std::free, nullptr, nullptr} {
        if (v3)
            c = fmi3InstantiateCoSimulation("fuzz", FMU_GUID, "", fmi3False, logging, fmi3False,
                                            fmi3False, nullptr, 0, nullptr, logger3, nullptr);
        else
            c = fmi2Instantiate("fuzz", fmi2CoSimulation, FMU_GUID, "", &cb2, fmi2False, logging);
        if (!c) std::abort();
    }
    ~Unit() {
        if (v3) fmi3FreeInstance(c);
        else fmi2FreeInstance(c);
    }
    int set_real(const unsigned *vr, size_t n, const double *v) {
        return v3 ? (int)fmi3SetFloat64(c, vr, n, v, n) : (int)fmi2SetReal(c, vr, n, v);
    }
    int get_real(const unsigned *vr, size_t n, double *v) {
        return v3 ? (int)fmi3GetFloat64(c, vr, n, v, n) : (int)fmi2GetReal(c, vr, n, v);
    }
    int set_int(const unsigned *vr, size_t n, const int32_t *v) {
        return v3 ? (int)fmi3SetInt32(c, vr, n, v, n) : (int)fmi2SetInteger(c, vr, n, v);
    }
    int get_int(const unsigned *vr, size_t n, int32_t *v) {
        return v3 ? (int)fmi3GetInt32(c, vr, n, v, n) : (int)fmi2GetInteger(c, vr, n, v);
    }
    // Returns the status and the last successful time the unit reports.
    int do_step(double t, double h, double *last) {
        if (v3) {
            fmi3Boolean event = fmi3True, terminate = fmi3True, early = fmi3True;
            const int s = fmi3DoStep(c, t, h, fmi3True, &event, &terminate, &early, last);
            if (event || terminate || early) std::abort();
            return s;
        }
        const int s = fmi2DoStep(c, t, h, fmi2True);
        if (fmi2GetRealStatus(c, fmi2LastSuccessfulTime, last) != fmi2OK) *last = 0;
        return s;
    }
    int setup(double t) {  // FMI 2 sets the start time here, FMI 3 at EnterInitializationMode
        return v3 ? 0 : (int)fmi2SetupExperiment(c, fmi2False, 0, t, fmi2False, 0);
    }
    int enter_init(double t) {
        return v3 ? (int)fmi3EnterInitializationMode(c, fmi3False, 0, t, fmi3False, 0)
                  : (int)fmi2EnterInitializationMode(c);
    }
    int exit_init() { return v3 ? (int)fmi3ExitInitializationMode(c) : (int)fmi2ExitInitializationMode(c); }
    int reset() { return v3 ? (int)fmi3Reset(c) : (int)fmi2Reset(c); }
    int terminate() { return v3 ? (int)fmi3Terminate(c) : (int)fmi2Terminate(c); }
    int get_state(void **s) { return v3 ? (int)fmi3GetFMUState(c, s) : (int)fmi2GetFMUstate(c, s); }
    int set_state(void *s) { return v3 ? (int)fmi3SetFMUState(c, s) : (int)fmi2SetFMUstate(c, s); }
    int free_state(void **s) { return v3 ? (int)fmi3FreeFMUState(c, s) : (int)fmi2FreeFMUstate(c, s); }
    int state_size(void *s, size_t *n) {
        return v3 ? (int)fmi3SerializedFMUStateSize(c, s, n) : (int)fmi2SerializedFMUstateSize(c, s, n);
    }
    int serialize(void *s, std::vector<uint8_t> &buf) {
        return v3 ? (int)fmi3SerializeFMUState(c, s, buf.data(), buf.size())
                  : (int)fmi2SerializeFMUstate(c, s, reinterpret_cast<fmi2Byte *>(buf.data()), buf.size());
    }
    int deserialize(const std::vector<uint8_t> &buf, size_t n, void **s) {
        return v3 ? (int)fmi3DeserializeFMUState(c, buf.data(), n, s)
                  : (int)fmi2DeSerializeFMUstate(c, reinterpret_cast<const fmi2Byte *>(buf.data()), n, s);
    }
    int debug_logging(bool on, size_t n, const char *const *cats) {
        return v3 ? (int)fmi3SetDebugLogging(c, on, n, cats) : (int)fmi2SetDebugLogging(c, on, n, cats);
    }
    int input_derivative(unsigned vr, int order, double v) {
        if (v3) return 0;  // FMI 3 co-simulation has no input derivatives (the *_dot inputs serve)
        const fmi2ValueReference r = vr;
        const fmi2Integer o = order;
        return fmi2SetRealInputDerivatives(c, &r, 1, &o, &v);
    }
};

void check_outputs(Unit &u, std::vector<double> *keep = nullptr) {
    std::vector<double> out(real_outputs.size());
    if (u.get_real(real_outputs.data(), out.size(), out.data()) == 0) {
        for (double d : out)
            if (!std::isfinite(d)) std::abort();
        if (keep) *keep = out;
    }
    const unsigned vr_status = VR_status;
    int32_t status = 0;
    if (u.get_int(&vr_status, 1, &status) == 0 && (status < 0 || status > 3)) std::abort();
}

// The instance for this FMI version and logging flag, as after instantiation: kept from an
// earlier input and Reset, or new.
Unit &unit_for(bool fmi3, bool logging) {
    static Unit *units[4] = {};
    Unit *&u = units[(fmi3 ? 2 : 0) + (logging ? 1 : 0)];
    if (u && (u->reset() != 0 || u->debug_logging(logging, 0, nullptr) != 0)) {
        delete u;
        u = nullptr;
    }
    if (!u) u = new Unit(fmi3, logging);
    return *u;
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
    void *state = nullptr;
    std::vector<double> at_state;
    int ops = 0;
    while (in.left > 0 && ++ops < 512) {
        const uint8_t op = in.byte() % 14;
        switch (op) {
            case 0: {  // SetReal of any Real variable (outputs and time must be refused)
                const unsigned vr = reals[in.byte() % reals.size()];
                const double v = in.value();
                u.set_real(&vr, 1, &v);
                break;
            }
            case 1: {  // SetReal of a pose input (most useful for coverage)
                const unsigned vr = in.byte() % 18;
                const double v = in.value();
                u.set_real(&vr, 1, &v);
                break;
            }
            case 2: {  // SetInteger
                const unsigned vr = integers[in.byte() % integers.size()];
                int32_t v = 0;
                const uint8_t sel = in.byte();
                if (sel < 200) v = sel % 4;
                else in.take(&v, sizeof v);
                u.set_int(&vr, 1, &v);
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
            case 4:
                check_outputs(u);
                break;
            case 5: {  // SetRealInputDerivatives (FMI 2), any order
                const unsigned vr = in.byte() % 20;
                const int order = in.byte() % 4;
                u.input_derivative(vr, order, in.value());
                break;
            }
            case 6:  // FMU state: take one and remember the outputs it holds
                at_state.clear();
                if (u.get_state(&state) == 0) check_outputs(u, &at_state);
                break;
            case 7:  // ... and roll back to it: the same outputs bit for bit
                if (state && u.set_state(state) == 0 && !at_state.empty()) {
                    std::vector<double> now;
                    check_outputs(u, &now);
                    if (!now.empty() && std::memcmp(now.data(), at_state.data(),
                                                    now.size() * sizeof(double)) != 0)
                        std::abort();
                }
                break;
            case 8: {  // serialise and deserialise (possibly corrupted)
                if (!state) break;
                size_t n = 0;
                if (u.state_size(state, &n) != 0 || n == 0) break;
                std::vector<uint8_t> buf(n);
                if (u.serialize(state, buf) != 0) break;
                const uint8_t corrupt = in.byte();
                // anywhere in the state: two bytes of offset (states are a few kB)
                auto offset = [&in](size_t limit) {
                    const size_t lo = in.byte(), hi = in.byte();
                    return (lo | hi << 8) % limit;
                };
                if (corrupt & 1) buf[offset(n)] ^= in.byte();
                if (corrupt & 4) {  // a whole double field: any value (NaN, Inf, huge)
                    const double value = in.value();
                    std::memcpy(&buf[offset(n - 7)], &value, sizeof value);
                }
                if (corrupt & 8) {  // a whole int32 field (mode, status, flags, options)
                    int32_t value = static_cast<int8_t>(in.byte());  // small, negative, or raw
                    if (value == 127) in.take(&value, sizeof value);
                    std::memcpy(&buf[offset(n - 3)], &value, sizeof value);
                }
                const size_t m = (corrupt & 2) ? n - 1 : n;
                void *other = nullptr;
                if (u.deserialize(buf, m, &other) == 0) {
                    u.set_state(other);
                    check_outputs(u);
                    u.free_state(&other);
                }
                break;
            }
            case 9:
                u.reset();
                u.setup(0.0);
                t = 0;
                break;
            case 10:
                u.terminate();
                break;
            case 11:  // initialisation, at a random start time
                t = in.value();
                u.setup(t);
                u.enter_init(t);
                u.exit_init();
                check_outputs(u);
                break;
            case 12: {
                const char *cats[] = {"logEvents", "logStatusWarning", "logStatusDiscard",
                                      "logStatusError", "noSuchCategory"};
                const uint8_t b = in.byte();
                u.debug_logging(b & 1, (b >> 1) % 3, &cats[(b >> 3) % 3]);
                break;
            }
            case 13: {  // read every Real variable (inputs and parameters may hold what was set)
                std::vector<double> all(reals.size());
                u.get_real(reals.data(), all.size(), all.data());
                check_outputs(u);
                break;
            }
        }
    }
    check_outputs(u);
    if (state) u.free_state(&state);
    return 0;
}
