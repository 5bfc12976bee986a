// stewart_batch.h: n rows through stewart_inverse_solve (at the kinematic and massless levels
// four rows at a time on the vector units, closed_form_quad.hpp), stewart_forward_solve (one
// solver object) or stewart_plant_step (one plant), arrays in and out.
#include "stewart/stewart_batch.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "batch_paths.hpp"
#include "drives/drive_outputs.hpp"
#include "forward/forward_object.hpp"
#include "model.hpp"
#include "util/columns.hpp"
#include "util/message.hpp"

namespace {

// Blocks of four rows the kernel runs before their drive columns (about 40 kB of outputs).
constexpr size_t kDriveChunkBlocks = 16;

using stewart::put_row;

// Every column of the output tables is a member of the output struct, of its type and count,
// and together they are the whole struct: a struct laid out from the table has its size (a field
// missing from a table is caught here).
#define MIRROR_COLUMN(name, member, count, type, unit, description) type name[count];
#define INVERSE_COLUMN(name, member, count, type, unit, description)                \
    static_assert(sizeof(stewart_inverse_output::member) == (count) * sizeof(type), \
                  #name ": count and type as in stewart_inverse_output");
#define FORWARD_COLUMN(name, member, count, type, unit, description)                \
    static_assert(sizeof(stewart_forward_output::member) == (count) * sizeof(type), \
                  #name ": count and type as in stewart_forward_output");
#define PLANT_COLUMN(name, member, count, type, unit, description)                \
    static_assert(sizeof(stewart_plant_output::member) == (count) * sizeof(type), \
                  #name ": count and type as in stewart_plant_output");
#define PLANT_STEP_COLUMN(name, member, count, type, unit, description)               \
    static_assert(sizeof(stewart_plant_statistics::member) == (count) * sizeof(type), \
                  #name ": count and type as in stewart_plant_statistics");
struct InverseMirror {
    STEWART_INVERSE_OUTPUT_TABLE(MIRROR_COLUMN)
};
struct ForwardMirror {
    STEWART_FORWARD_OUTPUT_TABLE(MIRROR_COLUMN)
};
STEWART_INVERSE_OUTPUT_TABLE(INVERSE_COLUMN)
STEWART_FORWARD_OUTPUT_TABLE(FORWARD_COLUMN)
// (the plant's tables are a choice of its structs' fields: time and accelerations are left out)
STEWART_PLANT_OUTPUT_TABLE(PLANT_COLUMN)
STEWART_PLANT_STEP_TABLE(PLANT_STEP_COLUMN)
static_assert(sizeof(InverseMirror) == sizeof(stewart_inverse_output),
              "STEWART_INVERSE_OUTPUT_TABLE lists every field of stewart_inverse_output");
static_assert(sizeof(ForwardMirror) == sizeof(stewart_forward_output),
              "STEWART_FORWARD_OUTPUT_TABLE lists every field of stewart_forward_output");
#undef INVERSE_COLUMN
#undef FORWARD_COLUMN
#undef PLANT_COLUMN
#undef PLANT_STEP_COLUMN
#undef MIRROR_COLUMN

#define PUT_COLUMN(name, member, count, type, unit, description) put_row(out.name, j, o.member);

// Writes one row's results (zeros for a failed row) and its status.
void write_row(const stewart_inverse_batch_outputs &out, size_t j, const stewart_inverse_output &o,
               stewart_status s) {
    STEWART_INVERSE_OUTPUT_TABLE(PUT_COLUMN)
    out.status[j] = s;
}

void keep_message(stewart_batch_messages *messages, size_t j, const char *text) {
    if (!messages || messages->count >= messages->capacity || !messages->rows || !messages->text)
        return;
    messages->rows[messages->count] = j;
    std::snprintf(messages->text + messages->count * STEWART_MESSAGE_SIZE, STEWART_MESSAGE_SIZE,
                  "%s", text);
    ++messages->count;
}

// The bookkeeping of a batch's failing rows: every message (as many as kept), the first status,
// its row and its message (kept aside while later rows overwrite the solver's message).
struct FailureLog {
    stewart_batch_messages *messages;
    size_t *first_failed;
    stewart_status first = STEWART_OK;
    char first_message[STEWART_MESSAGE_SIZE] = "";

    FailureLog(stewart_batch_messages *m, size_t *f, size_t n) : messages(m), first_failed(f) {
        if (first_failed) *first_failed = n;
        if (messages) messages->count = 0;
    }
    void record(size_t j, stewart_status s, const char *text) {
        keep_message(messages, j, text);
        if (first != STEWART_OK) return;
        first = s;
        if (first_failed) *first_failed = j;
        std::snprintf(first_message, sizeof first_message, "%s", text);
    }
};

// Writes one forward row's results (zeros for a failed row, but a row on another assembly mode
// keeps its warnings, branch and stroke legs).
void write_forward_row(const stewart_forward_batch_outputs &out, size_t j,
                       const stewart_forward_output &r, stewart_status s) {
    stewart_forward_output o{};
    if (s == STEWART_OK) {
        o = r;
    } else if (s == STEWART_ERR_OTHER_BRANCH) {
        o.warnings = r.warnings;
        o.branch = r.branch;
        o.stroke_legs = r.stroke_legs;
    }
    STEWART_FORWARD_OUTPUT_TABLE(PUT_COLUMN)
    out.status[j] = s;
}

// Writes one plant row (zeros, status STEWART_BATCH_NOT_RUN, for a row that did not run).
void write_plant_row(const stewart_plant_batch_outputs &out, size_t j,
                     const stewart_plant_output &o, const stewart_plant_statistics &step, int s) {
    STEWART_PLANT_OUTPUT_TABLE(PUT_COLUMN)
#define PUT_STEP_COLUMN(name, member, count, type, unit, description) \
    put_row(out.name, j, step.member);
    STEWART_PLANT_STEP_TABLE(PUT_STEP_COLUMN)
#undef PUT_STEP_COLUMN
    out.status[j] = s;
}

#undef PUT_COLUMN

// The last rows (tail_rows < 4) of an inverse batch through the four-pose kernel: copies of the
// rows, the last repeated, into four-row columns, and tail_rows rows back to out. Returns the
// rows the scalar solve decides (closed_form_quad).
unsigned tail_block(stewart::VectorPath path, const stewart::QuadModel &model, const double *q,
                    const double *q_dot, const double *q_ddot,
                    const stewart_inverse_batch_outputs &out, size_t block, size_t tail_rows) {
    double rows[3][24];
    const double *given[3] = {q, q_dot, q_ddot};
    for (int i = 0; i < 3; ++i)
        for (size_t r = 0; r < 4 && given[i]; ++r) {
            const size_t from = block + (r < tail_rows ? r : tail_rows - 1);
            std::memcpy(rows[i] + 6 * r, given[i] + 6 * from, 6 * sizeof(double));
        }
#define TAIL_COLUMN(name, member, count, type, unit, description) type name[4 * (count)];
    struct {
        STEWART_INVERSE_OUTPUT_TABLE(TAIL_COLUMN)
    } tail{};  // the drive columns, which the kernel leaves, as zeros
#undef TAIL_COLUMN
    int status[4];
    stewart_inverse_batch_outputs tail_out{};
    tail_out.status = status;
#define TAIL_POINT(name, member, count, type, unit, description) \
    if (out.name) tail_out.name = tail.name;
    STEWART_INVERSE_OUTPUT_TABLE(TAIL_POINT)
#undef TAIL_POINT
    const stewart::QuadRows quad = {rows[0], q_dot ? rows[1] : nullptr, q_ddot ? rows[2] : nullptr};
    const unsigned left = stewart::closed_form_quad(path, model, quad, tail_out, 0);
#define TAIL_COPY(name, member, count, type, unit, description) \
    if (out.name)                                               \
        std::memcpy(out.name + block * (count), tail.name, tail_rows * (count) * sizeof(type));
    STEWART_INVERSE_OUTPUT_TABLE(TAIL_COPY)
#undef TAIL_COPY
    std::memcpy(out.status + block, status, tail_rows * sizeof(int));
    return left;
}

}  // namespace

stewart_status stewart::inverse_batch(stewart_inverse *d, size_t n, const double *q,
                                      const double *q_dot, const double *q_ddot,
                                      const stewart_inverse_batch_outputs *out,
                                      stewart_batch_messages *messages, size_t *first_failed,
                                      VectorPath path) {
    FailureLog log(messages, first_failed, n);
    if (!d || !out || !out->status || (n > 0 && !q)) {
        if (d)
            stewart::set_message(d->message, sizeof d->message, STEWART_ERR_ARGUMENT,
                                 "NULL argument to stewart_inverse_batch");
        return STEWART_ERR_ARGUMENT;
    }
    stewart_inverse_input in{};
    stewart_pose &pose = in.pose;
    // Row j by stewart_inverse_solve.
    auto solve_scalar = [&](size_t j) {
        std::memcpy(pose.q, q + 6 * j, sizeof pose.q);
        if (q_dot) std::memcpy(pose.q_dot, q_dot + 6 * j, sizeof pose.q_dot);
        if (q_ddot) std::memcpy(pose.q_ddot, q_ddot + 6 * j, sizeof pose.q_ddot);
        stewart_inverse_output o_j;  // written whole by a successful solve, zeroed on failure
        const stewart_status s = stewart_inverse_solve(d, &in, &o_j);
        if (s != STEWART_OK) {
            o_j = stewart_inverse_output{};
            log.record(j, s, d->message);
        }
        write_row(*out, j, o_j, s);
    };
    const stewart_model *m = d->model;
    // The drive columns come after the kernel from its lengths, rates, accelerations and forces.
    const bool drive_inputs = out->length && out->length_rate && out->length_accel && out->force;
    const bool vector = path != VectorPath::scalar && d->options.fidelity != STEWART_FULL &&
                        m->frames.identity && (!m->drives || drive_inputs);
    if (!vector) {
        for (size_t j = 0; j < n; ++j) solve_scalar(j);
    } else {
        if (!vector_path_available(path)) path = VectorPath::portable;
        const QuadModel model =
            quad_model(m->geometry, m->platform, m->gravity, m->params, d->options);
        // Blocks of four rows in order (a failing row's message keeps its place): the kernel
        // writes blocks in a run until one leaves rows to the scalar solve, which overwrites
        // them. The last block, if short, through four-row copies (its last row repeated), so
        // that a row's numbers do not depend on where a batch starts.
        // The drive columns of rows [from, to) while the kernel's are still in the cache (a
        // row whose drive columns overflow: its solve refuses it with a message).
        auto drive_rows = [&](size_t from, size_t to) {
            if (!m->drives) return batch_drive_zeros(*out, from, to);
            for (size_t j = from; j < to; ++j)
                if (out->status[j] == STEWART_OK && !batch_drive_row(m->drive, m->params, *out, j))
                    solve_scalar(j);
        };
        const size_t whole = n - n % 4;
        const size_t chunk = m->drives ? kDriveChunkBlocks : whole / 4 + 1;
        for (size_t block = 0; block < whole;) {
            const QuadRows rows = {q + 6 * block, q_dot ? q_dot + 6 * block : nullptr,
                                   q_ddot ? q_ddot + 6 * block : nullptr};
            unsigned left;  // rows the scalar solve decides, bit r for row last + r
            const size_t run = closed_form_quad_run(path, model, rows, *out, block,
                                                    std::min(chunk, (whole - block) / 4), left);
            const size_t last = block + 4 * (run - 1);
            for (size_t r = 0; left && r < 4; ++r)
                if (left >> r & 1) solve_scalar(last + r);
            drive_rows(block, block + 4 * run);
            block += 4 * run;
        }
        if (whole < n) {
            const unsigned left = tail_block(path, model, q, q_dot, q_ddot, *out, whole, n - whole);
            for (size_t r = 0; left && r < n - whole; ++r)
                if (left >> r & 1) solve_scalar(whole + r);
            drive_rows(whole, n);
        }
    }
    std::memcpy(d->message, log.first_message, sizeof log.first_message);
    return log.first;
}

extern "C" stewart_status stewart_inverse_batch_current_rates(
    const stewart_model *m, size_t n, const double *t, const stewart_inverse_batch_outputs *out,
    char *msg, size_t size) {
    if (!m || !out || !out->status || (n > 0 && !t) ||
        (m->drives && !(out->current && out->current_rate && out->motor_speed && out->voltage)))
        return stewart::set_message(msg, size, STEWART_ERR_ARGUMENT,
                                    "stewart_inverse_batch_current_rates: a NULL argument or "
                                    "column (current, current_rate, motor_speed, voltage, status)");
    for (size_t j = 0; j < n; ++j)
        if (!std::isfinite(t[j]) || (j > 0 && !(t[j] > t[j - 1])))
            return stewart::set_message(msg, size, STEWART_ERR_ARGUMENT,
                                        "t[%zu] = %.17g s: the times of a trajectory must be "
                                        "finite and increase from row to row",
                                        j, t[j]);
    const size_t bad =
        m->drives ? stewart::trajectory_current_rates(m->drive, m->params, n, t, *out) : n;
    if (bad < n)
        return stewart::set_message(msg, size, STEWART_ERR_ARGUMENT,
                                    "row %zu (t = %.17g s): the currents' rates over t overflow "
                                    "(times too close for the currents' change): give the "
                                    "trajectory's times farther apart",
                                    bad, t[bad]);
    return stewart::clear_message(msg, size);
}

extern "C" stewart_status stewart_inverse_batch_current_rates_from_jerks(
    const stewart_model *m, int fidelity, size_t n, const double *q, const double *q_dot,
    const double *q_ddot, const double *q_dddot, const stewart_inverse_batch_outputs *out,
    char *msg, size_t size) {
    if (!m || !out || !out->status || (n > 0 && !(q && q_dddot)) ||
        (m->drives && !(out->current && out->current_rate && out->motor_speed && out->voltage &&
                        out->force && out->length_rate && out->length_accel)))
        return stewart::set_message(msg, size, STEWART_ERR_ARGUMENT,
                                    "stewart_inverse_batch_current_rates_from_jerks: a NULL "
                                    "argument or column");
    if (!m->drives) return stewart::clear_message(msg, size);
    stewart_linearize_options o;
    stewart_linearize_options_default(&o);
    o.fidelity = fidelity == STEWART_FULL ? STEWART_FULL : STEWART_MASSLESS;
    stewart_linearize *lin = stewart_linearize_create(m, &o, msg, size);
    if (!lin) return STEWART_ERR_MEMORY;
    const stewart_status s =
        stewart::jerk_current_rates(m->drive, m->params, lin, fidelity != STEWART_KINEMATIC, n, q,
                                    q_dot, q_ddot, q_dddot, *out, msg, size);
    stewart_linearize_free(lin);
    return s == STEWART_OK ? stewart::clear_message(msg, size) : s;
}

extern "C" stewart_status stewart_inverse_batch(stewart_inverse *d, size_t n, const double *q,
                                                const double *q_dot, const double *q_ddot,
                                                const stewart_inverse_batch_outputs *out,
                                                stewart_batch_messages *messages,
                                                size_t *first_failed) {
    return stewart::inverse_batch(d, n, q, q_dot, q_ddot, out, messages, first_failed,
                                  stewart::batch_vector_path(d->options.fidelity));
}

namespace {

// The rows of a forward batch: tracked (guesses: row 0's start or NULL) or each on its own
// (cold: stewart_forward_solve_cold; guesses: n x 6 starts or NULL for home).
stewart_status forward_rows(stewart_forward *d, size_t n, const double *time, const double *lengths,
                            const double *rates, const double *accels, const double *guesses,
                            bool cold, const stewart_forward_batch_outputs *out,
                            stewart_batch_messages *messages, size_t *first_failed) {
    FailureLog log(messages, first_failed, n);
    if (!d || !out || !out->status || (n > 0 && !lengths) || (accels && !rates)) {
        if (d)
            stewart::set_message(d->message, sizeof d->message, STEWART_ERR_ARGUMENT,
                                 accels && !rates ? "stewart_forward_batch: accels need rates"
                                                  : "NULL argument to stewart_forward_batch");
        return STEWART_ERR_ARGUMENT;
    }
    stewart_forward_input in{};
    in.derivatives = accels ? 2 : rates ? 1 : 0;
    for (size_t j = 0; j < n; ++j) {
        in.time = time ? time[j] : 0.0;
        std::memcpy(in.lengths.length, lengths + 6 * j, sizeof in.lengths.length);
        if (rates)
            std::memcpy(in.lengths.length_rate, rates + 6 * j, sizeof in.lengths.length_rate);
        if (accels)
            std::memcpy(in.lengths.length_accel, accels + 6 * j, sizeof in.lengths.length_accel);
        in.use_guess = guesses && (cold || j == 0);
        if (in.use_guess) std::memcpy(in.guess, guesses + (cold ? 6 * j : 0), sizeof in.guess);
        stewart_forward_output r{};
        const stewart_status s =
            cold ? stewart_forward_solve_cold(d, &in, &r) : stewart_forward_solve(d, &in, &r);
        if (s != STEWART_OK) log.record(j, s, d->message);
        write_forward_row(*out, j, r, s);
    }
    if (cold) stewart_forward_reset(d);
    std::memcpy(d->message, log.first_message, sizeof log.first_message);
    return log.first;
}

}  // namespace

extern "C" stewart_status stewart_forward_batch(stewart_forward *d, size_t n, const double *time,
                                                const double *lengths, const double *rates,
                                                const double *accels, const double guess[6],
                                                const stewart_forward_batch_outputs *out,
                                                stewart_batch_messages *messages,
                                                size_t *first_failed) {
    return forward_rows(d, n, time, lengths, rates, accels, guess, false, out, messages,
                        first_failed);
}

extern "C" stewart_status stewart_forward_batch_cold(stewart_forward *d, size_t n,
                                                     const double *lengths, const double *rates,
                                                     const double *accels, const double *guesses,
                                                     const stewart_forward_batch_outputs *out,
                                                     stewart_batch_messages *messages,
                                                     size_t *first_failed) {
    return forward_rows(d, n, nullptr, lengths, rates, accels, guesses, true, out, messages,
                        first_failed);
}

extern "C" stewart_status stewart_plant_batch(stewart_plant *plant, size_t n, const double *time,
                                              const double *force, const double start_pose[6],
                                              const double start_rate[6],
                                              const stewart_plant_batch_outputs *out,
                                              stewart_batch_messages *messages,
                                              size_t *first_failed) {
    return stewart_plant_batch_rows(plant, n, 0, n, time, force, start_pose, start_rate, out,
                                    messages, first_failed);
}

extern "C" stewart_status stewart_plant_batch_rows(stewart_plant *plant, size_t n, size_t first,
                                                   size_t stop, const double *time,
                                                   const double *force, const double start_pose[6],
                                                   const double start_rate[6],
                                                   const stewart_plant_batch_outputs *out,
                                                   stewart_batch_messages *messages,
                                                   size_t *first_failed) {
    FailureLog log(messages, first_failed, stop);
    if (!plant || !out || !out->status || (n > 0 && (!time || !force)) || first > stop || stop > n)
        return STEWART_ERR_ARGUMENT;
    const stewart_plant_output none{};
    const stewart_plant_statistics no_steps{};
    size_t j = first;
    stewart_status s = STEWART_OK;
    stewart_plant_output o;
    if (first == 0 && stop > 0) {
        // The start: the plant's own pose and rates where the caller gives none.
        s = stewart_plant_output_get(plant, nullptr, &o);
        if (s == STEWART_OK)
            s = stewart_plant_set_state(plant, time[0], start_pose ? start_pose : o.pose.q,
                                        start_rate ? start_rate : o.pose.q_dot);
        if (s == STEWART_OK) s = stewart_plant_output_get(plant, force, &o);
        if (s == STEWART_OK) write_plant_row(*out, 0, o, no_steps, STEWART_OK), j = 1;
    }
    stewart_plant_input in{};
    for (; j < stop && s == STEWART_OK; ++j) {
        in.h = time[j] - time[j - 1];
        std::memcpy(in.force_start, force + 6 * (j - 1), sizeof in.force_start);
        std::memcpy(in.force_end, force + 6 * j, sizeof in.force_end);
        s = stewart_plant_step(plant, &in, &o);
        if (s != STEWART_OK) break;
        stewart_plant_statistics stats;
        stewart_plant_statistics_get(plant, &stats);
        write_plant_row(*out, j, o, stats, STEWART_OK);
    }
    if (s == STEWART_OK) return s;
    char text[STEWART_MESSAGE_SIZE];
    std::snprintf(text, sizeof text, "row %zu (t = %.17g): %s", j, time[j],
                  stewart_plant_message(plant));
    log.record(j, s, text);
    write_plant_row(*out, j, none, no_steps, s);
    for (size_t k = j + 1; k < n; ++k)
        write_plant_row(*out, k, none, no_steps, STEWART_BATCH_NOT_RUN);
    return s;
}
