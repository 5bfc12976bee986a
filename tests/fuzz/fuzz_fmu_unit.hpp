// What the FMU fuzz targets share (fuzz_fmu.cpp: the inverse model, fuzz_plant_fmu.cpp: the
// plant, fuzz_plant_me_fmu.cpp: the Model Exchange plant): loggers that touch every byte of a
// message, the model's variables by kind, and one instance behind either FMI layer whose every
// call must return a known status. Included by one target per executable: the FMI functions and
// variables.h are those of the model linked in.
#ifndef STEWART_FUZZ_FMU_UNIT_HPP
#define STEWART_FUZZ_FMU_UNIT_HPP

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
    volatile size_t n =
        std::strlen(name ? name : "") + std::strlen(category) + std::strlen(message);
    (void)n;
    if (status < fmi2OK || status > fmi2Pending) std::abort();
}

void logger3(fmi3InstanceEnvironment, fmi3Status status, fmi3String category, fmi3String message) {
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
        if (v.type == FMU_REAL &&
            (v.causality == FMU_OUTPUT_VAR || v.causality == FMU_INDEPENDENT_VAR))
            real_outputs.push_back(v.vr);
    }
}

// A call's status, which must be OK, Warning, Discard or Error (never Fatal, Pending or garbage).
int known(int status) {
    if (status < 0 || status > 3) std::abort();
    return status;
}

// One instance behind either FMI layer (statuses have the same numbers in both).
struct Unit {
    bool v3;
    void *c;
    fmi2CallbackFunctions cb2;

    Unit(bool fmi3, bool logging)
        : v3(fmi3), c(nullptr), cb2{logger, alloc, std::free, nullptr, nullptr} {
#if defined(FMU_MODEL_EXCHANGE) && FMU_MODEL_EXCHANGE  // a Model Exchange model (plant_me)
        if (v3)
            c = fmi3InstantiateModelExchange("fuzz", FMU_GUID, "", fmi3False, logging, nullptr,
                                             logger3);
        else c = fmi2Instantiate("fuzz", fmi2ModelExchange, FMU_GUID, "", &cb2, fmi2False, logging);
#else
        if (v3)
            c = fmi3InstantiateCoSimulation("fuzz", FMU_GUID, "", fmi3False, logging, fmi3False,
                                            fmi3False, nullptr, 0, nullptr, logger3, nullptr);
        else c = fmi2Instantiate("fuzz", fmi2CoSimulation, FMU_GUID, "", &cb2, fmi2False, logging);
#endif
        if (!c) std::abort();
    }
    ~Unit() {
        if (v3) fmi3FreeInstance(c);
        else fmi2FreeInstance(c);
    }
    int set_real(const unsigned *vr, size_t n, const double *v) {
        return known(v3 ? (int)fmi3SetFloat64(c, vr, n, v, n) : (int)fmi2SetReal(c, vr, n, v));
    }
    int get_real(const unsigned *vr, size_t n, double *v) {
        return known(v3 ? (int)fmi3GetFloat64(c, vr, n, v, n) : (int)fmi2GetReal(c, vr, n, v));
    }
    int set_int(const unsigned *vr, size_t n, const int32_t *v) {
        return known(v3 ? (int)fmi3SetInt32(c, vr, n, v, n) : (int)fmi2SetInteger(c, vr, n, v));
    }
    int get_int(const unsigned *vr, size_t n, int32_t *v) {
        return known(v3 ? (int)fmi3GetInt32(c, vr, n, v, n) : (int)fmi2GetInteger(c, vr, n, v));
    }
    // Returns the status and the last successful time the unit reports.
    int do_step(double t, double h, double *last) {
        if (v3) {
            fmi3Boolean event = fmi3True, terminate = fmi3True, early = fmi3True;
            const int s = known(fmi3DoStep(c, t, h, fmi3True, &event, &terminate, &early, last));
            if (event || terminate || early) std::abort();
            return s;
        }
        const int s = known(fmi2DoStep(c, t, h, fmi2True));
        if (fmi2GetRealStatus(c, fmi2LastSuccessfulTime, last) != fmi2OK) *last = 0;
        return s;
    }
    int setup(double t) {  // FMI 2 sets the start time here, FMI 3 at EnterInitializationMode
        return v3 ? 0 : (int)fmi2SetupExperiment(c, fmi2False, 0, t, fmi2False, 0);
    }
    int enter_init(double t) {
        return known(v3 ? (int)fmi3EnterInitializationMode(c, fmi3False, 0, t, fmi3False, 0)
                        : (int)fmi2EnterInitializationMode(c));
    }
    int exit_init() {
        return known(v3 ? (int)fmi3ExitInitializationMode(c) : (int)fmi2ExitInitializationMode(c));
    }
    int reset() { return known(v3 ? (int)fmi3Reset(c) : (int)fmi2Reset(c)); }
    int terminate() { return known(v3 ? (int)fmi3Terminate(c) : (int)fmi2Terminate(c)); }
    int get_state(void **s) {
        return known(v3 ? (int)fmi3GetFMUState(c, s) : (int)fmi2GetFMUstate(c, s));
    }
    int set_state(void *s) {
        return known(v3 ? (int)fmi3SetFMUState(c, s) : (int)fmi2SetFMUstate(c, s));
    }
    int free_state(void **s) {
        return known(v3 ? (int)fmi3FreeFMUState(c, s) : (int)fmi2FreeFMUstate(c, s));
    }
    int state_size(void *s, size_t *n) {
        return known(v3 ? (int)fmi3SerializedFMUStateSize(c, s, n)
                        : (int)fmi2SerializedFMUstateSize(c, s, n));
    }
    int serialize(void *s, std::vector<uint8_t> &buf) {
        return known(v3 ? (int)fmi3SerializeFMUState(c, s, buf.data(), buf.size())
                        : (int)fmi2SerializeFMUstate(c, s, reinterpret_cast<fmi2Byte *>(buf.data()),
                                                     buf.size()));
    }
    int deserialize(const std::vector<uint8_t> &buf, size_t n, void **s) {
        return known(v3 ? (int)fmi3DeserializeFMUState(c, buf.data(), n, s)
                        : (int)fmi2DeSerializeFMUstate(
                              c, reinterpret_cast<const fmi2Byte *>(buf.data()), n, s));
    }
    int debug_logging(bool on, size_t n, const char *const *cats) {
        return known(v3 ? (int)fmi3SetDebugLogging(c, on, n, cats)
                        : (int)fmi2SetDebugLogging(c, on, n, cats));
    }
    int input_derivative(unsigned vr, int order, double v) {
        if (v3) return 0;  // FMI 3 co-simulation has no input derivatives
        const fmi2ValueReference r = vr;
        const fmi2Integer o = order;
        return known(fmi2SetRealInputDerivatives(c, &r, 1, &o, &v));
    }
};


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

// SetReal of any Real variable (a selector byte) to any value.
void random_set_real(Unit &u, Reader &in) {
    const unsigned vr = reals[in.byte() % reals.size()];
    const double v = in.value();
    u.set_real(&vr, 1, &v);
}

// SetInteger of any Integer variable: a small value 0 .. small - 1, or a raw int32.
void random_set_integer(Unit &u, Reader &in, int small) {
    const unsigned vr = integers[in.byte() % integers.size()];
    int32_t v = 0;
    const uint8_t sel = in.byte();
    if (sel < 200) v = sel % small;
    else in.take(&v, sizeof v);
    u.set_int(&vr, 1, &v);
}

// Every Real output read back with OK is finite, and `status` read back with OK is one the model
// reports (bit s of `statuses` set for status s); aborts otherwise. Keeps the Reals if asked.
void check_real_outputs(Unit &u, unsigned statuses, std::vector<double> *keep) {
    std::vector<double> out(real_outputs.size());
    if (u.get_real(real_outputs.data(), out.size(), out.data()) == 0) {
        for (double d : out)
            if (!std::isfinite(d)) std::abort();
        if (keep) *keep = out;
    }
    const unsigned vr_status = VR_status;
    int32_t status = 0;
    if (u.get_int(&vr_status, 1, &status) == 0 &&
        (status < 0 || status > 31 || !((statuses >> status) & 1u)))
        std::abort();
}

// A target's check of the outputs: aborts on a broken invariant; keeps the Reals if asked.
using OutputCheck = void (*)(Unit &, std::vector<double> *);

// An FMU state taken during an input and the outputs it held: rolled back, it must give them
// back bit for bit.
struct StateProbe {
    void *state = nullptr;
    std::vector<double> outputs;

    // Takes the state (or updates the one taken) and remembers the outputs.
    void take(Unit &u, OutputCheck check) {
        outputs.clear();
        if (u.get_state(&state) == 0) check(u, &outputs);
    }
    // Rolls back to it: the same outputs bit for bit.
    void roll_back(Unit &u, OutputCheck check) {
        if (!state || u.set_state(state) != 0 || outputs.empty()) return;
        std::vector<double> now;
        check(u, &now);
        if (!now.empty() &&
            std::memcmp(now.data(), outputs.data(), now.size() * sizeof(double)) != 0)
            std::abort();
    }
    void free(Unit &u) {
        if (state) u.free_state(&state);
    }
};

// A serialise / deserialise round trip of `state`, corrupted as the input says (a byte, a whole
// double or int32 field anywhere, one byte short); a state that deserialises is set and checked.
void corrupted_round_trip(Unit &u, void *state, Reader &in, OutputCheck check) {
    size_t n = 0;
    if (u.state_size(state, &n) != 0 || n < 8) return;
    std::vector<uint8_t> buf(n);
    if (u.serialize(state, buf) != 0) return;
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
        check(u, nullptr);
        u.free_state(&other);
    }
}

// Operations 6 to 8 of every FMU target's input: take an FMU state (and the outputs it holds),
// roll back to it (the same outputs bit for bit), or a corrupted serialise / deserialise round
// trip of it.
void state_operation(StateProbe &probe, int op, Unit &u, Reader &in, OutputCheck check) {
    if (op == 6) probe.take(u, check);
    else if (op == 7) probe.roll_back(u, check);
    else if (probe.state) corrupted_round_trip(u, probe.state, in, check);
}

// The operations every FMU target's input shares: 0 SetReal of any Real variable, 2 SetInteger
// of any Integer one (small values below `small`), 4 the outputs checked, 6 to 8 FMU states
// (state_operation), 9 Reset (the master's time t back to 0), 10 Terminate, 11 initialisation
// at a random start time t. prepare() gives the unit what the target sets before every
// initialisation. False for any other op (the target's own).
template <class Prepare>
bool shared_operation(int op, Unit &u, Reader &in, StateProbe &probe, double &t, int small,
                      OutputCheck check, Prepare prepare) {
    switch (op) {
        case 0: random_set_real(u, in); return true;
        case 2: random_set_integer(u, in, small); return true;
        case 4: check(u, nullptr); return true;
        case 6:
        case 7:
        case 8: state_operation(probe, op, u, in, check); return true;
        case 9:
            u.reset();
            prepare();
            u.setup(0.0);
            t = 0;
            return true;
        case 10: u.terminate(); return true;
        case 11:
            t = in.value();
            prepare();
            u.setup(t);
            u.enter_init(t);
            u.exit_init();
            check(u, nullptr);
            return true;
    }
    return false;
}

// SetDebugLogging with the categories a selector byte picks (an unknown one among them).
void random_debug_logging(Unit &u, uint8_t b) {
    const char *cats[] = {"logEvents", "logStatusWarning", "logStatusDiscard", "logStatusError",
                          "noSuchCategory"};
    u.debug_logging(b & 1, (b >> 1) % 3, &cats[(b >> 3) % 3]);
}

}  // namespace

#endif
