// stewart_batch.h: n poses through stewart_solve with one data block, arrays in and out.
#include "stewart/stewart_batch.h"

#include <cstdio>
#include <cstring>

#include "model.hpp"
#include "util/message.hpp"

namespace {

// Row j of an n x width array, or nullptr for an output the caller skipped.
template <typename T>
T *row(T *array, size_t j, size_t width) {
    return array ? array + j * width : nullptr;
}

void copy_out(double *to, const double *from, int count) {
    if (to) std::memcpy(to, from, sizeof(double) * count);
}

// Writes one row's results (zeros for a failed row) and its status.
void write_row(const stewart_batch_outputs &out, size_t j, const stewart_output &o,
               stewart_status s) {
    copy_out(row(out.length, j, 6), o.length, STEWART_LEGS);
    copy_out(row(out.length_rate, j, 6), o.length_rate, STEWART_LEGS);
    copy_out(row(out.length_accel, j, 6), o.length_accel, STEWART_LEGS);
    copy_out(row(out.force, j, 6), o.force, STEWART_LEGS);
    copy_out(row(out.condition, j, 1), &o.condition, 1);
    copy_out(row(out.residual, j, 1), &o.residual, 1);
    copy_out(row(out.base_force, j, 3), o.base_force, 3);
    copy_out(row(out.base_torque, j, 3), o.base_torque, 3);
    if (out.iterations) out.iterations[j] = o.iterations;
    if (out.warnings) out.warnings[j] = o.warnings;
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

}  // namespace

extern "C" stewart_status stewart_solve_batch(const stewart_model *m, stewart_data *d,
                                              const stewart_options *o, size_t n, const double *q,
                                              const double *q_dot, const double *q_ddot,
                                              const stewart_batch_outputs *out,
                                              stewart_batch_messages *messages,
                                              size_t *first_failed) {
    if (first_failed) *first_failed = n;
    if (messages) messages->count = 0;
    if (!m || !d || !o || !out || !out->status || (n > 0 && !q)) {
        if (d) stewart::set_message(d->message, sizeof d->message, STEWART_ERR_ARGUMENT,
                                    "NULL argument to stewart_solve_batch");
        return STEWART_ERR_ARGUMENT;
    }
    stewart_status first = stewart_options_check(o, d->message, sizeof d->message);
    if (first != STEWART_OK) return first;

    // The first failure's message is kept here while later rows overwrite d->message.
    char first_message[STEWART_MESSAGE_SIZE] = "";
    stewart_pose pose{};
    for (size_t j = 0; j < n; ++j) {
        std::memcpy(pose.q, q + 6 * j, sizeof pose.q);
        if (q_dot) std::memcpy(pose.q_dot, q_dot + 6 * j, sizeof pose.q_dot);
        if (q_ddot) std::memcpy(pose.q_ddot, q_ddot + 6 * j, sizeof pose.q_ddot);
        stewart_output o_j;  // written whole by a successful solve, zeroed on failure
        const stewart_status s = stewart_solve(m, d, o, &pose, &o_j);
        if (s != STEWART_OK) {
            o_j = stewart_output{};
            keep_message(messages, j, d->message);
            if (first == STEWART_OK) {
                first = s;
                if (first_failed) *first_failed = j;
                std::memcpy(first_message, d->message, sizeof first_message);
            }
        }
        write_row(*out, j, o_j, s);
    }
    std::memcpy(d->message, first_message, sizeof first_message);
    return first;
}
