// What every direction's create function starts with: the model and options given and the
// options within their table's ranges, then the object allocated; what its copy starts with;
// and what a call on the object starts with. Each refusal leaves its message.
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

// The checks a call on an object starts with: the object given (without it the call has nowhere
// to leave a message) and both its pointer arguments; else the object's message "NULL <names>".
template <class T>
stewart_status call_arguments_ok(T *object, const void *first, const void *second,
                                 const char *names) {
    if (!object) return STEWART_ERR_ARGUMENT;
    if (!first || !second)
        return set_message(object->message, sizeof object->message, STEWART_ERR_ARGUMENT, "NULL %s",
                           names);
    return STEWART_OK;
}

// A new T, or nullptr with msg "out of memory creating the <what>".
template <class T>
T *new_object(const char *what, char *msg, size_t size) {
    T *object = new (std::nothrow) T;
    if (!object) set_message(msg, size, STEWART_ERR_MEMORY, "out of memory creating the %s", what);
    return object;
}

// The start of most creates: the arguments checked (create_arguments_ok), then a new T (new_object)
// with its model and a copy of the options; or nullptr with msg naming the cause.
template <class T, class Options>
T *new_object_for(const stewart_model *model, const Options *options,
                  stewart_status (*check)(const Options *, char *, size_t), const char *what,
                  char *msg, size_t size) {
    if (!create_arguments_ok(model, options, check, msg, size)) return nullptr;
    T *object = new_object<T>(what, msg, size);
    if (!object) return nullptr;
    object->model = model;
    object->options = *options;
    return object;
}

}  // namespace stewart
