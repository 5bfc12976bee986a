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
    stewart_data_reset(data);
    stewart_data_free(saved);
    stewart_data_free(data);
    stewart_model_free(model);
    return 0;
}
