// stewart._core's limits (limits.py, check.py): the limit check and axis ranges of poses, and
// the home check of a platform.
#include "_core.hpp"

extern "C" {
#include "stewart/stewart_check.h"
}

namespace stewart_core {

namespace {

// A limits object for model with condition limit warn_condition (none: the default), from the
// model's pool and given back to it.
struct LimitsObject {
    LimitsObject(const Model &model, std::optional<double> warn_condition)
        : lease(model.limits_pool(), warn_condition) {
        if (lease.solver) return;
        stewart_limits_options o;
        stewart_limits_options_default(&o);
        if (warn_condition) o.warn_condition = *warn_condition;
        char message[STEWART_MESSAGE_SIZE];
        lease.solver = stewart_limits_create(model.get(), &o, message, sizeof message);
        if (!lease.solver) fail(message);
    }
    Lease<stewart_limits, std::optional<double>> lease;
};

// The check of every row of q (with data's rows for the leg classes) into the arrays (rows as
// q's); a row the library refuses raises ValueError naming the row and the cause.
void limits_check(const Model &model, Poses q, std::optional<Poses> rates,
                  std::optional<Poses> accels, std::optional<Poses> jerks,
                  std::optional<Poses> forces, std::optional<double> warn_condition,
                  Column<int> first, Column<int> failed, Rows<double, STEWART_LIMIT_CLASSES> margin,
                  Rows<int, STEWART_LIMIT_CLASSES> leg, Rows<int, STEWART_LIMIT_CLASSES> other_leg,
                  Column<double> condition, Rows<double, STEWART_LIMIT_CLASSES * 6> leg_margin) {
    const size_t n = q.shape(0);
    if (first.shape(0) != n || failed.shape(0) != n || margin.shape(0) != n || leg.shape(0) != n ||
        other_leg.shape(0) != n || condition.shape(0) != n || leg_margin.shape(0) != n)
        fail("output arrays must have as many rows as the poses");
    for (const auto *rows : {&rates, &accels, &jerks, &forces})
        if (*rows && (*rows)->shape(0) != n)
            fail("rates, accels, jerks and forces need a row per pose");
    if ((accels && !rates) || (jerks && !accels))
        fail("the pose's derivatives go in order: accels need rates, jerks need accels");
    const int derivatives = jerks ? 3 : accels ? 2 : rates ? 1 : 0;
    LimitsObject object(model, warn_condition);
    size_t bad = n;
    {
        nb::gil_scoped_release release;
        for (size_t r = 0; r < n && bad == n; ++r) {
            stewart_limits_input in{};
            in.derivatives = derivatives;
            in.has_force = forces ? 1 : 0;
            for (int i = 0; i < 6; ++i) {
                in.q[i] = q(r, i);
                if (rates) in.q_dot[i] = (*rates)(r, i);
                if (accels) in.q_ddot[i] = (*accels)(r, i);
                if (jerks) in.q_dddot[i] = (*jerks)(r, i);
                if (forces) in.force[i] = (*forces)(r, i);
            }
            stewart_limits_output out;
            if (stewart_limits_check(object.lease.solver, &in, &out) != STEWART_OK) {
                bad = r;
                break;
            }
            first(r) = out.first;
            failed(r) = out.failed;
            condition(r) = out.condition;
            for (int c = 0; c < STEWART_LIMIT_CLASSES; ++c) {
                margin(r, c) = out.margin[c];
                leg(r, c) = out.leg[c];
                other_leg(r, c) = out.other_leg[c];
                for (int k = 0; k < 6; ++k) leg_margin(r, 6 * c + k) = out.leg_margin[c][k];
            }
        }
    }
    if (bad < n)
        fail(("poses row " + std::to_string(bad) + ": " +
              stewart_limits_message(object.lease.solver))
                 .c_str());
}

// The axis ranges of every row of q: ends (min of the six axes, then max), the class at each
// end and its leg and other leg, in the same order.
void limits_ranges(const Model &model, Poses q, std::optional<double> warn_condition,
                   Rows<double, 12> ends, Rows<int, 12> limit, Rows<int, 12> leg,
                   Rows<int, 12> other_leg) {
    const size_t n = q.shape(0);
    if (ends.shape(0) != n || limit.shape(0) != n || leg.shape(0) != n || other_leg.shape(0) != n)
        fail("output arrays must have as many rows as the poses");
    LimitsObject object(model, warn_condition);
    size_t bad = n;
    {
        nb::gil_scoped_release release;
        for (size_t r = 0; r < n; ++r) {
            stewart_limits_input in{};
            for (int i = 0; i < 6; ++i) in.q[i] = q(r, i);
            stewart_axis_ranges out;
            if (stewart_limits_ranges(object.lease.solver, &in, &out) != STEWART_OK) {
                bad = r;
                break;
            }
            for (int a = 0; a < 6; ++a) {
                ends(r, a) = out.min[a];
                ends(r, 6 + a) = out.max[a];
                limit(r, a) = out.min_limit[a];
                limit(r, 6 + a) = out.max_limit[a];
                leg(r, a) = out.min_leg[a];
                leg(r, 6 + a) = out.max_leg[a];
                other_leg(r, a) = out.min_other_leg[a];
                other_leg(r, 6 + a) = out.max_other_leg[a];
            }
        }
    }
    if (bad < n)
        fail(("poses row " + std::to_string(bad) + ": " +
              stewart_limits_message(object.lease.solver))
                 .c_str());
}

// The home check of stewart_check.h: its numbers and its text (lengths in length_unit, angles in
// angle_unit: names of stewart_unit_per_si, "" for m and deg), in a dict.
nb::dict check_home(const Model &model, std::optional<double> warn_condition,
                    const std::string &length_unit, const std::string &angle_unit) {
    stewart_limits_options options;
    stewart_limits_options_default(&options);
    if (warn_condition) options.warn_condition = *warn_condition;
    stewart_check_report r;
    char message[STEWART_MESSAGE_SIZE];
    if (stewart_check_home(model.get(), &options, &r, message, sizeof message) != STEWART_OK)
        fail(message);
    const char *length = length_unit.c_str(), *angle = angle_unit.c_str();
    const size_t needed = stewart_check_text_in(&r, length, angle, nullptr, 0);
    if (needed == 0)
        fail(("not a length and an angle unit: " + length_unit + ", " + angle_unit).c_str());
    std::string text(needed + 1, '\0');
    stewart_check_text_in(&r, length, angle, text.data(), text.size());
    text.resize(text.size() - 1);
    auto values = [](const double *v) { return std::vector<double>(v, v + 6); };
    nb::dict d;
    d["home"] = values(r.home);
    d["length"] = values(r.length);
    d["stroke_min"] = values(r.stroke_min);
    d["stroke_max"] = values(r.stroke_max);
    d["joint_spread"] = r.joint_spread;
    d["crossing"] = std::make_pair(r.crossing[0], r.crossing[1]);
    d["hints"] = r.hints;
    d["valid"] = r.valid != 0;
    d["text"] = text;
    return d;
}

}  // namespace

void bind_limits(nb::module_ &m) {
    m.def("limits_check", &limits_check, nb::arg("model"), nb::arg("q"), nb::arg("rates").none(),
          nb::arg("accels").none(), nb::arg("jerks").none(), nb::arg("forces").none(),
          nb::arg("warn_condition").none(), nb::arg("first"), nb::arg("failed"), nb::arg("margin"),
          nb::arg("leg"), nb::arg("other_leg"), nb::arg("condition"), nb::arg("leg_margin"));
    m.def("limits_ranges", &limits_ranges, nb::arg("model"), nb::arg("q"),
          nb::arg("warn_condition").none(), nb::arg("ends"), nb::arg("limit"), nb::arg("leg"),
          nb::arg("other_leg"));
    m.def("check_home", &check_home, nb::arg("model"), nb::arg("warn_condition").none(),
          nb::arg("length_unit"), nb::arg("angle_unit"));
    m.attr("CHECK_UNITS") = STEWART_CHECK_UNITS;
    m.attr("CHECK_SWAPPED_LEGS") = STEWART_CHECK_SWAPPED_LEGS;
    m.attr("CHECK_FRAME") = STEWART_CHECK_FRAME;
    m.def("limit_class_name", [](int c) { return std::string(stewart_limit_class_name(c)); });
    m.attr("LIMIT_CLASSES") = STEWART_LIMIT_CLASSES;
}

}  // namespace stewart_core
