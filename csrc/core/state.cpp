#include "core/state.hpp"

#include "core/position_solver.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>

namespace mbs {

State::State(const Mechanism &m, const SolverOptions &kind)
    : mechanism(m), q(m.coordinates), q_dot(m.coordinates), q_ddot(m.coordinates),
      lambda(m.equations), drive(m.drivers), values(m.values()), rhs(m.equations),
      force(m.coordinates) {
    for (size_t b = 0; b < m.bodies.size(); ++b)
        for (int c = 0; c < 7; ++c) q[7 * b + c] = m.bodies[b].q_reference[c];
    linear = make_linear_solver(m, kind.linear);
    if (!linear) {
        std::snprintf(message, sizeof message, "the requested block linear solver does not fit "
                      "this mechanism's structure");
        return;
    }
    newton_options = kind;
    newton = std::make_unique<PositionSolver>(*this, kind);
    if (!newton->ok()) newton.reset();
}

State::~State() = default;

void copy_state(State &dst, const State &src) {
    dst.q = src.q;
    dst.q_dot = src.q_dot;
    dst.q_ddot = src.q_ddot;
    dst.lambda = src.lambda;
    dst.drive = src.drive;
    dst.time = src.time;
    dst.has_history = src.has_history;
    dst.stats = src.stats;
    std::copy(src.message, src.message + sizeof src.message, dst.message);
    dst.factor_current = false;
    dst.values_current = false;
}

namespace {

constexpr unsigned char kStateTag[8] = {'M', 'B', 'S', 'S', 'T', 'A', 'T', '1'};

// The saved vectors, in order; drive values count as three doubles each.
struct Counts {
    uint64_t q, lambda, drive;
};

Counts counts(const State &s) {
    return {s.q.size(), s.lambda.size(), 3 * s.drive.size()};
}

size_t doubles(const Counts &c) { return 3 * c.q + c.lambda + c.drive + 2; }  // + time, residual

}  // namespace

size_t saved_state_size(const State &s) {
    return sizeof kStateTag + sizeof(Counts) + 2 * sizeof(int32_t) + doubles(counts(s)) * sizeof(double);
}

void save_state(const State &s, unsigned char *out) {
    const Counts c = counts(s);
    auto put = [&out](const void *p, size_t n) {
        std::memcpy(out, p, n);
        out += n;
    };
    put(kStateTag, sizeof kStateTag);
    put(&c, sizeof c);
    const int32_t flags[2] = {s.has_history ? 1 : 0, s.stats.iterations};
    put(flags, sizeof flags);
    put(s.q.data(), c.q * sizeof(double));
    put(s.q_dot.data(), c.q * sizeof(double));
    put(s.q_ddot.data(), c.q * sizeof(double));
    put(s.lambda.data(), c.lambda * sizeof(double));
    for (const DriverValue &d : s.drive) {
        const double v[3] = {d.value, d.rate, d.accel};
        put(v, sizeof v);
    }
    const double tail[2] = {s.time, s.stats.residual};
    put(tail, sizeof tail);
}

bool load_state(State &s, const unsigned char *in, size_t size) {
    const Counts expected = counts(s);
    Counts c;
    int32_t flags[2];
    if (size != saved_state_size(s) || std::memcmp(in, kStateTag, sizeof kStateTag) != 0) return false;
    in += sizeof kStateTag;
    std::memcpy(&c, in, sizeof c);
    in += sizeof c;
    if (c.q != expected.q || c.lambda != expected.lambda || c.drive != expected.drive) return false;
    std::memcpy(flags, in, sizeof flags);
    in += sizeof flags;
    for (size_t i = 0; i < doubles(c); ++i) {
        double x;
        std::memcpy(&x, in + i * sizeof x, sizeof x);
        if (!std::isfinite(x)) return false;  // a corrupt state never reaches the solver
    }
    if ((flags[0] != 0 && flags[0] != 1) || flags[1] < 0) return false;
    auto get = [&in](void *p, size_t bytes) {
        std::memcpy(p, in, bytes);
        in += bytes;
    };
    get(s.q.data(), c.q * sizeof(double));
    get(s.q_dot.data(), c.q * sizeof(double));
    get(s.q_ddot.data(), c.q * sizeof(double));
    get(s.lambda.data(), c.lambda * sizeof(double));
    for (DriverValue &d : s.drive) {
        double x[3];
        get(x, sizeof x);
        d = {x[0], x[1], x[2]};
    }
    double tail[2];
    get(tail, sizeof tail);
    s.time = tail[0];
    s.stats.residual = tail[1];
    s.has_history = flags[0] == 1;
    s.stats.iterations = flags[1];
    s.message[0] = '\0';
    s.factor_current = false;
    s.values_current = false;
    return true;
}

void reset_history(State &s) {
    s.has_history = false;
    s.factor_current = false;
    s.values_current = false;
    s.stats = SolveStats{};
    s.message[0] = '\0';
}

}  // namespace mbs
