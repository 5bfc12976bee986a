/* The trajectory file (trajectory.h): reading it at initialisation, and the quintic Hermite
 * between its rows. */
#define _POSIX_C_SOURCE 200809L /* getline, newlocale, uselocale */
#include "trajectory.h"

#include <errno.h>
#include <locale.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "logging.h"

static const char *const kColumns[TRAJECTORY_COLUMNS] = {
    "t",      "x",      "y",         "z",          "roll",      "pitch",   "yaw",
    "x_dot",  "y_dot",  "z_dot",     "roll_dot",   "pitch_dot", "yaw_dot", "x_ddot",
    "y_ddot", "z_ddot", "roll_ddot", "pitch_ddot", "yaw_ddot"};

enum { MAX_FIELDS = 256 };

/* What a read keeps while it goes: the file's name for messages, the header's column of each
 * value, the rows so far. */
typedef struct reader {
    fmu_instance *inst;
    const char *path;
    int column_of[TRAJECTORY_COLUMNS]; /* field index of each value */
    int n_fields;                      /* fields of the header */
    double *rows;
    size_t n, capacity;
} reader;

static fmu_status refuse(reader *r, long line, const char *fmt, const char *a, const char *b) {
    char why[512];
    snprintf(why, sizeof why, fmt, a, b);
    if (line > 0)
        fmu_log(r->inst, FMU_ERROR, LOG_ERROR, "trajectory_file \"%s\", line %ld: %s", r->path,
                line, why);
    else fmu_log(r->inst, FMU_ERROR, LOG_ERROR, "trajectory_file \"%s\": %s", r->path, why);
    return FMU_ERROR;
}

/* Splits a line at commas in place, each field trimmed of blanks; the number of fields, or -1 if
 * more than max. */
static int split(char *line, char *fields[], int max) {
    int n = 0;
    for (char *p = line;; ++p) {
        char *end = p + strcspn(p, ",");
        const int last = *end == '\0';
        *end = '\0';
        while (*p == ' ' || *p == '\t') ++p;
        for (char *q = end; q > p && strchr(" \t\r\n", q[-1]); --q) q[-1] = '\0';
        if (n == max) return -1;
        fields[n++] = p;
        if (last) return n;
        p = end;
    }
}

static int blank(const char *line) {
    line += strspn(line, " \t\r\n");
    return *line == '\0' || *line == '#';
}

static fmu_status read_header(reader *r, char *line, long number) {
    char *fields[MAX_FIELDS];
    r->n_fields = split(line, fields, MAX_FIELDS);
    if (r->n_fields < 0) return refuse(r, number, "the header has more than 256 columns", "", "");
    char missing[256] = "";
    for (int c = 0; c < TRAJECTORY_COLUMNS; ++c) {
        r->column_of[c] = -1;
        for (int f = 0; f < r->n_fields; ++f) {
            if (strcmp(fields[f], kColumns[c])) continue;
            if (r->column_of[c] >= 0)
                return refuse(r, number, "the header names column %s twice", kColumns[c], "");
            r->column_of[c] = f;
        }
        if (r->column_of[c] < 0) {
            strcat(missing, *missing ? ", " : "");
            strcat(missing, kColumns[c]);
        }
    }
    if (*missing)
        return refuse(r, number,
                      "the header has no column %s: give t, x, y, z, roll, pitch, yaw, "
                      "their rates x_dot .. yaw_dot and accelerations x_ddot .. yaw_ddot (the "
                      "table scripts/move.py writes)",
                      missing, "");
    return FMU_OK;
}

/* One field as a decimal number in any locale (the caller has made the C locale current). */
static int parse(const char *text, double *value) {
    if (!*text || strpbrk(text, "xX")) return 0; /* no hexadecimal */
    char *end;
    *value = strtod(text, &end);
    return *end == '\0';
}

static fmu_status read_row(reader *r, char *line, long number) {
    char *fields[MAX_FIELDS];
    const int n = split(line, fields, MAX_FIELDS);
    if (n != r->n_fields) {
        char counts[64];
        snprintf(counts, sizeof counts, "%d fields, the header %d", n < 0 ? MAX_FIELDS : n,
                 r->n_fields);
        return refuse(r, number, "the row has %s", counts, "");
    }
    if (r->n == r->capacity) {
        const size_t capacity = r->capacity ? 2 * r->capacity : 1024;
        double *rows = realloc(r->rows, capacity * TRAJECTORY_COLUMNS * sizeof *rows);
        if (!rows) return refuse(r, number, "out of memory", "", "");
        r->rows = rows, r->capacity = capacity;
    }
    double *row = r->rows + r->n * TRAJECTORY_COLUMNS;
    for (int c = 0; c < TRAJECTORY_COLUMNS; ++c) {
        const char *text = fields[r->column_of[c]];
        if (!parse(text, &row[c]))
            return refuse(r, number, "%s = \"%s\" is not a number", kColumns[c], text);
        if (!isfinite(row[c]))
            return refuse(r, number, "%s = \"%s\" is not finite", kColumns[c], text);
    }
    if (r->n > 0 && !(row[0] > row[-TRAJECTORY_COLUMNS])) {
        char times[96];
        snprintf(times, sizeof times, "%.17g is not after the previous row's %.17g", row[0],
                 row[-TRAJECTORY_COLUMNS]);
        return refuse(r, number, "t = %s: t must increase from row to row", times, "");
    }
    ++r->n;
    return FMU_OK;
}

static const char *open_error(int error) {
    switch (error) {
        case ENOENT: return "there is no such file";
        case EACCES: return "permission denied";
        case EISDIR: return "it is a directory";
        default: return "it cannot be opened";
    }
}

static fmu_status read_lines(reader *r, FILE *file) {
    char *line = NULL;
    size_t size = 0;
    long number = 0;
    int have_header = 0;
    fmu_status s = FMU_OK;
    errno = 0;
    while (s == FMU_OK && getline(&line, &size, file) >= 0) {
        ++number;
        /* a UTF-8 byte order mark (spreadsheets write one) is not part of the first column */
        char *text = number == 1 && !strncmp(line, "\xEF\xBB\xBF", 3) ? line + 3 : line;
        if (blank(text)) continue;
        s = have_header ? read_row(r, text, number) : read_header(r, text, number);
        have_header = 1;
    }
    if (s == FMU_OK && ferror(file))
        s = refuse(r, number + 1, "cannot be read: %s",
                   errno == EISDIR ? "it is a directory" : "a read error", "");
    free(line);
    if (s == FMU_OK && !have_header)
        s = refuse(r, 0, "the file is empty: give a header and at least one row", "", "");
    else if (s == FMU_OK && r->n == 0)
        s = refuse(r, 0, "the file has a header but no rows", "", "");
    return s;
}

fmu_status trajectory_read(fmu_instance *inst, const char *path, double **rows, size_t *n) {
    reader r = {.inst = inst, .path = path};
    FILE *file = fopen(path, "r");
    if (!file) return refuse(&r, 0, "cannot be read: %s", open_error(errno), "");
    locale_t c_locale = newlocale(LC_NUMERIC_MASK, "C", (locale_t)0);
    if (c_locale == (locale_t)0) {
        fclose(file);
        return refuse(&r, 0, "cannot be read: the C locale is not available", "", "");
    }
    const locale_t before = uselocale(c_locale); /* this thread only */
    const fmu_status s = read_lines(&r, file);
    uselocale(before);
    freelocale(c_locale);
    fclose(file);
    if (s != FMU_OK) {
        free(r.rows);
        return s;
    }
    *rows = r.rows;
    *n = r.n;
    return FMU_OK;
}

/* The quintic Hermite on [t0, t0 + h] through (p, v, a) at both ends (a[0] at t0, a[1] at the
 * end), at s = (t - t0) / h in (0, 1): its value and first two derivatives in time. */
static void hermite(const double p[2], const double v[2], const double a[2], double h, double s,
                    double out[3]) {
    const double d = p[1] - p[0], hv0 = h * v[0], hv1 = h * v[1];
    const double ha0 = h * h * a[0], ha1 = h * h * a[1];
    const double c3 = 10 * d - 6 * hv0 - 4 * hv1 - 1.5 * ha0 + 0.5 * ha1;
    const double c4 = -15 * d + 8 * hv0 + 7 * hv1 + 1.5 * ha0 - ha1;
    const double c5 = 6 * d - 3 * hv0 - 3 * hv1 - 0.5 * ha0 + 0.5 * ha1;
    out[0] = p[0] + s * (hv0 + s * (0.5 * ha0 + s * (c3 + s * (c4 + s * c5))));
    out[1] = v[0] + s * (h * a[0] + s * (3 * c3 + s * (4 * c4 + s * 5 * c5)) / h);
    out[2] = a[0] + s * (6 * c3 + s * (12 * c4 + s * 20 * c5)) / (h * h);
}

static void copy_row(const double *row, double out[3][6]) {
    for (int d = 0; d < 3; ++d)
        for (int i = 0; i < 6; ++i) out[d][i] = row[1 + 6 * d + i];
}

/* Times this close past the last row (relative) still are its: a master's t = n h may miss it
 * by rounding. */
#define END_SLACK 1e-9

trajectory_where trajectory_at(const double *rows, size_t n, double t, double out[3][6]) {
    const double *last = rows + (n - 1) * TRAJECTORY_COLUMNS;
    if (t < rows[0]) return TRAJECTORY_BEFORE;
    if (t >= last[0]) {
        copy_row(last, out);
        if (t - last[0] <= END_SLACK * fmax(1.0, fabs(last[0]))) return TRAJECTORY_ON;
        for (int c = 7; c < 13; ++c) /* the rates */
            if (last[c] != 0.0) return TRAJECTORY_PAST;
        for (int i = 0; i < 6; ++i) out[1][i] = out[2][i] = 0.0; /* held at rest */
        return TRAJECTORY_ON;
    }
    size_t lo = 0, hi = n - 1; /* rows[lo].t <= t < rows[hi].t */
    while (hi - lo > 1) {
        const size_t mid = lo + (hi - lo) / 2;
        if (rows[mid * TRAJECTORY_COLUMNS] <= t) lo = mid;
        else hi = mid;
    }
    const double *r0 = rows + lo * TRAJECTORY_COLUMNS, *r1 = r0 + TRAJECTORY_COLUMNS;
    if (t == r0[0]) {
        copy_row(r0, out);
        return TRAJECTORY_ON;
    }
    const double h = r1[0] - r0[0], s = (t - r0[0]) / h;
    for (int i = 0; i < 6; ++i) {
        const double p[2] = {r0[1 + i], r1[1 + i]}, v[2] = {r0[7 + i], r1[7 + i]};
        const double a[2] = {r0[13 + i], r1[13 + i]};
        double value[3];
        hermite(p, v, a, h, s, value);
        for (int d = 0; d < 3; ++d) out[d][i] = value[d];
    }
    return TRAJECTORY_ON;
}
