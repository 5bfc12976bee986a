// stewart._core's forward kinematics: one run object per Platform.forward call (forward.py), its
// solver from the model's pool, its rows tracked a slice at a time.
#include "_core.hpp"

namespace stewart_core {

namespace {

const OptionTable<stewart_forward_options> kForwardOptions = {
    "forward", stewart_forward_options_default, stewart_forward_option_find,
    stewart_forward_option_set, stewart_forward_options_check};

// bind_outputs and from_row of the forward table.
STEWART_OUTPUT_BINDINGS(stewart_forward_batch_outputs, STEWART_FORWARD_OUTPUT_TABLE)

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

}  // namespace

// The run object keeps its Model alive (keep_alive<1, 2>) and holds its arrays.
void bind_forward(nb::module_ &m) {
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
}

}  // namespace stewart_core
