// stewart._core's inverse: one run object per Platform.inverse call (inverse.py), its solver
// from the model's pool, its rows solved a slice at a time.
#include "_core.hpp"

namespace stewart_core {

namespace {

const OptionTable<stewart_inverse_options> kInverseOptions = {
    "solver", stewart_inverse_options_default, stewart_inverse_option_find,
    stewart_inverse_option_set, stewart_inverse_options_check};

// place_outputs, placement_columns, from_row and bind_outputs of the inverse table.
STEWART_OUTPUT_BINDINGS(stewart_inverse_batch_outputs, STEWART_INVERSE_OUTPUT_TABLE)
STEWART_OUTPUTS_BY_NAME(stewart_inverse_batch_outputs, STEWART_INVERSE_OUTPUT_TABLE)

// One Platform.inverse call: its arrays and one inverse solver, made once. rows(a, b) solves rows
// [a, b) continuing from the rows before (the full level's warm start), so that slices give the
// numbers of one batch and Python can take Ctrl-C between them.
class InverseRun {
public:
    // out: the batch outputs, bound to arrays that held keeps alive.
    InverseRun(const Model &model, Poses q, std::optional<Poses> q_dot, std::optional<Poses> q_ddot,
               const OptionValues &option_values, stewart_inverse_batch_outputs out,
               std::vector<nb::object> held)
        : model_(model.get()), n_(q.shape(0)), q_(q), q_dot_(q_dot), q_ddot_(q_ddot),
          held_(std::move(held)), out_(out), inverse_(model.inverse_pool(), option_values) {
        if ((q_dot && q_dot->shape(0) != n_) || (q_ddot && q_ddot->shape(0) != n_))
            fail("rates and accels must have as many rows as the poses");
        if (inverse_.solver) return;
        const stewart_inverse_options options = options_by_name(kInverseOptions, option_values);
        char message[STEWART_MESSAGE_SIZE];
        inverse_.solver = stewart_inverse_create(model.get(), &options, message, sizeof message);
        if (!inverse_.solver) fail(message);  // the options were checked: memory is short
    }

    // Solves rows [first, stop). Returns as run_rows.
    Messages rows(size_t first, size_t stop, size_t max_messages) {
        if (stop > n_) fail("rows: stop is beyond the last row");
        const stewart_inverse_batch_outputs out = from_row(out_, first);
        return run_rows(inverse_.solver, stewart_inverse_message, first, stop, max_messages,
                        [&](stewart_batch_messages *messages, size_t *first_failed) {
                            return stewart_inverse_batch(
                                inverse_.solver, stop - first, q_.data() + 6 * first,
                                q_dot_ ? q_dot_->data() + 6 * first : nullptr,
                                q_ddot_ ? q_ddot_->data() + 6 * first : nullptr, &out, messages,
                                first_failed);
                        });
    }

    // Along a trajectory at times t (n): the drives' current rates and the voltages with them
    // (stewart_inverse_batch_current_rates), once every row is solved.
    void current_rates(Column<const double> t) {
        if (t.shape(0) != n_) fail("t must have as many rows as the poses");
        char message[STEWART_MESSAGE_SIZE];
        if (stewart_inverse_batch_current_rates(model_, n_, t.data(), &out_, message,
                                                sizeof message) != STEWART_OK)
            fail(message);
    }

    // With the poses' jerks (n x 6): the drives' current rates from them at the inverse's
    // fidelity (stewart_inverse_batch_current_rates_from_jerks), once every row is solved.
    void current_rates_from_jerks(int fidelity, Poses q_dddot) {
        if (q_dddot.shape(0) != n_) fail("jerks must have as many rows as the poses");
        char message[STEWART_MESSAGE_SIZE];
        if (stewart_inverse_batch_current_rates_from_jerks(model_, fidelity, n_, q_.data(),
                                                           q_dot_ ? q_dot_->data() : nullptr,
                                                           q_ddot_ ? q_ddot_->data() : nullptr,
                                                           q_dddot.data(), &out_, message,
                                                           sizeof message) != STEWART_OK)
            fail(message);
    }

private:
    const stewart_model *model_;
    size_t n_;
    Poses q_;
    std::optional<Poses> q_dot_, q_ddot_;
    // The output arrays (or their block), held so that they outlive the pointers in out_.
    std::vector<nb::object> held_;
    stewart_inverse_batch_outputs out_{};
    // The solver, from the model's pool and back to it when the run is freed.
    Lease<stewart_inverse, OptionValues> inverse_;
};

}  // namespace

// The run object keeps its Model alive (keep_alive<1, 2>) and holds its arrays: a new result's
// as their block and its placement (made by inverse_placement; bound by their offsets), or an
// earlier result's by name (outputs, each checked). The block comes first: nanobind tries the
// overloads in order, converting every argument, and a new result is the common call.
void bind_inverse(nb::module_ &m) {
    nb::class_<InverseRun>(m, "InverseRun")
        .def(
            "__init__",
            [](InverseRun *self, const Model &model, Poses q, std::optional<Poses> q_dot,
               std::optional<Poses> q_ddot, const OptionValues &options, Column<uint8_t> block,
               const Placement &placement) {
                uint8_t *data = placement.data(block, q.shape(0));
                new (self) InverseRun(model, q, q_dot, q_ddot, options,
                                      place_outputs({}, data, placement), {nb::cast(block)});
            },
            nb::keep_alive<1, 2>(), nb::arg("model"), nb::arg("q"), nb::arg("q_dot").none(),
            nb::arg("q_ddot").none(), nb::arg("options"), nb::arg("block"), nb::arg("placement"))
        .def(
            "__init__",
            [](InverseRun *self, const Model &model, Poses q, std::optional<Poses> q_dot,
               std::optional<Poses> q_ddot, const OptionValues &options, const nb::dict &outputs,
               Column<int> status) {
                const size_t n = q.shape(0);
                if (status.shape(0) != n) fail("output arrays must have as many rows as the poses");
                std::vector<nb::object> held;
                stewart_inverse_batch_outputs out = bind_outputs({}, outputs, n, held);
                out.status = status.data();
                held.push_back(nb::cast(status));
                new (self) InverseRun(model, q, q_dot, q_ddot, options, out, std::move(held));
            },
            nb::keep_alive<1, 2>(), nb::arg("model"), nb::arg("q"), nb::arg("q_dot").none(),
            nb::arg("q_ddot").none(), nb::arg("options"), nb::arg("outputs"), nb::arg("status"))
        .def("rows", &InverseRun::rows, nb::arg("first"), nb::arg("stop"), nb::arg("max_messages"))
        .def("current_rates", &InverseRun::current_rates, nb::arg("t"))
        .def("current_rates_from_jerks", &InverseRun::current_rates_from_jerks, nb::arg("fidelity"),
             nb::arg("q_dddot"));
    // Where a new result's arrays lie in its block: for rows rows, a block of bytes bytes, the
    // byte offset of each inverse output column then status's (-1: a column left alone).
    m.def(
        "inverse_placement",
        [](size_t rows, size_t bytes, std::vector<long> offsets) {
            return Placement(placement_columns(), rows, bytes, std::move(offsets));
        },
        nb::arg("rows"), nb::arg("bytes"), nb::arg("offsets"));
}

}  // namespace stewart_core
