// Nanoseconds per row of the C batches (stewart_batch.h) along the combined cue at 1 ms, one line
// per batch: the inverse at its three levels, forward kinematics tracking the kinematic lengths,
// and the plant at both fidelities driven by the full level's forces. The median over repeated
// whole batches. studies/bench/batches.py runs this beside the Python API on the same rows.
// The kinematic and massless levels also on each kernel (batch_paths.hpp: "scalar", one
// stewart_inverse_solve per row; "portable"; "avx2" and "avx512vl" where the CPU has them), in
// the same run.
// usage: bench-batch [ROWS (6000)]
//        bench-batch ROWS --kernels           the kinematic and massless levels on each kernel
//                                             only (201 batches each)
//        bench-batch ROWS --once LEVEL PATH   one batch only, LEVEL 0 or 1, PATH scalar, portable,
//                                             avx2 or avx512vl (for callgrind)
//        ... --drives                        any of these on a model with a drive on every leg
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

#include "batch_paths.hpp"
#include "bench/bench_support.hpp"
#include "bench/combined_cue.hpp"
#include "stewart/stewart_batch.h"
#include "stewart/stewart_forward.h"
#include "stewart/stewart_plant.h"

namespace {

constexpr double kStep = 1e-3;  // [s] between rows

// The median of `repeats` runs of batch, in ns per row (a failed batch aborts the program: a
// benchmark of a refusal measures nothing).
double median_ns_per_row(int repeats, size_t rows, const std::function<stewart_status()> &batch,
                         double *fastest = nullptr) {
    std::vector<double> ns;
    for (int r = 0; r < repeats; ++r) {
        const auto start = bench::Clock::now();
        const stewart_status s = batch();
        const double elapsed = bench::ns_since(start);
        if (s != STEWART_OK) {
            std::fprintf(stderr, "bench-batch: a batch failed with status %d\n", s);
            std::exit(1);
        }
        ns.push_back(elapsed / rows);
    }
    if (fastest) *fastest = *std::min_element(ns.begin(), ns.end());
    return bench::median(std::move(ns));
}

// Every column of a batch's output tables, n rows each, and the batch outputs pointing at them:
// the arrays the Python API asks for, so that both sides do the same work.
#define BENCH_VECTOR(name, member, count, type, unit, description) std::vector<type> name;
#define BENCH_SIZE(name, member, count, type, unit, description) name.resize(n *(count));
#define BENCH_POINT(name, member, count, type, unit, description) out.name = name.data();
// The drive columns only for a model with drives (as the Python API and stewart-solve ask).
#define BENCH_NO_DRIVE(name, member, count, type, unit, description) out.name = nullptr;
struct InverseColumns {
    STEWART_INVERSE_OUTPUT_TABLE(BENCH_VECTOR)
    std::vector<int> status;
    bool drive_columns;
    InverseColumns(size_t n, const stewart_model *model) : status(n), drive_columns(false) {
        STEWART_INVERSE_OUTPUT_TABLE(BENCH_SIZE)
        for (double lead : stewart_model_params(model)->screw_lead)
            drive_columns = drive_columns || lead > 0;
    }
    stewart_inverse_batch_outputs outputs() {
        stewart_inverse_batch_outputs out{};
        STEWART_INVERSE_OUTPUT_TABLE(BENCH_POINT)
        if (!drive_columns) {
            STEWART_INVERSE_DRIVE_OUTPUT_TABLE(BENCH_NO_DRIVE)
        }
        out.status = status.data();
        return out;
    }
};
struct ForwardColumns {
    STEWART_FORWARD_OUTPUT_TABLE(BENCH_VECTOR)
    std::vector<int> status;
    explicit ForwardColumns(size_t n)
        : status(n){STEWART_FORWARD_OUTPUT_TABLE(BENCH_SIZE)} stewart_forward_batch_outputs
          outputs() {
        stewart_forward_batch_outputs out{};
        STEWART_FORWARD_OUTPUT_TABLE(BENCH_POINT)
        out.status = status.data();
        return out;
    }
};
struct PlantColumns {
    STEWART_PLANT_OUTPUT_TABLE(BENCH_VECTOR)
    STEWART_PLANT_STEP_TABLE(BENCH_VECTOR)
    std::vector<int> status;
    explicit PlantColumns(size_t n)
        : status(n){STEWART_PLANT_OUTPUT_TABLE(BENCH_SIZE)
                        STEWART_PLANT_STEP_TABLE(BENCH_SIZE)} stewart_plant_batch_outputs
          outputs() {
        stewart_plant_batch_outputs out{};
        STEWART_PLANT_OUTPUT_TABLE(BENCH_POINT)
        STEWART_PLANT_STEP_TABLE(BENCH_POINT)
        out.status = status.data();
        return out;
    }
};
#undef BENCH_VECTOR
#undef BENCH_SIZE
#undef BENCH_POINT

// An inverse solver at level (STEWART_KINEMATIC, ...) with default options otherwise.
stewart_inverse *inverse_at(const stewart_model *model, int level) {
    stewart_inverse_options o;
    stewart_inverse_options_default(&o);
    o.fidelity = level;
    return stewart_inverse_create(model, &o, nullptr, 0);
}

// One batch of level (0 kinematic, 1 massless) on the kernel named path: what callgrind counts.
int one_batch(const stewart_model *model, size_t n, const std::vector<double> &q,
              const std::vector<double> &q_dot, const std::vector<double> &q_ddot, int level,
              const std::string &path_name) {
    const stewart::VectorPath path = path_name == "avx512vl"   ? stewart::VectorPath::avx512vl
                                     : path_name == "avx2"     ? stewart::VectorPath::avx2
                                     : path_name == "portable" ? stewart::VectorPath::portable
                                                               : stewart::VectorPath::scalar;
    if (!stewart::vector_path_available(path)) return 2;  // not on this CPU
    stewart_inverse *inverse = inverse_at(model, level);
    if (!inverse) return 1;
    InverseColumns columns(n, model);
    const stewart_inverse_batch_outputs out = columns.outputs();
    const stewart_status s = stewart::inverse_batch(inverse, n, q.data(), q_dot.data(),
                                                    q_ddot.data(), &out, nullptr, nullptr, path);
    std::printf("%s %s: status %d\n", level ? "massless" : "kinematic", path_name.c_str(), s);
    stewart_inverse_free(inverse);
    return s == STEWART_OK ? 0 : 1;
}

// The kinematic and massless levels on each kernel this CPU runs, repeats whole batches each: one
// line per level and kernel, the median and with show_fastest the fastest batch (the least
// disturbed by other processes on a shared machine; studies/bench/batches.py reads the median as
// a line's last value). Returns 0, 1 where a solver cannot be made.
int time_kernels(const stewart_model *model, size_t n, const std::vector<double> &q,
                 const std::vector<double> &q_dot, const std::vector<double> &q_ddot, int repeats,
                 bool show_fastest) {
    const char *level_name[] = {"inverse kinematic", "inverse massless"};
    const char *path_name[] = {"scalar", "portable", "avx2", "avx512vl"};
    InverseColumns columns(n, model);
    const stewart_inverse_batch_outputs out = columns.outputs();
    for (int level = 0; level < 2; ++level)
        for (int path = 0; path < 4; ++path) {
            if (!stewart::vector_path_available(stewart::VectorPath(path))) continue;
            stewart_inverse *inverse = inverse_at(model, level);
            if (!inverse) return 1;
            double fastest;
            const double ns = median_ns_per_row(
                repeats, n,
                [&] {
                    return stewart::inverse_batch(inverse, n, q.data(), q_dot.data(), q_ddot.data(),
                                                  &out, nullptr, nullptr,
                                                  stewart::VectorPath(path));
                },
                &fastest);
            char name[64];
            std::snprintf(name, sizeof name, "%s %s", level_name[level], path_name[path]);
            if (show_fastest) std::printf("%-30s %10.1f  (fastest %.1f)\n", name, ns, fastest);
            else std::printf("%-30s %10.1f\n", name, ns);
            stewart_inverse_free(inverse);
        }
    return 0;
}

}  // namespace

// A drive on every leg (docs/drives.md): screw, gear, rotor, motor winding and friction with a
// Stribeck peak, so that every term of the drive columns is computed.
stewart_params drive_params() {
    stewart_params p;
    stewart_params_default(&p);
    for (int k = 0; k < STEWART_LEGS; ++k) {
        p.screw_lead[k] = 0.005, p.gear_ratio[k] = 3, p.rotor_inertia[k] = 1.37e-4;
        p.screw_efficiency[k] = 0.9, p.screw_back_efficiency[k] = 0.8;
        p.torque_constant[k] = 0.5, p.winding_resistance[k] = 1.2;
        p.winding_inductance[k] = 3e-3, p.coulomb_friction[k] = 20;
        p.stribeck_friction[k] = 30, p.stribeck_speed[k] = 0.01, p.viscous_friction[k] = 100;
    }
    return p;
}

int main(int argc, char **argv) {
    // a last argument --drives: the same runs on a model with drives
    const bool drives = argc > 1 && std::string(argv[argc - 1]) == "--drives";
    if (drives) --argc;
    const size_t n = argc > 1 ? std::strtoul(argv[1], nullptr, 10) : 6000;
    if (n < 2) return std::fprintf(stderr, "usage: bench-batch [ROWS >= 2] [--drives]\n"), 2;
    const bool once = argc == 5 && std::string(argv[2]) == "--once";
    const stewart_params with_drives = drive_params();
    stewart_model *model = bench::make_model("bench-batch", drives ? &with_drives : nullptr);
    if (!model) return 1;
    std::vector<double> q(6 * n), q_dot(6 * n), q_ddot(6 * n), time(n);
    for (size_t j = 0; j < n; ++j) {
        const stewart_pose p = combined_cue(j * kStep);
        std::copy(p.q, p.q + 6, &q[6 * j]);
        std::copy(p.q_dot, p.q_dot + 6, &q_dot[6 * j]);
        std::copy(p.q_ddot, p.q_ddot + 6, &q_ddot[6 * j]);
        time[j] = j * kStep;
    }
    if (once) return one_batch(model, n, q, q_dot, q_ddot, std::atoi(argv[3]), argv[4]);
    const bool kernels_only = argc == 3 && std::string(argv[2]) == "--kernels";
    std::printf("# ns per row, median of whole batches of %zu rows (combined cue, 1 ms)\n", n);
    if (kernels_only) return time_kernels(model, n, q, q_dot, q_ddot, 201, true);

    // (the kinematic level's lengths drive forward kinematics, the full level's forces the plant)
    const char *level_name[] = {"inverse kinematic", "inverse massless", "inverse full"};
    const int level_repeats[] = {51, 51, 5};
    std::vector<InverseColumns> levels(3, InverseColumns(n, model));
    for (int level = 0; level < 3; ++level) {
        stewart_inverse *inverse = inverse_at(model, level);
        if (!inverse) return 1;
        const stewart_inverse_batch_outputs out = levels[level].outputs();
        const double ns = median_ns_per_row(level_repeats[level], n, [&] {
            stewart_inverse_reset(inverse);
            return stewart_inverse_batch(inverse, n, q.data(), q_dot.data(), q_ddot.data(), &out,
                                         nullptr, nullptr);
        });
        std::printf("%-22s %10.1f\n", level_name[level], ns);
        stewart_inverse_free(inverse);
    }

    // The closed-form levels on each kernel.
    if (time_kernels(model, n, q, q_dot, q_ddot, level_repeats[0], false) != 0) return 1;

    stewart_forward_options fo;
    stewart_forward_options_default(&fo);
    stewart_forward *forward = stewart_forward_create(model, &fo, nullptr, 0);
    if (!forward) return 1;
    ForwardColumns tracked(n);
    const stewart_forward_batch_outputs fout = tracked.outputs();
    const double forward_ns = median_ns_per_row(21, n, [&] {
        stewart_forward_reset(forward);
        return stewart_forward_batch(forward, n, time.data(), levels[0].length.data(), nullptr,
                                     nullptr, nullptr, &fout, nullptr, nullptr);
    });
    std::printf("%-22s %10.1f\n", "forward tracking", forward_ns);
    stewart_forward_free(forward);

    const char *plant_name[] = {"plant massless", "plant full"};
    const int plant_repeats[] = {11, 3};
    PlantColumns simulated(n);
    const stewart_plant_batch_outputs pout = simulated.outputs();
    for (int fidelity = 1; fidelity <= 2; ++fidelity) {
        stewart_plant_options po;
        stewart_plant_options_default(&po);
        po.fidelity = fidelity;
        stewart_plant *plant = stewart_plant_create(model, &po, nullptr, 0);
        if (!plant) return 1;
        const double ns = median_ns_per_row(plant_repeats[fidelity - 1], n, [&] {
            stewart_plant_reset(plant);
            return stewart_plant_batch(plant, n, time.data(), levels[2].force.data(), q.data(),
                                       q_dot.data(), &pout, nullptr, nullptr);
        });
        std::printf("%-22s %10.1f\n", plant_name[fidelity - 1], ns);
        stewart_plant_free(plant);
    }
    stewart_model_free(model);
    return 0;
}
