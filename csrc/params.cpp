// Parameter defaults (the thesis platform in SI, model.md §2) and their validation.
#include "stewart/stewart.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstring>

#include "util/message.hpp"

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

// A solid cylinder of mass m, radius r, length l, axis along z: principal moments about its centre.
void rod_inertia(double m, double r, double l, double inertia[3]) {
    inertia[0] = m * (3.0 * r * r + l * l) / 12.0;
    inertia[1] = inertia[0];
    inertia[2] = m * r * r / 2.0;
}

}  // namespace

extern "C" void stewart_params_default(stewart_params *p) {
    if (!p) return;
    *p = stewart_params{};
    static const double beta_deg[STEWART_LEGS] = {0, 30, 120, 150, 240, 270};
    static const double tau_deg[STEWART_LEGS] = {330, 60, 90, 180, 210, 300};
    p->base_radius = 0.5;
    p->platform_radius = 0.5;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        p->base_angle[k] = beta_deg[k] * kDeg;
        p->platform_angle[k] = tau_deg[k] * kDeg;
    }
    p->home_height = 0.5;
    p->gravity[2] = -9.81;

    // Aluminium (2700 kg/m^3) disc, D = 1 m, 0.05 m thick (thesis 4.2.8): m = rho pi R^2 t.
    const double rho = 2700.0, plate_r = 0.5, plate_t = 0.05;
    p->platform_mass = rho * kPi * plate_r * plate_r * plate_t;
    p->platform_inertia[0] = p->platform_mass * plate_r * plate_r / 4.0;
    p->platform_inertia[1] = p->platform_inertia[0];
    p->platform_inertia[2] = p->platform_mass * plate_r * plate_r / 2.0;

    // Each cylinder and piston: aluminium rod, d = 0.015 m, 0.3 m long, centre 0.15 m from its Cardan.
    const double rod_r = 0.0075, rod_l = 0.3;
    const double rod_m = rho * kPi * rod_r * rod_r * rod_l;
    p->cylinder_mass = rod_m;
    p->piston_mass = rod_m;
    rod_inertia(rod_m, rod_r, rod_l, p->cylinder_inertia);
    rod_inertia(rod_m, rod_r, rod_l, p->piston_inertia);
    p->cylinder_com = rod_l / 2.0;
    p->piston_com = rod_l / 2.0;

    // Not in the thesis: a stroke that contains its four manoeuvres (0.53 to 0.60 m) with margin.
    p->stroke_min = 0.40;
    p->stroke_max = 0.70;
}

namespace {

// Field names of stewart_params, in declaration order, for messages about a non-finite value.
struct Field { const char *name; size_t offset; int count; };
#define STEWART_FIELD(f) {#f, offsetof(stewart_params, f), sizeof(stewart_params::f) / sizeof(double)}
const Field kFields[] = {
    STEWART_FIELD(base_radius),     STEWART_FIELD(platform_radius),  STEWART_FIELD(base_angle),
    STEWART_FIELD(platform_angle),  STEWART_FIELD(home_height),      STEWART_FIELD(gravity),
    STEWART_FIELD(platform_mass),   STEWART_FIELD(platform_com),     STEWART_FIELD(platform_inertia),
    STEWART_FIELD(payload_mass),    STEWART_FIELD(payload_com),      STEWART_FIELD(payload_inertia),
    STEWART_FIELD(cylinder_mass),   STEWART_FIELD(cylinder_inertia), STEWART_FIELD(cylinder_com),
    STEWART_FIELD(piston_mass),     STEWART_FIELD(piston_inertia),   STEWART_FIELD(piston_com),
    STEWART_FIELD(stroke_min),      STEWART_FIELD(stroke_max)};
#undef STEWART_FIELD

// "gravity[3]" for the double at byte offset `offset` of stewart_params: array elements counted
// from 1, as in the FMU's model description, scene files and stewart-solve --param.
void field_name(size_t offset, char *out, size_t size) {
    for (const Field &f : kFields)
        if (offset >= f.offset && offset < f.offset + f.count * sizeof(double)) {
            if (f.count == 1)
                std::snprintf(out, size, "%s", f.name);
            else
                std::snprintf(out, size, "%s[%zu]", f.name, (offset - f.offset) / sizeof(double) + 1);
            return;
        }
    std::snprintf(out, size, "?");
}

// Levenshtein distance of the part of `a` before any '[' to `b` (both short names).
size_t edit_distance(const char *a, const char *b) {
    const size_t n = std::strcspn(a, "["), m = std::strlen(b);
    size_t row[64];
    if (n >= 64 || m >= 64) return n > m ? n : m; // no field name is that long: far from all
    for (size_t j = 0; j <= m; ++j) row[j] = j;
    for (size_t i = 1; i <= n; ++i) {
        size_t diagonal = row[0];
        row[0] = i;
        for (size_t j = 1; j <= m; ++j) {
            const size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
            diagonal = up;
        }
    }
    return row[m];
}

// The field named `name` ("payload_mass", "base_angle[2]"): its double, or nullptr.
double *field_by_name(stewart_params *p, const char *name) {
    const char *bracket = std::strchr(name, '[');
    const size_t base = bracket ? static_cast<size_t>(bracket - name) : std::strlen(name);
    for (const Field &f : kFields) {
        if (std::strlen(f.name) != base || std::strncmp(f.name, name, base) != 0) continue;
        int index = 1;
        if (f.count > 1) {
            // "[k]" with k a single digit 1..count (every array has at most 6 elements)
            if (!bracket || bracket[1] < '1' || bracket[1] > '0' + f.count || bracket[2] != ']' ||
                bracket[3] != '\0')
                return nullptr;
            index = bracket[1] - '0';
        } else if (bracket) {
            return nullptr;
        }
        return reinterpret_cast<double *>(reinterpret_cast<char *>(p) + f.offset) + (index - 1);
    }
    return nullptr;
}

// Principal moments of a rigid body must be non-negative and satisfy the triangle inequalities.
bool inertia_ok(const double I[3]) {
    return I[0] >= 0 && I[1] >= 0 && I[2] >= 0 && I[0] + I[1] >= I[2] && I[1] + I[2] >= I[0] &&
           I[0] + I[2] >= I[1];
}

}  // namespace

extern "C" stewart_status stewart_params_check(const stewart_params *p, char *msg, size_t size) {
    using stewart::clear_message;
    using stewart::set_message;
    if (!p) return set_message(msg, size, STEWART_ERR_ARGUMENT, "params is NULL");

    // Every field is a double: one sweep catches NaN and Inf wherever they are.
    const double *all = reinterpret_cast<const double *>(p);
    static_assert(sizeof(stewart_params) % sizeof(double) == 0, "stewart_params holds doubles only");
    for (size_t i = 0; i < sizeof(stewart_params) / sizeof(double); ++i)
        if (!std::isfinite(all[i])) {
            char name[48];
            field_name(i * sizeof(double), name, sizeof name);
            return set_message(msg, size, STEWART_ERR_PARAMETER,
                               "parameter %s is %g: every parameter must be finite", name, all[i]);
        }

    if (!(p->base_radius > 0))
        return set_message(msg, size, STEWART_ERR_PARAMETER, "base_radius = %g m must be > 0",
                           p->base_radius);
    if (!(p->platform_radius > 0))
        return set_message(msg, size, STEWART_ERR_PARAMETER, "platform_radius = %g m must be > 0",
                           p->platform_radius);
    if (!(p->home_height > 0))
        return set_message(msg, size, STEWART_ERR_PARAMETER, "home_height = %g m must be > 0",
                           p->home_height);
    if (!(p->platform_mass > 0))
        return set_message(msg, size, STEWART_ERR_PARAMETER, "platform_mass = %g kg must be > 0",
                           p->platform_mass);
    if (!(p->payload_mass >= 0))
        return set_message(msg, size, STEWART_ERR_PARAMETER, "payload_mass = %g kg must be >= 0",
                           p->payload_mass);
    if (!(p->cylinder_mass >= 0))
        return set_message(msg, size, STEWART_ERR_PARAMETER, "cylinder_mass = %g kg must be >= 0",
                           p->cylinder_mass);
    if (!(p->piston_mass >= 0))
        return set_message(msg, size, STEWART_ERR_PARAMETER, "piston_mass = %g kg must be >= 0",
                           p->piston_mass);

    struct Named { const char *name; const double *I; bool positive; };
    const Named inertias[] = {{"platform_inertia", p->platform_inertia, true},
                              {"payload_inertia", p->payload_inertia, false},
                              {"cylinder_inertia", p->cylinder_inertia, false},
                              {"piston_inertia", p->piston_inertia, false}};
    for (const Named &n : inertias) {
        const bool ok = inertia_ok(n.I) && (!n.positive || (n.I[0] > 0 && n.I[1] > 0 && n.I[2] > 0));
        if (!ok)
            return set_message(msg, size, STEWART_ERR_PARAMETER,
                               "%s = (%g, %g, %g) kg m^2 is not a %s inertia (principal moments "
                               "must be %s and satisfy the triangle inequalities)",
                               n.name, n.I[0], n.I[1], n.I[2],
                               n.positive ? "positive definite" : "valid",
                               n.positive ? "> 0" : ">= 0");
    }

    if (!(p->stroke_min > 0 && p->stroke_max > p->stroke_min))
        return set_message(msg, size, STEWART_ERR_PARAMETER,
                           "stroke limits [%g, %g] m must satisfy 0 < stroke_min < stroke_max",
                           p->stroke_min, p->stroke_max);
    return clear_message(msg, size);
}

extern "C" stewart_status stewart_params_set(stewart_params *p, const char *name, double value,
                                             char *msg, size_t size) {
    using stewart::set_message;
    if (!p || !name) return set_message(msg, size, STEWART_ERR_ARGUMENT, "NULL argument");
    double *field = field_by_name(p, name);
    if (!field) {
        const Field *nearest = &kFields[0];
        size_t best = static_cast<size_t>(-1);
        for (const Field &f : kFields) {
            const size_t d = edit_distance(name, f.name);
            if (d < best) best = d, nearest = &f;
        }
        char suffix[16];
        std::snprintf(suffix, sizeof suffix, "[1..%d]", nearest->count);
        return set_message(msg, size, STEWART_ERR_ARGUMENT,
                           "no parameter is named '%s'; the nearest is %s%s (names as in the FMU's "
                           "model description: arrays take an element counted from 1)",
                           name, nearest->name, nearest->count > 1 ? suffix : "");
    }
    *field = value;
    return stewart::clear_message(msg, size);
}
