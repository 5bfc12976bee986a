// The parameter table (stewart/stewart_table.h) expanded: defaults, per-element checks, lookup
// by name and id, and stewart_params_check's cross-field checks.
#include "stewart/stewart_table.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstring>

#include "kinematics/frames.hpp"
#include "kinematics/joints.hpp"
#include "table/singular_geometry.hpp"
#include "limits/limit_check.hpp"
#include "util/message.hpp"
#include "util/range.hpp"

using stewart::ExactText;
using stewart::set_message;

namespace {

#define STEWART_UNPAREN(...) __VA_ARGS__

// Each parameter's defaults, as an array of its count doubles.
#define DEFAULTS(id, name, count, unit, display, min, min_closed, max, max_closed, defaults, text) \
    constexpr double kDefault_##name[] = {STEWART_UNPAREN defaults};                               \
    static_assert(sizeof kDefault_##name == (count) * sizeof(double),                              \
                  #name ": one default per element");                                              \
    static_assert(sizeof(stewart_params::name) == (count) * sizeof(double),                        \
                  #name ": the table's count is the field's");
STEWART_PARAM_TABLE(DEFAULTS)
#undef DEFAULTS

constexpr bool same_text(const char *a, const char *b) {
    return *a == *b && (*a == '\0' || same_text(a + 1, b + 1));
}
// A pose is marked twice, by its count's name (for the FMU's preprocessor) and its unit (at run
// time): the two agree.
#define POSE_MARKS(id, name, count, unit, ...)                  \
    static_assert(same_text(#count, "STEWART_POSE_ELEMENTS") == \
                      same_text(unit, STEWART_POSE_UNIT),       \
                  #name ": a pose has count STEWART_POSE_ELEMENTS and unit STEWART_POSE_UNIT");
STEWART_PARAM_TABLE(POSE_MARKS)
#undef POSE_MARKS

#define INFO(id, name, count, unit, display, min, min_closed, max, max_closed, defaults, text) \
    {id, #name, count, unit, display, text, min, max, min_closed, max_closed, kDefault_##name},
const stewart_param_info kParams[] = {STEWART_PARAM_TABLE(INFO)};
#undef INFO
constexpr int kParamCount = sizeof kParams / sizeof kParams[0];

#define OFFSET(id, name, ...) offsetof(stewart_params, name),
constexpr size_t kOffsets[] = {STEWART_PARAM_TABLE(OFFSET)};
#undef OFFSET
#define COUNT(id, name, count, ...) count,
constexpr int kCounts[] = {STEWART_PARAM_TABLE(COUNT)};
#undef COUNT

// The table lists every field of stewart_params once, in declaration order, with nothing between.
constexpr bool table_matches_struct() {
    size_t offset = 0;
    for (int i = 0; i < kParamCount; ++i) {
        if (kOffsets[i] != offset) return false;
        offset += kCounts[i] * sizeof(double);
    }
    return offset == sizeof(stewart_params);
}
static_assert(table_matches_struct(),
              "STEWART_PARAM_TABLE must list stewart_params' fields in order");

const char *const kAxis[3] = {"x", "y", "z"};
const char *const kPoseAxis[6] = {"x", "y", "z", "roll", "pitch", "yaw"};

bool is_pose(const stewart_param_info &p) { return !std::strcmp(p.unit, STEWART_POSE_UNIT); }

// Per-leg parameters that a single value (the bare name, e.g. "stroke_min") fills for all six
// legs: the legs of most machines are alike (the strokes were scalars in earlier releases).
const char *const kScalarFills[] = {
    "stroke_min",       "stroke_max",         "screw_lead",         "gear_ratio",
    "rotor_inertia",    "screw_inertia",      "screw_efficiency",   "screw_back_efficiency",
    "torque_constant",  "winding_resistance", "winding_inductance", "coulomb_friction",
    "viscous_friction", "stribeck_friction",  "stribeck_speed",     "end_stop_stiffness",
    "end_stop_damping", "leg_stiffness",      "leg_damping",        "current_max",
    "voltage_max",      "motor_speed_max",    "leg_speed_max",      "leg_accel_max",
    "leg_jerk_max",     "leg_force_max"};

// The element index of "[k]" (k = 1..count, no leading zero, then the end), or -1.
int element_index(const char *bracket, int count) {
    if (bracket[0] != '[' || bracket[1] < '1' || bracket[1] > '9') return -1;
    int k = 0;
    const char *c = bracket + 1;
    for (; *c >= '0' && *c <= '9' && k <= count; ++c) k = 10 * k + (*c - '0');
    if (c[0] != ']' || c[1] != '\0' || k > count) return -1;
    return k - 1;
}

// Levenshtein distance of the part of `a` before any '[' to `b` (both short names).
size_t edit_distance(const char *a, const char *b) {
    const size_t n = std::strcspn(a, "["), m = std::strlen(b);
    size_t row[64];
    if (n >= 64 || m >= 64) return n > m ? n : m;  // no field name is that long: far from all
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

// Bounds on the magnitude of the values that set the machine's size and load, beyond the table's
// ranges: far past any machine, squares and products of these leave the doubles (joints of 1e300
// m square to infinity and read as one point; gravity of 1e308 m/s2 overflows the forces), and
// such a value is nearly always a unit mistake. max: the largest |value|; the lengths' bound
// leaves room for the largest tested scale (a 5 km radius).
struct Magnitude {
    const char *name;
    double max;
};
const Magnitude kMagnitudes[] = {
    {"base_radius", 1e6},    {"platform_radius", 1e6}, {"base_joint", 1e6},
    {"platform_joint", 1e6}, {"home_height", 1e6},     {"gravity", 1e4},
};
// A side's joints closer to its origin than this all (a radius, or the largest |joint|) are a
// unit mistake too: their differences would square to nothing.
constexpr double kSmallestSide = 1e-6;

// Principal moments of a rigid body must satisfy the triangle inequalities (signs are the
// table's per-element ranges).
bool triangle_ok(const double I[3]) {
    return I[0] + I[1] >= I[2] && I[1] + I[2] >= I[0] && I[0] + I[2] >= I[1];
}

// Every element of kMagnitudes' parameters within its bound.
stewart_status check_magnitudes(stewart_params &p, char *msg, size_t size) {
    for (const Magnitude &m : kMagnitudes)
        for (int i = 0; i < kParamCount; ++i) {
            if (std::strcmp(kParams[i].name, m.name)) continue;
            for (int e = 0; e < kParams[i].count; ++e) {
                const double value = *stewart_param_element(&p, i, e);
                if (std::fabs(value) <= m.max) continue;
                char name[48];
                stewart_param_element_name(i, e, name, sizeof name);
                const char *unit = stewart_param_element_unit(i, e);
                return set_message(msg, size, STEWART_ERR_PARAMETER,
                                   "%s = %s %s is beyond any machine: its magnitude must be at "
                                   "most %g %s (check the units)",
                                   name, ExactText(value).c_str(), unit, m.max, unit);
            }
        }
    return STEWART_OK;
}

// Each side's joints reach at least kSmallestSide from its origin (a side whose joints are all
// at the origin is one point, which check_not_singular_everywhere names).
// The largest coordinate, not the norm, whose squares would underflow.
stewart_status check_side_sizes(const stewart_params &p, char *msg, size_t size) {
    const bool joints = p.geometry == 1.0;
    for (int side = 0; side < 2; ++side) {
        double reach = side ? p.platform_radius : p.base_radius;
        if (joints) {
            reach = 0;
            for (double x : side ? p.platform_joint : p.base_joint)
                reach = std::max(reach, std::fabs(x));
        }
        if (reach > 0 && reach < kSmallestSide)
            return set_message(msg, size, STEWART_ERR_PARAMETER,
                               "%s: every %s joint is within %s m of its frame's origin: a "
                               "machine's joints are at least %g m from it (check the units)",
                               joints ? (side ? "platform_joint" : "base_joint")
                                      : (side ? "platform_radius" : "base_radius"),
                               side ? "platform" : "base", ExactText(reach).c_str(), kSmallestSide);
    }
    return STEWART_OK;
}

// The drive parameters across fields (docs/drives.md, "Entering a drive"): each leg with a
// screw has a motor constant; the motor's and screw's parameters only on a leg with a screw
// (elsewhere they would be ignored), friction and end stops too; a Stribeck peak has its speed;
// damping has its spring; no leg compliance (not modelled).
stewart_status check_drive_parameters(const stewart_params &p, char *msg, size_t size) {
    struct Field {
        const char *name;
        const double *value;
        double neutral;
        const char *unit;
    };
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const int leg = k + 1;
        const bool drive = p.screw_lead[k] > 0;
        if (drive && !(p.torque_constant[k] > 0))
            return set_message(msg, size, STEWART_ERR_PARAMETER,
                               "torque_constant[%d] = %s N.m/A: leg %d has a drive (screw_lead[%d] "
                               "= %s m) and its motor needs a torque constant > 0 (the datasheet's "
                               "Kt; a motor not chosen yet: any Kt, then read the torques)",
                               leg, ExactText(p.torque_constant[k]).c_str(), leg, leg,
                               ExactText(p.screw_lead[k]).c_str());
        const Field motor[] = {
            {"gear_ratio", p.gear_ratio, 1, ""},
            {"rotor_inertia", p.rotor_inertia, 0, " kg.m2"},
            {"screw_inertia", p.screw_inertia, 0, " kg.m2"},
            {"screw_efficiency", p.screw_efficiency, 1, ""},
            {"screw_back_efficiency", p.screw_back_efficiency, 1, ""},
            {"torque_constant", p.torque_constant, 0, " N.m/A"},
            {"winding_resistance", p.winding_resistance, 0, " Ohm"},
            {"winding_inductance", p.winding_inductance, 0, " H"},
            {"current_max", p.current_max, 0, " A"},
            {"voltage_max", p.voltage_max, 0, " V"},
            {"motor_speed_max", p.motor_speed_max, 0, " rad/s"},
            // friction and end stops act through the drive (with force input the plant takes
            // the leg's whole axial force as given)
            {"coulomb_friction", p.coulomb_friction, 0, " N"},
            {"viscous_friction", p.viscous_friction, 0, " N.s/m"},
            {"stribeck_friction", p.stribeck_friction, 0, " N"},
            {"stribeck_speed", p.stribeck_speed, 0, " m/s"},
            {"end_stop_stiffness", p.end_stop_stiffness, 0, " N/m"},
            {"end_stop_damping", p.end_stop_damping, 0, " N.s/m"}};
        for (const Field &f : motor)
            if (!drive && f.value[k] != f.neutral)
                return set_message(msg, size, STEWART_ERR_PARAMETER,
                                   "%s[%d] = %s%s, but leg %d has no drive (screw_lead[%d] = 0): "
                                   "give its screw_lead, or leave %s[%d] at %g",
                                   f.name, leg, ExactText(f.value[k]).c_str(), f.unit, leg, leg,
                                   f.name, leg, f.neutral);
        if (p.stribeck_friction[k] > p.coulomb_friction[k] && !(p.stribeck_speed[k] > 0))
            return set_message(msg, size, STEWART_ERR_PARAMETER,
                               "stribeck_speed[%d] = %s m/s: leg %d has a Stribeck peak "
                               "(stribeck_friction[%d] = %s N > coulomb_friction[%d] = %s N), "
                               "which needs the speed over which it falls, > 0",
                               leg, ExactText(p.stribeck_speed[k]).c_str(), leg, leg,
                               ExactText(p.stribeck_friction[k]).c_str(), leg,
                               ExactText(p.coulomb_friction[k]).c_str());
        if (p.leg_stiffness[k] != 0 || p.leg_damping[k] != 0)
            return set_message(msg, size, STEWART_ERR_PARAMETER,
                               "leg_stiffness[%d] = %s N/m, leg_damping[%d] = %s N.s/m: the legs' "
                               "axial compliance is not modelled yet (every leg is rigid); leave "
                               "both at 0",
                               leg, ExactText(p.leg_stiffness[k]).c_str(), leg,
                               ExactText(p.leg_damping[k]).c_str());
        struct Damper {
            const char *name, *spring_name;
            const double *damping, *spring;
        };
        const Damper dampers[] = {
            {"end_stop_damping", "end_stop_stiffness", p.end_stop_damping, p.end_stop_stiffness}};
        for (const Damper &d : dampers)
            if (d.damping[k] > 0 && !(d.spring[k] > 0))
                return set_message(msg, size, STEWART_ERR_PARAMETER,
                                   "%s[%d] = %s N.s/m without a spring (%s[%d] = 0): give the "
                                   "stiffness, or leave the damping at 0",
                                   d.name, leg, ExactText(d.damping[k]).c_str(), d.spring_name,
                                   leg);
    }
    return STEWART_OK;
}

// A drive whose motor angle per leg length 2 pi N / lead or reflected inertia J (2 pi N /
// lead)^2 overflows: every torque and current of that leg would be inf or NaN, which the inverse
// would blame on the pose.
stewart_status check_drive_overflow(const stewart_params &p, char *msg, size_t size) {
    for (int k = 0; k < STEWART_LEGS; ++k) {
        if (!(p.screw_lead[k] > 0)) continue;
        const double N = p.gear_ratio[k], ratio = 2.0 * M_PI * N / p.screw_lead[k];
        const double inertia = p.rotor_inertia[k] + p.screw_inertia[k] / (N * N);
        if (std::isfinite(ratio) && std::isfinite(inertia * ratio * ratio)) continue;
        const int leg = k + 1;
        return set_message(
            msg, size, STEWART_ERR_PARAMETER,
            "screw_lead[%d] = %s m, gear_ratio[%d] = %s: the motor turns %g rad "
            "per metre of leg (2 pi N / lead) and its inertia reflects to %g kg on "
            "the leg, beyond a double; give the lead in metres and the gear as motor "
            "turns per screw turn",
            leg, ExactText(p.screw_lead[k]).c_str(), leg, ExactText(N).c_str(), ratio,
            inertia * ratio * ratio);
    }
    return STEWART_OK;
}

}  // namespace

extern "C" {

int stewart_param_count(void) { return kParamCount; }

const stewart_param_info *stewart_param(int i) {
    return i >= 0 && i < kParamCount ? &kParams[i] : nullptr;
}

double *stewart_param_element(stewart_params *p, int i, int e) {
    if (!p || i < 0 || i >= kParamCount || e < 0 || e >= kParams[i].count) return nullptr;
    return reinterpret_cast<double *>(reinterpret_cast<char *>(p) + kOffsets[i]) + e;
}

int stewart_param_find(const char *name, int *element) {
    if (!name) return -1;
    const char *bracket = std::strchr(name, '[');
    const size_t base = bracket ? static_cast<size_t>(bracket - name) : std::strlen(name);
    for (int i = 0; i < kParamCount; ++i) {
        const stewart_param_info &p = kParams[i];
        if (std::strlen(p.name) != base || std::strncmp(p.name, name, base) != 0) continue;
        int e = 0;
        if (p.count > 1) {
            if (!bracket || (e = element_index(bracket, p.count)) < 0) return -1;
        } else if (bracket) {
            return -1;
        }
        if (element) *element = e;
        return i;
    }
    return -1;
}

int stewart_param_find_id(int id, int *element) {
    for (int i = 0; i < kParamCount; ++i)
        if (id >= kParams[i].id && id < kParams[i].id + kParams[i].count) {
            if (element) *element = id - kParams[i].id;
            return i;
        }
    return -1;
}

int stewart_param_element_name(int i, int e, char *text, size_t size) {
    const stewart_param_info *p = stewart_param(i);
    if (!p || e < 0 || e >= p->count) return -1;
    if (p->count == 1) return std::snprintf(text, size, "%s", p->name);
    return std::snprintf(text, size, "%s[%d]", p->name, e + 1);
}

int stewart_param_element_description(int i, int e, char *text, size_t size) {
    const stewart_param_info *p = stewart_param(i);
    if (!p || e < 0 || e >= p->count) return -1;
    if (is_pose(*p)) return std::snprintf(text, size, "%s %s", p->description, kPoseAxis[e]);
    if (p->count == STEWART_LEGS)
        return std::snprintf(text, size, "%s of leg %d", p->description, e + 1);
    if (p->count == 3) return std::snprintf(text, size, "%s %s", p->description, kAxis[e]);
    if (p->count == 3 * STEWART_LEGS)
        return std::snprintf(text, size, "%s %s of leg %d", p->description, kAxis[e % 3],
                             e / 3 + 1);
    return std::snprintf(text, size, "%s", p->description);
}

const char *stewart_param_element_unit(int i, int e) {
    const stewart_param_info *p = stewart_param(i);
    if (!p || e < 0 || e >= p->count) return nullptr;
    return is_pose(*p) ? (e < 3 ? "m" : "rad") : p->unit;
}

const char *stewart_param_element_display_unit(int i, int e) {
    const stewart_param_info *p = stewart_param(i);
    if (!p || e < 0 || e >= p->count) return nullptr;
    return is_pose(*p) ? (e < 3 ? "" : "deg") : p->display_unit;
}

stewart_status stewart_param_check_value(int i, int e, double value, char *msg, size_t size) {
    const stewart_param_info *p = stewart_param(i);
    if (!p || e < 0 || e >= p->count)
        return set_message(msg, size, STEWART_ERR_ARGUMENT, "no parameter %d element %d", i, e);
    if (stewart::in_range(value, p->min, p->min_closed, p->max, p->max_closed))
        return stewart::clear_message(msg, size);
    char name[48], range[96];
    stewart_param_element_name(i, e, name, sizeof name);
    if (!std::isfinite(value))
        return set_message(msg, size, STEWART_ERR_PARAMETER,
                           "parameter %s is %g: every parameter must be finite", name, value);
    stewart::describe_range(p->min, p->min_closed, p->max, p->max_closed, range, sizeof range);
    return set_message(msg, size, STEWART_ERR_PARAMETER, "%s = %s %s must be %s", name,
                       ExactText(value).c_str(), stewart_param_element_unit(i, e), range);
}

void stewart_params_default(stewart_params *p) {
    if (!p) return;
    for (int i = 0; i < kParamCount; ++i)
        for (int e = 0; e < kParams[i].count; ++e)
            *stewart_param_element(p, i, e) = kParams[i].defaults[e];
}

stewart_status stewart_params_check(const stewart_params *p, char *msg, size_t size) {
    if (!p) return set_message(msg, size, STEWART_ERR_ARGUMENT, "params is NULL");
    stewart_params &values = const_cast<stewart_params &>(*p);  // read only
    for (int i = 0; i < kParamCount; ++i)
        for (int e = 0; e < kParams[i].count; ++e) {
            const stewart_status s =
                stewart_param_check_value(i, e, *stewart_param_element(&values, i, e), msg, size);
            if (s != STEWART_OK) return s;
        }

    struct Named {
        const char *name;
        const double *I;
    };
    const Named inertias[] = {{"platform_inertia", p->platform_inertia},
                              {"payload_inertia", p->payload_inertia},
                              {"cylinder_inertia", p->cylinder_inertia},
                              {"piston_inertia", p->piston_inertia}};
    for (const Named &n : inertias)
        if (!triangle_ok(n.I))
            return set_message(msg, size, STEWART_ERR_PARAMETER,
                               "%s = (%s, %s, %s) kg.m2 is not a rigid body's inertia: principal "
                               "moments must satisfy the triangle inequalities",
                               n.name, ExactText(n.I[0]).c_str(), ExactText(n.I[1]).c_str(),
                               ExactText(n.I[2]).c_str());

    for (int k = 0; k < STEWART_LEGS; ++k)
        if (!(p->stroke_max[k] > p->stroke_min[k]))
            return set_message(msg, size, STEWART_ERR_PARAMETER,
                               "stroke limits of leg %d [%s, %s] m must satisfy stroke_min[%d] < "
                               "stroke_max[%d]",
                               k + 1, ExactText(p->stroke_min[k]).c_str(),
                               ExactText(p->stroke_max[k]).c_str(), k + 1, k + 1);
    if (p->rotation_order != 0.0 && p->rotation_order != 1.0)
        return set_message(msg, size, STEWART_ERR_PARAMETER,
                           "rotation_order = %s must be 0 (R = Rz(yaw) Ry(pitch) Rx(roll)) or 1 "
                           "(R = Rx(roll) Ry(pitch) Rz(yaw))",
                           ExactText(p->rotation_order).c_str());
    if (p->frame_convention != 0.0 && p->frame_convention != 1.0)
        return set_message(msg, size, STEWART_ERR_PARAMETER,
                           "frame_convention = %s must be 0 (z up) or 1 (z down, x forward, y "
                           "right)",
                           ExactText(p->frame_convention).c_str());
    stewart_status s = check_magnitudes(values, msg, size);
    if (s == STEWART_OK) s = check_side_sizes(*p, msg, size);
    // The circles of geometry 0 lie in z = 0 of each frame: the platform is above the base. Joints
    // given as coordinates (geometry 1) take any origin, so any home_height.
    if (s == STEWART_OK && p->geometry == 0.0 && !(p->home_height > 0))
        return set_message(msg, size, STEWART_ERR_PARAMETER,
                           "home_height = %s m must be > 0 with geometry 0 (the joints' circles "
                           "in z = 0 of each frame); with geometry 1 (joints as coordinates) any "
                           "origin, so any home_height, is taken",
                           ExactText(p->home_height).c_str());
    // Singular everywhere first: joints at one point also fail the Cardans' checks, which would
    // name a consequence instead.
    if (s == STEWART_OK && (p->geometry == 0.0 || p->geometry == 1.0))
        s = stewart::check_not_singular_everywhere(*p, msg, size);
    // On the z-up twin of a z-down machine: the check places home above the base.
    if (s == STEWART_OK)
        s = stewart::check_joint_geometry(stewart::params_in_solver_frames(*p), msg, size);
    if (s == STEWART_OK) s = stewart::check_limit_parameters(*p, msg, size);
    if (s == STEWART_OK) s = check_drive_parameters(*p, msg, size);
    if (s == STEWART_OK) s = check_drive_overflow(*p, msg, size);
    if (s != STEWART_OK) return s;
    return stewart::clear_message(msg, size);
}

stewart_status stewart_params_set(stewart_params *p, const char *name, double value, char *msg,
                                  size_t size) {
    if (!p || !name) return set_message(msg, size, STEWART_ERR_ARGUMENT, "NULL argument");
    int e = 0;
    const int i = stewart_param_find(name, &e);
    if (i < 0)
        for (int k = 0; k < kParamCount; ++k)
            if (!std::strcmp(name, kParams[k].name) && stewart_param_fills_from_scalar(k)) {
                for (int leg = 0; leg < kParams[k].count; ++leg)
                    *stewart_param_element(p, k, leg) = value;
                return stewart::clear_message(msg, size);
            }
    if (i < 0) {
        int nearest = 0;
        size_t best = static_cast<size_t>(-1);
        for (int k = 0; k < kParamCount; ++k) {
            const size_t d = edit_distance(name, kParams[k].name);
            if (d < best) best = d, nearest = k;
        }
        char suffix[16];
        std::snprintf(suffix, sizeof suffix, "[1..%d]", kParams[nearest].count);
        return set_message(msg, size, STEWART_ERR_ARGUMENT,
                           "no parameter is named '%s'; the nearest is %s%s (names as in the FMU's "
                           "model description: arrays take an element counted from 1)",
                           name, kParams[nearest].name, kParams[nearest].count > 1 ? suffix : "");
    }
    *stewart_param_element(p, i, e) = value;
    return stewart::clear_message(msg, size);
}

int stewart_param_fills_from_scalar(int i) {
    const stewart_param_info *info = stewart_param(i);
    if (!info) return 0;
    for (const char *name : kScalarFills)
        if (!std::strcmp(info->name, name)) return 1;
    return 0;
}

}  // extern "C"
