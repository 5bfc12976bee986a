/*
 * Platform files (docs/geometry.md): a JSON object of parameter names to values, the names of
 * the parameter table (stewart/stewart_table.h), so that a file is also an FMU parameter set:
 *
 *     {"description": "...", "geometry": 1, "base_joint": [x1, y1, z1, ..., z6], "stroke_min": 0.4}
 *
 * A parameter of one element takes a number; an array a list of all its elements (or, for one
 * element, its own name, "gravity[3]": 9.81); a per-leg parameter that was a scalar
 * (stroke_min, stroke_max) also one number for all legs. "description" (a string) is the only
 * other field. The reader is strict: UTF-8 JSON without duplicate names, numbers only where the
 * table has numbers; a file that gives base_joint or platform_joint gives geometry 1 and both.
 */
#ifndef STEWART_STEWART_PLATFORM_FILE_H
#define STEWART_STEWART_PLATFORM_FILE_H

#include <stddef.h>

#include "stewart/stewart.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Sets the parameters the text (length bytes) gives, each checked against the table, in params:
 * STEWART_OK, or STEWART_ERR_PARAMETER with params unchanged and a message giving the line and
 * column and naming the field and its value. Cross-field checks are stewart_params_check's (at
 * model creation). given, if not NULL, has stewart_param_count() entries: set to 1 for each
 * parameter the file gives (whole or in part), else 0. */
stewart_status stewart_params_read_json(stewart_params *params, const char *text, size_t length,
                                        unsigned char *given, char *message, size_t size);

#ifdef __cplusplus
}
#endif

#endif /* STEWART_STEWART_PLATFORM_FILE_H */
