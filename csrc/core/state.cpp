#include "core/state.hpp"

#include "core/assembly.hpp"
#include "core/message.hpp"
#include "core/position_solver.hpp"

#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>

namespace mbs {

State::State(const Mechanism &m, const SolverOptions &kind)
    : mechanism(m), q(m.coordinates), q_dot(m.coordinates), q_ddot(m.coordinates),
      lambda(m.equations), drive(m.drivers), values(m.values()), load_q(m.coordinates),
      load_phi(m.equations), load_drive(m.drivers) {
    place_at_reference(m, q.data());
    linear = make_linear_solver(m, kind.linear);
    if (!linear) {
        std::snprintf(message, sizeof message,
                      "the requested block linear solver does not fit "
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

Counts counts(const State &s) { return {s.q.size(), s.lambda.size(), 3 * s.drive.size()}; }

size_t doubles(const Counts &c) { return 3 * c.q + c.lambda + c.drive + 2; }  // + time, residual

}  // namespace

size_t saved_state_size(const State &s) {
    return sizeof kStateTag + sizeof(Counts) + 2 * sizeof(int32_t) +
           doubles(counts(s)) * sizeof(double);
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

namespace {

// Whether the loaded q (s.load_q) and driver values (s.load_drive) fit the mechanism.
bool fits_mechanism(State &s, bool solved, double recorded_residual, char *msg, size_t size) {
    const Mechanism &m = s.mechanism;
    const double *q = s.load_q.data();
    double largest = 1.0;
    for (size_t b = 0; b < m.bodies.size(); ++b) {
        const Body &body = m.bodies[b];
        const double *qb = body_r(q, b);
        for (int c = 0; c < 3; ++c) largest = std::fmax(largest, std::fabs(qb[c]));
        if (body.fixed) {
            for (int c = 0; c < 7; ++c)
                if (qb[c] != body.q_reference[c])
                    return set_message(msg, size, false,
                                       "body %zu (%s) is fixed, but the state has its coordinate "
                                       "%d at %.17g, not %.17g",
                                       b, body.name.c_str(), c, qb[c], body.q_reference[c]);
            continue;
        }
        if (body.pose_driven) continue;
        const double norm2 = qb[3] * qb[3] + qb[4] * qb[4] + qb[5] * qb[5] + qb[6] * qb[6];
        if (!(std::fabs(norm2 - 1.0) <= kLoadNormalization))
            return set_message(msg, size, false,
                               "the Euler parameters of body %zu (%s) have norm^2 %.17g in the "
                               "state: they must be unit",
                               b, body.name.c_str(), norm2);
    }
    if (!solved) return true;  // q is only the next solve's initial guess
    assemble_residual(m, q, s.load_drive.data(), s.load_phi.data());
    double residual = 0;
    for (double r : s.load_phi)
        residual = std::isfinite(r) ? std::fmax(residual, std::fabs(r)) : INFINITY;
    const double allowed = 2.0 * recorded_residual + 16.0 * DBL_EPSILON * largest;
    if (!(residual <= allowed))
        return set_message(msg, size, false,
                           "the state's constraint residual is %.3g, above the %.3g it records: "
                           "its bodies do not satisfy the joints",
                           residual, recorded_residual);
    return true;
}

}  // namespace

bool load_state(State &s, const unsigned char *in, size_t size, char *msg, size_t msg_size) {
    const Counts expected = counts(s);
    Counts c;
    int32_t flags[2];
    if (size != saved_state_size(s) || std::memcmp(in, kStateTag, sizeof kStateTag) != 0)
        return set_message(msg, msg_size, false,
                           "the bytes (%zu) are not a saved state of this "
                           "model (%zu bytes, tag MBSSTAT1)",
                           size, saved_state_size(s));
    in += sizeof kStateTag;
    std::memcpy(&c, in, sizeof c);
    in += sizeof c;
    if (c.q != expected.q || c.lambda != expected.lambda || c.drive != expected.drive)
        return set_message(msg, msg_size, false,
                           "the saved state is of a mechanism of another shape");
    std::memcpy(flags, in, sizeof flags);
    in += sizeof flags;
    for (size_t i = 0; i < doubles(c); ++i) {
        double x;
        std::memcpy(&x, in + i * sizeof x, sizeof x);
        if (!std::isfinite(x))  // a corrupt state never reaches the solver
            return set_message(msg, msg_size, false,
                               "value %zu of the saved state is %g: every "
                               "value must be finite",
                               i, x);
    }
    if ((flags[0] != 0 && flags[0] != 1) || flags[1] < 0)
        return set_message(msg, msg_size, false, "the saved state's flags (%d, %d) are corrupt",
                           flags[0], flags[1]);
    // q and the driver values into the load workspaces, checked against the mechanism first.
    const unsigned char *q_bytes = in, *drive_bytes = in + (3 * c.q + c.lambda) * sizeof(double);
    std::memcpy(s.load_q.data(), q_bytes, c.q * sizeof(double));
    for (DriverValue &d : s.load_drive) {
        double x[3];
        std::memcpy(x, drive_bytes, sizeof x);
        drive_bytes += sizeof x;
        d = {x[0], x[1], x[2]};
    }
    double tail[2];
    std::memcpy(tail, drive_bytes, sizeof tail);
    if (!fits_mechanism(s, flags[0] == 1, tail[1], msg, msg_size)) return false;

    auto get = [&in](void *p, size_t bytes) {
        std::memcpy(p, in, bytes);
        in += bytes;
    };
    get(s.q.data(), c.q * sizeof(double));
    get(s.q_dot.data(), c.q * sizeof(double));
    get(s.q_ddot.data(), c.q * sizeof(double));
    get(s.lambda.data(), c.lambda * sizeof(double));
    s.drive = s.load_drive;
    s.time = tail[0];
    s.stats.residual = tail[1];
    s.has_history = flags[0] == 1;
    s.stats.iterations = flags[1];
    s.message[0] = '\0';
    s.factor_current = false;
    s.values_current = false;
    return true;
}

void reset(State &s) {
    reset_history(s);
    place_at_reference(s.mechanism, s.q.data());
}

void reset_history(State &s) {
    s.has_history = false;
    s.factor_current = false;
    s.values_current = false;
    s.stats = SolveStats{};
    s.message[0] = '\0';
}

}  // namespace mbs
