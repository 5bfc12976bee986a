// What every direction's create function starts with: the model and options given and the
// options within their table's ranges, then the object allocated; and what its copy starts
// with. Each refusal leaves its message.
#pragma once

#include <new>

#include "stewart/stewart.h"
#include "util/message.hpp"

namespace stewart {

// True when model and options are given and check (the direction's stewart_*_options_check)
// takes the options; otherwise false with msg naming the cause.
template <class Options>
bool create_arguments_ok(const stewart_model *model, const Options *options,
                         stewart_status (*check)(const Options *, char *, size_t), char *msg,
                         size_t size) {
    if (!model || !options) {
        set_message(msg, size, STEWART_ERR_ARGUMENT, "%s is NULL", model ? "options" : "model");
        return false;
    }
    return check(options, msg, size) == STEWART_OK;
}

// The checks a copy starts with: dst and src given and made for the same model. STEWART_OK, or
// the status with dst's message naming the cause ("the <what> were made for different models").
template <class T>
stewart_status copy_arguments_ok(T *dst, const T *src, const char *what) {
    if (!dst) return STEWART_ERR_ARGUMENT;
    if (!src)
        return set_message(dst->message, sizeof dst->message, STEWART_ERR_ARGUMENT, "src is NULL");
    if (dst->model != src->model)
        return set_message(dst->message, sizeof dst->message, STEWART_ERR_ARGUMENT,
                           "the %s were made for different models", what);
    return STEWART_OK;
}

// A new T, or nullptr with msg "out of memory creating the <what>".
template <class T>
T *new_object(const char *what, char *msg, size_t size) {
    T *object = new (std::nothrow) T;
    if (!object) set_message(msg, size, STEWART_ERR_MEMORY, "out of memory creating the %s", what);
    return object;
}

}  // namespace stewart
