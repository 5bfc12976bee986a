// Cueing unit speed: median, p99 and max microseconds per stewart_cueing_step at 1 kHz on the
// thesis platform, for a gentle vehicle signal the machine can follow (the limiter checks the
// pose, and the extrapolated ones, and finds them within every limit) with the default
// lookahead and with none, and for a violent one (2 g, 200 deg/s: the limiter bisects); then the
// same with leg speed and acceleration limits (0.3 m/s, 3 m/s2: the leg limiter checks the legs
// and the stop pose at every step, and on the violent signal scales its tracking acceleration).
// usage: bench-cueing [STEPS (20000)]
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "bench/bench_support.hpp"
#include "stewart/stewart_cueing.h"

namespace {

// The vehicle at sample k of a 1 kHz run: sines of `force` m/s2 and `rate` rad/s.
stewart_cueing_input vehicle(int k, double force, double rate) {
    const double t = 1e-3 * k;
    stewart_cueing_input in;
    in.dt = k ? 1e-3 : 0.0;
    in.specific_force[0] = force * std::sin(1.3 * t);
    in.specific_force[1] = force * std::cos(0.7 * t);
    in.specific_force[2] = 9.81 + 0.5 * force * std::sin(2.9 * t);
    in.angular_velocity[0] = rate * std::sin(1.7 * t);
    in.angular_velocity[1] = rate * std::cos(2.3 * t);
    in.angular_velocity[2] = rate * std::sin(0.5 * t);
    return in;
}

int run(stewart_model *model, const char *what, int steps, double force, double rate,
        double lookahead) {
    stewart_cueing_options o;
    stewart_cueing_options_default(&o);
    o.limiter_lookahead = lookahead;
    char message[STEWART_MESSAGE_SIZE];
    stewart_cueing *c = stewart_cueing_create(model, &o, message, sizeof message);
    if (!c) {
        std::fprintf(stderr, "bench-cueing: %s\n", message);
        return 1;
    }
    std::vector<double> us;
    us.reserve(steps);
    int limited = 0;
    for (int k = 0; k < steps; ++k) {
        const stewart_cueing_input in = vehicle(k, force, rate);
        stewart_cueing_output out;
        const auto start = bench::Clock::now();
        const stewart_status s = stewart_cueing_step(c, &in, &out);
        us.push_back(1e-3 * bench::ns_since(start));
        if (s != STEWART_OK) {
            std::fprintf(stderr, "bench-cueing: step %d: %s\n", k, stewart_cueing_message(c));
            stewart_cueing_free(c);
            return 1;
        }
        limited += out.limited;
    }
    std::printf("%-34s median %7.3f us  p99 %7.3f us  max %8.3f us  (%d steps, limited %.0f%%)\n",
                what, bench::percentile(us, 0.5), bench::percentile(us, 0.99),
                bench::percentile(us, 1.0), steps, 100.0 * limited / steps);
    stewart_cueing_free(c);
    return 0;
}

}  // namespace

int main(int argc, char **argv) {
    const int steps = argc > 1 ? std::max(1, std::atoi(argv[1])) : 20000;
    stewart_model *model = bench::make_model("bench-cueing");
    if (!model) return 1;
    stewart_cueing_options o;
    stewart_cueing_options_default(&o);
    int failed = run(model, "gentle, lookahead 0.5 s (default)", steps, 0.5, 0.05, 0.5);
    failed |= run(model, "gentle, no lookahead", steps, 0.5, 0.05, 0.0);
    failed |= run(model, "violent (2 g, 200 deg/s)", steps, 2 * 9.81, 200 * M_PI / 180, 0.5);
    stewart_params limited = *stewart_model_params(model);
    for (int k = 0; k < STEWART_LEGS; ++k)
        limited.leg_speed_max[k] = 0.3, limited.leg_accel_max[k] = 3.0;
    stewart_model *legs = bench::make_model("bench-cueing", &limited);
    if (!legs) return 1;
    failed |= run(legs, "leg limits, gentle, lookahead 0.5 s", steps, 0.5, 0.05, 0.5);
    failed |= run(legs, "leg limits, violent", steps, 2 * 9.81, 200 * M_PI / 180, 0.5);
    stewart_model_free(legs);
    stewart_model_free(model);
    return failed;
}
