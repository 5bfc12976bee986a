// stewart._core: the nanobind extension over the C API (stewart.h, stewart_batch.h). It holds a
// model, and per Platform.inverse, forward or simulate call one run object (the call's arrays and
// solver or plant) whose rows(a, b) runs a slice; Python (stewart/platform.py) shapes arrays and
// results and takes Ctrl-C between slices.
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/pair.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/tuple.h>
#include <nanobind/stl/vector.h>

#include <algorithm>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

extern "C" {
#include "stewart/stewart.h"
#include "stewart/stewart_batch.h"
#include "stewart/stewart_check.h"
#include "stewart/stewart_calibration.h"
#include "stewart/stewart_forward.h"
#include "stewart/stewart_linearize.h"
#include "stewart/stewart_limits.h"
#include "stewart/stewart_plant.h"
#include "stewart/stewart_platform_file.h"
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
// Left uninitialised: the batch writes only the entries it keeps (c.count), and a sweep asks room
// for every row (max_messages = rows: 256 bytes each), which zeroing would page-fault and clear.
struct MessageBuffer {
    explicit MessageBuffer(size_t max)
        : rows(new size_t[max]), text(new char[max * STEWART_MESSAGE_SIZE]),
          c{max, 0, rows.get(), text.get()} {}
    Messages kept() const {
        Messages out;
        for (size_t i = 0; i < c.count; ++i)
            out.emplace_back(rows[i], std::string(text.get() + i * STEWART_MESSAGE_SIZE));
        return out;
    }
    std::unique_ptr<size_t[]> rows;
    std::unique_ptr<char[]> text;
    stewart_batch_messages c;
};

// One direction's option table (stewart/stewart_table.h) and its calls.
template <typename Options> struct OptionTable {
    const char *kind;  // in the message for an unknown name
    void (*defaults)(Options *);
    int (*find)(const char *);
    stewart_status (*set)(Options *, int, double, char *, size_t);
    stewart_status (*check)(const Options *, char *, size_t);
};

const OptionTable<stewart_inverse_options> kInverseOptions = {
    "solver", stewart_inverse_options_default, stewart_inverse_option_find,
    stewart_inverse_option_set, stewart_inverse_options_check};
const OptionTable<stewart_forward_options> kForwardOptions = {
    "forward", stewart_forward_options_default, stewart_forward_option_find,
    stewart_forward_option_set, stewart_forward_options_check};
const OptionTable<stewart_plant_options> kPlantOptions = {
    "plant", stewart_plant_options_default, stewart_plant_option_find, stewart_plant_option_set,
    stewart_plant_options_check};

// Options by name over the defaults, each value set through the table (ValueError naming an
// unknown option, or the option and its value) and then the whole set checked by the library.
template <typename Options>
Options options_by_name(const OptionTable<Options> &table,
                        const std::vector<std::pair<std::string, double>> &values) {
    Options o;
    table.defaults(&o);
    char message[STEWART_MESSAGE_SIZE];
    for (const auto &[name, v] : values) {
        const int i = table.find(name.c_str());
        if (i < 0) fail(("unknown " + std::string(table.kind) + " option '" + name + "'").c_str());
        if (table.set(&o, i, v, message, sizeof message) != STEWART_OK) fail(message);
    }
    if (table.check(&o, message, sizeof message) != STEWART_OK) fail(message);
    return o;
}

// An option table for Python: one dict per option (name, id, integer, unit, min, max,
// min_closed, max_closed, default, description).
nb::list option_table(int (*count)(), const stewart_option_info *(*option)(int)) {
    nb::list table;
    for (int i = 0; i < count(); ++i) {
        const stewart_option_info *o = option(i);
        nb::dict entry;
        entry["name"] = o->name;
        entry["id"] = o->id;
        entry["integer"] = o->is_integer != 0;
        entry["unit"] = o->unit;
        entry["min"] = o->min;
        entry["max"] = o->max;
        entry["min_closed"] = o->min_closed != 0;
        entry["max_closed"] = o->max_closed != 0;
        entry["default"] = o->default_value;
        entry["description"] = o->description;
        table.append(entry);
    }
    return table;
}

// Solvers of one kind (inverse, forward, linearisation, limits) kept between calls on one Model
// by the key they were made with (their option values): creating one costs as much as solving
// tens to hundreds of rows, which a call of a few rows would otherwise pay every time. A solver
// is reset when taken (these solvers' reset leaves them as created: nothing carries over from
// an earlier call), so a call's numbers are those of a new solver. Taken and given back with the
// GIL held (run objects are made and freed with it), so that two threads never get the same one.
template <typename Solver, typename Key>
class SolverPool {
public:
    SolverPool(void (*free)(Solver *), void (*reset)(Solver *)) : free_(free), reset_(reset) {}
    SolverPool(const SolverPool &) = delete;
    SolverPool &operator=(const SolverPool &) = delete;
    ~SolverPool() { close(); }

    // A kept solver made with key, reset, or nullptr (the caller makes one).
    Solver *take(const Key &key) {
        for (auto it = kept_.begin(); it != kept_.end(); ++it)
            if (it->first == key) {
                Solver *solver = it->second;
                kept_.erase(it);
                if (reset_) reset_(solver);
                return solver;
            }
        return nullptr;
    }
    // Keeps solver (made with key) for a later call, or frees it: the pool is closed (its
    // model is gone) or full (the oldest solver goes).
    void give(const Key &key, Solver *solver) {
        if (closed_) return free_(solver);
        if (kept_.size() == kMaxKept) {
            free_(kept_.front().second);
            kept_.erase(kept_.begin());
        }
        kept_.emplace_back(key, solver);
    }
    // Frees every kept solver and every one given later (before the model is freed).
    void close() {
        for (auto &k : kept_) free_(k.second);
        kept_.clear();
        closed_ = true;
    }

private:
    static constexpr size_t kMaxKept = 4;  // e.g. both closed-form levels, with and without options
    std::vector<std::pair<Key, Solver *>> kept_;
    void (*free_)(Solver *);
    void (*reset_)(Solver *);
    bool closed_ = false;
};

using OptionValues = std::vector<std::pair<std::string, double>>;
using InversePool = SolverPool<stewart_inverse, OptionValues>;
using ForwardPool = SolverPool<stewart_forward, OptionValues>;
using LinearizePool = SolverPool<stewart_linearize, int>;  // by fidelity
using LimitsPool = SolverPool<stewart_limits, std::optional<double>>;  // by warn_condition

// A solver taken from its pool (or made by the caller) and given back to it when the lease
// ends; freed instead when it was never given a pool.
template <typename Solver, typename Key>
class Lease {
public:
    Lease(std::shared_ptr<SolverPool<Solver, Key>> pool, Key key)
        : pool_(std::move(pool)), key_(std::move(key)), solver(pool_->take(key_)) {}
    ~Lease() {
        if (solver) pool_->give(key_, solver);
    }
    Lease(const Lease &) = delete;
    Lease &operator=(const Lease &) = delete;

private:
    std::shared_ptr<SolverPool<Solver, Key>> pool_;
    Key key_;

public:
    Solver *solver;  // nullptr until taken from the pool or made
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
    ~Model() {
        inverse_pool_->close();
        forward_pool_->close();
        linearize_pool_->close();
        limits_pool_->close();
        stewart_model_free(model_);
    }
    Model(const Model &) = delete;
    Model &operator=(const Model &) = delete;

    // The library's model (the Python Run objects keep this Model alive while they use it).
    const stewart_model *get() const { return model_; }
    // The solvers kept for this model.
    const std::shared_ptr<InversePool> &inverse_pool() const { return inverse_pool_; }
    const std::shared_ptr<ForwardPool> &forward_pool() const { return forward_pool_; }
    const std::shared_ptr<LinearizePool> &linearize_pool() const { return linearize_pool_; }
    const std::shared_ptr<LimitsPool> &limits_pool() const { return limits_pool_; }

private:
    stewart_model *model_ = nullptr;
    std::shared_ptr<InversePool> inverse_pool_ =
        std::make_shared<InversePool>(stewart_inverse_free, stewart_inverse_reset);
    std::shared_ptr<ForwardPool> forward_pool_ =
        std::make_shared<ForwardPool>(stewart_forward_free, stewart_forward_reset);
    std::shared_ptr<LinearizePool> linearize_pool_ =
        std::make_shared<LinearizePool>(stewart_linearize_free, stewart_linearize_reset);
    std::shared_ptr<LimitsPool> limits_pool_ =
        std::make_shared<LimitsPool>(stewart_limits_free, nullptr);  // no history to reset
};

// The data of an output array of n rows, or nullptr for an output the caller skips (None).
template <typename Array>
auto rows_of(std::optional<Array> &a, size_t n) -> decltype(a->data()) {
    if (!a) return nullptr;
    if (a->shape(0) != n) fail("output arrays must have as many rows as the inputs");
    return a->data();
}

// The numpy dtype of a table column's C type.
template <typename T>
constexpr const char *dtype_name() {
    static_assert(std::is_same_v<T, double> || std::is_same_v<T, int> ||
                      (std::is_same_v<T, long> && sizeof(long) == 8),
                  "a table column is double, int or a 64-bit long");
    return std::is_same_v<T, double> ? "float64" : std::is_same_v<T, int> ? "int32" : "int64";
}

// One output column of a direction's table (stewart_outputs.h) as Python sees it: name, values per
// row, numpy dtype, unit, description. Python makes the result arrays from these, so a column
// added to a table reaches the result classes without a binding change.
using ColumnInfo = std::tuple<std::string, int, std::string, std::string, std::string>;
#define STEWART_COLUMN_INFO(name, member, count, type, unit, description)                         \
    ColumnInfo{#name, count, dtype_name<type>(), unit, description},
std::vector<ColumnInfo> inverse_columns() {
    return {STEWART_INVERSE_OUTPUT_TABLE(STEWART_COLUMN_INFO)};
}
std::vector<ColumnInfo> forward_columns() {
    return {STEWART_FORWARD_OUTPUT_TABLE(STEWART_COLUMN_INFO)};
}
std::vector<ColumnInfo> plant_columns() {
    return {STEWART_PLANT_OUTPUT_TABLE(STEWART_COLUMN_INFO)
                STEWART_PLANT_STEP_TABLE(STEWART_COLUMN_INFO)};
}
#undef STEWART_COLUMN_INFO

// The data of outputs[name], an array of n rows of count values of T, C-ordered and never
// converted (a converted copy would take the results); nullptr when outputs has no such column
// (the caller skips it). The arrays are kept in held, so that they outlive the pointers.
template <typename T>
T *table_column(const nb::dict &outputs, const char *name, size_t n, int count,
                std::vector<nb::object> &held) {
    PyObject *item = PyDict_GetItemString(outputs.ptr(), name);  // borrowed; one lookup
    if (!item) return nullptr;
    nb::object a = nb::borrow(item);
    using Array = nb::ndarray<T, nb::c_contig, nb::device::cpu>;
    Array array;
    if (!nb::try_cast<Array>(a, array, false))
        fail((std::string("output ") + name + " must be a C-ordered array of " + dtype_name<T>())
                 .c_str());
    const bool shaped = count == 1 ? array.ndim() == 1
                                   : array.ndim() == 2 && array.shape(1) == size_t(count);
    if (!shaped || array.shape(0) != n)
        fail((std::string("output ") + name + " must have " + std::to_string(n) + " rows of " +
              std::to_string(count) + " values").c_str());
    held.push_back(a);
    return array.data();
}

// The batch outputs of a direction's table bound to the arrays of outputs (name -> array).
#define STEWART_BIND_COLUMN(name, member, count, type, unit, description)                         \
    o.name = table_column<type>(outputs, #name, n, count, held);
stewart_inverse_batch_outputs bind_outputs(stewart_inverse_batch_outputs o, const nb::dict &outputs,
                                           size_t n, std::vector<nb::object> &held) {
    STEWART_INVERSE_OUTPUT_TABLE(STEWART_BIND_COLUMN)
    return o;
}
stewart_forward_batch_outputs bind_outputs(stewart_forward_batch_outputs o, const nb::dict &outputs,
                                           size_t n, std::vector<nb::object> &held) {
    STEWART_FORWARD_OUTPUT_TABLE(STEWART_BIND_COLUMN)
    return o;
}
stewart_plant_batch_outputs bind_outputs(stewart_plant_batch_outputs o, const nb::dict &outputs,
                                         size_t n, std::vector<nb::object> &held) {
    STEWART_PLANT_OUTPUT_TABLE(STEWART_BIND_COLUMN)
    STEWART_PLANT_STEP_TABLE(STEWART_BIND_COLUMN)
    return o;
}
#undef STEWART_BIND_COLUMN

// A batch's outputs (one pointer per column of its X-macro table, at row 0) moved on to row
// `first`: where a batch over rows first.. of the arrays writes.
#define STEWART_SHIFT_COLUMN(name, member, count, type, unit, description)                        \
    if (o.name) o.name += first * (count);
stewart_inverse_batch_outputs from_row(stewart_inverse_batch_outputs o, size_t first) {
    STEWART_INVERSE_OUTPUT_TABLE(STEWART_SHIFT_COLUMN)
    o.status += first;
    return o;
}
stewart_forward_batch_outputs from_row(stewart_forward_batch_outputs o, size_t first) {
    STEWART_FORWARD_OUTPUT_TABLE(STEWART_SHIFT_COLUMN)
    o.status += first;
    return o;
}
#undef STEWART_SHIFT_COLUMN

// A plant, freed with its run.
struct OwnedPlant {
    stewart_plant *solver = nullptr;
    OwnedPlant() = default;
    ~OwnedPlant() { stewart_plant_free(solver); }
    OwnedPlant(const OwnedPlant &) = delete;
    OwnedPlant &operator=(const OwnedPlant &) = delete;
};

// Runs batch(messages, first_failed) -> status over rows [first, stop) of solver with the GIL
// released (the batch numbers rows from first = 0). Returns (status of the first failing row or
// 0, its index or stop, its message, [(row, message)] of up to max_messages failing rows), rows
// numbered in the whole call; a failure before any row raises ValueError.
template <typename T, typename Batch>
BatchResult run_rows(T *solver, const char *(*message)(const T *), size_t first, size_t stop,
                     size_t max_messages, Batch batch) {
    if (first > stop) fail("rows: first must not be after stop");
    MessageBuffer messages(max_messages);
    size_t first_failed = stop - first;
    stewart_status status;
    std::string first_message;
    {
        nb::gil_scoped_release release;
        status = batch(&messages.c, &first_failed);
        first_message = message(solver);
    }
    if (status != STEWART_OK && first_failed == stop - first) fail(first_message.c_str());
    Messages kept = messages.kept();
    for (auto &m : kept) m.first += first;
    return {status, first + first_failed, first_message, kept};
}

// One Platform.inverse call: its arrays and one inverse solver, made once. rows(a, b) solves rows
// [a, b) continuing from the rows before (the full level's warm start), so that slices give the
// numbers of one batch and Python can take Ctrl-C between them.
class InverseRun {
public:
    InverseRun(const Model &model, Poses q, std::optional<Poses> q_dot,
               std::optional<Poses> q_ddot, const OptionValues &option_values,
               const nb::dict &outputs, Column<int> status)
        : n_(q.shape(0)), q_(q), q_dot_(q_dot), q_ddot_(q_ddot), status_(status),
          inverse_(model.inverse_pool(), option_values) {
        if ((q_dot && q_dot->shape(0) != n_) || (q_ddot && q_ddot->shape(0) != n_))
            fail("rates and accels must have as many rows as the poses");
        if (status.shape(0) != n_) fail("output arrays must have as many rows as the poses");
        out_ = bind_outputs(out_, outputs, n_, held_);
        out_.status = status.data();
        if (inverse_.solver) return;
        const stewart_inverse_options options = options_by_name(kInverseOptions, option_values);
        char message[STEWART_MESSAGE_SIZE];
        inverse_.solver = stewart_inverse_create(model.get(), &options, message, sizeof message);
        if (!inverse_.solver) fail(message);  // the options were checked: memory is short
    }

    // Solves rows [first, stop). Returns as run_rows.
    BatchResult rows(size_t first, size_t stop, size_t max_messages) {
        if (stop > n_) fail("rows: stop is beyond the last row");
        const stewart_inverse_batch_outputs out = from_row(out_, first);
        return run_rows(inverse_.solver, stewart_inverse_message, first, stop, max_messages,
                        [&](stewart_batch_messages *messages, size_t *first_failed) {
            return stewart_inverse_batch(inverse_.solver, stop - first, q_.data() + 6 * first,
                                         q_dot_ ? q_dot_->data() + 6 * first : nullptr,
                                         q_ddot_ ? q_ddot_->data() + 6 * first : nullptr, &out,
                                         messages, first_failed);
        });
    }

private:
    size_t n_;
    Poses q_;
    std::optional<Poses> q_dot_, q_ddot_;
    // The output arrays, held so that they outlive the pointers in out_.
    Column<int> status_;
    std::vector<nb::object> held_;
    stewart_inverse_batch_outputs out_{};
    // The solver, from the model's pool and back to it when the run is freed.
    Lease<stewart_inverse, OptionValues> inverse_;
};

// One Platform.forward call: its arrays and one forward solver, made once (a cold start, or
// row 0 from guess). rows(a, b) tracks rows [a, b) on from the rows before, as one batch would.
class ForwardRun {
public:
    ForwardRun(const Model &model, Poses lengths, std::optional<Poses> rates,
               std::optional<Poses> accels, std::optional<Times> time,
               std::optional<Column<const double>> guess, bool cold,
               const std::vector<std::pair<std::string, double>> &option_values,
               const nb::dict &outputs, Column<int> status)
        : n_(lengths.shape(0)), lengths_(lengths), rates_(rates), accels_(accels), time_(time),
          guess_(guess), cold_(cold), status_(status),
          forward_(model.forward_pool(), option_values) {
        if ((rates && rates->shape(0) != n_) || (accels && accels->shape(0) != n_) ||
            (time && time->shape(0) != n_))
            fail("t, rates and accels must have as many rows as the lengths");
        if (accels && !rates) fail("accels need rates");
        if (guess && guess->shape(0) != (cold ? 6 * n_ : 6))
            fail(cold ? "guess must have 6 values per row" : "guess must have 6 values");
        if (cold && time) fail("rows solved cold have no time");
        if (status.shape(0) != n_) fail("output arrays must have as many rows as the lengths");
        std::optional<stewart_forward_options> options;  // of a solver still to make
        if (!forward_.solver) options = options_by_name(kForwardOptions, option_values);
        out_ = bind_outputs(out_, outputs, n_, held_);
        out_.status = status.data();
        if (!options) return;
        char message[STEWART_MESSAGE_SIZE];
        forward_.solver = stewart_forward_create(model.get(), &*options, message, sizeof message);
        if (!forward_.solver) fail(message);
    }

    // Solves rows [first, stop) (the guess only for row 0; cold: each row from its own guess
    // or home). Returns as run_rows.
    BatchResult rows(size_t first, size_t stop, size_t max_messages) {
        if (stop > n_) fail("rows: stop is beyond the last row");
        const stewart_forward_batch_outputs out = from_row(out_, first);
        if (cold_)
            return run_rows(forward_.solver, stewart_forward_message, first, stop, max_messages,
                            [&](stewart_batch_messages *messages, size_t *first_failed) {
                return stewart_forward_batch_cold(
                    forward_.solver, stop - first, lengths_.data() + 6 * first,
                    rates_ ? rates_->data() + 6 * first : nullptr,
                    accels_ ? accels_->data() + 6 * first : nullptr,
                    guess_ ? guess_->data() + 6 * first : nullptr, &out, messages, first_failed);
            });
        const double *guess = guess_ && first == 0 ? guess_->data() : nullptr;
        return run_rows(forward_.solver, stewart_forward_message, first, stop, max_messages,
                        [&](stewart_batch_messages *messages, size_t *first_failed) {
            return stewart_forward_batch(forward_.solver, stop - first,
                                         time_ ? time_->data() + first : nullptr,
                                         lengths_.data() + 6 * first,
                                         rates_ ? rates_->data() + 6 * first : nullptr,
                                         accels_ ? accels_->data() + 6 * first : nullptr, guess,
                                         &out, messages, first_failed);
        });
    }

private:
    size_t n_;
    Poses lengths_;
    std::optional<Poses> rates_, accels_;
    std::optional<Times> time_;
    std::optional<Column<const double>> guess_;
    bool cold_;
    // The output arrays, held so that they outlive the pointers in out_.
    Column<int> status_;
    std::vector<nb::object> held_;
    stewart_forward_batch_outputs out_{};
    // The solver, from the model's pool and back to it (reset when taken again) when the run is
    // freed.
    Lease<stewart_forward, OptionValues> forward_;
};

// One Platform.simulate call: its arrays and one plant, made once. rows(a, b) runs the
// communication points [a, b) on from where the rows before left the plant (row 0 is the start
// state), so that slices give the numbers of one run.
class PlantRun {
public:
    PlantRun(const Model &model, Times time, Poses force,
             std::optional<Column<const double>> start_pose,
             std::optional<Column<const double>> start_rate,
             const std::vector<std::pair<std::string, double>> &option_values,
             const nb::dict &outputs, Column<int> status)
        : n_(time.shape(0)), time_(time), force_(force), start_pose_(start_pose),
          start_rate_(start_rate), status_(status) {
        if (force.shape(0) != n_) fail("forces must have as many rows as t");
        if ((start_pose && start_pose->shape(0) != 6) || (start_rate && start_rate->shape(0) != 6))
            fail("start and start_rate must have 6 values");
        if (status.shape(0) != n_) fail("output arrays must have as many rows as t");
        const stewart_plant_options options = options_by_name(kPlantOptions, option_values);
        out_ = bind_outputs(out_, outputs, n_, held_);
        out_.status = status.data();
        char message[STEWART_MESSAGE_SIZE] = "";
        {
            nb::gil_scoped_release release;
            plant_.solver = stewart_plant_create(model.get(), &options, message, sizeof message);
        }
        if (!plant_.solver) {  // the message says why: the model and options, or memory
            if (std::string(message).find("out of memory") != std::string::npos)
                throw std::bad_alloc();
            fail(message);
        }
    }

    // Runs rows [first, stop). Returns (status of the row that stopped the run or 0, its index
    // or stop, its message); a refused step marks every later row of the run not run.
    std::tuple<int, size_t, std::string> rows(size_t first, size_t stop) {
        if (first > stop || stop > n_) fail("rows: need first <= stop <= the number of rows");
        char message[STEWART_MESSAGE_SIZE] = "";
        size_t first_failed = stop;
        stewart_status status;
        {
            nb::gil_scoped_release release;
            size_t row = 0;
            stewart_batch_messages messages = {1, 0, &row, message};
            status = stewart_plant_batch_rows(plant_.solver, n_, first, stop, time_.data(),
                                              force_.data(),
                                              start_pose_ ? start_pose_->data() : nullptr,
                                              start_rate_ ? start_rate_->data() : nullptr, &out_,
                                              &messages, &first_failed);
        }
        if (status == STEWART_ERR_MEMORY && first_failed == stop) throw std::bad_alloc();
        return {status, first_failed, std::string(message)};
    }

    // The integrator's totals by name, over the rows run so far.
    std::vector<std::pair<std::string, double>> statistics() const {
        stewart_plant_statistics stats{};
        stewart_plant_statistics_get(plant_.solver, &stats);
        return {{"steps", double(stats.total_steps)},
                {"rhs_evaluations", double(stats.total_rhs_evaluations)},
                {"nonlinear_iterations", double(stats.total_nonlinear_iterations)},
                {"error_test_failures", double(stats.total_error_test_failures)},
                {"jacobian_evaluations", double(stats.total_jacobian_evaluations)},
                {"last_order", double(stats.last_order)},
                {"last_step_size", stats.last_step_size}};
    }

private:
    size_t n_;
    Times time_;
    Poses force_;
    std::optional<Column<const double>> start_pose_, start_rate_;
    // The output arrays, held so that they outlive the pointers in out_.
    Column<int> status_;
    std::vector<nb::object> held_;
    stewart_plant_batch_outputs out_{};
    OwnedPlant plant_;
};

// A linearisation of model at fidelity from the model's pool, or ValueError with the library's
// message. Used with the GIL held throughout.
struct Linearization {
    Linearization(const Model &model, int fidelity) : lease(model.linearize_pool(), fidelity) {
        if (lease.solver) return;
        stewart_linearize_options o;
        stewart_linearize_options_default(&o);
        o.fidelity = fidelity;
        char message[STEWART_MESSAGE_SIZE];
        lease.solver = stewart_linearize_create(model.get(), &o, message, sizeof message);
        if (!lease.solver) fail(message);
    }
    Lease<stewart_linearize, int> lease;
};

// A result array of a linearisation, of a fixed shape, which the caller makes.
template <size_t... Shape>
using Fixed = nb::ndarray<double, nb::shape<Shape...>, nb::c_contig, nb::device::cpu>;

// Copies the n values at first into a (of n values).
template <typename Array>
void put(const double *first, Array &a) {
    std::copy_n(first, a.size(), a.data());
}

// Platform.linearize's call, into the caller's arrays: (status, message, warnings).
std::tuple<int, std::string, int> linearize_plant(
    const Model &model, int fidelity, const std::vector<double> &q,
    const std::vector<double> &q_dot, const std::vector<double> &force, Fixed<12> state_rate,
    Fixed<24> output, Fixed<12, 12> A, Fixed<12, 6> B, Fixed<24, 12> C, Fixed<24, 6> D) {
    if (q.size() != 6 || q_dot.size() != 6 || force.size() != 6)
        fail("linearize: pose, pose_rate and forces need 6 values each");
    Linearization l(model, fidelity);
    stewart_linearize_input in{};
    std::copy(q.begin(), q.end(), in.pose.q);
    std::copy(q_dot.begin(), q_dot.end(), in.pose.q_dot);
    std::copy(force.begin(), force.end(), in.force);
    stewart_linearize_output out{};
    const stewart_status s = stewart_linearize_plant(l.lease.solver, &in, &out);
    put(out.state_rate, state_rate);
    put(out.output, output);
    put(&out.A[0][0], A);
    put(&out.B[0][0], B);
    put(&out.C[0][0], C);
    put(&out.D[0][0], D);
    return {static_cast<int>(s), stewart_linearize_message(l.lease.solver), out.warnings};
}

// Platform.linearize_inverse's call, into the caller's arrays (L, L_dot, L_ddot, force,
// base_force, base_torque, jacobian): (status, message, warnings).
std::tuple<int, std::string, int> linearize_inverse(
    const Model &model, int fidelity, const std::vector<double> &q,
    const std::vector<double> &q_dot, const std::vector<double> &q_ddot, Fixed<6> length,
    Fixed<6> length_rate, Fixed<6> length_accel, Fixed<6> force, Fixed<3> base_force,
    Fixed<3> base_torque, Fixed<30, 18> jacobian) {
    if (q.size() != 6 || q_dot.size() != 6 || q_ddot.size() != 6)
        fail("linearize_inverse: pose, pose_rate and pose_accel need 6 values each");
    Linearization l(model, fidelity);
    stewart_pose pose{};
    std::copy(q.begin(), q.end(), pose.q);
    std::copy(q_dot.begin(), q_dot.end(), pose.q_dot);
    std::copy(q_ddot.begin(), q_ddot.end(), pose.q_ddot);
    stewart_linearize_inverse_output out{};
    const stewart_status s = stewart_linearize_inverse(l.lease.solver, &pose, &out);
    put(out.lengths.length, length);
    put(out.lengths.length_rate, length_rate);
    put(out.lengths.length_accel, length_accel);
    put(out.force, force);
    put(out.base_force, base_force);
    put(out.base_torque, base_torque);
    put(&out.jacobian[0][0], jacobian);
    return {static_cast<int>(s), stewart_linearize_message(l.lease.solver), out.warnings};
}

// stewart_geometry_jacobian over the rows of poses, into the caller's arrays (rows of 6, 18 and
// 36: leg-major blocks of stewart_geometry_jacobian_output). Returns (-1, "") or the first failing
// row and its message; the rows before it are written.
std::pair<long, std::string> geometry_jacobian_rows(
    const Model &model, Poses poses, Rows<double, 6> length, Rows<double, 6> reading,
    Rows<double, 18> base_joint, Rows<double, 18> platform_joint, Rows<double, 36> tool_frame,
    Rows<double, 36> user_frame, Rows<double, 36> pose) {
    const size_t n = poses.shape(0);
    for (size_t rows : {length.shape(0), reading.shape(0), base_joint.shape(0),
                        platform_joint.shape(0), tool_frame.shape(0), user_frame.shape(0),
                        pose.shape(0)})
        if (rows != n) fail("output arrays must have as many rows as the poses");
    char message[STEWART_MESSAGE_SIZE];
    stewart_geometry_jacobian_output out;
    for (size_t i = 0; i < n; ++i) {
        if (stewart_geometry_jacobian(model.get(), poses.data() + 6 * i, &out, message,
                                      sizeof message) != STEWART_OK)
            return {static_cast<long>(i), message};
        std::copy_n(out.length, 6, length.data() + 6 * i);
        std::copy_n(out.reading, 6, reading.data() + 6 * i);
        std::copy_n(&out.base_joint[0][0], 18, base_joint.data() + 18 * i);
        std::copy_n(&out.platform_joint[0][0], 18, platform_joint.data() + 18 * i);
        std::copy_n(&out.tool_frame[0][0], 36, tool_frame.data() + 36 * i);
        std::copy_n(&out.user_frame[0][0], 36, user_frame.data() + 36 * i);
        std::copy_n(&out.pose[0][0], 36, pose.data() + 36 * i);
    }
    return {-1, ""};
}

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

// The check of every row of q into the arrays (rows as q's); a non-finite row raises ValueError
// naming the row and the component.
void limits_check(const Model &model, Poses q, std::optional<double> warn_condition, Column<int> first,
                  Column<int> failed, Rows<double, STEWART_LIMIT_CLASSES> margin,
                  Rows<int, STEWART_LIMIT_CLASSES> leg, Rows<int, STEWART_LIMIT_CLASSES> other_leg,
                  Column<double> condition) {
    const size_t n = q.shape(0);
    if (first.shape(0) != n || failed.shape(0) != n || margin.shape(0) != n ||
        leg.shape(0) != n || other_leg.shape(0) != n || condition.shape(0) != n)
        fail("output arrays must have as many rows as the poses");
    LimitsObject object(model, warn_condition);
    size_t bad = n;
    {
        nb::gil_scoped_release release;
        for (size_t r = 0; r < n && bad == n; ++r) {
            stewart_limits_input in;
            for (int i = 0; i < 6; ++i) in.q[i] = q(r, i);
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
            }
        }
    }
    if (bad < n)
        fail(("poses row " + std::to_string(bad) + ": " + stewart_limits_message(object.lease.solver)).c_str());
}

// The axis ranges of every row of q: ends (min of the six axes, then max), the class at each
// end and its leg and other leg, in the same order.
void limits_ranges(const Model &model, Poses q, std::optional<double> warn_condition, Rows<double, 12> ends,
                   Rows<int, 12> limit, Rows<int, 12> leg, Rows<int, 12> other_leg) {
    const size_t n = q.shape(0);
    if (ends.shape(0) != n || limit.shape(0) != n || leg.shape(0) != n || other_leg.shape(0) != n)
        fail("output arrays must have as many rows as the poses");
    LimitsObject object(model, warn_condition);
    size_t bad = n;
    {
        nb::gil_scoped_release release;
        for (size_t r = 0; r < n; ++r) {
            stewart_limits_input in;
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
        fail(("poses row " + std::to_string(bad) + ": " + stewart_limits_message(object.lease.solver)).c_str());
}

// The home check of stewart_check.h: its numbers and its text, in a dict.
nb::dict check_home(const Model &model, std::optional<double> warn_condition) {
    stewart_limits_options options;
    stewart_limits_options_default(&options);
    if (warn_condition) options.warn_condition = *warn_condition;
    stewart_check_report r;
    char message[STEWART_MESSAGE_SIZE];
    if (stewart_check_home(model.get(), &options, &r, message, sizeof message) != STEWART_OK)
        fail(message);
    std::string text(stewart_check_text(&r, nullptr, 0) + 1, '\0');
    stewart_check_text(&r, text.data(), text.size());
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

// The parameters a platform file gives, read by `read` (the library's reader of a path or of a
// text): [(name, all its values)], or std::invalid_argument (ValueError) with the message.
template <class Read>
std::vector<std::pair<std::string, std::vector<double>>> platform_fields(Read read) {
    stewart_params params;
    stewart_params_default(&params);
    std::vector<unsigned char> given(static_cast<size_t>(stewart_param_count()));
    char message[STEWART_MESSAGE_SIZE];
    if (read(&params, given.data(), message, sizeof message) != STEWART_OK)
        throw std::invalid_argument(message);
    std::vector<std::pair<std::string, std::vector<double>>> fields;
    for (int i = 0; i < stewart_param_count(); ++i)
        if (given[static_cast<size_t>(i)]) {
            std::vector<double> values;
            for (int e = 0; e < stewart_param(i)->count; ++e)
                values.push_back(*stewart_param_element(&params, i, e));
            fields.emplace_back(stewart_param(i)->name, values);
        }
    return fields;
}

}  // namespace

NB_MODULE(_core, m) {
    m.doc() = "The C library of the Stewart platform solver (use the stewart package instead).";
    nb::class_<Model>(m, "Model")
        .def(nb::init<const std::vector<std::pair<std::string, double>> &>(),
             nb::arg("assignments"));
    // The run objects keep their Model alive (keep_alive<1, 2>) and hold their arrays.
    nb::class_<InverseRun>(m, "InverseRun")
        .def(nb::init<const Model &, Poses, std::optional<Poses>, std::optional<Poses>,
                      const std::vector<std::pair<std::string, double>> &, const nb::dict &,
                      Column<int>>(),
             nb::keep_alive<1, 2>(), nb::arg("model"), nb::arg("q"), nb::arg("q_dot").none(),
             nb::arg("q_ddot").none(), nb::arg("options"), nb::arg("outputs"), nb::arg("status"))
        .def("rows", &InverseRun::rows, nb::arg("first"), nb::arg("stop"),
             nb::arg("max_messages"));
    nb::class_<ForwardRun>(m, "ForwardRun")
        .def(nb::init<const Model &, Poses, std::optional<Poses>, std::optional<Poses>,
                      std::optional<Times>, std::optional<Column<const double>>, bool,
                      const std::vector<std::pair<std::string, double>> &, const nb::dict &,
                      Column<int>>(),
             nb::keep_alive<1, 2>(), nb::arg("model"), nb::arg("lengths"),
             nb::arg("rates").none(), nb::arg("accels").none(), nb::arg("time").none(),
             nb::arg("guess").none(), nb::arg("cold"), nb::arg("options"), nb::arg("outputs"),
             nb::arg("status"))
        .def("rows", &ForwardRun::rows, nb::arg("first"), nb::arg("stop"),
             nb::arg("max_messages"));
    nb::class_<PlantRun>(m, "PlantRun")
        .def(nb::init<const Model &, Times, Poses, std::optional<Column<const double>>,
                      std::optional<Column<const double>>,
                      const std::vector<std::pair<std::string, double>> &, const nb::dict &,
                      Column<int>>(),
             nb::keep_alive<1, 2>(), nb::arg("model"), nb::arg("time"), nb::arg("force"),
             nb::arg("start_pose").none(), nb::arg("start_rate").none(), nb::arg("options"),
             nb::arg("outputs"), nb::arg("status"))
        .def("rows", &PlantRun::rows, nb::arg("first"), nb::arg("stop"))
        .def("statistics", &PlantRun::statistics);
    m.def("linearize_plant", &linearize_plant, nb::arg("model"), nb::arg("fidelity"),
          nb::arg("q"), nb::arg("q_dot"), nb::arg("force"), nb::arg("state_rate"),
          nb::arg("output"), nb::arg("A"), nb::arg("B"), nb::arg("C"), nb::arg("D"));
    m.def("linearize_inverse", &linearize_inverse, nb::arg("model"), nb::arg("fidelity"),
          nb::arg("q"), nb::arg("q_dot"), nb::arg("q_ddot"), nb::arg("length"),
          nb::arg("length_rate"), nb::arg("length_accel"), nb::arg("force"),
          nb::arg("base_force"), nb::arg("base_torque"), nb::arg("jacobian"));
    m.def("geometry_jacobian", &geometry_jacobian_rows, nb::arg("model"), nb::arg("poses"),
          nb::arg("length"), nb::arg("reading"), nb::arg("base_joint"), nb::arg("platform_joint"),
          nb::arg("tool_frame"), nb::arg("user_frame"), nb::arg("pose"));
    // The joint centres the model uses: (base_joint, platform_joint), 18 values each.
    m.def("model_joints", [](const Model &model) {
        std::vector<double> base(18), platform(18);
        stewart_model_joints(model.get(), base.data(), platform.data());
        return std::make_pair(base, platform);
    });
    m.def("limits_check", &limits_check, nb::arg("model"), nb::arg("q"),
          nb::arg("warn_condition").none(), nb::arg("first"), nb::arg("failed"), nb::arg("margin"),
          nb::arg("leg"), nb::arg("other_leg"), nb::arg("condition"));
    m.def("limits_ranges", &limits_ranges, nb::arg("model"), nb::arg("q"),
          nb::arg("warn_condition").none(), nb::arg("ends"), nb::arg("limit"), nb::arg("leg"),
          nb::arg("other_leg"));
    m.def("check_home", &check_home, nb::arg("model"), nb::arg("warn_condition").none());
    m.attr("CHECK_UNITS") = STEWART_CHECK_UNITS;
    m.attr("CHECK_SWAPPED_LEGS") = STEWART_CHECK_SWAPPED_LEGS;
    m.attr("CHECK_FRAME") = STEWART_CHECK_FRAME;
    m.def("limit_class_name", [](int c) { return std::string(stewart_limit_class_name(c)); });
    m.attr("LIMIT_CLASSES") = STEWART_LIMIT_CLASSES;
    m.attr("BATCH_NOT_RUN") = STEWART_BATCH_NOT_RUN;
    // A platform file read by the library (stewart_params_read_json_file): [(name, values)] of the parameters it gives, each with all its
    // elements in SI; ValueError with the library's message (line, column, field and value) if
    // any field is bad, or the path is not a regular file of at most the size cap.
    m.def("read_platform_file", [](const std::string &path) {
        return platform_fields([&](stewart_params *p, unsigned char *given, char *message, size_t size) {
            return stewart_params_read_json_file(p, path.c_str(), given, message, size);
        });
    });
    m.attr("PLATFORM_FILE_MAX_BYTES") = STEWART_PLATFORM_FILE_MAX_BYTES;
    // (True, "") if the library knows the parameter name, else (False, its message).
    m.def("parameter_known", [](const std::string &name) {
        stewart_params scratch;
        stewart_params_default(&scratch);
        char message[STEWART_MESSAGE_SIZE];
        const bool known = stewart_params_set(&scratch, name.c_str(), 0.0, message,
                                              sizeof message) == STEWART_OK;
        return std::make_pair(known, std::string(known ? "" : message));
    });
    m.def("inverse_columns", &inverse_columns,
          "(name, values per row, dtype, unit, description) of each inverse output column");
    m.def("forward_columns", &forward_columns,
          "(name, values per row, dtype, unit, description) of each forward output column");
    m.def("plant_columns", &plant_columns,
          "(name, values per row, dtype, unit, description) of each plant output column");
    m.def("option_table", [](const std::string &direction) {
        if (direction == "inverse") return option_table(stewart_inverse_option_count, stewart_inverse_option);
        if (direction == "forward") return option_table(stewart_forward_option_count, stewart_forward_option);
        if (direction == "plant") return option_table(stewart_plant_option_count, stewart_plant_option);
        fail(("no option table '" + direction + "': inverse, forward or plant").c_str());
    }, nb::arg("direction"),
          "The library's option table of a direction (inverse, forward, plant): one dict per "
          "option (name, id, integer, unit, min, max, min_closed, max_closed, default, "
          "description)");
    m.def("status_name", [](int s) { return std::string(stewart_status_name(static_cast<stewart_status>(s))); });
    // The library's parameter table: one dict per parameter (name, count, unit, description,
    // defaults, min, max, scalar_fills: one value by the bare name sets every leg).
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
            entry["scalar_fills"] = stewart_param_fills_from_scalar(i) != 0;
            table.append(entry);
        }
        return table;
    });
}
