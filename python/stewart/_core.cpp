// stewart._core: the nanobind extension over the C API (stewart.h, stewart_batch.h). It holds a
// model and one data block; Python (stewart/platform.py) shapes arrays and results.
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/pair.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/tuple.h>
#include <nanobind/stl/vector.h>

#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

extern "C" {
#include "stewart/stewart.h"
#include "stewart/stewart_batch.h"
#include "stewart/stewart_table.h"
}

namespace nb = nanobind;

namespace {

template <typename T, size_t W>
using Rows = nb::ndarray<T, nb::shape<-1, W>, nb::c_contig, nb::device::cpu>;
template <typename T>
using Column = nb::ndarray<T, nb::shape<-1>, nb::c_contig, nb::device::cpu>;
using Poses = Rows<const double, 6>;

// A Python ValueError subclass defined in stewart/errors.py is raised from Python; here the
// C messages travel as ValueError (bad parameters, options) and the caller re-raises.
[[noreturn]] void fail(const char *message) { throw nb::value_error(message); }

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
        data_ = stewart_data_create(model_);
        if (!data_) {
            stewart_model_free(model_);
            throw std::bad_alloc();
        }
    }
    ~Model() {
        stewart_data_free(data_);
        stewart_model_free(model_);
    }
    Model(const Model &) = delete;
    Model &operator=(const Model &) = delete;

    // Solves the rows of q from a fresh data block. Returns (status of the first failing row or
    // 0, its index or n, its message, [(row, message)] of up to max_messages failing rows).
    std::tuple<int, size_t, std::string, std::vector<std::pair<size_t, std::string>>> solve(
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
        stewart_options options = make_options(option_values);
        const stewart_batch_outputs out = {
            rows_of(length, n),     rows_of(length_rate, n), rows_of(length_accel, n),
            rows_of(force, n),      rows_of(condition, n),   rows_of(residual, n),
            rows_of(base_force, n), rows_of(base_torque, n), rows_of(iterations, n),
            rows_of(warnings, n),   status.data()};
        std::vector<size_t> rows(max_messages);
        std::vector<char> text(max_messages * STEWART_MESSAGE_SIZE);
        stewart_batch_messages messages = {max_messages, 0, rows.data(), text.data()};
        size_t first_failed = n;
        stewart_status first;
        std::string first_message;
        {
            // The GIL goes first and comes back last: a thread waiting for the mutex must not
            // hold the GIL that the solving thread needs to return.
            nb::gil_scoped_release release;
            std::lock_guard<std::mutex> lock(mutex_);
            stewart_data_reset(data_);
            first = stewart_solve_batch(model_, data_, &options, n, q.data(),
                                        q_dot ? q_dot->data() : nullptr,
                                        q_ddot ? q_ddot->data() : nullptr, &out, &messages,
                                        &first_failed);
            first_message = stewart_data_message(data_);
        }
        if (first != STEWART_OK && first_failed == n) fail(first_message.c_str());  // bad options
        std::vector<std::pair<size_t, std::string>> kept;
        for (size_t i = 0; i < messages.count; ++i)
            kept.emplace_back(rows[i], std::string(text.data() + i * STEWART_MESSAGE_SIZE));
        return {first, first_failed, first_message, kept};
    }

private:
    // The data of an output array of n rows, or nullptr for an output the caller skips (None).
    template <typename Array>
    static auto rows_of(std::optional<Array> &a, size_t n) -> decltype(a->data()) {
        if (!a) return nullptr;
        if (a->shape(0) != n) fail("output arrays must have as many rows as the poses");
        return a->data();
    }

    // Options by name (the library's option table) over stewart_options_default, each value
    // and then the whole set checked by the library.
    static stewart_options make_options(const std::vector<std::pair<std::string, double>> &values) {
        stewart_options o;
        stewart_options_default(&o);
        char message[STEWART_MESSAGE_SIZE];
        for (const auto &[name, v] : values) {
            const int i = stewart_option_find(name.c_str());
            if (i < 0) fail(("unknown solver option '" + name + "'").c_str());
            if (stewart_option_set(&o, i, v, message, sizeof message) != STEWART_OK) fail(message);
        }
        if (stewart_options_check(&o, message, sizeof message) != STEWART_OK) fail(message);
        return o;
    }

    stewart_model *model_ = nullptr;
    stewart_data *data_ = nullptr;
    std::mutex mutex_;
};

}  // namespace

NB_MODULE(_core, m) {
    m.doc() = "The C library of the Stewart platform solver (use the stewart package instead).";
    nb::class_<Model>(m, "Model")
        .def(nb::init<const std::vector<std::pair<std::string, double>> &>(), nb::arg("assignments"))
        .def("solve", &Model::solve, nb::arg("q"), nb::arg("q_dot").none(), nb::arg("q_ddot").none(),
             nb::arg("options"), nb::arg("length").none(), nb::arg("length_rate").none(),
             nb::arg("length_accel").none(), nb::arg("force").none(), nb::arg("condition").none(),
             nb::arg("residual").none(), nb::arg("base_force").none(),
             nb::arg("base_torque").none(), nb::arg("iterations").none(),
             nb::arg("warnings").none(), nb::arg("status"),
             nb::arg("max_messages"));
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
