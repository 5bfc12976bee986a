/*
 * The check a user runs first on a new platform file (docs/geometry.md, "Check your machine"):
 * the home pose against every limit, the axis ranges it leaves, and hints in words where the
 * numbers look like an entry mistake (units, swapped legs, a frame).
 *
 *   stewart_check_home(model, &options, &report, message, size)   the numbers
 *   stewart_check_text(&report, text, size)                      the same as text to print
 *
 * `stewart-solve --check FILE.json` prints the text and exits 1 when home is not a valid pose;
 * Python's Platform.check() returns the report. Lengths [m], angles [rad] in the struct; the text
 * gives them in m and degrees, or in the units asked (stewart_check_text_in: the file's).
 */
#ifndef STEWART_STEWART_CHECK_H
#define STEWART_STEWART_CHECK_H

#include <stddef.h>

#include "stewart/stewart.h"
#include "stewart/stewart_limits.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Hints: bits of stewart_check_report.hints. */
#define STEWART_CHECK_UNITS 1        /* the legs' lengths do not fit the strokes or the joints */
#define STEWART_CHECK_SWAPPED_LEGS 2 /* two legs cross each other (seen along the base's z) */
#define STEWART_CHECK_FRAME 4        /* the platform joints look given in another frame */

/* What the check of a model's home pose finds. */
typedef struct stewart_check_report {
    double home[6];       /* the home pose as poses are given (the tool in the user frame) */
    double length[6];     /* each leg's joint-to-joint length at home [m] */
    double stroke_min[6]; /* each leg's stroke [m] */
    double stroke_max[6];
    double joint_spread;          /* the largest distance between two joints of one plate [m] */
    stewart_limits_output limits; /* the limit check at home */
    stewart_axis_ranges ranges;   /* each axis' range from home, the other five held */
    int crossing[2];              /* the first two legs that cross (1..6), else 0, 0 */
    int hints;                    /* STEWART_CHECK_* bits */
    int valid;                    /* 1: home is within every limit; 0: it is not */
} stewart_check_report;

/* Checks model's home pose with the limits of options (NULL: stewart_limits_options_default).
 * STEWART_ERR_ARGUMENT for a NULL model or report, STEWART_ERR_PARAMETER for a bad option,
 * STEWART_ERR_MEMORY; the message says which. An invalid home is not an error: report->valid. */
stewart_status stewart_check_home(const stewart_model *model, const stewart_limits_options *options,
                                  stewart_check_report *report, char *message, size_t size);

/* The report as lines of text (each leg against its stroke, the margins, the axis ranges, the
 * verdict and a sentence per hint), NUL-terminated in text (cut to size); returns the length the
 * whole text needs, without the NUL. */
size_t stewart_check_text(const stewart_check_report *report, char *text, size_t size);

/* stewart_check_text with the lengths (legs, strokes, clearances, x y z) in length_unit and the
 * angles (joint angles, roll pitch yaw) in angle_unit: unit names of stewart_unit_per_si
 * ("mm", "in", "deg", "urad"; NULL or "": m and deg, as stewart_check_text), e.g. the platform
 * file's (stewart_platform_file_units). 0 and text "" for a name that is not a unit of its kind. */
size_t stewart_check_text_in(const stewart_check_report *report, const char *length_unit,
                             const char *angle_unit, char *text, size_t size);

#ifdef __cplusplus
}
#endif

#endif /* STEWART_STEWART_CHECK_H */
