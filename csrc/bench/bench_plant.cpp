// CPU microseconds per communication step of the plant (forward dynamics) along the combined cue
// (scenes/combined.json's formula), driven by the inverse side's forces and their rates, for
// both fidelities: the default integrator (ARKODE explicit Runge-Kutta) against the same plant
// on CVODE Adams and on CVODE BDF with a dense Jacobian, plus a tolerance and step-size sweep
// with the pose error against the cue. Prints the medians of 7 passes and writes them to argv[1].
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <ctime>
#include <string>
#include <vector>

#include "bench/bench_support.hpp"
#include "bench/combined_cue.hpp"
#include "drives/plant_drive.hpp"
#include "stewart/stewart_plant.h"

namespace {

struct Drive {
    double h;
    std::vector<double> force, rate;         // 6 per sample
    std::vector<stewart_plant_input> input;  // step i: samples i to i + 1, cubic Hermite
};

// An inverse solver at fidelity (nullptr if it cannot be made).
stewart_inverse *inverse_at(const stewart_model *model, int fidelity) {
    stewart_inverse_options o;
    stewart_inverse_options_default(&o);
    o.fidelity = fidelity;
    return stewart_inverse_create(model, &o, nullptr, 0);
}

// d's step h and room for its values and rates at the communication points of duration; their
// count less one (the steps).
int start_drive(double h, double duration, Drive &d) {
    const int n = static_cast<int>(duration / h + 0.5);
    d.h = h;
    d.force.assign(6 * (n + 1), 0);
    d.rate.assign(6 * (n + 1), 0);
    return n;
}

// The n steps' inputs: each from the values and rates at its two ends.
void add_step_inputs(int n, Drive &d) {
    for (int i = 0; i < n; ++i) {
        stewart_plant_input in{};
        in.h = d.h;
        in.derivatives = 1;
        for (int k = 0; k < 6; ++k) {
            in.force_start[k] = d.force[6 * i + k];
            in.force_end[k] = d.force[6 * i + 6 + k];
            in.force_rate_start[k] = d.rate[6 * i + k];
            in.force_rate_end[k] = d.rate[6 * i + 6 + k];
        }
        d.input.push_back(in);
    }
}

// Inverse-side forces at every communication point and their rates (central differences).
bool make_drive(const stewart_model *model, int fidelity, double h, double duration, Drive &d) {
    stewart_inverse *data = inverse_at(model, fidelity);
    const int n = start_drive(h, duration, d);
    const double delta = 1e-4;
    bool ok = data != nullptr;
    for (int i = 0; i <= n && ok; ++i) {
        stewart_inverse_output now, ahead, behind;
        stewart_inverse_input p = {combined_cue(i * h)};
        ok = stewart_inverse_solve(data, &p, &now) == STEWART_OK;
        p.pose = combined_cue(i * h + delta);
        ok = ok && stewart_inverse_solve(data, &p, &ahead) == STEWART_OK;
        p.pose = combined_cue(i * h - delta);
        ok = ok && stewart_inverse_solve(data, &p, &behind) == STEWART_OK;
        for (int k = 0; k < 6; ++k) {
            d.force[6 * i + k] = now.force[k];
            d.rate[6 * i + k] = (ahead.force[k] - behind.force[k]) / (2 * delta);
        }
    }
    if (ok) add_step_inputs(n, d);
    stewart_inverse_free(data);
    return ok;
}

const char *const kMethodNames[4] = {"CVODE Adams, fixed point", "CVODE BDF, dense Jacobian",
                                     "ARKODE ERK 4(3) (default)", "ARKODE ERK DP5(4)"};

const char *const kShortNames[4] = {"Adams", "BDF", "ERK4", "ERK5"};

struct Result {
    double us_per_step = 0, rhs_per_step = 0, pose_error = 0;
    bool ok = true;
};

double cpu_seconds() {
    timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

Result run(const stewart_model *model, const stewart_plant_options &o, const Drive &d, int passes) {
    Result r;
    char msg[STEWART_MESSAGE_SIZE];
    stewart_plant *plant = stewart_plant_create(model, &o, msg, sizeof msg);
    if (!plant) {
        std::fprintf(stderr, "bench-plant: %s\n", msg);
        r.ok = false;
        return r;
    }
    const int steps = static_cast<int>(d.force.size() / 6) - 1;
    std::vector<double> per_step;
    const stewart_pose start = combined_cue(0);
    for (int pass = 0; pass < passes && r.ok; ++pass) {
        stewart_plant_set_state(plant, 0, start.q, start.q_dot);
        stewart_plant_statistics before;
        stewart_plant_statistics_get(plant, &before);
        const double t0 = cpu_seconds();
        stewart_plant_output out;
        for (int i = 0; i < steps; ++i)
            if (stewart_plant_step(plant, &d.input[i], &out) != STEWART_OK) {
                std::fprintf(stderr, "bench-plant: step %d: %s\n", i, stewart_plant_message(plant));
                r.ok = false;
                break;
            }
        per_step.push_back((cpu_seconds() - t0) / steps * 1e6);
        stewart_plant_statistics after;
        stewart_plant_statistics_get(plant, &after);
        r.rhs_per_step = double(after.total_rhs_evaluations - before.total_rhs_evaluations) / steps;
    }
    // The pose error against the cue, on one more pass.
    stewart_plant_set_state(plant, 0, start.q, start.q_dot);
    for (int i = 0; i < steps && r.ok; ++i) {
        stewart_plant_output out;
        stewart_plant_step(plant, &d.input[i], &out);
        const stewart_pose cue = combined_cue((i + 1) * d.h);
        for (int c = 0; c < 6; ++c)
            r.pose_error = std::max(r.pose_error, std::fabs(out.pose.q[c] - cue.q[c]));
    }
    stewart_plant_free(plant);
    r.us_per_step = bench::median(std::move(per_step));
    return r;
}

// A loop a master could close (not the controller FMU): the inverse side's forces along the cue
// plus PD on the leg lengths the plant reports, held over each step (zero-order hold). Returns
// the largest position and angle errors over 4 s, or a negative number if the loop diverges.
void closed_loop(const stewart_model *model, double kp, double kd, double h, double &position,
                 double &angle) {
    char msg[STEWART_MESSAGE_SIZE];
    stewart_plant_options po;
    stewart_plant_options_default(&po);
    stewart_plant *plant = stewart_plant_create(model, &po, msg, sizeof msg);
    stewart_inverse_options so;
    stewart_inverse_options_default(&so);
    so.fidelity = STEWART_FULL;
    stewart_inverse *data = stewart_inverse_create(model, &so, nullptr, 0);
    const stewart_pose start = combined_cue(0);
    stewart_plant_set_state(plant, 0, start.q, start.q_dot);
    stewart_plant_output out;
    stewart_plant_output_get(plant, nullptr, &out);
    position = angle = 0;
    const int n = static_cast<int>(4.0 / h + 0.5);
    for (int i = 0; i < n; ++i) {
        stewart_pose cue = combined_cue(i * h);
        const stewart_inverse_input in = {cue};
        stewart_inverse_output inverse;
        double force[6];
        if (stewart_inverse_solve(data, &in, &inverse) != STEWART_OK) break;
        for (int k = 0; k < 6; ++k)
            force[k] = inverse.force[k] + kp * (inverse.lengths.length[k] - out.lengths.length[k]) +
                       kd * (inverse.lengths.length_rate[k] - out.lengths.length_rate[k]);
        stewart_plant_input held{};  // zero-order hold
        held.h = h;
        std::copy(force, force + 6, held.force_start);
        std::copy(force, force + 6, held.force_end);
        if (stewart_plant_step(plant, &held, &out) != STEWART_OK) {
            position = angle = -1;
            break;
        }
        cue = combined_cue((i + 1) * h);
        for (int c = 0; c < 6; ++c)
            (c < 3 ? position : angle) =
                std::max(c < 3 ? position : angle, std::fabs(out.pose.q[c] - cue.q[c]));
        if (!(position < 0.1)) {  // diverging: the loop is unstable at this step
            position = angle = -1;
            break;
        }
    }
    stewart_inverse_free(data);
    stewart_plant_free(plant);
}

}  // namespace

// A drive on every leg (5 mm lead, gear 3, k_t 0.5 N m/A, efficiencies 0.9 / 0.8, Coulomb,
// Stribeck and viscous friction; rigid legs).
void with_drives(stewart_params &p) {
    for (int k = 0; k < 6; ++k) {
        p.screw_lead[k] = 0.005;
        p.gear_ratio[k] = 3;
        p.rotor_inertia[k] = 2e-5;
        p.screw_inertia[k] = 9e-5;
        p.torque_constant[k] = 0.5;
        p.winding_resistance[k] = 1.2;
        p.screw_efficiency[k] = 0.9;
        p.screw_back_efficiency[k] = 0.8;
        p.coulomb_friction[k] = 40;
        p.stribeck_friction[k] = 60;
        p.stribeck_speed[k] = 0.01;
        p.viscous_friction[k] = 300;
    }
}

// The currents of the inverse side's forces by the plant's drive law (plant_drive.hpp, with the
// plant's smoothing speed vs); rates by the same central differences.
bool make_current_drive(const stewart_model *model, const stewart_params &p, int fidelity, double h,
                        double duration, double vs, Drive &d) {
    stewart_inverse *data = inverse_at(model, fidelity);
    const int n = start_drive(h, duration, d);
    auto current = [&](double t, double i[6]) {
        stewart_inverse_output out;
        stewart_inverse_input in = {combined_cue(t)};
        if (stewart_inverse_solve(data, &in, &out) != STEWART_OK) return false;
        for (int k = 0; k < 6; ++k) {
            i[k] =
                stewart::drive_current(stewart::leg_drive(p, k), out.force[k],
                                       out.lengths.length_rate[k], out.lengths.length_accel[k], vs);
        }
        return true;
    };
    bool ok = data != nullptr;
    const double delta = 1e-4;
    for (int i = 0; i <= n && ok; ++i) {
        double now[6], ahead[6], behind[6];
        ok = current(i * h, now) && current(i * h + delta, ahead) && current(i * h - delta, behind);
        for (int k = 0; k < 6 && ok; ++k) {
            d.force[6 * i + k] = now[k];
            d.rate[6 * i + k] = (ahead[k] - behind[k]) / (2 * delta);
        }
    }
    if (ok) add_step_inputs(n, d);
    stewart_inverse_free(data);
    return ok;
}

// The plant driven by currents against the same plant driven by forces (the drives' cost), at
// 1 ms, default method and tolerances: the report's lines.
bool drives_report(std::string &report, int passes, bool lossless) {
    stewart_params p;
    stewart_params_default(&p);
    with_drives(p);
    if (lossless)
        for (int k = 0; k < 6; ++k) {
            p.screw_efficiency[k] = p.screw_back_efficiency[k] = 1;
            p.coulomb_friction[k] = p.stribeck_friction[k] = p.viscous_friction[k] = 0;
        }
    stewart_model *driven = bench::make_model("bench-plant", &p);
    stewart_model *plain = bench::make_model("bench-plant");
    bool ok = driven && plain;
    char line[256];
    report += lossless ? "\ndrives, lossless (current input, rotor and screw inertia only, rigid "
                         "legs) against force input, 1 ms, default tolerances:\n"
                       : "\ndrives (current input, efficiencies 0.9/0.8, friction, rigid legs) "
                         "against force input, 1 ms, default tolerances:\n";
    report += "fidelity  input                   us/step  rhs/step  pose error\n";
    const char *names[3] = {"", "massless", "full"};
    for (int f : {STEWART_MASSLESS, STEWART_FULL}) {
        Drive forces;
        ok = ok && make_drive(plain, f, 1e-3, 2.0, forces);
        if (!ok) break;
        stewart_plant_options o;
        stewart_plant_options_default(&o);
        o.fidelity = f;
        const Result by_force = run(plain, o, forces, passes);
        ok = ok && by_force.ok;
        std::snprintf(line, sizeof line, "%-9s force                   %7.2f  %8.1f  %10.2e\n",
                      names[f], by_force.us_per_step, by_force.rhs_per_step, by_force.pose_error);
        report += line;
        o.input = STEWART_PLANT_INPUT_CURRENT;
        // the friction's smoothing speed: what the turns cost (lossless: no friction, one run)
        for (double vs : {1e-4, 1e-3, 1e-2}) {
            if (lossless && vs != 1e-4) break;
            o.smoothing_speed = vs;
            Drive currents;
            ok = ok && make_current_drive(driven, p, f, 1e-3, 2.0, vs, currents);
            if (!ok) break;
            const Result by_current = run(driven, o, currents, passes);
            ok = ok && by_current.ok;
            std::snprintf(line, sizeof line,
                          "%-9s current, v_s %-8.0e  %7.2f  %8.1f  %10.2e   (%.2f x force)\n",
                          names[f], vs, by_current.us_per_step, by_current.rhs_per_step,
                          by_current.pose_error, by_current.us_per_step / by_force.us_per_step);
            report += line;
        }
    }
    stewart_model_free(driven);
    stewart_model_free(plain);
    return ok;
}

// One plant of drives_report (fidelity 1 or 2, the kind of input and losses below, smoothing
// speed vs), one pass over the cue: what callgrind counts per step
// (`valgrind --tool=callgrind --toggle-collect=stewart_plant_step bench-plant drives-one ...`).
// kind: "force", "current" (every loss), "lossless", "friction" (lossless screw), "screw" (no
// friction)
bool drives_one(int fidelity, const std::string &kind, double vs) {
    const bool current = kind != "force", lossless = kind == "lossless";
    stewart_params p;
    stewart_params_default(&p);
    if (current) with_drives(p);
    for (int k = 0; k < 6; ++k) {
        if (lossless || kind == "friction") p.screw_efficiency[k] = p.screw_back_efficiency[k] = 1;
        if (lossless || kind == "screw")
            p.coulomb_friction[k] = p.stribeck_friction[k] = p.viscous_friction[k] = 0;
    }
    stewart_model *model = bench::make_model("bench-plant", &p);
    if (!model) return false;
    Drive d;
    bool ok = current ? make_current_drive(model, p, fidelity, 1e-3, 2.0, vs, d)
                      : make_drive(model, fidelity, 1e-3, 2.0, d);
    stewart_plant_options o;
    stewart_plant_options_default(&o);
    o.fidelity = fidelity;
    o.smoothing_speed = vs;
    if (current) o.input = STEWART_PLANT_INPUT_CURRENT;
    const Result r = ok ? run(model, o, d, 1) : Result();
    std::printf("%s, %s: %.2f us/step, %.1f rhs/step\n",
                fidelity == STEWART_FULL ? "full" : "massless", kind.c_str(), r.us_per_step,
                r.rhs_per_step);
    stewart_model_free(model);
    return ok && r.ok;
}

int main(int argc, char **argv) {
    if (argc > 4 && std::string(argv[1]) == "drives-one")
        return drives_one(std::atoi(argv[2]), argv[3], std::atof(argv[4])) ? 0 : 1;
    // "bench-plant drives": the drives' comparison alone (for callgrind, docs/latency.md)
    if (argc > 1 && std::string(argv[1]) == "drives") {
        std::string report;
        const int passes = argc > 2 ? std::atoi(argv[2]) : 7;
        const bool ok = drives_report(report, passes, true) && drives_report(report, passes, false);
        std::fputs(report.c_str(), stdout);
        return ok ? 0 : 1;
    }
    stewart_model *model = bench::make_model("bench-plant");
    if (!model) return 1;
    const double duration = 2.0;
    const int passes = 7;
    std::string report =
        "plant (forward dynamics) along the combined cue, 2 s, inverse-side forces with their "
        "rates (cubic Hermite);\nmedian CPU us per communication step over 7 passes; pose error = "
        "max |pose - cue| [m, rad]\n";
    char line[256];
    const char *names[3] = {"", "massless", "full"};
    bool ok = true;
    Drive drive[3];
    for (int f : {STEWART_MASSLESS, STEWART_FULL})
        ok = ok && make_drive(model, f, 1e-3, duration, drive[f]);

    report += "\n1 ms steps, default tolerances (rtol 1e-10, atol 1e-12):\n";
    report += "fidelity  method                       us/step  rhs/step  pose error\n";
    double ours_us[3] = {0}, bdf_us[3] = {0};
    for (int f : {STEWART_MASSLESS, STEWART_FULL}) {
        for (int method :
             {STEWART_PLANT_ERK, STEWART_PLANT_ERK5, STEWART_PLANT_ADAMS, STEWART_PLANT_BDF}) {
            stewart_plant_options o;
            stewart_plant_options_default(&o);
            o.fidelity = f;
            o.method = method;
            const Result r = run(model, o, drive[f], passes);
            ok = ok && r.ok;
            if (method == STEWART_PLANT_ERK) ours_us[f] = r.us_per_step;
            if (method == STEWART_PLANT_BDF) bdf_us[f] = r.us_per_step;
            std::snprintf(line, sizeof line, "%-9s %-28s %7.2f  %8.1f  %10.2e\n", names[f],
                          kMethodNames[method], r.us_per_step, r.rhs_per_step, r.pose_error);
            report += line;
        }
        std::snprintf(line, sizeof line, "%-9s dense / ours = %.2f\n", names[f],
                      bdf_us[f] / ours_us[f]);
        report += line;
    }

    report += "\ntolerance sweep, 1 ms steps:\n";
    report += "fidelity  method  rtol     atol     us/step  rhs/step  pose error\n";
    for (int f : {STEWART_MASSLESS, STEWART_FULL})
        for (int method : {STEWART_PLANT_ERK, STEWART_PLANT_ERK5, STEWART_PLANT_ADAMS})
            for (double rtol : {1e-6, 1e-8, 1e-10, 1e-12}) {
                stewart_plant_options o;
                stewart_plant_options_default(&o);
                o.method = method;
                o.fidelity = f;
                o.relative_tolerance = rtol;
                o.absolute_tolerance = rtol * 1e-2;
                const Result r = run(model, o, drive[f], passes);
                ok = ok && r.ok;
                std::snprintf(line, sizeof line, "%-9s %-7s %-8.0e %-8.0e %7.2f  %8.1f  %10.2e\n",
                              names[f], kShortNames[method], rtol, rtol * 1e-2, r.us_per_step,
                              r.rhs_per_step, r.pose_error);
                report += line;
            }

    report += "\ncommunication step sweep, default method and tolerances, full fidelity:\n";
    report += "step [s]  us/step  rhs/step  pose error\n";
    for (double h : {1e-4, 5e-4, 1e-3, 2e-3, 5e-3, 1e-2}) {
        Drive d;
        ok = ok && make_drive(model, STEWART_FULL, h, duration, d);
        stewart_plant_options o;
        stewart_plant_options_default(&o);
        o.method = STEWART_PLANT_ERK;
        const Result r = run(model, o, d, 3);
        ok = ok && r.ok;
        std::snprintf(line, sizeof line, "%-8.0e  %7.2f  %8.1f  %10.2e\n", h, r.us_per_step,
                      r.rhs_per_step, r.pose_error);
        report += line;
    }
    report += "\nclosed loop: inverse-side forces + PD on the leg lengths, held over each step, "
              "full fidelity, 4 s;\nmax position [m] / angle [rad] error, or unstable:\n";
    report += "Kp [N/m]  Kd [N s/m]  step 1 ms               2 ms                    5 ms\n";
    const double gains[3][2] = {{2e5, 2e3}, {1e6, 1e4}, {5e6, 3e4}};
    for (const auto &g : gains) {
        std::snprintf(line, sizeof line, "%-9.0e %-11.0e", g[0], g[1]);
        report += line;
        for (double h : {1e-3, 2e-3, 5e-3}) {
            double position, angle;
            closed_loop(model, g[0], g[1], h, position, angle);
            if (position < 0) std::snprintf(line, sizeof line, " %-23s", "unstable");
            else std::snprintf(line, sizeof line, " %.2e / %.2e    ", position, angle);
            report += line;
        }
        report += "\n";
    }
    ok = drives_report(report, passes, true) && drives_report(report, passes, false) && ok;
    std::fputs(report.c_str(), stdout);
    if (argc > 1) {
        FILE *out = std::fopen(argv[1], "w");
        if (!out || std::fputs(report.c_str(), out) < 0 || std::fclose(out) != 0) {
            std::fprintf(stderr, "bench-plant: cannot write %s\n", argv[1]);
            return 1;
        }
    }
    stewart_model_free(model);
    return ok ? 0 : 1;
}
