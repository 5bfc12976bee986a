// Status-plus-message helper: every error leaves a sentence naming the variable and its value.
#pragma once

#include <cstdarg>
#include <cstddef>
#include <cstdio>

#include "stewart/stewart.h"

namespace stewart {

// Formats into msg (if any room) and returns status, so callers can `return set_message(...)`.
inline stewart_status set_message(char *msg, size_t size, stewart_status status, const char *fmt,
                                  ...) __attribute__((format(printf, 4, 5)));

inline stewart_status set_message(char *msg, size_t size, stewart_status status, const char *fmt,
                                  ...) {
    if (msg && size > 0) {
        va_list args;
        va_start(args, fmt);
        std::vsnprintf(msg, size, fmt, args);
        va_end(args);
    }
    return status;
}

inline stewart_status clear_message(char *msg, size_t size) {
    if (msg && size > 0) msg[0] = '\0';
    return STEWART_OK;
}

}  // namespace stewart
