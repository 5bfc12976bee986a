// stewart_full.h: the full level's mechanism.
#include "stewart/stewart_full.h"

#include <cmath>

#include "model.hpp"
#include "util/message.hpp"

extern "C" const mbs_model *stewart_model_mechanism(const stewart_model *m) {
    return m ? m->full.get() : nullptr;
}

extern "C" double stewart_model_length_unit(const stewart_model *m) {
    return m ? m->full_layout.length_unit : 0.0;
}

extern "C" const mbs_data *stewart_inverse_mechanism(const stewart_inverse *d) {
    return d ? d->full.get() : nullptr;
}
