// libFuzzer target over the C API: random parameter edits, options and a sequence of poses, with
// raw doubles (NaN, Inf, huge and tiny values included). Invariants: nothing crashes, and a solve
// that returns STEWART_OK never writes a non-finite output. Built with clang -fsanitize=fuzzer by
// scripts/fuzz.sh; tests/CMakeLists.txt also builds it with a replay main (fuzz_replay.cpp) that
// runs the committed corpus in tests/fuzz/corpus/api under ctest.
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

    char message[STEWART_MESSAGE_SIZE];
    stewart_model *model = stewart_model_create(&params, message, sizeof message);
    if (!model) return 0;
    stewart_data *data = stewart_data_create(model);
    stewart_data *saved = stewart_data_create(model);
    stewart_pose pose;
    stewart_output out;
    while (in.take(&pose, sizeof pose)) {
        if (stewart_solve(model, data, &options, &pose, &out) == STEWART_OK) require_finite(out);
        stewart_data_copy(saved, data);
    }
    Reader again{bytes, size};  // the pose loop takes every byte: read them again
    fuzz_forward(again, model, data);
    stewart_data_reset(data);
    stewart_data_free(saved);
    stewart_data_free(data);
    stewart_model_free(model);
    return 0;
}
