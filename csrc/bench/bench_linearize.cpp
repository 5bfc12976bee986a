// Linearisation's cost (the goal: A and B at full fidelity in <= 50 us, well below a finite-
// difference linearisation): median
// nanoseconds per call of stewart_linearize_plant and stewart_linearize_inverse at both
// fidelities, at the poses of the combined cue (scenes/combined.json's formula) under the inverse
// side's forces. `bench-linearize` runs every row; `bench-linearize ROW CALLS` one row, whose
// API function is then called exactly CALLS times (studies/bench/linearize.sh counts its
// instructions with callgrind --toggle-collect). Rows: plant-massless, plant-full,
// inverse-massless, inverse-full.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "bench/bench_support.hpp"
#include "bench/combined_cue.hpp"
#include "stewart/stewart_linearize.h"

namespace {

using bench::median;
constexpr double kStep = 1e-3;

// Median ns of `calls` calls of the row (and -1 if a call fails).
double run_row(const stewart_model *model, const std::string &row, int calls) {
    const bool full = row.find("full") != std::string::npos;
    const bool plant = row.rfind("plant", 0) == 0;
    stewart_inverse_options io;
    stewart_inverse_options_default(&io);
    io.fidelity = full ? STEWART_FULL : STEWART_MASSLESS;
    stewart_inverse *inverse = stewart_inverse_create(model, &io, nullptr, 0);
    stewart_linearize_options lo;
    stewart_linearize_options_default(&lo);
    lo.fidelity = io.fidelity;
    stewart_linearize *l = stewart_linearize_create(model, &lo, nullptr, 0);
    if (!inverse || !l) return -1;
    // The operating points first, so that the timed loop holds only the calls.
    std::vector<stewart_linearize_input> points(calls);
    for (int i = 0; i < calls; ++i) {
        stewart_inverse_input in{combined_cue(i * kStep)};
        stewart_inverse_output out;
        if (stewart_inverse_solve(inverse, &in, &out) != STEWART_OK) return -1;
        points[i].pose = in.pose;
        std::memcpy(points[i].force, out.force, sizeof out.force);
    }
    std::vector<double> ns(calls);
    stewart_linearize_output plant_out;
    stewart_linearize_inverse_output inverse_out;
    bool ok = true;
    for (int i = 0; i < calls; ++i) {
        const bench::Clock::time_point start = bench::Clock::now();
        ok &= (plant ? stewart_linearize_plant(l, &points[i], &plant_out)
                     : stewart_linearize_inverse(l, &points[i].pose, &inverse_out)) == STEWART_OK;
        ns[i] = bench::ns_since(start);
    }
    stewart_linearize_free(l);
    stewart_inverse_free(inverse);
    return ok ? median(ns) : -1;
}

}  // namespace

int main(int argc, char **argv) {
    stewart_model *model = bench::make_model("bench-linearize");
    if (!model) return 1;
    std::vector<std::string> rows = {"plant-massless", "plant-full", "inverse-massless",
                                     "inverse-full"};
    int calls = 20000;
    if (argc == 3) {
        rows = {argv[1]};
        calls = std::atoi(argv[2]);
    }
    int status = 0;
    std::printf("linearisation, median of %d calls along the combined cue (thesis platform)\n",
                calls);
    for (const std::string &row : rows) {
        const double ns = run_row(model, row, calls);
        if (ns < 0) status = 1;
        std::printf("%-18s median %.0f ns (%.1f us)\n", row.c_str(), ns, ns / 1000);
    }
    stewart_model_free(model);
    return status;
}
