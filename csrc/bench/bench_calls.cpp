// One row of the cost-per-call table (docs/speed-accuracy.md) per run, through the public API
// only, along the combined cue
// (scenes/combined.json's formula): `bench-calls ROW CALLS` makes CALLS calls of the row's API
// function and prints the median nanoseconds per call. The calls are the only uses of that
// function in the run, so a profiler toggled on it (studies/bench/instructions.sh: callgrind
// --toggle-collect) counts exactly CALLS calls. `bench-calls ROW CALLS NAME=VALUE ...` changes
// parameters of the thesis platform first (e.g. tool_frame[3]=0.1: the cue is then the tool's).
// Rows:
//   inverse-kinematic, inverse-massless, inverse-full   stewart_inverse_solve at each fidelity
//   forward-tracking                                    stewart_forward_solve at 1 kHz, with rates
//   inverse-full-fresh, forward-fresh                   as a one-row Python call makes them: each
//       call resets the solver first (the binding's kept solvers are reset when taken), the reset
//       timed with it; forward from the cue's previous pose as its guess, without a time
//   plant-massless, plant-full                          stewart_plant_step, 1 ms, Hermite forces
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "bench/bench_support.hpp"
#include "bench/combined_cue.hpp"
#include "stewart/stewart.h"
#include "stewart/stewart_forward.h"
#include "stewart/stewart_plant.h"

namespace {

constexpr double kStep = 1e-3;  // 1 kHz

using bench::Clock;
using bench::median;
using bench::ns_since;

// An inverse solver at `fidelity` (NULL if it cannot be made).
stewart_inverse *inverse_at(const stewart_model *m, int fidelity) {
    stewart_inverse_options o;
    stewart_inverse_options_default(&o);
    o.fidelity = fidelity;
    char msg[STEWART_MESSAGE_SIZE];
    return stewart_inverse_create(m, &o, msg, sizeof msg);
}

// Inverse outputs (lengths, their rates and accelerations, forces) along the cue, at `fidelity`;
// forces and their central-difference rates for the plant's Hermite drive.
bool inverse_along_cue(const stewart_model *m, int fidelity, int calls,
                       std::vector<stewart_inverse_output> &out, std::vector<double> *force_rate) {
    stewart_inverse *d = inverse_at(m, fidelity);
    out.resize(calls + 1);
    bool ok = d != nullptr;
    for (int i = 0; i <= calls && ok; ++i) {
        const stewart_inverse_input in{combined_cue(i * kStep)};
        ok = stewart_inverse_solve(d, &in, &out[i]) == STEWART_OK;
    }
    if (force_rate && ok) {
        force_rate->assign(6 * (calls + 1), 0.0);
        for (int i = 0; i <= calls; ++i)
            for (int k = 0; k < 6; ++k) {
                const double before = out[std::max(i - 1, 0)].force[k];
                const double after = out[std::min(i + 1, calls)].force[k];
                (*force_rate)[6 * i + k] = (after - before) / (2 * kStep);
            }
    }
    stewart_inverse_free(d);
    return ok;
}

// fresh: each call on a reset solver (inverse-full-fresh).
double run_inverse(const stewart_model *m, int fidelity, int calls, bool fresh = false) {
    stewart_inverse *d = inverse_at(m, fidelity);
    if (!d) return -1;
    std::vector<stewart_inverse_input> poses(calls);
    for (int i = 0; i < calls; ++i) poses[i].pose = combined_cue(i * kStep);
    std::vector<double> ns(calls);
    stewart_inverse_output out;
    for (int i = 0; i < calls; ++i) {
        const Clock::time_point start = Clock::now();
        if (fresh) stewart_inverse_reset(d);
        const stewart_status s = stewart_inverse_solve(d, &poses[i], &out);
        ns[i] = ns_since(start);
        if (s != STEWART_OK) return -1;
    }
    stewart_inverse_free(d);
    return median(ns);
}

// fresh: each call on a reset solver from the previous cue pose (forward-fresh).
double run_forward(const stewart_model *m, int calls, bool fresh = false) {
    std::vector<stewart_inverse_output> legs;
    if (!inverse_along_cue(m, STEWART_KINEMATIC, calls, legs, nullptr)) return -1;
    stewart_forward_options o;
    stewart_forward_options_default(&o);
    char msg[STEWART_MESSAGE_SIZE];
    stewart_forward *d = stewart_forward_create(m, &o, msg, sizeof msg);
    if (!d) return -1;
    std::vector<stewart_forward_input> in(calls);
    for (int i = 0; i < calls; ++i) {
        in[i].time = fresh ? 0.0 : i * kStep;
        in[i].lengths = legs[fresh ? i + 1 : i].lengths;
        in[i].derivatives = 2;
        in[i].use_guess = fresh;
        if (fresh) std::copy_n(combined_cue(i * kStep).q, 6, in[i].guess);
    }
    std::vector<double> ns(calls);
    stewart_forward_output r;
    for (int i = 0; i < calls; ++i) {
        const Clock::time_point start = Clock::now();
        if (fresh) stewart_forward_reset(d);
        const stewart_status s = stewart_forward_solve(d, &in[i], &r);
        ns[i] = ns_since(start);
        if (s != STEWART_OK) return -1;
    }
    stewart_forward_free(d);
    return median(ns);
}

double run_plant(const stewart_model *m, int fidelity, int calls) {
    std::vector<stewart_inverse_output> drive;
    std::vector<double> rate;
    if (!inverse_along_cue(m, fidelity, calls, drive, &rate)) return -1;
    stewart_plant_options o;
    stewart_plant_options_default(&o);
    o.fidelity = fidelity;
    char msg[STEWART_MESSAGE_SIZE];
    stewart_plant *plant = stewart_plant_create(m, &o, msg, sizeof msg);
    if (!plant) return -1;
    const stewart_pose start = combined_cue(0);
    stewart_plant_set_state(plant, 0, start.q, start.q_dot);
    std::vector<stewart_plant_input> in(calls);
    for (int i = 0; i < calls; ++i) {
        in[i].h = kStep;
        in[i].derivatives = 1;
        for (int k = 0; k < 6; ++k) {
            in[i].force_start[k] = drive[i].force[k], in[i].force_end[k] = drive[i + 1].force[k];
            in[i].force_rate_start[k] = rate[6 * i + k];
            in[i].force_rate_end[k] = rate[6 * i + 6 + k];
        }
    }
    std::vector<double> ns(calls);
    stewart_plant_output out;
    for (int i = 0; i < calls; ++i) {
        const Clock::time_point t0 = Clock::now();
        const stewart_status s = stewart_plant_step(plant, &in[i], &out);
        ns[i] = ns_since(t0);
        if (s != STEWART_OK) return -1;
    }
    stewart_plant_free(plant);
    return median(ns);
}

}  // namespace

int main(int argc, char **argv) {
    if (argc < 3) {
        std::fprintf(stderr,
                     "usage: bench-calls ROW CALLS [NAME=VALUE ...] (rows: see the source)\n");
        return 2;
    }
    const char *row = argv[1];
    const int calls = std::atoi(argv[2]);
    if (calls < 1) {
        std::fprintf(stderr, "bench-calls: CALLS = %s is not a positive count\n", argv[2]);
        return 2;
    }
    stewart_params params;
    stewart_params_default(&params);
    char msg[STEWART_MESSAGE_SIZE];
    for (int a = 3; a < argc; ++a) {
        char name[64];
        const char *equals = std::strchr(argv[a], '=');
        const size_t length = equals ? static_cast<size_t>(equals - argv[a]) : 0;
        if (!equals || length >= sizeof name) {
            std::fprintf(stderr, "bench-calls: %s is not NAME=VALUE\n", argv[a]);
            return 2;
        }
        std::memcpy(name, argv[a], length);
        name[length] = '\0';
        if (stewart_params_set(&params, name, std::atof(equals + 1), msg, sizeof msg) !=
            STEWART_OK) {
            std::fprintf(stderr, "bench-calls: %s\n", msg);
            return 2;
        }
    }
    stewart_model *m = bench::make_model("bench-calls", &params);
    if (!m) return 1;
    double ns = -2;
    if (!std::strcmp(row, "inverse-kinematic")) ns = run_inverse(m, STEWART_KINEMATIC, calls);
    if (!std::strcmp(row, "inverse-massless")) ns = run_inverse(m, STEWART_MASSLESS, calls);
    if (!std::strcmp(row, "inverse-full")) ns = run_inverse(m, STEWART_FULL, calls);
    if (!std::strcmp(row, "forward-tracking")) ns = run_forward(m, calls);
    if (!std::strcmp(row, "inverse-full-fresh")) ns = run_inverse(m, STEWART_FULL, calls, true);
    if (!std::strcmp(row, "forward-fresh")) ns = run_forward(m, calls, true);
    if (!std::strcmp(row, "plant-massless")) ns = run_plant(m, STEWART_MASSLESS, calls);
    if (!std::strcmp(row, "plant-full")) ns = run_plant(m, STEWART_FULL, calls);
    stewart_model_free(m);
    if (ns == -2) {
        std::fprintf(stderr, "bench-calls: unknown row %s\n", row);
        return 2;
    }
    if (ns < 0) {
        std::fprintf(stderr, "bench-calls: a call of row %s failed\n", row);
        return 1;
    }
    std::printf("%s: %d calls, median %.1f ns per call\n", row, calls, ns);
    return 0;
}
