// stewart._core's model (platform.py, params.py, calibration): a Model from parameters by name,
// the parameter table, platform files, and the geometry calibration measures.
#include "_core.hpp"

#include <stdexcept>

extern "C" {
#include "stewart/stewart_calibration.h"
#include "stewart/stewart_platform_file.h"
}

namespace stewart_core {

namespace {

// stewart_geometry_jacobian over the rows of poses, into the caller's arrays (rows of 6, 18 and
// 36: leg-major blocks of stewart_geometry_jacobian_output). Returns (-1, "") or the first failing
// row and its message; the rows before it are written.
std::pair<long, std::string> geometry_jacobian_rows(
    const Model &model, Poses poses, Rows<double, 6> length, Rows<double, 6> reading,
    Rows<double, 18> base_joint, Rows<double, 18> platform_joint, Rows<double, 36> tool_frame,
    Rows<double, 36> user_frame, Rows<double, 36> pose) {
    const size_t n = poses.shape(0);
    for (size_t rows :
         {length.shape(0), reading.shape(0), base_joint.shape(0), platform_joint.shape(0),
          tool_frame.shape(0), user_frame.shape(0), pose.shape(0)})
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

Model::Model(const std::vector<std::pair<std::string, double>> &assignments) {
    stewart_params params;
    stewart_params_default(&params);
    char message[STEWART_MESSAGE_SIZE];
    for (const auto &[name, value] : assignments)
        if (stewart_params_set(&params, name.c_str(), value, message, sizeof message) != STEWART_OK)
            fail(message);
    model_ = stewart_model_create(&params, message, sizeof message);
    if (!model_) fail(message);
}
Model::~Model() {
    inverse_pool_->close();
    forward_pool_->close();
    linearize_pool_->close();
    limits_pool_->close();
    stewart_model_free(model_);
}

namespace {

// What a made model holds: its joints, tool frame, drives and geometry Jacobian.
void bind_model_queries(nb::module_ &m) {
    m.def("geometry_jacobian", &geometry_jacobian_rows, nb::arg("model"), nb::arg("poses"),
          nb::arg("length"), nb::arg("reading"), nb::arg("base_joint"), nb::arg("platform_joint"),
          nb::arg("tool_frame"), nb::arg("user_frame"), nb::arg("pose"));
    // The joint centres the model uses: (base_joint, platform_joint), 18 values each.
    m.def("model_joints", [](const Model &model) {
        std::vector<double> base(18), platform(18);
        stewart_model_joints(model.get(), base.data(), platform.data());
        return std::make_pair(base, platform);
    });
    // The tool frame the model uses (x, y, z [m], angles [rad] in the frames the parameters are
    // given in, as stewart_model_joints' joints): every element, however it was set.
    m.def("model_tool_frame", [](const Model &model) {
        const double *t = stewart_model_params(model.get())->tool_frame;
        return std::vector<double>(t, t + 6);
    });
    // The drive's inertia seen on each leg's axis [kg] (stewart_model_reflected_mass).
    m.def("model_reflected_mass", [](const Model &model) {
        std::vector<double> mass(STEWART_LEGS);
        stewart_model_reflected_mass(model.get(), mass.data());
        return mass;
    });
    // Whether some leg has a drive (screw_lead > 0): the batch then writes the drive columns.
    m.def("model_has_drives", [](const Model &model) {
        for (double lead : stewart_model_params(model.get())->screw_lead)
            if (lead > 0) return true;
        return false;
    });
}

// Platform files and the units they are written in.
void bind_platform_files(nb::module_ &m) {
    // A platform file read by the library (stewart_params_read_json_file): [(name, values)] of the parameters it gives, each with all its
    // elements in SI; ValueError with the library's message (line, column, field and value) if
    // any field is bad, or the path is not a regular file of at most the size cap.
    m.def("read_platform_file", [](const std::string &path) {
        return platform_fields([&](stewart_params *p, unsigned char *given, char *message,
                                   size_t size) {
            return stewart_params_read_json_file(p, path.c_str(), given, message, size);
        });
    });
    m.attr("PLATFORM_FILE_MAX_BYTES") = STEWART_PLATFORM_FILE_MAX_BYTES;
    // (length, angle): the units a platform file writes in (stewart_platform_file_units; ""
    // where it states none); ValueError with the library's message.
    m.def("platform_file_units", [](const std::string &path) {
        stewart_file_units units;
        char message[STEWART_MESSAGE_SIZE];
        if (stewart_platform_file_units(path.c_str(), &units, message, sizeof message) !=
            STEWART_OK)
            fail(message);
        return std::make_pair(std::string(units.length), std::string(units.angle));
    });
    // (SI unit, what an SI value is multiplied by to be in name), or None for a name that is no
    // unit (stewart_unit_per_si).
    m.def("unit_per_si",
          [](const std::string &name) -> std::optional<std::pair<std::string, double>> {
              double per_si = 0;
              const char *si = stewart_unit_per_si(name.c_str(), &per_si);
              if (!si) return std::nullopt;
              return std::make_pair(std::string(si), per_si);
          });
}

// The library's parameter table.
void bind_parameter_table(nb::module_ &m) {
    // (True, "") if the library knows the parameter name, else (False, its message).
    m.def("parameter_known", [](const std::string &name) {
        stewart_params scratch;
        stewart_params_default(&scratch);
        char message[STEWART_MESSAGE_SIZE];
        const bool known =
            stewart_params_set(&scratch, name.c_str(), 0.0, message, sizeof message) == STEWART_OK;
        return std::make_pair(known, std::string(known ? "" : message));
    });
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

}  // namespace

void bind_model(nb::module_ &m) {
    nb::class_<Model>(m, "Model")
        .def(nb::init<const std::vector<std::pair<std::string, double>> &>(),
             nb::arg("assignments"));
    bind_model_queries(m);
    bind_platform_files(m);
    bind_parameter_table(m);
}

}  // namespace stewart_core
