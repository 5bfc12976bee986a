// Status-plus-message helper of the platform library: the core's (core/message.hpp, published in
// core/published.hpp) with stewart_status, and the mapping of the core's statuses onto the
// platform's.
#pragma once

#include "core/published.hpp"
#include "stewart/stewart.h"

namespace stewart {

using mbs::set_message;

inline stewart_status clear_message(char *msg, size_t size) {
    return mbs::clear_message(msg, size, STEWART_OK);
}

// The platform's status of the same meaning as a core status.
inline stewart_status from_mbs(mbs_status s) {
    switch (s) {
        case MBS_OK: return STEWART_OK;
        case MBS_ERR_ARGUMENT: return STEWART_ERR_ARGUMENT;
        case MBS_ERR_PARAMETER: return STEWART_ERR_PARAMETER;
        case MBS_ERR_SINGULAR: return STEWART_ERR_SINGULAR;
        case MBS_ERR_NOT_CONVERGED: return STEWART_ERR_NOT_CONVERGED;
        case MBS_ERR_MEMORY: return STEWART_ERR_MEMORY;
    }
    return STEWART_ERR_ARGUMENT;
}

static_assert(MBS_MESSAGE_SIZE <= STEWART_MESSAGE_SIZE, "a core message fits a platform message");

}  // namespace stewart
