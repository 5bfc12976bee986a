// libFuzzer target over the platform-file reader (stewart_params_read_json) and the model made from
// what it reads. Invariants: nothing crashes or hangs; a refused file leaves the parameters as they
// were and says why; a file read gives finite elements within the table's ranges and changes only
// the parameters it gives; the model is made or refused with a message. Built with clang
// -fsanitize=fuzzer by scripts/fuzz.sh (target `platform`); tests/CMakeLists.txt also builds it
// with the replay main (fuzz_replay.cpp) that runs tests/fuzz/corpus/platform_file under ctest.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "stewart/stewart.h"
#include "stewart/stewart_platform_file.h"
#include "stewart/stewart_table.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *bytes, size_t size) {
    stewart_params p, before;
    stewart_params_default(&p);
    before = p;
    char message[STEWART_MESSAGE_SIZE];
    std::vector<unsigned char> given(static_cast<size_t>(stewart_param_count()), 2);
    const stewart_status s = stewart_params_read_json(&p, reinterpret_cast<const char *>(bytes),
                                                      size, given.data(), message, sizeof message);
    if (s != STEWART_OK) {
        if (std::memcmp(&p, &before, sizeof p) != 0 || message[0] == '\0') std::abort();
        return 0;
    }
    for (int i = 0; i < stewart_param_count(); ++i) {
        if (given[static_cast<size_t>(i)] > 1) std::abort();  // every entry written
        for (int e = 0; e < stewart_param(i)->count; ++e) {
            const double value = *stewart_param_element(&p, i, e);
            if (stewart_param_check_value(i, e, value, message, sizeof message) != STEWART_OK)
                std::abort();
            if (!given[static_cast<size_t>(i)] && value != *stewart_param_element(&before, i, e))
                std::abort();
        }
    }
    stewart_model *model = stewart_model_create(&p, message, sizeof message);
    if (!model && message[0] == '\0') std::abort();
    stewart_model_free(model);
    return 0;
}
