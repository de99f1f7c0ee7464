#pragma once
// The paper's Figs. 4 and 5 redrawn from the logs identify read: the effort
// of free-tip rows against the joint angle at each depth (Fig. 4), and the
// effort against the angle on one clamp per joint, loading and unloading
// branches apart (Fig. 5). A missing picture is a warning, never a failure.
#include <string>

#include "pliant/estimation/identification_data.h"

namespace pliant::cli {

/// Writes PATH_STEM_fig4.EXT and PATH_STEM_fig5.EXT beside `figure_path`.
void DrawDataFigures(const estimation::IdentificationData& data, const std::string& figure_path);

}  // namespace pliant::cli
