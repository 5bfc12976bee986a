// The check of a platform's home pose (stewart/stewart_check.h): the limits and axis ranges at
// home through the limits object, and the hints that name a likely entry mistake.
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <string>

#include "kinematics/frames.hpp"
#include "model.hpp"
#include "stewart/stewart_check.h"
#include "stewart/stewart_platform_file.h"
#include "util/message.hpp"

using stewart::clear_message;
using stewart::set_message;

namespace {

const char *const kAxes[6] = {"x", "y", "z", "roll", "pitch", "yaw"};

// The largest distance between two columns of points.
double spread(const stewart::Matrix36 &points) {
    double d = 0.0;
    for (int i = 0; i < 6; ++i)
        for (int j = i + 1; j < 6; ++j) d = std::max(d, (points.col(i) - points.col(j)).norm());
    return d;
}

// True when segments p0-p1 and q0-q1 of the xy plane cross at interior points of both (the ends
// excluded, so legs that share a joint do not count).
bool cross_in_plan(const Eigen::Vector3d &p0, const Eigen::Vector3d &p1, const Eigen::Vector3d &q0,
                   const Eigen::Vector3d &q1) {
    const double ux = p1.x() - p0.x(), uy = p1.y() - p0.y();
    const double vx = q1.x() - q0.x(), vy = q1.y() - q0.y();
    const double den = ux * vy - uy * vx;
    const double scale = std::hypot(ux, uy) * std::hypot(vx, vy);
    if (!(std::fabs(den) > 1e-9 * scale)) return false;  // parallel in plan
    const double wx = q0.x() - p0.x(), wy = q0.y() - p0.y();
    const double s = (wx * vy - wy * vx) / den, t = (wx * uy - wy * ux) / den;
    const double inner = 0.02;
    return s > inner && s < 1 - inner && t > inner && t < 1 - inner;
}

// The hints of a report whose lengths, strokes and spread are filled.
void find_hints(const stewart_model &m, stewart_check_report &r) {
    const stewart::PlatformGeometry &g = m.geometry;
    const double h = m.params.home_height;
    // A unit mistake scales lengths by 25.4 (inch), 100 (cm) or 1000 (mm): every leg a factor
    // of 3 or more away from its stroke, where a wrong stroke or home is off by less.
    int far_outside = 0;
    double longest = 0.0;
    for (int k = 0; k < 6; ++k) {
        far_outside += r.length[k] < r.stroke_min[k] / 3.0 || r.length[k] > 3.0 * r.stroke_max[k];
        longest = std::max(longest, r.length[k]);
    }
    if (far_outside == 6 || longest > 10.0 * r.joint_spread) r.hints |= STEWART_CHECK_UNITS;
    for (int i = 0; i < 6 && !r.crossing[0]; ++i)
        for (int j = i + 1; j < 6 && !r.crossing[0]; ++j) {
            const Eigen::Vector3d top_i = g.platform_points.col(i) + Eigen::Vector3d(0, 0, h);
            const Eigen::Vector3d top_j = g.platform_points.col(j) + Eigen::Vector3d(0, 0, h);
            if (cross_in_plan(g.base_points.col(i), top_i, g.base_points.col(j), top_j)) {
                r.crossing[0] = i + 1;
                r.crossing[1] = j + 1;
                r.hints |= STEWART_CHECK_SWAPPED_LEGS;
            }
        }
    const double lowest_base = g.base_points.row(2).minCoeff();
    const double highest_top = g.platform_points.row(2).maxCoeff() + h;
    bool like_base_frame = h > 0.0;
    for (int k = 0; k < 6; ++k)
        like_base_frame = like_base_frame && std::fabs(g.platform_points(2, k) - h) < 0.1 * h;
    // The mistake itself: joints entered in the base frame get home_height added twice, so a
    // leg misses its stroke at home while every leg measured between the joints as entered fits
    // it. This catches machines whose platform joints lie at several heights (the flat tests
    // above miss them); a home refused for another limit with the strokes met is not hinted.
    bool fits_as_entered = h != 0.0, misses_at_home = false;
    for (int k = 0; k < 6; ++k) {
        const double entered = (g.platform_points.col(k) - g.base_points.col(k)).norm();
        fits_as_entered =
            fits_as_entered && entered >= r.stroke_min[k] && entered <= r.stroke_max[k];
        misses_at_home =
            misses_at_home || r.length[k] < r.stroke_min[k] || r.length[k] > r.stroke_max[k];
    }
    fits_as_entered = fits_as_entered && misses_at_home;
    if (highest_top < lowest_base || like_base_frame || fits_as_entered)
        r.hints |= STEWART_CHECK_FRAME;
}

// The home pose as the caller's poses give it: the tool's in the user frame.
void home_pose(const stewart_model &m, double q[6]) {
    stewart_pose platform{};
    platform.q[2] = m.params.home_height;
    stewart_pose tool{};
    stewart::tool_pose(m.frames, platform, 0, tool);
    std::memcpy(q, tool.q, sizeof tool.q);
}

// Appends printf-style text to out.
void add(std::string &out, const char *format, ...) {
    char line[512];
    va_list args;
    va_start(args, format);
    std::vsnprintf(line, sizeof line, format, args);
    va_end(args);
    out += line;
}

// The units the text is in: SI values are multiplied by length or angle (stewart_unit_per_si).
struct Shown {
    double length = 1.0, angle = 1.0;
    const char *length_name = "m", *angle_name = "deg";
    // An axis' value (x, y, z a length, the rest angles) and its unit.
    double axis(int a, double v) const { return v * (a < 3 ? length : angle); }
    const char *axis_unit(int a) const { return a < 3 ? length_name : angle_name; }
};

// A class's margin in the text's units and its unit ("" for the condition number).
double shown_margin(const Shown &u, int limit_class, double margin) {
    switch (limit_class) {
        case STEWART_LIMIT_STROKE:
        case STEWART_LIMIT_INTERFERENCE: return margin * u.length;
        case STEWART_LIMIT_BASE_JOINT:
        case STEWART_LIMIT_PLATFORM_JOINT: return margin * u.angle;
        default: return margin;
    }
}

std::string margin_unit(const Shown &u, int limit_class) {
    switch (limit_class) {
        case STEWART_LIMIT_STROKE:
        case STEWART_LIMIT_INTERFERENCE: return std::string(" ") + u.length_name;
        case STEWART_LIMIT_BASE_JOINT:
        case STEWART_LIMIT_PLATFORM_JOINT: return std::string(" ") + u.angle_name;
        default: return "";
    }
}

// "leg 3", "legs 2 and 5", or "" for a margin of no leg.
std::string legs_of(int leg, int other_leg) {
    if (other_leg > 0) return "legs " + std::to_string(leg) + " and " + std::to_string(other_leg);
    return leg > 0 ? "leg " + std::to_string(leg) : "";
}

// "stroke (leg 3)", "interference (legs 2 and 5)", "the search's end".
std::string limit_at(int limit_class, int leg, int other_leg) {
    if (limit_class == STEWART_LIMIT_NONE) return "the search's end";
    const std::string where = legs_of(leg, other_leg);
    return std::string(stewart_limit_class_name(limit_class)) +
           (where.empty() ? "" : " (" + where + ")");
}

// The axis class: its margin in its axis' unit and the axis' name, or that no axis has a limit.
void add_axis_margin(const stewart_limits_output &limits, const Shown &u, std::string &out) {
    const int a = limits.leg[STEWART_LIMIT_AXIS - 1] - 1;
    const double margin = limits.margin[STEWART_LIMIT_AXIS - 1];
    if (a < 0 || a >= 6 || !(std::fabs(margin) < 0.5 * DBL_MAX))
        return add(out, "  %-15s none set (axis_min, axis_max)\n",
                   stewart_limit_class_name(STEWART_LIMIT_AXIS));
    add(out, "  %-15s %-12.6g %-4s %s\n", stewart_limit_class_name(STEWART_LIMIT_AXIS),
        u.axis(a, margin), u.axis_unit(a), kAxes[a]);
}

void add_legs_and_margins(const stewart_check_report &r, const Shown &u, std::string &out) {
    out += "home pose:";
    for (int a = 0; a < 6; ++a)
        add(out, "%s %s %.6g %s", a ? "," : "", kAxes[a], u.axis(a, r.home[a]), u.axis_unit(a));
    const std::string unit = std::string("[") + u.length_name + "]";
    add(out, "\nleg  length %-7s stroke %-22s to the nearer end %s\n", unit.c_str(), unit.c_str(),
        unit.c_str());
    for (int k = 0; k < 6; ++k) {
        const double margin =
            std::min(r.length[k] - r.stroke_min[k], r.stroke_max[k] - r.length[k]);
        add(out, "%d    %-13.7g  %-12.7g .. %-12.7g   %.6g%s\n", k + 1, r.length[k] * u.length,
            r.stroke_min[k] * u.length, r.stroke_max[k] * u.length, margin * u.length,
            margin < 0 ? "  (outside)" : "");
    }
    add(out, "margins at home (> 0 within, < 0 beyond):\n");
    // The pose's own classes: home is at rest, so the leg classes have nothing to check.
    for (int c = 1; c < STEWART_LIMIT_AXIS; ++c)
        add(out, "  %-15s %-12.6g%-5s %s\n", stewart_limit_class_name(c),
            shown_margin(u, c, r.limits.margin[c - 1]), margin_unit(u, c).c_str(),
            legs_of(r.limits.leg[c - 1], r.limits.other_leg[c - 1]).c_str());
    add_axis_margin(r.limits, u, out);
    add(out, "  condition number %.6g\n", r.limits.condition);
}

void add_ranges(const stewart_check_report &r, const Shown &u, std::string &out) {
    add(out, "axis ranges from home (the other five axes held):\n");
    for (int a = 0; a < 6; ++a) {
        add(out, "  %-5s %.6g .. %.6g %s  (%s / %s)\n", kAxes[a], u.axis(a, r.ranges.min[a]),
            u.axis(a, r.ranges.max[a]), u.axis_unit(a),
            limit_at(r.ranges.min_limit[a], r.ranges.min_leg[a], r.ranges.min_other_leg[a]).c_str(),
            limit_at(r.ranges.max_limit[a], r.ranges.max_leg[a], r.ranges.max_other_leg[a])
                .c_str());
    }
}

void add_hints(const stewart_check_report &r, const Shown &u, std::string &out) {
    if (r.hints & STEWART_CHECK_UNITS)
        add(out,
            "hint: units? The legs (%.6g to %.6g %s at home) do not fit the strokes or the "
            "joints (spread %.6g %s): are the joints, home_height and the strokes all in "
            "the same unit (metres, or the file's \"units\")?\n",
            *std::min_element(r.length, r.length + 6) * u.length, u.length_name,
            *std::max_element(r.length, r.length + 6) * u.length, r.joint_spread * u.length,
            u.length_name);
    if (r.hints & STEWART_CHECK_SWAPPED_LEGS)
        add(out,
            "hint: swapped legs? Legs %d and %d cross each other (seen from above): leg k "
            "joins base_joint k to platform_joint k; check the order of both lists.\n",
            r.crossing[0], r.crossing[1]);
    if (r.hints & STEWART_CHECK_FRAME)
        add(out, "hint: frame? The platform joints are below the base joints at home, their z "
                 "equals home_height, or the legs would fit their strokes without home_height "
                 "added: platform_joint is in the platform frame (its origin moves with the "
                 "platform, at home_height above the base frame's at home), with z toward the "
                 "platform from the base. Ignore this if the platform hangs below its base.\n");
}

// name (NULL or "": keep the default) as the text's unit of the SI unit si; false if it is not one.
bool set_unit(const char *name, const char *si, double &factor, const char *&shown_name) {
    if (!name || !*name) return true;
    const char *its_si = stewart_unit_per_si(name, &factor);
    if (!its_si || std::strcmp(its_si, si)) return false;
    shown_name = name;
    return true;
}

}  // namespace

extern "C" {

stewart_status stewart_check_home(const stewart_model *model, const stewart_limits_options *options,
                                  stewart_check_report *report, char *message, size_t size) {
    if (!model || !report)
        return set_message(message, size, STEWART_ERR_ARGUMENT, "%s is NULL",
                           model ? "report" : "model");
    stewart_limits_options defaults;
    stewart_limits_options_default(&defaults);
    stewart_limits *limits =
        stewart_limits_create(model, options ? options : &defaults, message, size);
    if (!limits) return options ? STEWART_ERR_PARAMETER : STEWART_ERR_MEMORY;
    stewart_check_report &r = *report;
    r = stewart_check_report{};
    home_pose(*model, r.home);
    const stewart::PlatformGeometry &g = model->geometry;
    for (int k = 0; k < 6; ++k) {
        const Eigen::Vector3d top =
            g.platform_points.col(k) + Eigen::Vector3d(0, 0, model->params.home_height);
        r.length[k] = (top - g.base_points.col(k)).norm();
        r.stroke_min[k] = model->params.stroke_min[k];
        r.stroke_max[k] = model->params.stroke_max[k];
    }
    r.joint_spread = std::max(spread(g.base_points), spread(g.platform_points));
    stewart_limits_input in{};
    std::memcpy(in.q, r.home, sizeof in.q);
    stewart_status s = stewart_limits_check(limits, &in, &r.limits);
    if (s == STEWART_OK) s = stewart_limits_ranges(limits, &in, &r.ranges);
    if (s != STEWART_OK) set_message(message, size, s, "%s", stewart_limits_message(limits));
    stewart_limits_free(limits);
    if (s != STEWART_OK) return s;
    r.valid = r.limits.first == STEWART_LIMIT_NONE;
    find_hints(*model, r);
    return clear_message(message, size);
}

size_t stewart_check_text(const stewart_check_report *report, char *text, size_t size) {
    return stewart_check_text_in(report, nullptr, nullptr, text, size);
}

size_t stewart_check_text_in(const stewart_check_report *report, const char *length_unit,
                             const char *angle_unit, char *text, size_t size) {
    Shown u;
    if (!set_unit(length_unit, "m", u.length, u.length_name) ||
        !set_unit(angle_unit, "rad", u.angle, u.angle_name)) {
        if (text && size > 0) text[0] = '\0';
        return 0;
    }
    std::string out;
    if (!report) {
        out = "no report\n";
    } else {
        add_legs_and_margins(*report, u, out);
        add_ranges(*report, u, out);
        if (report->valid) out += "home is within every limit.\n";
        else
            add(out, "home is NOT a valid pose: the first limit it fails is %s.\n",
                limit_at(report->limits.first, report->limits.leg[report->limits.first - 1],
                         report->limits.other_leg[report->limits.first - 1])
                    .c_str());
        add_hints(*report, u, out);
    }
    if (text && size > 0) {
        const size_t n = std::min(out.size(), size - 1);
        std::memcpy(text, out.data(), n);
        text[n] = '\0';
    }
    return out.size();
}

}  // extern "C"
