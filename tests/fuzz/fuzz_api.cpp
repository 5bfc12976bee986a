// libFuzzer target over the C API: random parameter edits, options and a sequence of poses, with
// raw doubles (NaN, Inf, huge and tiny values included). Invariants: nothing crashes, and a solve
// that returns STEWART_OK never writes a non-finite output. Built with clang -fsanitize=fuzzer by
// scripts/fuzz.sh; tests/CMakeLists.txt also builds it with a replay main (fuzz_replay.cpp) that
// runs the committed corpus in tests/fuzz/corpus/api under ctest.
//
// Building a model (the 14-body mechanism, its block plan) costs far more than a solve, so models
// are kept across inputs, keyed by their parameters, in a small cache of the harness (the library
// itself has no global state); each input starts from a reset data block, so that it sees the
// same thing as in a fresh process.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>

#include "fuzz_reader.hpp"
#include "stewart/stewart.h"
#include "stewart/stewart_forward.h"

namespace {

void require_finite(const stewart_output &o) {
    const double *all[] = {o.length, o.length_rate, o.length_accel, o.force};
    for (const double *g : all)
        for (int k = 0; k < STEWART_LEGS; ++k)
            if (!std::isfinite(g[k])) std::abort();
    if (!std::isfinite(o.condition) || !std::isfinite(o.residual)) std::abort();
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(o.base_force[i]) || !std::isfinite(o.base_torque[i])) std::abort();
}

// A model with its two data blocks, kept for inputs with the same parameters.
struct CachedModel {
    stewart_params params;
    stewart_model *model = nullptr;
    stewart_data *data = nullptr, *saved = nullptr;
};

// Bounded: at most kCacheSize models live at once; a new parameter set replaces the oldest entry.
constexpr int kCacheSize = 8;
CachedModel cache[kCacheSize];
int next_victim = 0;

// The cached model for these parameters (built on first use, data reset), or null with the
// library's message if the parameters are refused.
CachedModel *model_for(const stewart_params &params) {
    for (CachedModel &c : cache)
        if (c.model && std::memcmp(&c.params, &params, sizeof params) == 0) {
            stewart_data_reset(c.data);
            stewart_data_reset(c.saved);
            return &c;
        }
    char message[STEWART_MESSAGE_SIZE];
    stewart_model *model = stewart_model_create(&params, message, sizeof message);
    if (!model) return nullptr;
    CachedModel &c = cache[next_victim];
    next_victim = (next_victim + 1) % kCacheSize;
    stewart_data_free(c.saved);
    stewart_data_free(c.data);
    stewart_model_free(c.model);
    c.params = params;
    c.model = model;
    c.data = stewart_data_create(model);
    c.saved = stewart_data_create(model);
    return &c;
}

// The forward API on the same model: raw lengths, rates, accelerations, guesses and options
// (NaN, Inf, huge), tracking or cold. Every call returns a known status; a filled result
// (STEWART_OK, STEWART_ERR_OTHER_BRANCH) is finite.
void fuzz_forward(Reader &in, const stewart_model *model, stewart_data *data) {
    stewart_forward_options options;
    stewart_forward_options_default(&options);
    const uint8_t choice = in.byte();
    if (choice & 1) options.tolerance = in.value();
    if (choice & 2) options.max_iterations = static_cast<int8_t>(in.byte());
    double lengths[6], rates[6], accels[6], guess[6], time = 0;
    for (int call = 0; call < 16 && in.left > 0; ++call) {
        const uint8_t what = in.byte();
        for (int k = 0; k < 6; ++k) lengths[k] = (what & 1) ? in.value() : 0.55 + in.value() / 10;
        for (int k = 0; k < 6 && (what & 2); ++k) rates[k] = in.value();
        for (int k = 0; k < 6 && (what & 4); ++k) accels[k] = in.value();
        for (int k = 0; k < 6 && (what & 8); ++k) guess[k] = in.value();
        if (what & 16) stewart_forward_reset(data);
        time = (what & 32) ? in.value() : time + 1e-3;
        stewart_forward_result r;
        const stewart_status s = stewart_forward_solve(
            model, data, &options, time, lengths, (what & 2) ? rates : nullptr,
            (what & 4) ? accels : nullptr, (what & 8) ? guess : nullptr, &r);
        if (s > STEWART_OK || s < STEWART_ERR_OTHER_BRANCH) std::abort();
        if (s != STEWART_OK && s != STEWART_ERR_OTHER_BRANCH) continue;
        const double *groups[3] = {r.pose.q, r.pose.q_dot, r.pose.q_ddot};
        for (const double *g : groups)
            for (int i = 0; i < 6; ++i)
                if (!std::isfinite(g[i])) std::abort();
        if (!std::isfinite(r.residual) || !std::isfinite(r.condition) || !std::isfinite(r.jump))
            std::abort();
    }
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
    stewart_options options;
    stewart_options_default(&options);
    uint8_t choice = 0;
    in.take(&choice, 1);
    options.fidelity = choice % 4;  // 3 is invalid on purpose
    options.modified_newton = (choice >> 2) & 1;
    if (choice & 0x80) in.take(&options.tolerance, sizeof options.tolerance);

    CachedModel *c = model_for(params);
    if (!c) return 0;
    stewart_pose pose;
    stewart_output out;
    while (in.take(&pose, sizeof pose)) {
        if (stewart_solve(c->model, c->data, &options, &pose, &out) == STEWART_OK) require_finite(out);
        stewart_data_copy(c->saved, c->data);
    }
    Reader again{bytes, size};  // the pose loop takes every byte: read them again
    fuzz_forward(again, c->model, c->data);
    stewart_data_reset(c->data);
    return 0;
}
