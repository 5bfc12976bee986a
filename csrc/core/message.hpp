// Status-plus-message helper: every error leaves a sentence naming the variable and its value.
// A template over the status type, so that each layer (mbs_status here, mbs_status above)
// uses the same helper with its own statuses.
#pragma once

#include <cstdarg>
#include <cstddef>
#include <cstdio>

#include "mbs/mbs.h"

namespace mbs {

// Formats into msg (if any room) and returns status, so callers can `return set_message(...)`.
template <class Status>
Status set_message(char *msg, size_t size, Status status, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

template <class Status>
Status set_message(char *msg, size_t size, Status status, const char *fmt, ...) {
    if (msg && size > 0) {
        va_list args;
        va_start(args, fmt);
        std::vsnprintf(msg, size, fmt, args);
        va_end(args);
    }
    return status;
}

// Empties msg and returns `ok`.
template <class Status>
Status clear_message(char *msg, size_t size, Status ok) {
    if (msg && size > 0) msg[0] = '\0';
    return ok;
}

}  // namespace mbs
