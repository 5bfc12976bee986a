/* FMU state: snapshots of an instance (its plain values and the model's saved resources), and
 * their serialised form. */
#ifndef STEWART_FMU_STATE_H
#define STEWART_FMU_STATE_H

#include <stddef.h>

#include "instance.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fmu_snapshot fmu_snapshot;
/* Takes a snapshot into *state (a new one if *state is NULL, else reuses it). */
fmu_status fmu_get_state(fmu_instance *inst, fmu_snapshot **state);
/* Restores a snapshot (of this instance or another of the same model); allowed in Error too,
 * the instance then takes the snapshot's mode. */
fmu_status fmu_set_state(fmu_instance *inst, const fmu_snapshot *state);
/* Frees *state and sets it to NULL (NULL is ignored). */
fmu_status fmu_free_state(fmu_instance *inst, fmu_snapshot **state);
/* Bytes of a serialised snapshot. */
fmu_status fmu_serialized_size(fmu_instance *inst, const fmu_snapshot *state, size_t *size);
/* Writes a snapshot into out (size bytes, at least fmu_serialized_size). */
fmu_status fmu_serialize_state(fmu_instance *inst, const fmu_snapshot *state, unsigned char *out,
                               size_t size);
/* Reads a serialised snapshot; every field is checked (the model checks its own) and a state
 * that no instance can have is an Error naming what is wrong. */
fmu_status fmu_deserialize_state(fmu_instance *inst, const unsigned char *in, size_t size,
                                 fmu_snapshot **state);

#ifdef __cplusplus
}
#endif

#endif
