// The latency workloads (latency_steps.h): the library's calls on the thesis platform along the
// combined cue at 1 kHz, and each FMU's step through its FMI 2 binary.
#include "latency_steps.h"

#include <dlfcn.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <new>
#include <string>

#include "bench/combined_cue.hpp"
#include "fmi2Functions.h"
#include "stewart/stewart.h"
#include "stewart/stewart_forward.h"
#include "stewart/stewart_plant.h"

namespace {

constexpr double kStep = 1e-3;  // [s]: a 1 kHz loop
constexpr long kRewind = 200;   // calls between rewinds of an open-loop plant to rest at home

// A leg force wobble around the static forces (N): smooth, bounded, different per leg.
double wobble(long n, int k) { return 10.0 * std::sin((4.0 + k) * n * kStep + k); }

}  // namespace

struct latency_step {
    long first = 0;  // the number of the caller's call 0: the calls after the warm-up's
    virtual ~latency_step() = default;
    virtual void prepare(long n) { (void)n; }
    virtual int run(long n) = 0;
    // The integrator's counters of the last call (steps, evaluations, rejections), if any.
    virtual bool work(long counts[3]) const {
        (void)counts;
        return false;
    }
};

namespace {

// The empty call: the loop, the clock and one indirect call (the machine's own noise).
struct Empty : latency_step {
    int run(long n) override { return static_cast<int>(n & 0); }
};

// A fixed amount of arithmetic (about 5 us here): the machine's noise at the calls' length, where
// preemption and interrupts show that a 30 ns empty call rarely meets.
struct FixedWork : latency_step {
    volatile double sink = 0;
    int run(long n) override {
        double x = 1.0 + 1e-9 * static_cast<double>(n & 1);
        for (int i = 0; i < 2000; ++i) x = x * 0.999999 + 1e-7;  // a dependent chain
        sink = x;
        return 0;
    }
};

// The thesis platform's model, shared by the library workloads.
struct Library : latency_step {
    stewart_model *model = nullptr;
    bool build(char *msg, size_t size) {
        stewart_params p;
        stewart_params_default(&p);
        model = stewart_model_create(&p, msg, size);
        return model != nullptr;
    }
    ~Library() override { stewart_model_free(model); }
};

// The static leg forces at home at a fidelity (the inverse side's), or false.
bool static_forces(const stewart_model *model, int fidelity, double force[6], char *msg,
                   size_t size) {
    stewart_inverse_options o;
    stewart_inverse_options_default(&o);
    o.fidelity = fidelity;
    stewart_inverse *inv = stewart_inverse_create(model, &o, msg, size);
    if (!inv) return false;
    stewart_inverse_input in{};
    in.pose.q[2] = 0.5;
    stewart_inverse_output out;
    const bool ok = stewart_inverse_solve(inv, &in, &out) == STEWART_OK;
    if (ok) std::memcpy(force, out.force, sizeof out.force);
    else std::snprintf(msg, size, "%s", stewart_inverse_message(inv));
    stewart_inverse_free(inv);
    return ok;
}

// The thesis platform's static forces at home at the full level (for the FMU workloads).
bool home_static_forces(double force[6], char *msg, size_t size) {
    stewart_params p;
    stewart_params_default(&p);
    stewart_model *model = stewart_model_create(&p, msg, size);
    const bool ok = model && static_forces(model, STEWART_FULL, force, msg, size);
    stewart_model_free(model);
    return ok;
}

struct InverseFull : Library {
    stewart_inverse *inv = nullptr;
    stewart_inverse_input in{};
    stewart_inverse_output out{};
    bool build(char *msg, size_t size) {
        if (!Library::build(msg, size)) return false;
        stewart_inverse_options o;
        stewart_inverse_options_default(&o);
        o.fidelity = STEWART_FULL;
        inv = stewart_inverse_create(model, &o, msg, size);
        return inv != nullptr;
    }
    void prepare(long n) override { in.pose = combined_cue(n * kStep); }
    int run(long) override { return stewart_inverse_solve(inv, &in, &out); }
    ~InverseFull() override { stewart_inverse_free(inv); }
};

// Forward kinematics tracking the cue's lengths (from the kinematic inverse, untimed).
struct ForwardTracking : Library {
    stewart_inverse *lengths = nullptr;
    stewart_forward *fwd = nullptr;
    stewart_forward_input in{};
    stewart_forward_output out{};
    bool build(char *msg, size_t size) {
        if (!Library::build(msg, size)) return false;
        stewart_inverse_options io;
        stewart_inverse_options_default(&io);
        io.fidelity = STEWART_KINEMATIC;
        lengths = stewart_inverse_create(model, &io, msg, size);
        stewart_forward_options fo;
        stewart_forward_options_default(&fo);
        fwd = lengths ? stewart_forward_create(model, &fo, msg, size) : nullptr;
        return fwd != nullptr;
    }
    void prepare(long n) override {
        stewart_inverse_input pose{combined_cue(n * kStep)};
        stewart_inverse_output legs;
        stewart_inverse_solve(lengths, &pose, &legs);
        in.time = n * kStep;
        in.lengths = legs.lengths;
        in.derivatives = 2;
    }
    int run(long) override { return stewart_forward_solve(fwd, &in, &out); }
    ~ForwardTracking() override {
        stewart_forward_free(fwd);
        stewart_inverse_free(lengths);
    }
};

// The plant open loop around its static forces, rewound to rest at home every kRewind calls.
struct PlantStep : Library {
    int fidelity;
    int fixed_steps = 0;  // stewart_plant_options.fixed_steps (0: adaptive, the default)
    stewart_plant *plant = nullptr;
    double force[6] = {0};
    stewart_plant_input in{};
    stewart_plant_output out{};
    explicit PlantStep(int f, int fixed = 0) : fidelity(f), fixed_steps(fixed) {}
    bool build(char *msg, size_t size) {
        if (!Library::build(msg, size) || !static_forces(model, fidelity, force, msg, size))
            return false;
        stewart_plant_options o;
        stewart_plant_options_default(&o);
        o.fidelity = fidelity;
        o.fixed_steps = fixed_steps;
        plant = stewart_plant_create(model, &o, msg, size);
        in.h = kStep;
        return plant != nullptr;
    }
    void prepare(long n) override {
        if (n % kRewind == 0) {
            const double home[6] = {0, 0, 0.5, 0, 0, 0}, rest[6] = {0};
            stewart_plant_set_state(plant, 0.0, home, rest);
        }
        for (int k = 0; k < 6; ++k) {
            in.force_start[k] = force[k] + wobble(n, k);
            in.force_end[k] = force[k] + wobble(n + 1, k);
        }
    }
    int run(long) override { return stewart_plant_step(plant, &in, &out); }
    bool work(long counts[3]) const override {
        stewart_plant_statistics st;
        stewart_plant_statistics_get(plant, &st);
        counts[0] = st.steps;
        counts[1] = st.rhs_evaluations;
        counts[2] = st.error_test_failures;
        return true;
    }
    ~PlantStep() override { stewart_plant_free(plant); }
};

// The plant's right-hand side (what the Model Exchange unit evaluates) at states near home.
struct PlantDerivatives : PlantStep {
    stewart_plant_derivative_input din{};
    PlantDerivatives() : PlantStep(STEWART_FULL) {}
    void prepare(long n) override {
        const stewart_pose p = combined_cue(n * kStep);
        din.pose = p;
        for (int k = 0; k < 6; ++k) din.force[k] = force[k] + wobble(n, k);
    }
    int run(long) override { return stewart_plant_derivatives(plant, &din, &out); }
    bool work(long counts[3]) const override { return latency_step::work(counts); }
};

// ---------------------------------------------------------------- FMUs through FMI 2

void fmu_log(fmi2ComponentEnvironment, fmi2String, fmi2Status, fmi2String, fmi2String, ...) {}

// One FMI 2 unit, dlopen'ed from fmu_dir/<name>/fmi2/<name>.so, instantiated and initialised.
struct Fmu : latency_step {
    void *lib = nullptr;
    fmi2Component c = nullptr;
    fmi2CallbackFunctions callbacks{fmu_log, calloc, free, nullptr, nullptr};
    fmi2SetRealTYPE *set_real = nullptr;
    fmi2DoStepTYPE *do_step = nullptr;
    fmi2FreeInstanceTYPE *free_instance = nullptr;
    template <class F>
    F *symbol(const char *name) {
        return reinterpret_cast<F *>(dlsym(lib, name));
    }
    // Loads and instantiates; parameters (vr, integer value) are set before initialisation.
    bool build(const char *fmu_dir, const char *name, fmi2Type type, const unsigned *int_vr,
               const int *int_value, size_t n_int, char *msg, size_t size) {
        const std::string dir = std::string(fmu_dir) + "/" + name;
        std::ifstream xml(dir + "/modelDescription2.xml");
        const std::string text((std::istreambuf_iterator<char>(xml)),
                               std::istreambuf_iterator<char>());
        const size_t at = text.find("guid=\"");
        lib = dlopen((dir + "/fmi2/" + name + ".so").c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!lib || at == std::string::npos) {
            std::snprintf(msg, size, "%s: cannot load the binary or find the GUID (%s)", name,
                          lib ? "no guid" : dlerror());
            return false;
        }
        const std::string guid = text.substr(at + 6, text.find('"', at + 6) - at - 6);
        set_real = symbol<fmi2SetRealTYPE>("fmi2SetReal");
        do_step = symbol<fmi2DoStepTYPE>("fmi2DoStep");
        free_instance = symbol<fmi2FreeInstanceTYPE>("fmi2FreeInstance");
        c = symbol<fmi2InstantiateTYPE>("fmi2Instantiate")(name, type, guid.c_str(), nullptr,
                                                           &callbacks, fmi2False, fmi2False);
        if (!c) {
            std::snprintf(msg, size, "%s: instantiation failed", name);
            return false;
        }
        symbol<fmi2SetupExperimentTYPE>("fmi2SetupExperiment")(c, fmi2False, 0, 0, fmi2False, 0);
        symbol<fmi2EnterInitializationModeTYPE>("fmi2EnterInitializationMode")(c);
        if (n_int) symbol<fmi2SetIntegerTYPE>("fmi2SetInteger")(c, int_vr, n_int, int_value);
        if (symbol<fmi2ExitInitializationModeTYPE>("fmi2ExitInitializationMode")(c) > fmi2Warning) {
            std::snprintf(msg, size, "%s: initialisation failed", name);
            return false;
        }
        return true;
    }
    ~Fmu() override {
        if (c) free_instance(c);
        if (lib) dlclose(lib);
    }
};

// StewartPlatform at the full level, the cue's pose, rates and accelerations as inputs.
struct FmuInverse : Fmu {
    double pose[18] = {0};
    unsigned vr[18];
    bool build(const char *dir, char *msg, size_t size) {
        const unsigned int_vr[2] = {200, 201};  // fidelity, derivatives
        const int value[2] = {STEWART_FULL, 1};
        for (unsigned i = 0; i < 18; ++i) vr[i] = i;  // x .. yaw_ddot
        return Fmu::build(dir, "StewartPlatform", fmi2CoSimulation, int_vr, value, 2, msg, size);
    }
    void prepare(long n) override {
        const stewart_pose p = combined_cue(n * kStep);
        std::memcpy(pose, p.q, sizeof p.q);
        std::memcpy(pose + 6, p.q_dot, sizeof p.q_dot);
        std::memcpy(pose + 12, p.q_ddot, sizeof p.q_ddot);
        set_real(c, vr, 18, pose);
    }
    int run(long n) override { return do_step(c, n * kStep, kStep, fmi2True) > fmi2Warning; }
};

// StewartPlant (full level) open loop around static forces, rewound by its FMU state.
struct FmuPlant : Fmu {
    double force[6] = {0};
    fmi2FMUstate start = nullptr;
    bool build(const char *dir, char *msg, size_t size) {
        if (!home_static_forces(force, msg, size) ||
            !Fmu::build(dir, "StewartPlant", fmi2CoSimulation, nullptr, nullptr, 0, msg, size))
            return false;
        return symbol<fmi2GetFMUstateTYPE>("fmi2GetFMUstate")(c, &start) == fmi2OK;
    }
    void prepare(long n) override {
        if (n % kRewind == 0) symbol<fmi2SetFMUstateTYPE>("fmi2SetFMUstate")(c, start);
        double f[6];
        for (int k = 0; k < 6; ++k) f[k] = force[k] + wobble(n, k);
        const unsigned vr[6] = {0, 1, 2, 3, 4, 5};
        set_real(c, vr, 6, f);
    }
    int run(long n) override {
        return do_step(c, (n % kRewind) * kStep, kStep, fmi2True) > fmi2Warning;
    }
    ~FmuPlant() override {
        if (start) symbol<fmi2FreeFMUstateTYPE>("fmi2FreeFMUstate")(c, &start);
    }
};

// StewartController: references and measurements that move with n.
struct FmuController : Fmu {
    bool build(const char *dir, char *msg, size_t size) {
        return Fmu::build(dir, "StewartController", fmi2CoSimulation, nullptr, nullptr, 0, msg,
                          size);
    }
    void prepare(long n) override {
        double in[30];
        unsigned vr[30];
        for (unsigned i = 0; i < 30; ++i) {
            vr[i] = i;  // L_ref, L_dot_ref, F_ff, L, L_dot
            in[i] = (i / 6 == 2                 ? 200.0
                     : i / 6 == 0 || i / 6 == 3 ? 0.56
                                                : 0.0) +
                    1e-3 * std::sin(n * kStep + i);
        }
        set_real(c, vr, 30, in);
    }
    int run(long n) override { return do_step(c, n * kStep, kStep, fmi2True) > fmi2Warning; }
};

struct FmuScene : Fmu {
    bool build(const char *dir, char *msg, size_t size) {
        return Fmu::build(dir, "StewartScene", fmi2CoSimulation, nullptr, nullptr, 0, msg, size);
    }
    int run(long n) override { return do_step(c, n * kStep, kStep, fmi2True) > fmi2Warning; }
};

// StewartPlantME: the master sets the states (the cue's pose and rates) and forces, untimed, and
// asks for the derivatives.
struct FmuPlantME : Fmu {
    double force[6] = {0};
    fmi2SetContinuousStatesTYPE *set_states = nullptr;
    fmi2GetDerivativesTYPE *derivatives = nullptr;
    bool build(const char *dir, char *msg, size_t size) {
        if (!home_static_forces(force, msg, size) ||
            !Fmu::build(dir, "StewartPlantME", fmi2ModelExchange, nullptr, nullptr, 0, msg, size))
            return false;
        fmi2EventInfo info{};
        symbol<fmi2NewDiscreteStatesTYPE>("fmi2NewDiscreteStates")(c, &info);
        symbol<fmi2EnterContinuousTimeModeTYPE>("fmi2EnterContinuousTimeMode")(c);
        set_states = symbol<fmi2SetContinuousStatesTYPE>("fmi2SetContinuousStates");
        derivatives = symbol<fmi2GetDerivativesTYPE>("fmi2GetDerivatives");
        return true;
    }
    void prepare(long n) override {
        const stewart_pose p = combined_cue(n * kStep);
        double x[12], f[6];
        std::memcpy(x, p.q, sizeof p.q);
        std::memcpy(x + 6, p.q_dot, sizeof p.q_dot);
        set_states(c, x, 12);
        for (int k = 0; k < 6; ++k) f[k] = force[k] + wobble(n, k);
        const unsigned vr[6] = {0, 1, 2, 3, 4, 5};
        set_real(c, vr, 6, f);
    }
    int run(long) override {
        double dx[12];
        return derivatives(c, dx, 12) != fmi2OK;
    }
};

const char *const kNames[] = {
    "empty call (noise)",
    "fixed arithmetic (noise at ~5 us)",
    "inverse full solve",
    "forward kinematics tracking solve",
    "plant step, massless (1 ms)",
    "plant step, full (1 ms)",
    "plant derivatives, full",
    "FMU StewartPlatform doStep (full)",
    "FMU StewartPlant doStep (full)",
    "FMU StewartController doStep",
    "FMU StewartScene doStep",
    "FMU StewartPlantME GetDerivatives",
    "plant step, full (1 ms), 1 fixed ERK step",
    "plant step, full (1 ms), 2 fixed ERK steps",
};
constexpr int kCount = sizeof kNames / sizeof kNames[0];

// A built workload or nullptr (the message says why).
template <class T>
latency_step *made(T *s, bool ok) {
    if (ok) return s;
    delete s;
    return nullptr;
}

}  // namespace

extern "C" int latency_step_count(void) { return kCount; }

extern "C" const char *latency_step_name(int i) { return i >= 0 && i < kCount ? kNames[i] : "?"; }

extern "C" latency_step *latency_step_create(int i, const char *dir, char *msg, size_t size) {
    latency_step *s = nullptr;
    switch (i) {
        case 0: s = new (std::nothrow) Empty; break;
        case 1: s = new (std::nothrow) FixedWork; break;
        case 2: {
            auto *w = new InverseFull;
            s = made(w, w->build(msg, size));
            break;
        }
        case 3: {
            auto *w = new ForwardTracking;
            s = made(w, w->build(msg, size));
            break;
        }
        case 4: {
            auto *w = new PlantStep(STEWART_MASSLESS);
            s = made(w, w->build(msg, size));
            break;
        }
        case 5: {
            auto *w = new PlantStep(STEWART_FULL);
            s = made(w, w->build(msg, size));
            break;
        }
        case 6: {
            auto *w = new PlantDerivatives;
            s = made(w, w->build(msg, size));
            break;
        }
        case 7: {
            auto *w = new FmuInverse;
            s = made(w, w->build(dir, msg, size));
            break;
        }
        case 8: {
            auto *w = new FmuPlant;
            s = made(w, w->build(dir, msg, size));
            break;
        }
        case 9: {
            auto *w = new FmuController;
            s = made(w, w->build(dir, msg, size));
            break;
        }
        case 10: {
            auto *w = new FmuScene;
            s = made(w, w->build(dir, msg, size));
            break;
        }
        case 11: {
            auto *w = new FmuPlantME;
            s = made(w, w->build(dir, msg, size));
            break;
        }
        case 12: {
            auto *w = new PlantStep(STEWART_FULL, 1);
            s = made(w, w->build(msg, size));
            break;
        }
        case 13: {
            auto *w = new PlantStep(STEWART_FULL, 2);
            s = made(w, w->build(msg, size));
            break;
        }
        default: std::snprintf(msg, size, "no workload %d", i);
    }
    // warm up: the first calls touch memory and fill caches (and SUNDIALS' lazy workspaces); the
    // caller's calls continue the sequence (an FMU's time goes on)
    constexpr long kWarmUp = 100;
    for (long n = 0; s && n < kWarmUp; ++n) {
        s->prepare(n);
        if (s->run(n) != 0) {
            std::snprintf(msg, size, "%s: call %ld failed in the warm-up", kNames[i], n);
            delete s;
            s = nullptr;
        }
    }
    if (s) s->first = kWarmUp;
    return s;
}

extern "C" void latency_step_prepare(latency_step *s, long n) { s->prepare(s->first + n); }

extern "C" int latency_step_run(latency_step *s, long n) { return s->run(s->first + n); }

extern "C" int latency_step_work(const latency_step *s, long work[3]) {
    return s->work(work) ? 1 : 0;
}

extern "C" void latency_step_free(latency_step *s) { delete s; }
