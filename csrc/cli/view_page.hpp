// --view of the command lines: the page of stewart.view (docs/view.md), written by C++ from the
// template the build embeds (python/stewart/view_template.py), with the same data.
#pragma once

#include <string>
#include <vector>

#include "cli/arguments.hpp"
#include "stewart/stewart.h"

namespace stewart {

// "" when this build holds the page's template, else why not (naming scripts/setup.sh).
const char *view_page_missing();

// The page's path for OUT.csv: OUT.html beside it (the extension replaced, or added).
std::string view_page_beside(const std::string &out_csv);

// What a page shows: per row its time t [s], pose q (6 per row, the tool's in the user frame)
// and, optionally, the legs' forces (6 per row, or empty).
struct ViewRows {
    const std::vector<double> &t;
    const std::vector<double> &q;
    const std::vector<double> &force;
};

// Writes the page of the machine params (the limit check's warn_condition) playing rows to path.
// "" or a message naming the cause (a pose the model cannot solve, a file not written).
std::string write_view_page(const std::string &path, const stewart_params &params,
                            double warn_condition, const ViewRows &rows, const std::string &title);

// The command lines' --view (the page beside OUT.csv) and --view=PAGE.html: sets view and path
// ("" for beside OUT.csv); an empty PAGE.html is refused.
CliOption view_option(const char *tool, bool &view, std::string &path);

// --view's page: write_view_page to path (or beside out_csv when path is ""); 0, or 1 with
// "TOOL: --view: why" on stderr.
int write_view(const char *tool, const std::string &path, const char *out_csv,
               const stewart_params &params, double warn_condition, const ViewRows &rows);

}  // namespace stewart
