// stewart._core's plant (forward dynamics): one run object per Platform.simulate call
// (simulate.py), its communication points run a slice at a time.
#include "_core.hpp"

#include <new>

namespace stewart_core {

namespace {

const OptionTable<stewart_plant_options> kPlantOptions = {
    "plant", stewart_plant_options_default, stewart_plant_option_find, stewart_plant_option_set,
    stewart_plant_options_check};


// The batch outputs of the plant table bound to the arrays of outputs (name -> array).
stewart_plant_batch_outputs bind_outputs(stewart_plant_batch_outputs o, const nb::dict &outputs,
                                         size_t n, std::vector<nb::object> &held) {
    STEWART_PLANT_OUTPUT_TABLE(STEWART_BIND_COLUMN)
    STEWART_PLANT_STEP_TABLE(STEWART_BIND_COLUMN)
    return o;
}

// A plant, freed with its run.
struct OwnedPlant {
    stewart_plant *solver = nullptr;
    OwnedPlant() = default;
    ~OwnedPlant() { stewart_plant_free(solver); }
    OwnedPlant(const OwnedPlant &) = delete;
    OwnedPlant &operator=(const OwnedPlant &) = delete;
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
            status =
                stewart_plant_batch_rows(plant_.solver, n_, first, stop, time_.data(),
                                         force_.data(), start_pose_ ? start_pose_->data() : nullptr,
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

}  // namespace

// The run object keeps its Model alive (keep_alive<1, 2>) and holds its arrays.
void bind_plant(nb::module_ &m) {
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
}

}  // namespace stewart_core
