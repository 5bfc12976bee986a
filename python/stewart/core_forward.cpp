// stewart._core's forward kinematics: one run object per Platform.forward call (forward.py), its
// solver from the model's pool, its rows tracked a slice at a time.
#include "_core.hpp"

namespace stewart_core {

namespace {

const OptionTable<stewart_forward_options> kForwardOptions = {
    "forward", stewart_forward_options_default, stewart_forward_option_find,
    stewart_forward_option_set, stewart_forward_options_check};

// place_outputs, placement_columns and from_row of the forward table.
STEWART_OUTPUT_BINDINGS(stewart_forward_batch_outputs, STEWART_FORWARD_OUTPUT_TABLE)

// One Platform.forward call: its arrays and one forward solver, made once (a cold start, or
// row 0 from guess). rows(a, b) tracks rows [a, b) on from the rows before, as one batch would.
class ForwardRun {
public:
    // out: the batch outputs, bound to arrays that held keeps alive.
    ForwardRun(const Model &model, Poses lengths, std::optional<Poses> rates,
               std::optional<Poses> accels, std::optional<Times> time,
               std::optional<Column<const double>> guess, bool cold,
               const OptionValues &option_values, stewart_forward_batch_outputs out,
               std::vector<nb::object> held)
        : n_(lengths.shape(0)), lengths_(lengths), rates_(rates), accels_(accels), time_(time),
          guess_(guess), cold_(cold), held_(std::move(held)), out_(out),
          forward_(model.forward_pool(), option_values) {
        if ((rates && rates->shape(0) != n_) || (accels && accels->shape(0) != n_) ||
            (time && time->shape(0) != n_))
            fail("t, rates and accels must have as many rows as the lengths");
        if (accels && !rates) fail("accels need rates");
        if (guess && guess->shape(0) != (cold ? 6 * n_ : 6))
            fail(cold ? "guess must have 6 values per row" : "guess must have 6 values");
        if (cold && time) fail("rows solved cold have no time");
        if (forward_.solver) return;
        const stewart_forward_options options = options_by_name(kForwardOptions, option_values);
        char message[STEWART_MESSAGE_SIZE];
        forward_.solver = stewart_forward_create(model.get(), &options, message, sizeof message);
        if (!forward_.solver) fail(message);
    }

    // Solves rows [first, stop) (the guess only for row 0; cold: each row from its own guess
    // or home). Returns as run_rows.
    Messages rows(size_t first, size_t stop, size_t max_messages) {
        if (stop > n_) fail("rows: stop is beyond the last row");
        const stewart_forward_batch_outputs out = from_row(out_, first);
        if (cold_)
            return run_rows(forward_.solver, stewart_forward_message, first, stop, max_messages,
                            [&](stewart_batch_messages *messages, size_t *first_failed) {
                                return stewart_forward_batch_cold(
                                    forward_.solver, stop - first, lengths_.data() + 6 * first,
                                    rates_ ? rates_->data() + 6 * first : nullptr,
                                    accels_ ? accels_->data() + 6 * first : nullptr,
                                    guess_ ? guess_->data() + 6 * first : nullptr, &out, messages,
                                    first_failed);
                            });
        const double *guess = guess_ && first == 0 ? guess_->data() : nullptr;
        return run_rows(forward_.solver, stewart_forward_message, first, stop, max_messages,
                        [&](stewart_batch_messages *messages, size_t *first_failed) {
                            return stewart_forward_batch(forward_.solver, stop - first,
                                                         time_ ? time_->data() + first : nullptr,
                                                         lengths_.data() + 6 * first,
                                                         rates_ ? rates_->data() + 6 * first
                                                                : nullptr,
                                                         accels_ ? accels_->data() + 6 * first
                                                                 : nullptr,
                                                         guess, &out, messages, first_failed);
                        });
    }

private:
    size_t n_;
    Poses lengths_;
    std::optional<Poses> rates_, accels_;
    std::optional<Times> time_;
    std::optional<Column<const double>> guess_;
    bool cold_;
    // The output arrays (or their block), held so that they outlive the pointers in out_.
    std::vector<nb::object> held_;
    stewart_forward_batch_outputs out_{};
    // The solver, from the model's pool and back to it (reset when taken again) when the run is
    // freed.
    Lease<stewart_forward, OptionValues> forward_;
};

}  // namespace

// The run object keeps its Model alive (keep_alive<1, 2>) and holds its arrays: a new result's,
// as their block and its placement (made by forward_placement; bound by their offsets).
void bind_forward(nb::module_ &m) {
    nb::class_<ForwardRun>(m, "ForwardRun")
        .def(
            "__init__",
            [](ForwardRun *self, const Model &model, Poses lengths, std::optional<Poses> rates,
               std::optional<Poses> accels, std::optional<Times> time,
               std::optional<Column<const double>> guess, bool cold, const OptionValues &options,
               Column<uint8_t> block, const Placement &placement) {
                uint8_t *data = placement.data(block, lengths.shape(0));
                new (self) ForwardRun(model, lengths, rates, accels, time, guess, cold, options,
                                      place_outputs({}, data, placement), {nb::cast(block)});
            },
            nb::keep_alive<1, 2>(), nb::arg("model"), nb::arg("lengths"), nb::arg("rates").none(),
            nb::arg("accels").none(), nb::arg("time").none(), nb::arg("guess").none(),
            nb::arg("cold"), nb::arg("options"), nb::arg("block"), nb::arg("placement"))
        .def("rows", &ForwardRun::rows, nb::arg("first"), nb::arg("stop"), nb::arg("max_messages"));
    // Where a new result's arrays lie in its block: for rows rows, a block of bytes bytes, the
    // byte offset of each forward output column then status's (-1: a column left alone).
    m.def(
        "forward_placement",
        [](size_t rows, size_t bytes, std::vector<long> offsets) {
            return Placement(placement_columns(), rows, bytes, std::move(offsets));
        },
        nb::arg("rows"), nb::arg("bytes"), nb::arg("offsets"));
}

}  // namespace stewart_core
