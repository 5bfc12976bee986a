// What the files of stewart._core share (the nanobind extension over the C API; one file per
// direction: core_inverse.cpp, core_forward.cpp, core_plant.cpp, core_linearize.cpp,
// core_limits.cpp; the model and its parameters in core_model.cpp; the tables Python reads in
// core_tables.cpp; the module in _core.cpp): array types, errors, the option tables' setter, the
// batch helpers and the Model with the solvers it keeps.
#pragma once

#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/pair.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/tuple.h>
#include <nanobind/stl/vector.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

extern "C" {
#include "stewart/stewart.h"
#include "stewart/stewart_batch.h"
#include "stewart/stewart_forward.h"
#include "stewart/stewart_linearize.h"
#include "stewart/stewart_limits.h"
#include "stewart/stewart_plant.h"
#include "stewart/stewart_table.h"
}

namespace nb = nanobind;

namespace stewart_core {

template <typename T, size_t W>
using Rows = nb::ndarray<T, nb::shape<-1, W>, nb::c_contig, nb::device::cpu>;
template <typename T>
using Column = nb::ndarray<T, nb::shape<-1>, nb::c_contig, nb::device::cpu>;
using Poses = Rows<const double, 6>;
using Times = Column<const double>;
using Messages = std::vector<std::pair<size_t, std::string>>;

// A Python ValueError subclass defined in stewart/errors.py is raised from Python; here the
// C messages travel as ValueError (bad parameters, options) and the caller re-raises.
[[noreturn]] inline void fail(const char *message) { throw nb::value_error(message); }

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
template <typename Options>
struct OptionTable {
    const char *kind;  // in the message for an unknown name
    void (*defaults)(Options *);
    int (*find)(const char *);
    stewart_status (*set)(Options *, int, double, char *, size_t);
    stewart_status (*check)(const Options *, char *, size_t);
};

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

// Solvers of one kind (inverse, forward, linearisation, limits) kept between calls on one Model
// by the key they were made with (their option values): creating one costs as much as solving
// tens to hundreds of rows, which a call of a few rows would otherwise pay every time. A solver
// is reset when taken (these solvers' reset leaves them as created: nothing carries over from
// an earlier call), so a call's numbers are those of a new solver. Taking and giving back hold the
// pool's lock, so that two threads never get the same one, with or without the GIL (free-threaded
// Python).
template <typename Solver, typename Key>
class SolverPool {
public:
    SolverPool(void (*free)(Solver *), void (*reset)(Solver *)) : free_(free), reset_(reset) {}
    SolverPool(const SolverPool &) = delete;
    SolverPool &operator=(const SolverPool &) = delete;
    ~SolverPool() { close(); }

    // A kept solver made with key, reset, or nullptr (the caller makes one).
    Solver *take(const Key &key) {
        std::lock_guard<std::mutex> hold(lock_);
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
        std::lock_guard<std::mutex> hold(lock_);
        if (closed_) return free_(solver);
        if (kept_.size() == kMaxKept) {
            free_(kept_.front().second);
            kept_.erase(kept_.begin());
        }
        kept_.emplace_back(key, solver);
    }
    // Frees every kept solver and every one given later (before the model is freed).
    void close() {
        std::lock_guard<std::mutex> hold(lock_);
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
    std::mutex lock_;
};

using OptionValues = std::vector<std::pair<std::string, double>>;
using InversePool = SolverPool<stewart_inverse, OptionValues>;
using ForwardPool = SolverPool<stewart_forward, OptionValues>;
using LinearizePool = SolverPool<stewart_linearize, int>;              // by fidelity
using LimitsPool = SolverPool<stewart_limits, std::optional<double>>;  // by warn_condition

// A solver taken from its pool (or, when the pool has none made with key, made by the caller
// into `solver`), given back to the pool when the lease ends.
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
    explicit Model(const std::vector<std::pair<std::string, double>> &assignments);
    ~Model();
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

// The numpy dtype of a table column's C type.
template <typename T>
constexpr const char *dtype_name() {
    static_assert(std::is_same_v<T, double> || std::is_same_v<T, int> ||
                      (std::is_same_v<T, long> && sizeof(long) == 8),
                  "a table column is double, int or a 64-bit long");
    return std::is_same_v<T, double> ? "float64" : std::is_same_v<T, int> ? "int32" : "int64";
}

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
    const bool shaped =
        count == 1 ? array.ndim() == 1 : array.ndim() == 2 && array.shape(1) == size_t(count);
    if (!shaped || array.shape(0) != n)
        fail((std::string("output ") + name + " must have " + std::to_string(n) + " rows of " +
              std::to_string(count) + " values")
                 .c_str());
    held.push_back(a);
    return array.data();
}

// Where a result's arrays lie in its block (results.py table_arrays): per column of a direction's
// output table, then status, the byte offset of its row 0, or -1 for a column the batch leaves
// alone. Made once per (direction, rows, columns left alone) and kept by Python, so that a call
// binds its outputs by arithmetic, not by checking two dozen arrays. Checked when made: every
// column lies inside `bytes`, aligned for its type, and no two overlap; a block takes it when it
// has `bytes` bytes and starts aligned for every column's type.
class Placement {
public:
    struct ColumnSize {
        size_t row_bytes, align;
    };
    Placement(const std::vector<ColumnSize> &columns, size_t rows, size_t bytes,
              std::vector<long> offsets)
        : rows_(rows), bytes_(bytes), offsets_(std::move(offsets)) {
        if (offsets_.size() != columns.size())
            fail(("a placement needs " + std::to_string(columns.size()) + " offsets").c_str());
        std::vector<std::pair<size_t, size_t>> spans;  // [start, end) of each placed column
        for (size_t i = 0; i < columns.size(); ++i) {
            const long o = offsets_[i];
            if (o < 0) continue;
            if (size_t(o) % columns[i].align != 0 || size_t(o) > bytes ||
                rows > (bytes - size_t(o)) / columns[i].row_bytes)
                fail(("placement column " + std::to_string(i) + " at " + std::to_string(o) +
                      " is misaligned or beyond the block")
                         .c_str());
            align_ = std::max(align_, columns[i].align);
            spans.emplace_back(size_t(o), size_t(o) + rows * columns[i].row_bytes);
        }
        std::sort(spans.begin(), spans.end());
        for (size_t i = 1; i < spans.size(); ++i)
            if (spans[i].first < spans[i - 1].second)
                fail(("placement columns overlap at byte " + std::to_string(spans[i].first))
                         .c_str());
    }
    size_t rows() const { return rows_; }
    // The block's data if it holds the placement (rows as the call's, at least `bytes` bytes).
    uint8_t *data(Column<uint8_t> block, size_t rows) const {
        if (rows != rows_ || block.shape(0) < bytes_ ||
            reinterpret_cast<uintptr_t>(block.data()) % align_ != 0)
            fail("the result block does not match its placement");
        return block.data();
    }
    template <typename T>
    T *column(uint8_t *data, size_t i) const {
        return offsets_[i] < 0 ? nullptr : reinterpret_cast<T *>(data + offsets_[i]);
    }

private:
    size_t rows_, bytes_, align_ = 1;
    std::vector<long> offsets_;
};

// A Placement::ColumnSize per column of an output table.
#define STEWART_PLACEMENT_COLUMN(name, member, count, type, unit, description) \
    Placement::ColumnSize{size_t(count) * sizeof(type), alignof(type)},

// The batch outputs of a direction's table bound to the arrays of outputs (name -> array).
#define STEWART_BIND_COLUMN(name, member, count, type, unit, description) \
    o.name = table_column<type>(outputs, #name, n, count, held);

// A batch's outputs (one pointer per column of its X-macro table, at row 0) moved on to row
// `first`: where a batch over rows first.. of the arrays writes.
#define STEWART_SHIFT_COLUMN(name, member, count, type, unit, description) \
    if (o.name) o.name += first * (count);

// A batch's output bound to its column of a block (Placement).
#define STEWART_PLACE_COLUMN(name, member, count, type, unit, description) \
    o.name = placement.column<type>(data, i++);

// A direction's place_outputs (its batch outputs bound to a block's columns), placement_columns
// (its table's ColumnSize, then status's) and from_row (moved on to row first), from its output
// table.
#define STEWART_OUTPUT_BINDINGS(Outputs, TABLE)                                                \
    Outputs place_outputs(Outputs o, uint8_t *data, const Placement &placement) {              \
        size_t i = 0;                                                                          \
        TABLE(STEWART_PLACE_COLUMN)                                                            \
        o.status = placement.column<int>(data, i);                                             \
        return o;                                                                              \
    }                                                                                          \
    const std::vector<Placement::ColumnSize> &placement_columns() {                            \
        static const std::vector<Placement::ColumnSize> columns = {                            \
            TABLE(STEWART_PLACEMENT_COLUMN) Placement::ColumnSize{sizeof(int), alignof(int)}}; \
        return columns;                                                                        \
    }                                                                                          \
    Outputs from_row(Outputs o, size_t first) {                                                \
        TABLE(STEWART_SHIFT_COLUMN)                                                            \
        o.status += first;                                                                     \
        return o;                                                                              \
    }

// A direction's bind_outputs: its batch outputs bound to the arrays of outputs (name -> array).
#define STEWART_OUTPUTS_BY_NAME(Outputs, TABLE)                        \
    Outputs bind_outputs(Outputs o, const nb::dict &outputs, size_t n, \
                         std::vector<nb::object> &held) {              \
        TABLE(STEWART_BIND_COLUMN)                                     \
        return o;                                                      \
    }

// Runs batch(messages, first_failed) -> status over rows [first, stop) of solver with the GIL
// released (the batch numbers rows from first = 0). Returns [(row, message)] of up to
// max_messages failing rows, rows numbered in the whole call (each failing row's status is in
// the result's status array); a failure before any row raises ValueError.
template <typename T, typename Batch>
Messages run_rows(T *solver, const char *(*message)(const T *), size_t first, size_t stop,
                  size_t max_messages, Batch batch) {
    if (first > stop) fail("rows: first must not be after stop");
    MessageBuffer messages(max_messages);
    size_t first_failed = stop - first;
    stewart_status status;
    {
        nb::gil_scoped_release release;
        status = batch(&messages.c, &first_failed);
    }
    if (status != STEWART_OK && first_failed == stop - first) fail(message(solver));
    Messages kept = messages.kept();
    for (auto &m : kept) m.first += first;
    return kept;
}

// Each file's part of the module (the functions and classes Python calls).
void bind_model(nb::module_ &m);
void bind_tables(nb::module_ &m);
void bind_inverse(nb::module_ &m);
void bind_forward(nb::module_ &m);
void bind_plant(nb::module_ &m);
void bind_linearize(nb::module_ &m);
void bind_limits(nb::module_ &m);
void bind_cueing(nb::module_ &m);

}  // namespace stewart_core
