/*
 * Platform files (docs/geometry.md, section 3): a JSON object of parameter names to values, the
 * names of the parameter table (stewart/stewart_table.h), so that a file is also an FMU parameter
 * set:
 *
 *     {"description": "...", "geometry": 1, "base_joint": [x1, y1, z1, ..., z6], "stroke_min": 0.4}
 *
 * A parameter of one element takes a number; an array a list of all its elements (or, for one
 * element, its own name, "gravity[3]": 9.81); a per-leg parameter that was a scalar
 * (stroke_min, stroke_max) also one number for all legs. A number may be written with its unit
 * ("12.5 mm", "0.36 deg"), and "units": {"length": "mm", "angle": "deg"} gives the unit of every
 * number written without one whose parameter is in m or rad; the values are SI after reading.
 * "stroke_neutral" and "stroke_travel" (per leg, or one number for all) give the strokes as
 * neutral length +- travel instead of stroke_min and stroke_max. "description" (a string) is the
 * only other field. The reader is strict: UTF-8 JSON of at most STEWART_PLATFORM_FILE_MAX_BYTES,
 * every element given at most once whatever the spelling, numbers only where the table has
 * numbers (read the same in every locale); a file that gives base_joint or platform_joint gives
 * geometry 1, and one with geometry 1 gives every coordinate of both.
 */
#ifndef STEWART_STEWART_PLATFORM_FILE_H
#define STEWART_STEWART_PLATFORM_FILE_H

#include <stddef.h>

#include "stewart/stewart.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The largest platform file read (1 MiB; a platform file is a few kB). */
#define STEWART_PLATFORM_FILE_MAX_BYTES 1048576

/* Sets the parameters the text (length bytes) gives, each checked against the table, in params:
 * STEWART_OK, or STEWART_ERR_PARAMETER with params unchanged and a message giving the line and
 * column and naming the field and its value. Cross-field checks are stewart_params_check's (at
 * model creation). given, if not NULL, has stewart_param_count() entries: set to 1 for each
 * parameter the file gives (whole or in part; stroke_min and stroke_max for stroke_neutral and
 * stroke_travel), else 0. Time linear in length. */
stewart_status stewart_params_read_json(stewart_params *params, const char *text, size_t length,
                                        unsigned char *given, char *message, size_t size);

/* stewart_params_read_json of the file at path: a regular file (a directory, FIFO or device is
 * refused at once, without waiting for a writer) of at most STEWART_PLATFORM_FILE_MAX_BYTES. The
 * message does not name the path (the caller does). */
stewart_status stewart_params_read_json_file(stewart_params *params, const char *path,
                                             unsigned char *given, char *message, size_t size);

/* The units a platform file writes its lengths and angles in, to print results in them (the
 * values read are SI whatever they are). Each is a unit name of the list below, or "" when the
 * file states none (then SI). */
typedef struct stewart_file_units {
    char length[8]; /* the file's "units" length; else the one length unit its values written
                       with a unit use ("12.5 mm"), when they all use the same one; else "" */
    char angle[8];  /* the same for angles */
} stewart_file_units;

/* The units of the platform file at path (read as stewart_params_read_json_file reads it; only
 * its "units" and the units of its values are looked at, the parameters are not checked). */
stewart_status stewart_platform_file_units(const char *path, stewart_file_units *units,
                                           char *message, size_t size);

/* The one conversion from SI to a unit a platform file may name (m cm mm um nm in, rad mrad urad
 * deg; um and urad also with the micro sign): sets *per_si to what a value in SI is multiplied
 * by to be in name and returns name's SI unit ("m" or "rad"); NULL (per_si unchanged) for a
 * name that is not one. */
const char *stewart_unit_per_si(const char *name, double *per_si);

#ifdef __cplusplus
}
#endif

#endif /* STEWART_STEWART_PLATFORM_FILE_H */
