// stewart._core: the nanobind extension over the C API (stewart.h, stewart_batch.h). It holds a
// model and one data block (inverse and forward kinematics; each simulate makes its own plant);
// Python (stewart/platform.py) shapes arrays and results.
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/pair.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/tuple.h>
#include <nanobind/stl/vector.h>

#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

extern "C" {
#include "stewart/stewart.h"
#include "stewart/stewart_batch.h"
#include "stewart/stewart_forward.h"
#include "stewart/stewart_plant.h"
#include "stewart/stewart_table.h"
}

namespace nb = nanobind;

namespace {

template <typename T, size_t W>
using Rows = nb::ndarray<T, nb::shape<-1, W>, nb::c_contig, nb::device::cpu>;
template <typename T>
using Column = nb::ndarray<T, nb::shape<-1>, nb::c_contig, nb::device::cpu>;
using Poses = Rows<const double, 6>;
using Times = Column<const double>;
using Messages = std::vector<std::pair<size_t, std::string>>;
using BatchResult = std::tuple<int, size_t, std::string, Messages>;

// A Python ValueError subclass defined in stewart/errors.py is raised from Python; here the
// C messages travel as ValueError (bad parameters, options) and the caller re-raises.
[[noreturn]] void fail(const char *message) { throw nb::value_error(message); }

// Room for the messages of up to max failing rows, and the (row, message) pairs a batch kept.
struct MessageBuffer {
    explicit MessageBuffer(size_t max)
        : rows(max), text(max * STEWART_MESSAGE_SIZE), c{max, 0, rows.data(), text.data()} {}
    Messages kept() const {
        Messages out;
        for (size_t i = 0; i < c.count; ++i)
            out.emplace_back(rows[i], std::string(text.data() + i * STEWART_MESSAGE_SIZE));
        return out;
    }
    std::vector<size_t> rows;
    std::vector<char> text;
    stewart_batch_messages c;
};

class Model {
public:
    // Default (thesis) parameters, then each (name, value) through stewart_params_set, then the
    // model: any bad name or value raises ValueError with the library's message.
    explicit Model(const std::vector<std::pair<std::string, double>> &assignments) {
        stewart_params params;
        stewart_params_default(&params);
        char message[STEWART_MESSAGE_SIZE];
        for (const auto &[name, value] : assignments)
            if (stewart_params_set(&params, name.c_str(), value, message, sizeof message) !=
                STEWART_OK)
                fail(message);
        model_ = stewart_model_create(&params, message, sizeof message);
        if (!model_) fail(message);
    }
    ~Model() { stewart_model_free(model_); }
    Model(const Model &) = delete;
    Model &operator=(const Model &) = delete;

    // Solves the rows of q with a fresh inverse solver. Returns (status of the first failing row or
    // 0, its index or n, its message, [(row, message)] of up to max_messages failing rows).
    BatchResult solve(
        Poses q, std::optional<Poses> q_dot, std::optional<Poses> q_ddot,
        const std::vector<std::pair<std::string, double>> &option_values,
        std::optional<Rows<double, 6>> length, std::optional<Rows<double, 6>> length_rate,
        std::optional<Rows<double, 6>> length_accel, std::optional<Rows<double, 6>> force,
        std::optional<Column<double>> condition, std::optional<Column<double>> residual,
        std::optional<Rows<double, 3>> base_force, std::optional<Rows<double, 3>> base_torque,
        std::optional<Column<int>> iterations, std::optional<Column<int>> warnings,
        Column<int> status, size_t max_messages) {
        const size_t n = q.shape(0);
        if ((q_dot && q_dot->shape(0) != n) || (q_ddot && q_ddot->shape(0) != n))
            fail("rates and accels must have as many rows as the poses");
        if (status.shape(0) != n) fail("output arrays must have as many rows as the poses");
        const stewart_inverse_options options = make_options(option_values);
        const stewart_inverse_batch_outputs out = {
            rows_of(length, n),     rows_of(length_rate, n), rows_of(length_accel, n),
            rows_of(force, n),      rows_of(condition, n),   rows_of(residual, n),
            rows_of(base_force, n), rows_of(base_torque, n), rows_of(iterations, n),
            rows_of(warnings, n),   nullptr /* stroke_legs: not asked for */, status.data()};
        char message[STEWART_MESSAGE_SIZE];
        Solver<stewart_inverse> inverse(
            stewart_inverse_create(model_, &options, message, sizeof message),
            stewart_inverse_free, stewart_inverse_message);
        if (!inverse.solver) fail(message);  // the options were checked: memory is short
        return inverse.run(n, max_messages, [&](stewart_batch_messages *messages,
                                                size_t *first_failed) {
            return stewart_inverse_batch(inverse.solver, n, q.data(),
                                         q_dot ? q_dot->data() : nullptr,
                                         q_ddot ? q_ddot->data() : nullptr, &out, messages,
                                         first_failed);
        });
    }

    // Forward kinematics of the rows of lengths from a cold start (or guess), tracking in order.
    // Returns as solve.
    BatchResult forward(
        Poses lengths, std::optional<Poses> rates, std::optional<Poses> accels,
        std::optional<Times> time, std::optional<Column<const double>> guess,
        const std::vector<std::pair<std::string, double>> &option_values,
        std::optional<Rows<double, 6>> pose, std::optional<Rows<double, 6>> pose_rate,
        std::optional<Rows<double, 6>> pose_accel, std::optional<Column<double>> residual,
        std::optional<Column<double>> condition, std::optional<Column<double>> jump,
        std::optional<Column<int>> iterations, std::optional<Column<int>> warnings,
        std::optional<Column<int>> branch, std::optional<Column<int>> start, Column<int> status,
        size_t max_messages) {
        const size_t n = lengths.shape(0);
        if ((rates && rates->shape(0) != n) || (accels && accels->shape(0) != n) ||
            (time && time->shape(0) != n))
            fail("t, rates and accels must have as many rows as the lengths");
        if (accels && !rates) fail("accels need rates");
        if (guess && guess->shape(0) != 6) fail("guess must have 6 values");
        if (status.shape(0) != n) fail("output arrays must have as many rows as the lengths");
        const stewart_forward_options options = make_forward_options(option_values);
        const stewart_forward_batch_outputs out = {
            rows_of(pose, n),     rows_of(pose_rate, n),  rows_of(pose_accel, n),
            rows_of(residual, n), rows_of(condition, n),  rows_of(jump, n),
            rows_of(iterations, n), rows_of(warnings, n), rows_of(branch, n),
            rows_of(start, n),    nullptr /* stroke_legs: not asked for */, status.data()};
        char message[STEWART_MESSAGE_SIZE];
        Solver<stewart_forward> forward(
            stewart_forward_create(model_, &options, message, sizeof message),
            stewart_forward_free, stewart_forward_message);
        if (!forward.solver) fail(message);
        return forward.run(n, max_messages, [&](stewart_batch_messages *messages,
                                                size_t *first_failed) {
            return stewart_forward_batch(forward.solver, n, time ? time->data() : nullptr,
                                         lengths.data(), rates ? rates->data() : nullptr,
                                         accels ? accels->data() : nullptr,
                                         guess ? guess->data() : nullptr, &out, messages,
                                         first_failed);
        });
    }

    // Runs a fresh plant through the communication points t with the forces (linear between
    // rows) from the start state (None: at rest at home). Returns (status of the row that stopped
    // the run or 0, its index or n, its message, the integrator's totals by name).
    std::tuple<int, size_t, std::string, std::vector<std::pair<std::string, double>>> simulate(
        Times time, Poses force, std::optional<Column<const double>> start_pose,
        std::optional<Column<const double>> start_rate,
        const std::vector<std::pair<std::string, double>> &option_values,
        std::optional<Rows<double, 6>> pose, std::optional<Rows<double, 6>> pose_rate,
        std::optional<Rows<double, 6>> length, std::optional<Rows<double, 6>> length_rate,
        std::optional<Rows<double, 3>> base_force, std::optional<Rows<double, 3>> base_torque,
        std::optional<Column<int>> warnings, std::optional<Column<int64_t>> steps,
        std::optional<Column<int64_t>> rhs_evaluations,
        std::optional<Column<int64_t>> nonlinear_iterations,
        std::optional<Column<int64_t>> error_test_failures, Column<int> status) {
        const size_t n = time.shape(0);
        if (force.shape(0) != n) fail("forces must have as many rows as t");
        if ((start_pose && start_pose->shape(0) != 6) || (start_rate && start_rate->shape(0) != 6))
            fail("start and start_rate must have 6 values");
        if (status.shape(0) != n) fail("output arrays must have as many rows as t");
        const stewart_plant_options options = make_plant_options(option_values);
        static_assert(sizeof(int64_t) == sizeof(long), "plant counters are long");
        const stewart_plant_batch_outputs out = {
            rows_of(pose, n),       rows_of(pose_rate, n),   rows_of(length, n),
            rows_of(length_rate, n), rows_of(base_force, n), rows_of(base_torque, n),
            rows_of(warnings, n),
            reinterpret_cast<long *>(rows_of(steps, n)),
            reinterpret_cast<long *>(rows_of(rhs_evaluations, n)),
            reinterpret_cast<long *>(rows_of(nonlinear_iterations, n)),
            reinterpret_cast<long *>(rows_of(error_test_failures, n)), status.data()};
        char message[STEWART_MESSAGE_SIZE] = "";
        size_t first_failed = n;
        stewart_status first;
        stewart_plant_statistics stats{};
        bool created = true;
        {
            nb::gil_scoped_release release;
            stewart_plant *plant = stewart_plant_create(model_, &options, message, sizeof message);
            if (!plant) {
                created = false;  // the message says why: the model and options, or memory
                first = STEWART_ERR_PARAMETER;
            } else {
                size_t row = 0;
                stewart_batch_messages messages = {1, 0, &row, message};
                first = stewart_plant_batch(plant, n, time.data(), force.data(),
                                            start_pose ? start_pose->data() : nullptr,
                                            start_rate ? start_rate->data() : nullptr, &out,
                                            &messages, &first_failed);
                stewart_plant_statistics_get(plant, &stats);
                stewart_plant_free(plant);
            }
        }
        if (!created) {
            if (std::string(message).find("out of memory") != std::string::npos)
                throw std::bad_alloc();
            fail(message);
        }
        if (first == STEWART_ERR_MEMORY && first_failed == n) throw std::bad_alloc();
        const std::vector<std::pair<std::string, double>> totals = {
            {"steps", double(stats.total_steps)},
            {"rhs_evaluations", double(stats.total_rhs_evaluations)},
            {"nonlinear_iterations", double(stats.total_nonlinear_iterations)},
            {"error_test_failures", double(stats.total_error_test_failures)},
            {"jacobian_evaluations", double(stats.total_jacobian_evaluations)},
            {"last_order", double(stats.last_order)},
            {"last_step_size", stats.last_step_size}};
        return {first, first_failed, std::string(message), totals};
    }

private:
    // A solver object of one call (inverse or forward), freed with it.
    template <typename T>
    struct Solver {
        T *solver;
        void (*free)(T *);
        const char *(*message)(const T *);
        Solver(T *s, void (*f)(T *), const char *(*m)(const T *)) : solver(s), free(f), message(m) {}
        ~Solver() { free(solver); }
        Solver(const Solver &) = delete;
        Solver &operator=(const Solver &) = delete;

        // Runs batch(messages, first_failed) -> status with the GIL released. Returns (status of
        // the first failing row or 0, its index or n, its message, [(row, message)] of up to
        // max_messages failing rows); a failure before any row raises ValueError.
        template <typename Batch>
        BatchResult run(size_t n, size_t max_messages, Batch batch) {
            MessageBuffer messages(max_messages);
            size_t first_failed = n;
            stewart_status first;
            std::string first_message;
            {
                nb::gil_scoped_release release;
                first = batch(&messages.c, &first_failed);
                first_message = message(solver);
            }
            if (first != STEWART_OK && first_failed == n) fail(first_message.c_str());
            return {first, first_failed, first_message, messages.kept()};
        }
    };

    // The data of an output array of n rows, or nullptr for an output the caller skips (None).
    template <typename Array>
    static auto rows_of(std::optional<Array> &a, size_t n) -> decltype(a->data()) {
        if (!a) return nullptr;
        if (a->shape(0) != n) fail("output arrays must have as many rows as the poses");
        return a->data();
    }

    // Options by name (the library's option table) over stewart_inverse_options_default, each value
    // and then the whole set checked by the library.
    static stewart_inverse_options make_options(const std::vector<std::pair<std::string, double>> &values) {
        stewart_inverse_options o;
        stewart_inverse_options_default(&o);
        char message[STEWART_MESSAGE_SIZE];
        for (const auto &[name, v] : values) {
            const int i = stewart_inverse_option_find(name.c_str());
            if (i < 0) fail(("unknown solver option '" + name + "'").c_str());
            if (stewart_inverse_option_set(&o, i, v, message, sizeof message) != STEWART_OK) fail(message);
        }
        if (stewart_inverse_options_check(&o, message, sizeof message) != STEWART_OK) fail(message);
        return o;
    }

    // Options of a struct by name over its defaults: set(o, name, v) stores one (false: no such
    // name), then the library checks the whole set. Bad names and values raise ValueError.
    template <typename Options, typename Set>
    static Options named_options(const std::vector<std::pair<std::string, double>> &values,
                                 void (*defaults)(Options *),
                                 stewart_status (*check)(const Options *, char *, size_t),
                                 const char *kind, Set set) {
        Options o;
        defaults(&o);
        for (const auto &[name, v] : values)
            if (!set(o, name, v)) fail(("unknown " + std::string(kind) + " option '" + name + "'").c_str());
        char message[STEWART_MESSAGE_SIZE];
        if (check(&o, message, sizeof message) != STEWART_OK) fail(message);
        return o;
    }

    // stewart_forward_options by name, from the library's table.
    static stewart_forward_options make_forward_options(
        const std::vector<std::pair<std::string, double>> &values) {
        stewart_forward_options o;
        stewart_forward_options_default(&o);
        char message[STEWART_MESSAGE_SIZE];
        for (const auto &[name, v] : values) {
            const int i = stewart_forward_option_find(name.c_str());
            if (i < 0) fail(("unknown forward option '" + name + "'").c_str());
            if (stewart_forward_option_set(&o, i, v, message, sizeof message) != STEWART_OK)
                fail(message);
        }
        if (stewart_forward_options_check(&o, message, sizeof message) != STEWART_OK) fail(message);
        return o;
    }

    // stewart_plant_options by name.
    static stewart_plant_options make_plant_options(
        const std::vector<std::pair<std::string, double>> &values) {
        return named_options<stewart_plant_options>(
            values, stewart_plant_options_default, stewart_plant_options_check, "plant",
            [](stewart_plant_options &o, const std::string &name, double v) {
                if (name == "fidelity") o.fidelity = integer_option(name, v);
                else if (name == "method") o.method = integer_option(name, v);
                else if (name == "relative_tolerance") o.relative_tolerance = v;
                else if (name == "absolute_tolerance") o.absolute_tolerance = v;
                else if (name == "max_internal_steps") o.max_internal_steps = integer_option(name, v);
                else return false;
                return true;
            });
    }

    // v as an int, or ValueError naming the option and the value.
    static int integer_option(const std::string &name, double v) {
        // the range first: casting a NaN or a value beyond long long is undefined behaviour
        if (!(v >= -2147483648.0 && v <= 2147483647.0) ||
            v != static_cast<double>(static_cast<long long>(v)))
            fail((name + " = " + std::to_string(v) + " must be an integer").c_str());
        return static_cast<int>(v);
    }

    stewart_model *model_ = nullptr;
};

}  // namespace

NB_MODULE(_core, m) {
    m.doc() = "The C library of the Stewart platform solver (use the stewart package instead).";
    auto cls = nb::class_<Model>(m, "Model");
    cls        .def(nb::init<const std::vector<std::pair<std::string, double>> &>(), nb::arg("assignments"))
        .def("solve", &Model::solve, nb::arg("q"), nb::arg("q_dot").none(), nb::arg("q_ddot").none(),
             nb::arg("options"), nb::arg("length").none(), nb::arg("length_rate").none(),
             nb::arg("length_accel").none(), nb::arg("force").none(), nb::arg("condition").none(),
             nb::arg("residual").none(), nb::arg("base_force").none(),
             nb::arg("base_torque").none(), nb::arg("iterations").none(),
             nb::arg("warnings").none(), nb::arg("status"),
             nb::arg("max_messages"));
    cls.def("forward", &Model::forward, nb::arg("lengths"), nb::arg("rates").none(),
            nb::arg("accels").none(), nb::arg("time").none(), nb::arg("guess").none(),
            nb::arg("options"), nb::arg("pose").none(), nb::arg("pose_rate").none(),
            nb::arg("pose_accel").none(), nb::arg("residual").none(),
            nb::arg("condition").none(), nb::arg("jump").none(), nb::arg("iterations").none(),
            nb::arg("warnings").none(), nb::arg("branch").none(), nb::arg("start").none(),
            nb::arg("status"), nb::arg("max_messages"));
    cls.def("simulate", &Model::simulate, nb::arg("time"), nb::arg("force"),
            nb::arg("start_pose").none(), nb::arg("start_rate").none(), nb::arg("options"),
            nb::arg("pose").none(), nb::arg("pose_rate").none(), nb::arg("length").none(),
            nb::arg("length_rate").none(), nb::arg("base_force").none(),
            nb::arg("base_torque").none(), nb::arg("warnings").none(), nb::arg("steps").none(),
            nb::arg("rhs_evaluations").none(), nb::arg("nonlinear_iterations").none(),
            nb::arg("error_test_failures").none(), nb::arg("status"));
    m.attr("BATCH_NOT_RUN") = STEWART_BATCH_NOT_RUN;
    // (True, "") if the library knows the parameter name, else (False, its message).
    m.def("parameter_known", [](const std::string &name) {
        stewart_params scratch;
        stewart_params_default(&scratch);
        char message[STEWART_MESSAGE_SIZE];
        const bool known = stewart_params_set(&scratch, name.c_str(), 0.0, message,
                                              sizeof message) == STEWART_OK;
        return std::make_pair(known, std::string(known ? "" : message));
    });
    m.def("status_name", [](int s) { return std::string(stewart_status_name(static_cast<stewart_status>(s))); });
    // The library's parameter table: one dict per parameter (name, count, unit, description,
    // defaults, min, max).
    m.def("parameter_table", []() {
        nb::list table;
        for (int i = 0; i < stewart_param_count(); ++i) {
            const stewart_param_info *p = stewart_param(i);
            nb::dict entry;
            entry["name"] = p->name;
            entry["count"] = p->count;
            entry["unit"] = p->unit;
            entry["description"] = p->description;
            entry["defaults"] = std::vector<double>(p->defaults, p->defaults + p->count);
            entry["min"] = p->min;
            entry["max"] = p->max;
            table.append(entry);
        }
        return table;
    });
}
